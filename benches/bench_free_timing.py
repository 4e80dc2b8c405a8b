"""The straight-line problem with free timing (docs/optimisation.md, Free timing): six points on a vertical line,
the crank angles free, A0 and B0 free; a multi-start of ``mechfem.optimize`` for the seeds given.

    .venv/bin/python benches/bench_free_timing.py [--starts 20] [--seeds 1 2 3]

The data as used here (not checked against the papers of Kunjur & Krishnamurty 1997 and Cabrera et al. 2002):
points (20, 20), (20, 25), ..., (20, 45); A0 and B0 within [-60, 60], the three lengths within [5, 60], the coupler
point's u and v within [-60, 60], the six crank angles periodic, starting 0.4 rad apart from 0.5 rad.
"""

from __future__ import annotations

import argparse
import math
import time
import warnings

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


def four_bar(a0=(0.0, 0.0), b0=(40.0, 0.0), r2=10.0, r3=30.0, r4=35.0, u=10.0, v=15.0, theta=0.5):  # type: ignore[no-untyped-def]
    """A crank-rocker with its position 1 in closed form (B to the left of A -> B0)."""
    m = mechfem.Mechanism("straight_line")
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
    m.motion = mechfem.Motion.by(10, 0.1)
    return m


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--starts", type=int, default=20)
    parser.add_argument("--seeds", type=int, nargs="+", default=[1, 2, 3])
    args = parser.parse_args()
    targets = [mechfem.Target("P.x", POINTS[:, 0]), mechfem.Target("P.y", POINTS[:, 1])]
    timing = mechfem.FreeTiming("theta", list(0.5 + np.linspace(0.0, 2.0, 6)))
    print("| seed | starts usable | best sum of squared distances | seconds |\n|---|---|---|---|")
    for seed in args.seeds:
        t0 = time.perf_counter()
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            opt = mechfem.optimize(
                four_bar(), VARY, targets=targets, timing=timing, starts=args.starts, seed=seed, rtol=1e-12, atol=1e-20
            )
        usable = sum(s.values is not None for s in opt.starts)
        print(f"| {seed} | {usable} of {len(opt.starts)} | {opt.objective:.2e} | {time.perf_counter() - t0:.0f} |")


if __name__ == "__main__":
    main()
