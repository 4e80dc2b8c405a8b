//! Independent analyses on several cores.
//!
//! A design study runs many variants of a mechanism (other dimensions,
//! another motion). Each run has its own [`crate::Mechanism`], [`crate::State`]
//! and workspace and shares nothing with the others, so they spread over
//! threads with no locking: [`map`] hands out the jobs one at a time to
//! scoped worker threads, which keeps every core busy even when the jobs
//! take different times, and returns the results in job order.
//!
//! ```
//! use mechfem_core::batch;
//! // Stand-in for "build variant k and run it".
//! let squares = batch::map(10, 2, |k| k * k);
//! assert_eq!(squares, (0..10).map(|k| k * k).collect::<Vec<_>>());
//! ```

use std::sync::atomic::{AtomicUsize, Ordering};

/// The number of threads the machine runs in parallel (1 when unknown): the
/// default number of workers for [`map`].
pub fn available_workers() -> usize {
    std::thread::available_parallelism().map_or(1, usize::from)
}

/// Calls `job(k)` for every `k` in `0..jobs` on up to `workers` threads and
/// returns the results in the order of `k`. Each worker takes the next job
/// not yet taken; with one worker (or one job) everything runs on the calling
/// thread. A panic in a job is propagated once every worker has stopped.
pub fn map<T, F>(jobs: usize, workers: usize, job: F) -> Vec<T>
where
    T: Send,
    F: Fn(usize) -> T + Sync,
{
    let workers = workers.clamp(1, jobs.max(1));
    if workers == 1 {
        return (0..jobs).map(&job).collect();
    }
    let next = AtomicUsize::new(0);
    let mut results: Vec<Option<T>> = (0..jobs).map(|_| None).collect();
    let done: Vec<Vec<(usize, T)>> = std::thread::scope(|s| {
        let handles: Vec<_> = (0..workers)
            .map(|_| {
                s.spawn(|| {
                    let mut mine = Vec::new();
                    loop {
                        let k = next.fetch_add(1, Ordering::Relaxed);
                        if k >= jobs {
                            break mine;
                        }
                        mine.push((k, job(k)));
                    }
                })
            })
            .collect();
        handles.into_iter().map(|h| h.join().unwrap_or_else(|e| std::panic::resume_unwind(e))).collect()
    });
    for (k, r) in done.into_iter().flatten() {
        results[k] = Some(r);
    }
    results.into_iter().map(|r| r.expect("every job ran")).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::HashSet;
    use std::sync::Mutex;

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
}
