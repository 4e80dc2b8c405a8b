"""The names a :class:`~mechfem.RunResult` is addressed by.

A named model's run is addressed by the model's own names (``"C"``, ``"rocker.angle"``, a :class:`Point` or
:class:`Row` object). A deck's run by what the deck declares, built from its model echo when a name is first asked
for:

* ``x13`` for co-ordinate 13; ``P9`` for the point whose co-ordinates an element uses as a pair, named after its x
  co-ordinate (``P9.x``, ``P9.y`` its co-ordinates);
* ``ANGB(3)`` for a row or output that is one form parameter (form ANGB of element 3), also ``E3.angle``; a row of
  several terms by its formula as the print file writes it (``ANGB(2) - ANGB(4)``); any row as ``row6`` and any
  output as ``out1`` (dependent form parameter -1);
* the names the deck's comments declare (a single word after ``;`` on an XFIX/XMOV, ELEM or FORM line, as
  mechfem's deck writer puts them), and a point ``A`` for co-ordinates declared ``A.x`` and ``A.y``;
* an input by its DOF number ``j`` or any name of its row.
"""

from __future__ import annotations

import functools
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from mechfem._util.names import UnknownNameError
from mechfem.deck import deckio
from mechfem.deck.explain import PythonWords
from mechfem.deck.naming import DeckNames, Numbering
from mechfem.model import echo
from mechfem.model.echo import Model, ModelNames
from mechfem.model.mechanism import Coordinate, FormParameter, Mechanism, Point, Row
from mechfem.results.result import RunResult
from mechfem.results.result_tables import NameTarget
from mechfem.results.run_report import RunReport
from mechfem.results.words import Words

_DECK_NAMES = (
    "a deck's run also takes x<i> for co-ordinate i, a row's form parameter or formula as the print file writes "
    "it (ANGB(3)), row<r>, out<k> and the names its comments declare"
)

#: What each kind of target is, for ``isinstance``.
_KINDS: dict[str, type] = {"point": Point, "coordinate": Coordinate, "row": Row}


class Namespace:
    """The names of ``mechanism`` as ``numbering`` numbers its parts; ``aliases`` are more names for its parts (a
    deck's), ``named`` says whether these are a named model's own names."""

    def __init__(
        self, mechanism: Mechanism, numbering: Numbering, named: bool = True, aliases: dict[str, object] | None = None
    ) -> None:
        self.mechanism = mechanism
        self.numbering = numbering
        self.named = named
        self.aliases = aliases or {}

    def find(self, ref: object, what: str, kinds: tuple[str, ...]) -> object:
        """The part ``ref`` names (a form parameter gives its row); a name the model does not have is an error
        that suggests the closest ``what``."""
        types = tuple(_KINDS[k] for k in kinds)
        obj = self.aliases.get(ref) if isinstance(ref, str) else None
        if obj is None and isinstance(ref, str):
            accept = (lambda o: isinstance(o, (*types, FormParameter))) if types else None
            try:
                obj = self.mechanism.find(ref, what, accept)
            except UnknownNameError as e:
                if self.named:
                    raise
                raise UnknownNameError(f"{e}; {_DECK_NAMES}") from None
        elif obj is None:
            obj = ref
        if isinstance(obj, FormParameter):
            found = [r for r in self.numbering.rows if r.terms == ((1.0, obj),)]
            if not found:
                raise KeyError(
                    f"{obj.label} is neither prescribed nor an output; declare it with Mechanism.output() to get it"
                )
            obj = found[0]
        if types and not isinstance(obj, types):
            raise TypeError(f"{ref!r} is not {' or '.join(kinds)}")
        return obj

    def target(self, ref: object, what: str, kinds: tuple[str, ...]) -> NameTarget:
        obj = self.find(ref, what, kinds)
        nb = self.numbering
        if isinstance(obj, Row):
            if obj not in nb.row_dest:
                raise KeyError(f"row {obj.name!r} is not part of this run")
            return NameTarget("row", (nb.row_dest[obj],), obj.name, obj.is_angle)
        if isinstance(obj, Point):
            return NameTarget("point", (self._number(obj.x), self._number(obj.y)), obj.name, False)
        if isinstance(obj, Coordinate):
            return NameTarget("coordinate", (self._number(obj),), obj.name, obj.kind == "angle")
        raise TypeError(f"{ref!r} is not a point, co-ordinate, row or output")

    def input(self, j: int) -> NameTarget:
        return self.target(self.numbering.inputs[j], "input", ("row",))

    def coordinate(self, i: int) -> NameTarget:
        return self.target(self.numbering.coords[i - 1], "co-ordinate", ("coordinate",))

    def _number(self, c: Coordinate) -> int:
        try:
            return self.numbering.coord_number[c]
        except KeyError:
            raise KeyError(f"co-ordinate {c.name!r} is not part of this run") from None

    def dof(self, key: object) -> int:
        if isinstance(key, str) and key in self.aliases:
            key = self.aliases[key]
        return self.numbering.dof(key)  # type: ignore[arg-type]

    def words(self, report: RunReport) -> Words:
        return PythonWords(self.numbering, report.input_names) if self.named else Words(report.input_names)

    def model_names(self) -> ModelNames | None:
        if not self.named:
            return None
        nb = self.numbering
        return ModelNames(
            coordinates=[c.name for c in nb.coords],
            prescribed=[r.name for r in nb.prescribed],
            dependent=[r.name for r in nb.dependent],
            inputs=[r.name for r in nb.inputs],
        )

    def traced(self, names: Sequence[str] | None) -> list[Point]:
        if names is None:
            cols = self.numbering.coord_number
            return [p for p in self.mechanism.points if not p.fixed and p.x in cols and p.y in cols]
        out = []
        for name in names:
            p = self.find(name, "point", ("point",))
            assert isinstance(p, Point)
            out.append(p)
        return out

    def columns(self, coordinates: bool) -> tuple[list[Row], list[Row], list[Coordinate]]:
        nb = self.numbering
        return nb.inputs, nb.dependent, [c for c in nb.coords if not c.fixed] if coordinates else []


def model_result(
    mech: Mechanism, numbering: Numbering, d: Any, path: str, parameters: dict[str, Any] | None = None
) -> RunResult:
    """The result of a run of the named model ``mech`` (``d``: the compiled module's run)."""
    return RunResult(_deck_path(path), d, Namespace(mech, numbering), parameters)


@functools.lru_cache(maxsize=256)
def _deck_path(path: str) -> Path:
    # Making a Path costs about a microsecond of every run; a path is immutable, so one serves every run of a name.
    return Path(path)


def deck_namespace(result: RunResult) -> Namespace:
    """The names of a deck's run, from its model echo (see the module's docs)."""
    model = result.model
    mech = deckio.topology(
        result.deck.stem or "deck",
        [deckio.Declared(c.number, c.given, c.moving) for c in model.coordinates],
        [(e.number, e.type, list(e.coords)) for e in model.elements],
        [_declared_row(r) for r in model.prescribed],
        [_declared_row(r) for r in model.dependent],
        DeckNames.of_model(model),
    )
    # The deck's own numbers, as for a deck read into a mechanism (its inputs are its last prescribed rows).
    numbering = deckio.number_model(mech)
    return Namespace(mech, numbering, named=False, aliases=_aliases(model, numbering, mech))


def _declared_row(r: echo.EchoRow) -> deckio.DeclaredRow:
    return deckio.DeclaredRow(r.dest, [(t.element, t.form, t.factor) for t in r.terms], r.para, r.input)


def _aliases(model: Model, nb: Numbering, mech: Mechanism) -> dict[str, object]:
    """The deck's names for its parts beside those the topology made: ``x13``, ``ANGB(3)``, formulas, ``row6``,
    ``out1``, and the names its comments declare (which never replace a name the topology made)."""
    out: dict[str, object] = {}
    declared: dict[str, object] = {}
    for c in model.coordinates:
        out[f"x{c.number}"] = nb.coords[c.number - 1]
        if c.name:
            declared[c.name] = nb.coords[c.number - 1]
    for echo_rows, rows, stem in ((model.prescribed, nb.prescribed, "row"), (model.dependent, nb.dependent, "out")):
        for e, r in zip(echo_rows, rows, strict=True):
            out[f"{stem}{abs(e.dest)}"] = r
            out.setdefault(e.formula(), r)
            if len(r.terms) == 1 and r.terms[0][0] == 1.0:
                out.setdefault(r.terms[0][1].label, r)
            if e.name:
                declared[e.name] = r
    for declared_element, element in zip(model.elements, nb.elements, strict=True):
        if declared_element.name:
            declared[declared_element.name] = element
    # A point for co-ordinates declared ``A.x`` and ``A.y`` that an element uses as a pair.
    for name, obj in list(declared.items()):
        if name.endswith(".x") and isinstance(obj, Coordinate) and obj.point is not None:
            if declared.get(name[:-2] + ".y") is obj.point.y:
                declared[name[:-2]] = obj.point
    for name, obj in declared.items():
        if name not in mech:
            out.setdefault(name, obj)
    return out


__all__ = ["Namespace", "deck_namespace", "model_result"]
