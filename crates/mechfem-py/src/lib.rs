//! The compiled Python module `mechfem._core`: conversion and error mapping
//! only. The public API, the command line and the output files are Python
//! (`python/mechfem`); the module's types are in `python/mechfem/_core.pyi`.
//!
//! A tour:
//!
//! * `check_deck` reads a deck with [`mechfem_deck::load`] and computes
//!   position 1 with [`mechfem_core::run()`] (no motion).
//! * `run_deck` runs the deck's whole motion and returns what the deck
//!   records, one table in the core's named blocks
//!   ([`mechfem_core::run::Selection`]: the buffers, d x_i / d input 1 of
//!   every co-ordinate a PLOTHODO line names, a DYN deck's inputs, drive
//!   forces and energies, time and det(D^c)) with its block names, and
//!   the co-ordinates, as one `run::Run`: numpy arrays made on first
//!   access, the run report, the model echo and the storage requests
//!   (`convert`). Every run returns that one type. The run releases the
//!   GIL; `observe` (the one observer of every run) attaches only to
//!   report progress.
//! * `text` runs deck text (a design study's, or a named model's to word its
//!   mistake) and records
//!   every quantity of the buffer table; `batch` runs many variants of a
//!   few deck texts on worker threads without the GIL, for design studies.
//! * `builder` builds a `Model` item by item from Python's `Mechanism`
//!   (`ModelBuilder`), with no deck text written or parsed.
//! * `model` keeps a compiled deck for Python (`Model`), run again with
//!   other numbers without reading text; `cache` keeps the decks `run_deck`
//!   read, so that a file run again unchanged is not parsed again.
//! * `catalogue` hands the element catalogue and the solver's defaults and
//!   limits to Python, which repeats none of them.
//! * `echo` (the model echo), `masses` (the masses and loads), `described`
//!   (a deck described without solving, `describe_deck_text`) and
//!   `optimise_block` (its OPTIMISE block) are the typed objects Python reads
//!   a deck's model through, with getters in the deck's numbering.
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
mod builder;
mod cache;
mod catalogue;
mod checked;
mod convert;
mod described;
mod described_names;
mod design;
mod dynamic_design;
mod echo;
mod errors;
mod evaluation;
mod faults;
mod labels;
mod masses;
mod model;
mod names;
mod observe;
mod optimise_block;
mod report;
mod run;
mod simulated;
mod storage;
mod text;
mod tolerance;

use std::path::{Path, PathBuf};
use std::sync::Arc;

use mechfem_core::run::{Extent, MemoryRefusal, Selection, SimReport};
use mechfem_core::{Quantity, RunReport, State, TransferOrder};
use mechfem_deck::{Compiled, PlotItem};
use numpy::PyArray1;
use pyo3::prelude::*;
use pyo3::types::PyList;

use crate::cache::EchoSlot;
use crate::errors::{AssemblyError, ConvergenceError, DeckError, LimitPositionError, MechfemError, ResourceError};
use crate::observe::{Progress, Recording};

/// Reads and compiles a deck (or takes it from [`cache`]), without the GIL.
fn load(py: Python<'_>, path: &Path) -> PyResult<(Arc<Compiled>, Arc<EchoSlot>)> {
    let loaded = py.detach(|| cache::load(path)).map_err(|d| errors::deck_error(py, path, &d))?;
    names::warn(py, &loaded.0)?;
    Ok(loaded)
}

/// The model echo and storage requests of a run of `c` (see [`EchoSlot`]).
fn echo<'py>(
    py: Python<'py>,
    slot: &EchoSlot,
    c: &Compiled,
    given: &[f64],
    at_1: &[f64],
    rec: &Recording<'_, Selection>,
) -> PyResult<(Bound<'py, echo::EchoModel>, Bound<'py, PyAny>)> {
    let (prescribed, dependent) = (&rec.prescribed_at_1, &rec.dependent_at_1);
    if !c.units.is_identity() {
        // The echo speaks the deck's units.
        let (mut g, mut a, mut p, mut d) = (given.to_vec(), at_1.to_vec(), prescribed.clone(), dependent.clone());
        names::coords(c, &mut g);
        names::coords(c, &mut a);
        names::row_values(c, &mut p, true);
        names::row_values(c, &mut d, false);
        return slot.get_or_make(py, &[&g, &a, &p, &d], || {
            Ok((convert::model(py, c, &g, &a, &p, &d)?, convert::storage(py, c)?))
        });
    }
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

/// A finished run: the compiled deck, the recording and the report.
struct Ran {
    compiled: Arc<Compiled>,
    /// The state the run ended in.
    state: State,
    given: Vec<f64>,
    rec: Recording<'static, Selection>,
    report: RunReport,
    /// What the integrator of a simulation did.
    sim: Option<SimReport>,
    /// Ctrl-C stopped the run; the positions before it are kept.
    interrupted: bool,
}

/// Runs the compiled deck (its motion only when `with_motion`), without the
/// GIL; refuses before it starts when the results would take more than
/// `memory_limit` bytes. `det` asks for det(D^c) at every position (see
/// [`Recording`]).
fn execute(
    py: Python<'_>,
    c: Arc<Compiled>,
    with_motion: bool,
    progress: Option<Py<PyAny>>,
    memory_limit: u64,
    det: bool,
) -> PyResult<Ran> {
    let given = c.state.x.clone();
    let extent = if with_motion { Extent::Motion } else { Extent::PositionOne };
    let mut state = c.state.clone();
    let motion = c.motion_for(&mut state, extent);
    let buffers: Vec<Quantity> = c.buffers.iter().map(|b| b.quantity).collect();
    let hodograph = if with_motion { hodograph_coords(&c) } else { Vec::new() };
    let dynamics = c.run_mode().dynamics();
    let selection = Selection::deck(&c.mechanism, &buffers, &hodograph, dynamics.is_some());
    let (total, n) = (motion.as_ref().map_or(0, |m| m.steps) + 1, c.mechanism.n_coords());
    MemoryRefusal::check(total, selection.width() + n, memory_limit).map_err(|r| errors::resource_error(py, &r))?;
    // With `det`, det(D^c) at every position (and with it the first order,
    // and the watch for limit positions by its sign); without, its column
    // holds NaN unless a buffer asks for it, and a run whose quantities are
    // all positions and values computes positions only.
    let order = selection.transfer_order().max(det.then_some(TransferOrder::First));
    let width = selection.width();
    let progress = Some(Progress::new(progress, total));
    let mut rec =
        Recording::new(selection, width, n, total, order, progress, None).with_dynamics(&c.mechanism, dynamics);
    let result = py.detach(|| c.move_through(&mut state, motion.as_deref(), &mut rec));
    let interrupted = errors::interrupted(py, rec.raised(), result.is_ok())?;
    match result {
        // The report and an error speak the deck's units.
        Ok((report, sim)) => {
            let report = c.report_as_written(&report);
            let sim = sim.map(|s| c.sim_as_written(&s));
            Ok(Ran { compiled: c, state, given, rec, report, sim, interrupted })
        }
        Err(e) => {
            let e = c.error_as_written(&e);
            Err(errors::position_one_error(py, &c.mechanism, &c.names, &c.dynamics_lines, &mut state, &e))
        }
    }
}

/// The text of the deck at `path` up to its END line, read within the
/// bounds every deck is read in ([`mechfem_deck::read_deck`]); a deck that
/// cannot be read is a `DeckError`.
#[pyfunction]
fn read_deck_text(py: Python<'_>, path: PathBuf) -> PyResult<String> {
    py.detach(|| mechfem_deck::read_deck(&path)).map_err(|d| errors::deck_error(py, &path, &d))
}

/// What the deck at `path` reads and writes, from its text alone (nothing
/// compiled, no table read): `mode`, `tables` (the file names of MOV_FUNC,
/// LOADFUNC and TARGET, relative to the deck's folder), `savedata` (whether
/// it saves a data set), `pictures` (how many) and `animate` (the ANIMATE
/// name or None). A deck that cannot be read is a `DeckError`.
#[pyfunction]
fn deck_files(py: Python<'_>, path: PathBuf) -> PyResult<checked::DeckFiles> {
    let deck = py.detach(|| mechfem_deck::parse_file(&path)).map_err(|d| errors::deck_error(py, &path, &d))?;
    let storage = deck.storage.as_ref();
    Ok(checked::DeckFiles {
        mode: deck.mode.value.name(),
        tables: deck.table_files().iter().map(|f| f.value.clone()).collect(),
        savedata: storage.is_some_and(|s| !s.savedata.is_empty()),
        pictures: storage.map_or(0, |s| s.pictures.len()),
        animate: storage.and_then(|s| s.animate.as_ref()).map(|a| a.value.clone()),
    })
}

/// Reads the deck at `path`, compiles it and computes position 1 only.
///
/// Returns the sizes of the model, det(D^c) and the co-ordinates at
/// position 1, the adjustment that led there, and the model echo.
#[pyfunction]
fn check_deck(py: Python<'_>, path: PathBuf) -> PyResult<checked::Check> {
    let (compiled, slot) = load(py, &path)?;
    let Ran { compiled: c, given, rec, report, .. } = execute(py, compiled, false, None, u64::MAX, true)?;
    let mech = &c.mechanism;
    let n = mech.n_coords();
    let mut at_1 = rec.coords[..n].to_vec();
    let (model, _) = echo(py, &slot, &c, &given, &at_1, &rec)?;
    let det = rec.columns.block("det").map_or(f64::NAN, |b| rec.table.get(0, b.start));
    names::coords(&c, &mut at_1);
    Ok(checked::Check {
        n_coords: n,
        n_moving: mech.n_moving(),
        n_prescribed: mech.n_prescribed(),
        n_dependent: mech.n_dependent(),
        n_dof: mech.n_dof(),
        det: det * c.out_scale(Quantity::Det),
        coords: PyArray1::from_vec(py, at_1).unbind(),
        adjust: report::Adjust::of(&report.adjust),
        model: model.unbind(),
    })
}

/// Reads the deck at `path` and runs its whole motion.
///
/// `progress(done, total)` is called about every 1% of the positions. A
/// motion that stops early returns every position computed so far and the
/// reason in `report.stop`; only a failure at position 1 raises. Ctrl-C
/// (KeyboardInterrupt from a signal or from `progress`) stops the run and
/// returns the positions so far with `interrupted` set: the caller writes
/// them and then raises. A run whose results would take more than
/// `memory_limit` bytes raises `ResourceError` before it starts.
///
/// The recording is `table` (positions x columns, numpy in Fortran order:
/// each column contiguous), laid out in the core's named blocks of a deck
/// ([`Selection::deck`]), which `layout` gives as block name -> (first
/// column, shape at one position): `buffers` (in the order of
/// `buffer_numbers`), `hodograph` (d x_i / d input 1 of the co-ordinates
/// `hodograph_coords`, 1-based, that PLOTHODO lines name), for a DYN deck
/// `inputs`, `drive`, `ekin`, `epot`, `power`, `loadpow` and `vin`, then
/// `time` and `det`.
/// `coords` holds every co-ordinate per position. Every run of one deck
/// file shares its `layout`, `buffer_numbers` and `hodograph_coords`
/// objects ([`EchoSlot::shape`]).
///
/// With `det=False` det(D^c) is computed only where a buffer asks for it:
/// the `det` block holds NaN otherwise, no sign change of det(D^c) is
/// watched for, and a deck whose buffers are all positions and values
/// computes positions only. A deck file run again unchanged is not read
/// into a model again ([`cache`]).
#[pyfunction]
#[pyo3(signature = (path, progress=None, memory_limit=u64::MAX, det=true))]
fn run_deck(
    py: Python<'_>,
    path: PathBuf,
    progress: Option<Py<PyAny>>,
    memory_limit: u64,
    det: bool,
) -> PyResult<run::Run> {
    let (compiled, slot) = load(py, &path)?;
    let bands_start = compiled.tolerance.as_ref().map(|_| compiled.state.clone());
    let Ran { compiled: c, state, given, rec, report, sim, interrupted } =
        execute(py, compiled, true, progress, memory_limit, det)?;
    let mech = &c.mechanism;
    let (n, width, positions) = (mech.n_coords(), rec.columns.width(), rec.table.positions());
    let (model, storage) = echo(py, &slot, &c, &given, &rec.coords[..n], &rec)?;
    // The same for every run of the deck: made once, and shared.
    let shape = slot.shape(py, || {
        let layout = convert::layout(py, rec.columns.blocks())?;
        let hodograph = rec.columns.block("hodograph").map_or(0, |b| b.width());
        let coords = hodograph_coords(&c).into_iter().take(hodograph).map(|i| i + 1);
        let numbers = PyList::new(py, c.buffers.iter().map(|b| b.number))?;
        Ok([layout.into_any(), numbers.into_any(), PyList::new(py, coords)?.into_any()])
    })?;
    let buffers = rec.columns.block("buffers").map_or((0, 0), |b| (b.start, b.width()));
    let (mut table, mut coords) = (rec.table.into_vec(), rec.coords);
    if let Some(start) = bands_start {
        let block = &mut table[buffers.0 * positions..(buffers.0 + buffers.1) * positions];
        if let Err(e) = py.detach(|| c.fill_bands(start, block, positions)) {
            let e = c.error_as_written(&e);
            return Err(errors::position_one_error(py, mech, &c.names, &c.dynamics_lines, &mut state.clone(), &e));
        }
    }
    names::table(&c, rec.columns.quantities(), &mut table, positions, &mut coords);
    let steps = c.motion.as_ref().map_or(0, |m| m.steps);
    let report_of = || Bound::new(py, report::Report::of(py, mech, &c.names, &c.dynamics_lines, &report, steps)?);
    let report_of = match report::Report::plain_key(&report, steps).filter(|_| sim.is_none()) {
        Some(key) => slot.report(py, key, report_of)?,
        None => report_of()?,
    };
    let simulation = sim.as_ref().map(|s| Py::new(py, simulated::Simulation::of(s))).transpose()?;
    let parts = run::DeckRun {
        table,
        width,
        coords,
        positions,
        n_coords: n,
        buffers,
        shape,
        report: report_of,
        model,
        storage,
        simulation,
        interrupted,
        stopped: report.stop.is_some(),
    };
    run::Run::of_deck(&c, parts)
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
    m.add("UnitWarning", py.get_type::<names::UnitWarning>())?;
    m.add_class::<catalogue::ElementKind>()?;
    m.add_class::<catalogue::Defaults>()?;
    m.add("DEFAULTS", Py::new(py, catalogue::defaults())?)?;
    m.add_function(wrap_pyfunction!(catalogue::catalogue, m)?)?;
    m.add_function(wrap_pyfunction!(check_deck, m)?)?;
    m.add_function(wrap_pyfunction!(run_deck, m)?)?;
    m.add_function(wrap_pyfunction!(read_deck_text, m)?)?;
    m.add_function(wrap_pyfunction!(deck_files, m)?)?;
    m.add_function(wrap_pyfunction!(text::run_deck_text, m)?)?;
    m.add_function(wrap_pyfunction!(described::describe_deck_text, m)?)?;
    m.add_class::<described::DeckDescription>()?;
    m.add_class::<described::DeckMotion>()?;
    m.add_class::<described::DeckInput>()?;
    m.add_class::<optimise_block::OptimiseBlock>()?;
    m.add_class::<optimise_block::DeckVary>()?;
    m.add_class::<optimise_block::DeckTarget>()?;
    m.add_class::<optimise_block::DeckBound>()?;
    m.add_class::<optimise_block::DeckObjective>()?;
    m.add_class::<optimise_block::DeckMassVary>()?;
    m.add_class::<optimise_block::DeckSynthesis>()?;
    m.add_function(wrap_pyfunction!(batch::run_deck_variants, m)?)?;
    m.add_class::<model::Model>()?;
    m.add_class::<labels::Labels>()?;
    m.add_class::<echo::EchoModel>()?;
    m.add_class::<echo::EchoElement>()?;
    m.add_class::<echo::EchoRow>()?;
    m.add_class::<echo::Term>()?;
    m.add_class::<echo::EchoCoordinate>()?;
    m.add_class::<echo::EchoPoint>()?;
    m.add_class::<masses::EchoDynamics>()?;
    m.add_class::<masses::EchoBody>()?;
    m.add_class::<masses::EchoPointMass>()?;
    m.add_class::<masses::EchoInertia>()?;
    m.add_class::<masses::EchoForce>()?;
    m.add_class::<masses::EchoLoad>()?;
    m.add_class::<run::Run>()?;
    m.add_class::<checked::Check>()?;
    m.add_class::<checked::DeckFiles>()?;
    m.add_class::<simulated::Simulation>()?;
    m.add_class::<report::Adjust>()?;
    m.add_class::<report::Limit>()?;
    m.add_class::<report::Stop>()?;
    m.add_class::<report::Report>()?;
    m.add_class::<storage::Storage>()?;
    m.add_class::<storage::Buffer>()?;
    m.add_class::<storage::Picture>()?;
    m.add_class::<storage::Plot>()?;
    m.add_class::<builder::ModelBuilder>()?;
    m.add_class::<design::DesignModel>()?;
    m.add_class::<dynamic_design::DynamicDesignModel>()?;
    m.add_class::<evaluation::Evaluation>()?;
    m.add_class::<evaluation::Extremum>()?;
    m.add_class::<faults::DeckDiagnostic>()?;
    m.add_class::<faults::ElementFault>()?;
    m.add_function(wrap_pyfunction!(dynamic_design::deck_with_masses, m)?)?;
    m.add_function(wrap_pyfunction!(design::optimised_deck_text, m)?)?;
    m.add_function(wrap_pyfunction!(tolerance::deck_tolerance, m)?)?;
    m.add_function(wrap_pyfunction!(tolerance::built_tolerance, m)?)?;
    m.add_class::<tolerance::Bands>()?;
    Ok(())
}
