"""Path generation with prescribed timing: a crank-rocker four-bar whose coupler point P passes ten given points
at ten given crank angles, found from a poor start by ``mechfem.optimize`` with exact gradients.

The variables are the frame pivot B0 (x and y), the crank, coupler and rocker lengths and the coupler point's
local co-ordinates u, v (seven in all; A0 stays at the origin). The targets are the coupler points of a known
four-bar (B0 = (3.2, 0), lengths 1, 3, 2.5, P at 1.8 from A, 0.6 rad from A->B), so the best error is 0. The motion
turns the crank from 0 through 324 degrees in 90 steps of 3.6 degrees; the points are compared at every tenth
position (0, 36, ..., 324 degrees). The positions between are not compared (NaN targets): they keep each run on
its assembly branch with small steps.

Run it: ``python examples/synthesis/path_synthesis.py`` prints every iteration and the design found. The same
problem as a deck: ``mechfem run examples/synthesis/path.mec``.
"""

from __future__ import annotations

import math

import numpy as np

import mechfem

NAMES = ("B0.x", "B0.y", "crank.length", "coupler.length", "rocker.length", "coupler.u", "coupler.v")
START = (2.8, 0.4, 1.2, 2.6, 2.8, 1.0, 1.4)
LOWER = (1.0, -2.0, 0.5, 1.5, 1.0, -1.0, -1.0)
UPPER = (5.0, 2.0, 2.0, 5.0, 4.0, 3.0, 3.0)
THETAS = np.deg2rad(np.arange(10) * 36.0)
SUBSTEPS = 10
"""Positions of the motion per step between two compared crank angles."""


def known_points() -> np.ndarray:
    """The coupler points of the known four-bar at THETAS (10 x 2), in closed form."""
    xb, yb, a, b, c = 3.2, 0.0, 1.0, 3.0, 2.5
    u, v = 1.8 * math.cos(0.6), 1.8 * math.sin(0.6)
    out = []
    for t in THETAS:
        ax, ay = a * math.cos(t), a * math.sin(t)
        dx, dy = xb - ax, yb - ay
        d = math.hypot(dx, dy)
        along = (b * b - c * c + d * d) / (2 * d)
        h = math.sqrt(b * b - along * along)
        # B to the left of A->B0.
        bx, by = ax + (along * dx - h * dy) / d, ay + (along * dy + h * dx) / d
        ex, ey = (bx - ax) / b, (by - ay) / b
        out.append((ax + u * ex - v * ey, ay + u * ey + v * ex))
    return np.array(out)


def four_bar(design: tuple[float, ...] = START) -> mechfem.Mechanism:
    """The four-bar of ``design`` (in the order of NAMES), its crank at 0 at position 1, with the motion through
    the crank angles."""
    xb, yb, a, b, c, u, v = design
    m = mechfem.Mechanism("path_synthesis")
    a0, b0 = m.fixed("A0", 0.0, 0.0), m.fixed("B0", xb, yb)
    # Rough estimates of position 1 (B above the frame line); the run adjusts them.
    pa = m.point("A", a, 0.0)
    pb = m.point("B", a + 0.5 * (xb - a), 0.8 * b)
    p = m.point("P", a + u, v)
    m.bar("crank", a0, pa, length=a, angle=mechfem.Driven(0.0, name="theta"))
    m.ternary2("coupler", pa, pb, p, length=b, u=u, v=v)
    m.bar("rocker", b0, pb, length=c)
    steps = SUBSTEPS * (len(THETAS) - 1)
    m.motion = mechfem.Motion.by(steps, float(THETAS[-1]))
    return m


def targets() -> list[mechfem.Target]:
    """P's x and y compared at every SUBSTEPS-th position."""
    pts = known_points()
    n = SUBSTEPS * (len(THETAS) - 1) + 1
    out = []
    for k, name in enumerate(("P.x", "P.y")):
        values = np.full(n, np.nan)
        values[::SUBSTEPS] = pts[:, k]
        out.append(mechfem.Target(name, values))
    return out


def synthesise(progress: bool = False, steps: int = 200) -> mechfem.Optimum:
    """Optimises the start design; returns what :func:`mechfem.optimize` found."""
    vary = {name: (lo, hi) for name, lo, hi in zip(NAMES, LOWER, UPPER, strict=True)}
    return mechfem.optimize(four_bar(), vary, targets=targets(), steps=steps, progress=progress)


if __name__ == "__main__":
    opt = synthesise(progress=True)
    print(f"{opt.method}: {opt.runs} mechanism runs, {opt.seconds:.2f} s, {opt.message}")
    print(f"sum of squared distances: start {opt.start_objective:.4e}, end {opt.objective:.4e}")
    for name in NAMES:
        print(f"  {name:15s} {opt.start[name]:10.5f} -> {opt.values[name]:10.6f}")
