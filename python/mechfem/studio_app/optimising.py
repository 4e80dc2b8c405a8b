"""Optimising from the page: a point of the mechanism should pass through points the user clicked, at input values
left free (:class:`mechfem.timing.FreeTiming`), by changing the dimensions the user picked (:func:`mechfem.optimize`,
exact gradients). Each iteration's design is run and sent to the page, so the mechanism is seen moving towards the
points."""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from typing import Any

import numpy as np

from mechfem.design import Iteration
from mechfem.optimise import Target, optimize
from mechfem.parts import Coordinate, Row
from mechfem.studio_app.session import Session
from mechfem.studio_app.view import view
from mechfem.timing import FreeTiming

#: Least time between two iterations shown on the page, in seconds.
SHOW_EVERY = 0.25


def _span(session: Session, name: str, size: float) -> tuple[float, float]:
    """The range a dimension may take: a length within half and twice its value, an angle within 90 degrees of it,
    a frame pivot's co-ordinate within the mechanism's size of it."""
    obj = session.mechanism.find(name)
    value = float(obj.value)
    if isinstance(obj, Row) and obj.is_angle:
        quarter = 90.0 if session.mechanism.units.angle == "deg" else math.pi / 2
        return value - quarter, value + quarter
    if isinstance(obj, Row) and value > 0:
        return 0.5 * value, 2.0 * value
    if isinstance(obj, Coordinate | Row):
        return value - size, value + size
    raise ValueError(f"{name!r} cannot be varied")


def path_through(
    session: Session,
    point: str,
    points: list[tuple[float, float]],
    vary: list[str],
    push: Callable[[dict[str, Any]], object],
    steps: int = 200,
) -> dict[str, Any]:
    """Optimises ``vary`` so that ``point`` passes through ``points``; returns the values found and how well.
    ``push`` gets an ``iteration`` message (with the design's view) as the optimiser goes."""
    if len(points) < 1:
        raise ValueError("click at least one point for the path to pass through")
    if not vary:
        raise ValueError("pick at least one dimension to vary")
    mech, result = session.mechanism, session.result
    inputs = [r for r in mech.rows if r.kind == "input"]
    if len(inputs) != 1:
        raise ValueError("a path target needs a mechanism with one input")
    phi = inputs[0]
    target = mech.find(point)
    nb = result.numbering
    xs = result.coords[:, nb.coord_number[target.x] - 1]
    ys = result.coords[:, nb.coord_number[target.y] - 1]
    along = np.asarray(result.input(phi), dtype=np.float64)
    # Each clicked point starts at the input value where the path passes nearest to it.
    starts = [float(along[int(np.argmin(np.hypot(xs - x, ys - y)))]) for x, y in points]
    size = float(np.hypot(np.ptp(xs), np.ptp(ys))) or 1.0
    box = {name: _span(session, name, size) for name in vary}
    last = [0.0]

    def shown(it: Iteration) -> None:
        now = time.monotonic()
        if now - last[0] < SHOW_EVERY or len(it.x) < len(vary):
            return
        last[0] = now
        try:
            trial = session.mechanism.variant(dict(zip(vary, (float(v) for v in it.x[: len(vary)]), strict=True)))
            shown_session = Session(trial, session.deck)
        except Exception:  # a design the optimiser looks at need not assemble: it is then not shown
            return
        push({"type": "iteration", "number": it.number, "objective": it.objective, "design": view(shown_session)})

    problem = {
        "targets": [Target(f"{point}.x", [x for x, _ in points]), Target(f"{point}.y", [y for _, y in points])],
        "timing": FreeTiming(phi.name, starts),
        "steps": steps,
        "progress": shown,
    }
    found = optimize(mech, box, **problem)  # type: ignore[arg-type]
    if result.report.stop_reason() is None and phi.is_angle and not _runs_whole_motion(found.mechanism):
        # The points are met at three input values, but the crank no longer turns all the way: search again among
        # the designs whose crank does (slower: each design is also turned once round).
        found = optimize(mech, box, full_rotation=True, **problem)  # type: ignore[arg-type]
    return {
        "values": {name: float(found.values[name]) for name in vary},
        "objective": float(found.objective),
        "start_objective": float(found.start_objective),
        "iterations": len(found.history),
        "success": bool(found.success),
        "message": str(found.message),
        "timing": [float(t) for t in found.timing] if found.timing is not None else None,
    }


def _runs_whole_motion(mech: Any) -> bool:
    try:
        return Session(mech).result.report.stop_reason() is None
    except Exception:  # a design that cannot even be assembled does not run its motion
        return False


__all__ = ["path_through"]
