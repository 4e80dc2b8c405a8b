//! Rust results to Python dictionaries and numpy arrays. Everything that
//! names a co-ordinate, row, element, DOF or position is converted to the
//! deck's 1-based numbering here.

use mechfem_core::run::Block;
use mechfem_core::{DesignVar, FormRef};
use mechfem_deck::{Compiled, Optimise, RowInfo, Sense, TargetKind};
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

/// The OPTIMISE block of a `KIN OPT` deck as a dict, in the deck's
/// numbering: `vary` (`kind` 0 a fixed co-ordinate, 1 a prescribed row,
/// `number`, `lo`, `hi`, `line`), `targets` (`buffer`, `kind` "values",
/// "at" or "extremum", `values` with None where not compared and `file`,
/// `position` 1-based, `reference`, `value`, `weight`, `line`), `bounds`
/// (`buffer`, `lo`, `hi`, `line`), `objective` (`sense` "minimise" or
/// "maximise", `reduce` "max", "maxabs", "rms" or "end", `buffer`, `line`;
/// None without one), `steps`, `tol` and `line`.
pub fn optimise<'py>(py: Python<'py>, o: &Optimise) -> PyResult<Bound<'py, PyDict>> {
    let vary = o
        .vary
        .iter()
        .map(|v| {
            let d = PyDict::new(py);
            let (kind, number) = match v.var {
                DesignVar::Fixed(i) => (0, i + 1),
                DesignVar::Row(r) => (1, r + 1),
            };
            d.set_item("kind", kind)?;
            d.set_item("number", number)?;
            d.set_item("lo", v.lo)?;
            d.set_item("hi", v.hi)?;
            d.set_item("line", v.line)?;
            Ok(d)
        })
        .collect::<PyResult<Vec<_>>>()?;
    let targets = o
        .targets
        .iter()
        .map(|t| {
            let d = PyDict::new(py);
            d.set_item("buffer", t.buffer)?;
            let (kind, values, file, position, reference, value) = match &t.kind {
                TargetKind::Values { file, values } => ("values", Some(values.clone()), Some(file), None, None, None),
                TargetKind::At { position, value } => ("at", None, None, Some(position + 1), None, Some(*value)),
                TargetKind::Extremum { reference, value } => {
                    ("extremum", None, None, None, Some(*reference), Some(*value))
                }
            };
            d.set_item("kind", kind)?;
            d.set_item("values", values)?;
            d.set_item("file", file)?;
            d.set_item("position", position)?;
            d.set_item("reference", reference)?;
            d.set_item("value", value)?;
            d.set_item("weight", t.weight)?;
            d.set_item("line", t.line)?;
            Ok(d)
        })
        .collect::<PyResult<Vec<_>>>()?;
    let bounds = o
        .bounds
        .iter()
        .map(|b| {
            let d = PyDict::new(py);
            d.set_item("buffer", b.buffer)?;
            d.set_item("lo", b.lo)?;
            d.set_item("hi", b.hi)?;
            d.set_item("line", b.line)?;
            Ok(d)
        })
        .collect::<PyResult<Vec<_>>>()?;
    let objective = o
        .objective
        .map(|ob| {
            let d = PyDict::new(py);
            d.set_item("sense", if ob.sense == Sense::Minimise { "minimise" } else { "maximise" })?;
            d.set_item("reduce", ob.reduce.name().to_ascii_lowercase())?;
            d.set_item("buffer", ob.buffer)?;
            d.set_item("with_buffer", ob.with)?;
            d.set_item("line", ob.line)?;
            Ok::<_, PyErr>(d)
        })
        .transpose()?;
    let d = PyDict::new(py);
    d.set_item("vary", vary)?;
    d.set_item("targets", targets)?;
    d.set_item("bounds", bounds)?;
    d.set_item("objective", objective)?;
    d.set_item("steps", o.steps)?;
    d.set_item("tol", o.tol)?;
    d.set_item("ftol", o.ftol)?;
    let free_time =
        o.free_time.map(|f| synthesis_dict(py, &[("row", (f.row + 1) as f64)], f.ordered, f.line)).transpose()?;
    d.set_item("free_time", free_time)?;
    let full =
        o.full_rotation.map(|f| synthesis_dict(py, &[("row", (f.row + 1) as f64)], false, f.line)).transpose()?;
    d.set_item("full_rotation", full)?;
    let frame = o
        .frame
        .map(|f| synthesis_dict(py, &[("coordinate", (f.x + 1) as f64), ("lo", f.lo), ("hi", f.hi)], false, f.line))
        .transpose()?;
    d.set_item("frame", frame)?;
    let mass_vary = o
        .mass_vary
        .iter()
        .map(|v| {
            let d = PyDict::new(py);
            d.set_item("item", v.item.name())?;
            d.set_item("number", v.number)?;
            d.set_item("kind", 10 + mechfem_deck::MassItem::ALL.iter().position(|&m| m == v.item).unwrap_or(0))?;
            d.set_item("lo", v.lo)?;
            d.set_item("hi", v.hi)?;
            d.set_item("line", v.line)?;
            Ok(d)
        })
        .collect::<PyResult<Vec<_>>>()?;
    d.set_item("mass_vary", mass_vary)?;
    d.set_item("line", o.line)?;
    Ok(d)
}

/// A synthesis statement of the OPTIMISE block as a dict: its numbers (a
/// row or co-ordinate number as an int), `ordered` and `line`.
fn synthesis_dict<'py>(
    py: Python<'py>,
    items: &[(&str, f64)],
    ordered: bool,
    line: usize,
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    for &(key, value) in items {
        if key == "row" || key == "coordinate" {
            d.set_item(key, value as usize)?;
        } else {
            d.set_item(key, value)?;
        }
    }
    d.set_item("ordered", ordered)?;
    d.set_item("line", line)?;
    Ok(d)
}
