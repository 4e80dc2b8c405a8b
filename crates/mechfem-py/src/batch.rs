//! Many runs at once, for design studies: variants of a few deck texts
//! (each text with some co-ordinate or PARA values changed) are compiled
//! and run by the core's workers ([`mechfem_core::batch::stream`]) with the
//! GIL released. Each text is read and compiled once, by the first worker
//! that needs it; a variant runs it with its own numbers, so a study of one
//! mechanism writes and reads one deck, not one per variant. A worker does
//! all of a variant that needs no Python, its tables laid out as Python
//! gets them included. The calling thread is one of the workers: between
//! the variants it runs itself, it wraps each finished result (with the
//! objects every run of its text shares, converted once), reports progress
//! and hands the result over.

use std::path::PathBuf;
use std::sync::atomic::AtomicBool;
use std::sync::OnceLock;
use std::time::Duration;

use mechfem_core::run::transfer_order_of;
use mechfem_core::{batch, Lost};
use mechfem_deck::{Change, Compiled, Diagnostics};
use pyo3::exceptions::PyIndexError;
use pyo3::prelude::*;

use crate::builder::Source;
use crate::errors;
use crate::observe::Progress;
use crate::run::{outcome_run, Outcome, Shared};
use crate::text::run_variant;

/// A change as Python gives it: (kind, number, value); see [`Change::of_kind`].
type ChangeTriple = (u8, usize, f64);

/// How often the calling thread looks for Ctrl-C while it waits for the others.
const POLL: Duration = Duration::from_millis(100);

/// Runs every variant in `variants` on `workers` threads (default: one per
/// core), the calling thread one of them. A variant is `(t, changes)`: deck text `texts[t]` (named `path`
/// in messages; MOV_FUNC files are read from `base_dir`) or the model a
/// `ModelBuilder` `texts[t]` builds, with `changes`
/// made, each `(kind, number, value)`: kind 0 sets co-ordinate `number`
/// (its XFIX or XMOV value), kind 1 prescribed row `number` (its PARA
/// value), as if the deck said so.
///
/// For each variant the result is either the `Run` `run_deck_text` returns
/// or the exception it would raise (an instance of `DeckError`,
/// `AssemblyError`, `ConvergenceError`, `LimitPositionError`,
/// `ResourceError` or `MechfemError`): one failing variant does not stop the others.
///
/// Without `on_result` the results are returned, in the order of `variants`.
/// With it, `on_result(k, result)` is called for each variant k once it has
/// finished, on the calling thread between the variants that thread runs
/// (while the other workers go on), and the list returned is empty: a study
/// can reduce each result and let it go.
/// `order` is the transfer functions to compute and `memory_limit` the
/// most bytes of one deck's results, as for `run_deck_text`.
/// `progress(done, total)` is called each time a variant has finished. An
/// exception raised by either callback, or Ctrl-C, stops every worker and
/// is raised.
#[pyfunction]
#[pyo3(signature = (texts, variants, path, base_dir, workers=None, progress=None, on_result=None, order=Some(2), memory_limit=u64::MAX))]
#[allow(clippy::too_many_arguments)]
pub fn run_deck_variants(
    py: Python<'_>,
    texts: Vec<Bound<'_, PyAny>>,
    variants: Vec<(usize, Vec<ChangeTriple>)>,
    path: PathBuf,
    base_dir: PathBuf,
    workers: Option<usize>,
    progress: Option<Py<PyAny>>,
    on_result: Option<Py<PyAny>>,
    order: Option<u8>,
    memory_limit: u64,
) -> PyResult<Vec<Py<PyAny>>> {
    let texts = texts.iter().map(Source::extract).collect::<PyResult<Vec<_>>>()?;
    transfer_order_of(order).map_err(|e| errors::value_error(&e))?;
    let variants = variants
        .into_iter()
        .map(|(t, changes)| {
            // Python's batch runner numbers the texts it passes.
            if t >= texts.len() {
                return Err(PyIndexError::new_err(t));
            }
            let changes = changes.into_iter().map(|(kind, number, value)| Change::of_kind(kind, number, value));
            Ok((t, changes.collect::<Result<Vec<_>, _>>().map_err(|e| errors::value_error(&e))?))
        })
        .collect::<PyResult<Vec<_>>>()?;
    let compiled: Vec<OnceLock<Result<Compiled, Diagnostics>>> = texts.iter().map(|_| OnceLock::new()).collect();
    let n = variants.len();
    let workers = workers.unwrap_or_else(batch::available_workers);
    let cancel = AtomicBool::new(false);
    // Converted for Python once per text, when its first result arrives.
    let mut shared: Vec<Option<Shared>> = texts.iter().map(|_| None).collect();
    let mut results: Vec<Option<Py<PyAny>>> = (0..n).map(|_| None).collect();
    let mut raised: Option<PyErr> = None;
    let mut done = 0;

    // Python's signal handlers run on the calling thread, one of the workers
    // (`batch::stream`): a variant it runs itself looks for Ctrl-C as it goes.
    let caller = std::thread::current().id();
    let job = |k: usize| {
        let (t, changes) = &variants[k];
        let c = compiled[*t].get_or_init(|| texts[*t].compile(&path, &base_dir));
        let watch = (std::thread::current().id() == caller).then(Progress::interrupts);
        run_variant(c, changes, order, &cancel, watch, memory_limit)
    };
    // On the calling thread, as variants finish (or every POLL while it waits for some).
    let mut take = |finished: Option<(usize, (Outcome, Option<PyErr>))>| {
        done += usize::from(finished.is_some());
        if raised.is_some() {
            return false;
        }
        let finished = match finished {
            Some((_, (_, Some(interrupted)))) => {
                raised = Some(interrupted);
                return false;
            }
            Some((k, (outcome, None))) => Some((k, outcome)),
            None => None,
        };
        let result = Python::attach(|py| -> PyResult<()> {
            py.check_signals()?;
            let arrived = finished.is_some();
            if let Some((k, outcome)) = finished {
                let t = variants[k].0;
                let text = match compiled[t].get() {
                    Some(Ok(c)) => Some((
                        c,
                        &*match &mut shared[t] {
                            Some(s) => s,
                            slot => slot.insert(Shared::new(py, c)?),
                        },
                    )),
                    _ => None,
                };
                let object = match outcome_run(py, outcome, text, &path, false) {
                    Ok(run) => Py::new(py, run)?.into_any(),
                    Err(e) => e.into_value(py).into_any(),
                };
                match &on_result {
                    Some(callback) => drop(callback.call1(py, (k, object))?),
                    None => results[k] = Some(object),
                }
            }
            match &progress {
                Some(callback) if arrived => callback.call1(py, (done, n)).map(drop),
                _ => Ok(()),
            }
        });
        match result {
            Ok(()) => true,
            Err(e) => {
                raised = Some(e);
                false
            }
        }
    };
    py.detach(|| batch::stream(n, workers, &cancel, POLL, job, &mut take));
    if let Some(err) = raised {
        return Err(err);
    }
    if on_result.is_some() {
        return Ok(Vec::new());
    }
    results.into_iter().map(|object| object.ok_or_else(|| errors::lost(Lost::BatchRun))).collect()
}
