"""The synthesis statements of a deck's OPTIMISE block: ``FREETIME r [ORDERED [WITHIN w]]``, ``FULLROT r`` and
``VARYFRAME i lo hi``, stated as :func:`mechfem.optimize` states them from Python.

The deck's problem (:func:`mechfem.design.optimise_deck.problem`) is in the deck's numbering. With one of these
statements, its model is built as the Python API builds it: the deck read as a
:class:`~mechfem.model.mechanism.Mechanism` (which keeps the deck's numbers of co-ordinates, rows and buffers), compiled
through the typed builder, and wrapped by the same code as ``optimize``'s ``timing``, ``full_rotation`` and ``frame``:
:mod:`mechfem.design.timing`, :mod:`mechfem.design.full_rotation` and :mod:`mechfem.design.frame_angle`. No deck text is
written to do it. So the deck and Python state the same problem and reach the same code
(``tests/design/test_optimise_deck_synthesis.py``).
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from mechfem.design import engine as design
from mechfem.design import frame_angle, full_rotation, model_units, timing
from mechfem.design import rules as design_rules
from mechfem.design.frame_angle import FrameAngle, TurnedModel
from mechfem.design.optimise import _timed_model, synthesis_problem
from mechfem.design.timing import FreeTiming, Plan

if TYPE_CHECKING:
    from mechfem._core import DeckSynthesis, OptimiseBlock
    from mechfem.design.engine import FloatArray
    from mechfem.model.mechanism import Mechanism
    from mechfem.model.storage import Storage


class SynthesisError(ValueError):
    """A synthesis statement the deck's model cannot take; ``str()`` names the deck and the line."""


@dataclass
class Synthesis:
    """The deck's problem with its synthesis statements, and how its final design is written."""

    problem: design.Problem
    turn: frame_angle.Turn | None = None
    timed: Plan | None = None
    input_row: int | None = None
    """The free timing's input row (deck number)."""
    timing_scale: float = 1.0
    """What the free timing's variables (in the core's units, as the optimiser takes them) are multiplied by to give
    them in the deck's: 180/pi in a deck whose angles are in degrees."""

    def written(self, x: FloatArray) -> tuple[list[tuple[int, int]], FloatArray]:
        """The deck's numbers (rows and fixed co-ordinates) of the design ``x`` and their values: the frame turned
        into the fixed points and the input's start, a free-timed input starting at the first point's value."""
        p = self.problem
        variables, values = list(p.variables), np.asarray(x, dtype=np.float64)
        if self.turn is not None:
            core = turned_core(variables, self.turn)
            y, _ = TurnedModel(None, self.turn, variables, core).mapped([float(v) for v in values])
            variables, values = core, np.asarray(y)
        if self.timed is not None and self.input_row is not None:
            n = len(self.timed.thetas)
            inputs = timing.timed_inputs(self.timed, values[len(values) - n :])
            variables, values = [*variables[: len(values) - n], (1, self.input_row)], np.append(values[:-n], inputs[0])
        keep = [k for k, (kind, _) in enumerate(variables) if kind in (0, 1)]
        return [variables[k] for k in keep], values[keep]

    def inputs(self, x: FloatArray) -> list[float] | None:
        """The free-timed input's value at every point of the design ``x``, in the deck's unit (None without free
        timing)."""
        if self.timed is None:
            return None
        n = len(self.timed.thetas)
        return [float(t) * self.timing_scale for t in timing.timed_inputs(self.timed, np.asarray(x)[len(x) - n :])]


def turned_core(variables: list[tuple[int, int]], turn: frame_angle.Turn) -> list[tuple[int, int]]:
    """The core's variables behind ``variables`` (with the frame angle's sentinel), as :func:`frame_angle.turned`
    builds them."""
    at = variables.index(frame_angle.SENTINEL)
    moved: list[tuple[int, int]] = [v for v in [*turn.pivot, *turn.points, *turn.angles] if v not in variables]
    return [*variables[:at], *dict.fromkeys(moved), *variables[at + 1 :]]


def synthesis(deck: Path, opt: OptimiseBlock, p: design.Problem) -> Synthesis:
    """``p`` with the deck's FREETIME, FULLROT and VARYFRAME (unchanged without them)."""
    free, full, frame = opt.free_time, opt.full_rotation, opt.frame
    if not (free or full or frame):
        return Synthesis(p)
    from mechfem.model.mechanism import Mechanism
    from mechfem.run import building

    mech = Mechanism.from_deck(deck)
    storage = mech.storage
    if storage is None:
        raise AssertionError("a deck read as a mechanism keeps its buffers")
    built = building.builder(mech, mech.motion, storage)
    numbering = built.numbering
    base = os.fspath(deck.parent if deck.parent != Path("") else Path("."))
    rows = {numbering.row_dest[r]: r for r in mech.rows if r in numbering.row_dest}
    of: design.DesignModelOf = design.built_model(built.builder, base)
    timed, input_row, free_name, timing_scale = None, None, None, 1.0
    if free is not None and free.row is not None:
        input_row = free.row
        row = rows[input_row]
        free_name = row.name
        if not row.is_angle:
            raise SynthesisError(
                f"error: {deck}: line {free.line}: FREETIME names row {input_row}, which is not an angle: free "
                "timing wraps an angle input's values at the points as a turn; drive the mechanism by an angle"
            )
        timed = _plan(deck, mech, storage, free_name, free, numbering)
        if mech.units.angle == "deg":
            # The optimiser takes the points' inputs in the core's radians, as it takes every other variable of a
            # deck (VARY, VARYX, VARYFRAME): a deck in degrees then takes the steps of the deck in radians, and its
            # periodic variables share one turn. The deck's unit is for what is printed and written.
            timed, timing_scale = timing.in_units(timed, model_units.DEGREE), 1.0 / model_units.DEGREE
        of = _timed(timed, base)
    if full:
        line = full.line
        try:
            of = full_rotation.checked(of, mech, storage, base)
        except ValueError as e:
            raise SynthesisError(f"error: {deck}: line {line}: FULLROT: {e}") from None
    turn, framed = None, None
    if frame is not None and frame.lo is not None and frame.hi is not None:
        pivot = next((q for q in mech.points if q.fixed and q.x.number == frame.coordinate), None)
        if pivot is None:
            raise AssertionError("the deck reader checks that VARYFRAME names a fixed point")
        span = (frame.lo, frame.hi)
        # The deck's problem is in the core's units (the reader converts VARYFRAME's range to radians).
        turn = frame_angle.plan(mech, FrameAngle(pivot.name, span=span), numbering, free_name, core_units=True)
        framed = ("frame", span[0], span[1], design_rules.full_turn(*span))
    q = synthesis_problem(
        of,
        p.variables,
        p.names,
        p.lo,
        p.hi,
        p.periodic,
        frame=framed,
        turn=turn,
        timed=timed,
        terms=p.terms,
        bounds=p.bounds,
        objective=p.objective,
        steps=p.steps,
        tol=p.tol,
        stop=p.stop,
        # A turn of the free timing's input as the optimiser takes it, in the core's units (its values are reported
        # within one).
        whole_turn=timed.turn if timed is not None else design_rules.TURN,
    )
    return Synthesis(q, turn, timed, input_row, timing_scale)


def _plan(deck: Path, mech: Mechanism, storage: Storage, name: str, free: DeckSynthesis, numbering: Any) -> Plan:
    """The free timing of input ``name`` as FREETIME ``free`` states it: one point per position of the deck's motion,
    starting at the input's value there, ordered and within a sweep if it says so."""
    from mechfem.model.motion import By, To

    motion = mech.motion
    if motion is None:
        raise AssertionError("a KIN OPT deck has a motion")
    start = float(mech[name].value)
    step = motion.inputs[name]
    total = step.delta if isinstance(step, By) else (step.end - start if isinstance(step, To) else math.nan)
    starts = [start + total * k / motion.steps for k in range(motion.steps + 1)]
    # WITHIN comes in the core's units, the points' inputs in the deck's (free.scale: from the core's to the deck's).
    within = None if free.within is None else float(free.within) * float(free.scale)
    try:
        return timing.plan(mech, FreeTiming(name, starts, None, bool(free.ordered), within), storage, numbering)
    except (design.Infeasible, ValueError) as e:
        raise SynthesisError(f"error: {deck}: line {free.line}: FREETIME: {e}") from None


def _timed(timed: Plan, base: str) -> design.DesignModelOf:
    return _timed_model(timed, base)


__all__ = ["Synthesis", "SynthesisError", "synthesis", "turned_core"]
