"""The element methods of a :class:`~mechfem.Mechanism`: one per element type of the catalogue (``bar``,
``half_beam``, ...) and :meth:`~ElementMethods.element` for any type by its deck name, with the checks of the
points and co-ordinates they are given (objects of the mechanism, or their names)."""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from typing import TYPE_CHECKING, Any, Literal, TypeAlias

from mechfem.model.catalogue import FORMS, SLOTS
from mechfem.model.parts import (
    ATTRIBUTES,
    Coordinate,
    Element,
    FormParameter,
    Point,
    Role,
    Row,
    Slot,
    role_row,
    unknown_form,
)
from mechfem.model.units import Units

PointArg: TypeAlias = Point | str
"""A point given to an element method: the point, or its name."""

CoordinateArg: TypeAlias = Coordinate | float | str
"""A co-ordinate given to an element method: the co-ordinate, its name, or a number for a new one."""


class ElementMethods:
    """The element methods :class:`~mechfem.Mechanism` inherits; they add elements (and the rows their roles make)
    to its names, ``elements`` and ``rows``."""

    _names: dict[str, object]
    elements: list[Element]
    rows: list[Row]
    units: Units

    if TYPE_CHECKING:

        def find(
            self, name: object, what: str = "", accept: Callable[[object], bool] | None = None, kinds: str | None = None
        ) -> Any: ...

        def _own(self, obj: Slot) -> Slot: ...

        def _check_free(self, name: str, kind: type | None = None) -> None: ...

        def _claim(self, name: str, obj: object) -> None: ...

        def angle(self, name: str, value: float = 0.0, *, fixed: bool = False) -> Coordinate: ...

        def scalar(self, name: str, value: float, *, fixed: bool = True) -> Coordinate: ...

    def _slot(self, element: str, what: str, obj: Slot | float | str, kind: Literal["angle", "scalar"]) -> Coordinate:
        if isinstance(obj, str):
            obj = self.find(obj, "co-ordinate", lambda o: isinstance(o, Coordinate))
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
        if isinstance(obj, str):
            obj = self.find(obj, "point", lambda o: isinstance(o, Point))
        if not isinstance(obj, Point):
            raise TypeError(f"element {element!r}: {what} must be a point, got {obj!r}")
        p = self._own(obj)
        assert isinstance(p, Point)
        return p

    # -- elements

    def _element(self, name: str, type: str, slots: Sequence[Slot], roles: Mapping[str, Role]) -> Element:
        self._check_free(name, Element)
        e = Element(name, type, slots)
        angle = self.units.angle
        rows = [role_row(FormParameter(e, f), roles.get(f), angle) for f in FORMS[type]]
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

    def bar(self, name: str, p: PointArg, q: PointArg, *, length: Role = None, angle: Role = None) -> Element:
        """A binary element (BIN) from ``p`` to ``q``: ``length`` |PQ| and ``angle`` the direction P->Q."""
        return self._element(
            name, "BIN", [self._pt(name, "p", p), self._pt(name, "q", q)], {"LENL": length, "ANGB": angle}
        )

    def half_beam(self, name: str, p: PointArg, beta: CoordinateArg, *, angle: Role = None) -> Element:
        """A half beam (HLF): point ``p`` with the angle co-ordinate ``beta`` (a number makes a moving one)."""
        return self._element(
            name, "HLF", [self._pt(name, "p", p), self._slot(name, "beta", beta, "angle")], {"ANGV": angle}
        )

    def ternary1(
        self,
        name: str,
        p: PointArg,
        beta: CoordinateArg,
        r: PointArg,
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
        p: PointArg,
        q: PointArg,
        r: PointArg,
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
        a: CoordinateArg,
        b: CoordinateArg,
        c: CoordinateArg,
        *,
        ratio: CoordinateArg | None = None,
        radii: tuple[CoordinateArg, CoordinateArg] | None = None,
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
        p: PointArg,
        beta_b: CoordinateArg,
        q: PointArg,
        ratio: CoordinateArg,
        beta_a: CoordinateArg,
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
        p: PointArg,
        q: PointArg,
        r: PointArg,
        ratio: CoordinateArg,
        beta_a: CoordinateArg,
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
        p: PointArg,
        beta_a: CoordinateArg,
        q: PointArg,
        beta_c: CoordinateArg,
        r_p: CoordinateArg,
        r_q: CoordinateArg,
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

    def single_coordinate(self, name: str, coordinate: Coordinate | str, *, value: Role = None) -> Element:
        """A single-co-ordinate element (CRD) on ``coordinate`` (e.g. a slider's ``B.x``), to prescribe or drive it."""
        return self._element(name, "CRD", [self._slot(name, "x", coordinate, "scalar")], {"COOR": value})

    def element(self, name: str, type: str, slots: Sequence[Slot | str], **roles: Role) -> Element:
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
                raise TypeError(unknown_form(Element(name, ty, checked), key))
            by_form[matches[0]] = role
        return self._element(name, ty, checked, by_form)
