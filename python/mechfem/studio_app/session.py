"""One design being edited: a :class:`~mechfem.Mechanism`, its last good run, and the history of its edits.

An edit changes values of the mechanism in place (:meth:`Mechanism.set`, in the model's units) and re-runs the whole
motion. The mechanism keeps its compiled model per topology (:mod:`mechfem.run.compiled`), so a changed number is a
parameter of the kept model: nothing is re-read or recompiled. An edit whose position 1 cannot be assembled, or
whose motion stops where the last good design's did not, is undone at once and said in words; the last good design
stays. A moving point's value is only the start estimate of position 1: dragging it chooses the assembly branch, and
a change of branch is reported (det(D^c) at position 1 changes sign), never silent.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from mechfem.errors import MechfemError
from mechfem.model.mechanism import Mechanism
from mechfem.model.parts import Coordinate, Row
from mechfem.results.result import RunResult
from mechfem.studio_app.optimise_block import copy_targets, optimise_block, same_numbering, with_block

#: A value a user gives: a number, or a point's (x, y).
Value = float | tuple[float, float]
#: The values of a design: every co-ordinate's and every row's that has one.
Values = dict[Coordinate | Row, float | None]


class EditRefused(Exception):
    """An edit that was undone: its words say why; the last good design is unchanged."""


@dataclass
class EditOutcome:
    """What an accepted edit did: ``branch`` says in words that the assembly branch changed (None if not)."""

    branch: str | None = None
    notes: list[str] = field(default_factory=list)


def _unit(mech: Mechanism, angle: bool) -> str:
    return (mech.units.angle or "rad") if angle else (mech.units.length or "")


def _sign(x: float) -> int:
    return 0 if not math.isfinite(x) or x == 0.0 else (1 if x > 0 else -1)


class Session:
    """A mechanism under edit (``mechanism``, changed in place), its ``result`` (the last good run), undo and redo."""

    def __init__(self, mechanism: Mechanism, deck: Path | None = None, source: str | None = None) -> None:
        self.mechanism = mechanism
        self.deck = deck
        #: The text of the deck the design was opened from (read from ``deck`` when not given): what the mechanism
        #: does not hold of it (an OPTIMISE block) is saved from there (:mod:`mechfem.studio_app.optimise_block`).
        self.source = (
            source if source is not None or deck is None else deck.read_text(encoding="utf-8", errors="replace")
        )
        self._undo: list[Values] = []
        self._redo: list[Values] = []
        self.result = self._run()
        self.revision = 0
        self._group: object = None
        #: What the drawing of one design keeps for the next (:func:`mechfem.studio_app.scene.scene`).
        self.drawing_kept: dict[str, Any] = {}

    # -- what can be edited

    def dimensions(self) -> list[dict[str, Any]]:
        """The named numbers a user may change: prescribed values (lengths, angles) and input starts, each with its
        value and unit (the model's)."""
        out = []
        for row in self.mechanism.rows:
            if row.kind == "output" or row.value is None:
                continue
            out.append(
                {
                    "name": row.name,
                    "kind": row.kind,
                    "value": row.value,
                    "unit": _unit(self.mechanism, row.is_angle),
                    "angle": row.is_angle,
                    "formula": row.formula(),
                }
            )
        return out

    def points(self) -> list[dict[str, Any]]:
        """Every point: its name, whether it is a frame pivot, its given value (a moving point's start estimate) and
        where position 1 of the last good run has it."""
        numbering = self.result.numbering
        at = self.result.coords[0]
        out = []
        for p in self.mechanism.points:
            ix, iy = numbering.coord_number.get(p.x), numbering.coord_number.get(p.y)
            solved = [float(at[ix - 1]), float(at[iy - 1])] if ix and iy else [p.x.value, p.y.value]
            out.append(
                {
                    "name": p.name,
                    "fixed": p.x.fixed and p.y.fixed,
                    "given": [p.x.value, p.y.value],
                    "at": solved,
                }
            )
        return out

    # -- runs and edits

    def _run(self) -> RunResult:
        with warnings.catch_warnings():
            # A motion that stops early is said on the page (RunResult.report.stop_reason), not as a warning.
            warnings.simplefilter("ignore")
            return self.mechanism.run(order=2)

    def _values(self) -> Values:
        out: Values = {c: c.value for c in self.mechanism.coordinates}
        out.update({r: r.value for r in self.mechanism.rows if r.kind != "output"})
        return out

    def _restore(self, values: Values) -> None:
        for obj, v in values.items():
            obj.value = v

    def edit(self, changes: dict[str, Value], group: object = None) -> EditOutcome:
        """Sets ``changes`` (name -> value, a point's (x, y)) and re-runs the motion; raises :class:`EditRefused`
        (the design unchanged) when the new design cannot be assembled or stops where the last good one did not.
        Edits of one ``group`` (not None: the moves of one drag) are undone together."""
        before = self._values()
        try:
            for name, value in changes.items():
                self.mechanism.set(name, tuple(value) if isinstance(value, list | tuple) else value)  # type: ignore[arg-type]
            return self._accept(before, self._run(), group)
        except (MechfemError, ValueError, TypeError, KeyError) as e:
            self._restore(before)
            raise EditRefused(self._words(e)) from None

    def _words(self, e: Exception) -> str:
        text = e.args[0] if isinstance(e, KeyError) and e.args else str(e)
        return f"{type(e).__name__}: {text}" if not isinstance(e, MechfemError) else str(text)

    def _accept(self, before: Values, result: RunResult, group: object = None) -> EditOutcome:
        stop = result.report.stop_reason()
        if stop and result.positions < self.result.positions:
            self._restore(before)
            raise EditRefused(f"the motion stops at position {result.positions} of {result.report.steps + 1}: {stop}")
        branch = self._branch(result)
        if group is None or group != self._group or not self._undo:
            self._undo.append(before)
        self._group = group
        self._redo.clear()
        self.result = result
        self.revision += 1
        return EditOutcome(branch=branch)

    def _branch(self, result: RunResult) -> str | None:
        old, new = _sign(float(self.result.det[0])), _sign(float(result.det[0]))
        if old and new and old != new:
            side = {1: "positive", -1: "negative"}
            return (
                f"The mechanism assembled on its other branch: det(D^c) at position 1 turned {side[new]} "
                f"(it was {side[old]})."
            )
        return None

    def _step(self, source: list[Values], target: list[Values]) -> EditOutcome:
        if not source:
            raise EditRefused("nothing to " + ("undo" if source is self._undo else "redo"))
        before = self._values()
        self._restore(source[-1])
        try:
            result = self._run()
        except MechfemError as e:
            self._restore(before)
            raise EditRefused(str(e)) from None
        source.pop()
        target.append(before)
        self._group = None
        branch = self._branch(result)
        self.result = result
        self.revision += 1
        return EditOutcome(branch=branch)

    def undo(self) -> EditOutcome:
        """Goes back one edit."""
        return self._step(self._undo, self._redo)

    def redo(self) -> EditOutcome:
        """Does again the edit last undone."""
        return self._step(self._redo, self._undo)

    @property
    def can_undo(self) -> bool:
        return bool(self._undo)

    @property
    def can_redo(self) -> bool:
        return bool(self._redo)

    # -- saving

    def save(self, path: Path) -> list[Path]:
        """Writes the design as a deck at ``path`` (NAMES and UNITS included; the OPTIMISE block of the deck it
        came from, with the files its targets read), runs that deck's motion and writes its print file, data set and
        report beside it; returns the files written."""
        from mechfem import run_deck
        from mechfem.output.files import write_outputs
        from mechfem.report.html import write_report

        block = optimise_block(self.source) if self.source else None
        targets = []
        if block is not None and self.source is not None:
            folder = self.deck.parent if self.deck is not None else Path(".")
            if not same_numbering(self.mechanism.to_deck(), self.source, folder):
                raise ValueError(
                    "the deck's OPTIMISE block refers to co-ordinates and rows by the deck's numbers, and the saved "
                    "deck numbers them otherwise: it cannot be kept (save, then copy the block by hand)"
                )
            # The files the block's targets read first: a save that cannot take them writes no deck.
            if self.deck is not None:
                targets = copy_targets(block, self.deck.parent, path.parent)
            deck = self.mechanism.save_deck(path)
            deck.write_text(with_block(deck.read_text(encoding="utf-8"), self.source, block), encoding="utf-8")
        else:
            deck = self.mechanism.save_deck(path)
        result = run_deck(deck)
        written = [deck, *targets, *write_outputs(result, deck.parent), write_report(result, deck.parent)]
        self.deck = deck
        self.source = deck.read_text(encoding="utf-8")
        return written


__all__ = ["EditRefused", "EditOutcome", "Session", "Value"]
