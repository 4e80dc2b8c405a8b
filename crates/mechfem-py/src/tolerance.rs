//! Tolerance bands for Python: [`Bands`] wraps the bands the deck reader
//! and the core computed ([`mechfem_deck::EvaluatedBands`], in the model's
//! units) and hands its columns as numpy arrays, each made once from its column.
//! [`deck_tolerance`] evaluates a deck's TOLERANCE block,
//! [`built_tolerance`] the dimensions and buffers of a model built item by
//! item (`ModelBuilder`).

use std::path::{Path, PathBuf};

use mechfem_core::DesignVar;
use mechfem_deck::{BandsError, Compiled, EvaluatedBands, Tolerance};
use numpy::ndarray::Array1;
use numpy::{PyArray1, PyArray2, PyArray3};
use pyo3::prelude::*;

use crate::builder::Source;
use crate::errors;
use crate::text::compile_text;

/// The tolerance bands of some buffers at every position of a motion:
/// `positions` computed; `tolerances` (dimensions); `inputs` (positions x
/// inputs); `values`, `worst`, `rss` (positions x bands); `sensitivity`
/// (positions x bands x dimensions); `widest` (per band, the position of
/// its largest worst case, or None) and `shares` there (per band, `(dim,
/// sensitivity, deviation, of_worst, of_variance)` largest first); `dims`
/// `(kind, number, t, line)` (kind 0 a fixed co-ordinate, 1 a prescribed
/// row; deck numbering), `bands` `(source, b, line)`, `labels` `(label,
/// unit)` of each band's buffer, `dim_units`, `input_units`; every number in
/// the model's units.
#[pyclass(module = "mechfem._core", frozen, name = "ToleranceBands")]
pub struct Bands {
    tolerances: Py<PyArray1<f64>>,
    inputs: Py<PyArray2<f64>>,
    values: Py<PyArray2<f64>>,
    worst: Py<PyArray2<f64>>,
    rss: Py<PyArray2<f64>>,
    sensitivity: Py<PyArray3<f64>>,
    evaluated: EvaluatedBands,
    tolerance: Tolerance,
}

/// One dimension's share: `(dim, sensitivity, deviation, of_worst, of_variance)`.
type ShareTuple = (usize, f64, f64, f64, f64);

/// `data` (row-major) as an array of `shape`.
fn shaped<D: numpy::ndarray::Dimension, S: numpy::ndarray::ShapeBuilder<Dim = D>>(
    shape: S,
    data: Vec<f64>,
) -> PyResult<numpy::ndarray::Array<f64, D>> {
    numpy::ndarray::Array::from_shape_vec(shape, data).map_err(|e| errors::value_error(&e))
}

impl Bands {
    /// The bands with their columns made numpy arrays once, each owning its
    /// column (moved, not copied).
    fn new(py: Python<'_>, mut evaluated: EvaluatedBands, tolerance: Tolerance, dofs: usize) -> PyResult<Bands> {
        let b = &mut evaluated.bands;
        let (n, nb, nv) = (b.positions, evaluated.labels.len(), b.tolerances.len());
        let take = std::mem::take;
        Ok(Bands {
            tolerances: PyArray1::from_owned_array(py, Array1::from_vec(b.tolerances.clone())).unbind(),
            inputs: PyArray2::from_owned_array(py, shaped((n, dofs), take(&mut b.inputs))?).unbind(),
            values: PyArray2::from_owned_array(py, shaped((n, nb), take(&mut b.values))?).unbind(),
            worst: PyArray2::from_owned_array(py, shaped((n, nb), take(&mut b.worst))?).unbind(),
            rss: PyArray2::from_owned_array(py, shaped((n, nb), take(&mut b.rss))?).unbind(),
            sensitivity: PyArray3::from_owned_array(py, shaped((n, nb, nv), take(&mut b.sensitivity))?).unbind(),
            evaluated,
            tolerance,
        })
    }
}

#[pymethods]
impl Bands {
    #[getter]
    fn positions(&self) -> usize {
        self.evaluated.bands.positions
    }

    #[getter]
    fn tolerances<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.tolerances.bind(py).clone()
    }

    #[getter]
    fn inputs<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        self.inputs.bind(py).clone()
    }

    #[getter]
    fn values<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        self.values.bind(py).clone()
    }

    #[getter]
    fn worst<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        self.worst.bind(py).clone()
    }

    #[getter]
    fn rss<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        self.rss.bind(py).clone()
    }

    #[getter]
    fn sensitivity<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray3<f64>> {
        self.sensitivity.bind(py).clone()
    }

    #[getter]
    fn widest(&self) -> Vec<Option<usize>> {
        self.evaluated.bands.widest.iter().map(|w| w.as_ref().map(|w| w.position)).collect()
    }

    #[getter]
    fn shares(&self) -> Vec<Vec<ShareTuple>> {
        let shares = |w: &mechfem_core::run::tolerance::Widest| {
            w.shares.iter().map(|s| (s.dim, s.sensitivity, s.deviation, s.of_worst, s.of_variance)).collect()
        };
        self.evaluated.bands.widest.iter().map(|w| w.as_ref().map_or_else(Vec::new, shares)).collect()
    }

    #[getter]
    fn dims(&self) -> Vec<(u8, usize, f64, usize)> {
        let t = &self.evaluated.bands.tolerances;
        let number = |v: DesignVar| match v {
            DesignVar::Fixed(i) => (0, i + 1),
            DesignVar::Row(r) => (1, r + 1),
        };
        self.tolerance.dims.iter().zip(t).map(|(d, &t)| (number(d.var).0, number(d.var).1, t, d.line)).collect()
    }

    #[getter]
    fn bands(&self) -> Vec<(u32, u32, usize)> {
        self.tolerance.bands.iter().map(|b| (b.source, b.buffer, b.line)).collect()
    }

    #[getter]
    fn labels(&self) -> Vec<(String, String)> {
        self.evaluated.labels.clone()
    }

    #[getter]
    fn dim_units(&self) -> Vec<String> {
        self.evaluated.dim_units.clone()
    }

    #[getter]
    fn input_units(&self) -> Vec<String> {
        self.evaluated.input_units.clone()
    }
}

/// The bands of `tolerance` over `c`'s motion, a failure mapped to Python's
/// error.
fn evaluated(py: Python<'_>, c: &Compiled, tolerance: Tolerance) -> PyResult<Bands> {
    match py.detach(|| tolerance.evaluate(c)) {
        Ok(e) => Bands::new(py, e, tolerance, c.mechanism.n_dof()),
        Err(BandsError::Solve(e)) => {
            let mut at = c.state.clone();
            Err(errors::position_one_error(py, &c.mechanism, &c.names, &c.dynamics_lines, &mut at, &e))
        }
        Err(e) => Err(errors::value_error(&e)),
    }
}

/// The TOLERANCE block of the deck `text` (named `path`, its files read
/// from `base_dir`) evaluated, or None when the deck has none.
#[pyfunction]
pub fn deck_tolerance(py: Python<'_>, text: &str, path: PathBuf, base_dir: PathBuf) -> PyResult<Option<Bands>> {
    let c = py.detach(|| compile_text(text, &path, &base_dir)).map_err(|d| errors::deck_error(py, &path, &d))?;
    let Some(tolerance) = c.tolerance.clone() else { return Ok(None) };
    evaluated(py, &c, tolerance).map(Some)
}

/// The bands of the buffers `sources` of the model `builder` builds (a
/// `ModelBuilder`, its files read from `base_dir`; named `path` in
/// messages) when each of `dims` `(kind, number, t)` (kind 0 a fixed
/// co-ordinate, 1 a prescribed row; deck numbering; t in the model's
/// units) is within +-t.
#[pyfunction]
pub fn built_tolerance(
    py: Python<'_>,
    builder: &Bound<'_, PyAny>,
    path: PathBuf,
    base_dir: PathBuf,
    dims: Vec<(u8, usize, f64)>,
    sources: Vec<u32>,
) -> PyResult<Bands> {
    let source = Source::extract(builder)?;
    let c = py.detach(|| source.compile(Path::new(&path), &base_dir)).map_err(|d| errors::deck_error(py, &path, &d))?;
    let var = |kind: u8, number: usize| match kind {
        0 => DesignVar::Fixed(number.wrapping_sub(1)),
        _ => DesignVar::Row(number.wrapping_sub(1)),
    };
    let dims: Vec<(DesignVar, f64)> = dims.iter().map(|&(k, n, t)| (var(k, n), t)).collect();
    let tolerance = Tolerance::of_items(&c, &dims, &sources).map_err(|e| errors::value_error(&e))?;
    evaluated(py, &c, tolerance)
}
