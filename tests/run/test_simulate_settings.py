"""The integrator and the stop condition of ``Mechanism.simulate``: the method chosen reaches the core, a stop
condition ends a pendulum where its closed form says, mistakes are named in the model's words, and the deck keeps
both (INTEGRATOR, STOPWHEN)."""

from __future__ import annotations

import math

import pytest

from mechfem import Driven, Mechanism, Motion
from mechfem.model.mechanism import By, Storage

L, M, G = 0.8, 1.5, 9.81


def elliptic_k(k: float) -> float:
    """The complete elliptic integral of the first kind K(k) (modulus k), by the arithmetic-geometric mean."""
    a, b = 1.0, math.sqrt(1.0 - k * k)
    for _ in range(40):  # quadratic convergence: far more than enough, and no loop on a last-bit wobble
        a, b = 0.5 * (a + b), math.sqrt(a * b)
    return math.pi / (2.0 * a)


def pendulum(amplitude: float, angle: str = "rad") -> Mechanism:
    """A point mass on a bar of length L about a fixed pivot, released from rest ``amplitude`` from the lowest
    position; its angle ``theta`` (from the x axis, in ``angle``) is the input, stored in buffer 2 and its speed in
    buffer 3."""
    start = -math.pi / 2 + amplitude
    m = Mechanism("pendulum", units={"angle": angle})
    pivot = m.fixed("O", 0.0, 0.0)
    tip = m.point("A", L * math.cos(start), L * math.sin(start))
    given = math.degrees(start) if angle == "deg" else start
    m.bar("bar", pivot, tip, length=L, angle=Driven(start=given, name="theta"))
    m.point_mass(tip, M)
    m.gravity(0.0, -G)
    m.storage = Storage().buffer(2, "BUFE0", "theta").buffer(3, "BUFVE", "theta")
    return m


def test_the_integrator_chosen_is_the_one_that_runs() -> None:
    m = pendulum(1.0)
    runs = {name: m.simulate(1.0, 20, integrator=name, rtol=1e-9, atol=1e-9) for name in ("radau5", "dopri5", "dop853")}
    for name, start in (("radau5", "Radau"), ("dopri5", "Dormand-Prince"), ("dop853", "DOP853")):
        sim = runs[name].simulation
        assert runs[name].complete and sim is not None
        assert {method for method, *_ in sim.segments} == {sim.method} and sim.method.startswith(start)
    # Three methods, one motion.
    theta = {name: r.input("theta") for name, r in runs.items()}
    assert abs(theta["radau5"] - theta["dopri5"]).max() < 1e-6
    assert abs(theta["dop853"] - theta["dopri5"]).max() < 1e-6
    assert runs["radau5"].simulation.jacobians > 0 and runs["dopri5"].simulation.jacobians == 0  # type: ignore[union-attr]


@pytest.mark.parametrize("buffer", ["theta", 2])
def test_stop_when_ends_the_pendulum_at_the_bottom_after_a_quarter_period(buffer: int | str) -> None:
    # Released from rest 1.2 rad from the bottom, the pendulum reaches the bottom (theta = -pi/2) after a quarter
    # of its exact period 4 sqrt(L/g) K(sin(amplitude/2)).
    amplitude = 1.2
    quarter = math.sqrt(L / G) * elliptic_k(math.sin(amplitude / 2))
    m = pendulum(amplitude)
    m.storage = Storage().buffer(2, "BUFE0", "theta")
    r = m.simulate(2.0, 200, stop_when=(buffer, -math.pi / 2))
    sim = r.simulation
    assert sim is not None and sim.event is not None
    number, value, time, inputs = sim.event
    assert (number, value) == (2, -math.pi / 2)
    assert time == pytest.approx(quarter, abs=1e-8) and inputs[0] == pytest.approx(-math.pi / 2, abs=1e-8)
    assert r.time[-1] == time and r.positions == math.floor(quarter / 0.01) + 2


def test_a_model_in_degrees_stops_at_its_value_in_degrees_and_runs_again_from_its_own_start() -> None:
    # The same pendulum given in degrees: the start angle and the stop value are read in degrees, by the model
    # built afresh and by the kept model that a second run reuses.
    amplitude = 1.2
    quarter = math.sqrt(L / G) * elliptic_k(math.sin(amplitude / 2))
    m = pendulum(amplitude, "deg")
    m.storage = Storage().buffer(2, "BUFE0", "theta")
    for _ in range(2):
        r = m.simulate(2.0, 200, stop_when=("theta", -90.0))
        assert r.input("theta")[0] == pytest.approx(math.degrees(-math.pi / 2 + amplitude), abs=1e-9)
        sim = r.simulation
        assert sim is not None and sim.event is not None
        number, value, time, inputs = sim.event
        assert (number, value) == (2, -90.0)
        assert time == pytest.approx(quarter, abs=1e-8) and inputs[0] == pytest.approx(-90.0, abs=1e-6)


def test_mistakes_are_named_in_the_models_words() -> None:
    m = pendulum(1.0)
    with pytest.raises(ValueError, match=r"integrator 'rk4' is not an integration method: give one of auto, explicit"):
        m.simulate(1.0, 10, integrator="rk4")
    with pytest.raises(ValueError, match=r"no buffer of the storage of mechanism 'pendulum' holds 'omega'.*2 \(BUFE0 "):
        m.simulate(1.0, 10, stop_when=("omega", 0.0))
    with pytest.raises(ValueError, match=r"'theta', which several buffers of mechanism 'pendulum' hold"):
        m.simulate(1.0, 10, stop_when=("theta", 0.0))
    with pytest.raises(ValueError, match=r"buffer 9, which the storage of mechanism 'pendulum' does not define"):
        m.simulate(1.0, 10, stop_when=(9, 0.0))
    with pytest.raises(ValueError, match=r"the value of stop_when must be a finite number"):
        m.simulate(1.0, 10, stop_when=(2, math.nan))
    with pytest.raises(ValueError, match=r"stop_when is a \(buffer, value\) pair"):
        m.simulate(1.0, 10, stop_when=2)  # type: ignore[arg-type]
    with pytest.raises(ValueError, match=r"integrator and stop_when set how a simulation is integrated"):
        Motion(5, {"theta": By(0.1)}, integrator="radau5")


def test_the_deck_keeps_the_integrator_and_the_stop_condition() -> None:
    m = pendulum(1.0)
    m.storage = Storage().buffer(2, "BUFE0", "theta").buffer(3, "BUFVE", "theta")
    motion = Motion.dynamic(1.0, 10, integrator="radau5", stop_when=(3, 0.5))
    text = m.to_deck(motion)
    assert "\nINTEGRATOR radau5\n" in text and "\nSTOPWHEN 3 0.5\n" in text
    back = Mechanism.from_deck_text(text)
    assert back.motion is not None
    assert back.motion.integrator == "radau5" and back.motion.stop_when == (3, 0.5)
    assert back.to_deck().splitlines()[1:] == text.splitlines()[1:]  # the first line names the model
    # A name comes back as the name, "auto" writes no line.
    m.storage = Storage().buffer(2, "BUFE0", "theta")
    text = m.to_deck(Motion.dynamic(1.0, 10, stop_when=("theta", -1.5)))
    assert "INTEGRATOR" not in text and "\nSTOPWHEN 2 -1.5\n" in text
    back = Mechanism.from_deck_text(text)
    assert back.motion is not None and back.motion.stop_when == ("theta", -1.5) and back.motion.integrator == "auto"
    # The deck and the typed builder run the same simulation.
    ran = back.run()
    assert ran.simulation is not None and ran.simulation.event is not None
