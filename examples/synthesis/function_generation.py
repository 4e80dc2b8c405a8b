"""Function generation: a four-bar whose rocker angle phi follows phi0 + 60 deg * log2(x) while its crank angle
theta = theta0 + 90 deg * (x - 1) runs over 1 <= x <= 2 (the classic logarithm generator), found by
``mechfem.optimize`` from a rough start.

The variables are the crank, coupler and rocker lengths and the crank's start angle theta0 (an input's start
value is a design variable too); the frame A0-B0 stays 3 long on the x axis (the angles do not change when every
length is scaled, so one length must be fixed). Longer cranks follow the logarithm ever better; the ranges keep
the mechanism compact, and the crank ends at its upper limit, as long as the frame (rms error about 0.4 degrees).
The rocker's start angle phi0 is
fixed at 100 degrees. A four-bar cannot follow a logarithm exactly: the best error is small, not 0. The motion
turns the crank 90 degrees in 30 steps; the rocker angle is compared at all 31 positions.

Run it: ``python examples/synthesis/function_generation.py``; as a deck: ``mechfem run
examples/synthesis/function.mec``.
"""

from __future__ import annotations

import math

import numpy as np

import mechfem

NAMES = ("crank.length", "coupler.length", "rocker.length", "theta")
START = (1.0, 3.5, 2.5, 1.2)
LOWER = (0.3, 1.0, 1.0, 0.0)
UPPER = (3.0, 8.0, 6.0, 2.5)
FRAME = 3.0
STEPS = 30
PHI0 = math.radians(100.0)


def wanted() -> np.ndarray:
    """The rocker angle wanted at every position."""
    x = 1.0 + np.arange(STEPS + 1) / STEPS
    return PHI0 + math.radians(60.0) * np.log2(x)


def four_bar(design: tuple[float, ...] = START) -> mechfem.Mechanism:
    """The four-bar of ``design`` (in the order of NAMES), the rocker's angle the output ``phi``."""
    a, b, c, theta0 = design
    xb = FRAME
    m = mechfem.Mechanism("function_generation")
    a0, b0 = m.fixed("A0", 0.0, 0.0), m.fixed("B0", xb, 0.0)
    pa = m.point("A", a * math.cos(theta0), a * math.sin(theta0))
    pb = m.point("B", xb + c * math.cos(PHI0), c * math.sin(PHI0))
    m.bar("crank", a0, pa, length=a, angle=mechfem.Driven(theta0, name="theta"))
    m.bar("coupler", pa, pb, length=b)
    m.bar("rocker", b0, pb, length=c, angle=mechfem.Output("phi"))
    m.motion = mechfem.Motion.by(STEPS, math.radians(90.0))
    return m


def synthesise(progress: bool = False, steps: int = 200) -> mechfem.Optimum:
    """Optimises the start design; returns what :func:`mechfem.optimize` found."""
    vary = {name: (lo, hi) for name, lo, hi in zip(NAMES, LOWER, UPPER, strict=True)}
    return mechfem.optimize(four_bar(), vary, targets=[mechfem.Target("phi", wanted())], steps=steps, progress=progress)


if __name__ == "__main__":
    opt = synthesise(progress=True)
    print(f"{opt.method}: {opt.runs} mechanism runs, {opt.seconds:.2f} s, {opt.message}")
    rms = math.degrees(math.sqrt(opt.objective / (STEPS + 1)))
    print(f"sum of squares: start {opt.start_objective:.4e}, end {opt.objective:.4e} (rms {rms:.4f} deg)")
    for name in NAMES:
        print(f"  {name:15s} {opt.start[name]:10.5f} -> {opt.values[name]:10.6f}")
