"""Masses and loads of a :class:`~mechfem.Mechanism`: what makes its deck a ``DYN ANA`` one (inverse dynamics), or a
``DYN SIM`` one when an input moves under the forces (a simulation, :meth:`~mechfem.Mechanism.simulate`).

Each mass or load is a small frozen dataclass that holds the model's own objects (an element, a point,
a co-ordinate, a row); :class:`Loads` keeps them in the order they were given, which is the order of
the DYNAMICS block written for the mechanism (keywords in ``docs/deck.md``, mechanics in
``dynamics.md``). The ``add_*`` functions check what the :class:`~mechfem.Mechanism` methods
(:meth:`~mechfem.Mechanism.mass`, ...) are given, with the model's names in every message;
:func:`mode` chooses the deck's mode line, :func:`deck_lines` writes the block and :func:`read` reads a deck's
block back into a mechanism.

A generalised force acts on a row: a prescribed row or an input (its drive then delivers the rest) or
an output (a dependent form parameter, e.g. a slider's position), named as everywhere in the API: by
name, by the row itself, or by a form parameter (or combination) that a row holds alone.
"""

from __future__ import annotations

from collections.abc import Iterator, MutableMapping, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Protocol, TypeAlias, TypeVar

import numpy as np
import numpy.typing as npt

from mechfem._util.checks import finite
from mechfem.model.catalogue import FRAMES
from mechfem.model.parts import ELEMENT_WORDS, Combination, Coordinate, Element, Expression, FormParameter, Point, Row

if TYPE_CHECKING:
    from mechfem.deck.naming import Numbering


class MechanismLoads(Protocol):
    """What the loads need of a :class:`~mechfem.Mechanism` (which sits above them: it offers the loads as methods)."""

    name: str
    rows: list[Row]
    loads: Loads | None

    def __getitem__(self, name: str) -> Any: ...

    def __contains__(self, name: object) -> bool: ...

    def _terms(self, expr: Expression) -> tuple[tuple[float, FormParameter], ...]: ...


FloatArray = npt.NDArray[np.float64]

# --- the masses and loads ---------------------------------------------------------------------------------------------


@dataclass(frozen=True, eq=False)
class Body:
    """A rigid body on an element (MASS): ``mass`` with its centre at ``(u, v)`` in the element's frame and the
    moment of inertia ``inertia`` about that centre."""

    element: Element
    mass: float
    u: float = 0.0
    v: float = 0.0
    inertia: float = 0.0


@dataclass(frozen=True, eq=False)
class PointMass:
    """A point mass (PMASS) at the point whose co-ordinates are ``x`` and ``y``."""

    x: Coordinate
    y: Coordinate
    mass: float


@dataclass(frozen=True, eq=False)
class Inertia:
    """A rotational inertia (INERTIA) on a co-ordinate, usually a wheel's angle."""

    coordinate: Coordinate
    inertia: float


@dataclass(frozen=True)
class Gravity:
    """The acceleration of gravity (GRAVITY), e.g. ``Gravity(0, -9.81)``."""

    gx: float
    gy: float


@dataclass(frozen=True, eq=False)
class Force:
    """A constant force (FORCE) ``(fx, fy)`` at the point whose co-ordinates are ``x`` and ``y``."""

    x: Coordinate
    y: Coordinate
    fx: float
    fy: float


@dataclass(frozen=True, eq=False)
class Load:
    """A constant generalised force (LOAD) on a row: a torque on an angle, a force along a length."""

    row: Row
    value: float


@dataclass(frozen=True, eq=False)
class LoadTable:
    """A generalised force on a row given at times ``time`` (LOADFUNC), linear between them and constant outside.

    ``file`` names the file a deck written for the mechanism uses for it (default ``<mechanism>_load<k>.dat``).
    """

    row: Row
    time: FloatArray
    values: FloatArray
    file: str | None = None


@dataclass(frozen=True, eq=False)
class Spring:
    """A spring (SPRING) on a row: ``-stiffness (eps - free_value) - damping d(eps)/dt``."""

    row: Row
    stiffness: float
    free_value: float
    damping: float = 0.0


@dataclass(frozen=True, eq=False)
class Motor:
    """A motor (MOTOR) on a row: ``stall_torque (1 - d(eps)/dt / no_load_speed)``."""

    row: Row
    stall_torque: float
    no_load_speed: float


Item: TypeAlias = Body | PointMass | Inertia | Gravity | Force | Load | LoadTable | Spring | Motor
"""One line of the DYNAMICS block."""

_I = TypeVar("_I", bound=Item)


@dataclass
class Loads:
    """The masses and loads of a mechanism, in the order they were given (the order of its DYNAMICS block)."""

    items: list[Item] = field(default_factory=list)

    @property
    def gravity(self) -> tuple[float, float] | None:
        """``(gx, gy)``, or None when no gravity was given."""
        g = [i for i in self.items if isinstance(i, Gravity)]
        return (g[0].gx, g[0].gy) if g else None

    def of(self, kind: type[_I]) -> list[_I]:
        """The items of one kind, e.g. ``m.loads.of(Body)``."""
        return [i for i in self.items if isinstance(i, kind)]

    def in_deck_order(self) -> list[Item]:
        """The items in the order the deck reader keeps them: bodies, point masses, inertias, gravity, forces,
        then the loads on form parameters (each kind in the order given)."""
        rank = (Body, PointMass, Inertia, Gravity, Force)
        return sorted(self.items, key=lambda it: next((k for k, t in enumerate(rank) if isinstance(it, t)), 5))

    def __len__(self) -> int:
        return len(self.items)

    def __iter__(self) -> Iterator[Item]:
        return iter(self.items)


def _add(mech: MechanismLoads, item: _I) -> _I:
    """Adds ``item`` to the mechanism's masses and loads (a gravity replaces the one given before)."""
    if mech.loads is None:
        mech.loads = Loads()
    items = mech.loads.items
    if isinstance(item, Gravity):
        for k, old in enumerate(items):
            if isinstance(old, Gravity):
                items[k] = item
                return item
    items.append(item)
    return item


# --- checks, with the model's names -----------------------------------------------------------------------------------


def _not_negative(value: float, what: str, hint: str) -> float:
    v = finite(value, what)
    if v < 0:
        raise ValueError(f"{what} must not be negative, got {v!r}: {hint}")
    return v


_KINDS: dict[type, str] = {Element: "an element", Point: "a point", Coordinate: "a co-ordinate", Row: "a row"}


def _owned(mech: MechanismLoads, ref: object, kind: type, what: str) -> object:
    """``ref`` (a name or the object) when it is a ``kind`` of ``mech``."""
    obj = mech[ref] if isinstance(ref, str) else ref
    if not isinstance(obj, kind):
        raise TypeError(f"{what} must be {_KINDS[kind]} of the mechanism {mech.name!r}, got {obj!r}")
    name = getattr(obj, "name", None)
    if not isinstance(name, str) or name not in mech or mech[name] is not obj:
        raise ValueError(f"{what}: {obj!r} belongs to another mechanism")
    return obj


def _element(mech: MechanismLoads, ref: Element | str, what: str) -> Element:
    e = _owned(mech, ref, Element, what)
    assert isinstance(e, Element)
    return e


def _coordinate(mech: MechanismLoads, ref: Coordinate | str, what: str) -> Coordinate:
    c = _owned(mech, ref, Coordinate, what)
    assert isinstance(c, Coordinate)
    return c


PointRef: TypeAlias = Point | str | tuple[Coordinate | str, Coordinate | str]
"""A point by name or itself, or two co-ordinates ``(x, y)`` that act as one."""


def _point(mech: MechanismLoads, ref: PointRef, what: str) -> tuple[Coordinate, Coordinate]:
    if isinstance(ref, tuple):
        if len(ref) != 2:
            raise TypeError(f"{what} must be a point or two co-ordinates (x, y), got {ref!r}")
        return _coordinate(mech, ref[0], what), _coordinate(mech, ref[1], what)
    p = _owned(mech, ref, Point, what)
    assert isinstance(p, Point)
    return p.x, p.y


RowRef: TypeAlias = Row | FormParameter | Combination | str
"""A prescribed row, an input or an output: by name, itself, or the form parameter (combination) it holds."""


def find_row(mech: MechanismLoads, ref: RowRef, what: str) -> Row:
    """The row ``ref`` names: a row or output by name or itself, or the row that holds a form parameter or a
    combination alone."""
    obj = mech[ref] if isinstance(ref, str) else ref
    if isinstance(obj, Row):
        _owned(mech, obj, Row, what)
        return obj
    if isinstance(obj, FormParameter | Combination):
        terms = mech._terms(obj)
        for r in mech.rows:
            if r.terms == terms:
                return r
        raise ValueError(
            f"{what}: {obj.formula()} is neither prescribed nor an output, so nothing can carry a load on it: "
            "make it an output with Mechanism.output() (or prescribe or drive it) first"
        )
    raise TypeError(f"{what} must be a row, an output or a form parameter of the mechanism {mech.name!r}, got {obj!r}")


def _frame(e: Element) -> None:
    if e.type in FRAMES:
        return
    if e.type == "CRD":
        raise ValueError(
            f"element {e.name!r} is a single co-ordinate element, which has no frame to carry a mass: it only "
            "constrains a co-ordinate; "
            "put a mass at a point with point_mass(), or a body on a bar, half beam or ternary element with mass()"
        )
    angles = ", ".join(repr(s.name) for s in e.slots if isinstance(s, Coordinate) and s.kind == "angle")
    raise ValueError(
        f"element {e.name!r} is a {ELEMENT_WORDS.get(e.type, e.type)}, which has no frame to carry a mass: it "
        "only couples wheels; put the wheel's mass on its half beam or ternary-1 element with mass(), or its "
        f"inertia on its angle co-ordinate with inertia() (the angles of {e.name!r}: {angles})"
    )


# --- the Mechanism methods --------------------------------------------------------------------------------------------


def add_mass(mech: MechanismLoads, element: Element | str, m: float, u: float, v: float, J: float) -> Body:
    """See :meth:`Mechanism.mass`."""
    e = _element(mech, element, "mass()")
    _frame(e)
    mass = _not_negative(m, f"the mass of {e.name!r}", "give the body's mass, 0 or more")
    inertia = _not_negative(J, f"the moment of inertia J of {e.name!r}", "give it about the centre of mass, 0 or more")
    return _add(
        mech,
        Body(e, mass, finite(u, f"u of the mass of {e.name!r}"), finite(v, f"v of the mass of {e.name!r}"), inertia),
    )


def add_point_mass(mech: MechanismLoads, point: PointRef, m: float) -> PointMass:
    """See :meth:`Mechanism.point_mass`."""
    x, y = _point(mech, point, "point_mass()")
    mass = _not_negative(m, f"the mass at {_label(x, y)!r}", "give the point's mass, 0 or more")
    return _add(mech, PointMass(x, y, mass))


def add_inertia(mech: MechanismLoads, coordinate: Coordinate | str, J: float) -> Inertia:
    """See :meth:`Mechanism.inertia`."""
    c = _coordinate(mech, coordinate, "inertia()")
    return _add(
        mech, Inertia(c, _not_negative(J, f"the inertia on {c.name!r}", "give it about the angle's axis, 0 or more"))
    )


def add_gravity(mech: MechanismLoads, gx: float, gy: float) -> Gravity:
    """See :meth:`Mechanism.gravity`."""
    return _add(mech, Gravity(finite(gx, "gravity gx"), finite(gy, "gravity gy")))


def add_force(mech: MechanismLoads, point: PointRef, fx: float, fy: float) -> Force:
    """See :meth:`Mechanism.force`."""
    x, y = _point(mech, point, "force()")
    where = _label(x, y)
    return _add(
        mech, Force(x, y, finite(fx, f"fx of the force at {where!r}"), finite(fy, f"fy of the force at {where!r}"))
    )


def add_load(mech: MechanismLoads, row: RowRef, value: float) -> Load:
    """See :meth:`Mechanism.load`."""
    r = find_row(mech, row, "load()")
    return _add(mech, Load(r, finite(value, f"the load on {r.name!r}")))


def add_load_table(
    mech: MechanismLoads, row: RowRef, time: npt.ArrayLike, values: npt.ArrayLike, file: str | None
) -> LoadTable:
    """See :meth:`Mechanism.load_table`."""
    r = find_row(mech, row, "load_table()")
    t = np.array(time, dtype=np.float64, ndmin=1)
    q = np.array(values, dtype=np.float64, ndmin=1)
    what = f"the load table on {r.name!r}"
    if t.ndim != 1 or q.shape != t.shape or t.size == 0:
        raise ValueError(f"{what} needs as many values as times, at least one, got {q.shape} and {t.shape}")
    if not (np.isfinite(t).all() and np.isfinite(q).all()):
        raise ValueError(f"{what} must hold finite numbers only")
    if (np.diff(t) < 0).any():
        k = int(np.argmax(np.diff(t) < 0))
        raise ValueError(
            f"{what}: the time {float(t[k + 1])!r} comes before the time {float(t[k])!r}; give the times in order"
        )
    if file is not None and (not file or any(ch.isspace() or ch == ";" for ch in file)):
        raise ValueError(f"{what}: the file name of a load table cannot be empty or hold blanks or ';': {file!r}")
    return _add(mech, LoadTable(r, t, q, file))


def add_spring(mech: MechanismLoads, row: RowRef, k: float, free_value: float, damping: float) -> Spring:
    """See :meth:`Mechanism.spring`."""
    r = find_row(mech, row, "spring()")
    stiffness = _not_negative(k, f"the stiffness of the spring on {r.name!r}", "it pulls the row to its free value")
    c = _not_negative(damping, f"the damping of the spring on {r.name!r}", "a damper works against the motion")
    return _add(mech, Spring(r, stiffness, finite(free_value, f"the free value of the spring on {r.name!r}"), c))


def add_motor(mech: MechanismLoads, row: RowRef, stall_torque: float, no_load_speed: float) -> Motor:
    """See :meth:`Mechanism.motor`."""
    r = find_row(mech, row, "motor()")
    t0 = finite(stall_torque, f"the stall torque of the motor on {r.name!r}")
    w0 = finite(no_load_speed, f"the no-load speed of the motor on {r.name!r}")
    if w0 == 0:
        raise ValueError(
            f"the no-load speed of the motor on {r.name!r} must not be 0: its torque falls to zero at that speed "
            "(negative for a motor that runs backwards)"
        )
    return _add(mech, Motor(r, t0, w0))


def _label(x: Coordinate, y: Coordinate) -> str:
    return x.point.name if x.point is not None and x.point is y.point else f"({x.name}, {y.name})"


# --- the DYNAMICS block of a deck -------------------------------------------------------------------------------------


Line: TypeAlias = tuple[str, tuple[str, str], str]
"""A deck line: its text, what it declares (for messages) and its comment."""


def _n(v: float) -> str:
    return repr(float(v))


def mode(mech: MechanismLoads, simulated: Sequence[str]) -> str:
    """The deck's mode line: ``KIN ANA`` without masses and loads, ``DYN SIM`` when the inputs ``simulated`` move
    under the forces (MOV_DYN), else ``DYN ANA``."""
    if mech.loads is None and simulated:
        raise ValueError(
            f"the motion lets {', '.join(map(repr, simulated))} of the mechanism {mech.name!r} move under the forces "
            "(Dynamic), but the mechanism has no masses or loads to move it: give them with Mechanism.mass, "
            "point_mass, inertia, gravity, force, load, spring or motor"
        )
    return "KIN ANA" if mech.loads is None else "DYN SIM" if simulated else "DYN ANA"


def table_text(item: LoadTable) -> str:
    """The LOADFUNC file of a load table: rows ``t value``."""
    head = f"# load on {item.row.name}: t value, one row per time\n"
    return head + "".join(f"{_n(t)} {_n(q)}\n" for t, q in zip(item.time, item.values, strict=True))


def deck_lines(loads: Loads, nb: Numbering, stem: str, tables: MutableMapping[str, str]) -> list[Line]:
    """The lines of the DYNAMICS block (without its header); the files of load tables go into ``tables``."""
    element = {e: k for k, e in enumerate(nb.elements, 1)}
    i = nb.coord_number
    out: list[Line] = []
    n_tables = 0
    for it in loads.in_deck_order():
        if isinstance(it, Body):
            e = it.element
            out.append(
                (f"MASS {element[e]} {_n(it.mass)} {_n(it.u)} {_n(it.v)} {_n(it.inertia)}", ("mass", e.name), e.name)
            )
        elif isinstance(it, PointMass):
            where = _label(it.x, it.y)
            out.append((f"PMASS {i[it.x]} {i[it.y]} {_n(it.mass)}", ("point mass", where), where))
        elif isinstance(it, Inertia):
            name = it.coordinate.name
            out.append((f"INERTIA {i[it.coordinate]} {_n(it.inertia)}", ("inertia", name), name))
        elif isinstance(it, Gravity):
            out.append((f"GRAVITY {_n(it.gx)} {_n(it.gy)}", ("gravity", ""), "gravity"))
        elif isinstance(it, Force):
            where = _label(it.x, it.y)
            out.append((f"FORCE {i[it.x]} {i[it.y]} {_n(it.fx)} {_n(it.fy)}", ("force", where), where))
        else:
            r = nb.row_dest[it.row]
            note = ("load", it.row.name)
            if isinstance(it, Load):
                out.append((f"LOAD {r} {_n(it.value)}", note, it.row.name))
            elif isinstance(it, LoadTable):
                n_tables += 1
                file = it.file or f"{stem}_load{n_tables}.dat"
                add_table(tables, file, table_text(it))
                out.append((f"LOADFUNC {r} {file}", note, it.row.name))
            elif isinstance(it, Spring):
                out.append((f"SPRING {r} {_n(it.stiffness)} {_n(it.free_value)} {_n(it.damping)}", note, it.row.name))
            else:
                out.append((f"MOTOR {r} {_n(it.stall_torque)} {_n(it.no_load_speed)}", note, it.row.name))
    return out


def add_table(tables: MutableMapping[str, str], file: str, text: str) -> None:
    """Adds the file ``file`` of a table motion or load; two different tables under one name are refused."""
    if tables.get(file, text) != text:
        raise ValueError(f"two different tables would be written to the one file {file!r}: give them other names")
    tables[file] = text


__all__ = [
    "Body",
    "Force",
    "Gravity",
    "Inertia",
    "Item",
    "Load",
    "Loads",
    "LoadTable",
    "Motor",
    "PointMass",
    "Spring",
    "deck_lines",
    "find_row",
    "mode",
]
