"""The masses and loads of a dynamic model (the DYNAMICS block as compiled) and how the print file says a
dynamic run's numbers: in the deck's units and with its names.

Numbers that name things are the deck's own (1-based, destinations signed).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field

from mechfem._core import EchoDynamics, EchoLoad
from mechfem.model.units import symbol

Exponents = Mapping[str, int]
"""A kind of quantity as its exponents of ``length``, ``angle``, ``mass``, ``force`` and ``time``."""


@dataclass(frozen=True)
class Said:
    """How the print file says a run's numbers: in the deck's units (its echo's ``units``, None where not
    declared), each with its unit, and a point or a row by its NAMES name."""

    units: Mapping[str, str | None] = field(default_factory=dict)
    rows: Mapping[int, Exponents] = field(default_factory=dict)
    """The kind of every row by destination (dependent form parameters negative)."""
    inputs: list[Exponents] = field(default_factory=list)
    """The kind of every input, DOF 1 first."""
    coords: Mapping[int, Exponents] = field(default_factory=dict)
    """The kind of every co-ordinate by number (a length where not given)."""
    points: Mapping[tuple[int, int], str] = field(default_factory=dict)
    """The named points by their co-ordinates ``(x, y)``."""
    row_names: Mapping[int, str] = field(default_factory=dict)
    """The named rows by destination."""

    def unit(self, exponents: Exponents, work: bool = False) -> str:
        """`` mm`` (with its space) for a quantity of that kind (``work``: force x length that is work, in joules
        where it can be), "" without a unit."""
        u = symbol(self.units, work, **exponents)
        return f" {u}" if u else ""

    def point(self, x: int, y: int) -> str:
        """``K`` for a named point, else ``(x13, y14)``."""
        return self.points.get((x, y)) or f"(x{x}, y{y})"

    def row(self, dest: int) -> str:
        """``psi`` for a named row, else ``eps(-1)``."""
        return self.row_names.get(dest) or f"eps({dest})"


def over(a: Exponents, b: Exponents) -> dict[str, int]:
    """The kind ``a / b``."""
    return {k: a.get(k, 0) - b.get(k, 0) for k in {*a, *b}}


def generalised_force(e: Exponents) -> dict[str, int]:
    """The kind of a generalised force on a quantity of kind ``e``: work over it, an angle not counted (a force
    on a length, a torque on an angle)."""
    return over({"force": 1, "length": 1}, {k: v for k, v in e.items() if k != "angle"})


LENGTH: Exponents = {"length": 1}
MASS: Exponents = {"mass": 1}
TIME: Exponents = {"time": 1}
ENERGY: Exponents = {"force": 1, "length": 1}


def dynamics_lines(d: EchoDynamics, said: Said | None = None) -> list[str]:
    """The echo of the masses and loads (the DYNAMICS block as compiled: ``EchoModel.dynamics``) in the print file,
    in the deck's units and with its names (``said``)."""
    said = said or Said()
    u = said.unit
    inertia = {"mass": 1, "length": 2}
    out = ["", "  masses and loads (DYNAMICS)"]
    if d.gravity != (0.0, 0.0):
        g = u({"length": 1, "time": -2})
        out.append(f"    GRAVITY   ({d.gravity[0]:.10g}, {d.gravity[1]:.10g}){g}")
    for b in d.bodies:
        out.append(
            f"    MASS      element {b.element}: m {b.mass:.10g}{u(MASS)}, centre (u, v) = "
            f"({b.u:.10g}, {b.v:.10g}){u(LENGTH)}, J {b.inertia:.10g}{u(inertia)}"
        )
    for p in d.point_masses:
        out.append(f"    PMASS     point {said.point(p.x, p.y)}: m {p.mass:.10g}{u(MASS)}")
    for i in d.inertias:
        lengths = 2 * (1 - said.coords.get(i.coord, LENGTH).get("length", 0))
        j = u({"mass": 1, "length": lengths})
        out.append(f"    INERTIA   co-ordinate {i.coord}: J {i.inertia:.10g}{j}")
    for f in d.forces:
        out.append(f"    FORCE     point {said.point(f.x, f.y)}: ({f.fx:.10g}, {f.fy:.10g}){u({'force': 1})}")
    for ld in d.loads:
        out.append(f"    {ld.kind:<9} {said.row(ld.dest)}: {_load_text(ld, said, said.rows.get(ld.dest, {}))}")
    return out


def _load_text(ld: EchoLoad, said: Said, e: Exponents) -> str:
    """A load's numbers with their units: ``e`` is the kind of the row it acts on."""
    q = generalised_force(e)
    u = said.unit
    match ld.kind:
        case "LOAD":
            return f"constant {ld.value:.10g}{u(q)}"
        case "LOADFUNC":
            return f"table of {len(ld.rows)} rows, linear in time"
        case "SPRING":
            k = over(q, e)
            c = over(k, over({}, TIME))
            return f"stiffness {ld.k:.10g}{u(k)}, free value {ld.e0:.10g}{u(e)}, damping {ld.c:.10g}{u(c)}"
        case _:
            return f"stall torque {ld.t0:.10g}{u(q)}, no-load speed {ld.w0:.10g}{u(over(e, TIME))}"
