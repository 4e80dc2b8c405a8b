"""Free timing: the input's value at each target point is a design variable.

In path generation without prescribed timing the designer gives N points and leaves open at which input values
(crank angles) the coupler passes them. :func:`mechfem.optimize` with ``timing=FreeTiming(...)`` makes those N
values design variables beside the dimensions. Its positions are then the N target points, in order: a
``Target`` has one value per point, ``TargetAt`` names a point.

Each point is a model of its own, compiled once: the mechanism at that point's input value, whose design variables
are the dimensions and the input's start value (an input's start is a design variable of the core, with its exact
sensitivity: the first-order transfer function). :class:`TimedModel` puts the N models together behind the
interface of the core's ``DesignModel``, so the optimisation engine (:mod:`mechfem.design.engine`) sees one model with N
positions. Every point keeps the assembly branch it had at the start design, where the points' models start on
one continuous run of the mechanism through the start values: so the designs compared are on one branch at every
point (no branch defect between the points), as long as the start timing is.

``ordered=True`` keeps the points in order along the motion: the variables are then the first point's input and
the N - 1 advances from one point to the next, each within ``[0, one turn]`` for an angle (the optimiser's bounds
hold the order, no constraint is needed), and the input at point k is their sum.
"""

from __future__ import annotations

import copy
import dataclasses
import math
import warnings
from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

import mechfem._core as _core
from mechfem.design import evaluated
from mechfem.design.engine import DesignBound, FloatArray, Infeasible

if TYPE_CHECKING:
    from mechfem.model.mechanism import Mechanism
    from mechfem.model.storage import Storage

TURN = 2.0 * math.pi


@dataclass(frozen=True)
class FreeTiming:
    """The input ``input`` (its name, e.g. ``"theta"``) takes a value of its own at each of the target points,
    starting from ``starts`` (one per point); ``span`` bounds every value (None: an angle input wraps, a length
    input is refused); ``ordered`` keeps each value at or after the one before (by at most one turn for an angle,
    at most the width of ``span`` otherwise); ``within`` (with ``ordered``) keeps the last point at most that far
    after the first, e.g. a little less than a turn for points passed in one turn of the crank (an inequality with
    its exact gradient, so SLSQP solves the problem; the start values may lie beyond it)."""

    input: str
    starts: Sequence[float]
    span: tuple[float, float] | None = None
    ordered: bool = False
    within: float | None = None

    def __post_init__(self) -> None:
        if len(self.starts) < 1:
            raise ValueError("free timing needs at least one target point (one start value each)")
        if not all(math.isfinite(float(s)) for s in self.starts):
            raise ValueError(f"the start values of the free timing are not all finite: {list(self.starts)}")
        if self.span is not None and not float(self.span[0]) < float(self.span[1]):
            raise ValueError(f"the free timing's span {self.span} is empty")
        if self.within is not None and not (self.ordered and float(self.within) > 0.0):
            raise ValueError(f"within ({self.within}) bounds ordered free timing: give ordered=True and within > 0")
        if self.ordered and any(b < a for a, b in zip(self.starts, self.starts[1:], strict=False)):
            raise ValueError(
                f"ordered free timing: the start values {list(self.starts)} are not in order; give them in the "
                "order the points are passed"
            )


class TimedModel:
    """N single-point models as one model of N positions: the shared variables, then the timing variables (the
    input at each point, or with ``ordered`` the first point's input and the advances)."""

    def __init__(
        self,
        points: list[_core.DesignModel],
        shared: int,
        thetas: FloatArray,
        ordered: bool,
        angle: bool,
        turn: float = TURN,
    ):
        self.points, self.shared, self.ordered, self.angle, self.turn = points, shared, ordered, angle, turn
        self.thetas0 = np.asarray(thetas, dtype=np.float64)
        n = len(points)
        # theta = T y: the inputs at the points from the timing variables.
        self.T = np.tril(np.ones((n, n))) if ordered else np.eye(n)

    @property
    def runs(self) -> int:
        return sum(int(p.runs) for p in self.points)

    def timing_of(self, thetas: FloatArray) -> FloatArray:
        """The timing variables of the inputs ``thetas`` at the points."""
        t = np.asarray(thetas, dtype=np.float64)
        return np.concatenate([t[:1], np.diff(t)]) if self.ordered else t

    def thetas(self, values: Sequence[float]) -> FloatArray:
        """The inputs at the points of the variables ``values`` (shared first)."""
        return np.asarray(self.T @ np.asarray(values[self.shared :], dtype=np.float64), dtype=np.float64)

    def start(self) -> list[float]:
        shared = list(self.points[0].start())[: self.shared]
        return shared + [float(v) for v in self.timing_of(self.thetas0)]

    def start_at(self, values: list[float]) -> _core.Evaluation:
        return self._each(values, start=True)

    def evaluate(self, values: list[float]) -> _core.Evaluation:
        return self._each(values, start=False)

    def _each(self, values: list[float], start: bool) -> _core.Evaluation:
        shared = [float(v) for v in values[: self.shared]]
        thetas = self.thetas(values)
        if self.angle:
            # The same position a whole number of turns away, nearest the point's own start: its model's
            # continuation from the start design never goes round the long way.
            d = thetas - self.thetas0
            thetas = self.thetas0 + (d - self.turn * np.round(d / self.turn))
        rows, grads, first = [], [], None
        for k, (model, theta) in enumerate(zip(self.points, thetas, strict=True)):
            got = model.start_at([*shared, float(theta)]) if start else model.evaluate([*shared, float(theta)])
            if not got.feasible:
                return evaluated.replaced(got, reason=f"at target point {k + 1}: {got.reason}")
            rows.append(np.asarray(got.values, dtype=np.float64)[0])
            grads.append(np.asarray(got.gradient, dtype=np.float64)[0])
            if first is None:
                first = got
        values_ = np.vstack(rows)
        g = np.stack(grads)  # points x buffers x (shared + 1)
        n = len(self.points)
        gradient = np.zeros((n, values_.shape[1], self.shared + n))
        gradient[:, :, : self.shared] = g[:, :, : self.shared]
        for k in range(n):
            # d/dy_i of point k's buffers: its input's sensitivity times d theta_k / d y_i.
            gradient[k, :, self.shared :] = np.outer(g[k, :, self.shared], self.T[k])
        # One position a target point; position 1 and the report are the first point's.
        assert first is not None
        return evaluated.replaced(first, positions=n, values=values_, gradient=gradient, extrema=[])


@dataclass
class Plan:
    """A free timing made ready for the engine: one builder per point, the input's variable, and the timing
    variables' names, ranges and which of them wrap."""

    builders: list[Any]
    input_var: tuple[int, int]
    thetas: FloatArray
    names: list[str]
    lo: FloatArray
    hi: FloatArray
    periodic: list[bool]
    angle: bool
    ordered: bool
    turn: float = TURN
    """One turn in the input's unit: 2 pi, or 360 in a model whose angles are in degrees."""
    within: float | None = None
    """With ``ordered``: the largest sum of the advances, the last point's input less the first's."""


def within_bound(timed: Plan, first: int) -> DesignBound | None:
    """The bound of ``timed.within`` on the sum of the advances, the timing variables from index ``first`` on (the
    first point's input, then the advances): linear, its gradient ones on the advances."""
    if timed.within is None or not timed.ordered:
        return None
    n = len(timed.thetas)

    def f(x: FloatArray) -> tuple[float, FloatArray]:
        g = np.zeros(len(x))
        g[first + 1 : first + n] = 1.0
        return float(np.sum(x[first + 1 : first + n])), g

    return DesignBound("the ordered points' sweep", f, 0.0, float(timed.within))


POINT_MOTION_STEP = 1e-9
"""The single step of each point's own motion: the point is its position 1, the step is not compared."""


def plan(mechanism: Mechanism, timing: FreeTiming, storage: Storage, numbering: Any) -> Plan:
    """Builds each point's model: the mechanism with its input at the point's start value, its moving
    co-ordinates from a run of the mechanism through that value (so every point starts on the branch the
    mechanism's position 1 is on)."""
    from mechfem.design.optimise import _variable
    from mechfem.model.motion import Motion
    from mechfem.run import building

    row = mechanism[timing.input]
    if getattr(row, "kind", None) != "input":
        raise ValueError(f"{timing.input!r} is not an input: free timing gives an input a value at every point")
    angle = bool(row.is_angle)
    turn = 360.0 if mechanism.units.angle == "deg" else TURN
    if timing.span is None and not angle:
        raise ValueError(f"{timing.input!r} is not an angle: give the span its values may take")
    kind, number, start = _variable(mechanism, numbering, timing.input)
    thetas = np.array([float(s) for s in timing.starts])
    builders = []
    moving = [c for c in mechanism.coordinates if not c.fixed]
    kept = [c.value for c in moving]
    estimates = [_at(mechanism, timing.input, start, float(theta), k) for k, theta in enumerate(thetas)]
    try:
        for theta, estimate in zip(thetas, estimates, strict=True):
            # The mechanism itself, set to the point and built, then restored: the storage names its objects.
            for c, x in zip(moving, estimate, strict=True):
                c.value = x
            mechanism.set(timing.input, float(theta))
            builders.append(building.builder(mechanism, Motion.by(1, POINT_MOTION_STEP), storage).builder)
    finally:
        for c, x in zip(moving, kept, strict=True):
            c.value = x
        mechanism.set(timing.input, start)
    n = len(thetas)
    names = [f"{timing.input}@{k + 1}" for k in range(n)]
    if timing.ordered:
        t1 = _range(timing.span, thetas[0], turn)
        width = turn if timing.span is None else timing.span[1] - timing.span[0]
        lo = np.array([t1[0]] + [0.0] * (n - 1))
        hi = np.array([t1[1]] + [width] * (n - 1))
        periodic = [timing.span is None] + [False] * (n - 1)
        names = [names[0]] + [f"{timing.input}@{k + 1}-{k}" for k in range(1, n)]
    else:
        spans = [_range(timing.span, t, turn) for t in thetas]
        lo, hi = np.array([a for a, _ in spans]), np.array([b for _, b in spans])
        periodic = [timing.span is None] * n
    within = None if timing.within is None else float(timing.within)
    return Plan(builders, (kind, number), thetas, names, lo, hi, periodic, angle, timing.ordered, turn, within)


def in_units(timed: Plan, factor: float) -> Plan:
    """``timed`` with its input's values (the points' starts, the ranges, a turn, the sweep) multiplied by ``factor``:
    its variables in other units, for builders whose design models take them in those (a deck's, in the core's)."""
    within = None if timed.within is None else timed.within * factor
    return dataclasses.replace(
        timed,
        thetas=timed.thetas * factor,
        lo=timed.lo * factor,
        hi=timed.hi * factor,
        turn=timed.turn * factor,
        within=within,
    )


def timed_inputs(timed: Plan, y: FloatArray) -> FloatArray:
    """The input at each point from the timing variables ``y``."""
    n = len(timed.thetas)
    t = np.tril(np.ones((n, n))) if timed.ordered else np.eye(n)
    return np.asarray(t @ np.asarray(y, dtype=np.float64), dtype=np.float64)


def _range(span: tuple[float, float] | None, theta: float, turn: float) -> tuple[float, float]:
    if span is not None:
        return float(span[0]), float(span[1])
    return theta - turn / 2.0, theta + turn / 2.0


def _at(mechanism: Mechanism, name: str, start: float, theta: float, k: int) -> list[float]:
    """The moving co-ordinates' estimates with the input ``name`` at ``theta``: those of a run from ``start``."""
    from mechfem.errors import IncompleteRunWarning, MechfemError
    from mechfem.model.motion import Motion

    moving = [c for c in mechanism.coordinates if not c.fixed]
    if theta == start:
        return [c.value for c in moving]
    # Steps of 2 degrees at most, in the model's unit of angle.
    step = 2.0 if mechanism.units.angle == "deg" else math.radians(2.0)
    steps = max(1, math.ceil(abs(theta - start) / step))
    try:
        with warnings.catch_warnings():
            # A motion stopped on the way is said below, as the reason this start cannot be used.
            warnings.simplefilter("ignore", IncompleteRunWarning)
            result = copy.deepcopy(mechanism).run(Motion.by(steps, theta - start))
    except MechfemError as e:
        raise Infeasible(
            f"target point {k + 1}: the mechanism cannot be moved from its input's value {start:g} to the start "
            f"value {theta:g} of the free timing: {e}"
        ) from None
    if len(result.value(name)) != steps + 1:
        raise Infeasible(
            f"target point {k + 1}: the motion from the input's value {start:g} to the start value {theta:g} "
            "of the free timing stops on the way (a limit position): give start values the input reaches"
        )
    return [float(result.value(c.name)[-1]) for c in moving]


__all__ = ["FreeTiming", "Plan", "TimedModel", "in_units", "plan", "timed_inputs", "within_bound"]
