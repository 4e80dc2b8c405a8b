"""A variable frame angle: the whole frame turned about one of its points, as one design variable.

Published path-synthesis problems (Cabrera, Simon and Prado 2002, among others) place a four-bar in the plane by its
frame pivot, its frame length and the frame's angle theta0: the frame line may lie at any angle, and the crank
angle is measured from it. :func:`mechfem.optimize` with ``frame=FrameAngle("A0")`` adds that angle as a design
variable (named ``FrameAngle.name``, 0 for the mechanism as it is): every fixed point turns about the pivot by the
angle, every fixed angle co-ordinate and every angle input's start value grow by it (the inputs are measured from
the frame), and the other variables keep their meaning in the turned frame (``B0.x`` and ``B0.y`` are B0's place
before the turn).

The core has no variable of its own for this; it does not need one. The turn maps the problem's variables z (the
named ones and the angle) to the core's y (those of them that the turn moves, and the fixed co-ordinates and input
starts that it adds): y = g(z), and the core's exact sensitivities dy give those of z by the chain rule through
g's Jacobian, which is exact too (a rotation's derivative). :class:`TurnedModel` is that map around the core's
model, behind the interface of the core's ``DesignModel``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

import mechfem._core as _core
from mechfem.design import evaluated
from mechfem.design.model_units import Factors

if TYPE_CHECKING:
    from mechfem.design.engine import DesignModelOf, FloatArray
    from mechfem.model.mechanism import Mechanism

Var = tuple[int, int]
"""A variable of the core: ``(kind, number)``."""

SENTINEL = (3, 0)
"""The frame angle's entry in the engine's list of variables (the core has no kind 3: :class:`TurnedModel` takes
it out)."""


@dataclass(frozen=True)
class FrameAngle:
    """The frame turned by a design variable ``name`` about its fixed point ``pivot`` (a point's name), within
    ``span`` (in the model's angle unit; None: periodic, a whole turn)."""

    pivot: str
    name: str = "frame"
    span: tuple[float, float] | None = None

    def __post_init__(self) -> None:
        if self.span is not None and not (float(self.span[0]) <= 0.0 <= float(self.span[1])):
            raise ValueError(f"the frame angle's span {self.span} must hold 0, the mechanism as it is")


@dataclass
class Turn:
    """What the turn moves, in the core's numbering: the pivot's two co-ordinates, every fixed point's pair, the
    fixed angle co-ordinates and the angle inputs' start rows, each with its value in the mechanism."""

    pivot: tuple[Var, Var]
    points: list[Var]
    """The fixed points' co-ordinates as ``(kind, number)``, x then y of each point."""
    angles: list[tuple[int, int]]
    """``(kind, number)``: fixed angle co-ordinates (kind 0) and angle inputs' rows (kind 1)."""
    values: dict[tuple[int, int], float]
    names: dict[tuple[int, int], str]
    """The name of each of them in the mechanism (``"B0.x"``, ``"theta"``)."""
    unit: float = 1.0
    """Radians per unit of the frame angle, which is in the mechanism's angle unit (pi/180 for degrees)."""


def plan(
    mechanism: Mechanism, frame: FrameAngle, numbering: Any, free_input: str | None, core_units: bool = False
) -> Turn:
    """The turn of ``mechanism``'s frame; ``free_input`` (an input with free timing) is not turned: its values at
    the points are design variables of their own. The frame angle and what the turn moves are in the mechanism's
    units, as :func:`mechfem.optimize` takes them; with ``core_units`` in metres and radians, as a deck's problem
    (whose mechanism, read from a deck in mm and degrees, holds its numbers in those) is stated."""
    from mechfem.design.optimise import _variable

    fixed = [p for p in mechanism.points if p.fixed]
    pivot = next((p for p in fixed if p.name == frame.pivot), None)
    if pivot is None:
        known = ", ".join(p.name for p in fixed) or "none"
        raise ValueError(f"the frame angle's pivot {frame.pivot!r} is not a fixed point of the mechanism ({known})")
    values: dict[tuple[int, int], float] = {}
    names: dict[tuple[int, int], str] = {}

    def number(name: str) -> tuple[int, int]:
        kind, n, value = _variable(mechanism, numbering, name)
        values[(kind, n)], names[(kind, n)] = float(value), name
        return kind, n

    points = [(number(f"{p.name}.x"), number(f"{p.name}.y")) for p in fixed]
    angles = [number(c.name) for c in mechanism.coordinates if c.fixed and c.kind == "angle" and c.point is None]
    inputs = [r for r in mechanism.rows if r.kind == "input" and r.is_angle and r.name != free_input]
    angles += [number(r.name) for r in inputs]
    flat = [v for pair in points for v in pair]
    factors = Factors(mechanism)
    if core_units:
        values = {v: x * (factors.angle if v in angles else factors.length) for v, x in values.items()}
    unit = 1.0 if core_units else factors.angle
    return Turn((number(f"{pivot.name}.x"), number(f"{pivot.name}.y")), flat, angles, values, names, unit)


class TurnedModel:
    """The core's model of the variables y behind the variables z of the problem (the frame angle among them)."""

    def __init__(self, inner: Any, turn: Turn, exposed: list[tuple[int, int]], core: list[tuple[int, int]]) -> None:
        self.inner, self.turn, self.exposed, self.core = inner, turn, exposed, core
        self.at = exposed.index(SENTINEL)

    @property
    def runs(self) -> int:
        return int(self.inner.runs)

    def _value(self, z: list[float], var: tuple[int, int]) -> tuple[float, int | None]:
        """The value of the untouched variable ``var`` (before the turn) and its index in z (None: a constant)."""
        if var in self.exposed:
            k = self.exposed.index(var)
            return float(z[k]), k
        return self.turn.values[var], None

    def mapped(self, z: list[float]) -> tuple[list[float], FloatArray]:
        """y = g(z) and dy/dz."""
        theta, unit = float(z[self.at]), self.turn.unit
        c, s = math.cos(theta * unit), math.sin(theta * unit)
        y = [0.0] * len(self.core)
        jac = np.zeros((len(self.core), len(z)))
        done: set[int] = set()
        (cx, kcx), (cy, kcy) = self._value(z, self.turn.pivot[0]), self._value(z, self.turn.pivot[1])
        for i in range(0, len(self.turn.points), 2):
            vx, vy = self.turn.points[i], self.turn.points[i + 1]
            (px, kpx), (py, kpy) = self._value(z, vx), self._value(z, vy)
            dx, dy = px - cx, py - cy
            ix, iy = self.core.index(vx), self.core.index(vy)
            y[ix], y[iy] = cx + c * dx - s * dy, cy + s * dx + c * dy
            jac[ix, self.at], jac[iy, self.at] = (-s * dx - c * dy) * unit, (c * dx - s * dy) * unit
            for k, d in ((kpx, (c, s)), (kpy, (-s, c)), (kcx, (1.0 - c, -s)), (kcy, (s, 1.0 - c))):
                if k is not None:
                    jac[ix, k] += d[0]
                    jac[iy, k] += d[1]
            done.update((ix, iy))
        for var in self.turn.angles:
            value, k = self._value(z, var)
            i = self.core.index(var)
            y[i] = value + theta
            jac[i, self.at] = 1.0
            if k is not None:
                jac[i, k] = 1.0
            done.add(i)
        for i, var in enumerate(self.core):
            if i not in done:
                k = self.exposed.index(var)
                y[i], jac[i, k] = float(z[k]), 1.0
        return y, jac

    def start(self) -> list[float]:
        y = list(self.inner.start())
        return [0.0 if var == SENTINEL else float(y[self.core.index(var)]) for var in self.exposed]

    def start_at(self, values: list[float]) -> _core.Evaluation:
        return self._each(values, start=True)

    def evaluate(self, values: list[float]) -> _core.Evaluation:
        return self._each(values, start=False)

    def _each(self, z: list[float], start: bool) -> _core.Evaluation:
        y, jac = self.mapped(z)
        got: _core.Evaluation = self.inner.start_at(y) if start else self.inner.evaluate(y)
        if not got.feasible:
            return got
        gradient = np.asarray(got.gradient, dtype=np.float64) @ jac
        extrema = [evaluated.replaced(x, gradient=list(np.asarray(x.gradient) @ jac)) for x in got.extrema]
        return evaluated.replaced(got, gradient=gradient, extrema=extrema)


def turned(of: DesignModelOf, turn: Turn) -> DesignModelOf:
    """``of`` behind the frame angle: the engine's variables (with :data:`SENTINEL`) mapped to the core's."""

    def wrapped(variables: list[tuple[int, int]], buffers: list[int], extrema: list[tuple[int, int]]) -> Any:
        at = variables.index(SENTINEL)
        moved: list[Var] = [v for v in [*turn.pivot, *turn.points, *turn.angles] if v not in variables]
        core = [*variables[:at], *dict.fromkeys(moved), *variables[at + 1 :]]
        return TurnedModel(of(core, buffers, extrema), turn, variables, core)

    return wrapped


def apply(mechanism: Mechanism, turn: Turn, theta: float) -> None:
    """Turns ``mechanism``'s frame (its variables already at their final values) by ``theta`` (the turn's unit)."""
    c, s = math.cos(theta * turn.unit), math.sin(theta * turn.unit)
    cx, cy = (float(mechanism[turn.names[v]].value) for v in turn.pivot)
    for i in range(0, len(turn.points), 2):
        nx, ny = turn.names[turn.points[i]], turn.names[turn.points[i + 1]]
        dx, dy = float(mechanism[nx].value) - cx, float(mechanism[ny].value) - cy
        mechanism.set(nx, cx + c * dx - s * dy)
        mechanism.set(ny, cy + s * dx + c * dy)
    for var in turn.angles:
        name = turn.names[var]
        mechanism.set(name, float(mechanism[name].value) + theta)


__all__ = ["SENTINEL", "FrameAngle", "Turn", "TurnedModel", "apply", "plan", "turned"]
