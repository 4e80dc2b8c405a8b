"""The parts of a :class:`~mechfem.Mechanism`: co-ordinates, points, elements, form parameters and their
combinations, what a form parameter does (:class:`Keep`, :class:`Driven`, :class:`Output`) and the rows of D^c.

The Python names of the catalogue's form parameters (:data:`ATTRIBUTES`) live here too; the catalogue itself
(:data:`FORMS`, :data:`SLOTS`) is the core's, read by :mod:`mechfem.model.catalogue`.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Literal, TypeAlias

from mechfem._util.checks import finite
from mechfem._util.names import suggestion
from mechfem.model.catalogue import FORMS, form_dimension
from mechfem.model.units import Unit, angle_in, check_unit

ATTRIBUTES: dict[str, str] = {
    "LENL": "length",
    "ANGB": "angle",
    "ANGV": "angle",
    "LENU": "u",
    "LENV": "v",
    "GEAR": "gear",
    "BELT": "belt",
    "COOR": "value",
}
"""The Python attribute of each form parameter (``bar.length`` is ``LENL``)."""

# --- co-ordinates and points -------------------------------------------------------------------------------------


@dataclass(eq=False)
class Coordinate:
    """One co-ordinate of the mechanism: a point's x or y, an angle, a ratio or a radius.

    ``value`` is its initial value (for a moving one a possibly rough estimate of position 1).
    """

    name: str
    value: float
    fixed: bool
    kind: Literal["x", "y", "angle", "scalar"]
    point: Point | None = field(default=None, repr=False)
    number: int | None = field(default=None, repr=False)
    """The deck's number, kept for a mechanism read from a deck (None: numbered when written)."""

    def __repr__(self) -> str:
        return f"Coordinate({self.name!r}, {self.value!r}, {'fixed' if self.fixed else 'moving'})"


@dataclass(eq=False)
class Point:
    """A point: two co-ordinates, each fixed or moving."""

    name: str
    x: Coordinate
    y: Coordinate

    @property
    def fixed(self) -> bool:
        """True when both co-ordinates are fixed."""
        return self.x.fixed and self.y.fixed

    @property
    def xy(self) -> tuple[float, float]:
        """The initial values of x and y."""
        return self.x.value, self.y.value

    def __repr__(self) -> str:
        state = "fixed" if self.fixed else "moving"
        return f"Point({self.name!r}, {self.x.value!r}, {self.y.value!r}, {state})"


# --- form parameters and their combinations -------------------------------------------------------------------------


class _Expr:
    """Arithmetic shared by form parameters and their combinations."""

    def terms(self) -> tuple[tuple[float, FormParameter], ...]:
        raise NotImplementedError

    def __add__(self, other: _Expr) -> Combination:
        if not isinstance(other, _Expr):
            return NotImplemented
        return Combination(self.terms() + other.terms())

    def __sub__(self, other: _Expr) -> Combination:
        if not isinstance(other, _Expr):
            return NotImplemented
        return Combination(self.terms() + tuple((-f, p) for f, p in other.terms()))

    def __mul__(self, factor: float) -> Combination:
        if isinstance(factor, _Expr) or not isinstance(factor, int | float):
            return NotImplemented
        f = finite(factor, "a factor")
        return Combination(tuple((f * g, p) for g, p in self.terms()))

    __rmul__ = __mul__

    def __neg__(self) -> Combination:
        return Combination(tuple((-f, p) for f, p in self.terms()))

    def __pos__(self) -> Combination:
        return Combination(self.terms())

    def formula(self) -> str:
        """The combination in words, e.g. ``bar2.angle - bar4.angle``."""
        out = ""
        for f, p in self.terms():
            text = p.label if abs(f) == 1.0 else f"{abs(f):g}*{p.label}"
            out = ("-" if f < 0 else "") + text if not out else out + (" - " if f < 0 else " + ") + text
        return out


class FormParameter(_Expr):
    """One form parameter of one element, e.g. ``crank.angle`` (the ``ANGB`` of element ``crank``)."""

    def __init__(self, element: Element, form: str) -> None:
        self.element = element
        self.form = form
        """The deck's name (``LENL``, ``ANGB``, ...)."""

    @property
    def attribute(self) -> str:
        """The Python name on the element (``length``, ``angle``, ...)."""
        return ATTRIBUTES[self.form]

    @property
    def label(self) -> str:
        """``element.attribute``, the name of the row an element's own role makes."""
        return f"{self.element.name}.{self.attribute}"

    @property
    def is_angle(self) -> bool:
        """True for an angle, as the catalogue says: a direction, an angle co-ordinate, a gear pair's assembly
        angle, or the co-ordinate of a single-co-ordinate element on an angle."""
        dimension = form_dimension(self.element.type, self.form)
        if dimension == "any":
            return any(c.kind == "angle" for c in self.element.coordinates)
        return dimension == "angle"

    def terms(self) -> tuple[tuple[float, FormParameter], ...]:
        return ((1.0, self),)

    def __eq__(self, other: object) -> bool:
        return isinstance(other, FormParameter) and other.element is self.element and other.form == self.form

    def __hash__(self) -> int:
        return hash((id(self.element), self.form))

    def __repr__(self) -> str:
        what = ELEMENT_WORDS.get(self.element.type, self.element.type)
        return f"<{self.label}: the {self.attribute} of the {what} {self.element.name!r}>"


class Combination(_Expr):
    """A factor-weighted sum of form parameters (theory, eq. 5.33), made with ``+``, ``-`` and ``*``."""

    def __init__(self, terms: tuple[tuple[float, FormParameter], ...]) -> None:
        if not terms:
            raise ValueError("a combination needs at least one form parameter")
        self._terms = terms

    def terms(self) -> tuple[tuple[float, FormParameter], ...]:
        return self._terms

    def __repr__(self) -> str:
        return f"<{self.formula()}>"


Expression: TypeAlias = FormParameter | Combination


# --- what a form parameter does ------------------------------------------------------------------------------------


@dataclass(frozen=True)
class Keep:
    """Prescribed, at the value it has at the given co-ordinates (a FORM line without PARA)."""


@dataclass(frozen=True)
class Driven:
    """An input (degree of freedom) that the motion drives.

    ``start`` is its value at position 1 (default: its value at the given co-ordinates), for an angle in
    ``unit`` (``"rad"``, the default, or ``"deg"``); ``name`` names the input (default: the form parameter's
    label, e.g. ``crank.angle``).
    """

    start: float | None = None
    name: str | None = None
    unit: Unit | None = None


@dataclass(frozen=True)
class Output:
    """Not prescribed; computed at every position as the output ``name`` (a dependent form parameter)."""

    name: str


Role: TypeAlias = float | Keep | Driven | Output | None
"""What a form parameter passed to an element method does: a number prescribes it, ``None`` leaves it free."""


@dataclass(eq=False)
class Row:
    """A prescribed row of D^c (``kind`` ``prescribed`` or ``input``) or an output (``output``).

    ``value`` is the prescribed value (an input's value at position 1); None keeps the value at
    the given co-ordinates. ``element`` is True for a row that an element's own keyword made.
    """

    name: str
    kind: Literal["prescribed", "input", "output"]
    terms: tuple[tuple[float, FormParameter], ...]
    value: float | None = None
    element: bool = False

    def formula(self) -> str:
        """The combination in words."""
        return Combination(self.terms).formula()

    @property
    def is_angle(self) -> bool:
        """True when every form parameter of the row is an angle (so is the row)."""
        return all(p.is_angle for _, p in self.terms)

    def __repr__(self) -> str:
        value = "" if self.value is None else f" = {self.value!r}"
        return f"Row({self.name!r}, {self.kind}: {self.formula()}{value})"


# --- elements ------------------------------------------------------------------------------------------------------


Slot: TypeAlias = Point | Coordinate


class Element:
    """One element: its type (deck name), its points and co-ordinates in the type's order."""

    def __init__(self, name: str, type: str, slots: Sequence[Slot]) -> None:
        self.name = name
        self.type = type
        self.slots: tuple[Slot, ...] = tuple(slots)
        """Points and co-ordinates in the order of the catalogue (``elements.md``)."""

    @property
    def coordinates(self) -> tuple[Coordinate, ...]:
        """Every co-ordinate in deck order (a point gives its x and y)."""
        out: list[Coordinate] = []
        for s in self.slots:
            out.extend((s.x, s.y) if isinstance(s, Point) else (s,))
        return tuple(out)

    @property
    def points(self) -> tuple[Point, ...]:
        """The element's points, in deck order."""
        return tuple(s for s in self.slots if isinstance(s, Point))

    @property
    def forms(self) -> tuple[FormParameter, ...]:
        """Every form parameter of the element."""
        return tuple(FormParameter(self, f) for f in FORMS[self.type])

    def form(self, name: str) -> FormParameter:
        """The form parameter ``name``: a deck name (``LENL``) or an attribute (``length``)."""
        for f in FORMS[self.type]:
            if name.upper() == f or name == ATTRIBUTES[f]:
                return FormParameter(self, f)
        raise AttributeError(unknown_form(self, name))

    @property
    def length(self) -> FormParameter:
        """``LENL``: the distance P-Q (BIN, TR2, BLT)."""
        return self.form("LENL")

    @property
    def angle(self) -> FormParameter:
        """``ANGB`` (direction P->Q of BIN, TR2, BLT) or ``ANGV`` (the angle co-ordinate of HLF, TR1)."""
        return self.form("ANGB") if "ANGB" in FORMS[self.type] else self.form("ANGV")

    @property
    def u(self) -> FormParameter:
        """``LENU``: u of the third point in the element's frame (TR1, TR2)."""
        return self.form("LENU")

    @property
    def v(self) -> FormParameter:
        """``LENV``: v of the third point in the element's frame (TR1, TR2)."""
        return self.form("LENV")

    @property
    def gear(self) -> FormParameter:
        """``GEAR``: the assembly angle of a gear pair or rack (GR1, GR2, RK1, RK2)."""
        return self.form("GEAR")

    @property
    def belt(self) -> FormParameter:
        """``BELT``: the belt length from mark to mark (BLT)."""
        return self.form("BELT")

    @property
    def value(self) -> FormParameter:
        """``COOR``: the co-ordinate itself (CRD)."""
        return self.form("COOR")

    def __repr__(self) -> str:
        names = " ".join(s.name for s in self.slots)
        return f"Element({self.name!r}, {ELEMENT_WORDS.get(self.type, self.type)}: {names})"


# --- the mechanism -------------------------------------------------------------------------------------------------


def role_row(fp: FormParameter, role: Role, angle: str = "rad") -> Row | None:
    """The row ``role`` makes of ``fp`` in a model whose angles are in ``angle`` (None for no role)."""
    if role is None:
        return None
    if isinstance(role, Keep):
        return Row(fp.label, "prescribed", fp.terms(), None, True)
    if isinstance(role, Driven):
        start = None if role.start is None else finite(role.start, f"the start value of {fp.label}")
        unit = check_unit(role.unit, f"the unit of {fp.label}'s start")
        if start is not None and unit not in (None, angle):
            if not fp.is_angle:
                raise ValueError(
                    f"Driven(start={role.start!r}, unit={unit!r}) on {fp.label}, which is not an angle: give its "
                    f"start in its own unit, without unit={unit!r}"
                )
            start = angle_in(start, unit, angle)
        return Row(role.name or fp.label, "input", fp.terms(), start, True)
    if isinstance(role, Output):
        return Row(role.name, "output", fp.terms(), None, True)
    if isinstance(role, bool) or not isinstance(role, int | float):
        raise TypeError(f"{fp.label}: expected a number, Keep(), Driven(), Output(name) or None, got {role!r}")
    return Row(fp.label, "prescribed", fp.terms(), finite(role, fp.label), True)


def unknown_form(element: Element, name: object) -> str:
    """The message for a form parameter ``name`` that ``element`` does not have, with the closest it has."""
    forms = FORMS[element.type]
    known = [ATTRIBUTES[f] for f in forms]
    close = suggestion(name, known + list(forms))
    close = ATTRIBUTES.get(close, close) if close is not None else None
    hint = f"; did you mean {close!r}?" if close is not None else ""
    what = ELEMENT_WORDS.get(element.type, element.type)
    listed = ", ".join(known)
    return f"no form parameter named {name!r} on the {what} {element.name!r}{hint} (its form parameters: {listed})"


ELEMENT_WORDS: dict[str, str] = {
    "BIN": "bar",
    "HLF": "half beam",
    "TR1": "ternary-1",
    "TR2": "ternary-2",
    "GR1": "gear pair",
    "GR2": "gear pair",
    "RK1": "rack",
    "RK2": "rack",
    "BLT": "belt",
    "CRD": "single co-ordinate",
}
"""Each element type in the words of the Python API (its :class:`~mechfem.Mechanism` method)."""


def kind_of(obj: object) -> str:
    """What a part of a mechanism is, in words: ``point``, ``co-ordinate``, ``element``, ``input``, ``output`` or
    ``prescribed value``."""
    if isinstance(obj, Row):
        return {"input": "input", "output": "output"}.get(obj.kind, "prescribed value")
    if isinstance(obj, Point):
        return "point"
    if isinstance(obj, Coordinate):
        return "co-ordinate"
    if isinstance(obj, Element):
        return "element"
    return type(obj).__name__
