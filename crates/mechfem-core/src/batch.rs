//! Independent analyses on several cores.
//!
//! A design study runs many variants of a mechanism (other dimensions,
//! another motion). Each run has its own [`crate::Mechanism`], [`crate::State`]
//! and workspace and shares nothing with the others, so they spread over
//! threads with no locking. The threads are those of a rayon pool of the
//! size asked for, started the first time a batch needs it and kept for the
//! next ones (a study of many small batches starts no threads of its own):
//!
//! * [`map`] runs every job and returns the results in job order;
//! * [`stream`] hands each result to a sink on the calling thread, which
//!   works through the jobs beside the pool's threads, and stops starting
//!   jobs when asked to.
//!
//! ```
//! use mechfem_core::batch;
//! // Stand-in for "build variant k and run it".
//! let squares = batch::map(10, 2, |k| k * k);
//! assert_eq!(squares, (0..10).map(|k| k * k).collect::<Vec<_>>());
//! ```

use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{mpsc, Mutex, PoisonError};
use std::time::Duration;

use rayon::prelude::*;
use rayon::{ThreadPool, ThreadPoolBuilder};

/// The number of threads the machine runs in parallel (1 when unknown): the
/// default number of workers.
pub fn available_workers() -> usize {
    std::thread::available_parallelism().map_or(1, usize::from)
}

/// Pools not in use, with their number of threads.
static IDLE: Mutex<Vec<(usize, ThreadPool)>> = Mutex::new(Vec::new());

/// A pool of `workers` threads lent to one batch and given back when it
/// ends: batches run at the same time from different threads (the tasks
/// of a threaded executor, each running its chunk of a study) each have
/// threads of their own instead of queueing on one shared pool.
struct Lease {
    workers: usize,
    pool: Option<ThreadPool>,
}

impl Lease {
    fn new(workers: usize) -> Lease {
        let idle = {
            let mut idle = IDLE.lock().unwrap_or_else(PoisonError::into_inner);
            idle.iter().position(|(w, _)| *w == workers).map(|k| idle.swap_remove(k).1)
        };
        let pool = idle.unwrap_or_else(|| {
            ThreadPoolBuilder::new()
                .num_threads(workers)
                .thread_name(|k| format!("mechfem-worker-{k}"))
                .build()
                .expect("the operating system starts the worker threads")
        });
        Lease { workers, pool: Some(pool) }
    }

    fn pool(&self) -> &ThreadPool {
        self.pool.as_ref().expect("a lease holds its pool until dropped")
    }
}

impl Drop for Lease {
    fn drop(&mut self) {
        if let Some(pool) = self.pool.take() {
            IDLE.lock().unwrap_or_else(PoisonError::into_inner).push((self.workers, pool));
        }
    }
}

/// Calls `job(k)` for every `k` in `0..jobs` on up to `workers` threads and
/// returns the results in the order of `k`. With one worker (or one job)
/// everything runs on the calling thread. A panic in a job is propagated
/// once every worker has stopped.
pub fn map<T, F>(jobs: usize, workers: usize, job: F) -> Vec<T>
where
    T: Send,
    F: Fn(usize) -> T + Sync,
{
    let workers = workers.clamp(1, jobs.max(1));
    if workers == 1 {
        return (0..jobs).map(&job).collect();
    }
    Lease::new(workers).pool().install(|| (0..jobs).into_par_iter().map(&job).collect())
}

/// Calls `job(k)` for every `k` in `0..jobs` on up to `workers` threads and
/// hands each result to `sink` on the calling thread: `sink(Some((k,
/// result)))` once per job, and `sink(None)` whenever `poll` passes with
/// none finished, so that the caller can look for an interruption in
/// between.
///
/// The calling thread is one of the workers, beside `workers - 1` threads
/// of a pool: it takes jobs as they do, and between two of its own jobs
/// hands over whatever has finished. So exactly `workers` threads run (the
/// sink's work, which may need a lock such as Python's, takes its share of
/// one of them instead of competing with them), and with one worker
/// everything runs on the calling thread, in job order. Each worker takes
/// the next job not yet taken, which keeps every thread busy even when the
/// jobs take different times; a long job on the calling thread holds up the
/// hand-over, so such a job may look for interruptions itself.
///
/// Once `cancel` is set (by a job, by another thread, or because `sink`
/// returned `false`) no more jobs start; those running finish (a job may
/// watch `cancel` to stop early) and their results still reach the sink.
/// Returns when every job started has been handed over; a panic in a job is
/// propagated then, and stops the other workers taking jobs.
pub fn stream<T, J, S>(jobs: usize, workers: usize, cancel: &AtomicBool, poll: Duration, job: J, mut sink: S)
where
    T: Send,
    J: Fn(usize) -> T + Sync,
    S: FnMut(Option<(usize, T)>) -> bool,
{
    let workers = workers.clamp(1, jobs.max(1));
    let next = AtomicUsize::new(0);
    let take = || match cancel.load(Ordering::Relaxed) {
        true => None,
        false => Some(next.fetch_add(1, Ordering::Relaxed)).filter(|&k| k < jobs),
    };
    let mut hand = |item: Option<(usize, T)>| {
        if !sink(item) {
            cancel.store(true, Ordering::Relaxed);
        }
    };
    if workers == 1 {
        while let Some(k) = take() {
            hand(Some((k, job(k))));
        }
        return;
    }
    let (tx, rx) = mpsc::channel::<(usize, T)>();
    let lease = Lease::new(workers - 1);
    lease.pool().in_place_scope(|s| {
        for _ in 1..workers {
            let (tx, job, take) = (tx.clone(), &job, &take);
            s.spawn(move |_| {
                // A panic in a job stops the other workers taking more.
                let _stop = StopOnPanic(cancel);
                while let Some(k) = take() {
                    if tx.send((k, job(k))).is_err() {
                        break;
                    }
                }
            });
        }
        drop(tx);
        let _stop = StopOnPanic(cancel);
        while let Some(k) = take() {
            hand(Some((k, job(k))));
            while let Ok(item) = rx.try_recv() {
                hand(Some(item));
            }
        }
        // Every job is taken: what is left is the pool's.
        loop {
            match rx.recv_timeout(poll) {
                Ok(item) => hand(Some(item)),
                Err(mpsc::RecvTimeoutError::Timeout) => hand(None),
                Err(mpsc::RecvTimeoutError::Disconnected) => break,
            }
        }
    });
}

/// Sets the flag when dropped while its thread panics.
struct StopOnPanic<'a>(&'a AtomicBool);

impl Drop for StopOnPanic<'_> {
    fn drop(&mut self) {
        if std::thread::panicking() {
            self.0.store(true, Ordering::Relaxed);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::HashSet;

    const POLL: Duration = Duration::from_millis(10);

    #[test]
    fn results_come_back_in_job_order() {
        for workers in [1, 2, 3, 8] {
            let r = map(25, workers, |k| 2 * k + 1);
            assert_eq!(r, (0..25).map(|k| 2 * k + 1).collect::<Vec<_>>());
        }
        assert!(map(0, 4, |k| k).is_empty());
    }

    #[test]
    fn every_job_runs_once() {
        let seen = Mutex::new(HashSet::new());
        map(200, 4, |k| assert!(seen.lock().unwrap().insert(k)));
        assert_eq!(seen.lock().unwrap().len(), 200);
    }

    #[test]
    #[should_panic(expected = "job 7 failed")]
    fn a_failing_job_panics_the_caller() {
        map(20, 2, |k| assert!(k != 7, "job 7 failed"));
    }

    #[test]
    fn a_stream_hands_over_every_result_once_on_the_calling_thread() {
        let caller = std::thread::current().id();
        for workers in [1, 2, 5] {
            let cancel = AtomicBool::new(false);
            let mut got = vec![None; 60];
            let mut threads = HashSet::new();
            stream(
                60,
                workers,
                &cancel,
                POLL,
                |k| (k, std::thread::current().id()),
                |item| {
                    assert_eq!(std::thread::current().id(), caller);
                    if let Some((k, (value, thread))) = item {
                        assert!(got[k].is_none(), "job {k} handed over twice");
                        threads.insert(thread);
                        got[k] = Some(value);
                    }
                    true
                },
            );
            assert_eq!(got, (0..60).map(Some).collect::<Vec<_>>());
            assert!(threads.len() <= workers, "{} threads ran the jobs of {workers} workers", threads.len());
            if workers == 1 {
                assert_eq!(threads, HashSet::from([caller]));
            }
        }
    }

    #[test]
    fn the_calling_thread_polls_while_the_pool_works() {
        let caller = std::thread::current().id();
        // Both jobs start at once, so the pool has one; it takes a while.
        let meet = std::sync::Barrier::new(2);
        let cancel = AtomicBool::new(false);
        let (mut polls, mut results) = (0, 0);
        let job = |_| {
            meet.wait();
            if std::thread::current().id() != caller {
                std::thread::sleep(Duration::from_millis(80));
            }
        };
        stream(2, 2, &cancel, POLL, job, |item| {
            polls += usize::from(item.is_none());
            results += usize::from(item.is_some());
            true
        });
        assert_eq!(results, 2);
        assert!(polls >= 2, "{polls} polls");
    }

    #[test]
    fn a_stream_with_one_worker_takes_the_jobs_in_order() {
        let cancel = AtomicBool::new(false);
        let mut order = Vec::new();
        stream(
            30,
            1,
            &cancel,
            POLL,
            |k| k,
            |item| {
                order.extend(item.map(|(k, _)| k));
                true
            },
        );
        assert_eq!(order, (0..30).collect::<Vec<_>>());
    }

    #[test]
    fn a_sink_that_says_stop_starts_no_more_jobs() {
        let cancel = AtomicBool::new(false);
        let started = AtomicUsize::new(0);
        let mut handed = 0;
        stream(
            1000,
            2,
            &cancel,
            POLL,
            |_| {
                started.fetch_add(1, Ordering::Relaxed);
                std::thread::sleep(Duration::from_millis(1));
            },
            |item| {
                handed += usize::from(item.is_some());
                handed < 5
            },
        );
        assert!(cancel.load(Ordering::Relaxed));
        // The jobs running when the sink said stop still finish and are handed over.
        assert_eq!(handed, started.load(Ordering::Relaxed));
        assert!(handed < 1000, "{handed} jobs ran after the sink said stop");
    }

    #[test]
    fn a_cancelled_stream_starts_nothing() {
        let cancel = AtomicBool::new(true);
        stream(
            10,
            2,
            &cancel,
            POLL,
            |k| k,
            |item| {
                assert!(item.is_none(), "a job started after the batch was cancelled");
                true
            },
        );
    }

    #[test]
    #[should_panic(expected = "job 3 failed")]
    fn a_failing_job_in_a_stream_panics_the_caller() {
        let cancel = AtomicBool::new(false);
        stream(20, 2, &cancel, POLL, |k| assert!(k != 3, "job 3 failed"), |_| true);
    }

    #[test]
    fn batches_at_the_same_time_each_have_their_threads() {
        // Two two-worker batches at once, whose four jobs wait for each other: unless each
        // batch has a pool thread of its own beside its calling thread, one job never starts
        // and neither batch ends.
        let meet = std::sync::Barrier::new(4);
        std::thread::scope(|s| {
            for _ in 0..2 {
                s.spawn(|| {
                    let cancel = AtomicBool::new(false);
                    stream(2, 2, &cancel, POLL, |_| _ = meet.wait(), |_| true);
                });
            }
        });
    }
}
