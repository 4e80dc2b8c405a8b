"""The starts of a multi-start of :func:`mechfem.optimize`: space-filling draws in a start box, and every start
design assembled afresh.

* **Draws.** A scrambled Halton sequence (``scipy.stats.qmc.Halton``): its points fill the box evenly (a uniform
  random draw leaves holes and clusters), it takes any number of points (a Sobol sequence wants powers of two),
  and it is seeded. The box's dimensions are taken in the order of the variables' names, so the same seed gives
  the same start designs whatever order ``vary`` lists them in.
* **A four-bar** (:mod:`mechfem.design.fourbar_starts`) is drawn where its dyad closes over the crank's whole sweep in
  the problem (a whole turn with ``full_rotation``) and each draw assembled from its closed-form position 1 on the
  mechanism's assembly branch: its draws can do the problem's crank motion by construction.
* **A four-bar with free timing** whose targets are its coupler point's place has its starts fitted to them
  (:mod:`mechfem.design.fourbar_fit`): drawn coupler curves placed on the points, each start with the crank angles
  of its laid points as its own start timing (every other start a plain draw when no whole turn is asked).
* **Any other mechanism** draws in the box itself, and each start is reached by continuation from the mechanism's
  position 1: its variables move there in stages, each stage's position 1 solved from the last one's (a stage that
  fails is halved, down to 1/64 of the way). So every start lies on the branch of the mechanism's own estimates,
  and a start that cannot be reached (a limit position on the way: the design does not exist on that branch) is
  discarded with that reason before any optimisation.
* **Check.** Each draw, assembled, runs the problem's motion once (with free timing, from position 1 to every
  point's start value; with ``full_rotation``, a whole turn); the first ``starts - 1`` that can are the drawn
  starts. Those passed over are kept with their reason (``Optimum.rejected``), and ``Optimum.drawn`` counts every
  draw looked at, at most ``SCREEN`` per start, so ``(starts - 1) / drawn`` is the usable fraction of the draws.
"""

from __future__ import annotations

import copy
import dataclasses
import math
import time
from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING, Any, TypeVar

import numpy as np

from mechfem.design import fourbar_fit, fourbar_starts
from mechfem.design.engine import Infeasible
from mechfem.errors import MechfemError

if TYPE_CHECKING:
    from mechfem.design.optimise import Optimum
    from mechfem.design.timing import FreeTiming
    from mechfem.model.mechanism import Mechanism

T = TypeVar("T")

SMALLEST_STAGE = 1.0 / 64.0
SCREEN = 20
"""Draws looked at per drawn start, at most: a box of which less than one design in twenty can do the motion gives
fewer starts than asked for (``Optimum.starts`` says how many)."""
FULL_TURN_STEPS = 72
POSITION_ONE_STEP = 1e-9
"""The single step of the motion that computes a stage's position 1 (the second position is not used)."""


def draws(box: Mapping[str, tuple[float, float]], n: int, seed: int | None) -> list[dict[str, float]]:
    """``n`` start designs filling ``box`` (name -> (lo, hi)), independent of the order of its names."""
    from scipy.stats import qmc

    if n <= 0:
        return []
    names, lo, hi, unit = unit_draws(box, n, seed)
    points = qmc.scale(unit, lo, hi)
    return [dict(zip(names, map(float, p), strict=True)) for p in points]


def unit_draws(
    box: Mapping[str, tuple[float, float]], n: int, seed: int | None
) -> tuple[list[str], np.ndarray, np.ndarray, np.ndarray]:
    """The box's names (sorted: the draws do not depend on their order), lower and upper ends, and ``n`` scrambled
    Halton points in the unit cube of that order (n x names)."""
    from scipy.stats import qmc

    names = sorted(box)
    lo = np.array([float(box[k][0]) for k in names])
    hi = np.array([float(box[k][1]) for k in names])
    if not np.all(lo < hi):
        raise ValueError(f"the start box {dict(box)} has an empty range")
    unit = qmc.Halton(d=len(names), scramble=True, seed=np.random.default_rng(seed)).random(n)
    return names, lo, hi, unit


def assembled(mechanism: Mechanism, values: Mapping[str, float]) -> Mechanism | str:
    """The mechanism with ``values`` set and its moving co-ordinates at that design's position 1, reached by
    continuation from the mechanism's own position 1; or why it cannot be reached."""
    from mechfem.model.motion import Motion

    motion = Motion.by(1, POSITION_ONE_STEP)
    moving = [c.name for c in mechanism.coordinates if not c.fixed]
    start = {name: float(mechanism[name].value) for name in values}
    try:
        here = _position_one(mechanism, moving, motion)
    except MechfemError as e:
        return f"the mechanism's own position 1 cannot be computed: {e}"
    at, lam, h = copy.deepcopy(mechanism), 0.0, 0.25
    last_error = ""
    while lam < 1.0:
        nxt = min(1.0, lam + h)
        trial = copy.deepcopy(at)
        for name, v in values.items():
            trial.set(name, start[name] + nxt * (float(v) - start[name]))
        for name, x in zip(moving, here, strict=True):
            trial[name].value = x
        try:
            here = _position_one(trial, moving, motion)
        except MechfemError as e:
            last_error = str(e)
            h *= 0.5
            if h < SMALLEST_STAGE:
                return (
                    f"cannot be reached from the mechanism's design by continuation (stuck {lam:.0%} of the way: "
                    f"{last_error})"
                )
            continue
        at, lam, h = trial, nxt, min(2.0 * h, 1.0)
    for name, x in zip(moving, here, strict=True):
        at[name].value = x
    return at


def _position_one(mech: Mechanism, moving: Sequence[str], motion: object) -> list[float]:
    result = mech.run(motion)  # type: ignore[arg-type]
    out = [float(result.value(name)[0]) for name in moving]
    if not all(math.isfinite(x) for x in out):
        raise MechfemError("position 1 is not finite")
    return out


def runs_through(mech: Mechanism, kwargs: Mapping[str, Any]) -> str:
    """Why the assembled design ``mech`` cannot do the problem's motion ("" when it can): the motion stops (a limit
    position) or cannot be computed; with free timing, a point's start value cannot be reached from position 1;
    with ``full_rotation``, the input cannot turn fully."""
    import warnings

    from mechfem.design import timing as _timing
    from mechfem.errors import IncompleteRunWarning
    from mechfem.model.motion import Motion

    def whole(motion: Motion, what: str) -> str:
        with warnings.catch_warnings():
            # The stop is said here, as the reason the draw is passed over.
            warnings.simplefilter("ignore", IncompleteRunWarning)
            result = mech.run(motion)
        if result.complete:
            return ""
        return f"{what} stops after position {result.positions} of {motion.steps + 1} (a limit position)"

    try:
        free = kwargs.get("timing")
        if free is not None:
            start = float(mech[free.input].value)
            for k, theta in enumerate(free.starts):
                _timing._at(mech, free.input, start, float(theta), k)
        else:
            motion = kwargs.get("motion") or mech.motion
            if motion is not None and (why := whole(motion, "the motion")):
                return why
        if kwargs.get("full_rotation"):
            return whole(Motion.by(FULL_TURN_STEPS, 2.0 * math.pi), "a whole turn of the input")
    except (Infeasible, MechfemError, ValueError) as e:
        return str(e) or type(e).__name__
    return ""


def screened(
    mechanism: Mechanism,
    base: Mapping[str, float],
    box: Mapping[str, tuple[float, float]],
    n: int,
    seed: int | None,
    kwargs: Mapping[str, Any],
) -> tuple[list[dict[str, float]], list[Mechanism], list[tuple[dict[str, float], str]], int]:
    """The first ``n`` draws of ``box`` (in the sequence's order, at most ``SCREEN * n`` looked at) that assemble
    and do the problem's motion: their designs, their assembled mechanisms, the draws passed over with the reason,
    and how many draws were looked at.

    A four-bar with free timing and no whole turn of the crank asked takes every other start from plain draws of
    the box (the first of them first), assembled by continuation as any mechanism's, the rest from the draws made
    to close over the sweep of the start values. That sweep is no constraint of the problem (the timing moves), and
    the fitted draws crowd where the lengths' intervals are narrow; the plain draws that pass the check cover every
    linkage that reaches the start values evenly, rockers and linkages with a long crank on a short frame among
    them (where the straight line's exact solutions lie), on either assembly branch the continuation reaches. With
    a prescribed motion or a whole turn, the fitted draws are those of the constraint stated, and all starts are."""
    four_bar = _four_bar(mechanism, kwargs)
    if four_bar is None:
        plain = [(d, "") for d in draws(box, SCREEN * n, seed)]
        return _screen(mechanism, base, plain, n, kwargs, None)
    fb, branch, sweep = four_bar
    fitted = fourbar_starts.draws(fb, mechanism, box, SCREEN * n, seed, sweep)
    if sweep is None or kwargs.get("timing") is None:
        return _screen(mechanism, base, fitted, n, kwargs, (fb, branch))
    half = (n + 1) // 2
    plain = [(d, "") for d in draws(box, SCREEN * half, seed)]
    one = _screen(mechanism, base, plain, half, kwargs, None)
    other = _screen(mechanism, base, fitted, n - len(one[0]), kwargs, (fb, branch))
    return _alternate(one[0], other[0]), _alternate(one[1], other[1]), one[2] + other[2], one[3] + other[3]


def _alternate(first: Sequence[T], second: Sequence[T]) -> list[T]:
    """The items of two lists taken in turn, the first's first; the longer one's last items at the end."""
    out: list[T] = []
    for k in range(max(len(first), len(second))):
        out += ([first[k]] if k < len(first) else []) + ([second[k]] if k < len(second) else [])
    return out


def _screen(
    mechanism: Mechanism,
    base: Mapping[str, float],
    candidates: Sequence[tuple[dict[str, float], str]],
    n: int,
    kwargs: Mapping[str, Any],
    four_bar: tuple[fourbar_starts.FourBar, float] | None,
) -> tuple[list[dict[str, float]], list[Mechanism], list[tuple[dict[str, float], str]], int]:
    begins: list[dict[str, float]] = []
    reached: list[Mechanism] = []
    rejected: list[tuple[dict[str, float], str]] = []
    looked = 0
    for d, why in candidates:
        if len(begins) == n:
            break
        looked += 1
        begin = {**base, **d}
        if why:
            rejected.append((begin, why))
            continue
        at = (
            assembled(mechanism, begin)
            if four_bar is None
            else fourbar_starts.assembled(four_bar[0], mechanism, four_bar[1], begin)
        )
        why = f"cannot be assembled: {at}" if isinstance(at, str) else runs_through(at, kwargs)
        if why or isinstance(at, str):
            rejected.append((begin, why))
            continue
        begins.append(begin)
        reached.append(at)
    return begins, reached, rejected, looked


def _four_bar(
    mechanism: Mechanism, kwargs: Mapping[str, Any]
) -> tuple[fourbar_starts.FourBar, float, tuple[float, float] | None] | None:
    """The four-bar ``mechanism`` is, with its assembly branch (the side of A -> B0 its position 1 has B on) and the
    crank's sweep in the problem (:func:`fourbar_starts.sweep`), when its starts are drawn and assembled as a
    four-bar's (not with a frame angle, which turns the frame after the draw); else None."""
    if kwargs.get("frame") is not None:
        return None
    fb = fourbar_starts.recognised(mechanism)
    if fb is None:
        return None
    own = assembled(mechanism, {})
    if isinstance(own, str):
        return None
    return fb, fourbar_starts.side(fb, own), fourbar_starts.sweep(fb, mechanism, kwargs)


def _fitted(
    mechanism: Mechanism,
    vary: Mapping[str, tuple[float, float] | None],
    base: Mapping[str, float],
    box: Mapping[str, tuple[float, float]],
    n: int,
    seed: int | None,
    kwargs: Mapping[str, Any],
) -> (
    tuple[list[dict[str, float]], list[Mechanism], list[tuple[dict[str, float], str]], int, list[FreeTiming | None]]
    | None
):
    """A four-bar's starts fitted to its targets with free timing (:mod:`mechfem.design.fourbar_fit`), as
    :func:`screened` gives starts, with each one's free timing (None: the problem's); None when the starts are not
    fitted. The fitted linkages' cranks turn fully; without a whole turn asked (the start values' sweep less than a
    turn) every other start is a plain draw of the box instead, as :func:`screened` takes them, so that linkages
    whose crank does not turn fully are started from too."""
    four_bar = _four_bar(mechanism, kwargs)
    if four_bar is None or n <= 0:
        return None
    fb, branch, sweep = four_bar
    fit = fourbar_fit.applicable(fb, vary, kwargs)
    if fit is None or not {f"{fb.b0}.x", f"{fb.b0}.y"} <= set(box):
        # The frame is drawn by its length and angle from B0's co-ordinates in the unit cube of the box.
        return None
    half = 0 if sweep is None else (n + 1) // 2
    plain = _screen(mechanism, base, [(d, "") for d in draws(box, SCREEN * half, seed)], half, kwargs, None)
    kept, _ = fourbar_fit.starts(fb, mechanism, box, fit, branch, n - len(plain[0]), seed)
    begins: list[dict[str, float]] = []
    reached: list[Mechanism] = []
    rejected: list[tuple[dict[str, float], str]] = []
    timings: list[FreeTiming] = []
    looked = 0
    for _, design, angles in kept:
        if len(begins) == n - len(plain[0]):
            break
        looked += 1
        begin = {**base, **{k: v for k, v in design.items() if k in vary}}
        timing = fourbar_fit.timings(kwargs["timing"], angles)
        at = fourbar_starts.assembled(fb, mechanism, branch, {**begin, fb.input: angles[0]})
        why = f"cannot be assembled: {at}" if isinstance(at, str) else runs_through(at, {**kwargs, "timing": timing})
        if why or isinstance(at, str):
            rejected.append((begin, why))
            continue
        begins.append(begin)
        reached.append(at)
        timings.append(timing)
    return (
        _alternate(plain[0], begins),
        _alternate(plain[1], reached),
        plain[2] + rejected,
        plain[3] + looked,
        _alternate([None] * len(plain[0]), timings),
    )


def _one_start(
    task: tuple[Mechanism, dict[str, tuple[float, float] | None], dict[str, Any]],
) -> Optimum | tuple[str, float]:
    """One start of a multi-start: its optimum, or why it failed and the seconds it took."""
    from mechfem.design.optimise import optimize

    mech, vary, kwargs = task
    t0 = time.perf_counter()
    try:
        return optimize(mech, vary, **kwargs)
    except MechfemError as err:
        return str(err) or type(err).__name__, time.perf_counter() - t0


def multi_start(
    mechanism: Mechanism,
    vary: Mapping[str, tuple[float, float] | None],
    kwargs: dict[str, Any],
    starts: int | Sequence[Mapping[str, float]],
    seed: int | None,
    executor: object | None,
    box: Mapping[str, tuple[float, float]] | None = None,
) -> Optimum:
    from mechfem.design.optimise import Optimum, Start, _span
    from mechfem.studies import cluster

    if isinstance(starts, int) and starts < 1:
        raise ValueError(f"starts must be at least 1, got {starts}")
    begins = [{name: float(v) for name in vary if (v := getattr(mechanism[name], "value", None)) is not None}]
    reached: list[Mechanism | str] = [mechanism]
    rejected: list[tuple[dict[str, float], str]] = []
    timed: list[FreeTiming | None] = [None]
    drawn = 0
    if isinstance(starts, int):
        if box is None:
            box = {name: _span(mechanism, name, span) for name, span in vary.items()}
        unknown = set(box) - set(vary)
        if unknown:
            raise ValueError(f"the start box names {sorted(unknown)}, which vary does not")
        # Draws screened for the problem's motion, each assembled afresh by continuation from the mechanism's own
        # position 1; with free timing a four-bar's are fitted to the targets, each with its own start timing.
        fitted = _fitted(mechanism, vary, begins[0], box, starts - 1, seed, kwargs)
        if fitted is None:
            more, at, rejected, drawn = screened(mechanism, begins[0], box, starts - 1, seed, kwargs)
            timed += [None] * len(more)
        else:
            more, at, rejected, drawn, own = fitted
            timed += own
        begins += more
        reached += at
    else:
        begins += [{**begins[0], **{k: float(v) for k, v in d.items()}} for d in starts]
        # Every start assembled afresh (a four-bar from its closed-form position 1, any other mechanism by
        # continuation from its own position 1); one that cannot be is discarded with the reason.
        four_bar = _four_bar(mechanism, kwargs)
        reached += [
            assembled(mechanism, b)
            if four_bar is None
            else fourbar_starts.assembled(four_bar[0], mechanism, four_bar[1], b)
            for b in begins[1:]
        ]
        timed += [None] * len(starts)
    usable = [k for k, m in enumerate(reached) if not isinstance(m, str)]
    tasks = [
        (m, dict(vary), kwargs if t is None else {**kwargs, "timing": t})
        for m, t in zip(reached, timed, strict=True)
        if not isinstance(m, str)
    ]
    if executor is None:
        outs: list[Any] = [_one_start(t) for t in tasks]
    else:
        tasks = [(m, v, {**k, "progress": None}) for m, v, k in tasks]
        outs = cluster.run_tasks(executor, _one_start, tasks, reraise=(ValueError, TypeError, KeyError))
    by_start = dict(zip(usable, outs, strict=True))
    outcomes: list[Start] = []
    for k, begin in enumerate(begins):
        out = by_start.get(k, f"start design discarded: {reached[k]}")
        if isinstance(out, Optimum):
            outcomes.append(out.starts[0])
            continue
        if isinstance(out, str):
            reason, seconds = out, 0.0
        else:
            reason, seconds = (out.reason, math.nan) if isinstance(out, cluster.TaskFailed) else out
        # A failed start still says which timing it would have started from: its own, else the problem's.
        stated = timed[k] if timed[k] is not None else kwargs.get("timing")
        began = None if stated is None else [float(t) for t in stated.starts]
        outcomes.append(Start(begin, None, math.nan, 0, False, reason, seconds, began))
    found = [out for out in outs if isinstance(out, Optimum)]
    if not found:
        raise Infeasible(
            "every start failed: " + "; ".join(f"start {k + 1}: {o.message}" for k, o in enumerate(outcomes))
        )
    best = min(found, key=lambda o: o.objective)
    passed = [Start(b, None, math.nan, 0, False, f"draw passed over: {why}", 0.0) for b, why in rejected]
    return dataclasses.replace(best, starts=outcomes, usable=len(found) / len(begins), drawn=drawn, rejected=passed)


__all__ = ["SCREEN", "assembled", "draws", "multi_start", "runs_through", "screened", "unit_draws"]
