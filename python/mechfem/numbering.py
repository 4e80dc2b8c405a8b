"""How a written deck numbers a model (co-ordinates, elements, rows, inputs) and the written deck itself.

Below the deck writer (:mod:`mechfem.deckio`) so that the loads, the error messages in the model's words and the run
can read the numbering without importing the writer.
"""

from __future__ import annotations

import re
from collections.abc import Iterable
from dataclasses import dataclass, field

from mechfem.motion import InputKey, input_dof
from mechfem.parts import Coordinate, Element, Point, Row


def number(v: float) -> str:
    """A float as deck text that reads back as exactly the same double."""
    return repr(float(v))


@dataclass
class Numbering:
    """How a written deck numbers the model: co-ordinates, elements, rows and inputs."""

    coords: list[Coordinate]
    """Co-ordinate number i is ``coords[i - 1]``."""
    elements: list[Element]
    """Element number k is ``elements[k - 1]``."""
    prescribed: list[Row]
    """Prescribed row r is ``prescribed[r - 1]``; the last ``n_dof`` are the inputs, in DOF order."""
    dependent: list[Row]
    """Dependent form parameter -k (an output) is ``dependent[k - 1]``."""
    coord_number: dict[Coordinate, int] = field(default_factory=dict)
    row_dest: dict[Row, int] = field(default_factory=dict)

    def __post_init__(self) -> None:
        self.coord_number = {c: i for i, c in enumerate(self.coords, 1)}
        self.row_dest = {r: k for k, r in enumerate(self.prescribed, 1)}
        self.row_dest.update({r: -k for k, r in enumerate(self.dependent, 1)})

    @property
    def inputs(self) -> list[Row]:
        """The input rows in DOF order."""
        return [r for r in self.prescribed if r.kind == "input"]

    @property
    def rows(self) -> list[Row]:
        """Prescribed rows, then outputs: the row order of the results."""
        return self.prescribed + self.dependent

    def dof(self, key: InputKey) -> int:
        """The DOF number (1-based) of an input given by name, DOF number, row or form parameter (None: the only
        input)."""
        return input_dof(key, self.inputs)


@dataclass
class DeckText:
    """A written deck: its text, what each line declares, the numbering and the files of its table motions."""

    text: str
    path: str
    """The name diagnostics show."""
    notes: dict[int, tuple[str, str]]
    """Line -> (what, name), e.g. ``(element, crank)``."""
    numbering: Numbering
    tables: dict[str, str]
    """MOV_FUNC file name -> its text."""
    simulated: list[str] = field(default_factory=list)
    """The inputs that move under the forces (MOV_DYN)."""


_DECK_NAME = re.compile(r"[A-Za-z_][A-Za-z0-9_]{0,39}")
"""A name a deck's NAMES block can hold; others (``coupler.length``) stay the Python model's own."""


def deck_names(points: Iterable[Point], nb: Numbering) -> list[tuple[str, list[int], str]]:
    """The names of a model numbered ``nb`` that its core model carries, as the lines of its deck's NAMES block
    (kind, deck numbers, name): its ``points`` (their co-ordinates ``A.x``, ``A.y`` named by them), the other
    co-ordinates, elements, prescribed rows (``ROW``) and outputs (``DEP``), each whose name a deck can hold."""
    coord = nb.coord_number
    out: list[tuple[str, list[int], str]] = []
    in_point: set[Coordinate] = set()
    for p in points:
        if p.x in coord and p.y in coord and _DECK_NAME.fullmatch(p.name):
            out.append(("POINT", [coord[p.x], coord[p.y]], p.name))
            in_point.update((p.x, p.y))
    for i, c in enumerate(nb.coords, 1):
        if c not in in_point and _DECK_NAME.fullmatch(c.name):
            out.append(("COORD", [i], c.name))
    out += [("ELEM", [k], e.name) for k, e in enumerate(nb.elements, 1) if _DECK_NAME.fullmatch(e.name)]
    for r in nb.rows:
        if _DECK_NAME.fullmatch(r.name):
            dest = nb.row_dest[r]
            out.append(("ROW", [dest], r.name) if dest > 0 else ("DEP", [-dest], r.name))
    return out
