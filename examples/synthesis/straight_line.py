"""The straight-line problem with free timing: the coupler point P of a four-bar should pass six points on a
vertical line, (20, 20), (20, 25), ..., (20, 45), at crank angles left free (``FreeTiming``), with a crank that
turns fully (``full_rotation``), from one start design.

The same problem as a deck: ``mechfem run examples/synthesis/straight_line.mec`` (``FREETIME 6``, ``FULLROT 6``);
both state the same problem and give the same result (``tests/design/test_optimise_deck_synthesis.py``). A multi-start
of it: ``benches/bench_multistart.py``.
"""

from __future__ import annotations

import math

import numpy as np

import mechfem

POINTS = np.array([(20.0, 20.0 + 5.0 * i) for i in range(6)])
VARY: dict[str, tuple[float, float] | None] = {
    "A0.x": (-60, 60),
    "A0.y": (-60, 60),
    "B0.x": (-60, 60),
    "B0.y": (-60, 60),
    "crank.length": (5, 60),
    "coupler.length": (5, 60),
    "rocker.length": (5, 60),
    "coupler.u": (-60, 60),
    "coupler.v": (-60, 60),
}
STARTS = [0.5 + 0.4 * k for k in range(6)]
"""The crank angle at each point to start from: the deck's motion (0.5 rad, five steps of 0.4 rad)."""


def four_bar(a0=(0.0, 0.0), b0=(40.0, 0.0), r2=10.0, r3=30.0, r4=35.0, u=10.0, v=15.0, theta=0.5, name="straight_line"):  # type: ignore[no-untyped-def]
    """A crank-rocker with its position 1 in closed form (B to the left of A -> B0)."""
    m = mechfem.Mechanism(name)
    A0, B0 = m.fixed("A0", *a0), m.fixed("B0", *b0)
    ax, ay = a0[0] + r2 * math.cos(theta), a0[1] + r2 * math.sin(theta)
    dx, dy = b0[0] - ax, b0[1] - ay
    d = math.hypot(dx, dy)
    along = (r3 * r3 - r4 * r4 + d * d) / (2 * d)
    h = math.sqrt(max(r3 * r3 - along * along, 0.0))
    bx, by = ax + (along * dx - h * dy) / d, ay + (along * dy + h * dx) / d
    ex, ey = (bx - ax) / r3, (by - ay) / r3
    pa, pb = m.point("A", ax, ay), m.point("B", bx, by)
    p = m.point("P", ax + u * ex - v * ey, ay + u * ey + v * ex)
    m.bar("crank", A0, pa, length=r2, angle=mechfem.Driven(theta, name="theta"))
    m.ternary2("coupler", pa, pb, p, length=r3, u=u, v=v)
    m.bar("rocker", B0, pb, length=r4)
    m.motion = mechfem.Motion.by(5, 2.0)
    return m


def synthesise(**kwargs: object) -> mechfem.Optimum:
    """The straight line from the start design, the crank angles free; ``kwargs`` go to :func:`mechfem.optimize`
    (e.g. ``starts=20, seed=1``; ``steps`` 50 as in the deck unless given)."""
    kwargs.setdefault("steps", 50)
    targets = [mechfem.Target("P.x", POINTS[:, 0]), mechfem.Target("P.y", POINTS[:, 1])]
    return mechfem.optimize(
        four_bar(),
        VARY,
        targets=targets,
        timing=mechfem.FreeTiming("theta", STARTS),
        full_rotation=True,
        rtol=1e-12,
        atol=1e-20,
        **kwargs,  # type: ignore[arg-type]
    )


if __name__ == "__main__":
    opt = synthesise(progress=True)
    print(f"{opt.method}: {opt.runs} runs, {opt.seconds:.2f} s; sum of squared distances {opt.objective:.4e}")
    print("crank angles at the points:", ", ".join(f"{t:.6f}" for t in opt.timing or []))
    for name, value in opt.values.items():
        print(f"  {name:15s} {opt.start[name]:10.4f} -> {value:12.6f}")
