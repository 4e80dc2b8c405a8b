"""``optimize(..., full_rotation=True)`` turns the input once round (360 degrees) in a model whose angles are in
degrees, as in one in radians: the check is not a turn of 6.28 degrees.

The four-bar of the studio's template (frame 4, coupler 3.5, rocker 3) turns its crank fully while
crank + 4 <= 3.5 + 3 (Grashof's condition), so for crank lengths up to 2.5. Asked for the coupler point's x at
position 1 that only a crank of 2.8 gives, the optimiser must stop at a crank that still turns."""

from __future__ import annotations

import warnings

import mechfem
from mechfem.design.optimise import TargetAt
from mechfem.studio_app.template import four_bar

#: The deck number of C's x co-ordinate in the template (A0, B0, A, B, C: x and y each), which grows with the crank.
C_X = 9


def test_full_rotation_in_degrees_keeps_the_crank_turning() -> None:
    m = four_bar()
    m.storage = None
    # A motion of 10 degrees only: the plain optimisation does not see that the crank would not turn round.
    m.motion = mechfem.Motion.by(2, 10.0, unit="deg")
    wanted = float(m.variant({"crank.length": 2.8}).check().coords[0, C_X - 1])
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        free = mechfem.optimize(m, {"crank.length": (0.5, 2.9)}, targets=[TargetAt("C.x", 0, wanted)], steps=60)
        turning = mechfem.optimize(
            m, {"crank.length": (0.5, 2.9)}, targets=[TargetAt("C.x", 0, wanted)], full_rotation=True, steps=60
        )
    # Without the check the optimum is the crank of 2.8, which cannot turn; with it, one that does.
    assert abs(free.values["crank.length"] - 2.8) < 1e-3
    assert turning.values["crank.length"] <= 2.5 + 1e-6
    assert turning.mechanism.run().report.stop_reason() is None
