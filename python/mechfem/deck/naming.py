"""How a written deck numbers a model and names it.

The numbering (:class:`Numbering`, :func:`number`): the deck numbers of a model's co-ordinates, elements, rows and
inputs, and the written deck itself (:class:`DeckText`). It sits below the deck writer (:mod:`mechfem.deck.deckio`)
so that the loads, the error messages in the model's words and the run read it without importing the writer.

The names and units: the ``NAMES`` block and the ``UNITS`` line the deck writer puts in (:func:`names_block`), a
motion's values in the model's units (:func:`model_unit`), and the names a deck declares, by deck number, for the
deck reader's mechanism (:class:`DeckNames`).

A deck name is ``[A-Za-z_][A-Za-z0-9_]*`` of at most :data:`MAX_NAME` characters (docs/deck.md, NAMES). A point's
co-ordinates ``A.x`` and ``A.y`` are named by its ``POINT`` line, an element's own row (``crank.angle``) by its
element's ``ELEM`` line; a name the deck language cannot hold (a blank or a dot in it) stays out of the block, and
so does a name the deck reader gives a thing by its number anyway (``P5``, ``x7``, ``E1``, ``row6``, ``out1``).
"""

from __future__ import annotations

import dataclasses
import re
from collections.abc import Iterator, Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from mechfem.model.echo import Model
from mechfem.model.mechanism import By, Dynamic, InputMotion, Mechanism, Table, To
from mechfem.model.motion import InputKey, input_dof
from mechfem.model.parts import Coordinate, Element, Row
from mechfem.model.units import angle_in


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


#: The longest name a deck's NAMES block takes.
MAX_NAME = 40

_NAME = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")


def deck_name(name: str) -> bool:
    """Whether ``name`` can stand in a deck's NAMES block."""
    return len(name) <= MAX_NAME and _NAME.fullmatch(name) is not None


def names_block(mech: Mechanism, nb: Numbering) -> Iterator[tuple[str, tuple[str, str]]]:
    """The lines of the NAMES block of ``mech`` numbered by ``nb`` (none when nothing has a deck name), each with
    the note of what it declares."""
    lines: list[tuple[str, tuple[str, str]]] = []
    numbered = nb.coord_number
    in_point: set[object] = set()
    # Points in the order of their x co-ordinate's number, as a deck read back has them.
    for p in sorted((p for p in mech.points if p.x in numbered), key=lambda p: numbered[p.x]):
        if p.x in numbered and p.y in numbered and deck_name(p.name) and p.name != f"P{numbered[p.x]}":
            lines.append((f"POINT {numbered[p.x]} {numbered[p.y]} {p.name}", ("point", p.name)))
            in_point.update((p.x, p.y))
    for i, c in enumerate(nb.coords, 1):
        if c not in in_point and deck_name(c.name) and c.name != f"x{i}":
            lines.append((f"COORD {i} {c.name}", ("co-ordinate", c.name)))
    for k, e in enumerate(nb.elements, 1):
        if deck_name(e.name) and e.name != f"E{k}":
            lines.append((f"ELEM {k} {e.name}", ("element", e.name)))
    for r in nb.rows:
        if _own_row(r) or not deck_name(r.name):
            continue
        dest = nb.row_dest[r]
        keyword, number = ("ROW", dest) if dest > 0 else ("DEP", -dest)
        if r.name == f"{'row' if dest > 0 else 'out'}{number}":
            continue
        lines.append((f"{keyword} {number} {r.name}", (r.kind, r.name)))
    if lines:
        yield "NAMES", ("names", mech.name)
        yield from lines


def _own_row(r: Row) -> bool:
    """Whether ``r`` is named as its element's own row (``crank.angle``), a name its element's name gives back."""
    return len(r.terms) == 1 and r.terms[0][0] == 1.0 and r.name == r.terms[0][1].label


def model_unit(im: InputMotion, row: Row, angle: str) -> InputMotion:
    """The motion ``im`` of the input ``row`` with its values in the model's units (``angle``: the model's angle
    unit): a motion of an angle given in a unit of its own (``unit="deg"``) converted, any other as it is."""
    unit = getattr(im, "unit", None)
    if unit is None or not row.is_angle:
        return im
    if isinstance(im, By):
        return By(angle_in(im.delta, unit, angle))
    if isinstance(im, To):
        return To(angle_in(im.end, unit, angle))
    if isinstance(im, Dynamic):
        return Dynamic(angle_in(im.v0, unit, angle))
    if isinstance(im, Table) and unit == angle:
        return dataclasses.replace(im, unit=None)
    # A table in degrees for a model in radians converts itself (Table.rows).
    if isinstance(im, Table) and angle == "deg":
        # Given in radians (its own unit) for a model in degrees: as math.degrees converts each value.
        def deg(a: Any) -> Any:
            return None if a is None else np.degrees(np.asarray(a, dtype=np.float64))

        return Table(deg(im.values), deg(im.velocities), deg(im.accelerations), im.time, im.file)
    return im


@dataclass
class DeckNames:
    """The names a deck's NAMES block declares, by deck number (1-based; rows by signed destination)."""

    points: dict[tuple[int, int], str] = field(default_factory=dict)
    coordinates: dict[int, str] = field(default_factory=dict)
    elements: dict[int, str] = field(default_factory=dict)
    rows: dict[int, str] = field(default_factory=dict)

    @classmethod
    def of_model(cls, model: Model) -> DeckNames:
        """The names a run's model echo carries (its deck's NAMES block)."""
        out = cls()
        out.points = {(p.x, p.y): p.name for p in model.points}
        named = {c for p in model.points for c in (p.x, p.y)}
        out.coordinates = {c.number: c.name for c in model.coordinates if c.name and c.number not in named}
        out.elements = {e.number: e.name for e in model.elements if e.name}
        out.rows = {r.dest: r.name for r in [*model.prescribed, *model.dependent] if r.name}
        return out

    @classmethod
    def of(cls, names: Mapping[str, Any] | None) -> DeckNames:
        """The names as the compiled module describes them (None: a deck without NAMES)."""
        if not names:
            return cls()
        out = cls()
        for ix, iy, name in names.get("points", []):
            out.points[(int(ix), int(iy))] = str(name)
        for key, kind in (("coordinates", out.coordinates), ("elements", out.elements)):
            for k, name in enumerate(names.get(key, []), 1):
                if name is not None:
                    kind[k] = str(name)
        for k, name in enumerate(names.get("prescribed", []), 1):
            if name is not None:
                out.rows[k] = str(name)
        for k, name in enumerate(names.get("dependent", []), 1):
            if name is not None:
                out.rows[-k] = str(name)
        return out


__all__ = ["MAX_NAME", "DeckNames", "deck_name", "model_unit", "names_block"]
