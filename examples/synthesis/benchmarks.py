"""The classic four-bar path-synthesis benchmarks, each stated as a problem ``mechfem.optimize`` solves.

The definitions (points, timing, ranges, constraints) are those of the code published with Nguyen-Van, Lieu,
Xuan-Mung and Nguyen, "A New Study on Optimization of Four-Bar Mechanisms Based on a Hybrid-Combined Differential
Evolution and Jaya Algorithm", Symmetry 14 (2022) 381, https://doi.org/10.3390/sym14020381: the repository
sy-nguyen-van/Dimensional_Synthesis_Four_Bar_Mechanisms on GitHub, files ``src/cases/case1.py`` ... ``case5.py``
(points, timing, constraints) and ``src/config.py`` (ranges). Its cases are the classic ones of the literature:

* ``five_points`` (its Case2; Cabrera, Simon and Prado 2002): five points, prescribed crank angles pi/6, pi/4,
  pi/3, 5 pi/12, pi/2; A0 at the origin and the frame along x; the frame, crank, coupler and rocker lengths within
  [0, 50], the coupler point's u and v within [-50, 50]; Grashof.
* ``straight_line`` (its Case1; Kunjur and Krishnamurty 1997, Cabrera et al. 2002): six points on the vertical
  line x = 20, y = 20, 25, ..., 45, crank angles free and in order; the lengths within [0, 60], A0, u, v within
  [-60, 60], the frame angle and the six crank angles within [0, 2 pi]; Grashof with the crank the shortest link
  (the crank turns fully).
* ``closed_curve`` (its Case3; Kunjur and Krishnamurty 1997): eighteen points on a closed curve, passed at crank
  angles 20 degrees apart from a free first one; the lengths within [0, 50], A0, u, v within [-50, 50], the frame
  angle and the first crank angle within [0, 2 pi]; Grashof.
* ``ellipse`` (its Case5; Cabrera et al. 2002, Acharyya and Mandal 2009): ten points on an ellipse (the first and
  the last the same), crank angles free and in order; the lengths within [0, 80], A0, u, v within [-80, 80], the
  angles within [0, 2 pi]; Grashof.

The error of a design is the sum over the points of the squared distance between the coupler point and the target
(the source's ``objf``). :func:`published_error` is that function, written again here in NumPy in the source's
variables (frame length r1, crank r2, coupler r3, rocker r4, the coupler point rcx, rcy in the coupler's frame at
A, A0 = (x0, y0), the frame angle theta0, the crank angles theta2 measured from the frame): the benches evaluate
mechfem's optimum with it, so the error reported is the published problem's, computed independently of mechfem.

How mechfem states them: the frame by its two pivots A0 and B0 (the source's frame length and angle), the crank
angle from the global x axis (the source's theta0 + theta2; with free timing the frame angle is then contained in
the free crank angles), the constraints as ``full_rotation`` (the crank turns fully: Grashof with the crank
shortest) and ``FreeTiming(..., ordered=True, within=ONE_TURN)`` (in order, within one turn). B0 has a box (A0's
range widened by the frame length), and with free timing the source's range of the frame length is stated as a
bound, ``Bound(FrameLength("A0", "B0"), 0, r1_max)``; the frame angle needs no range (the pivots give every
angle). :func:`published_design` converts mechfem's optimum and :func:`within_published_ranges` checks it against
every published range. Grashof alone (a rocker input allowed) is not a constraint mechfem states;
:func:`grashof` reports it of the optimum.

The decks of the same problems: ``five_points.mec``, ``closed_curve.mec`` (prescribed timing) and
``ellipse.mec`` (free timing) beside this file; the straight line is ``straight_line.mec``/``straight_line.py``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import straight_line

import mechfem

ROUNDING = 1e-12
"""Of a range's size: how far outside it a value computed from others (r1 from the pivots) may come by rounding."""
ONE_TURN = 2.0 * math.pi * (1.0 - 1e-9)
"""The source's order of free crank angles is strict within one turn (two points at the same angle count as a
violation): the last point at most a hair less than a turn after the first."""
SOURCE = "sy-nguyen-van/Dimensional_Synthesis_Four_Bar_Mechanisms, src/cases/case*.py and src/config.py"


@dataclass(frozen=True)
class Benchmark:
    """One published problem: its points, its crank angles (prescribed: every point's; free: the start values),
    whether the timing is free, the published ranges and what mechfem is asked."""

    name: str
    case: str
    """The source's name of the case."""
    points: np.ndarray
    thetas: np.ndarray
    free: bool
    length: float
    """Upper end of the lengths' range (lower end 0)."""
    place: float
    """Half-width of the range of A0, u and v."""
    crank_shortest: bool
    """The source asks Grashof with the crank the shortest (mechfem: ``full_rotation``); else Grashof only."""
    frame_fixed: bool = False
    """A0 at the origin and the frame along x (the five points)."""
    vary: dict[str, tuple[float, float] | None] = field(default_factory=dict)


def _vary(length: float, place: float, frame_fixed: bool, start_free: bool) -> dict[str, tuple[float, float] | None]:
    # A length of exactly 0 is a degenerate bar; the ranges start a hair above the published 0.
    tiny = 1e-3 * length
    out: dict[str, tuple[float, float] | None] = {}
    if frame_fixed:
        out["B0.x"] = (tiny, length)
    else:
        out |= {"A0.x": (-place, place), "A0.y": (-place, place)}
        out |= {"B0.x": (-place - length, place + length), "B0.y": (-place - length, place + length)}
    out |= {n: (tiny, length) for n in ("crank.length", "coupler.length", "rocker.length")}
    out |= {"coupler.u": (-place, place), "coupler.v": (-place, place)}
    if start_free:
        out["theta"] = None
    return out


ELLIPSE_X = [20.0, 17.66, 11.736, 5.0, 0.60307, 0.60307, 5.0, 11.736, 17.66, 20.0]
ELLIPSE_Y = [10.0, 15.142, 17.878, 16.928, 12.736, 7.2638, 3.0718, 2.1215, 4.8577, 10.0]
CURVE = [
    (0.5, 1.1), (0.4, 1.1), (0.3, 1.1), (0.2, 1.0), (0.1, 0.9), (0.05, 0.75), (0.02, 0.6), (0.0, 0.5), (0.0, 0.4),
    (0.03, 0.3), (0.1, 0.25), (0.15, 0.2), (0.2, 0.3), (0.3, 0.4), (0.4, 0.5), (0.5, 0.7), (0.6, 0.9), (0.6, 1.0),
]  # fmt: skip

BENCHMARKS = {
    "five_points": Benchmark(
        "five points, prescribed timing",
        "Case2",
        np.array(list(zip([3, 2.759, 2.372, 1.890, 1.355], [3, 3.363, 3.663, 3.862, 3.943], strict=True))),
        np.array([math.pi / 6, math.pi / 4, math.pi / 3, 5 * math.pi / 12, math.pi / 2]),
        free=False,
        length=50.0,
        place=50.0,
        crank_shortest=False,
        frame_fixed=True,
        vary=_vary(50.0, 50.0, True, False),
    ),
    "straight_line": Benchmark(
        "six points on a straight line, free timing",
        "Case1",
        np.array([(20.0, 20.0 + 5.0 * i) for i in range(6)]),
        np.array([0.5 + 0.4 * k for k in range(6)]),
        free=True,
        length=60.0,
        place=60.0,
        crank_shortest=True,
        vary=_vary(60.0, 60.0, False, False),
    ),
    "closed_curve": Benchmark(
        "eighteen points on a closed curve, prescribed timing",
        "Case3",
        np.array(CURVE),
        np.arange(18) * math.pi / 9,
        free=False,
        length=50.0,
        place=50.0,
        crank_shortest=False,
        vary=_vary(50.0, 50.0, False, True),
    ),
    "ellipse": Benchmark(
        "ten points on an ellipse, free timing",
        "Case5",
        np.array(list(zip(ELLIPSE_X, ELLIPSE_Y, strict=True))),
        np.array([2.0 * math.pi * k / 9 for k in range(10)]),
        free=True,
        length=80.0,
        place=80.0,
        crank_shortest=False,
        vary=_vary(80.0, 80.0, False, False),
    ),
}


def four_bar(bench: Benchmark) -> mechfem.Mechanism:
    """The start design of ``bench``: a crank-rocker scaled to the points, its position 1 in closed form (B to the
    left of A -> B0: the branch of the source's theta3 with the minus sign), with the motion through the prescribed
    crank angles (free timing: through the start values)."""
    centre = bench.points.mean(axis=0)
    size = float(np.ptp(bench.points, axis=0).max())
    a0 = (0.0, 0.0) if bench.frame_fixed else (float(centre[0]) - size, float(centre[1]) - size)
    d, r2, r3, r4, u, v = 1.2 * size, 0.4 * size, 1.1 * size, 1.0 * size, 0.5 * size, 0.5 * size
    b0 = (a0[0] + d, a0[1])
    m = straight_line.four_bar(a0, b0, r2, r3, r4, u, v, float(bench.thetas[0]), name=bench.case)
    steps = len(bench.thetas) - 1
    m.motion = mechfem.Motion.by(steps, float(bench.thetas[-1] - bench.thetas[0]))
    return m


def problem(bench: Benchmark) -> tuple[mechfem.Mechanism, dict[str, tuple[float, float] | None], dict[str, Any]]:
    """``(mechanism, vary, keyword arguments)`` of :func:`mechfem.optimize` for ``bench``."""
    targets = [mechfem.Target("P.x", bench.points[:, 0]), mechfem.Target("P.y", bench.points[:, 1])]
    kwargs: dict[str, Any] = {"targets": targets, "rtol": 1e-12, "atol": 1e-24, "steps": 1000 if bench.free else 200}
    if bench.free:
        kwargs["timing"] = mechfem.FreeTiming("theta", list(bench.thetas), ordered=True, within=ONE_TURN)
    if bench.crank_shortest:
        kwargs["full_rotation"] = True
    if bench.free:
        # The source's range of the frame length r1, stated as such (B0's box is A0's widened by it).
        kwargs["bounds"] = [mechfem.Bound(mechfem.FrameLength("A0", "B0"), 0.0, bench.length)]
    return four_bar(bench), dict(bench.vary), kwargs


def solve(bench: Benchmark, starts: int, seed: int, **more: Any) -> mechfem.Optimum:
    """A multi-start of ``bench`` with ``starts`` starts drawn with ``seed``."""
    mech, vary, kwargs = problem(bench)
    return mechfem.optimize(mech, vary, starts=starts, seed=seed, **{**kwargs, **more})


def published_design(bench: Benchmark, opt: mechfem.Optimum) -> dict[str, Any]:
    """The optimum in the source's variables: r1..r4, rcx, rcy, x0, y0, theta0 and the crank angles theta2 from
    the frame (one per point)."""
    m = opt.mechanism
    x0, y0 = float(m["A0.x"].value), float(m["A0.y"].value)
    x1, y1 = float(m["B0.x"].value), float(m["B0.y"].value)
    theta0 = math.atan2(y1 - y0, x1 - x0)
    if opt.timing is not None:
        crank = np.asarray(opt.timing, dtype=float)
    else:
        # The motion of four_bar: the prescribed angles' steps from the crank's (possibly varied) start.
        crank = float(m["theta"].value) + (bench.thetas - bench.thetas[0])
    return {
        "r1": math.hypot(x1 - x0, y1 - y0),
        "r2": float(m["crank.length"].value),
        "r3": float(m["coupler.length"].value),
        "r4": float(m["rocker.length"].value),
        "rcx": float(m["coupler.u"].value),
        "rcy": float(m["coupler.v"].value),
        "x0": x0,
        "y0": y0,
        "theta0": theta0 % (2.0 * math.pi),
        "theta2": (crank - theta0) % (2.0 * math.pi),
    }


def published_error(bench: Benchmark, d: dict[str, Any]) -> float:
    """The source's objective (sum of squared distances) of the design ``d`` in its variables, its branch as
    there: theta3 = 2 atan((-E - sqrt(E^2 - 4 D F)) / (2 D)) (Freudenstein's form; NaN where the dyad does not
    close)."""
    r1, r2, r3, r4, rcx, rcy = (d[k] for k in ("r1", "r2", "r3", "r4", "rcx", "rcy"))
    t2 = np.asarray(d["theta2"], dtype=float)
    k1, k4, k5 = r1 / r2, r1 / r3, (r4 * r4 - r1 * r1 - r2 * r2 - r3 * r3) / (2.0 * r3 * r2)
    dd = np.cos(t2) - k1 + k4 * np.cos(t2) + k5
    e = -2.0 * np.sin(t2)
    f = k1 + (k4 - 1.0) * np.cos(t2) + k5
    disc = e * e - 4.0 * dd * f
    if np.any(disc < 0.0):
        return math.nan
    t3 = 2.0 * np.arctan((-e - np.sqrt(disc)) / (2.0 * dd))
    crx = r2 * np.cos(t2) + rcx * np.cos(t3) - rcy * np.sin(t3)
    cry = r2 * np.sin(t2) + rcx * np.sin(t3) + rcy * np.cos(t3)
    c0, s0 = math.cos(d["theta0"]), math.sin(d["theta0"])
    cx, cy = c0 * crx - s0 * cry + d["x0"], s0 * crx + c0 * cry + d["y0"]
    return float(np.sum((cx - bench.points[:, 0]) ** 2 + (cy - bench.points[:, 1]) ** 2))


def grashof(d: dict[str, Any]) -> tuple[bool, bool]:
    """(Grashof: shortest + longest <= the other two, the crank the shortest link) of the design ``d``."""
    links = [d["r1"], d["r2"], d["r3"], d["r4"]]
    s, l_ = min(links), max(links)
    return s + l_ <= sum(links) - s - l_, d["r2"] == s


def ordered(d: dict[str, Any]) -> bool:
    """The source's order of free crank angles: increasing cyclically from the smallest (within one turn)."""
    t = np.asarray(d["theta2"], dtype=float)
    k = int(np.argmin(t))
    shifted = np.concatenate([t[k:], t[:k]])
    return bool(np.all(np.diff(shifted) > 0.0))


def within_published_ranges(bench: Benchmark, d: dict[str, Any]) -> bool:
    """Whether the design ``d`` lies within every range the source gives (angles are taken modulo a turn), to
    rounding: r1 is computed from the pivots, so an optimum on the frame length's bound comes out a few units in the
    last place either side of it."""
    eps = ROUNDING * bench.length
    lengths = all(-eps <= d[k] <= bench.length + eps for k in ("r1", "r2", "r3", "r4"))
    places = all(-bench.place - eps <= d[k] <= bench.place + eps for k in ("rcx", "rcy", "x0", "y0"))
    return lengths and places
