"""The designer's constraint "the crank turns fully" (``optimize(full_rotation=True)``): a design whose input meets
a limit position anywhere in a whole turn is infeasible, though the problem's own motion is shorter."""

from __future__ import annotations

import math
import sys
from pathlib import Path

import numpy as np
import pytest

import mechfem
from mechfem.design import engine as design

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "examples" / "synthesis"))
import path_synthesis as ps  # noqa: E402

KNOWN = (3.2, 0.0, 1.0, 3.0, 2.5, 1.8 * math.cos(0.6), 1.8 * math.sin(0.6))


def short_motion(design_: tuple[float, ...]) -> tuple[mechfem.Mechanism, list[mechfem.Target]]:
    """The four-bar with a motion of 20 degrees only; the targets are the known four-bar's points there."""
    m = ps.four_bar(design_)
    m.motion = mechfem.Motion.by(4, math.radians(20.0))
    r = ps.four_bar(KNOWN)
    r.motion = m.motion
    run = r.run()
    return m, [mechfem.Target("P.x", run.value("P.x")), mechfem.Target("P.y", run.value("P.y"))]


def test_a_crank_that_cannot_turn_fully_is_an_infeasible_start_only_with_full_rotation() -> None:
    # Crank 2.6 longer than the rocker 2.5: not a Grashof crank-rocker, yet 20 degrees of crank turn run.
    start = (3.2, 0.0, 2.6, 3.0, 2.5, KNOWN[5], KNOWN[6])
    m, targets = short_motion(start)
    assert m.run().complete
    vary = {"crank.length": (0.5, 3.0)}
    free = mechfem.optimize(m, vary, targets=targets, steps=5)
    assert free.runs > 1
    with pytest.raises(design.Infeasible, match="cannot turn fully"):
        mechfem.optimize(m, vary, targets=targets, full_rotation=True)


def test_with_full_rotation_the_optimum_turns_fully() -> None:
    start = (3.0, 0.2, 1.2, 2.8, 2.6, 1.3, 1.1)
    m, targets = short_motion(start)
    vary = {name: (lo, hi) for name, lo, hi in zip(ps.NAMES, ps.LOWER, ps.UPPER, strict=True)}
    opt = mechfem.optimize(m, vary, targets=targets, full_rotation=True, rtol=1e-12)
    assert opt.objective < 1e-12
    whole = opt.mechanism.run(mechfem.Motion.by(72, 2.0 * math.pi))
    assert whole.complete
    x = np.array([opt.values[n] for n in ps.NAMES])
    # Grashof with the crank the shortest link: s + l <= p + q.
    links = sorted([x[2], x[3], x[4], math.hypot(x[0], x[1])])
    assert x[2] == links[0] and links[0] + links[3] <= links[1] + links[2]


def test_full_rotation_needs_one_angle_input() -> None:
    m = mechfem.Mechanism("slider")
    a0 = m.fixed("A0", 0.0, 0.0)
    a = m.point("A", 1.0, 0.0)
    m.bar("bar", a0, a, length=mechfem.Driven(1.0, name="s"), angle=0.0)
    m.motion = mechfem.Motion.by(2, 0.1)
    with pytest.raises(ValueError, match="one input"):
        mechfem.optimize(
            m, {"bar.angle": (-1.0, 1.0)}, targets=[mechfem.Target("A.y", [0.0, 0.0, 0.0])], full_rotation=True
        )
