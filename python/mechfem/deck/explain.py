"""What the Python API says when a named model fails or stops early: the model's names and the Python calls that
change it, never deck keywords or deck line numbers.

A :class:`~mechfem.Mechanism` runs as a deck written for it, so the deck reader and the solver report its
mistakes in the deck's terms. This module words them for the model:

* :func:`translate` turns an error of the deck reader or of position 1 into the same exception with a message
  in the model's words, built from what the error carries (the deck line's model part, the element, the rows
  and co-ordinates at fault) and from the model itself; the attributes stay (``line``, ``name``, ``deck``,
  ``element``, ``rows``, ``coords``, ...);
* :class:`PythonWords` says why a motion stopped (:meth:`mechfem.RunResult.stop_reason`) and what deserves a
  second look (:attr:`mechfem.RunResult.warnings`), with the inputs' names and ``Motion.free``.

The core's messages arrive in parts (:data:`mechfem.results.words.Part`): the things they name (elements, co-ordinates,
rows, deck terms) are structure, which :class:`PythonWords` names by the model's names; the words between them are
never rewritten. The deck path (``mechfem.run_deck``, the command line) keeps the deck's words.
"""

from __future__ import annotations

import re
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, TypeVar

import mechfem._core as _core
from mechfem._util.names import listing
from mechfem.errors import AssemblyError, ConvergenceError, DeckError, LimitPositionError, MechfemError, ResourceError
from mechfem.model.parts import ELEMENT_WORDS, Coordinate, Element, Point, Row
from mechfem.results.words import Part, Words, with_unit

if TYPE_CHECKING:
    from mechfem.deck.naming import DeckText, Numbering


def element_words(e: Element) -> str:
    """``the bar 'crank' (A0, A)``: the element by its method's word, its name and its points and co-ordinates."""
    return f"the {ELEMENT_WORDS.get(e.type, 'element')} {e.name!r} ({', '.join(s.name for s in e.slots)})"


def _names(items: Sequence[Coordinate | Row | Point]) -> str:
    return listing(x.name for x in items)


def with_attributes(err: MechfemError, **attributes: object) -> MechfemError:
    """``err`` with ``attributes`` set on it (the facts a caller reads besides the message)."""
    for key, value in attributes.items():
        setattr(err, key, value)
    return err


# --- solver messages ------------------------------------------------------------------------------------------------

T = TypeVar("T")


def _numbered(items: Sequence[T], number: object) -> T | None:
    """The item of deck number ``number`` (1-based), or None when there is none."""
    return items[number - 1] if isinstance(number, int) and 1 <= number <= len(items) else None


_TERMS = {
    "a_degree_of_freedom": "an input",
    "free_motion": "Motion.free",
    "dynamic": "Dynamic",
    "simulation": "Mechanism.simulate",
}
"""The Python API's words for the terms the deck spells its own way (a ``term`` part), by code."""

_NOUNS = {"coordinate": "co-ordinate", "coords": "co-ordinates", "row": "row", "rows": "rows"}
"""The noun before the names of the co-ordinates and rows a message names, by the part's kind."""


def parts_of(err: BaseException) -> list[Part]:
    """The ``parts`` of an error of the core (see :data:`mechfem.results.words.Part`); its message as one plain part for
    an error without them."""
    parts = getattr(err, "parts", None)
    return list(parts) if isinstance(parts, list) else [str(err)]


def names_term(parts: Sequence[Part], code: str) -> bool:
    """Whether the message of ``parts`` uses the deck term ``code``."""
    return any(not isinstance(p, str) and p[0] == "term" and p[1] == code for p in parts)


# --- stop reasons ---------------------------------------------------------------------------------------------------


class PythonWords(Words):
    """The words of the Python API for a stop reason, a limit position or a warning: inputs by name,
    ``Motion.free`` and the Motion's steps instead of deck keywords."""

    more_steps = "a larger number of steps in the Motion"
    smaller_free_step = "Try a smaller ds in Motion.free, with more steps to cover the same path."
    free_needs_one_input = "free motion, Motion.free, needs a mechanism with one input"
    tolerances = "rtol and atol"
    singular_results = (
        "every result made from them (transfer functions of first and second order, velocities, accelerations) is "
        "NaN there"
    )

    def __init__(self, numbering: Numbering, inputs: Sequence[str] = ()) -> None:
        super().__init__([r.name for r in numbering.inputs])
        self.numbering = numbering
        # The units of the inputs and of det(D^c), from the run's inputs (:class:`mechfem.results.words.InputName`).
        self.inputs = list(inputs)

    def input(self, j: int) -> str:
        return f"the input {self.names[j - 1]!r}" if 1 <= j <= len(self.names) else f"input number {j}"

    def unit(self, j: int) -> str:
        return getattr(self.inputs[j - 1], "unit", "") if 1 <= j <= len(self.inputs) else ""

    def at(self, j: int, value: float, digits: int) -> str:
        name = self.names[j - 1] if 1 <= j <= len(self.names) else f"input number {j}"
        return f"{name} = {with_unit(f'{value:.{digits}g}', self.unit(j))}"

    def det(self, value: float, digits: int) -> str:
        unit = getattr(self.inputs[0], "det_unit", "") if self.inputs else ""
        return f"det(D^c) = {with_unit(f'{value:.{digits}g}', unit)}"

    def free_advice(self, ds: float, known: bool, steps: int) -> str:
        step = float(f"{ds:.2g}")
        size = "about the size of the steps made so far" if known else "choose it small against the mechanism"
        return (
            f"Use free motion instead, `Motion.free({steps}, ds={step:g})`: each of its {steps} steps moves the "
            f"co-ordinates a Euclidean distance {abs(step):g} ({size}) through the limit positions, the sign of ds "
            "keeps the input's direction, and Analysis.input() gives where the input goes."
        )

    def thing(self, kind: str, value: object, deck: str) -> str:
        """A thing a message of the core names, by the model's names (the deck's words for a number the model
        does not have)."""
        nb = self.numbering
        if kind == "line":
            # The line of a deck this model was written to: the model's own names already say which statement.
            return ""
        if kind == "term" and isinstance(value, str):
            return _TERMS.get(value, deck)
        if kind == "detail" and isinstance(value, _core.ElementFault):
            e = _numbered(nb.elements, value.element)
            return deck if e is None else element_detail(value, e, deck)
        if kind == "element":
            e = _numbered(nb.elements, value)
            return deck if e is None else element_words(e)
        if kind == "point" and isinstance(value, list):
            xy = [_numbered(nb.coords, k) for k in value]
            x = xy[0] if xy else None
            if len(xy) == 2 and x is not None and xy[1] is not None and x.name.endswith(".x"):
                return f"point {x.name[:-2]}"
            kind = "coords"
        if kind in _NOUNS:
            coordinates = kind in ("coordinate", "coords")
            items: Sequence[Coordinate | Row] = nb.coords if coordinates else nb.prescribed
            found = [_numbered(items, k) for k in (value if isinstance(value, list) else [value])]
            if found and None not in found:
                names = [x.name if coordinates else repr(x.name) for x in found if x is not None]
                return f"{_NOUNS[kind]} {', '.join(names)}"
        return deck


# --- errors ---------------------------------------------------------------------------------------------------------


def translate(err: MechfemError, deck: DeckText, model: str) -> MechfemError:
    """The error in the model's words, of the same type and with the attributes it had (deck numbers) and the
    model's names for them."""
    nb = deck.numbering
    words = PythonWords(nb)
    if isinstance(err, DeckError):
        return deck_error(err, deck, model)
    if isinstance(err, AssemblyError):
        e = _numbered(nb.elements, getattr(err, "element", None))
        if e is None:
            text = f"position 1 of the mechanism {model!r} cannot be computed: {words.render(parts_of(err))}"
        else:
            detail = element_detail(getattr(err, "detail_fields", None), e, str(getattr(err, "detail", "") or ""))
            text = (
                f"position 1 of the mechanism {model!r} cannot be computed: {element_words(e)} cannot be evaluated "
                f"there: {detail}; {_ESTIMATES.format(points=_moving_points(nb))}"
            )
        return with_attributes(AssemblyError(text), **_solver_fields(err), element_name=None if e is None else e.name)
    if isinstance(err, LimitPositionError):
        rows = list(getattr(err, "rows", []))
        coords = list(getattr(err, "coords", []))
        row_names = [nb.prescribed[r - 1].name if 1 <= r <= len(nb.prescribed) else str(r) for r in rows]
        coord_names = [nb.coords[i - 1].name if 1 <= i <= len(nb.coords) else str(i) for i in coords]
        rank, size = getattr(err, "rank", None), getattr(err, "size", None)
        text = singular_at_start(rank, size, model, row_names, coord_names)
        return with_attributes(
            LimitPositionError(text), **_solver_fields(err), row_names=row_names, coord_names=coord_names
        )
    if isinstance(err, ConvergenceError):
        text = (
            f"position 1 of the mechanism {model!r} cannot be computed: {words.render(parts_of(err))}; "
            f"{_ESTIMATES.format(points=_moving_points(nb))}"
        )
        return with_attributes(ConvergenceError(text), **_solver_fields(err))
    if isinstance(err, ResourceError):
        facts = str(err).split(". Ask for", 1)[0]
        return ResourceError(
            f"{facts}; ask for fewer steps (the Motion's steps) or a smaller model, or raise the limit with the "
            "environment variable MECHFEM_MEMORY_LIMIT (for example 8G)"
        )
    parts = parts_of(err)
    text = words.render(parts)
    if deck.simulated and names_term(parts, "dynamic"):
        text += f" (the inputs that move under the forces: {', '.join(map(repr, deck.simulated))})"
    return type(err)(text)


_SOLVER_FIELDS = (
    "position",
    "reason",
    "element",
    "element_type",
    "detail",
    "coordinate",
    "rows",
    "coords",
    "rank",
    "size",
    "iterations",
    "residual",
    "parts",
    "detail_fields",
)
"""The fields a solver error carries (deck numbers), which the model's error keeps beside its names."""


def _solver_fields(err: MechfemError) -> dict[str, object]:
    return {k: getattr(err, k) for k in _SOLVER_FIELDS if hasattr(err, k)}


_ESTIMATES = (
    "give the moving points ({points}) estimates near a position that fits (the (x, y) of Mechanism.point, or "
    "Mechanism.set; angles are taken as principal values in (-pi, pi]), and check the prescribed values"
)


def _moving_points(nb: Numbering) -> str:
    moving = [c for c in nb.coords if not c.fixed]
    names = [c.point.name if c.point is not None else c.name for c in moving]
    return listing(names)


def element_detail(fault: object, e: Element, deck: str) -> str:
    """Why the element ``e`` cannot be evaluated, from the core's reason (an :class:`ElementFault`, the value of a
    ``detail`` part or the ``detail_fields`` of an error), with the element's own point and co-ordinate names;
    ``deck`` is the reason in the core's words, for a reason without a fault or one these names do not fit."""
    if not isinstance(fault, _core.ElementFault):
        return deck
    slots = [s.name for s in e.slots]
    points = [p.name for p in e.points]
    kind = fault.kind
    if kind == "coincident_points" and len(points) >= 2:
        p, q = points[0], points[1]
        return f"its points {p} and {q} coincide, so the direction {p}->{q} is undefined"
    if kind == "no_belt_span" and len(slots) == 6:
        return (
            f"the belt has no free span: the distance {fault.distance} between the wheel centres {slots[0]} "
            f"and {slots[2]} is not larger than |{slots[4]} - {slots[5]}| = {fault.difference}"
        )
    if kind == "zero_radius" and e.type == "GR2":
        return f"the gear radius {slots[3] if fault.radius == 'R_a' else slots[4]} is zero"
    return deck


def singular_at_start(rank: int | None, size: int | None, model: str, rows: list[str], coords: list[str]) -> str:
    """Position 1 is singular (D^c of ``rank`` of ``size`` when known): which prescribed values depend on each other
    and which co-ordinates can still move."""
    of = f" (rank {rank} of {size})" if rank is not None and size is not None else ""
    head = f"position 1 of the mechanism {model!r} cannot be computed: D^c is singular there{of}"
    if not rows:
        return (
            f"{head}: the mechanism is in a limit position at position 1, or the model cannot move as described; "
            "check which form parameters are prescribed or inputs, and which co-ordinates are fixed"
        )
    which = (
        f"the prescribed value {rows[0]!r} is superfluous"
        if len(rows) == 1
        else f"the prescribed values {', '.join(map(repr, rows))} depend on each other"
    )
    return (
        f"{head}: {which}, and the co-ordinates {', '.join(coords)} can move with every prescribed value held; the "
        "mechanism is in a limit position at position 1, or the model cannot move as described: leave a "
        "superfluous form parameter free (None), or give the moving points estimates of another position"
    )


# --- mistakes the deck reader finds ---------------------------------------------------------------------------------


@dataclass
class _Context:
    """What a rule knows: the mechanism's name, its numbering, the model part the refused line declares and the
    diagnostic's fields (``kind``, ``text``, ``element``, ``coordinate``, ``detail``, ``message``)."""

    model: str
    nb: Numbering
    what: str
    name: str
    err: DeckError
    mode: str
    """The written deck's mode line (``KIN ANA``, ``DYN SIM``, ...)."""

    def field(self, key: str) -> object:
        return getattr(self.err, key, None)

    def element(self) -> Element | None:
        """The element the diagnostic is about, from its ``element`` field."""
        k = self.field("element")
        return self.nb.elements[k - 1] if isinstance(k, int) and 1 <= k <= len(self.nb.elements) else None

    def keyword(self) -> str:
        """The keyword of the refused deck line."""
        words = str(self.field("text") or "").split()
        return words[0].upper() if words else ""


Rule = Callable[[_Context], "str | None"]
"""Words a diagnostic of one kind in the model's terms, or None to leave it to the general wording."""


def _unused(c: _Context) -> str:
    i = c.field("coordinate")
    coord = c.nb.coords[i - 1] if isinstance(i, int) and 1 <= i <= len(c.nb.coords) else None
    part = (
        f"the point {coord.point.name!r}"
        if coord is not None and coord.point is not None
        else f"the co-ordinate {coord.name if coord is not None else c.name!r}"
    )
    return f"{part} of the mechanism {c.model!r} is used by no element; connect it to an element, or leave it out"


def _count(c: _Context) -> str:
    # The deck is the model's, so the rows and moving co-ordinates it counted are the model's own.
    nb = c.nb
    moving = [x for x in nb.coords if not x.fixed]
    k, few = abs(len(nb.prescribed) - len(moving)), len(nb.prescribed) < len(moving)
    rows = _counted(len(nb.prescribed), "form parameter or combination", "form parameters or combinations")
    text = (
        f"the mechanism {c.model!r} prescribes {rows}, inputs included ({_names(nb.prescribed)}), for "
        f"{_counted(len(moving), 'moving co-ordinate', 'moving co-ordinates')} ({_names(moving)}): {k} too "
        f"{'few' if few else 'many'}"
    )
    more = _counted(k, "more co-ordinate", "more co-ordinates")
    if not few:
        return f"{text}; leave {k} of them free (None instead of a number, Keep() or Driven()), or make {more} moving"
    involved = {x for r in nb.prescribed for _, p in r.terms for x in p.element.coordinates}
    loose = [x for x in moving if x not in involved]
    if loose:
        text += (
            f"; no prescribed form parameter involves the moving co-ordinates {_names(loose)}, which may move freely"
        )
    return (
        f"{text}; prescribe {k} more (a number or Keep() for a form parameter of an element, or "
        f"Mechanism.prescribe), make {k} more an input (Driven()), or fix {more} (Mechanism.fixed, or fixed= of "
        "Mechanism.point)"
    )


def _counted(n: int, one: str, many: str) -> str:
    return f"{n} {one if n == 1 else many}"


def _bad_value(c: _Context) -> str | None:
    e = c.element()
    if c.keyword() == "NRDOF":
        return (
            f"the mechanism {c.model!r} has no inputs; make a form parameter an input with Driven() (e.g. "
            "angle=Driven()) or Mechanism.drive"
        )
    if c.keyword() == "PARA" and e is not None:
        # The value is the one the deck's row gives the length (its PARA value over the term's factor).
        m = re.search(r" as (\S+), but", str(c.field("message")))
        value = m.group(1) if m else "a value that is not positive"
        points = [p.name for p in e.points]
        between = f"between {points[0]} and {points[1]}" if len(points) >= 2 else "between the element's two points"
        return (
            f"{c.name!r} prescribes the length of {element_words(e)} as {value}, but a length must be greater than "
            f"zero; give the distance {between}, a positive number (points that coincide have no direction)"
        )
    m = re.search(r"to change by (\S+) in a time of (\S+), faster", str(c.field("message")))
    if m is not None:
        return (
            f"the motion asks the input {c.name!r} to change by {m.group(1)} in a time of {m.group(2)}, faster than "
            "a number can hold; give a longer dt or a smaller change"
        )
    return None


def _element(c: _Context) -> str | None:
    e = c.element()
    if e is None:
        return None
    detail = element_detail(c.field("detail_fields"), e, str(c.field("detail") or ""))
    return (
        f"{element_words(e)} cannot be evaluated at the given co-ordinates: {detail}; change the initial positions "
        "of its points (Mechanism.point, or Mechanism.set) or its dimensions"
    )


def _free_many(c: _Context) -> str:
    inputs = c.nb.inputs
    return (
        f"free motion (Motion.free, Free) needs a mechanism with one input, and {c.model!r} has {len(inputs)} "
        f"({_names(inputs)}); drive them with Motion.by, Motion.to or Motion.table"
    )


def _wrong_mode(c: _Context) -> str | None:
    if c.keyword() != "MOV_FREE" or not c.mode.startswith("DYN"):
        return None
    return (
        f"free motion (Motion.free, Free) cannot drive the mechanism {c.model!r}, which has masses or loads: free "
        "motion has no timing, so its run has no velocities or accelerations; drive the input with Motion.by, "
        "Motion.to or Motion.table, or let it move under the forces (Mechanism.simulate)"
    )


def _no_frame(c: _Context) -> str:
    e = c.element()
    what = element_words(e) if e is not None else "the element"
    return f"{what} has no frame to carry a mass; give the mass to a bar, half beam or ternary element"


_RULES: dict[str, Rule] = {
    "coordinate_unused": _unused,
    "not_square": _count,
    "bad_value": _bad_value,
    "model": _element,
    "free_motion_dof": _free_many,
    "wrong_mode": _wrong_mode,
    "no_frame": _no_frame,
}
"""The model's words for a diagnostic, by its ``kind`` (the deck reader's stable code)."""


def deck_error(err: DeckError, deck: DeckText, model: str) -> DeckError:
    """A mistake the deck reader found in the deck written for ``model``, in the model's words; ``line`` and
    ``deck`` still say where it is in the written deck (``name`` names the model part of that line), and the
    diagnostic's fields (``kind``, ``column``, ``hint``, ...) stay."""
    line = int(getattr(err, "line", 0) or 0)
    what, name = deck.notes.get(line, ("", ""))
    mode = next((x.split(";", 1)[0].strip().upper() for x in deck.text.splitlines() if x.split(";", 1)[0].strip()), "")
    context = _Context(model, deck.numbering, what, name, err, mode)
    rule = _RULES.get(str(getattr(err, "kind", "")))
    message = rule(context) if rule is not None else None
    if message is None:
        headline = str(getattr(err, "message", "") or str(err))
        where = f"{what} {name!r}" if what else "the model"
        # The diagnostic speaks of the written deck, and says so: its numbers are that deck's.
        message = (
            f"in the mechanism {model!r}, {where}: the deck written for it was refused: {headline} (e.deck holds "
            "that deck, e.line the line)"
        )
    new = DeckError(message)
    fields = {k: getattr(err, k) for k in _DECK_FIELDS if hasattr(err, k)}
    with_attributes(new, **fields)
    with_attributes(new, path=getattr(err, "path", deck.path), line=line, name=name or None, deck=deck.text)
    return new


_DECK_FIELDS = (
    "kind",
    "column",
    "text",
    "message",
    "hint",
    "element",
    "coordinate",
    "detail",
    "detail_fields",
    "diagnostics",
)
"""The fields of the deck reader's diagnostic that a model's error keeps (deck numbers, the written deck's line)."""


__all__ = ["PythonWords", "deck_error", "element_words", "parts_of", "translate"]
