"""What the design layer's own constructs know of the model's units (its UNITS: lengths in mm, angles in degrees).

:func:`mechfem.optimize` and :meth:`mechfem.RunResult.sensitivity` work in the model's units throughout, as the
designer states the problem (ranges, start values, free timing and its order, a whole turn of 360, a TargetAt or
Bound of a length or an angle). The core's design models convert at their edges (``ModelBuilder.
design_in_model_units``, ``mechfem_deck::DesignUnits``): they take every variable in the model's units and give
every buffer's value, its gradient and the co-ordinates in them. What is left here is what the Python constructs
around those models need: a turn in the model's unit of angle, and the factors of lengths and angles for a frame
angle's turn (:mod:`mechfem.design.frame_angle`), whose variable the core does not have."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

from mechfem.model.units import scale

if TYPE_CHECKING:
    from mechfem.model.mechanism import Mechanism

DEGREE = math.pi / 180.0


class Factors:
    """What a length or an angle in the model's units is multiplied by to give it in the core's: ``length`` (1 for
    metres), ``angle`` (1 for radians, :data:`DEGREE` for degrees)."""

    def __init__(self, mech: Mechanism) -> None:
        self.length = scale(mech.units.length or "m", "m")
        self.angle = DEGREE if mech.units.angle == "deg" else 1.0


def whole_turn(mech: Mechanism) -> float:
    """One turn in the mechanism's unit of angle: 2 pi, or 360 when its angles are in degrees."""
    return 360.0 if mech.units.angle == "deg" else 2.0 * math.pi


__all__ = ["DEGREE", "Factors", "whole_turn"]
