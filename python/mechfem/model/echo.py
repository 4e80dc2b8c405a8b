"""The model and the storage requests of a run as the deck declares them (the echo of the print file). The storage
requests are the compiled module's own objects (:class:`EchoStorage`, :class:`Buffer`, :class:`EchoPicture`,
:class:`Plot`: owned by Rust, read through their attributes, equal when they hold the same, picklable). The classes
are ``Echo*`` where a class of the model a :class:`~mechfem.Mechanism` is built of has the plain name
(:class:`~mechfem.Element`, :class:`~mechfem.Storage`, ...).

Numbers that name things (co-ordinates, elements, rows, buffers) are the deck's own, 1-based and signed.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import mechfem._core as _core
from mechfem._core import Buffer as Buffer
from mechfem._core import EchoPicture as EchoPicture
from mechfem._core import EchoStorage as EchoStorage
from mechfem._core import Plot as Plot
from mechfem.model.masses import DynamicsModel


@dataclass(frozen=True)
class EchoElement:
    """One ELEM line."""

    number: int
    type: str
    coords: list[int]
    coord_names: list[str]
    line: int
    name: str | None = None
    """Its name in the deck's NAMES block (``ELEM 1 crank``), or None."""


@dataclass(frozen=True)
class Term:
    """One FORM line: ``factor * form`` of element ``element``."""

    element: int
    form: str
    factor: float
    seq: int
    """The FORM line's sequence number."""
    line: int


@dataclass(frozen=True)
class EchoRow:
    """A prescribed row of D^c (``dest > 0``) or a dependent form parameter (``dest < 0``)."""

    dest: int
    terms: list[Term]
    para: float | None
    """The value PARA prescribes, if any."""
    input: int | None
    """The DOF whose input this row is, if it is one."""
    value: float
    """Value at position 1."""
    name: str | None = None
    """Its name in the deck's NAMES block (``ROW 6 phi``, ``DEP 1 psi``), or None."""

    def formula(self) -> str:
        """The combination, e.g. ``ANGB(2) - ANGB(4)``."""
        out = ""
        for t in self.terms:
            mag = abs(t.factor)
            text = f"{t.form}({t.element})" if mag == 1.0 else f"{mag:g}*{t.form}({t.element})"
            if not out:
                out = ("-" if t.factor < 0 else "") + text
            else:
                out += (" - " if t.factor < 0 else " + ") + text
        return out


@dataclass(frozen=True)
class EchoCoordinate:
    """One co-ordinate: fixed or moving, its given value and its value at position 1."""

    number: int
    moving: bool
    given: float
    adjusted: float
    name: str | None = None
    """Its name from the deck's NAMES block (``C.x`` for ``POINT 9 10 C``, ``s`` for ``COORD 11 s``), or None."""


@dataclass(frozen=True)
class EchoPoint:
    """A point the NAMES block names: co-ordinates ``x`` and ``y`` (1-based) are ``name.x`` and ``name.y``."""

    x: int
    y: int
    name: str


@dataclass(frozen=True)
class Model:
    """The model as compiled from the deck, for the echo in the print file."""

    elements: list[EchoElement]
    prescribed: list[EchoRow]
    dependent: list[EchoRow]
    dofs: list[int]
    """For DOF j (1-based, list index j - 1): the prescribed row that is its input."""
    coordinates: list[EchoCoordinate]
    mode: str = "KIN ANA"
    """The deck's mode line."""
    dynamics: DynamicsModel | None = None
    """The masses and loads of a DYN deck."""
    units: dict[str, str | None] = field(default_factory=dict)
    """The deck's UNITS: ``length``, ``angle``, ``mass``, ``force``, ``time`` to a symbol (``mm``, ``deg``) or None
    where the deck declares none (all None without a UNITS line; with one, ``angle`` and ``time`` default to
    ``rad`` and ``s``). Every number of a run is in these units."""
    points: list[EchoPoint] = field(default_factory=list)
    """The points the NAMES block names (``POINT 9 10 C``)."""
    labels: _core.Labels | None = field(default=None, compare=False, repr=False)
    """The names and units of its co-ordinates, rows, inputs and buffers, as the core decides them."""

    @classmethod
    def from_core(cls, d: _core.ModelDict) -> Model:
        def row(r: _core.RowDict) -> EchoRow:
            terms = [Term(t["element"], t["form"], t["factor"], t["seq"], t["line"]) for t in r["terms"]]
            return EchoRow(r["dest"], terms, r["para"], r["input"], r["value"], r["name"])

        return cls(
            elements=[
                EchoElement(e["number"], e["type"], list(e["coords"]), list(e["coord_names"]), e["line"], e["name"])
                for e in d["elements"]
            ],
            prescribed=[row(r) for r in d["prescribed"]],
            dependent=[row(r) for r in d["dependent"]],
            dofs=list(d["dofs"]),
            coordinates=[
                EchoCoordinate(c["number"], c["moving"], c["given"], c["adjusted"], c["name"]) for c in d["coordinates"]
            ],
            mode=d.get("mode", "KIN ANA"),
            dynamics=None if d.get("dynamics") is None else DynamicsModel.from_core(d["dynamics"]),  # type: ignore[arg-type]
            units=dict(d.get("units", {})),
            points=[EchoPoint(p["x"], p["y"], p["name"]) for p in d.get("points", [])],
            labels=d.get("labels"),
        )

    @property
    def n_coords(self) -> int:
        return len(self.coordinates)

    @property
    def n_moving(self) -> int:
        return sum(c.moving for c in self.coordinates)


BUFFER_ARGS: dict[str, str] = {
    "BUFINP": "j",
    "BUFTIME": "",
    "BUFX0": "i",
    "BUFKX1": "ij",
    "BUFKX2": "ijm",
    "BUFVX": "i",
    "BUFAX": "i",
    "BUFE0": "r",
    "BUFKE1": "rj",
    "BUFKE2": "rjm",
    "BUFVE": "r",
    "BUFAE": "r",
    "BUFDET": "",
    "BUFSIG": "r",
    "BUFDRV": "j",
    "BUFREA": "i",
    "BUFEKIN": "",
    "BUFEPOT": "",
    "BUFPOW": "",
    "BUFMRED": "jj",
    "BUFTRA": "ee",
    "BUFPIN": "eii",
    "BUFSHAKE": "",
}
"""The arguments of each BUF keyword before the buffer number.

``i`` a co-ordinate, ``r`` a row, ``j`` and ``m`` an input (a last ``m`` may be left out: it is then ``j``).
BUFSIG takes a prescribed row, BUFREA a fixed co-ordinate; they and the other buffers of the dynamics
(BUFDRV, BUFEKIN, BUFEPOT, BUFPOW, BUFMRED) need masses or loads on the mechanism (mode ``DYN ANA``).
``e`` is an element: BUFTRA takes two, BUFPIN an element and its point's two co-ordinates (it fills buffers b and
b+1 with x and y; BUFSHAKE fills b, b+1 and b+2 with the shaking force's x, y and moment)."""


@dataclass(frozen=True)
class ModelNames:
    """A named model's own names for the deck numbers of its run (:class:`mechfem.Mechanism`), so that labels
    (:mod:`mechfem.results.labels`) speak the model's language instead of the deck's."""

    coordinates: list[str]
    """Co-ordinate i is ``coordinates[i - 1]``, e.g. ``P.x``."""
    prescribed: list[str]
    """Prescribed row r is ``prescribed[r - 1]``."""
    dependent: list[str]
    """Dependent form parameter -k (an output) is ``dependent[k - 1]``."""
    inputs: list[str]
    """The input of DOF j is ``inputs[j - 1]``."""
