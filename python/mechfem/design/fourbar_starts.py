"""Start designs of a four-bar that can do the problem's crank motion, drawn as such, and their position 1 in
closed form.

A start box of a four-bar's dimensions is mostly made of linkages that cannot run through the targets: with the
lengths drawn independently, half or more of the box cannot turn the crank through the motion, and with the frame
pivots free as well four draws in five cannot. Drawing those and throwing them away wastes the draws; here the
draws are made so that the dyad closes over the crank's whole sweep by construction, and every drawn design is
assembled from its own closed-form position 1.

* **Recognised mechanism.** Exactly three elements: a crank (a bar from a fixed point, its angle the only input,
  in radians), a coupler (a bar or a ternary-2 element) from the crank's moving end A to B, and a rocker (a bar
  from B to a fixed point B0); every length (and the coupler point's u, v) a prescribed value. Anything else is
  drawn in the box as before (:mod:`mechfem.design.multistart`).
* **Sweep.** The crank angles the problem turns the crank through (:func:`sweep`): the motion's, with free timing
  from the first to the last start value, with ``full_rotation`` (or a motion of a turn or more) a whole turn.
* **Draws.** One scrambled Halton point per start in the unit cube of the box (as for any mechanism), mapped to the
  box: every variable but the three lengths scaled to its range (a frame pivot B0 so far from A0 that no lengths
  of the ranges span it moved towards A0 until some do); then the lengths in turn, each within the part of its
  range where the dyad can still close over the sweep given the frame and the lengths before it. Over the sweep
  the distance |A B0| runs through [e, s] (for a whole turn [|d - a|, d + a], d = |A0 B0|), and the dyad closes
  all the way while ``|b - c| <= e`` and ``b + c >= s`` (for a whole turn: Grashof's condition with the crank or
  the frame the shortest link). Given a, the coupler b has an interval of such values, and given a and b the
  rocker c has one; the crank's own feasible values are found on a grid of its range. A margin of 1 % of the frame
  keeps the draws off the limit positions, where the dyad folds flat; closing over the whole sweep, the dyad meets
  none, so a draw stays on its branch through the motion.
* **Assembly.** The drawn design's position 1 is computed in closed form at the crank's start angle: A on the crank
  circle, B the intersection of the circles (A, b) and (B0, c) on the side of the line A -> B0 where the
  mechanism's own position 1 has it (its assembly branch), the coupler point from u and v. Those are the start's
  estimates; one solve of position 1 from them confirms them.
"""

from __future__ import annotations

import copy
import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, TypeAlias

import numpy as np

from mechfem.errors import MechfemError
from mechfem.model.motion import By, To

if TYPE_CHECKING:
    from mechfem.model.mechanism import Mechanism

MARGIN = 0.01
"""Of the frame length: how far the drawn lengths stay inside Grashof's condition."""
GRID = 257
"""Crank lengths looked at across its range to find the values that admit a turning crank."""


@dataclass(frozen=True)
class FourBar:
    """The names of a recognised four-bar's parts: the input (crank angle) row, the length rows of crank, coupler
    and rocker, the coupler point's u and v rows (empty without one), the points A0, A, B, B0 and the coupler point
    P, and whether the crank's angle is that of A0 -> A (else A -> A0) and the coupler's frame is at A (else at
    B)."""

    input: str
    lengths: tuple[str, str, str]
    uv: tuple[str, str] | tuple[()]
    a0: str
    a: str
    b: str
    b0: str
    p: str
    crank_from_a0: bool
    coupler_at_a: bool


def recognised(mech: Mechanism) -> FourBar | None:
    """The four-bar that ``mech`` is, or None."""
    if len(mech.elements) != 3 or len(mech.inputs) != 1 or mech.units.angle != "rad":
        return None
    drive = mech.inputs[0]
    if len(drive.terms) != 1 or drive.terms[0][1].form != "ANGB":
        return None
    crank = drive.terms[0][1].element
    if crank.type != "BIN":
        return None
    ends = crank.points
    fixed = [q for q in ends if q.fixed]
    if len(fixed) != 1:
        return None
    a0 = fixed[0]
    a = ends[1] if ends[0] is a0 else ends[0]
    others = [e for e in mech.elements if e is not crank]
    coupler = next((e for e in others if e.type in ("BIN", "TR2") and any(q is a for q in e.points)), None)
    if coupler is None:
        return None
    rocker = next(e for e in others if e is not coupler)
    bar = coupler.points[:2]
    if rocker.type != "BIN" or a not in bar:
        return None
    b = bar[1] if bar[0] is a else bar[0]
    rocker_fixed = [q for q in rocker.points if q.fixed]
    if len(rocker_fixed) != 1 or not any(q is b for q in rocker.points) or b.fixed or a.fixed:
        return None
    b0 = rocker_fixed[0]
    rows = {(r.terms[0][1].element.name, r.terms[0][1].form): r for r in mech.prescribed if len(r.terms) == 1}
    try:
        lengths = tuple(rows[(e.name, "LENL")].name for e in (crank, coupler, rocker))
    except KeyError:
        return None
    uv: tuple[str, str] | tuple[()] = ()
    p = b
    if coupler.type == "TR2":
        if (coupler.name, "LENU") not in rows or (coupler.name, "LENV") not in rows:
            return None
        uv = (rows[(coupler.name, "LENU")].name, rows[(coupler.name, "LENV")].name)
        p = coupler.points[2]
    if any(q.x.name != f"{q.name}.x" or q.y.name != f"{q.name}.y" for q in (a0, a, b, b0, p)):
        return None
    moving = {c.name for c in mech.coordinates if not c.fixed}
    if moving != {q.x.name for q in (a, b, p)} | {q.y.name for q in (a, b, p)}:
        return None
    return FourBar(
        drive.name,
        (lengths[0], lengths[1], lengths[2]),
        uv,
        a0.name,
        a.name,
        b.name,
        b0.name,
        p.name,
        crank.points[0] is a0,
        coupler.points[0] is a,
    )


def sweep(fb: FourBar, mech: Mechanism, kwargs: Mapping[str, Any]) -> tuple[float, float] | None:
    """The crank angles the problem turns the crank through, relative to its start value: (lowest, highest); None
    for a whole turn (``full_rotation``, or a motion of a turn or more)."""
    if kwargs.get("full_rotation"):
        return None
    start = float(mech[fb.input].value)
    free = kwargs.get("timing")
    if free is not None:
        offsets = [float(t) - start for t in free.starts] + [0.0]
    else:
        motion = kwargs.get("motion") or mech.motion
        if motion is None or len(motion.inputs) != 1:
            return None
        step = next(iter(motion.inputs.values()))
        if isinstance(step, By):
            offsets = [0.0, float(step.value)]
        elif isinstance(step, To):
            offsets = [0.0, float(step.value) - start]
        else:
            return None
    lo, hi = min(offsets), max(offsets)
    return None if hi - lo >= 2.0 * math.pi else (lo, hi)


def _value(mech: Mechanism, values: Mapping[str, float], name: str) -> float:
    return float(values[name]) if name in values else float(mech[name].value)


Cosines: TypeAlias = tuple[float, float]
"""The largest and smallest cosine of the angle between the crank A0 -> A and the frame A0 -> B0 over the sweep."""


def _cosines(sweep: tuple[float, float] | None, theta: float, phi: float) -> Cosines:
    """:data:`Cosines` for a crank at ``theta + sweep`` (None: a whole turn) and a frame at angle ``phi``."""
    if sweep is None:
        return 1.0, -1.0
    lo, hi = theta + sweep[0] - phi, theta + sweep[1] - phi
    ends = (math.cos(lo), math.cos(hi))
    turns = math.floor(hi / (2.0 * math.pi))
    top = 1.0 if turns * 2.0 * math.pi >= lo else max(ends)
    bottom = -1.0 if math.floor((hi - math.pi) / (2.0 * math.pi)) * 2.0 * math.pi + math.pi >= lo else min(ends)
    return top, bottom


def _reach(d: float, a: np.ndarray, cos: Cosines) -> tuple[np.ndarray, np.ndarray]:
    """The shortest and longest distance |A B0| over the sweep, for each crank ``a``, with the margin: e and s."""
    m = MARGIN * d
    near = np.sqrt(np.maximum(a * a + d * d - 2.0 * a * d * cos[0], 0.0))
    far = np.sqrt(a * a + d * d - 2.0 * a * d * cos[1])
    return near - m, far + m


def _crank_lengths(
    d: float, ranges: tuple[tuple[float, float], tuple[float, float], tuple[float, float]], cos: Cosines
) -> np.ndarray:
    """The crank lengths on a grid of its range for which some coupler and rocker in their ranges close the dyad
    over the whole sweep."""
    (a_lo, a_hi), (b_lo, b_hi), (c_lo, c_hi) = ranges
    a = np.linspace(a_lo, a_hi, GRID) if a_hi > a_lo else np.array([a_lo])
    b_low, b_high = _coupler_interval(d, a, (b_lo, b_hi), (c_lo, c_hi), cos)
    return np.asarray(a[(b_low <= b_high) & (a > 0.0)])


def _coupler_interval(
    d: float, a: np.ndarray | float, b_range: tuple[float, float], c_range: tuple[float, float], cos: Cosines
) -> tuple[np.ndarray, np.ndarray]:
    """The couplers b (an interval per crank a) that some rocker in its range completes to a dyad that closes
    over the sweep: with e and s the shortest and longest |A B0| (:func:`_reach`), c must lie in
    [max(b - e, s - b, c_lo), min(b + e, c_hi)]."""
    a = np.asarray(a, dtype=float)
    e, s = _reach(d, a, cos)
    c_lo, c_hi = c_range
    low = np.maximum.reduce([np.full_like(a, b_range[0]), (s - e) / 2.0, s - c_hi, c_lo - e])
    high = np.minimum(np.full_like(a, b_range[1]), c_hi + e)
    return low, np.where(e >= 0.0, high, -np.inf)


def draws(
    fb: FourBar,
    mech: Mechanism,
    box: Mapping[str, tuple[float, float]],
    n: int,
    seed: int | None,
    sweep: tuple[float, float] | None = None,
) -> list[tuple[dict[str, float], str]]:
    """``n`` start designs in ``box`` (name -> (lo, hi)) whose dyad closes over the crank's ``sweep`` (:func:`sweep`;
    None: a whole turn), from a scrambled Halton sequence taken in the order of the names; each with "" or, for a
    draw whose frame admits no such linkage within the ranges, the reason (its values are then the plain scaled
    draw)."""
    from scipy.stats import qmc

    from mechfem.design.multistart import unit_draws

    if n <= 0:
        return []
    names, lo, hi, unit = unit_draws(box, n, seed)
    out: list[tuple[dict[str, float], str]] = []
    for row in unit:
        draw = dict(zip(names, map(float, qmc.scale(row[None, :], lo, hi)[0]), strict=True))
        at = dict(zip(names, map(float, row), strict=True))
        out.append(_lengths(fb, mech, box, draw, at, sweep))
    return out


def _lengths(
    fb: FourBar,
    mech: Mechanism,
    box: Mapping[str, tuple[float, float]],
    draw: dict[str, float],
    at: Mapping[str, float],
    sweep: tuple[float, float] | None,
) -> tuple[dict[str, float], str]:
    """``draw`` with its lengths moved to where the dyad closes over the sweep, each by its own unit co-ordinate
    ``at``."""
    x0, y0 = (_value(mech, draw, f"{fb.a0}.{k}") for k in "xy")
    x1, y1 = (_value(mech, draw, f"{fb.b0}.{k}") for k in "xy")
    d = math.hypot(x1 - x0, y1 - y0)
    theta = _value(mech, draw, fb.input) + (0.0 if fb.crank_from_a0 else math.pi)
    cos = _cosines(sweep, theta, math.atan2(y1 - y0, x1 - x0))
    fixed = {name: _value(mech, draw, name) for name in fb.lengths}
    ranges = tuple((box[k] if k in box else (fixed[k], fixed[k])) for k in fb.lengths)
    r3 = (ranges[0], ranges[1], ranges[2])
    cranks = _crank_lengths(d, r3, cos)
    pivot = (f"{fb.b0}.x", f"{fb.b0}.y")
    if cranks.size == 0 and d > 0.0 and all(k in box for k in pivot):
        # A frame too long for any linkage of the ranges: B0 moves towards A0, within its box, to the longest
        # frame that admits a turning crank, found on a grid of the way.
        (xl, xh), (yl, yh) = box[pivot[0]], box[pivot[1]]
        for t in np.linspace(1.0, 0.0, GRID)[1:-1]:
            x, y = x0 + t * (x1 - x0), y0 + t * (y1 - y0)
            if not (xl <= x <= xh and yl <= y <= yh):
                break
            cranks = _crank_lengths(d * t, r3, cos)
            if cranks.size:
                x1, y1 = x, y
                draw[pivot[0]], draw[pivot[1]], d = x1, y1, d * t
                break
    if d <= 0.0 or cranks.size == 0:
        return draw, f"no crank, coupler and rocker within their ranges close over the motion on a frame of {d:.6g}"
    name_a, name_b, name_c = fb.lengths
    a = float(cranks[min(int(at.get(name_a, 0.5) * cranks.size), cranks.size - 1)])
    b_low, b_high = (float(v[0]) for v in _coupler_interval(d, np.array([a]), r3[1], r3[2], cos))
    b = b_low + at.get(name_b, 0.5) * (b_high - b_low)
    e, s = (float(v[0]) for v in _reach(d, np.array([a]), cos))
    c_low, c_high = max(b - e, s - b, r3[2][0]), min(b + e, r3[2][1])
    c = c_low + at.get(name_c, 0.5) * (c_high - c_low)
    for name, v in ((name_a, a), (name_b, b), (name_c, c)):
        if name in box:
            draw[name] = v
    return draw, ""


def side(fb: FourBar, mech: Mechanism) -> float:
    """+1 when B lies to the left of the line A -> B0 in the mechanism's (solved) position 1, -1 to the right."""
    ax, ay = (float(mech[f"{fb.a}.{k}"].value) for k in "xy")
    bx, by = (float(mech[f"{fb.b}.{k}"].value) for k in "xy")
    x1, y1 = (float(mech[f"{fb.b0}.{k}"].value) for k in "xy")
    return 1.0 if (x1 - ax) * (by - ay) - (y1 - ay) * (bx - ax) >= 0.0 else -1.0


def position_one(fb: FourBar, mech: Mechanism, branch: float) -> dict[str, float] | str:
    """The moving co-ordinates of ``mech``'s position 1 in closed form, B on side ``branch`` of A -> B0; or why
    the dyad does not close there."""
    x0, y0 = (float(mech[f"{fb.a0}.{k}"].value) for k in "xy")
    x1, y1 = (float(mech[f"{fb.b0}.{k}"].value) for k in "xy")
    a, b, c = (float(mech[name].value) for name in fb.lengths)
    theta = float(mech[fb.input].value) + (0.0 if fb.crank_from_a0 else math.pi)
    ax, ay = x0 + a * math.cos(theta), y0 + a * math.sin(theta)
    dx, dy = x1 - ax, y1 - ay
    dist = math.hypot(dx, dy)
    if dist == 0.0:
        return "the crank's end lies on the rocker's pivot"
    along = (b * b - c * c + dist * dist) / (2.0 * dist)
    h2 = b * b - along * along
    if not h2 > 0.0:
        return f"the coupler ({b:.6g}) and rocker ({c:.6g}) do not reach across {dist:.6g} at the crank's start"
    h = branch * math.sqrt(h2)
    ex, ey = dx / dist, dy / dist
    bx, by = ax + along * ex - h * ey, ay + along * ey + h * ex
    out = {f"{fb.a}.x": ax, f"{fb.a}.y": ay, f"{fb.b}.x": bx, f"{fb.b}.y": by}
    if fb.uv:
        u, v = (float(mech[name].value) for name in fb.uv)
        (ox, oy), (tx, ty) = ((ax, ay), (bx, by)) if fb.coupler_at_a else ((bx, by), (ax, ay))
        fx, fy = (tx - ox) / b, (ty - oy) / b
        out |= {f"{fb.p}.x": ox + u * fx - v * fy, f"{fb.p}.y": oy + u * fy + v * fx}
    return out


def assembled(fb: FourBar, mechanism: Mechanism, branch: float, values: Mapping[str, float]) -> Mechanism | str:
    """The mechanism with ``values`` set and its moving co-ordinates at that design's position 1 on side ``branch``
    (closed form, then confirmed by one solve of position 1); or why it cannot be assembled."""
    from mechfem.design.multistart import POSITION_ONE_STEP, _position_one
    from mechfem.model.motion import Motion

    at = copy.deepcopy(mechanism)
    for name, v in values.items():
        at.set(name, float(v))
    closed = position_one(fb, at, branch)
    if isinstance(closed, str):
        return closed
    for name, x in closed.items():
        at[name].value = x
    moving = [c.name for c in at.coordinates if not c.fixed]
    try:
        solved = _position_one(at, moving, Motion.by(1, POSITION_ONE_STEP))
    except MechfemError as e:
        return f"position 1 does not solve from its closed form: {e}"
    for name, x in zip(moving, solved, strict=True):
        at[name].value = x
    if side(fb, at) != branch:
        return "position 1 solves on the other assembly branch"
    return at


__all__ = ["FourBar", "assembled", "draws", "position_one", "recognised", "side", "sweep"]
