"""Masses and loads on the named model (mechfem.model.loads) and the inverse dynamics of its run, by name: a pendulum
and a slider-crank against closed forms, every kind of load, decks written and read back, and the messages of
every mistake."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import numpy.typing as npt
import pytest

import mechfem
from mechfem import Driven, Mechanism, Motion, Output
from mechfem.model.loads import Body, Gravity, LoadTable
from mechfem.model.mechanism import Storage
from mechfem.results.result import Analysis

FloatArray = npt.NDArray[np.float64]
G = 9.81


def close(a: npt.ArrayLike, b: npt.ArrayLike, atol: float = 1e-8) -> bool:
    return bool(np.allclose(np.asarray(a), np.asarray(b), rtol=1e-9, atol=atol))


# --- a pendulum: a bar of prescribed length turning about a fixed pivot, a point mass at its tip ----------------------

L, M = 0.8, 1.5
T = np.linspace(0.0, 2.0, 81)
THETA = -0.3 + 1.2 * np.sin(3.0 * T)
THETA_DOT = 3.6 * np.cos(3.0 * T)
THETA_DDOT = -10.8 * np.sin(3.0 * T)


def pendulum() -> Mechanism:
    m = Mechanism("pendulum")
    pivot = m.fixed("O", 0.0, 0.0)
    A = m.point("A", L * math.cos(-0.3), L * math.sin(-0.3))
    m.bar("bar", pivot, A, length=L, angle=Driven(name="theta"))
    m.single_coordinate("height", A.y, value=Output("tip_y"))
    m.point_mass(A, M)
    m.gravity(0.0, -G)
    return m


def swing() -> Motion:
    return Motion.table(THETA, THETA_DOT, THETA_DDOT, time=T)


def test_pendulum_drive_torque_stress_and_reaction_have_their_closed_forms() -> None:
    m = pendulum()
    r = m.run(swing())
    assert r.dynamic and r.complete and close(r.input("theta"), THETA)
    # Drive torque: m l^2 theta'' + m g l cos(theta).
    torque = M * L**2 * THETA_DDOT + M * G * L * np.cos(THETA)
    assert close(r.drive_torque(), torque) and close(r.drive_torque("theta"), torque)
    assert close(r.stress("theta"), torque)
    # Axial force of the bar, positive when it pushes its ends apart: -m l theta'^2 + m g sin(theta).
    sigma = -M * L * THETA_DOT**2 + M * G * np.sin(THETA)
    assert close(r.stress("bar.length"), sigma) and close(r.stress(m["bar"].length), sigma)
    # The force of the frame at the pivot: m a_tip - m g.
    a_tip = L * np.column_stack(
        [
            -(THETA_DOT**2) * np.cos(THETA) - THETA_DDOT * np.sin(THETA),
            -(THETA_DOT**2) * np.sin(THETA) + THETA_DDOT * np.cos(THETA),
        ]
    )
    reaction = M * a_tip - M * np.array([0.0, -G])
    assert r.reaction("O").shape == (81, 2) and close(r.reaction("O"), reaction)
    assert close(r.reaction("O.y"), reaction[:, 1]) and close(r.reaction(m["O"].x), reaction[:, 0])
    assert close(r.acceleration("A"), a_tip, atol=1e-7)


def test_pendulum_energy_power_and_mass_matrix() -> None:
    r = pendulum().run(swing())
    e = r.energy()
    assert close(e.kinetic, 0.5 * M * L**2 * THETA_DOT**2)
    assert close(e.potential, M * G * L * np.sin(THETA))
    assert close(e.total, e.kinetic + e.potential)
    kinetic, potential, total = e
    assert kinetic is e.kinetic and total is e.total
    assert close(r.power(), r.drive_torque() * THETA_DOT)
    assert r.mass_matrix().shape == (81, 1, 1) and close(r.mass_matrix()[:, 0, 0], M * L**2)


@pytest.mark.parametrize("kind", ["load", "load_table", "spring", "motor", "load_on_output", "force"])
def test_every_load_changes_the_drive_torque_by_its_generalised_force(kind: str) -> None:
    plain = pendulum().run(swing()).drive_torque()
    m = pendulum()
    if kind == "load":
        m.load("theta", 3.0)
        q = np.full_like(T, 3.0)
    elif kind == "load_table":
        m.load_table(m["bar"].angle, [0.5, 1.0, 1.5], [1.0, -2.0, 4.0])
        q = np.interp(T, [0.5, 1.0, 1.5], [1.0, -2.0, 4.0])
    elif kind == "spring":
        m.spring("theta", 20.0, 0.1, damping=0.7)
        q = -20.0 * (THETA - 0.1) - 0.7 * THETA_DOT
    elif kind == "motor":
        m.motor(m["theta"], 5.0, 8.0)
        q = 5.0 * (1.0 - THETA_DOT / 8.0)
    elif kind == "load_on_output":
        # A force along the tip's height is a vertical force at the tip: it works through d y / d theta.
        m.load("tip_y", 4.0)
        q = 4.0 * L * np.cos(THETA)
    else:
        m.force("A", 0.0, 4.0)
        q = 4.0 * L * np.cos(THETA)
    r = m.run(swing())
    assert close(r.drive_torque(), plain - q, atol=1e-7)


def test_springs_store_potential_energy() -> None:
    m = pendulum()
    m.spring("theta", 20.0, 0.1)
    e = m.run(swing()).energy()
    assert close(e.potential, M * G * L * np.sin(THETA) + 0.5 * 20.0 * (THETA - 0.1) ** 2)


# --- a slider-crank with masses on crank and rod, a slider mass and a gas force ---------------------------------------

R, ROD = 0.1, 0.3
BODIES = {"crank": (0.5, 0.05, 0.0, 1e-3), "rod": (1.2, 0.15, 0.01, 9e-3)}
SLIDER, GAS = 0.8, (-100.0, 0.0)


def slider_crank() -> Mechanism:
    m = Mechanism("slider crank")
    A0 = m.fixed("A0", 0.0, 0.0)
    A, B = m.point("A", 0.0878, 0.0479), m.point("B", 0.384, 0.0, fixed="y")
    m.bar("crank", A0, A, length=R, angle=Driven(start=0.5, name="phi"))
    m.bar("rod", A, B, length=ROD, angle=Output("rod_angle"))
    for name, (mass, u, v, j) in BODIES.items():
        m.mass(name, mass, u=u, v=v, J=j)
    m.point_mass("B", SLIDER)
    m.force("B", *GAS)
    m.gravity(0.0, -G)
    return m


def body_motion(r: Analysis, name: str, point: str | None, angle: str) -> tuple[FloatArray, FloatArray, FloatArray]:
    """Centre of mass, its velocity and acceleration of a body from the run's kinematics (rigid-body formulas)."""
    _, u, v, _ = BODIES[name]
    beta, w, alpha = r.value(angle), r.velocity(angle), r.acceleration(angle)
    rel = np.column_stack([u * np.cos(beta) - v * np.sin(beta), u * np.sin(beta) + v * np.cos(beta)])
    perp = np.column_stack([-rel[:, 1], rel[:, 0]])
    origin = np.zeros_like(rel) if point is None else r.value(point)
    v_p = np.zeros_like(rel) if point is None else r.velocity(point)
    a_p = np.zeros_like(rel) if point is None else r.acceleration(point)
    return origin + rel, v_p + w[:, None] * perp, a_p + alpha[:, None] * perp - (w**2)[:, None] * rel


def test_slider_crank_drive_torque_energies_and_power() -> None:
    m = slider_crank()
    r = m.run(Motion.by(72, 2 * math.pi, dt=0.005))
    assert r.complete
    speed = r.velocity("phi")
    assert close(r.power(), r.drive_torque() * speed)
    e = r.energy()
    assert close(e.total, e.kinetic + e.potential)
    # T, V and the balance of power from the rigid-body motion of each body.
    kinetic = 0.5 * SLIDER * np.sum(r.velocity("B") ** 2, axis=1)
    potential = np.zeros(r.positions)
    inertial = SLIDER * np.sum(r.acceleration("B") * r.velocity("B"), axis=1)
    applied = np.sum(np.array(GAS) * r.velocity("B"), axis=1)
    for name, point, angle in (("crank", None, "phi"), ("rod", "A", "rod_angle")):
        mass, _, _, j = BODIES[name]
        c, v_c, a_c = body_motion(r, name, point, angle)
        kinetic += 0.5 * mass * np.sum(v_c**2, axis=1) + 0.5 * j * r.velocity(angle) ** 2
        potential += mass * G * c[:, 1]
        inertial += mass * np.sum(a_c * v_c, axis=1) + j * r.acceleration(angle) * r.velocity(angle)
        applied += mass * -G * v_c[:, 1]
    assert close(e.kinetic, kinetic) and close(e.potential, potential)
    assert close(r.drive_torque() * speed, inertial - applied, atol=1e-6)
    assert close(e.kinetic, 0.5 * r.mass_matrix()[:, 0, 0] * speed**2)
    # The guide holds the slider up: its reaction is on B.y, the only fixed co-ordinate of B.
    assert r.reaction("B.y").shape == (73,)
    with pytest.raises(KeyError, match=r"B\.x moves: only the frame .* reaction\('B\.y'\)"):
        r.reaction("B")
    with pytest.raises(KeyError, match="A.x, A.y moves"):
        r.reaction("A")


# --- decks ------------------------------------------------------------------------------------------------------------


def everything() -> Mechanism:
    """A slider-crank with every kind of mass and load, a flywheel (a half beam keyed to the crank) among them."""
    m = slider_crank()
    fly = m.half_beam("flywheel", m["A0"], 0.5)
    m.fixed_angle("key", fly, m["crank"])
    m.mass(fly, 2.0, J=0.01)
    m.inertia("flywheel.beta", 0.05)
    m.single_coordinate("slide", m["B.x"], value=Output("s"))
    m.load("phi", 2.0)
    m.load_table("phi", [0.0, 0.1, 0.3], [0.0, 5.0, -1.0])
    m.spring("s", 500.0, 0.3, 2.0)
    m.motor("phi", 10.0, 200.0)
    return m


def storage() -> Storage:
    s = Storage().buffer(1, "BUFDRV", "phi").buffer(2, "BUFSIG", "rod.length").buffer(3, "BUFREA", "A0.y")
    s.buffer(4, "BUFEKIN").buffer(5, "BUFEPOT").buffer(6, "BUFPOW").buffer(7, "BUFMRED", "phi", "phi")
    return s


def test_every_mass_and_load_is_written_as_a_line_of_the_dynamics_block(tmp_path: Path) -> None:
    m = everything()
    text = m.to_deck(Motion.by(36, 2 * math.pi, dt=0.01), storage())
    assert text.splitlines()[1] == "DYN ANA"
    block = text.split("DYNAMICS\n")[1].split("MOVEMENT\n")[0].splitlines()
    # The deck reader's order: bodies, point masses, inertias, gravity, forces, then the loads.
    assert [line.split()[0] for line in block] == [
        "MASS", "MASS", "MASS", "PMASS", "INERTIA", "GRAVITY", "FORCE", "LOAD", "LOADFUNC", "SPRING", "MOTOR",
    ]  # fmt: skip
    assert block[0] == "MASS 1 0.5 0.05 0.0 0.001"
    assert "LOADFUNC 4 slider_crank_load1.dat" in block and "SPRING -2 500.0 0.3 2.0" in block
    lines = text.splitlines()
    assert "BUFDRV 1 1" in lines and "BUFMRED 1 1 7" in lines
    path = m.save_deck(tmp_path / "sc.mec", Motion.by(36, 2 * math.pi, dt=0.01), storage())
    assert (tmp_path / "slider_crank_load1.dat").read_text().splitlines()[1:] == ["0.0 0.0", "0.1 5.0", "0.3 -1.0"]
    assert mechfem.run_deck(path).report.complete
    # Without masses or loads a mechanism stays kinematic.
    assert Mechanism("empty").to_deck().splitlines()[1] == "KIN ANA"


def test_model_and_deck_read_back_give_the_same_dynamics(tmp_path: Path) -> None:
    m = everything()
    motion = Motion.by(36, 2 * math.pi, dt=0.01)
    r = m.run(motion, storage())
    path = m.save_deck(tmp_path / "sc.mec", motion, storage())
    ref = mechfem.run_deck(path)
    back = Mechanism.from_deck(path)
    assert m.loads is not None and back.loads is not None
    assert [type(i) for i in back.loads] == [type(i) for i in m.loads.in_deck_order()]

    # The deck read back is the same deck, line for line, its NAMES block included.
    def bare(text: str) -> list[str]:
        return [line.split(";")[0].strip() for line in text.splitlines()[1:]]

    assert bare(back.to_deck()) == bare(m.to_deck(motion, storage()))
    again = Mechanism.from_deck(back.save_deck(tmp_path / "again" / "sc.mec"))
    assert again.to_deck() == back.to_deck()
    rb = back.run()
    for b in range(1, 8):
        assert np.array_equal(r.buffers[b], ref.buffers[b]) and np.array_equal(rb.buffers[b], ref.buffers[b])
    # Results by name are the buffers of the deck.
    assert np.array_equal(r.drive_torque(), ref.buffers[1]) and np.array_equal(r.stress("rod.length"), ref.buffers[2])
    assert np.array_equal(r.reaction("A0.y"), ref.buffers[3]) and np.array_equal(r.energy().kinetic, ref.buffers[4])
    assert np.array_equal(r.energy().potential, ref.buffers[5]) and np.array_equal(r.power(), ref.buffers[6])
    assert np.array_equal(r.mass_matrix()[:, 0, 0], ref.buffers[7])
    assert np.array_equal(rb.drive_torque(), r.drive_torque()) and np.array_equal(rb.mass_matrix(), r.mass_matrix())
    # The deck run's own dynamic series (for its report) comes with the result of the model too.
    run = r.run_result()
    assert run.model.mode == "DYN ANA" and run.dynamic is not None and ref.dynamic is not None
    for field in ("inputs", "drive", "kinetic", "potential", "power"):
        assert np.array_equal(getattr(run.dynamic, field), getattr(ref.dynamic, field)), field


def test_a_variant_keeps_the_masses_and_loads() -> None:
    m = pendulum()
    v = m.variant({"bar.length": 1.0})
    assert v.loads is not None and len(v.loads) == 2 and v.loads.gravity == (0.0, -G)
    assert v.loads.of(Gravity) == [Gravity(0.0, -G)] and m.loads is not None and v.loads is not m.loads
    m.gravity(0.0, -1.0)
    assert m.loads.gravity == (0.0, -1.0) and len(m.loads) == 2
    assert v.run(swing()).drive_torque()[0] == pytest.approx(M * 1.0**2 * THETA_DDOT[0] + M * G * np.cos(THETA[0]))


# --- mistakes ---------------------------------------------------------------------------------------------------------


def test_masses_and_loads_are_checked_with_the_model_names() -> None:
    m = slider_crank()
    with pytest.raises(ValueError, match="the mass of 'crank' must not be negative, got -1.0"):
        m.mass("crank", -1.0)
    with pytest.raises(ValueError, match="the moment of inertia J of 'rod' must not be negative"):
        m.mass("rod", 1.0, J=-0.1)
    with pytest.raises(ValueError, match="u of the mass of 'rod' must be a finite number, not nan"):
        m.mass(m["rod"], 1.0, u=float("nan"))
    with pytest.raises(ValueError, match="the mass at 'B' must be a finite number"):
        m.point_mass("B", float("inf"))
    with pytest.raises(TypeError, match="mass\\(\\) must be an element of the mechanism 'slider crank', got Point"):
        m.mass("B", 1.0)
    with pytest.raises(TypeError, match="point_mass\\(\\) must be a point"):
        m.point_mass("crank", 1.0)
    with pytest.raises(KeyError, match="no part named 'C' in the mechanism 'slider crank'"):
        m.force("C", 1.0, 0.0)
    with pytest.raises(ValueError, match="belongs to another mechanism"):
        m.point_mass(Mechanism("other").point("B", 0.0, 0.0), 1.0)
    with pytest.raises(ValueError, match="the inertia on 'A.x' must not be negative"):
        m.inertia("A.x", -1.0)
    with pytest.raises(ValueError, match="gravity gy must be a finite number"):
        m.gravity(0.0, float("nan"))
    with pytest.raises(ValueError, match="fy of the force at 'B' must be a finite number"):
        m.force("B", 0.0, float("nan"))
    with pytest.raises(ValueError, match=r"load\(\): rod\.length - crank\.length is neither prescribed nor an output"):
        m.load(m["rod"].length - m["crank"].length, 1.0)
    with pytest.raises(TypeError, match="spring\\(\\) must be a row, an output or a form parameter"):
        m.spring("A", 1.0, 0.0)
    with pytest.raises(ValueError, match="the stiffness of the spring on 'rod_angle' must not be negative"):
        m.spring("rod_angle", -1.0, 0.0)
    with pytest.raises(ValueError, match="the damping of the spring on 'phi' must not be negative"):
        m.spring("phi", 1.0, 0.0, damping=-2.0)
    with pytest.raises(ValueError, match="the no-load speed of the motor on 'phi' must not be 0"):
        m.motor("phi", 1.0, 0.0)
    with pytest.raises(ValueError, match="the time 0.5 comes before the time 1.0"):
        m.load_table("phi", [0.0, 1.0, 0.5], [1.0, 2.0, 3.0])
    with pytest.raises(ValueError, match="the load table on 'phi' needs as many values as times"):
        m.load_table("phi", [0.0, 1.0], [1.0])
    with pytest.raises(ValueError, match="the load table on 'phi' must hold finite numbers only"):
        m.load_table("phi", [0.0, 1.0], [1.0, float("nan")])
    with pytest.raises(ValueError, match="cannot be empty or hold blanks"):
        m.load_table("phi", [0.0], [1.0], file="my table.dat")
    assert m.loads is not None and len(m.loads) == len(slider_crank().loads or [])


def test_a_free_form_parameter_carries_no_load() -> None:
    m = everything()
    with pytest.raises(
        ValueError,
        match=r"spring\(\): flywheel\.angle is neither prescribed nor an output, so nothing can carry a load on it: "
        r"make it an output with Mechanism\.output\(\)",
    ):
        m.spring(m["flywheel"].angle, 1.0, 0.0)
    m.output("wheel", m["flywheel"].angle)
    assert m.spring(m["flywheel"].angle, 1.0, 0.0).row is m["wheel"]
    with pytest.raises(TypeError, match="load\\(\\) must be a row, an output or a form parameter .* got Coordinate"):
        m.load(m["A.y"], 1.0)


@pytest.mark.parametrize("kind", ["GR1", "GR2", "RK1", "RK2", "BLT", "CRD"])
def test_a_mass_on_an_element_without_a_frame_says_where_it_goes(kind: str) -> None:
    m = Mechanism("frames")
    P, Q, R = m.fixed("P", 0.0, 0.0), m.point("Q", 1.0, 0.0), m.point("R", 1.0, 1.0)
    e = {
        "GR1": lambda: m.gear_pair("e", 0.0, 0.0, 0.0, ratio=-2.0),
        "GR2": lambda: m.gear_pair("e", 0.0, 0.0, 0.0, radii=(0.1, 0.2)),
        "RK1": lambda: m.rack1("e", P, 0.0, Q, 0.1, 0.0),
        "RK2": lambda: m.rack2("e", P, Q, R, 0.1, 0.0),
        "BLT": lambda: m.belt("e", P, 0.0, Q, 0.0, 0.1, 0.1),
        "CRD": lambda: m.single_coordinate("e", Q.x),
    }[kind]()
    words = {"GR1": "gear pair", "GR2": "gear pair", "RK1": "rack", "RK2": "rack", "BLT": "belt"}
    what = words.get(kind, "single co-ordinate element")
    with pytest.raises(ValueError, match=f"element 'e' is a {what}, which has no frame to carry a mass") as info:
        m.mass(e, 1.0)
    if kind == "CRD":
        assert "point_mass()" in str(info.value)
    else:
        assert "half beam or ternary-1 element" in str(info.value) and "inertia()" in str(info.value)
        assert "'e.beta_a'" in str(info.value)
    # A refused mass leaves the mechanism kinematic.
    assert m.loads is None


def test_results_of_the_dynamics_need_masses_or_loads() -> None:
    m = pendulum()
    m.loads = None
    r = m.run(swing())
    assert not r.dynamic
    for ask in (r.drive_torque, r.energy, r.power, r.mass_matrix, lambda: r.stress("theta"), lambda: r.reaction("O")):
        with pytest.raises(ValueError, match="'pendulum' has no masses or loads, .*Mechanism.mass, point_mass"):
            ask()


def test_results_of_the_dynamics_are_asked_for_by_name() -> None:
    r = pendulum().run(swing())
    with pytest.raises(KeyError, match="'tip_y' is an output, which carries no stress"):
        r.stress("tip_y")
    with pytest.raises(KeyError, match="no input named 'A' \\(inputs: theta\\)"):
        r.drive_torque("A")
    with pytest.raises(TypeError, match="not a point or co-ordinate"):
        r.reaction("bar")
    with pytest.raises(TypeError, match="'A' is a point of the mechanism 'pendulum', not a prescribed value or input"):
        r.stress("A")


def test_a_deck_mistake_in_a_dynamic_model_names_the_model_part() -> None:
    m = pendulum()
    with pytest.raises(mechfem.DeckError, match="free motion .* cannot drive the mechanism 'pendulum'") as info:
        m.run(Motion.free(10, 0.01))
    assert info.value.name == "theta"  # type: ignore[attr-defined]


def test_items_are_frozen_and_name_the_model_objects() -> None:
    m = slider_crank()
    body = m.loads.of(Body)[0] if m.loads else None
    assert body is not None and body.element is m["crank"] and body.u == 0.05
    with pytest.raises(AttributeError):
        body.mass = 2.0  # type: ignore[misc]
    table = m.load_table("phi", [0.0, 1.0], [1.0, 2.0])
    assert isinstance(table, LoadTable) and table.row is m["phi"] and table.time.dtype == np.float64
