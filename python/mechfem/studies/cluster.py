"""Tasks on an executor: a Dask ``distributed.Client`` or any ``concurrent.futures.Executor``.

The studies (:func:`mechfem.sweep`, :func:`mechfem.run_many`, :func:`mechfem.tolerance_study`) and the multi-start
optimisation (:func:`mechfem.optimize` with ``starts``) cut their work into tasks: pure functions of picklable
inputs (deck texts, mechanisms, the changes of each variant, the measures), each returning compact results. This
module sends them to an executor and brings the results back in order:

* on a Dask client every task is submitted with ``retries`` and without a key derived from its inputs; a worker
  lost mid-study is not a failure: the scheduler runs its tasks again elsewhere (the tasks are pure);
* a task that fails anyway (it raised ``retries + 1`` times, or killed every worker it ran on) gives a
  :class:`TaskFailed` in its place, so that the others are kept;
* without Dask installed nothing here imports it; ``executor=None`` never comes here.

A task's function and input travel as one cloudpickle (when installed; it comes with Dask), so lambdas and functions
of a script go as they are, to Dask and to a ``ProcessPoolExecutor`` alike; the task unpickles them itself, so that
an input a worker cannot read (a module only the client has) is that task's error, not a broken worker.
"""

from __future__ import annotations

import concurrent.futures
import math
import pickle
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

RETRIES = 3
"""How often a task that raised is run again on a Dask cluster before it counts as failed."""

CHUNK_POSITIONS = 150_000
"""Positions computed by one chunk of a study by default: about one second of one core for a four-bar."""


@dataclass
class TaskFailed:
    """A task that could not be run: ``reason`` is its error's type and text."""

    reason: str
    error: BaseException | None = None


def is_dask(executor: object) -> bool:
    """Whether ``executor`` is a Dask ``distributed.Client`` (checked without importing Dask)."""
    return any(c.__name__ == "Client" and c.__module__.startswith("distributed") for c in type(executor).__mro__)


def slots(executor: object) -> int:
    """How many tasks ``executor`` runs at once: the threads of every Dask worker, or the executor's workers."""
    if is_dask(executor):
        return max(1, sum(executor.nthreads().values()))  # type: ignore[attr-defined]
    return max(1, int(getattr(executor, "_max_workers", 1) or 1))


def chunk_size(n: int, positions: int, executor: object, requested: int | None = None) -> int:
    """Variants per task: ``requested``, or about :data:`CHUNK_POSITIONS` positions, but small enough that every
    slot of the executor gets at least two chunks of a study of ``n`` variants."""
    if requested is not None:
        if requested < 1:
            raise ValueError(f"chunk_size must be at least 1, got {requested}")
        return requested
    by_time = max(1, round(CHUNK_POSITIONS / max(positions, 1)))
    by_balance = max(1, math.ceil(n / (2 * slots(executor))))
    return min(by_time, by_balance)


def chunks(n: int, size: int) -> list[range]:
    """``range(n)`` cut into consecutive ranges of at most ``size``."""
    return [range(k, min(k + size, n)) for k in range(0, n, size)]


def _reason(err: BaseException) -> str:
    text = str(err).splitlines()[0] if str(err) else ""
    return f"{type(err).__name__}: {text}" if text else type(err).__name__


def _call_pickled(blob: bytes) -> Any:
    """Runs a task shipped as one pickle of ``(function, argument)``."""
    fn, arg = pickle.loads(blob)
    return fn(arg)


def _pickled(fn: Callable[[Any], Any], arg: Any) -> bytes:
    try:
        import cloudpickle
    except ImportError:  # pragma: no cover - cloudpickle comes with Dask
        return pickle.dumps((fn, arg))
    return bytes(cloudpickle.dumps((fn, arg)))


def run_tasks(
    executor: object,
    fn: Callable[[Any], Any],
    args: Sequence[Any],
    *,
    retries: int = RETRIES,
    on_done: Callable[[int, Any], object] | None = None,
    reraise: tuple[type[BaseException], ...] = (),
) -> list[Any]:
    """``[fn(a) for a in args]`` on ``executor``, in order; a task that failed is a :class:`TaskFailed`.

    ``on_done(k, result)`` is called in this thread as each task finishes (in the order they finish). An error of
    a type in ``reraise`` (a mistake of the caller, not of the cluster) cancels the other tasks and is raised, as
    is an error of ``on_done`` (Ctrl-C among them).
    """
    if is_dask(executor):
        from distributed import as_completed

        submit = executor.submit  # type: ignore[attr-defined]
        futures = [submit(_call_pickled, _pickled(fn, a), retries=retries, pure=False) for a in args]
        wait: Any = as_completed(futures)
    else:
        assert isinstance(executor, concurrent.futures.Executor), executor
        threads = isinstance(executor, concurrent.futures.ThreadPoolExecutor)
        futures = [executor.submit(fn, a) if threads else executor.submit(_call_pickled, _pickled(fn, a)) for a in args]
        wait = concurrent.futures.as_completed(futures)
    index = {f: k for k, f in enumerate(futures)}
    out: list[Any] = [None] * len(futures)
    try:
        for f in wait:
            k = index[f]
            try:
                out[k] = f.result()
            except reraise:
                raise
            except Exception as err:
                out[k] = TaskFailed(_reason(err), err)
            if on_done is not None:
                on_done(k, out[k])
    except BaseException:
        for f in futures:
            f.cancel()
        raise
    return out


__all__ = ["RETRIES", "TaskFailed", "chunk_size", "chunks", "is_dask", "run_tasks", "slots"]
