"""Design variables that are angles in a model whose angles are in degrees.

The core's design models take every variable in its own units, angles in radians, and give an angle's value (an
angle co-ordinate, an angle row, a transmission angle) in radians too. :func:`mechfem.optimize` works in the
model's units throughout, as the designer states the problem (ranges, start values, free timing and its order, a
whole turn of 360, a TargetAt or Bound of an angle): the models here hand the core an angle variable times pi/180
and scale its gradient column by the same factor (d/d degree = pi/180 d/d radian), and give an angle's value and
its gradient times 180/pi. (Transfer functions keep the core's units.) In a model in radians nothing is wrapped,
so its results stay bit for bit those of the core's models."""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING, Any

import numpy as np

if TYPE_CHECKING:
    from mechfem.design.timing import Plan
    from mechfem.model.mechanism import Mechanism

DEGREE = math.pi / 180.0


class ScaledModel:
    """A core design model whose variables are given in the model's units: ``factors`` (one per variable) turn
    them into the core's."""

    def __init__(self, inner: Any, factors: Sequence[float], angles: Sequence[int] = ()) -> None:
        self.inner, self.factors = inner, np.asarray(factors, dtype=np.float64)
        self.angles = list(angles)
        """The indices of the buffers that are an angle's value."""

    @property
    def runs(self) -> int:
        return int(self.inner.runs)

    def start(self) -> list[float]:
        return [float(y) / f for y, f in zip(self.inner.start(), self.factors, strict=True)]

    def start_at(self, values: list[float]) -> dict[str, Any]:
        return self._scaled(self.inner.start_at(self._core(values)))

    def evaluate(self, values: list[float]) -> dict[str, Any]:
        return self._scaled(self.inner.evaluate(self._core(values)))

    def _core(self, values: Sequence[float]) -> list[float]:
        return [float(v) * f for v, f in zip(values, self.factors, strict=True)]

    def _scaled(self, got: Any) -> dict[str, Any]:
        out = dict(got)
        if out.get("feasible") and "gradient" in out:
            gradient = np.asarray(out["gradient"], dtype=np.float64) * self.factors
            if self.angles:
                values = np.array(out["values"], dtype=np.float64)
                values[:, self.angles] /= DEGREE
                gradient[:, self.angles, :] /= DEGREE
                out["values"] = values
            out["gradient"] = gradient
        return out


class ScaledBuilder:
    """A model builder whose design models take the variables in ``angles`` (core numbering) in degrees and give
    the buffers ``angle_buffers`` (numbers) in degrees."""

    def __init__(self, builder: Any, angles: set[tuple[int, int]], angle_buffers: set[int]) -> None:
        self.builder, self.angles, self.angle_buffers = builder, angles, angle_buffers

    def design(self, base: str, variables: list[tuple[int, int]], buffers: list[int], extrema: Any) -> Any:
        model = self.builder.design(base, variables, buffers, extrema)
        factors = [DEGREE if v in self.angles else 1.0 for v in variables]
        return ScaledModel(model, factors, [k for k, b in enumerate(buffers) if b in self.angle_buffers])


def whole_turn(mech: Mechanism) -> float:
    """One turn in the mechanism's unit of angle: 2 pi, or 360 when its angles are in degrees."""
    return 360.0 if mech.units.angle == "deg" else 2.0 * math.pi


def degree_variables(
    mech: Mechanism,
    vary: Mapping[str, tuple[float, float] | None],
    variables: Sequence[tuple[int, int, float]],
    timed: Plan | None,
) -> set[tuple[int, int]]:
    """The variables (core numbering) of ``optimize`` that are angles, the free timing's input among them."""
    from mechfem.design.dynamic_optimise import is_mass
    from mechfem.design.optimise import _lookup
    from mechfem.model.mechanism import Coordinate

    out: set[tuple[int, int]] = set()
    for name, (kind, number, _) in zip(vary, variables, strict=True):
        if is_mass(kind):
            continue
        obj = _lookup(mech, name)
        if obj.kind == "angle" if isinstance(obj, Coordinate) else obj.is_angle:
            out.add((kind, number))
    if timed is not None and timed.angle:
        out.add(timed.input_var)
    return out


def angle_buffers(keys: Mapping[tuple[str, tuple[object, ...]], int]) -> set[int]:
    """Of the buffers ``keys`` (``optimize``'s (keyword, arguments) -> number), those that hold an angle's value:
    an angle co-ordinate or row (order 0), a transmission angle."""
    from mechfem.model.mechanism import Coordinate, FormParameter, Row

    out = set()
    for (keyword, args), number in keys.items():
        obj = args[0] if args else None
        if keyword == "BUFTRA":
            out.add(number)
        elif keyword == "BUFX0" and isinstance(obj, Coordinate) and obj.kind == "angle":
            out.add(number)
        elif keyword == "BUFE0" and isinstance(obj, Row | FormParameter) and bool(obj.is_angle):
            out.add(number)
    return out


__all__ = ["DEGREE", "ScaledBuilder", "ScaledModel", "angle_buffers", "degree_variables", "whole_turn"]
