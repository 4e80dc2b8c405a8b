"""The optimisation section of a ``KIN OPT`` deck's report: what the optimiser did, as plain JSON-ready data for the
page (``report/assets/optimisation.js`` draws it).

It holds the objective at every iteration (iteration 0 is the start design), every design variable by the deck's
name and in the deck's units with its start and final value, its bounds and whether the final value sits on one,
every target's value, the value achieved at the final design and the residual (target minus achieved) in the
model's units, and the start and final designs' shapes at position 1 with the paths of the points whose two
co-ordinates are targets (path generation), for the page to draw over each other.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from mechfem.design import engine as design
from mechfem.design.optimise_deck import deck_scales, missed_value, stated, unreached, variable_labels
from mechfem.design.optimum import Optimum
from mechfem.model.echo import Model
from mechfem.report.charts import num, nums
from mechfem.results.labels import buffer_name, core_input, point_name
from mechfem.results.result import RunResult
from mechfem.viz.drawing import MechanismDrawing

#: A variable is on a bound when it is within this fraction of its range from it: the trust-region least squares
#: stays strictly inside its bounds and ends this close to one it presses against.
ACTIVE_BOUND = 1e-6


@dataclass(frozen=True)
class VariableRow:
    """One design variable in the deck's units."""

    name: str
    unit: str
    start: float
    final: float
    lo: float
    hi: float
    active: str
    """``"lower"`` or ``"upper"`` when the final value is on that bound, else ""."""
    periodic: bool
    """An angle free to turn: its range is a whole turn and has no bound to be on."""


@dataclass(frozen=True)
class TargetRow:
    """One value a target asks for, in the model's units of its buffer."""

    keyword: str
    line: int
    name: str
    unit: str
    where: str
    target: float
    achieved: float

    @property
    def residual(self) -> float:
        return self.target - self.achieved


def exact(v: float) -> float | None:
    """A number for JSON at full precision (the tables are compared with the print file's); None if not finite."""
    v = float(v)
    return v if math.isfinite(v) else None


def active_bound(x: float, lo: float, hi: float) -> str:
    """``"lower"``, ``"upper"`` or "": whether ``x`` is on a bound of ``[lo, hi]`` (:data:`ACTIVE_BOUND`)."""
    tol = ACTIVE_BOUND * (hi - lo) if math.isfinite(hi - lo) else ACTIVE_BOUND * max(1.0, abs(x))
    if math.isfinite(lo) and x - lo <= tol:
        return "lower"
    if math.isfinite(hi) and hi - x <= tol:
        return "upper"
    return ""


def variable_rows(optimum: Optimum, model: Model | None) -> list[VariableRow]:
    """Every design variable of a deck's optimum, in the order of the OPTIMISE block, named and scaled as the print
    file says them."""
    deck = stated(optimum)
    p, block = deck.problem, deck.block
    labels = variable_labels(p, model)
    scales = deck_scales(block, p)
    x0, x1 = optimum.x_start, optimum.x
    periodic = p.periodic or [False] * len(labels)
    out = []
    for k, ((name, unit), f) in enumerate(zip(labels, scales, strict=True)):
        lo, hi, x = float(p.lo[k]), float(p.hi[k]), float(x1[k])
        active = "" if periodic[k] else active_bound(x, lo, hi)
        out.append(VariableRow(name, unit, float(x0[k]) * f, x * f, lo * f, hi * f, active, periodic[k]))
    return out


def _buffer_scale(model: Model | None, number: int) -> tuple[str, float]:
    """The unit the model shows buffer ``number`` in and the factor from the core's numbers to it."""
    labels = None if model is None else model.labels
    if labels is None:
        return "", 1.0
    try:
        _, _, said, dims = labels.buffer(number)
    except IndexError:
        return "", 1.0
    return ("" if said == "-" else said), float(labels.scale(dims))


def target_rows(optimum: Optimum, model: Model | None) -> list[TargetRow]:
    """Every value a deck's targets ask for (each compared position of a TARGET, each extremum of a TARGETEXT), with
    the value achieved at the final design."""
    deck, final = stated(optimum), optimum.final
    if final is None:
        raise ValueError("the optimum holds no final evaluation to compare the targets with")
    extrema: dict[int, list[tuple[float, float]]] = {}
    for t, at, value in optimum.extrema:
        extrema.setdefault(id(t), []).append((at, value))
    out = []
    for target, term in zip(deck.block.targets, deck.problem.terms, strict=True):
        b, line = target.buffer, target.line
        unit, f = _buffer_scale(model, b)
        name = buffer_name(model, b)
        # (keyword, where, asked for, achieved), in the core's numbers
        asked: list[tuple[str, str, float, float]] = []
        if isinstance(term, design.ValuesTerm):
            got = final.value(b)
            asked += [
                ("TARGET", f"position {k + 1}", float(want), float(got[k]))
                for k, want in enumerate(term.values)
                if not math.isnan(want)
            ]
        elif isinstance(term, design.AtTerm):
            got_at = float(final.value(b)[term.position])
            asked.append(("TARGETAT", f"position {term.position + 1}", term.value, got_at))
        else:
            reference = buffer_name(model, term.reference)
            asked += [
                ("TARGETEXT", f"extremum of {reference}, {core_input(model, 1, at, '.6g')}", term.value, value)
                for at, value in extrema.get(id(term), [])
            ]
        out += [TargetRow(kw, line, name, unit, where, want * f, got * f) for kw, where, want, got in asked]
    return out


def _design(drawing: MechanismDrawing, x: np.ndarray) -> dict[str, Any]:
    shapes = drawing.shapes(x)
    return {
        "kinds": [s.kind for s in shapes],
        "roles": [s.role for s in shapes],
        "data": [nums(s.data) for s in shapes],
    }


def _pairs(points: list[tuple[float | None, float | None]]) -> list[list[float | None]]:
    return [[x, y] for x, y in points]


def target_points(
    optimum: Optimum, start: RunResult | None, final: RunResult, drawing: MechanismDrawing
) -> list[dict[str, Any]]:
    """The points both of whose co-ordinates are TARGETs (path generation): the points asked for, and the point's
    path over the motion in the start (when run) and final designs (core units, as the drawing)."""

    def path(r: RunResult | None, ix: int, iy: int) -> list[list[float | None]]:
        return [] if r is None else _pairs(list(zip(nums(r.coords[:, ix]), nums(r.coords[:, iy]), strict=True)))

    coordinate_of = {b.number: b.args[0] for b in final.storage.buffers if b.keyword == "BUFX0" and b.args}
    wanted: dict[int, np.ndarray] = {}
    for term in stated(optimum).problem.terms:
        if isinstance(term, design.ValuesTerm) and term.buffer in coordinate_of:
            wanted[coordinate_of[term.buffer]] = term.values
    out = []
    for ix, iy in drawing.points:
        if ix + 1 in wanted and iy + 1 in wanted:
            tx, ty = wanted[ix + 1], wanted[iy + 1]
            both = ~(np.isnan(tx) | np.isnan(ty))
            out.append(
                {
                    "name": point_name(final, ix + 1, iy + 1),
                    "target": _pairs(list(zip(nums(tx[both]), nums(ty[both]), strict=True))),
                    "start": path(start, ix, iy),
                    "final": path(final, ix, iy),
                }
            )
    return out


def optimisation_section(s: Optimum, start: RunResult | None, final: RunResult) -> dict[str, Any]:
    """The report's ``optimisation`` data of a deck's optimum: ``start`` is the run of the deck's own (start) design
    (None: not drawn), ``final`` the run of the final design."""
    model = final.model
    final_drawing = MechanismDrawing(final.model, final.coords)
    start_drawing = None if start is None else MechanismDrawing(start.model, start.coords)
    b = final_drawing.bounds([0])
    a = b if start_drawing is None else start_drawing.bounds([0])
    missed = unreached(s)
    left = None
    if missed is not None:
        left = (
            f"The targets are not all reached: the largest difference left is {missed_value(s, missed, model)} "
            f"(the target on line {missed[1]})."
        )
    return {
        "line": stated(s).block.line,
        "method": s.method,
        "success": s.success,
        "message": s.message,
        "runs": s.runs,
        "infeasible": s.infeasible,
        "seconds": num(s.seconds),
        "objective": {"start": exact(s.start_objective), "final": exact(s.objective)},
        "unreached": left,
        "history": {
            "iteration": [it.number for it in s.history],
            "objective": [exact(it.objective) for it in s.history],
            "violation": nums([it.violation for it in s.history]),
            "runs": [it.runs for it in s.history],
        },
        "variables": [
            {
                "name": v.name,
                "unit": "" if v.unit == "-" else v.unit,
                "start": exact(v.start),
                "final": exact(v.final),
                "lo": exact(v.lo),
                "hi": exact(v.hi),
                "active": v.active,
                "periodic": v.periodic,
            }
            for v in variable_rows(s, model)
        ],
        "targets": [
            {
                "keyword": t.keyword,
                "line": t.line,
                "name": t.name,
                "unit": t.unit,
                "where": t.where,
                "target": exact(t.target),
                "achieved": exact(t.achieved),
                "residual": exact(t.residual),
            }
            for t in target_rows(s, model)
        ],
        "drawing": {
            "start": None if start is None or start_drawing is None else _design(start_drawing, start.coords[0]),
            "final": _design(final_drawing, final.coords[0]),
            "bounds": nums([min(a[0], b[0]), max(a[1], b[1]), min(a[2], b[2]), max(a[3], b[3])]),
            "points": target_points(s, start, final, final_drawing),
        },
    }


def deck_section(optimum: Optimum, final: RunResult, memory_limit: int | None = None) -> dict[str, Any]:
    """:func:`optimisation_section` of a deck's optimisation: its start design is the deck's own, run here (it was
    feasible, or the optimisation could not have started; should its run fail all the same, the final design is
    drawn alone)."""
    import warnings

    import mechfem

    start: RunResult | None
    try:
        with warnings.catch_warnings():
            # A start design whose motion stops early is drawn at its position 1 all the same.
            warnings.simplefilter("ignore", mechfem.IncompleteRunWarning)
            start = mechfem.run_deck(stated(optimum).path, memory_limit=memory_limit)
    except mechfem.MechfemError:
        # The report is still worth writing: the section then draws the final design alone.
        start = None
    return optimisation_section(optimum, start, final)
