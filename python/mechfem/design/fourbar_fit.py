"""Start designs of a four-bar with free timing fitted to the target points: coupler curves drawn, each placed
on the points, the best placed ones the starts.

With free timing a start needs the crank angle at each point as well as the dimensions, and a start whose angles
are not those at which its coupler curve comes near the points begins far from every good design: the local
optimiser then stops at the first wall it meets (for the straight line with the crank turning fully, Grashof's
condition) with an error of 1e-6 to 1e-4 where exact solutions exist. Here every start is made of a drawn linkage
and of the angles at which its curve passes the points, the curve placed on them first:

* **Draws.** A scrambled Halton point per draw in the unit cube of the start box (as every draw,
  :mod:`mechfem.design.multistart`). The frame is drawn by its length and angle (the unit co-ordinates of B0.x and
  B0.y): the length within the frame length's bound when one is stated (:class:`~mechfem.design.frame_length.
  FrameLength`), else within the largest range of the three lengths; the crank, coupler and rocker then as
  :func:`mechfem.design.fourbar_starts.draws` draws them, so that the dyad closes over a whole turn.
* **The coupler curve** of the draw on the mechanism's assembly branch, at ``SAMPLES`` crank angles over the turn.
* **Placed on the points.** The points are laid along the curve in order, spaced as they are along their own
  polyline, over a share of the curve's length from a starting sample (``SHARES`` x every third sample); for each
  laying the similarity (a turn, a scale and a shift, no mirror) that carries the laid curve points nearest the
  targets in least squares is found in closed form (complex numbers: z = sum conj(x) y / sum |x|^2 about the
  centroids). The best laying places the linkage: its pivots carried by the similarity, its lengths and u, v
  scaled, the crank angles turned with it, the timing those of the laid samples (in order along the turn).
* **Kept.** A placed linkage outside the start box or the frame length's bound is left out; the others are ranked
  by the sum of squared distances of the laying, and the best are screened and assembled as every four-bar start.

It applies when the timing is free, the targets include the coupler point's x and y at every point, and the
pivots, the three lengths and the coupler point's u and v all vary (the similarity then stays within the design's
variables); otherwise the starts are drawn as :mod:`mechfem.design.multistart` draws them.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from mechfem.design import fourbar_starts

if TYPE_CHECKING:
    from mechfem.design.fourbar_starts import FourBar
    from mechfem.model.mechanism import Mechanism

SAMPLES = 120
"""Crank angles over the turn at which a drawn linkage's coupler curve is computed."""
SHARES = (0.15, 0.25, 0.4, 0.6, 0.8, 0.95)
"""Shares of the coupler curve's length the points are laid over."""
POOL = 20
"""Linkages drawn per start asked for; the best placed of them are the starts."""


@dataclass(frozen=True)
class Fit:
    """What the starts are fitted to: the target points (N x 2), whether the timing is ordered, and the frame
    length's bound (None: not stated)."""

    points: np.ndarray
    ordered: bool
    frame: tuple[float, float] | None


def applicable(fb: FourBar, vary: Mapping[str, object], kwargs: Mapping[str, Any]) -> Fit | None:
    """The :class:`Fit` of the problem, when its starts can be fitted to its targets (see the module); else None."""
    from mechfem.design.frame_length import FrameLength
    from mechfem.design.optimise import Target

    timing = kwargs.get("timing")
    if timing is None or timing.input != fb.input or timing.span is not None or not fb.uv:
        return None
    needed = [f"{p}.{k}" for p in (fb.a0, fb.b0) for k in "xy"] + [*fb.lengths, *fb.uv]
    if any(vary.get(name) is None for name in needed):
        return None
    values: dict[str, np.ndarray] = {}
    for t in kwargs.get("targets") or ():
        if isinstance(t, Target) and isinstance(t.quantity, str):
            values[t.quantity] = np.asarray(t.values, dtype=np.float64)
    x, y = values.get(f"{fb.p}.x"), values.get(f"{fb.p}.y")
    n = len(timing.starts)
    if x is None or y is None or len(x) != n or len(y) != n or not np.all(np.isfinite(x) & np.isfinite(y)):
        return None
    frame = None
    for bd in kwargs.get("bounds") or ():
        if isinstance(bd.quantity, FrameLength) and {bd.quantity.first, bd.quantity.second} == {fb.a0, fb.b0}:
            frame = (max(float(bd.lo), 0.0), float(bd.hi))
    return Fit(np.column_stack([x, y]), bool(timing.ordered), frame)


def curve(
    fb: FourBar, design: Mapping[str, float], branch: float, samples: int = SAMPLES
) -> tuple[np.ndarray, np.ndarray] | None:
    """The crank angles (A0 -> A, from the x axis) and the coupler point there (samples x 2) over a whole turn, B on
    side ``branch`` of A -> B0 (as :func:`mechfem.design.fourbar_starts.position_one`); None where the dyad does
    not close all the way."""
    x0, y0, x1, y1 = (design[f"{p}.{k}"] for p in (fb.a0, fb.b0) for k in "xy")
    a, b, c = (design[name] for name in fb.lengths)
    u, v = (design[name] for name in fb.uv)
    phi = np.linspace(0.0, 2.0 * math.pi, samples, endpoint=False)
    ax, ay = x0 + a * np.cos(phi), y0 + a * np.sin(phi)
    dx, dy = x1 - ax, y1 - ay
    dist = np.hypot(dx, dy)
    if not np.all(dist > 0.0):
        return None
    along = (b * b - c * c + dist * dist) / (2.0 * dist)
    h2 = b * b - along * along
    if not np.all(h2 > 0.0):
        return None
    h = branch * np.sqrt(h2)
    ex, ey = dx / dist, dy / dist
    bx, by = ax + along * ex - h * ey, ay + along * ey + h * ex
    (ox, oy), (tx, ty) = ((ax, ay), (bx, by)) if fb.coupler_at_a else ((bx, by), (ax, ay))
    fx, fy = (tx - ox) / b, (ty - oy) / b
    return phi, np.column_stack([ox + u * fx - v * fy, oy + u * fy + v * fx])


def laid(points: np.ndarray, targets: np.ndarray) -> tuple[float, np.ndarray, complex, complex]:
    """The best laying of ``targets`` along the closed curve ``points``: (sum of squared distances, the sample of
    each target, z, t) with the similarity w -> z w + t (complex co-ordinates) carrying the samples nearest the
    targets."""
    m = len(points)
    closed = np.vstack([points, points[:1]])
    arc = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(closed, axis=0).T))])
    length = arc[-1]
    steps = np.hypot(*np.diff(targets, axis=0).T)
    along = np.concatenate([[0.0], np.cumsum(steps)])
    along = along / along[-1] if along[-1] > 0.0 else along
    p = points[:, 0] + 1j * points[:, 1]
    y = targets[:, 0] + 1j * targets[:, 1]
    yc = y - y.mean()
    best: tuple[float, np.ndarray, complex, complex] = (math.inf, np.zeros(len(y), dtype=int), 1.0 + 0j, 0j)
    first = np.arange(0, m, 3)
    for share in SHARES:
        at = (arc[first][:, None] + share * length * along[None, :]) % length
        idx = (np.searchsorted(arc, at, side="right") - 1) % m  # layings x targets
        x = p[idx]
        xc = x - x.mean(axis=1, keepdims=True)
        den = np.sum(np.abs(xc) ** 2, axis=1)
        z = np.where(den > 0.0, np.sum(np.conj(xc) * yc[None, :], axis=1) / np.maximum(den, 1e-300), 1.0)
        t = y.mean() - z * x.mean(axis=1)
        err = np.sum(np.abs(z[:, None] * x + t[:, None] - y[None, :]) ** 2, axis=1)
        k = int(np.argmin(err))
        if err[k] < best[0]:
            best = (float(err[k]), idx[k], complex(z[k]), complex(t[k]))
    return best


def placed(
    fb: FourBar, design: Mapping[str, float], branch: float, fit: Fit, crank_offset: float
) -> tuple[float, dict[str, float], list[float]] | None:
    """``design`` placed on the targets: (the laying's sum of squared distances, the placed design, the input at
    each point); None when its dyad does not close over the turn. ``crank_offset`` is the input's value minus the
    angle of A0 -> A (0, or pi for a crank measured A -> A0)."""
    got = curve(fb, design, branch)
    if got is None:
        return None
    phi, points = got
    err, idx, z, t = laid(points, fit.points)
    turn = math.atan2(z.imag, z.real)
    scale = abs(z)
    out = dict(design)
    for p in (fb.a0, fb.b0):
        w = z * complex(design[f"{p}.x"], design[f"{p}.y"]) + t
        out[f"{p}.x"], out[f"{p}.y"] = w.real, w.imag
    for name in (*fb.lengths, *fb.uv):
        out[name] = design[name] * scale
    # In order along the turn: each point's sample is reached from the one before by going forward.
    ahead = np.concatenate([[0], np.mod(np.diff(idx), len(phi))])
    angles = phi[idx[0]] + turn + crank_offset + np.cumsum(ahead) * (2.0 * math.pi / len(phi))
    return err, out, [float(a) for a in angles]


def starts(
    fb: FourBar,
    mechanism: Mechanism,
    box: Mapping[str, tuple[float, float]],
    fit: Fit,
    branch: float,
    n: int,
    seed: int | None,
) -> tuple[list[tuple[float, dict[str, float], list[float]]], list[tuple[dict[str, float], str]]]:
    """The ``POOL * n`` draws of ``box`` placed on the targets, the placed ones within the box and the frame's bound
    best first ``(laying error, design, timing)``; and the draws left out with the reason."""
    from mechfem.design.multistart import unit_draws

    names, lo, hi, unit = unit_draws(box, POOL * n, seed)
    frame = fit.frame
    if frame is None:
        frame = (0.0, max(box[name][1] for name in fb.lengths))
    bx, by = f"{fb.b0}.x", f"{fb.b0}.y"
    # The lengths are fitted to the frame drawn by its length and angle, wherever that puts B0.
    free = {**box, bx: (-math.inf, math.inf), by: (-math.inf, math.inf)}
    offset = 0.0 if fb.crank_from_a0 else math.pi
    needed = [f"{p}.{k}" for p in (fb.a0, fb.b0) for k in "xy"] + [*fb.lengths, *fb.uv]
    kept: list[tuple[float, dict[str, float], list[float]]] = []
    left: list[tuple[dict[str, float], str]] = []
    for row in unit:
        at = dict(zip(names, map(float, row), strict=True))
        draw = {k: float(a + r * (b - a)) for k, r, a, b in zip(names, row, lo, hi, strict=True)}
        d = frame[0] + at[bx] * (frame[1] - frame[0])
        angle = 2.0 * math.pi * at[by]
        draw[bx] = draw[f"{fb.a0}.x"] + d * math.cos(angle)
        draw[by] = draw[f"{fb.a0}.y"] + d * math.sin(angle)
        design, why = fourbar_starts._lengths(fb, mechanism, free, draw, at, None)
        design = {**{k: float(mechanism[k].value) for k in needed}, **design}
        if why:
            left.append((design, why))
            continue
        got = placed(fb, design, branch, fit, offset)
        if got is None:
            left.append((design, "its dyad does not close over a whole turn"))
            continue
        out = got[1]
        if not _within(out, box, fb, fit.frame):
            left.append((out, "placed on the targets, it leaves the start box or the frame length's bound"))
            continue
        kept.append(got)
    kept.sort(key=lambda k: k[0])
    return kept, left


def _within(
    design: Mapping[str, float], box: Mapping[str, tuple[float, float]], fb: FourBar, frame: tuple[float, float] | None
) -> bool:
    if not all(lo <= design[k] <= hi for k, (lo, hi) in box.items() if k in design):
        return False
    if frame is None:
        return True
    d = math.hypot(design[f"{fb.b0}.x"] - design[f"{fb.a0}.x"], design[f"{fb.b0}.y"] - design[f"{fb.a0}.y"])
    return frame[0] <= d <= frame[1]


def timings(timing: Any, angles: Sequence[float]) -> Any:
    """The free timing ``timing`` starting at ``angles`` instead."""
    import dataclasses

    return dataclasses.replace(timing, starts=list(angles))


__all__ = ["POOL", "SAMPLES", "SHARES", "Fit", "applicable", "curve", "laid", "placed", "starts", "timings"]
