//! Decks given as text instead of files (a deck read into a `Mechanism`,
//! the decks of design studies, and the deck text that words a named
//! model's mistake), and the run of a compiled model that a kept `Model`
//! shares with them.
//!
//! * [`describe_deck_text`] reads and compiles a deck and returns what it
//!   declares (co-ordinates, elements, rows, motion, storage) without solving.
//! * [`run_deck_text`] runs a deck and returns its own buffers plus every
//!   quantity of the deck's buffer table for every co-ordinate, row and input,
//!   in the core's full layout ([`mechfem_core::run::Layout`]), column by
//!   column.
//!
//! [`execute`] (no GIL) does all of a run but wrapping its results for
//! Python, which [`crate::run`] does; the batch runner
//! ([`crate::batch`]) runs it on worker threads.

use std::path::{Path, PathBuf};
use std::sync::atomic::AtomicBool;

use mechfem_core::dynamics::Integrator;
use mechfem_core::run::{Extent, MemoryRefusal};
use mechfem_core::{InputMotion, Quantity, TransferOrder};
use mechfem_deck::ast::{LoadDefKind, MotionKind};
use mechfem_deck::{Change, Compiled, Diagnostics, Numbers};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::masses::EchoDynamics;
use crate::observe::{Full, Progress, Recording};
use crate::run::{outcome_run, FullRun, Outcome, RecordedTable, Run, Shared};
use crate::{convert, errors};

/// Parses and compiles deck text; `path` names it in diagnostics, MOV_FUNC
/// files are read from `base_dir`.
pub fn compile_text(text: &str, path: &Path, base_dir: &Path) -> Result<Compiled, Diagnostics> {
    let deck = mechfem_deck::parse_str(text, path)?;
    mechfem_deck::compile(&deck, base_dir)
}

/// Runs a compiled deck with `numbers` (its motion only when
/// `with_motion`), recording everything, unless the results would take
/// more than `memory_limit` bytes. Needs no GIL unless `progress` is given.
/// Returns the error the progress callback raised, if any, beside the
/// outcome.
pub fn execute(
    c: &Compiled,
    numbers: Numbers,
    with_motion: bool,
    order: TransferOrder,
    cancel: &AtomicBool,
    progress: Option<Progress>,
    memory_limit: u64,
) -> (Outcome, Option<PyErr>) {
    let Numbers { mut state, para } = numbers;
    let extent = if with_motion { Extent::Motion } else { Extent::PositionOne };
    let bands_start = c.tolerance.as_ref().map(|_| state.clone());
    let motion = c.motion_for(&mut state, extent);
    let quantities: Vec<Quantity> = c.buffers.iter().map(|b| b.quantity).collect();
    let given = state.x.clone();
    let steps = motion.as_ref().map_or(0, |m| m.steps);
    let dynamics = c.run_mode().dynamics();
    let full = Full::new(&c.mechanism, dynamics.is_some(), &quantities, steps + 1);
    let (width, n) = (full.width(), c.mechanism.n_coords());
    if let Err(refusal) = MemoryRefusal::check(steps + 1, width + n, memory_limit) {
        return (Outcome::Refused(refusal), None);
    }
    // The full layout keeps its own record (`Full`): the recording's table has no column.
    let mut rec = Recording::new(full, 0, n, steps + 1, Some(order), progress, Some(cancel))
        .with_dynamics(&c.mechanism, dynamics);
    let result = c.move_through(&mut state, motion.as_deref(), &mut rec);
    let raised = rec.raised();
    let outcome = match result {
        Ok((report, sim)) => {
            let full = rec.columns;
            let positions = full.record.positions();
            let n_rows = c.mechanism.n_prescribed() + c.mechanism.n_dependent();
            let rows_at_1 = if positions > 0 { full.record.row_values(0).to_vec() } else { vec![f64::NAN; n_rows] };
            let mut buffers = full.buffer_table(&rec.coords, n);
            if let Some(Err(e)) = bands_start.map(|s| c.fill_bands(s, &mut buffers, positions)) {
                return (Outcome::Failed(Box::new(state), e), raised);
            }
            Outcome::Ran(Box::new(FullRun {
                width: full.layout.width(),
                table: RecordedTable::new(full.layout, full.record),
                buffers,
                coords: rec.coords,
                positions,
                report,
                sim,
                steps,
                given,
                para,
                rows_at_1,
            }))
        }
        Err(e) => Outcome::Failed(Box::new(state), e),
    };
    (outcome, raised)
}

/// Runs a variant of a compiled deck (its numbers with `changes` made)
/// without the GIL, for worker threads; `progress` is the run's (see
/// [`execute`]), whose error comes back beside the outcome.
pub fn run_variant(
    compiled: &Result<Compiled, Diagnostics>,
    changes: &[Change],
    order: Option<u8>,
    cancel: &AtomicBool,
    progress: Option<Progress>,
    memory_limit: u64,
) -> (Outcome, Option<PyErr>) {
    let c = match compiled {
        Ok(c) => c,
        Err(d) => return (Outcome::Deck(d.clone()), None),
    };
    let numbers = match c.numbers(changes) {
        Ok(n) => n,
        Err(e) => return (Outcome::BadChange(e), None),
    };
    // `order` has been checked by the caller.
    let order = c.transfer_order(order).unwrap_or(TransferOrder::Second);
    execute(c, numbers, true, order, cancel, progress, memory_limit)
}

/// Runs the deck `text` (named `path` in messages; MOV_FUNC files are read
/// from `base_dir`) and returns everything it computed.
///
/// With `motion=False` only position 1 is computed (as `check_deck` does).
/// `order` says which transfer functions to compute at every position (see
/// [`Compiled::transfer_order`]); quantities made from ones not computed are NaN.
/// `progress(done, total)` is called about every 1% of the positions. A
/// motion that stops early returns every position computed so far and the
/// reason in `report.stop`; a deck mistake raises `DeckError`, a failure
/// at position 1 `AssemblyError`, `ConvergenceError` or `LimitPositionError`.
/// Ctrl-C returns the positions so far with `interrupted` set, as `run_deck`;
/// results that would take more than `memory_limit` bytes raise
/// `ResourceError` before the run starts.
#[pyfunction]
#[pyo3(signature = (text, path, base_dir, motion=true, progress=None, order=Some(2), memory_limit=u64::MAX))]
#[allow(clippy::too_many_arguments)]
pub fn run_deck_text(
    py: Python<'_>,
    text: &str,
    path: PathBuf,
    base_dir: PathBuf,
    motion: bool,
    progress: Option<Py<PyAny>>,
    order: Option<u8>,
    memory_limit: u64,
) -> PyResult<Run> {
    let c = py.detach(|| compile_text(text, &path, &base_dir)).map_err(|d| errors::deck_error(py, &path, &d))?;
    crate::names::warn(py, &c)?;
    let numbers = c.numbers(&[]).map_err(|e| errors::value_error(&e))?;
    let shared = Shared::new(py, &c)?;
    run_compiled(py, (&c, &shared), numbers, &path, motion, progress, order, memory_limit)
}

/// Runs a compiled deck with `numbers` (its motion when `motion`) and
/// returns the run's dict with `interrupted` set: what `run_deck_text` and
/// a kept `Model` return alike. `text` is the deck with the objects its
/// runs share ([`Shared`], converted once for a kept `Model`).
#[allow(clippy::too_many_arguments)]
pub fn run_compiled(
    py: Python<'_>,
    text: (&Compiled, &Shared),
    numbers: Numbers,
    path: &Path,
    motion: bool,
    progress: Option<Py<PyAny>>,
    order: Option<u8>,
    memory_limit: u64,
) -> PyResult<Run> {
    let c = text.0;
    let order = c.transfer_order(order).map_err(|e| errors::value_error(&e))?;
    let total = if motion { c.motion.as_ref().map_or(0, |m| m.steps) + 1 } else { 1 };
    let cancel = AtomicBool::new(false);
    let (outcome, raised) =
        py.detach(|| execute(c, numbers, motion, order, &cancel, Some(Progress::new(progress, total)), memory_limit));
    let interrupted = errors::interrupted(py, raised, matches!(outcome, Outcome::Ran(_)))?;
    outcome_run(py, outcome, Some(text), path, interrupted)
}

/// Reads and compiles the deck `text` without solving anything and returns
/// what it declares: `coordinates`, `elements`, `prescribed` and `dependent`
/// rows with their FORM terms, `dofs`, `motion` (None without a MOVEMENT
/// block), `tol`, `max_iter`, `storage`, `inttol` (INTTOL's rtol and atol,
/// None without it), the `mode` and the `dynamics`
/// (masses and loads, LOADFUNC tables with their file names; None for a
/// KIN ANA deck) and the `optimise` block of a KIN OPT deck
/// ([`convert::optimise`]; None otherwise). Numbers are the deck's own.
#[pyfunction]
pub fn describe_deck_text<'py>(
    py: Python<'py>,
    text: &str,
    path: PathBuf,
    base_dir: PathBuf,
) -> PyResult<Bound<'py, PyDict>> {
    let parsed = py.detach(|| {
        let deck = mechfem_deck::parse_str(text, &path)?;
        let c = mechfem_deck::compile(&deck, &base_dir)?;
        Ok::<_, Diagnostics>((deck, c))
    });
    let (deck, c) = parsed.map_err(|d| errors::deck_error(py, &path, &d))?;
    let mech = &c.mechanism;
    let d = PyDict::new(py);
    // The deck's numbers as written, in its UNITS (crate::names).
    let (x, [prescribed, dependent]) = (c.coords_as_written(), c.rows_as_written());
    let (motion, dynamics) = (c.motion_as_written(), c.dynamics_as_written());
    let coords = (0..mech.n_coords())
        .map(|i| {
            let cd = PyDict::new(py);
            cd.set_item("number", i + 1)?;
            cd.set_item("moving", mech.is_moving(i))?;
            cd.set_item("value", x[i])?;
            Ok(cd)
        })
        .collect::<PyResult<Vec<_>>>()?;
    d.set_item("coordinates", coords)?;
    d.set_item("elements", convert::elements(py, &c)?)?;
    d.set_item("prescribed", convert::rows(py, &prescribed, &[])?)?;
    d.set_item("dependent", convert::rows(py, &dependent, &[])?)?;
    d.set_item("names", crate::described_names::names(py, &c)?)?;
    d.set_item("dofs", (0..mech.n_dof()).map(|j| mech.input_row(j) + 1).collect::<Vec<_>>())?;
    d.set_item("tol", c.units.as_written(mechfem_core::Dim::LENGTH, c.params.tol))?;
    d.set_item("max_iter", c.params.max_iter)?;
    let motion = match &motion {
        None => None,
        Some(m) => {
            let files: Vec<Option<String>> = (1..=m.inputs.len())
                .map(|j| {
                    deck.movement.as_ref().and_then(|mv| {
                        mv.motions.iter().find_map(|md| match &md.kind {
                            MotionKind::Function(f) if md.dof.value == j as i64 => Some(f.value.clone()),
                            _ => None,
                        })
                    })
                })
                .collect();
            let inputs = m
                .inputs
                .iter()
                .zip(files)
                .map(|(im, file)| {
                    let id = PyDict::new(py);
                    let (kind, value) = match im {
                        InputMotion::Relative { delta } => ("by", Some(*delta)),
                        InputMotion::Absolute { end } => ("to", Some(*end)),
                        InputMotion::Free { ds } => ("free", Some(*ds)),
                        InputMotion::Dynamic { v0 } => ("dynamic", Some(*v0)),
                        InputMotion::Table { .. } => ("table", None),
                    };
                    id.set_item("kind", kind)?;
                    id.set_item("value", value)?;
                    let table = match im {
                        InputMotion::Table { rows } => Some(rows.iter().map(|r| r.to_vec()).collect::<Vec<_>>()),
                        _ => None,
                    };
                    id.set_item("rows", table)?;
                    id.set_item("file", file)?;
                    Ok(id)
                })
                .collect::<PyResult<Vec<_>>>()?;
            let md = PyDict::new(py);
            md.set_item("steps", m.steps)?;
            md.set_item("dt", m.dt)?;
            md.set_item("inputs", inputs)?;
            Some(md)
        }
    };
    d.set_item("motion", motion)?;
    d.set_item("storage", convert::storage(py, &c)?)?;
    // The LOADFUNC file of every load, in the order the loads were compiled (deck order).
    let files: Vec<Option<String>> = deck.dynamics.as_ref().map_or_else(Vec::new, |dy| {
        dy.loads
            .iter()
            .map(|l| match &l.kind {
                LoadDefKind::Function(f) => Some(f.value.clone()),
                _ => None,
            })
            .collect()
    });
    // INTTOL as the deck gives it (None without: the tolerances are then ACCURACY's).
    let inttol = deck.movement.as_ref().and_then(|m| m.inttol.as_ref()).map(|t| vec![t.rtol.value, t.atol.value]);
    d.set_item("inttol", inttol)?;
    // INTEGRATOR as the deck's word of its method, STOPWHEN as [buffer, value] (each None without).
    let movement = deck.movement.as_ref();
    let integrator = movement.and_then(|m| m.integrator.as_ref()).map(|m| match m.value {
        Integrator::Auto => "auto",
        Integrator::Dop853 => "dop853",
        Integrator::Dopri5 => "dopri5",
        Integrator::Radau5 => "radau5",
    });
    d.set_item("integrator", integrator)?;
    let stop_when = movement.and_then(|m| m.stop_when.as_ref()).map(|s| (s.buffer.value, s.value.value));
    d.set_item("stop_when", stop_when)?;
    d.set_item("mode", c.mode.name())?;
    d.set_item("dynamics", dynamics.as_ref().map(|m| Py::new(py, EchoDynamics::of(m, &files))).transpose()?)?;
    let optimise = c.optimise.as_ref().map(|o| convert::optimise(py, o)).transpose()?;
    if let (Some(o), Some(dict)) = (&c.optimise, &optimise) {
        crate::names::optimise_units(&c, o, dict)?;
    }
    d.set_item("optimise", optimise)?;
    d.set_item("units", crate::names::units(py, &c)?)?;
    Ok(d)
}
