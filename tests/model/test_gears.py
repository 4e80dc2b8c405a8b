"""Gears, pinion-and-rack and belts: the decks of ``examples/gears`` against closed forms derived here,
independently of mechfem, and the messages for impossible gear and belt geometry.

Every closed form is compared within 1e-9 of the largest magnitude of the quantity over the run (1e-9
absolute for quantities that are zero). The deck constants are repeated here on purpose: a change to a
deck that is not made here too fails its test.
"""

from __future__ import annotations

from collections.abc import Callable
from functools import cache
from pathlib import Path

import numpy as np
import numpy.typing as npt
import pytest

import mechfem
from conftest import ROOT, Cli

Array = npt.NDArray[np.float64]

GEARS = ROOT / "examples" / "gears"
RTOL = 1e-9


@cache
def run(name: str) -> mechfem.RunResult:
    """The deck ``examples/gears/<name>.mec``, run once per test session; it must run to its end."""
    result = mechfem.run_deck(GEARS / f"{name}.mec")
    assert result.report.complete, result.report.stop_reason()
    return result


def assert_close(what: str, got: Array, want: Array | float, scale: float | None = None) -> None:
    """|got - want| <= RTOL * scale at every position; scale defaults to max(|want|, 1)."""
    got_a, want_a = np.broadcast_arrays(np.asarray(got, dtype=float), np.asarray(want, dtype=float))
    assert np.all(np.isfinite(got_a)), f"{what}: not finite"
    if scale is None:
        scale = max(float(np.max(np.abs(want_a))), 1.0)
    err = np.abs(got_a - want_a)
    k = int(np.argmax(err))
    assert err[k] <= RTOL * scale, (
        f"{what}: position {k + 1}: got {got_a[k]!r}, want {want_a[k]!r} "
        f"(error {err[k]:.3g}, allowed {RTOL * scale:.3g})"
    )


def richardson(f: Callable[[Array], Array], x: Array, h: float = 1e-3) -> Array:
    """d f / d x by the fourth-order central difference (error of order h^4)."""
    return (8 * (f(x + h) - f(x - h)) - (f(x + 2 * h) - f(x - 2 * h))) / (12 * h)


def test_every_gear_example_is_tested() -> None:
    decks = {p.stem for p in GEARS.glob("*.mec")}
    assert decks == {
        "step_dwell",
        "geared_slider_crank",
        "planetary_gr1",
        "planetary_gr2",
        "belt_swing_arm",
        "crossed_belt",
        "chain_swing_arm",
    }


# Step-dwell mechanism (fig. 5.4.11) ------------------------------------------------------------

# examples/gears/step_dwell.mec: ring wheel R about A0 = 0, planet r at A on the crank l1 = R - r,
# B on the planet's pitch circle on the x-axis, assembly angle g of the GR1 pair.
SD_R, SD_r, SD_L1, SD_G = 3.0, 2.0, 1.0, 0.0
SD_STEPS, SD_START = 72, -np.pi / 2


class StepDwell:
    """Closed form at crank angles b1.

    B = A + r (cos b2, sin b2) on y = 0 with A = l1 (cos b1, sin b1): l1 sin b1 + r sin b2 = 0, and B to
    the right of A (cos b2 > 0, possible for every b1 because l1 < r). Seen from the crank, the ring
    (inner teeth) turns R/r times slower than the planet and the same way:
    r (b2 - b1) = R (b4 - b1) - r g, so b4 = b1 + (r/R)(b2 - b1 + g). Differentiating the constraint
    once and twice gives b2' and b2''.
    """

    def __init__(self, b1: Array) -> None:
        R, r, l1 = SD_R, SD_r, SD_L1
        s1, c1 = np.sin(b1), np.cos(b1)
        b2 = -np.arcsin(l1 * s1 / r)
        s2, c2 = np.sin(b2), np.cos(b2)
        b2p = -l1 * c1 / (r * c2)
        b2pp = (l1 * s1 + r * s2 * b2p**2) / (r * c2)
        self.b2 = b2
        self.b4 = b1 + (r / R) * (b2 - b1 + SD_G)
        self.b4p = 1 - r / R + (r / R) * b2p
        self.b4pp = (r / R) * b2pp
        self.xb = l1 * c1 + r * c2
        self.xbp = -l1 * s1 - r * s2 * b2p


def test_step_dwell_ring_angle_and_transfer_functions() -> None:
    res = run("step_dwell")
    b1 = res.buffers[1]
    assert_close("crank angle", b1, SD_START + 2 * np.pi * np.arange(SD_STEPS + 1) / SD_STEPS)
    sd = StepDwell(b1)
    assert_close("ring angle beta4", res.buffers[2], sd.b4)
    assert_close("d beta4 / d beta1", res.buffers[3], sd.b4p)
    assert_close("d2 beta4 / d beta1^2", res.buffers[4], sd.b4pp)
    assert_close("x_B", res.buffers[5], sd.xb)
    assert_close("d x_B / d beta1", res.buffers[6], sd.xbp)
    assert_close("planet angle beta2", res.coords[:, 8], sd.b2)
    assert_close("x_A", res.coords[:, 2], SD_L1 * np.cos(b1))
    assert_close("y_A", res.coords[:, 3], SD_L1 * np.sin(b1))
    # The ring advances (1 - r/R) of a turn per crank turn.
    assert res.buffers[2][-1] - res.buffers[2][0] == pytest.approx(2 * np.pi * (1 - SD_r / SD_R), abs=1e-9)


def test_step_dwell_ring_dwells_where_b_is_at_its_extreme() -> None:
    res = run("step_dwell")
    b1, b4p, b4pp, xbp = res.buffers[1], res.buffers[3], res.buffers[4], res.buffers[6]
    # Crank angle 0 (position 19): B is at its right-most point, the pitch point of the two wheels.
    k = int(np.argmin(np.abs(b1)))
    assert k == 18 and abs(b1[k]) < 1e-12
    assert res.buffers[5][k] == pytest.approx(SD_R, abs=1e-12)
    assert np.sign(xbp[k - 1]) == 1 and np.sign(xbp[k + 1]) == -1
    # There the ring stands still to first and second order ...
    assert abs(b4p[k]) < 1e-12 and abs(b4pp[k]) < 1e-12
    # ... and nowhere else: it never turns back, and its speed is smallest in the dwell.
    others = np.delete(b4p, k)
    assert np.all(others > 1e-4)
    assert int(np.argmin(b4p)) == k
    # Around the dwell the ring's motion is of third order in the crank angle: with
    # b2 = -b1/2 + b1^3/16 + O(b1^5) the closed form gives b4 = b1^3/24 + O(b1^5).
    near = (np.abs(b1) < 0.2) & (b1 != 0)
    assert np.count_nonzero(near) == 4
    assert np.allclose((res.buffers[2][near] - res.buffers[2][k]) / b1[near] ** 3, 1 / 24, rtol=0.05)


# Geared slider-crank (fig. 5.4.14) -------------------------------------------------------------

# examples/gears/geared_slider_crank.mec: crank l1 about A0 = 0, rod l2, slider B on y = Y_B,
# pinion R on the slider under a fixed rack (i = -R), assembly length g of the RK1 element.
GS_L1, GS_L2, GS_YB, GS_R, GS_G = 1.0, 3.5, -0.25, 0.4, 4.5
GS_STEPS = 48


class GearedSliderCrank:
    """Closed form at crank angles b1.

    With h = y_A - y_B = l1 sin b1 - Y_B and w = sqrt(l2^2 - h^2): x_B = l1 cos b1 + w. The rack frame at
    B (direction 0) sees A0 at u = -x_B; g = i b3 - u with i = -R gives b3 = (x_B - g) / R.
    """

    def __init__(self, b1: Array) -> None:
        l1, l2 = GS_L1, GS_L2
        s, c = np.sin(b1), np.cos(b1)
        h, hp, hpp = l1 * s - GS_YB, l1 * c, -l1 * s
        w = np.sqrt(l2 * l2 - h * h)
        self.x = l1 * c + w
        self.xp = -l1 * s - h * hp / w
        self.xpp = -l1 * c - (hp * hp + h * hpp) / w - (h * hp) ** 2 / w**3
        self.b3 = (self.x - GS_G) / GS_R
        self.b3p = self.xp / GS_R
        self.b3pp = self.xpp / GS_R


def test_geared_slider_crank_pinion_follows_the_slider() -> None:
    res = run("geared_slider_crank")
    b1 = res.buffers[1]
    assert_close("crank angle", b1, 2 * np.pi * np.arange(GS_STEPS + 1) / GS_STEPS)
    gs = GearedSliderCrank(b1)
    assert_close("x_B", res.buffers[2], gs.x)
    assert_close("d x_B / d beta1", res.buffers[3], gs.xp)
    assert_close("d2 x_B / d beta1^2", res.buffers[4], gs.xpp)
    assert_close("y_B", res.coords[:, 1], GS_YB)
    assert_close("pinion angle beta3", res.buffers[5], gs.b3)
    assert_close("d beta3 / d beta1", res.buffers[6], gs.b3p)
    assert_close("d2 beta3 / d beta1^2", res.buffers[7], gs.b3pp)
    # The pinion turns 1/R radians per unit of slider travel, counter-clockwise when the slider moves right.
    x, b3 = res.buffers[2], res.buffers[5]
    assert_close("beta3 - x_B / R", b3 - x / GS_R, -GS_G / GS_R)
    # After one crank turn slider and pinion are back where they started.
    assert b3[-1] == pytest.approx(b3[0], abs=1e-9)


# Planetary gear trains (Willis) ----------------------------------------------------------------

# Both planetary decks: sun Rs and ring Rr (inner teeth) about O = 0, planet Rp on the carrier.
PL_RS, PL_RP, PL_RR = 30.0, 15.0, 60.0


def willis(sun: Array, carrier: Array) -> tuple[Array, Array]:
    """Planet and ring angles for given sun and carrier angles, all zero at the start.

    Seen from the carrier, sun and planet (outer teeth) turn opposite ways, planet and ring the same
    way; both meshes roll without slip at the pitch circles:
    Rp (bp - bc) = -Rs (bs - bc),  Rr (br - bc) = Rp (bp - bc).
    """
    planet = carrier - PL_RS / PL_RP * (sun - carrier)
    ring = carrier - PL_RS / PL_RR * (sun - carrier)
    return planet, ring


def test_planetary_gr1_two_inputs_follow_willis() -> None:
    res = run("planetary_gr1")
    steps, dt = 36, 0.01
    k = np.arange(steps + 1)
    sun, carrier = res.buffers[1], res.buffers[2]
    assert_close("sun angle", sun, 2 * np.pi * k / steps)
    assert_close("carrier angle", carrier, -np.pi / 2 * k / steps)
    planet, ring = willis(sun, carrier)
    assert_close("ring angle", res.buffers[3], ring)
    assert_close("planet angle", res.buffers[10], planet)
    assert_close("d ring / d sun", res.buffers[4], -PL_RS / PL_RR)
    assert_close("d ring / d carrier", res.buffers[5], 1 + PL_RS / PL_RR)
    assert_close("d2 ring / d sun d carrier", res.buffers[6], 0.0)
    assert_close("x_A", res.buffers[11], (PL_RS + PL_RP) * np.cos(carrier))
    assert_close("y_A", res.buffers[12], (PL_RS + PL_RP) * np.sin(carrier))
    # The Willis equation with the velocities of the timed motion.
    w_ring, w_sun, w_carrier = res.buffers[7], res.buffers[8], res.buffers[9]
    assert_close("sun velocity", w_sun, 2 * np.pi / (steps * dt))
    assert_close("carrier velocity", w_carrier, -np.pi / 2 / (steps * dt))
    assert_close("Willis ratio", (w_sun - w_carrier) / (w_ring - w_carrier), -PL_RR / PL_RS)


def test_planetary_gr2_fixed_ring_follows_willis() -> None:
    res = run("planetary_gr2")
    steps = 36
    sun = res.buffers[1]
    assert_close("sun angle", sun, 6 * np.pi * np.arange(steps + 1) / steps)
    # With the ring still, Willis gives w_carrier / w_sun = Rs / (Rs + Rr).
    ratio = PL_RS / (PL_RS + PL_RR)
    carrier = ratio * sun
    planet, ring = willis(sun, carrier)
    assert_close("ring stays", ring, 0.0)
    assert_close("carrier angle", res.buffers[2], carrier)
    assert_close("d carrier / d sun", res.buffers[3], ratio)
    assert_close("d2 carrier / d sun^2", res.buffers[4], 0.0)
    assert_close("planet angle", res.buffers[5], planet)
    assert_close("d planet / d sun", res.buffers[6], ratio - PL_RS / PL_RP * (1 - ratio))
    assert_close("x_A", res.buffers[7], (PL_RS + PL_RP) * np.cos(carrier))
    assert_close("y_A", res.buffers[8], (PL_RS + PL_RP) * np.sin(carrier))
    # Three sun turns make one carrier turn.
    assert res.buffers[2][-1] == pytest.approx(2 * np.pi, abs=1e-9)


# Belt with a moving wheel centre ---------------------------------------------------------------

# examples/gears/belt_swing_arm.mec: wheel R_P about P = 0, wheel R_Q at Q on the arm F-Q of
# length L, prescribed belt length (mark to mark).
BS_RP, BS_RQ, BS_F, BS_L, BS_BELT = 40.0, 20.0, np.array([150.0, -30.0]), 60.0, 120.0
BS_STEPS, BS_DT = 36, 0.05


class SwingArmBelt:
    """Closed form at driving wheel angles ba and arm angles t.

    Q = F + L (cos t, sin t). The straight span of an open belt touches both wheels at the points
    T_P = P + R_P n and T_Q = Q + R_Q n whose common normal n = (cos phi, sin phi) satisfies
    (T_Q - T_P) . n = 0, i.e. (Q - P) . n = R_P - R_Q: phi = beta_b + acos((R_P - R_Q) / l), the solution
    to the left of P->Q. The belt length from the mark on wheel a back to T_P, along the span and from T_Q
    to the mark on wheel c is R_P (ba - phi) + |T_Q - T_P| + R_Q (phi - bc); holding it at BELT gives bc.
    """

    def __init__(self, ba: Array, t: Array) -> None:
        self.ba, self.t = ba, t
        qx, qy = BS_F[0] + BS_L * np.cos(t), BS_F[1] + BS_L * np.sin(t)
        self.dist = np.hypot(qx, qy)
        beta_b = np.unwrap(np.arctan2(qy, qx))
        phi = beta_b + np.arccos((BS_RP - BS_RQ) / self.dist)
        nx, ny = np.cos(phi), np.sin(phi)
        span = np.hypot(qx + BS_RQ * nx - BS_RP * nx, qy + BS_RQ * ny - BS_RP * ny)
        self.span = span
        self.bc = phi + (BS_RP * (ba - phi) + span - BS_BELT) / BS_RQ

    @staticmethod
    def dbc_dt(t: Array) -> Array:
        """d bc / d t: l' = (Q.Q')/l, beta_b' = (Q x Q')/l^2, phi' = beta_b' + d l'/(l l*), span' = l l'/l*."""
        d = BS_RP - BS_RQ
        qx, qy = BS_F[0] + BS_L * np.cos(t), BS_F[1] + BS_L * np.sin(t)
        dqx, dqy = -BS_L * np.sin(t), BS_L * np.cos(t)
        dist = np.hypot(qx, qy)
        ls = np.sqrt(dist * dist - d * d)
        lp = (qx * dqx + qy * dqy) / dist
        bp = (qx * dqy - qy * dqx) / (dist * dist)
        phip = bp + d * lp / (dist * ls)
        return (dist * lp / ls - d * phip) / BS_RQ


def test_belt_on_swinging_arm_driven_wheel_angle() -> None:
    res = run("belt_swing_arm")
    k = np.arange(BS_STEPS + 1)
    ba, t = res.buffers[1], res.buffers[2]
    assert_close("driving wheel angle", ba, 2 * np.pi * k / BS_STEPS)
    assert_close("arm angle", t, np.pi / 2 + np.pi / 2 * k / BS_STEPS)
    sb = SwingArmBelt(ba, t)
    # The bar P->Q changes length by more than a third on the way.
    assert_close("centre distance", res.buffers[8], sb.dist)
    assert sb.dist.max() - sb.dist.min() > 0.3 * sb.dist.max()
    assert_close("span = l*", sb.span, np.sqrt(sb.dist**2 - (BS_RP - BS_RQ) ** 2))
    assert_close("driven wheel angle", res.buffers[3], sb.bc)
    assert_close("driven wheel angle (co-ordinate)", res.coords[:, 5], sb.bc)


def test_belt_on_swinging_arm_transfer_functions() -> None:
    res = run("belt_swing_arm")
    ba, t = res.buffers[1], res.buffers[2]
    assert_close("d bc / d ba", res.buffers[4], BS_RP / BS_RQ)
    assert_close("d bc / d t", res.buffers[5], SwingArmBelt.dbc_dt(t))
    assert_close("d2 bc / d t^2", res.buffers[6], richardson(SwingArmBelt.dbc_dt, t))
    assert_close("d2 bc / d ba d t", res.buffers[7], 0.0)
    speed_a, speed_t = 2 * np.pi / (BS_STEPS * BS_DT), np.pi / 2 / (BS_STEPS * BS_DT)
    assert_close("driven wheel velocity", res.buffers[9], BS_RP / BS_RQ * speed_a + SwingArmBelt.dbc_dt(t) * speed_t)
    # The closed form's own derivative agrees with its difference quotient (guards the closed form).
    h = 1e-6
    fd = (SwingArmBelt(ba, t + h).bc - SwingArmBelt(ba, t - h).bc) / (2 * h)
    assert np.allclose(fd, SwingArmBelt.dbc_dt(t), rtol=0, atol=1e-7)


def test_crossed_belt_turns_the_wheels_opposite_ways() -> None:
    res = run("crossed_belt")
    rp, rq = 50.0, -25.0
    ba = res.buffers[1]
    assert_close("driving wheel angle", ba, 2 * np.pi * np.arange(25) / 24)
    assert_close("driven wheel angle", res.buffers[2], rp / rq * ba)
    assert_close("d bc / d ba", res.buffers[3], -abs(rp / rq))
    assert_close("d2 bc / d ba^2", res.buffers[4], 0.0)


def test_chain_on_swinging_arm_gr2_and_belt_agree() -> None:
    res = run("chain_swing_arm")
    k = np.arange(25)
    front, arm = res.buffers[1], res.buffers[2]
    assert_close("front sprocket angle", front, 4 * np.pi * k / 24)
    assert_close("arm angle", arm, -0.4 + 0.6 * k / 24)
    # Seen from the arm the chain turns the rear wheel the same way, 8/20 as fast.
    i = 8.0 / 20.0
    rear = arm + i * (front - arm)
    assert_close("rear wheel angle (GR2)", res.buffers[3], rear)
    assert_close("rear wheel angle (BLT)", res.buffers[4] - res.buffers[4][0], rear - rear[0])
    for b, what in ((5, "GR2"), (7, "BLT")):
        assert_close(f"d rear / d front ({what})", res.buffers[b], i)
        assert_close(f"d rear / d arm ({what})", res.buffers[b + 1], 1 - i)
    assert_close("d2 rear / d arm^2 (BLT)", res.buffers[9], 0.0)
    # The arm keeps its length: the rear wheel centre stays on its circle.
    assert_close("arm length", np.hypot(res.coords[:, 3], res.coords[:, 4]), 60.0)


# Racks that turn ----------------------------------------------------------------------------

# A lever turns about the fixed point P = 0 and carries a rack along its u-axis. The pinion
# (R = 5) rolls along the rack on the lever's left, its centre sliding in the lever's frame at
# v = 5. Two inputs: the lever angle and the pinion angle. Holding the lever and turning the pinion
# counter-clockwise rolls it backward along the rack, so i = -5.
# RK1: the lever is a ternary-1 frame (angle co-ordinate 3), the pinion centre its point Q.
RACK_LEVER_RK1 = """\
KIN ANA
TOPOLOGY
ELEM 1 TR1 1 2 3 4 5          ; lever with the pinion centre Q
     2 RK1 1 2 3 4 5 6 7      ; rack on the lever, pinion at Q
     3 HLF 4 5 7              ; pinion
FORM 1 LENV 1 1
     2 GEAR 2 2
     3 ANGV 1 3               ; DOF 1: lever angle
     4 ANGV 3 4               ; DOF 2: pinion angle
     5 LENU 1 -1              ; u of the pinion centre along the rack
NRDOF 2
GEOMETRY
XFIX 1 0.0
     2 0.0
     6 -5.0
XMOV 3 0.3
     4 18.0
     5 10.0
     7 0.0
PARA 1 5.0
     2 -20.0
     3 0.3
     4 0.0
MOVEMENT
TSTEPE 20
MOV_RELE 1 1.2
MOV_RELE 2 -3.0
STORAGE
BUFINP 1 1
BUFINP 2 2
BUFE0 -1 3
BUFKE1 -1 1 4
BUFKE1 -1 2 5
BUFKE2 -1 1 6
BUFKE2 -1 1 2 7
"""

# RK2: the lever is the bar P->L of a ternary-2 element (L at distance 30), R the pinion centre.
RACK_LEVER_RK2 = """\
KIN ANA
TOPOLOGY
ELEM 1 TR2 1 2 3 4 5 6        ; lever P->L with the pinion centre R
     2 RK2 1 2 3 4 5 6 7 8    ; rack along P->L, pinion at R
     3 HLF 5 6 8              ; pinion
FORM 1 LENL 1 1
     2 LENV 1 2
     3 GEAR 2 3
     4 ANGB 1 4               ; DOF 1: lever angle
     5 ANGV 3 5               ; DOF 2: pinion angle
     6 LENU 1 -1              ; u of the pinion centre along the rack
NRDOF 2
GEOMETRY
XFIX 1 0.0
     2 0.0
     7 -5.0
XMOV 3 28.0
     4 9.0
     5 18.0
     6 10.0
     8 0.0
PARA 1 30.0
     2 5.0
     3 -20.0
     4 0.3
     5 0.0
MOVEMENT
TSTEPE 20
MOV_RELE 1 1.2
MOV_RELE 2 -3.0
STORAGE
BUFINP 1 1
BUFINP 2 2
BUFE0 -1 3
BUFKE1 -1 1 4
BUFKE1 -1 2 5
BUFKE2 -1 1 6
BUFKE2 -1 1 2 7
"""


@pytest.mark.parametrize(("text", "centre_x"), [(RACK_LEVER_RK1, 4), (RACK_LEVER_RK2, 5)], ids=["RK1", "RK2"])
def test_pinion_rolling_on_a_turning_rack(text: str, centre_x: int, tmp_path: Path) -> None:
    res = mechfem.run_deck(write_deck(tmp_path, "rack", text))
    assert res.report.complete, res.report.stop_reason()
    i, g, v = -5.0, -20.0, 5.0
    k = np.arange(21)
    lever, pinion = res.buffers[1], res.buffers[2]
    assert_close("lever angle", lever, 0.3 + 1.2 * k / 20)
    assert_close("pinion angle", pinion, -3.0 * k / 20)
    # The distance rolled along the rack follows the pinion's rotation relative to the rack:
    # u = i (beta_a - beta_b) - g.
    u = i * (pinion - lever) - g
    assert_close("u", res.buffers[3], u)
    assert_close("d u / d lever", res.buffers[4], -i)
    assert_close("d u / d pinion", res.buffers[5], i)
    assert_close("d2 u / d lever^2", res.buffers[6], 0.0)
    assert_close("d2 u / d lever d pinion", res.buffers[7], 0.0)
    # The pinion centre in the lever's frame at (u, v).
    centre = res.coords[:, [centre_x - 1, centre_x]]
    c, s = np.cos(lever), np.sin(lever)
    assert_close("x of the pinion centre", centre[:, 0], u * c - v * s)
    assert_close("y of the pinion centre", centre[:, 1], u * s + v * c)


# Impossible geometry: clear messages -----------------------------------------------------------

BELT_WITHOUT_SPAN = """\
KIN ANA
TOPOLOGY
ELEM 1 HLF 1 2 3
     2 BLT 1 2 3 4 5 6 7 8   ; centres 10 apart, radii 50 and 20
FORM 1 BELT 2 1
     2 ANGV 1 2
NRDOF 1
GEOMETRY
XFIX 1 0.0
     2 0.0
     4 10.0
     5 0.0
     7 50.0
     8 20.0
XMOV 3 0.0
     6 0.0
"""

GR2_ZERO_RADIUS = """\
KIN ANA
TOPOLOGY
ELEM 1 HLF 1 2 3
     2 HLF 1 2 4
     3 HLF 1 2 5
     4 GR2 3 4 5 6 7
FORM 1 GEAR 4 1
     2 ANGV 2 2
     3 ANGV 1 3
NRDOF 1
GEOMETRY
XFIX 1 0.0
     2 0.0
     6 30.0
     7 0.0                   ; R_c = 0
XMOV 3 0.0
     4 0.0
     5 0.0
"""

# The arm brings Q within |R_P - R_Q| = 20 of P at an arm angle of acos(-0.875) = 151 degrees.
BELT_LOSES_SPAN = """\
KIN ANA
TOPOLOGY
ELEM 1 HLF 1 2 3
     2 BIN 9 10 4 5
     3 BLT 1 2 3 4 5 6 7 8
FORM 1 LENL 2 1
     2 BELT 3 2
     3 ANGV 1 3
     4 ANGB 2 4
NRDOF 2
GEOMETRY
XFIX 1 0.0
     2 0.0
     7 40.0
     8 20.0
     9 40.0
    10 0.0
XMOV 3 0.0
     4 70.0
     5 0.0
     6 0.0
MOVEMENT
TSTEPE 18
MOV_RELE 1 0.0
MOV_RELE 2 3.141592653589793
STORAGE
BUFINP 2 1
SAVEDATA 1
"""


def write_deck(folder: Path, name: str, text: str) -> Path:
    deck = folder / f"{name}.mec"
    deck.write_text(text)
    return deck


def test_belt_without_span_names_the_element(cli: Cli, tmp_path: Path) -> None:
    proc = cli("run", write_deck(tmp_path, "nospan", BELT_WITHOUT_SPAN), "-o", tmp_path / "out")
    assert proc.returncode == 1
    assert "Traceback" not in proc.stderr
    assert "element 2 (BLT) cannot be evaluated at the initial co-ordinates" in proc.stderr
    assert "no free span: centre distance 10 <= |R_P - R_Q| = 30" in proc.stderr
    assert "nospan.mec:4" in proc.stderr


def test_gr2_with_zero_radius_names_the_element(cli: Cli, tmp_path: Path) -> None:
    proc = cli("run", write_deck(tmp_path, "zero", GR2_ZERO_RADIUS), "-o", tmp_path / "out")
    assert proc.returncode == 1
    assert "Traceback" not in proc.stderr
    assert "element 4 (GR2) cannot be evaluated at the initial co-ordinates" in proc.stderr
    assert "the gear radius R_c is zero" in proc.stderr
    assert "zero.mec:6" in proc.stderr


def test_belt_losing_its_span_stops_the_motion_there(cli: Cli, tmp_path: Path) -> None:
    out = tmp_path / "out"
    proc = cli("run", write_deck(tmp_path, "lost", BELT_LOSES_SPAN), "-o", out)
    assert proc.returncode == 3
    assert "element 3 (BLT): the belt has no free span" in proc.stderr
    assert "stopped after position 16 of 19" in proc.stderr
    # Every position before the span vanished is kept.
    rows = (out / "lost.csv").read_text().splitlines()
    assert len(rows) == 1 + 16
    assert float(rows[-1]) == pytest.approx(15 * np.pi / 18, abs=1e-12)
