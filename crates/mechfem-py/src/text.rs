//! Decks given as text instead of files (a deck read into a `Mechanism`,
//! the decks of design studies, and the deck text that words a named
//! model's mistake), and the run of a compiled model that a kept `Model`
//! shares with them.
//!
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

use mechfem_core::run::{Extent, MemoryRefusal};
use mechfem_core::{Quantity, TransferOrder};
use mechfem_deck::{Change, Compiled, Diagnostics, Numbers};
use pyo3::prelude::*;

use crate::errors;
use crate::observe::{Full, Progress, Recording};
use crate::run::{outcome_run, FullRun, Outcome, RecordedTable, Run, Shared};

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
            let mut full = rec.columns;
            let positions = full.record.positions();
            let n_rows = c.mechanism.n_prescribed() + c.mechanism.n_dependent();
            let rows_at_1 = if positions > 0 { full.record.row_values(0).to_vec() } else { vec![f64::NAN; n_rows] };
            let mut buffers = full.buffer_table();
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
