//! The compiled Python module `mechfem._core`: conversion and error mapping
//! only. The public API, the command line and the output files are Python
//! (`python/mechfem`); the module's types are in `python/mechfem/_core.pyi`.
//!
//! A tour:
//!
//! * `check_deck` reads a deck with [`mechfem_deck::load`] and computes
//!   position 1 with [`mechfem_core::run()`] (no motion).
//! * `run_deck` runs the deck's whole motion and returns the buffers, the
//!   co-ordinates, time and det(D^c) per position as numpy arrays, plus the
//!   run report, the model echo and the storage requests as dicts
//!   (`convert`). For the hodographs it also records d x_i / d input 1
//!   of every co-ordinate a PLOTHODO line names. The run releases the GIL;
//!   `observe` attaches only to report progress.
//! * `text` runs deck text (what the Python model API writes) and records
//!   every quantity of the buffer table; `batch` runs many variants of a
//!   few deck texts on worker threads without the GIL, for design studies.
//! * `model` keeps a compiled deck for Python (`Model`), run again with
//!   other numbers without reading text; `cache` keeps the decks `run_deck`
//!   read, so that a file run again unchanged is not parsed again.
//! * `catalogue` hands the element catalogue and the solver's defaults and
//!   limits to Python, which repeats none of them.
//! * `errors` defines `MechfemError` and its subclasses and maps deck
//!   diagnostics and solver errors onto them. A motion that stops after
//!   position 1 is not an error: the report says why.

/// The run's tables are large (a position's numbers times every position)
/// and go to Python as they are; mimalloc keeps the memory of freed tables
/// for the next run instead of handing it back to the system and faulting
/// it in again page by page.
#[global_allocator]
static ALLOCATOR: mimalloc::MiMalloc = mimalloc::MiMalloc;

mod batch;
mod cache;
mod catalogue;
mod convert;
mod design;
mod errors;
mod model;
mod observe;
mod rundict;
mod text;

use std::path::{Path, PathBuf};
use std::sync::Arc;

use mechfem_core::run::SimReport;
use mechfem_core::{InputMotion, Mechanism, Motion, Quantity, RunReport};
use mechfem_deck::{Compiled, PlotItem};
use numpy::PyArray1;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::cache::EchoSlot;
use crate::errors::{AssemblyError, ConvergenceError, DeckError, LimitPositionError, MechfemError, ResourceError};
use crate::observe::Recording;

/// Reads and compiles a deck (or takes it from [`cache`]), without the GIL.
fn load(py: Python<'_>, path: &Path) -> PyResult<(Compiled, Arc<EchoSlot>)> {
    py.detach(|| cache::load(path)).map_err(|d| errors::deck_error(py, path, &d))
}

/// The model echo and storage requests of a run of `c` (see [`EchoSlot`]).
fn echo<'py>(
    py: Python<'py>,
    slot: &EchoSlot,
    c: &Compiled,
    given: &[f64],
    at_1: &[f64],
    rec: &Recording,
) -> PyResult<(Bound<'py, PyDict>, Bound<'py, PyDict>)> {
    let (prescribed, dependent) = (&rec.prescribed_at_1, &rec.dependent_at_1);
    slot.get_or_make(py, &[given, at_1, prescribed, dependent], || {
        Ok((convert::model(py, c, given, at_1, prescribed, dependent)?, convert::storage(py, c)?))
    })
}

/// The co-ordinates (0-based, in order of first appearance) of the
/// PLOTHODO lines: their hodographs need d x_i / d input 1.
fn hodograph_coords(c: &Compiled) -> Vec<usize> {
    let mut out = Vec::new();
    for item in c.pictures.iter().flat_map(|p| &p.items) {
        if let PlotItem::Hodograph { x, y } = *item {
            for i in [x, y] {
                if !out.contains(&i) {
                    out.push(i);
                }
            }
        }
    }
    out
}

/// What a DYN deck's run records beyond its buffers, for the print file's
/// summary and the report's default charts: every input, every drive
/// force, kinetic and potential energy and drive power.
fn dynamic_quantities(mech: &Mechanism) -> Vec<Quantity> {
    let nd = mech.n_dof();
    let mut q: Vec<Quantity> = (0..nd).map(Quantity::Input).collect();
    q.extend((0..nd).map(Quantity::Drive));
    q.extend([Quantity::Ekin, Quantity::Epot, Quantity::Power]);
    q
}

/// A finished run: the compiled deck, the recording and the report.
struct Ran {
    compiled: Compiled,
    given: Vec<f64>,
    rec: Recording,
    report: RunReport,
    /// What the integrator of a simulation did.
    sim: Option<SimReport>,
    /// Ctrl-C stopped the run; the positions before it are kept.
    interrupted: bool,
}

/// Runs the compiled deck (its motion only when `with_motion`), without the
/// GIL; refuses before it starts when the results would take more than
/// `memory_limit` bytes. `det` asks for det(D^c) at every position (see
/// [`Recording::new`]).
fn execute(
    py: Python<'_>,
    mut c: Compiled,
    with_motion: bool,
    progress: Option<Py<PyAny>>,
    memory_limit: u64,
    det: bool,
) -> PyResult<Ran> {
    let given = c.state.x.clone();
    // Position 1 of a free-motion deck is computed as its run computes it:
    // free motion may start in a limit position of its input.
    let free_start = c
        .motion
        .as_ref()
        .filter(|m| m.inputs.iter().any(|im| matches!(im, InputMotion::Free { .. })))
        .map(|m| Motion { steps: 0, ..m.clone() });
    let motion = if with_motion { c.motion.as_ref() } else { free_start.as_ref() };
    if let (false, Some(m)) = (with_motion, c.motion.as_ref()) {
        // Position 1 alone, as a run would compute it.
        m.apply_initial_inputs(&c.mechanism, &mut c.state);
    }
    let quantities: Vec<Quantity> = c.buffers.iter().map(|b| b.quantity).collect();
    let mut extra: Vec<Quantity> = if with_motion && c.mechanism.n_dof() > 0 {
        hodograph_coords(&c).into_iter().map(|coord| Quantity::Kx1 { coord, j: 0 }).collect()
    } else {
        Vec::new()
    };
    if c.dynamics.is_some() {
        extra.extend(dynamic_quantities(&c.mechanism));
    }
    let total = motion.map_or(0, |m| m.steps) + 1;
    let mut rec = Recording::new(&quantities, &extra, total, progress, det);
    rec.with_dynamics(&c.mechanism, c.dynamics.as_ref());
    let n = c.mechanism.n_coords();
    if let Some(message) = errors::memory_refusal(total, rec.recorder.values_per_position(n), memory_limit) {
        return Err(ResourceError::new_err(message));
    }
    rec.recorder.reserve(total, n);
    let (mech, state, params) = (&c.mechanism, &mut c.state, &c.params);
    let sim = text::simulation(c.mode, c.dynamics.as_ref(), &c.integration);
    let result = py.detach(|| text::move_through(mech, state, motion, params, sim, &mut rec));
    let interrupted = errors::interrupted(py, rec.progress.error.take(), result.is_ok())?;
    match result {
        Ok((report, sim)) => Ok(Ran { compiled: c, given, rec, report, sim, interrupted }),
        Err(e) => Err(errors::position_one_error(py, &c.mechanism, &mut c.state, &e)),
    }
}

/// Reads the deck at `path`, compiles it and computes position 1 only.
///
/// Returns the sizes of the model, det(D^c) and the co-ordinates at
/// position 1, the adjustment that led there, and the model echo.
#[pyfunction]
fn check_deck(py: Python<'_>, path: PathBuf) -> PyResult<Bound<'_, PyDict>> {
    let (compiled, slot) = load(py, &path)?;
    let Ran { compiled: c, given, rec, report, .. } = execute(py, compiled, false, None, u64::MAX, true)?;
    let mech = &c.mechanism;
    let n = mech.n_coords();
    let at_1 = rec.recorder.coords()[..n].to_vec();
    let (model, _) = echo(py, &slot, &c, &given, &at_1, &rec)?;
    let d = PyDict::new(py);
    d.set_item("n_coords", n)?;
    d.set_item("n_moving", mech.n_moving())?;
    d.set_item("n_prescribed", mech.n_prescribed())?;
    d.set_item("n_dependent", mech.n_dependent())?;
    d.set_item("n_dof", mech.n_dof())?;
    d.set_item("det", rec.recorder.data()[rec.n_buffers + 1])?;
    d.set_item("coords", PyArray1::from_vec(py, at_1.clone()))?;
    d.set_item("adjust", convert::adjust(py, &report.adjust)?)?;
    d.set_item("model", model)?;
    Ok(d)
}

/// Reads the deck at `path` and runs its whole motion.
///
/// `progress(done, total)` is called about every 1% of the positions. A
/// motion that stops early returns every position computed so far and the
/// reason in `report["stop"]`; only a failure at position 1 raises. Ctrl-C
/// (KeyboardInterrupt from a signal or from `progress`) stops the run and
/// returns the positions so far with `interrupted` set: the caller writes
/// them and then raises. A run whose results would take more than
/// `memory_limit` bytes raises `ResourceError` before it starts.
/// `kx1_values` holds d x_i / d input 1 of the co-ordinates `kx1_coords`
/// that PLOTHODO lines name (for the hodographs). For a DYN deck `dynamic`
/// holds every input, every drive force, the kinetic and potential energy
/// and the drive power per position (None otherwise).
///
/// With `det=False` det(D^c) is computed only where a buffer asks for it:
/// `det` holds NaN otherwise, no sign change of det(D^c) is watched for,
/// and a deck whose buffers are all positions and values computes
/// positions only. Array columns (`buffer_values[:, k]` and the like) are
/// contiguous. A deck file run again unchanged is not read into a model
/// again ([`cache`]).
#[pyfunction]
#[pyo3(signature = (path, progress=None, memory_limit=u64::MAX, det=true))]
fn run_deck(
    py: Python<'_>,
    path: PathBuf,
    progress: Option<Py<PyAny>>,
    memory_limit: u64,
    det: bool,
) -> PyResult<Bound<'_, PyDict>> {
    let (compiled, slot) = load(py, &path)?;
    let Ran { compiled: c, given, rec, report, sim, interrupted } =
        execute(py, compiled, true, progress, memory_limit, det)?;
    let mech = &c.mechanism;
    let (n, nb, positions) = (mech.n_coords(), rec.n_buffers, rec.recorder.positions());
    let (model, storage) = echo(py, &slot, &c, &given, &rec.recorder.coords()[..n], &rec)?;
    let n_dynamic = if c.dynamics.is_some() { dynamic_quantities(mech).len() } else { 0 };
    let n_kx1 = rec.n_extra - n_dynamic;
    let kx1_coords: Vec<usize> = if n_kx1 > 0 { hodograph_coords(&c) } else { Vec::new() };
    let width = nb + 2 + rec.n_extra;
    let (data, coords) = rec.recorder.into_parts();
    // Column by column, so that each column of the array Python gets is contiguous.
    let block = |from: usize, to: usize| columns_of(&data, width, from..to);
    let column = |q: usize| block(q, q + 1);

    let d = PyDict::new(py);
    d.set_item("buffer_numbers", c.buffers.iter().map(|b| b.number).collect::<Vec<_>>())?;
    d.set_item("buffer_values", convert::columns(py, block(0, nb), positions, nb)?)?;
    d.set_item("coords", convert::array2(py, coords, positions, n)?)?;
    d.set_item("time", PyArray1::from_vec(py, column(nb)))?;
    d.set_item("det", PyArray1::from_vec(py, column(nb + 1)))?;
    d.set_item("kx1_coords", kx1_coords.iter().map(|i| i + 1).collect::<Vec<_>>())?;
    d.set_item("kx1_values", convert::columns(py, block(nb + 2, nb + 2 + n_kx1), positions, n_kx1)?)?;
    let dynamic = if n_dynamic > 0 {
        let (nd, at) = (mech.n_dof(), nb + 2 + n_kx1);
        let dd = PyDict::new(py);
        dd.set_item("inputs", convert::columns(py, block(at, at + nd), positions, nd)?)?;
        dd.set_item("drive", convert::columns(py, block(at + nd, at + 2 * nd), positions, nd)?)?;
        dd.set_item("ekin", PyArray1::from_vec(py, column(at + 2 * nd)))?;
        dd.set_item("epot", PyArray1::from_vec(py, column(at + 2 * nd + 1)))?;
        dd.set_item("power", PyArray1::from_vec(py, column(at + 2 * nd + 2)))?;
        Some(dd)
    } else {
        None
    };
    d.set_item("dynamic", dynamic)?;
    d.set_item("simulation", sim.as_ref().map(|s| convert::simulation(py, s)).transpose()?)?;
    let steps = c.motion.as_ref().map_or(0, |m| m.steps);
    let report_dict = || convert::report(py, mech, &report, steps);
    let plain = report.stop.is_none() && report.limits.is_empty() && report.singular_positions.is_empty();
    let report_dict = if plain && sim.is_none() {
        let a = &report.adjust;
        let mut numbers = vec![a.iterations as u64, a.stages as u64, a.residual.to_bits()];
        numbers.extend([report.positions, report.subdivided_steps, steps].map(|k| k as u64));
        numbers.extend(a.initial_deformations.iter().map(|v| v.to_bits()));
        slot.report(py, numbers, report_dict)?
    } else {
        report_dict()?
    };
    d.set_item("report", report_dict)?;
    d.set_item("model", model)?;
    d.set_item("storage", storage)?;
    d.set_item("interrupted", interrupted)?;
    Ok(d)
}

/// Columns `range` of a row-major table `width` wide, one after the other
/// (column-major). A deck's few buffers are recorded row by row and
/// transposed once after the run: writing each position into its columns
/// as it comes (`mechfem_core::run::Columns`, as the full layout of a named
/// model's run does) makes a run of a few columns slower, its stores spread
/// over as many streams as it has columns.
fn columns_of(data: &[f64], width: usize, range: std::ops::Range<usize>) -> Vec<f64> {
    let rows = data.len().checked_div(width).unwrap_or(0);
    let mut out = vec![0.0; rows * range.len()];
    for (k, row) in data.chunks_exact(width.max(1)).enumerate() {
        for (q, &v) in row[range.clone()].iter().enumerate() {
            out[q * rows + k] = v;
        }
    }
    out
}

/// The module `mechfem._core`.
#[pymodule]
fn _core(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("MechfemError", py.get_type::<MechfemError>())?;
    m.add("DeckError", py.get_type::<DeckError>())?;
    m.add("AssemblyError", py.get_type::<AssemblyError>())?;
    m.add("ConvergenceError", py.get_type::<ConvergenceError>())?;
    m.add("LimitPositionError", py.get_type::<LimitPositionError>())?;
    m.add("ResourceError", py.get_type::<ResourceError>())?;
    m.add("DEFAULTS", catalogue::defaults(py)?)?;
    m.add_function(wrap_pyfunction!(catalogue::catalogue, m)?)?;
    m.add_function(wrap_pyfunction!(check_deck, m)?)?;
    m.add_function(wrap_pyfunction!(run_deck, m)?)?;
    m.add_function(wrap_pyfunction!(text::run_deck_text, m)?)?;
    m.add_function(wrap_pyfunction!(text::describe_deck_text, m)?)?;
    m.add_function(wrap_pyfunction!(batch::run_deck_variants, m)?)?;
    m.add_class::<model::Model>()?;
    m.add_class::<design::DesignModel>()?;
    m.add_function(wrap_pyfunction!(design::optimised_deck_text, m)?)?;
    Ok(())
}
