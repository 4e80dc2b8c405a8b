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


def _turned_four_bar(length: str, angle: str) -> tuple[Mechanism, list[mechfem.Target]]:
    """The path-synthesis four-bar a little off the known one (tests/design/test_optimise_frame_angle.py), in
    ``length`` and ``angle``, and the known one's coupler points with its frame turned by 0.4 rad about A0."""
    f = 1000.0 if length == "mm" else 1.0
    turn, thetas, substeps = 0.4, np.deg2rad(np.arange(10) * 36.0), 10
    xb, yb, a, b, c, u, v = (f * x for x in (3.2, 0.0, 1.05, 2.95, 2.5, 1.5, 1.0))
    m = Mechanism("path", length=length, angle=angle)
    a0, b0 = m.fixed("A0", 0.0, 0.0), m.fixed("B0", xb, yb)
    pa, pb, p = m.point("A", a, 0.0), m.point("B", a + 0.5 * (xb - a), 0.8 * b), m.point("P", a + u, v)
    m.bar("crank", a0, pa, length=a, angle=Driven(0.0, name="theta"))
    m.ternary2("coupler", pa, pb, p, length=b, u=u, v=v)
    m.bar("rocker", b0, pb, length=c)
    m.motion = Motion.by(substeps * 9, 324.0 if angle == "deg" else float(thetas[-1]))
    # The known four-bar (3.2, 0, 1, 3, 2.5, P at 1.8 m and 0.6 rad from A on AB) in closed form, turned.
    a1, b1, c1, d1, p1, al = 1.0, 3.0, 2.5, 3.2, 1.8, 0.6
    ax, ay = a1 * np.cos(thetas), a1 * np.sin(thetas)
    e = np.hypot(d1 - ax, -ay)
    g = np.arctan2(-ay, d1 - ax) + np.arccos((b1 * b1 + e * e - c1 * c1) / (2 * b1 * e))
    px, py = ax + p1 * np.cos(g + al), ay + p1 * np.sin(g + al)
    cs, sn = np.cos(turn), np.sin(turn)
    points = f * np.column_stack([cs * px - sn * py, sn * px + cs * py])
    targets = []
    for k, name in enumerate(("P.x", "P.y")):
        values = np.full(substeps * 9 + 1, np.nan)
        values[::substeps] = points[:, k]
        targets.append(mechfem.Target(name, values))
    return m, targets


def test_a_frame_angle_is_found_in_the_models_units() -> None:
    from mechfem.design.frame_angle import FrameAngle

    found = {}
    for length, angle in (("m", "rad"), ("mm", "deg")):
        f = 1000.0 if length == "mm" else 1.0
        m, targets = _turned_four_bar(length, angle)
        vary = {
            "crank.length": (0.5 * f, 2.0 * f),
            "coupler.length": (1.5 * f, 5.0 * f),
            "rocker.length": (1.0 * f, 4.0 * f),
            "coupler.u": (-f, 3.0 * f),
            "coupler.v": (-f, 3.0 * f),
        }
        o = mechfem.optimize(m, vary, targets=targets, frame=FrameAngle("A0"), rtol=1e-14, atol=1e-24 * f * f)
        found[length] = o
        assert o.objective < 1e-18 * f * f
        # The optimised mechanism is turned in its own units: B0 on the turned frame line, the crank from there.
        assert (o.mechanism["B0.x"].value, o.mechanism["B0.y"].value) == pytest.approx(
            (3.2 * f * np.cos(0.4), 3.2 * f * np.sin(0.4)), rel=1e-9
        )
    assert found["m"].values["frame"] == pytest.approx(0.4, abs=1e-9)
    assert found["mm"].values["frame"] == pytest.approx(np.degrees(0.4), abs=1e-7)
    assert found["mm"].values["crank.length"] == pytest.approx(1000.0, rel=1e-9)
    assert found["mm"].mechanism["theta"].value == pytest.approx(np.degrees(0.4), abs=1e-7)


def test_a_transfer_function_target_is_in_the_models_derived_unit() -> None:
    # dB.x/dphi at the last position asked for in m/deg and in mm/deg (both models in degrees): the same design.
    found = {}
    for unit, f in (("m", 1.0), ("mm", 1000.0)):
        q = mechfem.Q("B.x", 1)
        o = mechfem.optimize(
            fourbar(unit), {"coupler.length": (3.0 * f, 4.0 * f)}, targets=[TargetAt(q, 10, -0.015 * f)], motion=MOTION
        )
        found[unit] = o.values["coupler.length"] / f
        assert o.objective < 1e-16 * f * f
        assert o.run().value("B.x", 1)[-1] == pytest.approx(-0.015 * f, rel=1e-6)
    assert found["mm"] == pytest.approx(found["m"], rel=1e-7)
    assert 3.5 < found["m"] < 3.8
