"""The designer's constraint "the input turns fully": no limit position of the input anywhere in a whole turn.

:func:`mechfem.optimize` with ``full_rotation=True`` (an angle input) compiles, beside the problem's own model, one
more model of the same design variables whose motion is one whole turn of the input in ``STEPS`` steps from its
start value. A design is feasible only if that turn runs through on the start design's assembly branch: a limit
position inside the turn stops it (for a four-bar: the crank is not the shortest link of a Grashof linkage), a jump
onto the other branch is caught by the branch rules. Such a design is infeasible like one that cannot be
assembled, so the optimiser steps back from it (docs/optimisation.md). The constraint is a wall, not a smooth
inequality: no gradient of it is taken.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

import mechfem._core as _core
from mechfem.design import evaluated

if TYPE_CHECKING:
    from mechfem.design.engine import DesignModelOf
    from mechfem.model.mechanism import Mechanism
    from mechfem.model.storage import Storage

STEPS = 72
"""Steps of the whole turn: 5 degrees each, small enough that a driven turn keeps its branch."""


class FullRotation:
    """A model whose designs are feasible only when the input also turns fully on the start design's branch."""

    def __init__(self, inner: Any, turn: _core.DesignModel, shared: int) -> None:
        self.inner, self.turn, self.shared = inner, turn, shared

    @property
    def runs(self) -> int:
        return int(self.inner.runs) + int(self.turn.runs)

    def start(self) -> list[float]:
        return list(self.inner.start())

    def start_at(self, values: list[float]) -> _core.Evaluation:
        return self._checked(values, start=True)

    def evaluate(self, values: list[float]) -> _core.Evaluation:
        return self._checked(values, start=False)

    def _checked(self, values: list[float], start: bool) -> _core.Evaluation:
        shared = [float(v) for v in values[: self.shared]]
        d = self.turn.start_at(shared) if start else self.turn.evaluate(shared)
        if not d.feasible:
            return evaluated.replaced(d, reason=f"the input cannot turn fully: {d.reason}", reason_kind="full_rotation")
        got: _core.Evaluation = self.inner.start_at(values) if start else self.inner.evaluate(values)
        return got


TURN = 2.0 * math.pi


def checked(
    of: DesignModelOf,
    mechanism: Mechanism,
    storage: Storage,
    base: str,
    in_model_units: bool = False,
) -> DesignModelOf:
    """``of`` with every design also checked for a full turn of the mechanism's only input (an angle); the
    variables in the model's units with ``in_model_units``, else in the core's."""
    from mechfem.model.motion import Motion
    from mechfem.run import building

    inputs = [r for r in mechanism.rows if r.kind == "input"]
    if len(inputs) != 1 or not inputs[0].is_angle:
        raise ValueError("full_rotation needs a mechanism with one input, an angle (a crank)")
    core = building.builder(mechanism, Motion.by(STEPS, TURN, unit="rad"), storage).builder
    # The turn's model records no buffer: only whether the design turns fully.
    core.design_in_model_units = in_model_units

    def wrapped(variables: list[tuple[int, int]], buffers: list[int], extrema: list[tuple[int, int]]) -> Any:
        shared = [v for v in variables if v[0] != 2]
        return FullRotation(of(variables, buffers, extrema), core.design(base, shared, [], []), len(shared))

    return wrapped


__all__ = ["STEPS", "TURN", "FullRotation", "checked"]
