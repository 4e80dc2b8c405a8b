"""The designer's outputs (BUFTRA, BUFPIN, BUFSHAKE, a MOTOR's torque in BUFDRV of DYN SIM) against closed forms
and Newton-Euler worked by hand, independently of the core's formulas."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

import mechfem

DECK = Path(__file__).parents[1] / "decks" / "fourbar_pins.mec"
G = np.array([0.0, -9.81])
#: element: (mass, u, v, J) as the deck's MASS lines give them
BODIES = {"crank": (2.0, 0.4, 0.1, 0.3), "coupler": (5.0, 1.6, 0.7, 4.0), "rocker": (3.0, 1.2, -0.2, 2.5)}
BRAKE = -4.0  # LOAD -1: torque on the rocker angle


def cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    return a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]


def perp(a: np.ndarray) -> np.ndarray:
    return np.stack([-a[..., 1], a[..., 0]], axis=-1)


@pytest.fixture(scope="module")
def run() -> mechfem.RunResult:
    return mechfem.run_deck(DECK)


def pair(r: mechfem.RunResult, b: int) -> np.ndarray:
    return np.column_stack([r.buffers[b], r.buffers[b + 1]])


def kinematics(r: mechfem.RunResult) -> dict[str, dict[str, np.ndarray]]:
    """Each body's P, Q, centre, its acceleration and the angular acceleration, from the points' recorded
    positions, velocities and accelerations by rigid-body kinematics: a_Q - a_P = alpha k x d - omega^2 d."""
    n = r.positions
    zero = np.zeros((n, 2))
    x = r.coords
    pts = {
        "A0": (zero, zero, zero),
        "B0": (np.tile([4.0, 0.0], (n, 1)), zero, zero),
        "A": (x[:, 4:6], pair(r, 40), pair(r, 44)),
        "B": (x[:, 6:8], pair(r, 42), pair(r, 46)),
    }
    ends = {"crank": ("A0", "A"), "coupler": ("A", "B"), "rocker": ("B0", "B")}
    out = {}
    for name, (p, q) in ends.items():
        (xp, vp, ap), (xq, vq, aq) = pts[p], pts[q]
        d = xq - xp
        l2 = np.sum(d * d, axis=1)
        omega = cross(d, vq - vp) / l2
        alpha = cross(d, aq - ap) / l2
        m, u, v, _ = BODIES[name]
        e = d / np.sqrt(l2)[:, None]
        rg = u * e + v * perp(e)
        a_g = ap + alpha[:, None] * perp(rg) - (omega**2)[:, None] * rg
        out[name] = {"P": xp, "Q": xq, "G": xp + rg, "aG": a_g, "alpha": alpha}
    return out


def body(
    a: np.ndarray,
    b: np.ndarray,
    row: int,
    kb: dict[str, np.ndarray],
    i: int,
    forces: list[tuple[int, float, np.ndarray]],
    torque_col: int | None,
    torque: float,
    props: tuple[float, float, float, float],
) -> None:
    """The three equations of one link at position i into rows ``row..row+2`` of ``a x = b``: forces (unknown
    column, sign, point of application) and an unknown (``torque_col``) or known torque on the link."""
    m, _, _, jg = props
    g_pt = kb["G"][i]
    for col, sign, at in forces:
        a[row, col] += sign
        a[row + 1, col + 1] += sign
        arm = at - g_pt
        a[row + 2, col] += -sign * arm[1]
        a[row + 2, col + 1] += sign * arm[0]
    if torque_col is not None:
        a[row + 2, torque_col] = 1.0
    b[row : row + 2] = m * kb["aG"][i] - m * G
    b[row + 2] = jg * kb["alpha"][i] - torque


def newton_euler(r: mechfem.RunResult) -> dict[str, np.ndarray]:
    """Pin forces, frame reactions and drive torque by Newton-Euler on each link, nine equations at each position:
    R_A0 (frame on crank), P_A (crank on pin A, = pin on coupler), F_B (coupler on pin B, = pin on rocker),
    R_B0 (frame on rocker) and the drive torque T on the crank; the brake acts on the rocker as a torque."""
    k = kinematics(r)
    n = r.positions
    sol = np.zeros((n, 9))
    ck, kk, rk = k["crank"], k["coupler"], k["rocker"]
    for i in range(n):
        a = np.zeros((9, 9))
        b = np.zeros(9)
        body(a, b, 0, k["crank"], i, [(0, 1.0, ck["P"][i]), (2, -1.0, ck["Q"][i])], 8, 0.0, BODIES["crank"])
        body(a, b, 3, k["coupler"], i, [(2, 1.0, kk["P"][i]), (4, -1.0, kk["Q"][i])], None, 0.0, BODIES["coupler"])
        body(a, b, 6, k["rocker"], i, [(4, 1.0, rk["Q"][i]), (6, 1.0, rk["P"][i])], None, BRAKE, BODIES["rocker"])
        sol[i] = np.linalg.solve(a, b)
    return {"R_A0": sol[:, 0:2], "P_A": sol[:, 2:4], "F_B": sol[:, 4:6], "R_B0": sol[:, 6:8], "T": sol[:, 8]}


def test_pin_forces_are_those_of_newton_euler_on_every_link(run: mechfem.RunResult) -> None:
    ne = newton_euler(run)
    scale = np.max(np.abs(ne["P_A"]))
    assert scale > 10.0  # the test means something: the links are loaded
    for got, want in [
        (pair(run, 12), ne["P_A"]),  # crank on pin A
        (pair(run, 14), -ne["P_A"]),  # coupler on pin A
        (pair(run, 16), ne["F_B"]),  # coupler on pin B
        (pair(run, 20), -ne["F_B"]),  # rocker on pin B
        (pair(run, 10), -ne["R_A0"]),  # crank on the frame pivot A0
        (pair(run, 22), -ne["R_B0"]),  # rocker on the frame pivot B0
    ]:
        np.testing.assert_allclose(got, want, rtol=0, atol=1e-7 * scale)
    np.testing.assert_allclose(run.buffers[3], ne["T"], rtol=1e-9, atol=1e-9 * scale)
    # The coupler point C is no pin: nothing else meets there.
    np.testing.assert_allclose(pair(run, 18), 0.0, atol=1e-9 * scale)


def test_pin_forces_at_a_frame_pivot_are_minus_the_reaction(run: mechfem.RunResult) -> None:
    np.testing.assert_allclose(pair(run, 10), -pair(run, 4), rtol=1e-12, atol=1e-9)
    np.testing.assert_allclose(pair(run, 22), -pair(run, 6), rtol=1e-12, atol=1e-9)


def test_on_every_body_the_pins_give_m_a_minus_the_loads(run: mechfem.RunResult) -> None:
    k = kinematics(run)
    for name, pins in [("crank", (10, 12)), ("coupler", (14, 16, 18)), ("rocker", (20, 22))]:
        m = BODIES[name][0]
        on_body = -sum(pair(run, b) for b in pins)
        np.testing.assert_allclose(on_body + m * G, m * k[name]["aG"], rtol=1e-9, atol=1e-8)


def test_shaking_is_minus_the_sum_of_the_inertia_forces(run: mechfem.RunResult) -> None:
    k = kinematics(run)
    force = -sum(BODIES[n][0] * k[n]["aG"] for n in BODIES)
    moment = -sum(BODIES[n][0] * cross(k[n]["G"], k[n]["aG"]) + BODIES[n][3] * k[n]["alpha"] for n in BODIES)
    np.testing.assert_allclose(pair(run, 30), force, rtol=1e-9, atol=1e-8)
    np.testing.assert_allclose(run.buffers[32], moment, rtol=1e-9, atol=1e-8)


def test_transmission_angle_is_the_law_of_cosines(run: mechfem.RunResult) -> None:
    # Triangle A B B0 with A on the crank circle: |AB| = 3.5, |B B0| = 3, |A B0|^2 = 17 - 8 cos(phi).
    phi = run.buffers[1]
    s2 = 17.0 - 8.0 * np.cos(phi)
    mu = np.arccos((3.5**2 + 3.0**2 - s2) / (2 * 3.5 * 3.0))
    np.testing.assert_allclose(run.buffers[2], mu, rtol=0, atol=1e-9)


ROTOR = """DYN ANA
TOPOLOGY
ELEM 1 BIN 1 2 3 4
FORM 1 LENL 1 1
     2 ANGB 1 2
NRDOF 1
GEOMETRY
XFIX 1 0.0
     2 0.0
XMOV 3 1.0
     4 0.0
PARA 1 1.0
     2 0.0
DYNAMICS
MASS 1 2.0 {u} 0.0 0.5
MOVEMENT
TSTEPE 10 0.1
MOV_RELE 1 {turn}
STORAGE
BUFINP 1 1
BUFSHAKE 2
END
"""


def test_a_balanced_rotor_does_not_shake(tmp_path: Path) -> None:
    deck = tmp_path / "rotor.mec"
    deck.write_text(ROTOR.format(u=0.0, turn=2.0))
    r = mechfem.run_deck(deck)
    for b in (2, 3, 4):
        np.testing.assert_allclose(r.buffers[b], 0.0, atol=1e-12)
    # Out of balance by 2 kg at 0.3: the centrifugal force m omega^2 r along the crank, at 2 rad/s.
    deck.write_text(ROTOR.format(u=0.3, turn=2.0))
    r = mechfem.run_deck(deck)
    phi = r.buffers[1]
    want = 2.0 * 2.0**2 * 0.3 * np.column_stack([np.cos(phi), np.sin(phi)])
    # Positions hold to the Newton tolerance: so does the force.
    np.testing.assert_allclose(pair(r, 2), want, rtol=0, atol=1e-8)
    np.testing.assert_allclose(r.buffers[4], 0.0, atol=1e-12)


def test_a_motor_driven_dof_records_the_motor_torque(tmp_path: Path) -> None:
    text = DECK.read_text().replace("DYN ANA", "DYN SIM")
    text = text.replace("LOAD -1 -4.0", "LOAD -1 -4.0\nMOTOR 6 60.0 12.0")
    text = text.replace("TSTEPE 24 0.02\nMOV_RELE 1 6.283185307179586", "TSTEPE 20 0.02\nMOV_DYN 1 3.0")
    text = text.replace("BUFEKIN 50", "BUFEKIN 50\nBUFVE 6 51")
    deck = tmp_path / "motor.mec"
    deck.write_text(text)
    r = mechfem.run_deck(deck)
    speed = r.buffers[51]
    assert np.ptp(speed) > 0.1  # the crank speeds up or slows down: the torque is not one number
    np.testing.assert_allclose(r.buffers[3], 60.0 * (1.0 - speed / 12.0), rtol=1e-12)
    # The simulated motion is the one the motor makes: Newton-Euler on the links needs the motor's torque, and
    # gives the pin forces recorded.
    ne = newton_euler(r)
    scale = np.max(np.abs(ne["P_A"]))
    np.testing.assert_allclose(ne["T"], r.buffers[3], rtol=0, atol=1e-7 * scale)
    np.testing.assert_allclose(pair(r, 16), ne["F_B"], rtol=0, atol=1e-7 * scale)
    np.testing.assert_allclose(pair(r, 10), -ne["R_A0"], rtol=0, atol=1e-7 * scale)


EXAMPLES = Path(__file__).parents[2] / "examples"


def test_a_non_grashof_crank_rocks_between_its_limit_positions() -> None:
    from mechfem.results.designer import sweep_lines

    r = mechfem.run_deck(EXAMPLES / "limits" / "nongrashof.mec")
    # Coupler and rocker in line: |A B0| = 1.2 + 1.4 with A on the crank circle (1.5) about A0, |A0 B0| = 2.
    limit = math.acos((1.5**2 + 2.0**2 - 2.6**2) / (2 * 1.5 * 2.0))
    (line,) = [x for x in sweep_lines(r) if "rocks" in x]
    lo, hi = (float(w) for w in line.split("between the limit positions at ")[1].split(" (")[0].split(" and "))
    assert lo == pytest.approx(-limit, abs=1e-5) and hi == pytest.approx(limit, abs=1e-5)


def test_the_print_file_names_the_worst_transmission_angle(run: mechfem.RunResult) -> None:
    from mechfem.output.files import print_file_lines

    lines = print_file_lines(run)
    at = lines.index("TRANSMISSION ANGLES")
    mu = np.degrees(run.buffers[2])
    k = int(np.argmax(np.abs(mu - 90.0)))
    assert f"worst deviation from 90 deg {abs(mu[k] - 90.0):.4g} deg" in lines[at + 1]
    assert f"at position {k + 1} " in lines[at + 1]
    assert any("full turn" in x for x in lines[lines.index("INPUT SWEEP") :])


def test_pin_forces_shaking_and_angles_by_name(run: mechfem.RunResult) -> None:
    np.testing.assert_array_equal(run.pin_force("crank", "A"), pair(run, 12))
    np.testing.assert_array_equal(run.pin_force(3, "B0"), pair(run, 22))
    assert set(run.pin_forces("B")) == {"coupler", "rocker"}
    np.testing.assert_array_equal(run.shaking(), np.column_stack([run.buffers[30], run.buffers[31], run.buffers[32]]))
    np.testing.assert_allclose(run.transmission_angle("coupler", "rocker"), run.buffers[2], atol=1e-12)
    with pytest.raises(KeyError, match="not a point of crank"):
        run.pin_force("crank", "B")
    with pytest.raises(KeyError, match="pin_forces"):
        run.reaction("A")
    # The columns of to_pandas() (without importing pandas, which takes seconds).
    table = run.table()
    for column in ("drive(phi)", "reaction(A0.x)", "pin(coupler,B).y", "shaking.M", "Ekin", "mu(coupler,rocker)"):
        assert column in table


def test_a_named_model_records_every_pin_force() -> None:
    deck = mechfem.Mechanism.from_deck(DECK)
    r = deck.run()
    deck_run = mechfem.run_deck(DECK)
    np.testing.assert_allclose(r.pin_force("coupler", "B"), pair(deck_run, 16), rtol=1e-12, atol=1e-9)
    np.testing.assert_allclose(r.shaking()[:, 2], deck_run.buffers[32], rtol=1e-12, atol=1e-9)
    table = r.table()
    for column in ("drive(phi)", "sigma(phi)", "reaction(B0.y)", "pin(rocker,B0).x", "shaking.x", "Ekin", "power"):
        assert column in table, list(table)
    np.testing.assert_array_equal(table["pin(coupler,B).y"], r.pin_force("coupler", "B")[:, 1])


def test_the_outputs_speak_the_decks_units(tmp_path: Path) -> None:
    text = DECK.read_text().replace("DYN ANA", "DYN ANA\nUNITS LENGTH mm ANGLE deg MASS kg FORCE N TIME s")
    deck = tmp_path / "units.mec"
    deck.write_text(text.replace("MOV_RELE 1 6.283185307179586", "MOV_RELE 1 360"))
    r = mechfem.run_deck(deck)
    units = {b.number: b.unit for b in r.storage.buffers}
    assert (units[2], units[16], units[17], units[30], units[32]) == ("deg", "N", "N", "N", "N·mm")
    assert 0.0 < float(np.min(r.buffers[2])) and float(np.max(r.buffers[2])) < 180.0
    np.testing.assert_allclose(r.transmission_angle("coupler", "rocker"), r.buffers[2], atol=1e-10)
    named = mechfem.Mechanism.from_deck(deck).run()
    np.testing.assert_allclose(named.pin_force("coupler", "B"), pair(r, 16), rtol=1e-12, atol=1e-12)


def test_the_report_says_the_transmission_and_the_sweep(run: mechfem.RunResult) -> None:
    from mechfem.report.html import report_data

    lines = report_data(run)["designer"]
    assert lines[0] == "TRANSMISSION ANGLES" and "INPUT SWEEP" in lines


def test_a_model_writes_its_designer_buffers_back_and_takes_them_by_name() -> None:
    m = mechfem.Mechanism.from_deck(DECK)
    lines = [line for line in m.to_deck().splitlines() if line.startswith(("BUFPIN", "BUFSHAKE", "BUFTRA"))]
    # One line per keyword: the y of a pin force and the y, moment of the shaking are its line's, not lines.
    assert lines.count("BUFSHAKE 30") == 1 and len(lines) == 9
    assert m.storage is not None
    m.storage.buffer(200, "BUFPIN", "crank", "A.x", "A.y")
    r = m.run()
    np.testing.assert_array_equal(np.column_stack([r.buffers[200], r.buffers[201]]), pair(r, 12))
