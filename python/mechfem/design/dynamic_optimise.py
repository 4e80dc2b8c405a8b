""":func:`mechfem.optimize` of a dynamic mechanism (one with masses and loads): the mass model's numbers as design
variables by name, the results of inverse dynamics as quantities, and the model evaluated by
``ModelBuilder.dynamic_design`` (the same engine as the OPTIMISE block of a DYN ANA deck).

Variable names, beside those of :meth:`Mechanism.set`:

* ``"crank.mass"``, ``"crank.mass_u"``, ``"crank.mass_v"``, ``"crank.mass_J"``: the mass, centre of mass (u, v) in
  the element's frame and moment of inertia of the body on element ``crank`` (:meth:`Mechanism.mass`);
* ``"B.mass"``: the point mass at point ``B`` (:meth:`Mechanism.point_mass`);
* ``"wheel.inertia"``: the rotational inertia on co-ordinate ``wheel`` (:meth:`Mechanism.inertia`).

Quantities: :class:`Drive` (the drive torque or force of an input), :class:`Shaking` (a component of the shaking
force or moment) and :class:`ShakingForce` (the magnitude of the shaking force, for ``minimize=("rms",
ShakingForce())`` or ``("maxabs", ShakingForce())``).
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Literal

from mechfem.model.loads import Body, Inertia, PointMass

if TYPE_CHECKING:
    from mechfem.deck import deckio
    from mechfem.design.engine import DesignModelOf
    from mechfem.model.mechanism import Mechanism

BODY_FIELDS = {"mass": (10, "mass"), "mass_u": (11, "u"), "mass_v": (12, "v"), "mass_J": (13, "inertia")}
"""A body's variable name suffix: its variable kind and the field of :class:`~mechfem.model.loads.Body`."""


@dataclass(frozen=True)
class Drive:
    """The drive torque or force of the input ``input`` (a row name), BUFDRV."""

    input: str


@dataclass(frozen=True)
class Shaking:
    """A component of the shaking force (``"x"``, ``"y"``) or the shaking moment (``"moment"``), BUFSHAKE."""

    component: Literal["x", "y", "moment"]


@dataclass(frozen=True)
class ShakingForce:
    """The magnitude of the shaking force, sqrt(x^2 + y^2), as an objective's quantity."""


DynamicQuantity = Drive | Shaking | ShakingForce


def _item(mech: Mechanism, name: str) -> tuple[Any, int, str] | None:
    """The mass or inertia item ``name`` names, its variable kind and field; None for a name of no such item."""
    owner, _, what = name.rpartition(".")
    if mech.loads is None or not owner or what not in (*BODY_FIELDS, "inertia"):
        return None
    try:
        obj = mech[owner]
    except KeyError:
        return None
    for item in mech.loads.items:
        if what in BODY_FIELDS and isinstance(item, Body) and item.element is obj:
            return item, *BODY_FIELDS[what]
        if what == "mass" and isinstance(item, PointMass) and getattr(obj, "x", None) is item.x:
            return item, 14, "mass"
        if what == "inertia" and isinstance(item, Inertia) and item.coordinate is obj:
            return item, 15, "inertia"
    return None


def variable_named(mech: Mechanism, name: str) -> bool:
    """Whether ``name`` names a number of the mass model."""
    return _item(mech, name) is not None


def variable(mech: Mechanism, numbering: deckio.Numbering, name: str) -> tuple[int, int, float] | None:
    """``(kind, deck number, start value)`` of a variable of the mass model; None when ``name`` names none."""
    found = _item(mech, name)
    if found is None:
        return None
    item, kind, field = found
    if isinstance(item, Body):
        number = numbering.elements.index(item.element) + 1
    else:
        number = numbering.coord_number[item.x if isinstance(item, PointMass) else item.coordinate]
    return kind, number, float(getattr(item, field))


def inertia_coordinate(mech: Mechanism, name: str) -> Any:
    """The co-ordinate an inertia variable ``name`` (``"wheel.inertia"``) sits on; None for any other name."""
    found = _item(mech, name)
    return found[0].coordinate if found is not None and isinstance(found[0], Inertia) else None


def is_mass(kind: int) -> bool:
    return kind >= 10


def apply(mech: Mechanism, name: str, value: float) -> bool:
    """Sets the mass variable ``name`` of ``mech`` to ``value``; False when ``name`` names none."""
    found = _item(mech, name)
    if found is None or mech.loads is None:
        return False
    item, _, field = found
    items = mech.loads.items
    items[items.index(item)] = dataclasses.replace(item, **{field: value})
    return True


def buffer(numbered: Any, q: DynamicQuantity) -> int:
    """The buffer of ``q`` in the optimiser's storage (``numbered(key, keyword, *args)`` numbers a buffer): a
    BUFSHAKE line fills three numbers, its x, y and moment."""
    if isinstance(q, Drive):
        number: int = numbered(("BUFDRV", (q.input,)), "BUFDRV", q.input)
        return number
    first: int = numbered(("BUFSHAKE", ()), "BUFSHAKE")
    # The y and the moment take the next two numbers: held by keys of their own.
    numbered(("BUFSHAKE+1", ()), None)
    numbered(("BUFSHAKE+2", ()), None)
    if isinstance(q, ShakingForce):
        return first
    return first + ("x", "y", "moment").index(q.component)


def recorded(keys: Any) -> bool:
    """Whether the optimiser's buffers (keys ``(keyword, args)``) hold a result of inverse dynamics."""
    return any(k[0] in ("BUFDRV", "BUFSHAKE") for k in keys)


def model(builder: Any, base: str) -> DesignModelOf:
    """The design model of a built dynamic mechanism (table files in ``base``)."""

    def of(variables: list[tuple[int, int]], buffers: list[int], extrema: list[tuple[int, int]]) -> Any:
        return builder.dynamic_design(base, variables, buffers, extrema)

    return of
