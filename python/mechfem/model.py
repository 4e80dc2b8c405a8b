"""Mechanisms built in Python: named points, elements and form parameters instead of co-ordinate numbers.

A :class:`Mechanism` is written as a deck and run through the same reader and solver as
``mechfem run``, so a model built here and the same model written as a deck give the same
numbers. Every element type of the catalogue has a method; each of its form parameters is

* left free (``None``, the default),
* prescribed to a value (a number) or kept at its value at the given co-ordinates (:class:`Keep`),
* an input that the motion drives (:class:`Driven`),
* or an output only (:class:`Output`).

Combinations of form parameters (a fixed angle between two bars, a gear relation, any
factor-weighted sum) are written with ``+``, ``-`` and ``*`` and passed to
:meth:`Mechanism.prescribe`, :meth:`Mechanism.drive` or :meth:`Mechanism.output`::

    m = Mechanism("fourbar")
    A0, B0 = m.fixed("A0", 0, 0), m.fixed("B0", 4, 0)
    A, B = m.point("A", 1, 0), m.point("B", 3.5, 2.5)
    crank = m.bar("crank", A0, A, length=1.0, angle=Driven())
    coupler = m.bar("coupler", A, B, length=3.5)
    rocker = m.bar("rocker", B0, B, length=3.0, angle=Output("psi"))
    result = m.run(Motion.by(72, 2 * math.pi))
    result.output("psi", order=1)          # d psi / d crank angle at every position
"""

from __future__ import annotations

import copy
import os
from collections.abc import Callable, Iterator, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any, Literal, TypeAlias

import numpy.typing as npt

from mechfem.checks import check_name, finite
from mechfem.motion import MAX_ITER, By, Dynamic, Free, InputKey, InputMotion, Motion, Table, To, input_dof, simulation
from mechfem.storage import BUFFER_ARGS, Picture, Ref, Storage

if TYPE_CHECKING:
    from mechfem.analysis import Analysis
    from mechfem.loads import (
        Body,
        Force,
        Gravity,
        Inertia,
        Load,
        Loads,
        LoadTable,
        Motor,
        PointMass,
        PointRef,
        RowRef,
        Spring,
    )

FORMS: dict[str, tuple[str, ...]] = {
    "BIN": ("LENL", "ANGB"),
    "HLF": ("ANGV",),
    "TR1": ("ANGV", "LENU", "LENV"),
    "TR2": ("LENL", "ANGB", "LENU", "LENV"),
    "GR1": ("GEAR",),
    "GR2": ("GEAR",),
    "RK1": ("GEAR",),
    "RK2": ("GEAR",),
    "BLT": ("LENL", "ANGB", "BELT"),
    "CRD": ("COOR",),
}
"""The form parameters of every element type (deck names, in the catalogue's order)."""

SLOTS: dict[str, str] = {
    "BIN": "PP",
    "HLF": "Pa",
    "TR1": "PaP",
    "TR2": "PPP",
    "GR1": "aaas",
    "GR2": "aaass",
    "RK1": "PaPsa",
    "RK2": "PPPsa",
    "BLT": "PaPass",
    "CRD": "s",
}
"""What an element type's co-ordinates are, in deck order: ``P`` a point (x, y), ``a`` an angle, ``s`` a scalar."""

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

    def terms(self) -> tuple[tuple[float, FormParameter], ...]:
        return ((1.0, self),)

    def __eq__(self, other: object) -> bool:
        return isinstance(other, FormParameter) and other.element is self.element and other.form == self.form

    def __hash__(self) -> int:
        return hash((id(self.element), self.form))

    def __repr__(self) -> str:
        return f"<{self.label} ({self.form} of {self.element.type} {self.element.name!r})>"


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

    ``start`` is its value at position 1 (default: its value at the given co-ordinates); ``name``
    names the input (default: the form parameter's label, e.g. ``crank.angle``).
    """

    start: float | None = None
    name: str | None = None


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
        names = ", ".join(f"{ATTRIBUTES[f]} ({f})" for f in FORMS[self.type])
        raise AttributeError(f"element {self.name!r} ({self.type}) has no form parameter {name!r}; it has {names}")

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
        return f"Element({self.name!r}, {self.type}: {names})"


# --- the mechanism -------------------------------------------------------------------------------------------------


def _role_row(fp: FormParameter, role: Role) -> Row | None:
    if role is None:
        return None
    if isinstance(role, Keep):
        return Row(fp.label, "prescribed", fp.terms(), None, True)
    if isinstance(role, Driven):
        start = None if role.start is None else finite(role.start, f"the start value of {fp.label}")
        return Row(role.name or fp.label, "input", fp.terms(), start, True)
    if isinstance(role, Output):
        return Row(role.name, "output", fp.terms(), None, True)
    if isinstance(role, bool) or not isinstance(role, int | float):
        raise TypeError(f"{fp.label}: expected a number, Keep(), Driven(), Output(name) or None, got {role!r}")
    return Row(fp.label, "prescribed", fp.terms(), finite(role, fp.label), True)


class Mechanism:
    """A planar mechanism: named points and co-ordinates, elements on them, prescribed form parameters,
    inputs and outputs.

    ``motion`` and ``storage`` are the defaults :meth:`run` and :meth:`to_deck` use (set by
    :meth:`from_deck` to the deck's own). ``loads`` holds the masses and loads (None without any: a
    kinematic model, mode ``KIN ANA``; with them its deck is a ``DYN ANA`` one, or ``DYN SIM`` for
    :meth:`simulate`).
    """

    def __init__(self, name: str = "mechanism") -> None:
        self.name = check_name(name)
        self.coordinates: list[Coordinate] = []
        self.points: list[Point] = []
        self.elements: list[Element] = []
        self.rows: list[Row] = []
        self.motion: Motion | None = None
        self.storage: Storage | None = None
        self.loads: Loads | None = None
        self._names: dict[str, object] = {}

    # -- names

    def _check_free(self, name: str) -> None:
        check_name(name)
        if name in self._names:
            raise ValueError(f"the name {name!r} is already used by {self._names[name]!r}")

    def _claim(self, name: str, obj: object) -> None:
        self._check_free(name)
        self._names[name] = obj

    def __getitem__(self, name: str) -> Any:
        """The point, co-ordinate, element or row called ``name`` (typed ``Any`` for convenience: check with
        ``isinstance`` where it matters)."""
        try:
            return self._names[name]
        except KeyError:
            raise KeyError(f"the mechanism {self.name!r} has nothing called {name!r}") from None

    def __contains__(self, name: object) -> bool:
        return name in self._names

    def names(self) -> Iterator[str]:
        """Every name, in the order they were given."""
        return iter(self._names)

    @property
    def inputs(self) -> list[Row]:
        """The input rows, in DOF order."""
        return [r for r in self.rows if r.kind == "input"]

    @property
    def outputs(self) -> list[Row]:
        """The output rows, in order."""
        return [r for r in self.rows if r.kind == "output"]

    @property
    def prescribed(self) -> list[Row]:
        """The prescribed rows that are not inputs."""
        return [r for r in self.rows if r.kind == "prescribed"]

    def _own(self, obj: Slot) -> Slot:
        if isinstance(obj, Point | Coordinate) and self._names.get(obj.name) is obj:
            return obj
        if isinstance(obj, Point | Coordinate):
            raise ValueError(f"{obj!r} belongs to another mechanism")
        raise TypeError(f"expected a point or a co-ordinate of this mechanism, got {obj!r}")

    # -- co-ordinates and points

    def _coordinate(
        self, name: str, value: float, fixed: bool, kind: Literal["x", "y", "angle", "scalar"]
    ) -> Coordinate:
        c = Coordinate(name, finite(value, f"the value of {name!r}"), bool(fixed), kind)
        self._claim(name, c)
        self.coordinates.append(c)
        return c

    def fixed(self, name: str, x: float, y: float) -> Point:
        """A point of the frame (both co-ordinates fixed)."""
        return self.point(name, x, y, fixed="xy")

    def point(self, name: str, x: float, y: float, *, fixed: Literal["", "x", "y", "xy"] = "") -> Point:
        """A moving point at ``(x, y)`` (an estimate of position 1); ``fixed`` names co-ordinates that do not move
        (``"y"``: a slider on a horizontal guide)."""
        if fixed not in ("", "x", "y", "xy"):
            raise ValueError(f"fixed must be '', 'x', 'y' or 'xy', not {fixed!r}")
        self._check_free(name)
        cx = self._coordinate(f"{name}.x", x, "x" in fixed, "x")
        cy = self._coordinate(f"{name}.y", y, "y" in fixed, "y")
        p = Point(name, cx, cy)
        cx.point = cy.point = p
        self._claim(name, p)
        self.points.append(p)
        return p

    def angle(self, name: str, value: float = 0.0, *, fixed: bool = False) -> Coordinate:
        """An angle co-ordinate (of a half beam, ternary-1, gear or belt wheel); moving unless ``fixed``."""
        return self._coordinate(name, value, fixed, "angle")

    def scalar(self, name: str, value: float, *, fixed: bool = True) -> Coordinate:
        """A scalar co-ordinate (a transmission ratio, a radius); fixed unless ``fixed=False``."""
        return self._coordinate(name, value, fixed, "scalar")

    def _slot(self, element: str, what: str, obj: Slot | float, kind: Literal["angle", "scalar"]) -> Coordinate:
        if isinstance(obj, Point):
            raise TypeError(f"element {element!r}: {what} must be a co-ordinate, not the point {obj.name!r}")
        if isinstance(obj, Coordinate):
            c = self._own(obj)
            assert isinstance(c, Coordinate)
            return c
        if isinstance(obj, int | float) and not isinstance(obj, bool):
            name = f"{element}.{what}"
            return self.angle(name, obj) if kind == "angle" else self.scalar(name, obj)
        raise TypeError(f"element {element!r}: {what} must be a co-ordinate or a number, got {obj!r}")

    def _pt(self, element: str, what: str, obj: object) -> Point:
        if not isinstance(obj, Point):
            raise TypeError(f"element {element!r}: {what} must be a point, got {obj!r}")
        p = self._own(obj)
        assert isinstance(p, Point)
        return p

    # -- elements

    def _element(self, name: str, type: str, slots: Sequence[Slot], roles: Mapping[str, Role]) -> Element:
        self._check_free(name)
        e = Element(name, type, slots)
        rows = [_role_row(FormParameter(e, f), roles.get(f)) for f in FORMS[type]]
        new = [r for r in rows if r is not None]
        seen: set[str] = set()
        for r in new:
            if r.name in self._names or r.name in seen or r.name == name:
                raise ValueError(f"element {name!r}: the name {r.name!r} is already used")
            seen.add(r.name)
        self._claim(name, e)
        self.elements.append(e)
        for r in new:
            self._claim(r.name, r)
            self.rows.append(r)
        return e

    def bar(self, name: str, p: Point, q: Point, *, length: Role = None, angle: Role = None) -> Element:
        """A binary element (BIN) from ``p`` to ``q``: ``length`` |PQ| and ``angle`` the direction P->Q."""
        return self._element(
            name, "BIN", [self._pt(name, "p", p), self._pt(name, "q", q)], {"LENL": length, "ANGB": angle}
        )

    def half_beam(self, name: str, p: Point, beta: Coordinate | float, *, angle: Role = None) -> Element:
        """A half beam (HLF): point ``p`` with the angle co-ordinate ``beta`` (a number makes a moving one)."""
        return self._element(
            name, "HLF", [self._pt(name, "p", p), self._slot(name, "beta", beta, "angle")], {"ANGV": angle}
        )

    def ternary1(
        self,
        name: str,
        p: Point,
        beta: Coordinate | float,
        r: Point,
        *,
        angle: Role = None,
        u: Role = None,
        v: Role = None,
    ) -> Element:
        """A ternary-1 element (TR1): a half beam at ``p`` with angle ``beta`` and the point ``r`` at ``(u, v)``
        in its frame."""
        slots: list[Slot] = [self._pt(name, "p", p), self._slot(name, "beta", beta, "angle"), self._pt(name, "r", r)]
        return self._element(name, "TR1", slots, {"ANGV": angle, "LENU": u, "LENV": v})

    def ternary2(
        self,
        name: str,
        p: Point,
        q: Point,
        r: Point,
        *,
        length: Role = None,
        angle: Role = None,
        u: Role = None,
        v: Role = None,
    ) -> Element:
        """A ternary-2 element (TR2): a bar ``p``-``q`` and the point ``r`` at ``(u, v)`` in the frame at ``p``
        along P->Q."""
        slots: list[Slot] = [self._pt(name, "p", p), self._pt(name, "q", q), self._pt(name, "r", r)]
        return self._element(name, "TR2", slots, {"LENL": length, "ANGB": angle, "LENU": u, "LENV": v})

    def gear_pair(
        self,
        name: str,
        a: Coordinate | float,
        b: Coordinate | float,
        c: Coordinate | float,
        *,
        ratio: Coordinate | float | None = None,
        radii: tuple[Coordinate | float, Coordinate | float] | None = None,
        gear: Role = None,
    ) -> Element:
        """A gear pair on the angle co-ordinates of wheel ``a``, carrier ``b`` and wheel ``c``.

        With ``ratio`` (the transmission ratio i as a co-ordinate, or a number for a fixed one) it is a GR1;
        with ``radii`` ``(R_a, R_c)`` a GR2. ``gear`` is the assembly angle.
        """
        angles = [self._slot(name, w, x, "angle") for w, x in (("beta_a", a), ("beta_b", b), ("beta_c", c))]
        if (ratio is None) == (radii is None):
            raise ValueError(f"gear pair {name!r}: give either ratio= (GR1) or radii= (GR2)")
        if ratio is not None:
            return self._element(name, "GR1", [*angles, self._slot(name, "i", ratio, "scalar")], {"GEAR": gear})
        assert radii is not None
        ra, rc = self._slot(name, "R_a", radii[0], "scalar"), self._slot(name, "R_c", radii[1], "scalar")
        return self._element(name, "GR2", [*angles, ra, rc], {"GEAR": gear})

    def rack1(
        self,
        name: str,
        p: Point,
        beta_b: Coordinate | float,
        q: Point,
        ratio: Coordinate | float,
        beta_a: Coordinate | float,
        *,
        gear: Role = None,
    ) -> Element:
        """Pinion and rack (RK1): the rack is a ternary-1 frame at ``p`` with angle ``beta_b``, ``q`` its third
        point; the pinion has angle ``beta_a`` and ``ratio`` i = +-R."""
        slots: list[Slot] = [
            self._pt(name, "p", p),
            self._slot(name, "beta_b", beta_b, "angle"),
            self._pt(name, "q", q),
            self._slot(name, "i", ratio, "scalar"),
            self._slot(name, "beta_a", beta_a, "angle"),
        ]
        return self._element(name, "RK1", slots, {"GEAR": gear})

    def rack2(
        self,
        name: str,
        p: Point,
        q: Point,
        r: Point,
        ratio: Coordinate | float,
        beta_a: Coordinate | float,
        *,
        gear: Role = None,
    ) -> Element:
        """Pinion and rack (RK2): the rack frame is at ``p`` along P->Q, ``r`` its third point; the pinion has
        angle ``beta_a`` and ``ratio`` i = +-R."""
        slots: list[Slot] = [
            self._pt(name, "p", p),
            self._pt(name, "q", q),
            self._pt(name, "r", r),
            self._slot(name, "i", ratio, "scalar"),
            self._slot(name, "beta_a", beta_a, "angle"),
        ]
        return self._element(name, "RK2", slots, {"GEAR": gear})

    def belt(
        self,
        name: str,
        p: Point,
        beta_a: Coordinate | float,
        q: Point,
        beta_c: Coordinate | float,
        r_p: Coordinate | float,
        r_q: Coordinate | float,
        *,
        length: Role = None,
        angle: Role = None,
        belt: Role = None,
    ) -> Element:
        """A belt (BLT) over wheel a (centre ``p``, angle ``beta_a``, radius ``r_p``) and wheel c (centre ``q``,
        angle ``beta_c``, radius ``r_q``); one negative radius makes a crossed belt."""
        slots: list[Slot] = [
            self._pt(name, "p", p),
            self._slot(name, "beta_a", beta_a, "angle"),
            self._pt(name, "q", q),
            self._slot(name, "beta_c", beta_c, "angle"),
            self._slot(name, "R_P", r_p, "scalar"),
            self._slot(name, "R_Q", r_q, "scalar"),
        ]
        return self._element(name, "BLT", slots, {"LENL": length, "ANGB": angle, "BELT": belt})

    def single_coordinate(self, name: str, coordinate: Coordinate, *, value: Role = None) -> Element:
        """A single-co-ordinate element (CRD) on ``coordinate`` (e.g. a slider's ``B.x``), to prescribe or drive it."""
        return self._element(name, "CRD", [self._slot(name, "x", coordinate, "scalar")], {"COOR": value})

    def element(self, name: str, type: str, slots: Sequence[Slot], **roles: Role) -> Element:
        """Any element by its deck type (``BIN``, ``TR2``, ...) with its points and co-ordinates in deck order
        (``elements.md``); ``roles`` by attribute or deck name (``length=0.4`` or ``LENL=0.4``)."""
        ty = type.upper()
        if ty not in FORMS:
            raise ValueError(f"unknown element type {type!r}; one of {', '.join(FORMS)}")
        given = list(slots)
        if len(given) != len(SLOTS[ty]):
            kinds = " ".join({"P": "point", "a": "angle", "s": "co-ordinate"}[k] for k in SLOTS[ty])
            raise ValueError(f"element {name!r}: {ty} takes {len(SLOTS[ty])} slots ({kinds}), got {len(given)}")
        checked: list[Slot] = []
        for k, (kind, obj) in enumerate(zip(SLOTS[ty], given, strict=True)):
            checked.append(
                self._pt(name, f"slot {k + 1}", obj) if kind == "P" else self._slot(name, f"slot {k + 1}", obj, "angle")
            )
        by_form: dict[str, Role] = {}
        for key, role in roles.items():
            matches = [f for f in FORMS[ty] if key.upper() == f or key == ATTRIBUTES[f]]
            if not matches:
                raise TypeError(f"element {name!r} ({ty}) has no form parameter {key!r}")
            by_form[matches[0]] = role
        return self._element(name, ty, checked, by_form)

    # -- rows

    def _terms(self, expr: Expression) -> tuple[tuple[float, FormParameter], ...]:
        if not isinstance(expr, FormParameter | Combination):
            raise TypeError(f"expected a form parameter or a combination of them, got {expr!r}")
        terms = expr.terms()
        for _, p in terms:
            if self._names.get(p.element.name) is not p.element:
                raise ValueError(f"{p!r} belongs to another mechanism")
        return terms

    def _row(
        self, name: str, kind: Literal["prescribed", "input", "output"], expr: Expression, value: float | None
    ) -> Row:
        v = None if value is None else finite(value, f"the value of {name!r}")
        r = Row(name, kind, self._terms(expr), v)
        self._claim(name, r)
        self.rows.append(r)
        return r

    def prescribe(self, name: str, expr: Expression, value: float | None = None) -> Row:
        """Prescribes a form parameter or a combination (a row of D^c) to ``value``; None keeps its value at the
        given co-ordinates."""
        return self._row(name, "prescribed", expr, value)

    def fixed_angle(self, name: str, a: Element, b: Element, value: float | None = None) -> Row:
        """Prescribes the angle ``a.angle - b.angle`` between two elements (e.g. two bars of one rigid link)."""
        return self.prescribe(name, a.angle - b.angle, value)

    def drive(self, name: str, expr: Expression, start: float | None = None) -> Row:
        """Makes a form parameter or a combination an input; ``start`` is its value at position 1."""
        return self._row(name, "input", expr, start)

    def output(self, name: str, expr: Expression) -> Row:
        """Computes a form parameter or a combination at every position, as the output ``name``."""
        return self._row(name, "output", expr, None)

    # -- masses and loads (mechfem.loads): inverse dynamics (DYN ANA) in a run, a simulation (DYN SIM) in simulate

    def mass(self, element: Element | str, m: float, u: float = 0.0, v: float = 0.0, J: float = 0.0) -> Body:
        """Makes ``element`` (BIN, HLF, TR1, TR2) a rigid body of mass ``m``, centre of mass at ``(u, v)`` in its frame
        (origin at its first point; u along P->Q of BIN and TR2, along the angle co-ordinate of HLF and TR1) and
        moment of inertia ``J`` about that centre."""
        from mechfem import loads

        return loads.add_mass(self, element, m, u, v, J)

    def point_mass(self, point: PointRef, m: float) -> PointMass:
        """A point mass ``m`` at ``point`` (or at two co-ordinates ``(x, y)``)."""
        from mechfem import loads

        return loads.add_point_mass(self, point, m)

    def inertia(self, angle: Coordinate | str, J: float) -> Inertia:
        """A rotational inertia ``J`` on an angle co-ordinate (a wheel of a gear pair or belt without an element)."""
        from mechfem import loads

        return loads.add_inertia(self, angle, J)

    def gravity(self, gx: float, gy: float) -> Gravity:
        """The acceleration of gravity, e.g. ``m.gravity(0, -9.81)`` (given again, it replaces the one before)."""
        from mechfem import loads

        return loads.add_gravity(self, gx, gy)

    def force(self, point: PointRef, fx: float, fy: float) -> Force:
        """A constant force ``(fx, fy)`` at ``point`` (or at two co-ordinates ``(x, y)``)."""
        from mechfem import loads

        return loads.add_force(self, point, fx, fy)

    def load(self, row: RowRef, value: float) -> Load:
        """A constant generalised force on a prescribed row, input or output (by name, row or form parameter): a
        torque on an angle, a force along a length; it does the work ``value * d row``."""
        from mechfem import loads

        return loads.add_load(self, row, value)

    def load_table(self, row: RowRef, t: npt.ArrayLike, values: npt.ArrayLike, *, file: str | None = None) -> LoadTable:
        """A generalised force on ``row`` given at the times ``t``, linear between them, constant outside (a LOADFUNC
        file written beside the deck, named ``file`` or ``<mechanism>_load<k>.dat``)."""
        from mechfem import loads

        return loads.add_load_table(self, row, t, values, file)

    def spring(self, row: RowRef, k: float, free_value: float, damping: float = 0.0) -> Spring:
        """A spring of stiffness ``k`` and free value ``free_value`` on ``row`` with a viscous damper ``damping``:
        the generalised force ``-k (row - free_value) - damping * d(row)/dt``."""
        from mechfem import loads

        return loads.add_spring(self, row, k, free_value, damping)

    def motor(self, row: RowRef, stall_torque: float, no_load_speed: float) -> Motor:
        """A motor on ``row`` whose torque falls linearly with its speed:
        ``stall_torque (1 - d(row)/dt / no_load_speed)``."""
        from mechfem import loads

        return loads.add_motor(self, row, stall_torque, no_load_speed)

    # -- values

    def set(self, name: str, value: float | tuple[float, float]) -> None:
        """Changes a value in place: a row's prescribed value (an input's start), a co-ordinate's initial value,
        or a point's ``(x, y)``."""
        for target, v in self._targets({name: value}).items():
            if isinstance(target, Row):
                target.value = v
            else:
                target.value = v

    def _targets(self, changes: Mapping[str, float | tuple[float, float]]) -> dict[Row | Coordinate, float]:
        out: dict[Row | Coordinate, float] = {}
        for name, value in changes.items():
            obj = self[name]
            if isinstance(obj, Point):
                if not isinstance(value, tuple | list) or len(value) != 2:
                    raise TypeError(f"point {name!r} takes (x, y), got {value!r}")
                out[obj.x] = finite(value[0], f"{name}.x")
                out[obj.y] = finite(value[1], f"{name}.y")
            elif isinstance(obj, Coordinate):
                out[obj] = finite(value, name)  # type: ignore[arg-type]
            elif isinstance(obj, Row):
                if obj.kind == "output":
                    raise ValueError(f"{name!r} is an output: it has no prescribed value")
                out[obj] = finite(value, name)  # type: ignore[arg-type]
            else:
                raise TypeError(f"{name!r} is {obj!r}: only rows, co-ordinates and points have values")
        return out

    def variant(self, changes: Mapping[str, float | tuple[float, float]] | None = None, /, **more: float) -> Mechanism:
        """A copy with some values changed (see :meth:`set`), e.g. ``m.variant(kappa=-5.2)``
        or ``m.variant({"B0.x": 0.6})``."""
        m = copy.deepcopy(self)
        for name, v in {**(changes or {}), **more}.items():
            m.set(name, v)
        return m

    # -- decks

    def to_deck(self, motion: Motion | None = None, storage: Storage | None = None) -> str:
        """The mechanism as deck text (with ``motion`` and ``storage``; defaults: :attr:`motion`, :attr:`storage`).

        A :class:`Table` motion refers to a MOV_FUNC file: :meth:`save_deck` writes it beside the deck.
        """
        from mechfem import deckio

        return deckio.write(self, motion or self.motion, storage or self.storage).text

    def save_deck(
        self, path: str | os.PathLike[str], motion: Motion | None = None, storage: Storage | None = None
    ) -> Path:
        """Writes the deck (and the files of its table motions, beside it); returns the deck's path."""
        from mechfem import deckio

        return deckio.save(self, Path(path), motion or self.motion, storage or self.storage)

    @classmethod
    def from_deck(cls, path: str | os.PathLike[str]) -> Mechanism:
        """Reads a deck: points are named ``P<i>`` after their x co-ordinate's number, other co-ordinates
        ``x<i>``, elements ``E<k>``, combined rows ``row<r>`` and outputs ``out<k>``; an element's own row
        is named by its label (``E1.angle``). The deck's motion and storage become :attr:`motion` and
        :attr:`storage`."""
        from mechfem import deckio

        return deckio.read(Path(path))

    @classmethod
    def from_deck_text(cls, text: str, name: str = "deck", base_dir: str | os.PathLike[str] = ".") -> Mechanism:
        """As :meth:`from_deck`, for deck text; MOV_FUNC files are read from ``base_dir``."""
        from mechfem import deckio

        return deckio.read_text(text, name, Path(base_dir))

    # -- analysis

    def run(
        self,
        motion: Motion | None = None,
        storage: Storage | None = None,
        progress: bool | Callable[[int, int], object] | None = None,
        order: int | None = 2,
    ) -> Analysis:
        """Runs the motion (default :attr:`motion`; without one, position 1 only) and returns every result.

        ``progress`` True shows a progress bar, a callable is called as ``progress(done, total)``.
        ``order`` is the transfer functions computed at every position: 2 (default) first and second
        order; 1 first order only (faster; second-order results and accelerations are NaN); None what the
        storage's buffers need, as ``mechfem run`` computes them. The solver predicts positions differently
        without the second order, so only runs with the same orders agree to the last bit (otherwise
        within the Newton tolerance, ACCURACY).
        Raises :class:`~mechfem.DeckError` for a model the deck reader refuses and
        :class:`~mechfem.AssemblyError`, :class:`~mechfem.ConvergenceError` or
        :class:`~mechfem.LimitPositionError` when position 1 cannot be computed, with this model's names, and
        :class:`~mechfem.ResourceError` before the run when its results would exceed the memory limit
        (:mod:`mechfem.limits`). Ctrl-C raises :class:`~mechfem.RunInterrupted` with the :class:`Analysis` of
        the positions computed so far. A motion that stops early returns the positions up to there
        (:meth:`Analysis.stop_reason` says why) and warns with :class:`~mechfem.IncompleteRunWarning`.
        """
        from mechfem import deckio
        from mechfem.errors import warn_incomplete

        analysis = deckio.run(self, motion or self.motion, storage or self.storage, progress=progress, order=order)
        warn_incomplete(analysis.stop_reason())
        return analysis

    def simulate(
        self,
        t_end: float,
        steps: int,
        v0: float | Mapping[InputKey, float] | None = None,
        *,
        drive: Mapping[InputKey, By | To | Table] | None = None,
        rtol: float | None = None,
        atol: float | None = None,
        accuracy: float | None = None,
        max_iter: int | None = None,
        storage: Storage | None = None,
        progress: bool | Callable[[int, int], object] | None = None,
        order: int | None = 2,
    ) -> Analysis:
        """Simulates the motion under the masses and loads from time 0 to ``t_end`` (mode ``DYN SIM``), with results
        at ``steps + 1`` positions ``t_end / steps`` apart: the inputs of ``drive`` (input -> :class:`By`,
        :class:`To` or :class:`Table`) follow that motion, every other input moves under the forces from the speed
        ``v0`` (a number for the only one, a mapping by input for several; None: from rest). ``rtol`` and ``atol``
        are the integrator's tolerances (default ``accuracy``, 1e-10); the rest is as for :meth:`run`, whose
        :class:`Analysis` it returns, with :attr:`Analysis.simulation` the integrator's work. A simulation that
        stops early (a limit position, a step size that collapsed) returns the positions it reached and says why,
        as a run does. The same as ``run(Motion.dynamic(...))`` with every input named."""
        motion = simulation(self, t_end, steps, v0, drive, rtol=rtol, atol=atol, accuracy=accuracy, max_iter=max_iter)
        return self.run(motion, storage, progress, order)

    def check(self, motion: Motion | None = None) -> Analysis:
        """Computes position 1 only (with the first values of a table motion, as a run would)."""
        from mechfem import deckio

        return deckio.run(self, motion or self.motion, self.storage, with_motion=False)

    def __repr__(self) -> str:
        return (
            f"Mechanism({self.name!r}: {len(self.points)} points, {len(self.elements)} elements, "
            f"{len(self.rows)} rows, {len(self.inputs)} input(s))"
        )

    def figure(self, names: bool = True) -> Any:
        """A figure (``matplotlib.figure.Figure``) of the mechanism at position 1, its points named."""
        from mechfem import figures

        return figures.mechanism_figure(self, names)

    def _repr_png_(self) -> bytes | None:
        """The mechanism at position 1 as a PNG image (for Jupyter), or None when it cannot be drawn."""
        from mechfem import figures

        return figures.mechanism_png(self)


# The input motion and the storage live in their own modules; they are named here too.
__all__ = [
    "ATTRIBUTES",
    "BUFFER_ARGS",
    "FORMS",
    "MAX_ITER",
    "SLOTS",
    "By",
    "Combination",
    "Coordinate",
    "Driven",
    "Dynamic",
    "Element",
    "Expression",
    "FormParameter",
    "Free",
    "InputKey",
    "InputMotion",
    "Keep",
    "Mechanism",
    "Motion",
    "Output",
    "Picture",
    "Point",
    "Ref",
    "Role",
    "Row",
    "Slot",
    "Storage",
    "Table",
    "To",
    "input_dof",
]
