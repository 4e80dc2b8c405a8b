//! Many runs at once, for design studies: variants of a few deck texts
//! (each text with some co-ordinate or PARA values changed) are compiled
//! and run on a pool of worker threads with the GIL released. Each text is
//! read and compiled once, by the first worker that needs it; a variant
//! runs a copy with its changes made, so a study of one mechanism writes
//! and reads one deck, not one per variant. The calling thread waits for
//! the results; only it touches Python, to report progress and to hand each
//! result over as soon as it is there.

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{mpsc, OnceLock};
use std::time::Duration;

use mechfem_deck::{Compiled, Diagnostics};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

use crate::text::{compile_text, outcome_dict, run_variant, Change, Outcome};

/// A change as Python gives it: (kind, number, value); see [`Change::from_triple`].
type ChangeTriple = (u8, usize, f64);

/// How often the waiting thread looks for Ctrl-C while no run finishes.
const POLL: Duration = Duration::from_millis(100);

/// Runs every variant in `variants` on `workers` threads (default: one per
/// core). A variant is `(t, changes)`: deck text `texts[t]` (named `path`
/// in messages; MOV_FUNC files are read from `base_dir`) with `changes`
/// made, each `(kind, number, value)`: kind 0 sets co-ordinate `number`
/// (its XFIX or XMOV value), kind 1 prescribed row `number` (its PARA
/// value), as if the deck said so.
///
/// For each variant the result is either the dict `run_deck_text` returns
/// or the exception it would raise (an instance of `DeckError`,
/// `AssemblyError`, `ConvergenceError`, `LimitPositionError`,
/// `ResourceError` or `MechfemError`): one failing variant does not stop the others.
///
/// Without `on_result` the results are returned, in the order of `variants`.
/// With it, `on_result(k, result)` is called for variant k as soon as it has
/// finished, on the calling thread while the workers go on, and the list
/// returned is empty: a study can reduce each result and let it go.
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
    texts: Vec<String>,
    variants: Vec<(usize, Vec<ChangeTriple>)>,
    path: PathBuf,
    base_dir: PathBuf,
    workers: Option<usize>,
    progress: Option<Py<PyAny>>,
    on_result: Option<Py<PyAny>>,
    order: Option<u8>,
    memory_limit: u64,
) -> PyResult<Vec<Py<PyAny>>> {
    if let Some(k) = order.filter(|k| !(1..=2).contains(k)) {
        return Err(pyo3::exceptions::PyValueError::new_err(format!("order must be 1, 2 or None, not {k}")));
    }
    let variants = variants
        .into_iter()
        .map(|(t, changes)| {
            if t >= texts.len() {
                return Err(PyValueError::new_err(format!("variant of text {t}, but there are {} texts", texts.len())));
            }
            Ok((t, changes.into_iter().map(Change::from_triple).collect::<PyResult<Vec<_>>>()?))
        })
        .collect::<PyResult<Vec<_>>>()?;
    let compiled: Vec<OnceLock<Result<Compiled, Diagnostics>>> = texts.iter().map(|_| OnceLock::new()).collect();
    let n = variants.len();
    let cores = std::thread::available_parallelism().map_or(1, usize::from);
    let workers = workers.unwrap_or(cores).clamp(1, n.max(1));
    let next = AtomicUsize::new(0);
    let cancel = AtomicBool::new(false);
    // Each result is converted for Python as it arrives, while the workers go on.
    let mut results: Vec<Option<Py<PyAny>>> = (0..n).map(|_| None).collect();
    let mut raised: Option<PyErr> = None;

    py.detach(|| {
        let (tx, rx) = mpsc::channel::<(usize, Outcome)>();
        std::thread::scope(|s| {
            for _ in 0..workers {
                let tx = tx.clone();
                let (texts, variants, compiled) = (&texts, &variants, &compiled);
                let (next, cancel, path, base_dir) = (&next, &cancel, &path, &base_dir);
                s.spawn(move || {
                    while !cancel.load(Ordering::Relaxed) {
                        let k = next.fetch_add(1, Ordering::Relaxed);
                        let Some((t, changes)) = variants.get(k) else { break };
                        let c = compiled[*t].get_or_init(|| compile_text(&texts[*t], path, base_dir));
                        if tx.send((k, run_variant(c, changes, order, cancel, memory_limit))).is_err() {
                            break;
                        }
                    }
                });
            }
            drop(tx);
            let mut done = 0;
            loop {
                let finished = match rx.recv_timeout(POLL) {
                    Ok(item) => Some(item),
                    Err(mpsc::RecvTimeoutError::Timeout) => None,
                    Err(mpsc::RecvTimeoutError::Disconnected) => break,
                };
                let arrived = finished.is_some();
                if arrived {
                    done += 1;
                }
                if raised.is_some() {
                    continue;
                }
                let result = Python::attach(|py| -> PyResult<()> {
                    py.check_signals()?;
                    if let Some((k, outcome)) = finished {
                        let object = result_object(py, outcome, &path);
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
                if let Err(e) = result {
                    raised = Some(e);
                    cancel.store(true, Ordering::Relaxed);
                }
            }
        });
    });
    if let Some(err) = raised {
        return Err(err);
    }
    if on_result.is_some() {
        return Ok(Vec::new());
    }
    results
        .into_iter()
        .map(|object| object.ok_or_else(|| pyo3::exceptions::PyRuntimeError::new_err("a batch run was lost")))
        .collect()
}

/// The run dict, or the exception instance for a deck that failed.
fn result_object(py: Python<'_>, outcome: Outcome, path: &Path) -> Py<PyAny> {
    match outcome_dict(py, outcome, path) {
        Ok(d) => d.into_any().unbind(),
        Err(e) => e.into_value(py).into_any(),
    }
}
