"""Design studies: many variants of a mechanism run on every core, summarised in a table.

A study of one mechanism hands it to the typed builder once (:mod:`mechfem.run.building`, no deck text); every
variant is a copy of the built model with some values changed, compiled once and run by the compiled module on
worker threads without the GIL (``_core.run_deck_variants``), so no Python runs per position (a model function's
mechanisms are built one per variant instead). Per
variant, the ``measures`` (Python functions of its :class:`~mechfem.RunResult`) give one number each::

    study = mechfem.sweep(
        supply,
        {"kappa": np.linspace(-5.25, -5.10, 16)},
        measures={"stroke": lambda r: np.ptp(r.output("delta"))},
        motion=Motion.by(72, 2 * math.pi),
    )
    study["stroke"]            # one value per variant
    study.to_pandas()          # the same as a DataFrame (needs pandas)
"""

from __future__ import annotations

import inspect
import itertools
import math
import operator
import warnings
from collections.abc import Callable, Iterator, Mapping, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np
import numpy.typing as npt

import mechfem._core as _core
from mechfem._util import optional
from mechfem._util.limits import memory_limit
from mechfem._util.names import unknown_name
from mechfem.errors import IncompleteRunWarning, MechfemError, RunStoppedError, user_stacklevel
from mechfem.model.mechanism import Mechanism, Motion, Storage
from mechfem.results.result import RunResult
from mechfem.run import compiled
from mechfem.run.namespace import model_result
from mechfem.studies import cluster

if TYPE_CHECKING:
    from mechfem.run import building

FloatArray = npt.NDArray[np.float64]
Measure = Callable[[RunResult], float]
Progress = bool | Callable[[int, int], object] | None


def _variants(parameters: Mapping[str, npt.ArrayLike] | Sequence[Mapping[str, Any]]) -> list[dict[str, Any]]:
    if isinstance(parameters, Mapping):
        names = list(parameters)
        values = [list(np.atleast_1d(np.asarray(parameters[n]))) for n in names]
        return [dict(zip(names, combo, strict=True)) for combo in itertools.product(*values)]
    return [dict(p) for p in parameters]


def _plain(v: Any) -> Any:
    return v.item() if isinstance(v, np.generic) else v


_SCALARS = (bool, int, float, str, np.generic)
"""Types whose values are scalars for numpy, told apart without asking numpy (a table has a value per variant)."""


def _scalar(v: Any) -> bool:
    return isinstance(v, _SCALARS) or np.ndim(v) == 0


def _column(values: list[Any], dtype: type | None = None) -> npt.NDArray[Any]:
    """One column: a plain numpy array, or an array of objects for values that are not scalars (points)."""
    if dtype is None and all(_scalar(v) for v in values):
        return np.asarray(values)
    out = np.empty(len(values), dtype=object)
    out[:] = [v if _scalar(v) else tuple(v) for v in values]
    return out


def run_many(
    mechanisms: Sequence[Mechanism],
    motion: Motion | None = None,
    storage: Storage | None = None,
    *,
    workers: int | None = None,
    progress: Progress = True,
    order: int | None = 2,
    executor: object | None = None,
    chunk_size: int | None = None,
    retries: int = cluster.RETRIES,
    raise_on_stop: bool = False,
) -> list[RunResult | MechfemError]:
    """Runs every mechanism (each with ``motion``, default its own :attr:`~Mechanism.motion`) on ``workers``
    threads (default: one per core), computing the transfer functions of ``order`` (see
    :meth:`Mechanism.run`). Returns, in order, a :class:`RunResult` or the error that stopped that mechanism
    at position 1 (with the model's names).

    With an ``executor`` (a Dask ``distributed.Client`` or a ``concurrent.futures.Executor``) the mechanisms go
    out in chunks of ``chunk_size`` (see :func:`sweep`), each run on ``workers`` threads of its worker (default
    1); a :class:`RunResult` that comes back holds a copy of its mechanism, and a chunk that could not be run
    gives a :class:`MechfemError` with the reason for each of its mechanisms.

    A run whose motion stops before its last position gives its :class:`RunResult` all the same (its
    ``stop_reason()`` says why), and the call warns once with :class:`~mechfem.IncompleteRunWarning`; with
    ``raise_on_stop`` such a run gives a :class:`~mechfem.RunStoppedError` carrying its :class:`RunResult` instead.
    """
    workers = check_workers(workers)
    if executor is not None:
        out = _run_many_on(executor, list(mechanisms), motion, storage, workers, progress, order, chunk_size, retries)
    else:
        out = _run_many_here(mechanisms, motion, storage, workers, progress, order)
    return _stopped_runs(out, raise_on_stop)


#: The most threads a study or :func:`run_many` runs on: more are never faster on any machine.
MAX_WORKERS = 1024


def check_workers(workers: int | None) -> int | None:
    """``workers`` when it is None (one thread per core) or a whole number from 1 to :data:`MAX_WORKERS`; else a
    ValueError that says so."""
    if workers is None:
        return None
    try:
        whole = None if isinstance(workers, bool) else operator.index(workers)
    except TypeError:
        whole = None
    if whole is None or not 1 <= whole <= MAX_WORKERS:
        raise ValueError(
            f"workers is the number of threads to run on: a whole number from 1 to {MAX_WORKERS}, or None for one "
            f"per core, not {workers!r}"
        )
    return whole


def _stopped_runs(results: list[RunResult | MechfemError], raise_on_stop: bool) -> list[RunResult | MechfemError]:
    """``results`` with each run that stopped early as a :class:`RunStoppedError` (``raise_on_stop``), or as it
    is after one warning that counts them."""
    stopped = [k for k, r in enumerate(results) if isinstance(r, RunResult) and r._raw.stopped]
    for k in stopped if raise_on_stop else ():
        a = results[k]
        assert isinstance(a, RunResult)
        results[k] = RunStoppedError(a.stop_reason() or "", a)
    if stopped and not raise_on_stop:
        first = results[stopped[0]]
        assert isinstance(first, RunResult)
        warnings.warn(
            f"{len(stopped)} of {len(results)} runs stopped before their last position; the first, index "
            f"{stopped[0]} (mechanism {first.mechanism.name!r}): {first.stop_reason()} (raise_on_stop=True gives "
            "a RunStoppedError for each of them instead)",
            IncompleteRunWarning,
            stacklevel=user_stacklevel(),
        )
    return results


def _run_many_here(
    mechanisms: Sequence[Mechanism],
    motion: Motion | None,
    storage: Storage | None,
    workers: int | None,
    progress: Progress,
    order: int | None,
) -> list[RunResult | MechfemError]:
    """:func:`run_many` on the threads of this process."""
    from mechfem.run import building

    # One model per distinct mechanism: the same mechanism given many times is built and compiled once.
    written: dict[tuple[int, int, int], int] = {}
    built: list[building.Built] = []
    sources: list[tuple[Motion | None, Storage | None]] = []
    variants: list[Variant] = []
    for m in mechanisms:
        mo, st = motion or m.motion, storage or m.storage
        key = (id(m), id(mo), id(st))
        if key not in written:
            written[key] = len(built)
            built.append(building.builder(m, mo, st))
            sources.append((mo, st))
        variants.append((written[key], []))
    outs = _run_variants(built, variants, workers, progress, order=order)
    results: list[RunResult | MechfemError] = []
    for m, (t, _), o in zip(mechanisms, variants, outs, strict=True):
        b = built[t]
        if isinstance(o, MechfemError):
            results.append(building.explain(o, b, m, *sources[t]))
        else:
            results.append(model_result(m, b.numbering, o, b.path))
    return results


@dataclass
class _ManyChunk:
    """The mechanisms of :func:`run_many` that one task runs."""

    mechanisms: list[Mechanism]
    motion: Motion | None
    storage: Storage | None
    workers: int | None
    order: int | None


def _run_many_chunk(c: _ManyChunk) -> list[RunResult | MechfemError]:
    return _run_many_here(c.mechanisms, c.motion, c.storage, c.workers, False, c.order)


def _run_many_on(
    executor: object,
    mechanisms: list[Mechanism],
    motion: Motion | None,
    storage: Storage | None,
    workers: int | None,
    progress: Progress,
    order: int | None,
    requested: int | None,
    retries: int,
) -> list[RunResult | MechfemError]:
    if not mechanisms:
        return []
    size = cluster.chunk_size(len(mechanisms), _positions(motion or mechanisms[0].motion), executor, requested)
    parts = cluster.chunks(len(mechanisms), size)
    tasks = [_ManyChunk([mechanisms[k] for k in r], motion, storage, workers or 1, order) for r in parts]
    outs = _on_executor(executor, _run_many_chunk, tasks, parts, progress, retries)
    results: list[RunResult | MechfemError] = []
    for r, out in zip(parts, outs, strict=True):
        if isinstance(out, cluster.TaskFailed):
            results += [MechfemError(f"the task of this chunk failed: {out.reason}") for _ in r]
        else:
            results += out
    return results


def _positions(motion: Motion | None) -> int:
    return int(motion.steps) + 1 if motion is not None else 1


def _on_executor(
    executor: object,
    fn: Callable[[Any], Any],
    tasks: Sequence[Any],
    parts: Sequence[range],
    progress: Progress,
    retries: int,
) -> list[Any]:
    """The tasks' results in order, with the progress counted in variants as chunks finish."""
    from mechfem.deck import deckio

    callback = deckio.progress_callback(progress, "variants")
    total = sum(len(r) for r in parts)
    done = [0]

    def finished(k: int, _: object) -> None:
        done[0] += len(parts[k])
        if callback is not None:
            callback(done[0], total)

    try:
        return cluster.run_tasks(executor, fn, tasks, retries=retries, on_done=finished)
    finally:
        close = getattr(callback, "close", None)
        if close is not None:
            close()


Variant = tuple[int, list[tuple[int, int, float]]]
"""A built model (its index) and the changes of one variant: (0, co-ordinate, value) or (1, prescribed row,
value), in the model's deck numbering."""


def _run_variants(
    decks: list[building.Built],
    variants: list[Variant],
    workers: int | None,
    progress: Progress,
    on_result: Callable[[int, _core.Run | MechfemError], object] | None = None,
    order: int | None = 2,
) -> list[_core.Run | MechfemError]:
    from mechfem.deck import deckio

    files: dict[str, str] = {}
    for d in decks:
        for name, text in d.tables.items():
            if files.setdefault(name, text) != text:
                raise ValueError(f"the variants use different motion tables under one file name {name!r}")
    callback = deckio.progress_callback(progress, "variants")
    models = [d.builder for d in decks]
    try:
        with deckio.tables_dir(files) as base:
            return _core.run_deck_variants(
                models, variants, "variant.mec", base, workers, callback, on_result, order, memory_limit()
            )
    finally:
        close = getattr(callback, "close", None)
        if close is not None:
            close()


class Study:
    """The table of a design study: one row per variant, columns by name (numpy arrays).

    Columns: the parameters, ``ok`` (the variant ran: position 1 was computed, and with ``raise_on_stop`` every
    position), ``complete`` (every position),
    ``positions``, ``limits`` (limit positions met), ``error`` (the error's text, "" when ok), then the
    measures (NaN for a variant that failed). ``results`` keeps every :class:`RunResult` (or error) when
    the study was run with ``keep_results=True``.
    """

    def __init__(
        self,
        columns: dict[str, npt.NDArray[Any]],
        parameters: list[str],
        measures: list[str],
        results: list[RunResult | MechfemError] | None,
    ) -> None:
        self.columns = columns
        self.parameters = parameters
        self.measures = measures
        self.results = results

    def __getitem__(self, column: str) -> npt.NDArray[Any]:
        return self.columns[column]

    def __len__(self) -> int:
        return len(next(iter(self.columns.values()))) if self.columns else 0

    def __iter__(self) -> Iterator[dict[str, Any]]:
        return iter(self.records())

    def records(self) -> list[dict[str, Any]]:
        """One dict per variant."""
        names = list(self.columns)
        return [{n: _plain(self.columns[n][k]) for n in names} for k in range(len(self))]

    def best(self, measure: str, largest: bool = False) -> dict[str, Any]:
        """The record of the variant with the smallest (``largest``: largest) value of ``measure``."""
        values = np.asarray(self.columns[measure], dtype=np.float64)
        if np.all(np.isnan(values)):
            raise ValueError(f"no variant has a value of {measure!r}")
        k = int(np.nanargmax(values) if largest else np.nanargmin(values))
        return self.records()[k]

    def to_pandas(self) -> Any:
        """The table as a ``pandas.DataFrame`` (needs pandas: ``pip install 'mechfem[pandas]'``)."""
        return optional.pandas().DataFrame(self.columns)

    def _repr_html_(self) -> str:
        from mechfem.viz import notebook

        return notebook.study_html(self)

    def __repr__(self) -> str:
        ok = int(np.sum(self.columns["ok"])) if "ok" in self.columns else 0
        return f"Study({len(self)} variants, {ok} ok; columns {', '.join(self.columns)})"


def _nan_extreme(reduce: np.ufunc, fallback: Callable[[FloatArray], np.float64]) -> Callable[[FloatArray], float]:
    """``np.nanmin`` or ``np.nanmax`` (``fallback``) as the reduction by ``np.fmin`` or ``np.fmax`` that they are:
    the same value, without their checks, which cost more than reducing a few hundred positions. Only where every
    value is NaN does ``fallback`` itself say so (with its warning)."""

    def extreme(values: FloatArray) -> float:
        v = float(reduce.reduce(values))
        return float(fallback(values)) if math.isnan(v) else v

    return extreme


_SMALLEST = _nan_extreme(np.fmin, np.nanmin)
_LARGEST = _nan_extreme(np.fmax, np.nanmax)


def default_measures(mech: Mechanism) -> dict[str, Measure]:
    """The smallest and largest value of every output, and the smallest |det(D^c)|."""
    out: dict[str, Measure] = {}

    def extreme(name: str, fn: Callable[[FloatArray], float]) -> Measure:
        return lambda a: fn(a.output(name))

    for r in mech.outputs:
        out[f"{r.name}.min"] = extreme(r.name, _SMALLEST)
        out[f"{r.name}.max"] = extreme(r.name, _LARGEST)
    out["min_abs_det"] = lambda a: _SMALLEST(np.abs(a.det))
    return out


@dataclass
class _Chunk:
    """The variants of a study that one task runs: the motion and storage of each model they change (each once),
    the mechanism of each model, every variant's model (its index here) and changes, its parameters, and the
    measures. ``built`` holds the models handed to the builder when the chunk runs where they were built (a task
    sent to an executor builds them itself: a builder stays in its process)."""

    sources: list[tuple[Motion | None, Storage | None]]
    mechanisms: list[Mechanism]
    variants: list[Variant]
    sets: list[dict[str, Any]]
    names: list[str]
    measures: dict[str, Measure]
    order: int | None
    keep: bool
    workers: int | None
    raise_on_stop: bool = False
    built: list[building.Built] | None = None


Rows = tuple[list[list[Any]], list["RunResult | MechfemError | None"]]


def _failed_row(p: dict[str, Any], names: list[str], measures: int, text: str) -> list[Any]:
    return [*(_plain(p.get(n, math.nan)) for n in names), False, False, 0, 0, text, *(math.nan,) * measures]


def _study_rows(c: _Chunk, progress: Progress = False) -> Rows:
    """Runs a chunk of a study: every variant's row of the table (and its result when ``c.keep``)."""
    from mechfem.run import building

    built = c.built
    if built is None:
        built = [building.builder(m, mo, st) for m, (mo, st) in zip(c.mechanisms, c.sources, strict=True)]
    rows: list[list[Any]] = [[] for _ in c.sets]
    kept: list[RunResult | MechfemError | None] = [None] * len(c.sets)

    def take(k: int, o: _core.Run | MechfemError) -> None:
        # Called as each variant finishes, while the workers go on with the others.
        p, t = c.sets[k], c.variants[k][0]
        m, d = c.mechanisms[t], built[t]
        if isinstance(o, MechfemError):
            err = building.explain(o, d, m, *c.sources[t])
            kept[k] = err if c.keep else None
            text = str(err).splitlines()[0] if str(err) else type(err).__name__
            rows[k] = _failed_row(p, c.names, len(c.measures), text)
            return
        a = model_result(m, d.numbering, o, d.path, p)
        kept[k] = a if c.keep else None
        # What the table needs of the report, from the run's own (cheaper than the full report).
        report = o.report
        if o.stopped and c.raise_on_stop:
            # A stopped run counts as failed: its measures would cover part of the motion only.
            reason = a.stop_reason() or ""
            kept[k] = RunStoppedError(reason, a) if c.keep else None
            done = [False, False, a.positions, len(report.limits), reason]
            rows[k] = [*(_plain(p.get(n, math.nan)) for n in c.names), *done, *(math.nan,) * len(c.measures)]
            return
        values, errors = [], []
        for name, fn in c.measures.items():
            try:
                values.append(float(fn(a)))
            except Exception as err:
                values.append(math.nan)
                errors.append(f"measure {name!r}: {type(err).__name__}: {err}")
        done = [True, not o.stopped, a.positions, len(report.limits), "; ".join(errors)]
        rows[k] = [*(_plain(p.get(n, math.nan)) for n in c.names), *done, *values]

    _run_variants(built, c.variants, c.workers, progress, take, c.order)
    return rows, kept


def sweep(
    model: Mechanism | Callable[..., Mechanism],
    parameters: Mapping[str, npt.ArrayLike] | Sequence[Mapping[str, Any]],
    measures: Mapping[str, Measure] | None = None,
    *,
    motion: Motion | None = None,
    storage: Storage | None = None,
    workers: int | None = None,
    progress: Progress = True,
    keep_results: bool = False,
    order: int | None = 2,
    executor: object | None = None,
    chunk_size: int | None = None,
    retries: int = cluster.RETRIES,
    raise_on_stop: bool = False,
) -> Study:
    """Runs a design study and tabulates it.

    ``model`` is a mechanism whose named values (see :meth:`Mechanism.set`: prescribed rows, co-ordinates,
    points) the parameters change, or a function that builds a mechanism from the parameters as keyword
    arguments. ``parameters`` is a mapping name -> values (every combination is run: one name gives a
    range, several a grid) or a list of parameter sets. ``measures`` maps a column name to a function of
    the variant's :class:`RunResult` (default :func:`default_measures`); a measure that raises leaves NaN and
    its error in the variant's ``error``. Variants run on ``workers`` threads
    (default: one per core) with a progress bar (``progress=False`` for none, or a callable
    ``progress(done, total)``). ``order`` is the transfer functions computed (see :meth:`Mechanism.run`);
    ``order=1`` is faster when the measures need no second order.

    With an ``executor`` (a Dask ``distributed.Client``, or any ``concurrent.futures.Executor``) the variants go
    out in chunks of ``chunk_size`` (default: about a second of work each, and at least two chunks for every
    worker thread); a chunk's task gets the deck text once, compiles it once and runs its variants on
    ``workers`` threads of its worker (default 1: Dask runs one task per worker thread), and sends back the
    rows (and the full results with ``keep_results``). A Dask task that raises is run again up to ``retries``
    times; a chunk that cannot be run at all is a set of rows with ``ok`` False and the reason in ``error``.

    A variant whose motion stops before its last position has ``complete`` False and measures of the positions it
    computed, and the study warns once with :class:`~mechfem.IncompleteRunWarning`; with ``raise_on_stop`` such
    a variant fails instead: ``ok`` False, NaN measures, the stop reason in ``error`` (and a
    :class:`~mechfem.RunStoppedError` carrying its :class:`RunResult` in ``results``).
    """
    from mechfem.run import building

    workers = check_workers(workers)
    sets = _variants(parameters)
    if not sets:
        raise ValueError("a study needs at least one variant")
    mechanisms: list[Mechanism] = []
    decks: list[building.Built] = []
    sources: list[tuple[Motion | None, Storage | None]] = []
    variants: list[Variant] = []
    if isinstance(model, Mechanism):
        # One model for the whole study; each variant changes numbers of it.
        mo, st = motion or model.motion, storage or model.storage
        base = building.builder(model, mo, st)
        variants = [(0, compiled.changes_of(model._targets(p), base.numbering)) for p in sets]
        decks, mechanisms, sources = [base], [model], [(mo, st)]
    else:
        _check_arguments(model, sets)
        for k, p in enumerate(sets):
            m = model(**p)
            if not isinstance(m, Mechanism):
                raise TypeError(f"the model function returned {m!r}, not a Mechanism")
            mo, st = motion or m.motion, storage or m.storage
            decks.append(building.builder(m, mo, st))
            sources.append((mo, st))
            variants.append((k, []))
            mechanisms.append(m)
    chosen = dict(measures) if measures is not None else default_measures(mechanisms[0])
    names = list(sets[0]) if isinstance(parameters, Mapping) else sorted({k for p in sets for k in p})
    fixed = ["ok", "complete", "positions", "limits", "error"]
    for extra in (*fixed, *chosen):
        if extra in names or (extra in chosen and extra in fixed):
            raise ValueError(f"the column name {extra!r} is used twice")

    def part(r: range, threads: int | None, here: bool = False) -> _Chunk:
        # A chunk carries each model it needs once; here, the models built already.
        some, vs = sets[r.start : r.stop], variants[r.start : r.stop]
        if isinstance(model, Mechanism):
            ds = decks if here else None
            return _Chunk(sources, mechanisms, vs, some, names, chosen, order, keep_results, threads, raise_on_stop, ds)
        ss, ms, vs = sources[r.start : r.stop], mechanisms[r.start : r.stop], [(j, []) for j in range(len(r))]
        ds = decks[r.start : r.stop] if here else None
        return _Chunk(ss, ms, vs, some, names, chosen, order, keep_results, threads, raise_on_stop, ds)

    if executor is None:
        rows, kept = _study_rows(part(range(len(sets)), workers, here=True), progress)
    else:
        positions = _positions(motion or mechanisms[0].motion)
        parts = cluster.chunks(len(sets), cluster.chunk_size(len(sets), positions, executor, chunk_size))
        tasks = [part(r, workers or 1) for r in parts]
        rows, kept = [], []
        for r, out in zip(parts, _on_executor(executor, _study_rows, tasks, parts, progress, retries), strict=True):
            if isinstance(out, cluster.TaskFailed):
                text = f"the task of this chunk failed: {out.reason}"
                rows += [_failed_row(sets[k], names, len(chosen), text) for k in r]
                kept += [MechfemError(text) if keep_results else None for _ in r]
            else:
                rows += out[0]
                kept += out[1]
    columns: dict[str, list[Any]] = {n: [r[c] for r in rows] for c, n in enumerate([*names, *fixed, *chosen])}
    results = [r for r in kept if r is not None] if keep_results else None
    arrays = {n: _column(v) for n, v in columns.items()}
    arrays["error"] = _column(columns["error"], object)
    stopped = int(np.sum(arrays["ok"] & ~arrays["complete"])) if len(rows) else 0
    if stopped:
        warnings.warn(
            f"{stopped} of {len(rows)} variants stopped before their last position: their rows have complete False, "
            "and their measures cover the positions computed only (raise_on_stop=True makes them failed rows with "
            "the reason in error)",
            IncompleteRunWarning,
            stacklevel=user_stacklevel(),
        )
    return Study(arrays, names, list(chosen), results)


def _check_arguments(model: Callable[..., Mechanism], sets: list[dict[str, Any]]) -> None:
    """A study's parameter that the model function does not take is an error that names the closest it takes."""
    try:
        signature = inspect.signature(model)
    except (TypeError, ValueError):
        return
    kinds = {p.kind for p in signature.parameters.values()}
    if inspect.Parameter.VAR_KEYWORD in kinds:
        return
    takes = [n for n, p in signature.parameters.items() if p.kind in (p.POSITIONAL_OR_KEYWORD, p.KEYWORD_ONLY)]
    for name in dict.fromkeys(k for p in sets for k in p):
        if name not in takes:
            where = f" of the model function {getattr(model, '__name__', model)!r}"
            raise unknown_name("parameter", name, takes, where)
