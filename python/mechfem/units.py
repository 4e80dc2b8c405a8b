"""Angles in radians or degrees at the edges of the Python API.

The model, its deck and the solver work in radians. A motion, an input's start value or a result may be given
or asked for in degrees (``unit="deg"``); the conversion happens where the value enters or leaves, with
:func:`math.radians` and :func:`math.degrees`, so that a value in degrees gives exactly the radians
``math.radians`` gives for it.
"""

from __future__ import annotations

import math
from typing import Literal, TypeAlias

import numpy as np
import numpy.typing as npt

Unit: TypeAlias = Literal["rad", "deg"]
"""The unit of an angle: ``"rad"`` (the model's own) or ``"deg"``."""

UNITS: tuple[str, ...] = ("rad", "deg")

LARGE_ANGLE = 100.0
"""An angular change of a motion larger than this many radians (about 16 turns) given without a unit is
probably meant in degrees: it warns with :class:`~mechfem.errors.UnitWarning`."""


def check_unit(unit: object, what: str = "unit") -> Unit | None:
    """``unit`` when it is None, ``"rad"`` or ``"deg"``; a ValueError otherwise."""
    if unit is None or unit == "rad" or unit == "deg":
        return unit
    raise ValueError(f"{what} must be 'rad' or 'deg', got {unit!r}")


def factor(unit: Unit | None) -> float:
    """What a value in radians is multiplied by to give it in ``unit``."""
    return 180.0 / math.pi if unit == "deg" else 1.0


def to_radians(value: float, unit: Unit | None) -> float:
    """``value`` given in ``unit``, in radians."""
    return math.radians(value) if unit == "deg" else float(value)


def array_to_radians(values: npt.ArrayLike, unit: Unit | None) -> npt.NDArray[np.float64]:
    """An array given in ``unit``, in radians (element by element as :func:`math.radians`)."""
    a = np.asarray(values, dtype=np.float64)
    return np.radians(a) if unit == "deg" else a


def from_radians(values: npt.NDArray[np.float64], unit: Unit | None) -> npt.NDArray[np.float64]:
    """Values in radians, in ``unit``."""
    return np.degrees(values) if unit == "deg" else values


__all__ = ["LARGE_ANGLE", "UNITS", "Unit", "array_to_radians", "check_unit", "factor", "from_radians", "to_radians"]
