//! A run of deck text as the dict Python gets from `run_deck_text`,
//! `Model.run` and `run_deck_variants`: what a run gave ([`Outcome`],
//! [`FullRun`]) and how it is wrapped.
//!
//! Everything a run computed arrives finished from [`crate::text::execute`]
//! (tables column by column, the row values of position 1, the PARA
//! values); here it is only wrapped: the tables become numpy arrays that
//! own the run's buffers (no copies), and what is the same for every run of
//! one compiled deck (the layout, the storage, the elements, the rows' FORM
//! terms, the buffer numbers) is converted once into [`Shared`], whose
//! Python objects every run's dict holds. A study of many variants of one
//! deck so builds little more than its arrays and small dicts per variant.

use std::path::Path;
use std::sync::Mutex;

use mechfem_core::run::{Layout, MemoryRefusal, SimReport};
use mechfem_core::{RunReport, SolveError, State};
use mechfem_deck::{Compiled, Diagnostics};
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};

use crate::{convert, errors};

/// A finished run with everything recorded, ready to be wrapped for Python.
pub struct FullRun {
    /// The full layout ([`Layout`]), column by column: positions x its width.
    pub table: Vec<f64>,
    /// The deck's buffers in the order of their definitions, column by column.
    pub buffers: Vec<f64>,
    /// Row-major, positions x co-ordinates.
    pub coords: Vec<f64>,
    /// Positions computed.
    pub positions: usize,
    /// Columns of `table`.
    pub width: usize,
    /// What the run did.
    pub report: RunReport,
    /// What the integrator of a simulation did.
    pub sim: Option<SimReport>,
    /// Steps the motion asked for.
    pub steps: usize,
    /// The co-ordinates as the deck gives them (before the adjustment of position 1).
    pub given: Vec<f64>,
    /// PARA value of each prescribed row.
    pub para: Vec<Option<f64>>,
    /// Value of every row, prescribed then dependent, at position 1.
    pub rows_at_1: Vec<f64>,
}

/// What running one deck text gave.
pub enum Outcome {
    /// The deck has a mistake.
    Deck(Diagnostics),
    /// Position 1 could not be computed (the state where it failed).
    Failed(Box<State>, SolveError),
    /// The run (possibly stopped early; see the report).
    Ran(Box<FullRun>),
    /// The results would not fit in the memory limit: nothing was run.
    Refused(MemoryRefusal),
    /// A change names a co-ordinate or row the deck does not have.
    BadChange(String),
}

/// What every run of one compiled deck has in common, converted for Python
/// once. Each run's dict holds these very objects: they are not to be
/// changed.
pub struct Shared {
    /// Block name -> (first column, shape at one position), the core's full layout.
    layout: Py<PyDict>,
    storage: Py<PyDict>,
    buffer_numbers: Py<PyList>,
    echo: convert::Echo,
    /// The model echo and the report of the last run, with the numbers
    /// they were made from (bit patterns): a run with the same numbers
    /// hands Python the same dicts, which it converted once.
    last_echo: Mutex<Option<(Vec<u64>, Py<PyDict>)>>,
    last_report: Mutex<Option<(Vec<u64>, Py<PyDict>)>>,
}

/// The dict kept in `slot` for `key`, else the one `make` builds (then kept).
fn kept<'py>(
    py: Python<'py>,
    slot: &Mutex<Option<(Vec<u64>, Py<PyDict>)>>,
    key: Vec<u64>,
    make: impl FnOnce() -> PyResult<Bound<'py, PyDict>>,
) -> PyResult<Bound<'py, PyDict>> {
    let lock = || slot.lock().unwrap_or_else(|e| e.into_inner());
    if let Some((_, d)) = lock().as_ref().filter(|(k, _)| *k == key) {
        return Ok(d.bind(py).clone());
    }
    // Made without the lock held: making it runs Python code.
    let d = make()?;
    *lock() = Some((key, d.clone().unbind()));
    Ok(d)
}

impl Shared {
    /// The Python objects of compiled deck `c` that every run of it shares.
    pub fn new(py: Python<'_>, c: &Compiled) -> PyResult<Shared> {
        let layout = Layout::full(&c.mechanism, c.dynamics.is_some());
        Ok(Shared {
            layout: convert::layout(py, layout.blocks())?.unbind(),
            storage: convert::storage(py, c)?.unbind(),
            buffer_numbers: PyList::new(py, c.buffers.iter().map(|b| b.number))?.unbind(),
            echo: convert::Echo::new(py, c)?,
            last_echo: Mutex::new(None),
            last_report: Mutex::new(None),
        })
    }
}

/// The run as a dict: `table` (positions x the columns of `layout`, the
/// core's full layout, in Fortran order), `layout` (block name -> first
/// column and shape), `buffer_values` (positions x the deck's buffers, in
/// the order of `buffer_numbers`), `coords`, the model's sizes, `report`,
/// and the `model` echo and `storage` requests as `run_deck` gives them.
fn run_dict<'py>(py: Python<'py>, c: &Compiled, s: &Shared, mut r: FullRun) -> PyResult<Bound<'py, PyDict>> {
    crate::names::full_run(c, &mut r);
    let mech = &c.mechanism;
    let (positions, n, nd, np) = (r.positions, mech.n_coords(), mech.n_dof(), mech.n_prescribed());
    let at_1 = r.coords.get(..n).unwrap_or(&r.given);
    let (prescribed, dependent) = r.rows_at_1.split_at(np.min(r.rows_at_1.len()));
    let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    let mut key = bits(&r.given);
    key.extend(bits(at_1).into_iter().chain(bits(prescribed)).chain(bits(dependent)));
    key.extend(r.para.iter().map(|p| p.map_or(u64::MAX, f64::to_bits)));
    let model = kept(py, &s.last_echo, key, || s.echo.model(py, &r.given, at_1, prescribed, dependent, Some(&r.para)))?;
    let report = || convert::report(py, mech, &c.dynamics_lines, &r.report, r.steps);
    let report = match convert::plain_report_key(&r.report, r.steps).filter(|_| r.sim.is_none()) {
        Some(key) => kept(py, &s.last_report, key, report)?,
        None => report()?,
    };

    let d = PyDict::new(py);
    d.set_item("model", model)?;
    d.set_item("storage", s.storage.bind(py))?;
    d.set_item("report", report)?;
    d.set_item("buffer_numbers", s.buffer_numbers.bind(py))?;
    d.set_item("n_coords", n)?;
    d.set_item("n_dof", nd)?;
    d.set_item("n_prescribed", np)?;
    d.set_item("n_dependent", mech.n_dependent())?;
    d.set_item("dynamic", c.dynamics.is_some())?;
    d.set_item("simulation", r.sim.as_ref().map(|sim| convert::simulation(py, sim)).transpose()?)?;
    d.set_item("layout", s.layout.bind(py))?;
    d.set_item("table", convert::columns(py, r.table, positions, r.width)?)?;
    d.set_item("buffer_values", convert::columns(py, r.buffers, positions, c.buffers.len())?)?;
    d.set_item("coords", convert::array2(py, r.coords, positions, n)?)?;
    Ok(d)
}

/// The outcome as a run dict, or as the exception it amounts to; `text` is
/// the compiled deck that ran, with its shared objects (None for a deck
/// that did not compile).
pub fn outcome_dict<'py>(
    py: Python<'py>,
    outcome: Outcome,
    text: Option<(&Compiled, &Shared)>,
    path: &Path,
) -> PyResult<Bound<'py, PyDict>> {
    let lost = || PyRuntimeError::new_err("a run came back without its compiled deck");
    match outcome {
        Outcome::Ran(r) => {
            let (c, s) = text.ok_or_else(lost)?;
            run_dict(py, c, s, *r)
        }
        Outcome::Deck(d) => Err(errors::deck_error(py, path, &d)),
        Outcome::Refused(refusal) => Err(errors::resource_error(py, &refusal)),
        Outcome::BadChange(message) => Err(PyValueError::new_err(message)),
        Outcome::Failed(mut state, e) => {
            let (c, _) = text.ok_or_else(lost)?;
            Err(errors::position_one_error(py, &c.mechanism, &c.dynamics_lines, &mut state, &c.error_as_written(&e)))
        }
    }
}
