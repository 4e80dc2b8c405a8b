"""Optimising from the page, by changing the dimensions the user picked (:func:`mechfem.optimize`, exact gradients),
towards one of three targets:

* a path: a point of the mechanism should pass through points the user clicked, at input values left free
  (:class:`mechfem.design.timing.FreeTiming`): :func:`path_through`;
* an extremum: the largest or smallest value over the motion of a named output or a point's co-ordinate should reach
  a value, or be pushed up or down as far as the dimensions' ranges allow (a Python objective on the quantity's
  values and gradients at every position): :func:`extremum`;
* a transmission-angle bound: every transmission angle (:func:`mechfem.studio_app.view.transmission_pairs`, the
  deck's BUFTRA) stays within [lo, 180 deg - lo] at every position (:class:`mechfem.Bound` on
  :class:`mechfem.Transmission`), with the least change of the dimensions: :func:`transmission`; the bound may also
  go with an extremum.

Each iteration's design is run and sent to the page, so the mechanism is seen moving towards the target.
:func:`mechfem.optimize` works in the model's units, as the page does: nothing is converted on the way."""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from typing import Any

import numpy as np

from mechfem.design.engine import Iteration
from mechfem.design.optimise import Bound, Evaluated, Q, Target, Transmission, optimize
from mechfem.design.timing import FreeTiming
from mechfem.model.parts import Coordinate, Row
from mechfem.studio_app.session import Session
from mechfem.studio_app.view import transmission_pairs, view

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
    problem = {
        "targets": [Target(f"{point}.x", [x for x, _ in points]), Target(f"{point}.y", [y for _, y in points])],
        "timing": FreeTiming(phi.name, starts),
        "steps": steps,
        "progress": _shower(session, vary, push),
    }
    found = optimize(mech, box, **problem)  # type: ignore[arg-type]
    if result.report.stop_reason() is None and phi.is_angle and not _runs_whole_motion(found.mechanism):
        # The points are met at three input values, but the crank no longer turns all the way: search again among
        # the designs whose crank does (slower: each design is also turned once round).
        found = optimize(mech, box, full_rotation=True, **problem)  # type: ignore[arg-type]
    timing = [float(t) for t in found.timing] if found.timing is not None else None
    return {**_found(found, vary), "timing": timing}


def _shower(session: Session, vary: list[str], push: Callable[[dict[str, Any]], object]) -> Callable[[Iteration], None]:
    """The optimiser's progress callback: an ``iteration`` message with the design's view, at most every
    :data:`SHOW_EVERY` seconds."""
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

    return shown


def _checked_vary(session: Session, vary: list[str]) -> dict[str, tuple[float, float]]:
    if not vary:
        raise ValueError("pick at least one dimension to vary")
    xs, ys = _extent(session)
    size = float(np.hypot(np.ptp(xs), np.ptp(ys))) or 1.0
    return {name: _span(session, name, size) for name in vary}


def _extent(session: Session) -> tuple[np.ndarray, np.ndarray]:
    """The x and y co-ordinates of every point over the motion."""
    result = session.result
    nb = result.numbering
    xs = [result.coords[:, nb.coord_number[p.x] - 1] for p in session.mechanism.points if p.x in nb.coord_number]
    ys = [result.coords[:, nb.coord_number[p.y] - 1] for p in session.mechanism.points if p.y in nb.coord_number]
    return np.concatenate(xs) if xs else np.zeros(1), np.concatenate(ys) if ys else np.zeros(1)


def _half_turn(session: Session) -> float:
    return 180.0 if session.mechanism.units.angle == "deg" else math.pi


def _transmission_bounds(session: Session, lo: float) -> list[Bound]:
    """Every transmission angle within [lo, half a turn - lo] (``lo`` in the model's angle unit)."""
    pairs = transmission_pairs(session.mechanism)
    if not pairs:
        raise ValueError(
            "this mechanism has no transmission angle (a link jointed to the frame, not driven, and the coupler "
            "that moves it)"
        )
    half = _half_turn(session)
    if not 0.0 < lo < half / 2:
        raise ValueError(f"the least transmission angle is between 0 and {half / 2:g}, not {lo:g}")
    return [Bound(Transmission(c.name, link.name), lo, half - lo) for c, link, _ in pairs]


def transmission_range(session: Session) -> tuple[float, float] | None:
    """The least and largest transmission angle over the last good run (model's angle unit; None: none)."""
    from mechfem.results.designer import transmission_angle

    pairs = transmission_pairs(session.mechanism)
    if not pairs:
        return None
    mus = np.concatenate([transmission_angle(session.result, c, link) for c, link, _ in pairs])
    return float(np.nanmin(mus)), float(np.nanmax(mus))


def extremum(
    session: Session,
    quantity: str,
    which: str,
    goal: str,
    value: float | None,
    vary: list[str],
    push: Callable[[dict[str, Any]], object],
    transmission_lo: float | None = None,
    steps: int = 100,
) -> dict[str, Any]:
    """Optimises ``vary`` so that the ``which`` (``"max"`` or ``"min"``) of ``quantity`` over the motion reaches
    ``value`` (``goal`` ``"value"``, in the model's units) or is pushed ``"up"`` or ``"down"``; with
    ``transmission_lo``, every transmission angle also stays within [lo, half a turn - lo]."""
    if which not in ("max", "min"):
        raise ValueError(f"an extremum is the max or the min, not {which!r}")
    if goal not in ("value", "up", "down"):
        raise ValueError(f"an extremum reaches a value, or goes up or down, not {goal!r}")
    if goal == "value" and (value is None or not math.isfinite(value)):
        raise ValueError("give the value the extremum should reach")
    box = _checked_vary(session, vary)
    before = session.result.value(quantity)
    # The objective's unit: the quantity's span over the start design, so that it is about 1 at the start.
    span = max(float(np.nanmax(before) - np.nanmin(before)), abs(value or 0.0) * 1e-3, 1e-12)
    sign = 1.0 if which == "max" else -1.0
    q = Q(quantity)

    def objective(e: Evaluated) -> tuple[float, np.ndarray]:
        v, g = e.value(q), e.gradient(q)
        k = int(np.nanargmax(sign * v))
        if goal == "value":
            assert value is not None
            d = (v[k] - value) / span
            return d * d, 2.0 * d / span * g[k]
        up = 1.0 if goal == "up" else -1.0
        return -up * v[k] / span, -up * g[k] / span

    bounds = [] if transmission_lo is None else _transmission_bounds(session, transmission_lo)
    found = optimize(
        session.mechanism,
        box,
        objective=objective,
        quantities=[q],
        bounds=bounds,
        steps=steps,
        progress=_shower(session, vary, push),
    )
    return _found(found, vary)


def transmission(
    session: Session, lo: float, vary: list[str], push: Callable[[dict[str, Any]], object], steps: int = 100
) -> dict[str, Any]:
    """Optimises ``vary`` so that every transmission angle stays within [lo, half a turn - lo] (``lo`` in the
    model's angle unit) with the least change of the dimensions, each measured against its range."""
    box = _checked_vary(session, vary)
    bounds = _transmission_bounds(session, lo)
    width = np.array([hi - lo_ for lo_, hi in box.values()])
    start: list[np.ndarray] = []

    def least_change(e: Evaluated) -> tuple[float, np.ndarray]:
        # The optimiser's first design is the start design.
        if not start:
            start.append(np.array(e.x, dtype=np.float64))
        d = (np.asarray(e.x, dtype=np.float64) - start[0]) / width
        return float(d @ d), 2.0 * d / width

    found = optimize(
        session.mechanism,
        box,
        objective=least_change,
        bounds=bounds,
        steps=steps,
        progress=_shower(session, vary, push),
    )
    return _found(found, vary)


def _found(found: Any, vary: list[str]) -> dict[str, Any]:
    return {
        "values": {name: float(found.values[name]) for name in vary},
        "objective": float(found.objective),
        "start_objective": float(found.start_objective),
        "iterations": len(found.history),
        "success": bool(found.success),
        "message": str(found.message),
    }


def _runs_whole_motion(mech: Any) -> bool:
    try:
        return Session(mech).result.report.stop_reason() is None
    except Exception:  # a design that cannot even be assembled does not run its motion
        return False


__all__ = ["extremum", "path_through", "transmission", "transmission_range"]
