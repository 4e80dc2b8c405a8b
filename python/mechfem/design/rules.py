"""Stopping tolerances and periodic variables of the optimisation engine (:mod:`mechfem.design.engine`).

* :class:`FTol`: stop when an iteration changes the objective f by less than ``atol + rtol |f|``, the same test for
  SciPy's least squares and SLSQP, whatever the start objective (SciPy's own tests are each only relative or only
  absolute, and the classic OPTTOL scales SLSQP's by the start objective).
* An angle variable with a range of one whole turn, or without one, wraps: the optimiser sees it without bounds,
  the engine evaluates it within half a turn of its start value and reports it within its range.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from mechfem.design.engine import FloatArray, Problem


@dataclass(frozen=True)
class FTol:
    """Stop when an iteration changes the objective f by less than ``atol + rtol * |f|`` (f at the new iterate):
    the same test for least squares and SLSQP, whatever the start objective was."""

    rtol: float = 0.0
    atol: float = 0.0

    def __post_init__(self) -> None:
        for name, v in (("rtol", self.rtol), ("atol", self.atol)):
            if not (math.isfinite(v) and v >= 0.0):
                raise ValueError(f"the stopping tolerance {name} must be zero or positive and finite, not {v}")
        if self.rtol >= 1.0:
            raise ValueError(f"rtol must be below 1, not {self.rtol}: the optimiser would stop before its first step")
        if self.rtol == 0.0 and self.atol == 0.0:
            raise ValueError("give rtol or atol above zero: with both zero the optimiser never stops on the objective")

    def met(self, before: float, after: float) -> bool:
        """Whether a step from objective ``before`` to ``after`` is small enough to stop."""
        return abs(before - after) <= self.atol + self.rtol * abs(after)


class _Converged(Exception):
    """Raised inside an optimiser's call to end it when :class:`FTol` is met (SciPy's own tests know only one
    tolerance, either relative or absolute)."""


_EPS = float(np.finfo(np.float64).eps)
TURN = 2.0 * math.pi


def full_turn(lo: float, hi: float, turn: float = TURN) -> bool:
    """Whether ``[lo, hi]`` is one whole turn (``turn``: 2 pi in radians, 360 in degrees): an angle variable with
    this range wraps."""
    return math.isclose(hi - lo, turn, rel_tol=1e-9, abs_tol=1e-12)


def _optimiser_bounds(problem: Problem) -> tuple[FloatArray, FloatArray]:
    """The ranges the optimiser sees: none for a periodic variable."""
    if not any(problem.periodic):
        return problem.lo, problem.hi
    free = np.array(problem.periodic, dtype=bool)
    return np.where(free, -np.inf, problem.lo), np.where(free, np.inf, problem.hi)


def _reported(problem: Problem, x: FloatArray) -> FloatArray:
    """``x`` with every periodic variable within ``[lo, lo + 2 pi)``."""
    if not any(problem.periodic):
        return x
    free = np.array(problem.periodic, dtype=bool)
    return np.where(free, problem.lo + np.mod(x - problem.lo, problem.whole_turn), x)


_FEASIBLE = 1e-10
"""The largest bound violation at which a :class:`FTol` ends SLSQP."""


def _stop_message(stop: FTol | None) -> str:
    assert stop is not None
    return f"the objective changed by less than atol + rtol |f| (atol {stop.atol:g}, rtol {stop.rtol:g})"
