"""Units at the edges of the Python API: the units a model's numbers are in, and another unit for one output.

A :class:`Units` is the deck's ``UNITS`` line: a unit of length, angle, mass, force and time
(``UNITS LENGTH mm ANGLE deg``). A :class:`~mechfem.Mechanism` carries one; every number given to it is read in
those units (``m.set("phi", 90)`` is 90 degrees when its angle unit is degrees), its deck says them on the
``UNITS`` line and the deck reader converts at its edge, so a run's numbers come back in them. Without a unit of
length, mass or force the numbers are the user's own consistent ones, as in a deck without ``UNITS``; angles
default to radians and time to seconds.

Where one output is wanted in another unit (``unit=`` of :meth:`~mechfem.RunResult.value`, ``x``, ``plot``,
``to_pandas``), the conversion is a factor between two units of one kind (:func:`scale`); a value given in degrees
for a model in radians gives exactly the radians :func:`math.radians` gives for it.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, fields
from typing import Literal, TypeAlias

import numpy as np
import numpy.typing as npt

Unit: TypeAlias = Literal["rad", "deg"]
"""The unit of an angle: ``"rad"`` (the default) or ``"deg"``."""

UNITS: tuple[str, ...] = ("rad", "deg")
"""The units of an angle."""

#: Each kind of quantity the UNITS line sets, with its units and what one of each is in SI units.
SI: dict[str, dict[str, float]] = {
    "length": {"m": 1.0, "mm": 1e-3, "cm": 1e-2, "in": 0.0254},
    "angle": {"rad": 1.0, "deg": math.pi / 180.0},
    "mass": {"kg": 1.0, "g": 1e-3},
    "force": {"N": 1.0, "kN": 1e3},
    "time": {"s": 1.0, "ms": 1e-3},
}

#: The deck's word for each kind (the UNITS line's field).
FIELD = {"length": "LENGTH", "angle": "ANGLE", "mass": "MASS", "force": "FORCE", "time": "TIME"}

LARGE_ANGLE = 100.0
"""An angular change of a motion larger than this many radians (about 16 turns) given without a unit is
probably meant in degrees: it warns with :class:`~mechfem.errors.UnitWarning`."""


@dataclass(frozen=True)
class Units:
    """The units of a model's numbers: ``length``, ``mass`` and ``force`` (None: the numbers as they are, in a
    consistent system of the user's), ``angle`` (``"rad"`` or ``"deg"``) and ``time`` (``"s"`` or ``"ms"``)."""

    length: str | None = None
    angle: str = "rad"
    mass: str | None = None
    force: str | None = None
    time: str = "s"

    def __post_init__(self) -> None:
        for f in fields(self):
            value = getattr(self, f.name)
            if value is None and f.name in ("angle", "time"):
                object.__setattr__(self, f.name, "rad" if f.name == "angle" else "s")
            elif value is not None and value not in SI[f.name]:
                allowed = ", ".join(repr(u) for u in SI[f.name])
                raise ValueError(f"the unit of {f.name} must be one of {allowed}, got {value!r}")

    @classmethod
    def of(cls, value: Units | Mapping[str, str | None] | None) -> Units:
        """``value`` as units: a :class:`Units`, a mapping by kind (``{"length": "mm", "angle": "deg"}``, as a
        model echo carries it) or None (the defaults)."""
        if value is None:
            return cls()
        if isinstance(value, Units):
            return value
        unknown = [k for k in value if k not in SI]
        if unknown:
            raise ValueError(f"no kind of unit {unknown[0]!r}: units are given for {', '.join(SI)}")
        get = value.get
        return cls(get("length"), get("angle") or "rad", get("mass"), get("force"), get("time") or "s")

    def get(self, kind: str) -> str | None:
        """The unit of ``kind`` (``length``, ``angle``, ``mass``, ``force``, ``time``)."""
        return getattr(self, kind)  # type: ignore[no-any-return]

    @property
    def default(self) -> bool:
        """True when these are the units of a deck without ``UNITS`` (radians, seconds, nothing else)."""
        return self == Units()

    def deck_line(self) -> str | None:
        """The deck's ``UNITS`` line for these units (the fields that differ from the defaults), or None for the
        defaults."""
        words = [
            f"{FIELD[f.name]} {getattr(self, f.name)}"
            for f in fields(self)
            if getattr(self, f.name) != getattr(Units(), f.name)
        ]
        return "UNITS " + " ".join(words) if words else None

    def as_dict(self) -> dict[str, str | None]:
        """The units by kind."""
        return {f.name: getattr(self, f.name) for f in fields(self)}


def kind_of(unit: str) -> str | None:
    """The kind of quantity ``unit`` measures (``"mm"`` -> ``"length"``), or None for a unit mechfem does not
    convert."""
    return next((k for k, units in SI.items() if unit in units), None)


def scale(source: str | None, target: str | None) -> float:
    """What a value in ``source`` is multiplied by to give it in ``target`` (two units of one kind); 1 when either
    is None (a quantity without a unit stays as it is)."""
    if source is None or target is None or source == target:
        return 1.0
    kind = kind_of(source)
    if kind is None or kind != kind_of(target):
        raise ValueError(f"cannot convert {source!r} to {target!r}: they are not units of one kind")
    if kind == "angle":
        # math.degrees and math.radians, exactly.
        return 180.0 / math.pi if target == "deg" else math.pi / 180.0
    return SI[kind][source] / SI[kind][target]


def check_output_unit(unit: object, what: str = "unit") -> str | None:
    """``unit`` when it is None or a unit mechfem converts (``"rad"``, ``"deg"``, ``"mm"``, ...); a ValueError
    otherwise."""
    if unit is None or (isinstance(unit, str) and kind_of(unit) is not None):
        return unit
    every = ", ".join(repr(u) for units in SI.values() for u in units)
    raise ValueError(f"{what} must be one of {every}, got {unit!r}")


def check_unit(unit: object, what: str = "unit") -> Unit | None:
    """``unit`` when it is None, ``"rad"`` or ``"deg"``; a ValueError otherwise."""
    if unit is None or unit == "rad" or unit == "deg":
        return unit
    raise ValueError(f"{what} must be 'rad' or 'deg', got {unit!r}")


def factor(unit: str | None) -> float:
    """What a value in radians is multiplied by to give it in ``unit``."""
    return 180.0 / math.pi if unit == "deg" else 1.0


def to_radians(value: float, unit: str | None) -> float:
    """``value`` given in ``unit``, in radians."""
    return math.radians(value) if unit == "deg" else float(value)


def array_to_radians(values: npt.ArrayLike, unit: str | None) -> npt.NDArray[np.float64]:
    """An array given in ``unit``, in radians (element by element as :func:`math.radians`)."""
    a = np.asarray(values, dtype=np.float64)
    return np.radians(a) if unit == "deg" else a


def from_radians(values: npt.NDArray[np.float64], unit: str | None) -> npt.NDArray[np.float64]:
    """Values in radians, in ``unit``."""
    return np.degrees(values) if unit == "deg" else values


def angle_in(value: float, given: str | None, model: str) -> float:
    """An angle ``value`` given in ``given`` (None: the model's own unit), in the model's angle unit ``model``."""
    if given is None or given == model:
        return float(value)
    return math.degrees(value) if model == "deg" else math.radians(value)


def looks_like_degrees(value: float) -> bool:
    """Whether ``value``, an angle in radians, looks like degrees: a whole number of at least 90 that is a multiple
    of 15 (90, 180, 360, 720). The deck reader asks the same of a deck's angles
    (``crates/mechfem-deck/src/compile/warn.rs``)."""
    v = float(value)
    return abs(v) >= 90.0 and v.is_integer() and v % 15.0 == 0.0


def looks_like_radians(value: float) -> bool:
    """Whether ``value``, an angle in degrees, looks like radians: pi/2, pi or 2 pi (or their multiples up to 4)
    written to at least three decimals, as the deck reader asks."""
    v = abs(float(value))
    return v != 0.0 and any(abs(v - k * math.pi / 2.0) < 5e-4 for k in range(1, 9))


def wrong_angle_unit(value: float, angle: str) -> str | None:
    """Why ``value``, an angle in the unit ``angle`` (``"rad"`` or ``"deg"``), looks like the other unit (``"it
    looks like degrees (720 deg is 12.566371 rad)"``), or None when it does not."""
    if angle == "deg" and looks_like_radians(value):
        return f"it looks like radians ({value:g} rad is {math.degrees(value):.4f} deg)"
    if angle != "deg" and looks_like_degrees(value):
        return f"it looks like degrees ({value:g} deg is {math.radians(value):.6f} rad)"
    return None


#: The watt's decimal multiples by name, as the core writes a power.
_WATTS = ((1e-6, "µW"), (1e-3, "mW"), (1.0, "W"), (1e3, "kW"), (1e6, "MW"))


def watts(units: Mapping[str, str | None]) -> str | None:
    """The unit of a power in ``units`` by the watt's name where force x length / time is one of its decimal
    multiples (N·m/s and N·mm/ms are ``W``, N·mm/s is ``mW``); None otherwise (N·in/s, or a unit not declared)."""
    length, force, time = units.get("length"), units.get("force"), units.get("time") or "s"
    if length is None or force is None:
        return None
    size = SI["force"][force] * SI["length"][length] / SI["time"][time]
    return next((name for w, name in _WATTS if abs(size - w) <= 1e-12 * w), None)


#: The joule's decimal multiples by name, as the core writes work.
_JOULES = ((1e-3, "mJ"), (1.0, "J"), (1e3, "kJ"))


def joules(units: Mapping[str, str | None]) -> str | None:
    """The unit of work (an energy) in ``units`` by the joule's name where force x length is one of its decimal
    multiples (N·m and kN·mm are ``J``, N·mm is ``mJ``); None otherwise (N·cm, N·in, or a unit not declared). A
    torque, of the same exponents, keeps force x length."""
    length, force = units.get("length"), units.get("force")
    if length is None or force is None:
        return None
    size = SI["force"][force] * SI["length"][length]
    return next((name for w, name in _JOULES if abs(size - w) <= 1e-12 * w), None)


#: The base kinds in the order of a :func:`symbol`'s exponents; force and mass are written first, as in ``N·mm``
#: and ``kg·mm²``.
_ORDER = ("force", "mass", "length", "angle", "time")
_POWER = {2: "²", 3: "³"}


def symbol(units: Mapping[str, str | None], work: bool = False, **exponents: int) -> str:
    """The unit of a quantity of the given ``exponents`` of ``length``, ``angle``, ``mass``, ``force`` and
    ``time`` in a model's ``units`` (its echo's ``units``, None where not declared), written as the core writes a
    buffer's unit: ``N·mm``, ``kg·mm²``, ``mm/s²``, ``mm/deg``, ``-`` for a pure number (deg/deg); "" when the model
    declares no units, or no unit of a kind the quantity needs. ``work`` says that force x length is work (an
    energy), named by the joule where it can be (:func:`joules`), not a torque."""
    if not any(units.values()):
        return ""
    if any(e and not units.get(k) for k, e in exponents.items()):
        return ""
    if {k: e for k, e in exponents.items() if e} == {"force": 1, "length": 1, "time": -1}:
        named = watts(units)
        if named is not None:
            return named
    if work and {k: e for k, e in exponents.items() if e} == {"force": 1, "length": 1}:
        named = joules(units)
        if named is not None:
            return named

    def part(sign: int) -> str:
        out = []
        for k in _ORDER:
            n = sign * exponents.get(k, 0)
            if n > 0:
                out.append(f"{units[k]}{_POWER.get(n, '' if n == 1 else f'^{n}')}")
        return "·".join(out)

    num, den = part(1), part(-1)
    if not den:
        return num or "-"
    if not num:
        return f"1/{den}"
    return f"{num}/({den})" if "·" in den else f"{num}/{den}"


__all__ = [
    "FIELD",
    "LARGE_ANGLE",
    "SI",
    "UNITS",
    "Unit",
    "Units",
    "angle_in",
    "array_to_radians",
    "check_output_unit",
    "check_unit",
    "factor",
    "from_radians",
    "kind_of",
    "looks_like_degrees",
    "looks_like_radians",
    "scale",
    "joules",
    "symbol",
    "to_radians",
    "watts",
    "wrong_angle_unit",
]
