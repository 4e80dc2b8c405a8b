//! Rust results to Python objects: numpy arrays, a table's layout, the
//! model echo ([`crate::echo`]) made once per compiled deck and filled with
//! each run's numbers, and the storage requests. Everything that names a
//! co-ordinate, row, element, DOF or position is converted to the deck's
//! 1-based numbering here.

use mechfem_core::run::Block;
use mechfem_core::FormRef;
use mechfem_deck::{Compiled, RowInfo};
use numpy::ndarray::{Array2, ShapeError};
use numpy::PyArray2;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList, PyTuple};

use crate::echo::{EchoCoordinate, EchoElement, EchoModel, EchoPoint, EchoRow, Term};
use crate::masses::EchoDynamics;

/// A row-major `rows x cols` array.
pub fn array2<'py>(py: Python<'py>, data: Vec<f64>, rows: usize, cols: usize) -> PyResult<Bound<'py, PyAny>> {
    owned(py, Array2::from_shape_vec((rows, cols), data))
}

/// The numpy array that owns `array`'s values (made in its own order, not
/// reshaped from a flat one).
fn owned<'py>(py: Python<'py>, array: Result<Array2<f64>, ShapeError>) -> PyResult<Bound<'py, PyAny>> {
    let array = array.map_err(|e| PyValueError::new_err(e.to_string()))?;
    Ok(PyArray2::from_owned_array(py, array).into_any())
}

/// A table's layout for Python: block name -> (first column, shape at one
/// position), as the core names its blocks.
pub fn layout<'py>(py: Python<'py>, blocks: &[Block]) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    for b in blocks {
        d.set_item(b.name, (b.start, PyTuple::new(py, &b.shape)?))?;
    }
    Ok(d)
}

/// The echo of the model: elements, rows with their FORM terms and values
/// at position 1, DOFs, and co-ordinates as given and at position 1; each
/// co-ordinate, element and row with the `name` its deck declares
/// ([`mechfem_deck::Names`]; None without one).
pub fn model<'py>(
    py: Python<'py>,
    c: &Compiled,
    given: &[f64],
    at_1: &[f64],
    prescribed: &[f64],
    dependent: &[f64],
) -> PyResult<Bound<'py, EchoModel>> {
    Echo::new(py, c)?.model(py, given, at_1, prescribed, dependent, None)
}

/// The echo of a compiled deck's model ([`model`]) with what every run of
/// the deck shares made once: a study of many variants of one deck fills
/// in only each run's numbers, and the echoes of its runs hold the same
/// element list, DOFs, units, points and labels (not to be changed).
pub struct Echo {
    elements: Py<PyList>,
    dofs: Py<PyList>,
    dynamics: Py<PyAny>,
    mode: &'static str,
    /// The rows and co-ordinates, whose numbers a run sets in a copy.
    prescribed: Vec<EchoRow>,
    dependent: Vec<EchoRow>,
    coordinates: Vec<EchoCoordinate>,
    /// The deck's units and named points ([`crate::names`]).
    units: Py<PyDict>,
    points: Py<PyList>,
    labels: Py<crate::labels::Labels>,
}

impl Echo {
    /// The shared part of the echo of `c`.
    pub fn new(py: Python<'_>, c: &Compiled) -> PyResult<Echo> {
        let mech = &c.mechanism;
        let coordinates = (0..mech.n_coords())
            .map(|i| EchoCoordinate {
                number: i + 1,
                moving: mech.is_moving(i),
                given: f64::NAN,
                adjusted: f64::NAN,
                name: declared(&c.names.coordinates, i).map(str::to_owned),
            })
            .collect();
        // The echo speaks the deck's units (crate::names).
        let [written, written_dependent] = c.rows_as_written();
        let dynamics = match &c.dynamics_as_written() {
            Some(m) => Py::new(py, EchoDynamics::of(m, &[]))?.into_any(),
            None => py.None(),
        };
        let points = c.names.points.iter().map(|(x, y, name)| EchoPoint { x: x + 1, y: y + 1, name: name.clone() });
        Ok(Echo {
            elements: PyList::new(py, echo_elements(c, &c.names.elements))?.unbind(),
            dofs: PyList::new(py, (0..mech.n_dof()).map(|j| mech.input_row(j) + 1))?.unbind(),
            dynamics,
            mode: c.mode.name(),
            prescribed: echo_rows(&written, &c.names.prescribed),
            dependent: echo_rows(&written_dependent, &c.names.dependent),
            coordinates,
            units: crate::names::units(py, c)?.unbind(),
            labels: Py::new(py, crate::labels::Labels::of(c))?,
            points: PyList::new(py, points)?.unbind(),
        })
    }

    /// The echo of one run: the co-ordinates as given and at position 1,
    /// the values of the prescribed and dependent rows at position 1 (NaN
    /// where they are shorter) and the PARA values the run had (None: the
    /// deck's own).
    pub fn model<'py>(
        &self,
        py: Python<'py>,
        given: &[f64],
        at_1: &[f64],
        prescribed: &[f64],
        dependent: &[f64],
        para: Option<&[Option<f64>]>,
    ) -> PyResult<Bound<'py, EchoModel>> {
        let value = |values: &[f64], k: usize| values.get(k).copied().unwrap_or(f64::NAN);
        let rows = |rows: &[EchoRow], values: &[f64], para: Option<&[Option<f64>]>| {
            let rows = rows.iter().enumerate().map(|(k, r)| EchoRow {
                value: value(values, k),
                para: para.and_then(|p| p.get(k).copied()).unwrap_or(r.para),
                ..r.clone()
            });
            PyList::new(py, rows)
        };
        let coordinates = self.coordinates.iter().enumerate().map(|(i, c)| EchoCoordinate {
            given: value(given, i),
            adjusted: value(at_1, i),
            ..c.clone()
        });
        let model = EchoModel {
            elements: self.elements.clone_ref(py),
            prescribed: rows(&self.prescribed, prescribed, para)?.unbind(),
            dependent: rows(&self.dependent, dependent, None)?.unbind(),
            dofs: self.dofs.clone_ref(py),
            coordinates: PyList::new(py, coordinates)?.unbind(),
            mode: self.mode.to_owned(),
            dynamics: self.dynamics.clone_ref(py),
            units: self.units.clone_ref(py),
            points: self.points.clone_ref(py),
            labels: self.labels.clone_ref(py).into_any(),
        };
        Bound::new(py, model)
    }
}

/// The elements of a deck as the echo holds them, with the names `names`
/// declares (none for a deck's description).
pub fn echo_elements(c: &Compiled, names: &[Option<String>]) -> Vec<EchoElement> {
    c.elements
        .iter()
        .enumerate()
        .map(|(k, e)| EchoElement {
            number: e.number,
            kind: e.ty.name().to_owned(),
            coords: e.coords.iter().map(|&i| i as i64).collect(),
            coord_names: e.ty.coord_names().iter().map(|n| (*n).to_owned()).collect(),
            line: e.line,
            name: declared(names, k).map(str::to_owned),
        })
        .collect()
}

/// The rows of a deck as the echo holds them, with the names `names`
/// declares and no value yet (NaN).
pub fn echo_rows(infos: &[RowInfo], names: &[Option<String>]) -> Vec<EchoRow> {
    infos
        .iter()
        .enumerate()
        .map(|(k, r)| EchoRow {
            dest: r.dest,
            terms: r
                .terms
                .iter()
                .map(|t| Term {
                    element: t.element,
                    form: t.name.to_owned(),
                    factor: t.factor,
                    seq: t.seq,
                    line: t.line,
                })
                .collect(),
            para: r.para,
            input: r.input,
            value: f64::NAN,
            name: declared(names, k).map(str::to_owned),
        })
        .collect()
}

/// The name the deck declares for thing `k` (0-based) of a kind, if any.
fn declared(names: &[Option<String>], k: usize) -> Option<&str> {
    names.get(k).and_then(Option::as_deref)
}

pub fn dest(f: FormRef) -> i64 {
    match f {
        FormRef::Prescribed(r) => r as i64 + 1,
        FormRef::Dependent(d) => -(d as i64 + 1),
    }
}

/// The storage requests of `c` as Python reads them (`_core.Storage`).
pub fn storage<'py>(py: Python<'py>, c: &Compiled) -> PyResult<Bound<'py, PyAny>> {
    Ok(Bound::new(py, crate::storage::Storage::of(c))?.into_any())
}
