"""Simulations (mode DYN SIM) from the named model: a pendulum released at a large amplitude against its exact period
and its energy, the deck written for a simulation and run by ``mechfem.run_deck``, an input driven beside one that
moves under the forces, a simulation that stops early, and the messages of every mistake."""

from __future__ import annotations

import math
from collections.abc import Callable
from pathlib import Path

import numpy as np
import numpy.typing as npt
import pytest

import mechfem
from mechfem import Driven, Mechanism, Motion
from mechfem.model.mechanism import By, Dynamic, Free, Storage, Table, To
from mechfem.results.inverse_dynamics import Simulation

FloatArray = npt.NDArray[np.float64]
G = 9.81


def elliptic_k(k: float) -> float:
    """The complete elliptic integral of the first kind K(k) (modulus k), by the arithmetic-geometric mean."""
    a, b = 1.0, math.sqrt(1.0 - k * k)
    while abs(a - b) > 1e-16 * a:
        a, b = 0.5 * (a + b), math.sqrt(a * b)
    return math.pi / (2.0 * a)


def zero_crossings(t: FloatArray, q: FloatArray, v: FloatArray) -> FloatArray:
    """The times where ``q`` (with its rate ``v``) passes zero: the cubic through the neighbouring outputs with their
    rates, solved by Newton's method."""
    out = []
    for k in np.nonzero(np.sign(q[:-1]) != np.sign(q[1:]))[0]:
        h = t[k + 1] - t[k]
        q0, q1, m0, m1 = q[k], q[k + 1], v[k] * h, v[k + 1] * h
        s = q0 / (q0 - q1)
        for _ in range(8):
            f = (2 * s**3 - 3 * s**2 + 1) * q0 + (s**3 - 2 * s**2 + s) * m0 + (3 * s**2 - 2 * s**3) * q1
            f += (s**3 - s**2) * m1
            df = (6 * s**2 - 6 * s) * q0 + (3 * s**2 - 4 * s + 1) * m0 + (6 * s - 6 * s**2) * q1
            df += (3 * s**2 - 2 * s) * m1
            s -= f / df
        out.append(t[k] + s * h)
    return np.array(out)


# --- a pendulum: a bar of prescribed length about a fixed pivot, its angle the input, a point mass at the tip --------

L, M, AMPLITUDE = 0.8, 1.5, 2.0
"""Released from rest 2 rad (115 degrees) from the lowest position."""
PERIOD = 4.0 * math.sqrt(L / G) * elliptic_k(math.sin(AMPLITUDE / 2.0))


def pendulum() -> Mechanism:
    start = -math.pi / 2 + AMPLITUDE
    m = Mechanism("pendulum")
    pivot = m.fixed("O", 0.0, 0.0)
    tip = m.point("A", L * math.cos(start), L * math.sin(start))
    m.bar("bar", pivot, tip, length=L, angle=Driven(start=start, name="theta"))
    m.point_mass(tip, M)
    m.gravity(0.0, -G)
    return m


def test_pendulum_released_at_a_large_amplitude_swings_with_the_exact_period() -> None:
    r = pendulum().simulate(10 * PERIOD, 2000)
    assert r.complete and r.positions == 2001 and r.simulation is not None
    assert r.simulation.reached == pytest.approx(10 * PERIOD, rel=1e-12)
    assert np.allclose(r.time, np.linspace(0.0, 10 * PERIOD, 2001), rtol=0, atol=1e-12)
    # The angle from the lowest position passes zero twice a period.
    below = r.input("theta") + math.pi / 2
    crossings = zero_crossings(r.time, below, r.velocity("theta"))
    assert len(crossings) == 20
    half_period = np.polyfit(np.arange(20), crossings, 1)[0]
    assert 2 * half_period == pytest.approx(PERIOD, rel=1e-8)
    assert np.abs(np.diff(crossings) * 2 / PERIOD - 1).max() < 1e-8
    # Released from rest: it turns back at the amplitude on either side.
    assert below.max() == pytest.approx(AMPLITUDE, abs=1e-5) and below.min() == pytest.approx(-AMPLITUDE, abs=1e-5)


def test_pendulum_keeps_its_energy_over_many_swings() -> None:
    r = pendulum().simulate(10 * PERIOD, 2000)
    e = r.energy()
    assert np.abs(e.total - e.total[0]).max() < 1e-8 * M * G * L
    assert e.kinetic[0] == 0.0 and e.kinetic.max() == pytest.approx(M * G * L * (1 - math.cos(AMPLITUDE)), rel=1e-6)
    # The free input's drive delivers nothing; the inverse dynamics along the motion hold as in a run.
    assert np.abs(r.drive_torque()).max() < 1e-9 * M * G * L
    assert np.abs(r.power()).max() < 1e-9 * M * G * L * r.velocity("theta").max()
    assert np.allclose(r.mass_matrix()[:, 0, 0], M * L**2)
    theta = r.input("theta")
    assert np.allclose(r.acceleration("theta"), -G / L * np.cos(theta), rtol=0, atol=1e-8)


def test_the_last_position_is_as_accurate_as_the_others() -> None:
    # Outputs 0.1 s apart, steps of a few milliseconds: the last output is where a longer simulation passes then.
    m = pendulum()
    short, longer = m.simulate(1.0, 10), m.simulate(1.1, 11)
    assert np.allclose(short.input(), longer.input()[:-1], rtol=0, atol=1e-9)
    assert np.allclose(short.velocity("theta"), longer.velocity("theta")[:-1], rtol=0, atol=1e-8)
    e = short.energy().total
    assert np.abs(e - e[0]).max() < 1e-8 * M * G * L


def test_tighter_tolerances_take_more_steps() -> None:
    m = pendulum()
    loose, tight = m.simulate(PERIOD, 50, rtol=1e-6, atol=1e-6), m.simulate(PERIOD, 50)
    assert loose.simulation is not None and tight.simulation is not None
    assert (loose.simulation.rtol, loose.simulation.atol) == (1e-6, 1e-6)
    assert (tight.simulation.rtol, tight.simulation.atol) == (1e-10, 1e-10)
    assert loose.simulation.steps < tight.simulation.steps
    assert loose.simulation.evaluations < tight.simulation.evaluations
    assert np.allclose(loose.input(), tight.input(), rtol=0, atol=1e-4)


def test_a_run_has_no_simulation() -> None:
    r = pendulum().run(Motion.by(10, 0.5, dt=0.1))
    assert r.dynamic and r.simulation is None


# --- the deck of a simulation ----------------------------------------------------------------------------------------


def test_a_simulated_mechanism_writes_a_dyn_sim_deck_that_runs_the_same(tmp_path: Path) -> None:
    m = pendulum()
    motion = Motion.dynamic(PERIOD, 100, v0=0.5, rtol=1e-9)
    text = m.to_deck(motion)
    assert text.splitlines()[1] == "DYN SIM" and "MOV_DYN 1 0.5" in text.splitlines() and "INTTOL 1e-09 1e-10" in text
    storage = Storage().buffer(1, "BUFINP", "theta").buffer(2, "BUFDRV", "theta").buffer(3, "BUFEKIN")
    storage.buffer(4, "BUFX0", "A.y")
    path = m.save_deck(tmp_path / "pendulum.mec", motion, storage)
    deck = mechfem.run_deck(path)
    # order=None: the transfer functions the deck's buffers need, as `mechfem run` computes them.
    r = m.simulate(PERIOD, 100, v0=0.5, rtol=1e-9, storage=storage, order=None)
    assert deck.model.mode == "DYN SIM" and deck.positions == r.positions == 101
    assert deck.simulation is not None and r.simulation == deck.simulation
    for number in (1, 2, 3, 4):
        assert np.array_equal(r.buffers[number], deck.buffers[number]), f"buffer {number}"
    assert np.array_equal(r.coords, deck.coords) and np.array_equal(r.time, deck.time)
    # With every transfer function computed (the default), the positions agree within the Newton tolerance.
    full = m.simulate(PERIOD, 100, v0=0.5, rtol=1e-9)
    assert np.allclose(full.coords, deck.coords, rtol=0, atol=1e-9)


def test_simulate_is_a_run_of_a_dynamic_motion() -> None:
    m = pendulum()
    r = m.simulate(1.0, 20, v0={"theta": -1.0}, atol=1e-9)
    motion = Motion(20, {"theta": Dynamic(-1.0)}, dt=0.05, atol=1e-9)
    same = m.run(motion)
    assert np.array_equal(r.coords, same.coords) and r.simulation == same.simulation
    assert m.to_deck(Motion.dynamic(1.0, 20, -1.0, atol=1e-9)) == m.to_deck(motion)
    assert r.velocity("theta")[0] == -1.0


def test_a_simulation_record_is_the_cores_and_survives_a_pickle() -> None:
    import pickle

    r = pendulum().simulate(1.0, 20, v0={"theta": -1.0}, atol=1e-9)
    sim = r.simulation
    assert isinstance(sim, Simulation) and isinstance(sim._run, mechfem._core.Simulation)
    assert sim.steps > 0 and sim.evaluations >= sim.steps and sim.reached == pytest.approx(1.0)
    assert sim.segments[0][1:3] == (0.0, pytest.approx(1.0)) and sim.event is None
    back = pickle.loads(pickle.dumps(r))
    assert back.simulation == sim and back.simulation is not sim
    assert np.array_equal(back.coords, r.coords)


def test_a_deck_read_back_keeps_the_simulation(tmp_path: Path) -> None:
    m = pendulum()
    motion = Motion.dynamic(PERIOD, 100, v0=0.25, rtol=1e-9, atol=1e-11, accuracy=1e-11)
    back = Mechanism.from_deck(m.save_deck(tmp_path / "pendulum.mec", motion))
    assert back.motion is not None
    assert dict(back.motion.inputs) == {"theta": Dynamic(0.25)}
    assert (back.motion.rtol, back.motion.atol, back.motion.accuracy) == (1e-9, 1e-11, 1e-11)
    assert strip(back.to_deck()) == strip(m.to_deck(motion))
    assert np.array_equal(back.run(order=None).coords, m.run(motion, order=None).coords)


def strip(text: str) -> list[str]:
    """The deck's lines without their comments and its first line (which names the model)."""
    return [line.split(";")[0].strip() for line in text.splitlines()[1:]]


# --- one input driven, one moving under the forces --------------------------------------------------------------------

CRANK, ARM = 0.2, 1.0


def crank_and_pendulum() -> Mechanism:
    """A pendulum hanging from the end of a crank: the crank angle ``phi`` and the pendulum's angle ``psi``."""
    m = Mechanism("crank and pendulum")
    pivot = m.fixed("O", 0.0, 0.0)
    A, B = m.point("A", CRANK, 0.0), m.point("B", CRANK, -ARM)
    m.bar("crank", pivot, A, length=CRANK, angle=Driven(start=0.0, name="phi"))
    m.bar("arm", A, B, length=ARM, angle=Driven(start=-math.pi / 2, name="psi"))
    m.mass("crank", 0.5, u=CRANK / 2, J=2e-3)
    m.point_mass(B, 1.0)
    m.gravity(0.0, -G)
    return m


def test_a_driven_input_reports_its_drive_torque_and_the_free_one_none() -> None:
    m = crank_and_pendulum()
    turns = 4 * math.pi
    r = m.simulate(2.0, 400, v0=0.5, drive={"phi": By(turns)})
    assert r.complete and r.simulation is not None
    # The crank turns as prescribed; the pendulum swings under gravity and the crank's shaking.
    assert np.allclose(r.input("phi"), np.linspace(0.0, turns, 401), rtol=0, atol=1e-12)
    assert np.allclose(r.velocity("phi"), turns / 2.0) and r.velocity("psi")[0] == 0.5
    assert np.ptp(r.input("psi")) > 0.1
    torque, free = r.drive_torque("phi"), r.drive_torque("psi")
    assert np.isfinite(torque).all() and np.abs(torque).max() > 1.0
    assert np.abs(free).max() < 1e-9 * np.abs(torque).max()
    # The crank's drive is the only source of work: its power is the rate of change of T + V.
    assert np.allclose(r.power(), torque * r.velocity("phi"))
    e = r.energy().total
    work = np.concatenate([[0.0], np.cumsum(0.5 * (r.power()[1:] + r.power()[:-1]) * np.diff(r.time))])
    assert np.abs(e - e[0] - work).max() < 1e-3 * np.abs(work).max()


def test_the_deck_of_a_mixed_simulation_runs_the_same(tmp_path: Path) -> None:
    m = crank_and_pendulum()
    r = m.simulate(1.0, 50, v0={"psi": 0.5}, drive={"phi": By(2 * math.pi)}, order=None)
    path = m.save_deck(tmp_path / "mixed.mec", Motion(50, {"phi": By(2 * math.pi), "psi": Dynamic(0.5)}, 0.02))
    deck = mechfem.run_deck(path)
    assert "MOV_RELE 1" in path.read_text() and "MOV_DYN 2 0.5" in path.read_text()
    assert np.array_equal(r.coords, deck.coords) and r.simulation == deck.simulation
    assert deck.dynamic is not None and np.array_equal(r.drive_torque("phi"), deck.dynamic.drive[:, 0])


def test_a_driven_input_may_follow_a_table() -> None:
    m = crank_and_pendulum()
    t = np.linspace(0.0, 1.0, 51)
    speed = 2 * math.pi
    table = Table(speed * t, np.full(51, speed), np.zeros(51), t)
    by_table = m.simulate(1.0, 50, v0=0.5, drive={"phi": table})
    by_steps = m.simulate(1.0, 50, v0=0.5, drive={"phi": By(speed)})
    assert np.allclose(by_table.coords, by_steps.coords, rtol=0, atol=1e-9)
    assert np.allclose(by_table.drive_torque("phi"), by_steps.drive_torque("phi"), rtol=1e-7, atol=1e-9)


# --- stopping early ---------------------------------------------------------------------------------------------------


def test_a_stiff_spring_damper_is_integrated_implicitly_to_the_end() -> None:
    # A stiff spring with a strong damper: the automatic choice detects the stiffness and goes over to Radau IIA,
    # which creeps to the spring's free angle with long steps.
    m = Mechanism("stiff")
    pivot = m.fixed("O", 0.0, 0.0)
    tip = m.point("A", 1.0, 0.0)
    m.bar("bar", pivot, tip, length=1.0, angle=Driven(start=0.0, name="theta"))
    m.point_mass(tip, 1.0)
    m.spring("theta", 1e4, 0.5, damping=1e5)
    r = m.simulate(10.0, 100, v0=1.0)
    assert r.complete and r.positions == 101 and r.simulation is not None
    assert r.simulation.reached == 10.0
    assert any(method.startswith("Radau") for method, *_ in r.simulation.segments)


# --- mistakes ---------------------------------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("call", "error", "words"),
    [
        (lambda m: m.simulate(0.0, 10), ValueError, ["t_end > 0", "0.0"]),
        (lambda m: m.simulate(1.0, 0), ValueError, ["at least one output step"]),
        (lambda m: m.simulate(1.0, 10, v0=1.0), ValueError, ["'phi', 'psi'", "mapping", "crank and pendulum"]),
        (lambda m: m.simulate(1.0, 10, drive={"rho": By(1.0)}), KeyError, ["no input named 'rho'", "inputs: phi, psi"]),
        (lambda m: m.simulate(1.0, 10, drive={"phi": Dynamic(1.0)}), TypeError, ["'phi'", "v0"]),
        (lambda m: m.simulate(1.0, 10, drive={"phi": Free(0.1)}), TypeError, ["'phi'", "free motion"]),
        (lambda m: m.simulate(1.0, 10, drive={"phi": 1.0}), TypeError, ["'phi'", "By(delta)"]),
        (lambda m: m.simulate(1.0, 10, v0={"phi": 1.0}, drive={"phi": By(1.0)}), ValueError, ["'phi'", "'psi'"]),
        (
            lambda m: m.simulate(1.0, 10, drive={"phi": By(1.0), "psi": To(0.0)}),
            ValueError,
            ["every input of 'crank and pendulum'", "'phi', 'psi'"],
        ),
        (lambda m: m.simulate(1.0, 10, drive={"phi": By(1.0), 1: By(2.0)}), ValueError, ["'phi'", "two motions"]),
        (
            lambda m: m.simulate(1.0, 10, drive={"phi": Table(np.zeros(5))}),
            ValueError,
            ["'phi'", "5 values", "11 positions"],
        ),
        (lambda m: m.simulate(1.0, 10, v0={"psi": math.nan}), ValueError, ["'psi'", "finite"]),
        (lambda m: m.simulate(1.0, 10, rtol=-1.0), ValueError, ["rtol", "positive"]),
        (lambda m: m.run(Motion(10, {"phi": By(1.0), "psi": By(1.0)}, rtol=1e-8)), ValueError, ["rtol and atol"]),
        (lambda m: m.run(Motion(10, {"phi": Free(0.1), "psi": Dynamic()})), ValueError, ["'phi'", "Free"]),
    ],
)
def test_mistakes_are_named_with_the_model(
    call: Callable[[Mechanism], object], error: type[Exception], words: list[str]
) -> None:
    with pytest.raises(error) as info:
        call(crank_and_pendulum())
    for word in words:
        assert word in str(info.value), (word, str(info.value))


def test_a_simulation_needs_masses_and_says_so() -> None:
    m = Mechanism("bare")
    pivot = m.fixed("O", 0.0, 0.0)
    m.bar("bar", pivot, m.point("A", 1.0, 0.0), length=1.0, angle=Driven(name="theta"))
    for call in (lambda: m.simulate(1.0, 10), lambda: m.to_deck(Motion.dynamic(1.0, 10))):
        with pytest.raises(ValueError, match="'theta' of the mechanism 'bare'.*no masses or loads"):
            call()
    # With a load but no mass, the free input has nothing to move: the core refuses it, and the message names it.
    m.spring("theta", 1.0, 0.5)
    with pytest.raises(mechfem.MechfemError, match=r"no mass or inertia.*'theta'"):
        m.simulate(1.0, 10)


def test_a_mechanism_without_inputs_has_nothing_to_simulate() -> None:
    m = Mechanism("rigid")
    pivot = m.fixed("O", 0.0, 0.0)
    m.bar("bar", pivot, m.point("A", 1.0, 0.0), length=1.0, angle=0.0)
    m.mass("bar", 1.0)
    with pytest.raises(ValueError, match="'rigid' has no inputs"):
        m.simulate(1.0, 10)


def test_simulation_statistics_are_a_dataclass() -> None:
    r = pendulum().simulate(0.5, 10)
    assert isinstance(r.simulation, Simulation) and r.simulation.method.startswith("auto (Dormand-Prince")
    assert r.simulation.rejected >= 0 and r.simulation.evaluations >= r.simulation.steps > 0
