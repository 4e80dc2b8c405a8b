"""``optimize`` and ``RunResult.sensitivity`` work in the model's units: a four-bar in mm and degrees gives the
metre model's optimum converted, its gradients match central differences of whole runs in mm and degrees, and a
length target is met in mm."""

from __future__ import annotations

import numpy as np
import pytest

import mechfem
from mechfem import Driven, Mechanism, Motion, Output
from mechfem.design.optimise import TargetAt

MOTION = Motion.by(10, 90)


def fourbar(length: str, coupler: float = 3.5) -> Mechanism:
    f = 1000.0 if length == "mm" else 1.0
    m = Mechanism("fourbar", length=length, angle="deg")
    a0, b0 = m.fixed("A0", 0.0, 0.0), m.fixed("B0", 4.0 * f, 0.0)
    a, b = m.point("A", 1.0 * f, 0.0), m.point("B", 3.5 * f, 2.5 * f)
    m.bar("crank", a0, a, length=1.0 * f, angle=Driven(start=0.0, name="phi"))
    m.bar("coupler", a, b, length=coupler * f)
    m.bar("rocker", b0, b, length=3.0 * f, angle=Output("psi"))
    return m


def test_an_optimum_in_mm_is_the_metre_optimum_converted() -> None:
    found = {}
    for unit, f in (("m", 1.0), ("mm", 1000.0)):
        o = mechfem.optimize(
            fourbar(unit), {"coupler.length": (3.0 * f, 4.0 * f)}, targets=[TargetAt("psi", 10, 100.0)], motion=MOTION
        )
        assert o.start["coupler.length"] == pytest.approx(3.5 * f)
        found[unit] = o.values["coupler.length"] / f
        # The optimised mechanism runs to the target in its own units.
        assert o.run().output("psi")[-1] == pytest.approx(100.0, abs=1e-6)
    assert found["mm"] == pytest.approx(found["m"], rel=1e-9)
    assert 3.0 < found["m"] < 4.0


def test_a_length_target_is_met_in_the_models_length_unit() -> None:
    m = fourbar("mm")
    o = mechfem.optimize(m, {"coupler.length": (3000.0, 4000.0)}, targets=[TargetAt("B.x", 10, 3300.0)], motion=MOTION)
    assert o.run().x("B")[-1] == pytest.approx(3300.0, abs=1e-3)


@pytest.mark.parametrize("unit", ["m", "mm"])
def test_sensitivity_is_in_the_models_units(unit: str) -> None:
    f = 1000.0 if unit == "mm" else 1.0
    g = fourbar(unit).run(MOTION).sensitivity("psi", ["coupler.length"])[:, 0]
    h = 1e-6 * f
    up = fourbar(unit, 3.5 + h / f).run(MOTION).output("psi")
    down = fourbar(unit, 3.5 - h / f).run(MOTION).output("psi")
    central = (up - down) / (2 * h)  # degrees per model length unit
    assert np.allclose(g, central, rtol=1e-5, atol=1e-9 * float(np.max(np.abs(central))))
    assert abs(g[-1]) > 0
