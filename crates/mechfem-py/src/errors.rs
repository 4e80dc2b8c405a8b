//! The Python exceptions and the mapping of deck and solver errors onto them.
//!
//! The words are the core's (`mechfem_core::worded`, the errors' `Display`)
//! and the deck reader's: here an error's type picks its exception class
//! and its fields become attributes. Beside its message, a solver error
//! carries its [`Part`]s, which a front end words in its own terms.

use std::path::Path;

use mechfem_core::run::MemoryRefusal;
use mechfem_core::worded::{self, Part, Worded};
use mechfem_core::{DesignError, Lost, Mechanism, Names, SolveError, State};
use mechfem_deck::Diagnostics;
use pyo3::exceptions::{PyException, PyKeyboardInterrupt, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyList, PyString, PyTuple};
use pyo3::{create_exception, PyErr};

use crate::faults::{DeckDiagnostic, ElementFault};

create_exception!(mechfem.errors, MechfemError, PyException, "Base class of every error mechfem raises.");
create_exception!(
    mechfem.errors,
    DeckError,
    MechfemError,
    "The deck has a mistake: str() is the rendered diagnostic; `kind`, `path`, `line`, `column`, `text`, `message`, \
     `hint`, `element`, `coordinate` and `detail` are the first one's fields, `diagnostics` every one's."
);
create_exception!(
    mechfem.errors,
    AssemblyError,
    MechfemError,
    "The model cannot be evaluated at position 1: `element` (deck number), `element_type`, the core's `detail` and \
     its `detail_fields`, and the message's `parts`."
);
create_exception!(
    mechfem.errors,
    ConvergenceError,
    MechfemError,
    "Newton iteration cannot reach position 1: `reason` (a stable code), `iterations` and `residual` when it ran out, \
     and the message's `parts`."
);
create_exception!(
    mechfem.errors,
    LimitPositionError,
    MechfemError,
    "D^c is singular at position 1: `rows` that depend on each other, `coords` that can still move (deck numbers), \
     `rank` and `size` of D^c, `coordinate` at whose column the pivot vanished, and the message's `parts`."
);

create_exception!(
    mechfem.errors,
    ResourceError,
    MechfemError,
    "The run would keep more results in memory than its limit allows; it was refused before it started."
);

/// The `ResourceError` of a run refused before it started, worded by the
/// core, with its facts as fields: `positions`, `values`, `need` and
/// `limit` (bytes).
pub fn resource_error(py: Python<'_>, refusal: &MemoryRefusal) -> PyErr {
    let e = ResourceError::new_err(refusal.to_string());
    let value = e.value(py);
    let _ = value.setattr("positions", refusal.positions);
    let _ = value.setattr("values", refusal.values);
    let _ = value.setattr("need", refusal.need);
    let _ = value.setattr("limit", refusal.limit);
    e
}

/// A `DeckError` carrying every diagnostic: str() renders them all, the
/// attributes are the first one's fields (see [`DeckDiagnostic`]) and
/// `diagnostics` holds every one, so that a front end names things from
/// the fields instead of reading the message.
pub fn deck_error(py: Python<'_>, path: &Path, diagnostics: &Diagnostics) -> PyErr {
    let err = DeckError::new_err(diagnostics.to_string());
    let value = err.value(py);
    // Setting attributes on a fresh exception instance cannot fail; making
    // the objects only fails when Python is out of memory, and then the
    // message alone still says what is wrong.
    let _ = value.setattr("path", path.to_string_lossy().into_owned());
    let _ = value.setattr("line", 0);
    let all: Vec<DeckDiagnostic> = diagnostics.iter().map(DeckDiagnostic::of).collect();
    if let Some(first) = all.first() {
        let _ = first.set_on(py, value.as_any());
    }
    let _ = value.setattr("diagnostics", all);
    err
}

/// What to do with the error `raised` by progress reporting during a run
/// that `kept` its positions (or not): Ctrl-C after which they were kept is
/// `Ok(true)`, the run was interrupted and its positions are returned (the
/// report says so); no error is `Ok(false)`; any other error is raised.
///
/// A Ctrl-C made after the run last looked for one is taken here too,
/// before anything is handed to Python: left pending, it would be raised
/// inside the first call into numpy, which cannot report it.
pub fn interrupted(py: Python<'_>, raised: Option<PyErr>, kept: bool) -> PyResult<bool> {
    let raised = raised.or_else(|| py.check_signals().err());
    match raised {
        None => Ok(false),
        Some(err) if kept && err.is_instance_of::<PyKeyboardInterrupt>(py) => Ok(true),
        Some(err) => Err(err),
    }
}

/// A part of a message as Python gets it: a plain string for
/// [`Part::Text`]; otherwise the tuple `(kind, value, deck words)`, the
/// value being a number, a list of numbers, a term's code or an
/// [`ElementFault`]. The things of the model a part names cross to Python
/// as structure, so that a front end names them in its own words (the
/// Python API with the model's names) without reading the message.
fn part_object<'py>(py: Python<'py>, part: &Part) -> PyResult<Bound<'py, PyAny>> {
    let value = match part {
        Part::Text(t) => return Ok(PyString::new(py, t).into_any()),
        Part::Element { number: n, .. }
        | Part::Coordinate { number: n, .. }
        | Part::Row { number: n, .. }
        | Part::Line(n) => n.into_pyobject(py)?.into_any(),
        Part::Coords { numbers: n, .. } | Part::Rows { numbers: n, .. } => PyList::new(py, n)?.into_any(),
        Part::Point { coords, .. } => PyList::new(py, coords)?.into_any(),
        Part::Term(t) => PyString::new(py, t.code()).into_any(),
        Part::Detail { element, error } => Py::new(py, ElementFault::of(*element, error))?.into_bound(py).into_any(),
    };
    let items = [PyString::new(py, part.kind()).into_any(), value, PyString::new(py, &part.deck()).into_any()];
    Ok(PyTuple::new(py, items)?.into_any())
}

/// The parts of a worded message as the Python list of `parts` (see [`part_object`]).
pub fn parts_object<'py>(py: Python<'py>, worded: &Worded) -> PyResult<Bound<'py, PyList>> {
    let items = worded.0.iter().map(|p| part_object(py, p)).collect::<PyResult<Vec<_>>>()?;
    PyList::new(py, items)
}

/// The `ValueError` of an argument the core or the deck reader refuses
/// (a change of a model's numbers, a design variable, an order of transfer
/// functions), worded by them.
pub fn value_error(e: &dyn std::error::Error) -> PyErr {
    PyValueError::new_err(e.to_string())
}

/// The `RuntimeError` of a run's answer lost between the core and Python,
/// worded by the core.
pub fn lost(e: Lost) -> PyErr {
    pyo3::exceptions::PyRuntimeError::new_err(e.to_string())
}

/// The `ValueError` of a change of a model's numbers that the model does
/// not have, worded by the core.
pub fn change_error(e: &DesignError) -> PyErr {
    value_error(e)
}

/// The DYNAMICS line of each mass and load, as the compiled deck gives
/// them ([`mechfem_deck::Compiled::dynamics_lines`]).
pub type Lines<'a> = mechfem_core::worded::Lines<'a>;

/// The exception for a failure at position 1, worded by the core
/// ([`worded::position_one`]): its class by the error's type, its facts as
/// attributes.
pub fn position_one_error(
    py: Python<'_>,
    mech: &Mechanism,
    names: &Names,
    lines: Lines<'_>,
    state: &mut State,
    err: &SolveError,
) -> PyErr {
    let (worded, dependence) = worded::position_one(mech, names, lines, state, err);
    let message = worded.to_string();
    let e = match err {
        SolveError::Element { .. } => AssemblyError::new_err(message),
        SolveError::Singular { .. } => LimitPositionError::new_err(message),
        SolveError::NoConvergence { .. }
        | SolveError::BranchJump { .. }
        | SolveError::DetSignChange { .. }
        | SolveError::NonFinite
        | SolveError::Simulation { .. } => ConvergenceError::new_err(message),
        SolveError::NotComputed | SolveError::Unsupported(_) | SolveError::Interrupted | SolveError::Dynamics(_) => {
            MechfemError::new_err(message)
        }
    };
    let value = e.value(py);
    // Every failure here is at position 1; a front end words it from this
    // and the fields below instead of from the message.
    let _ = value.setattr("position", 1);
    let _ = value.setattr("reason", err.code());
    if let Ok(parts) = parts_object(py, &worded) {
        let _ = value.setattr("parts", parts);
    }
    match err {
        SolveError::Element { element, source } => {
            let _ = value.setattr("element", element + 1);
            let _ = value.setattr("element_type", mech.elements().get(*element).map(|e| e.ty.name()));
            let _ = value.setattr("detail", source.to_string());
            let _ = value.setattr("detail_fields", ElementFault::of(element + 1, source));
        }
        SolveError::Singular { column, .. } => {
            let _ = value.setattr("coordinate", mech.moving_coords().get(*column).map(|i| i + 1));
            let d = dependence.as_ref();
            let _ = value.setattr("rows", d.map_or_else(Vec::new, |d| d.rows.clone()));
            let _ = value.setattr("coords", d.map_or_else(Vec::new, |d| d.coords.clone()));
            let _ = value.setattr("rank", d.map(|d| d.rank));
            let _ = value.setattr("size", d.map(|d| d.size));
        }
        SolveError::NoConvergence { iterations, residual } => {
            let _ = value.setattr("iterations", *iterations);
            let _ = value.setattr("residual", *residual);
        }
        _ => {}
    }
    e
}
