"""DYN SIM decks through `mechfem run` and `mechfem.run_deck`: a pendulum released from rest against the exact
period and the conservation of energy, the round trip inverse -> forward dynamics through a LOADFUNC file, the
supply mechanism's run-up to its steady speed, and what the print file says of the integrator."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

import mechfem
from conftest import ROOT, Cli

G = 9.81
SUPPLY = ROOT / "examples" / "supply" / "supply_sim.mec"
RELEASED = ROOT / "crates" / "mechfem-deck" / "tests" / "decks" / "valid" / "pendulum_released.mec"


def elliptic_k(k: float) -> float:
    """The complete elliptic integral of the first kind, by the arithmetic-geometric mean."""
    a, b = 1.0, math.sqrt(1.0 - k * k)
    # The mean converges quadratically: a handful of rounds reach the last bit.
    for _ in range(40):
        a, b = 0.5 * (a + b), math.sqrt(a * b)
    return math.pi / (2.0 * a)


PENDULUM = """{mode}
TOPOLOGY
ELEM 1 BIN 1 2 3 4
FORM 1 LENL 1 1
     2 ANGB 1 2
NRDOF 1
GEOMETRY
XFIX 1 0.0
     2 0.0
XMOV 3 {x!r}
     4 {y!r}
DYNAMICS
PMASS 3 4 1.5
GRAVITY 0 -9.81
{loads}
MOVEMENT
TSTEPE {n} {dt!r}
{motion}
ACCURACY 1E-12
STORAGE
BUFTIME 1
BUFINP 1 2
BUFVE 2 3
BUFDRV 1 4
BUFEKIN 5
BUFEPOT 6
"""


def pendulum(path: Path, mode: str, motion: str, n: int, dt: float, theta0: float, loads: str = "") -> Path:
    length = 0.7
    text = PENDULUM.format(
        mode=mode,
        x=length * math.cos(theta0),
        y=length * math.sin(theta0),
        loads=loads,
        n=n,
        dt=dt,
        motion=motion,
    )
    path.write_text(text)
    return path


def test_a_released_pendulum_keeps_its_energy_and_its_exact_period(tmp_path: Path) -> None:
    # Released from rest 150 degrees from the bottom: back after 4 sqrt(l/g) K(sin 75 deg).
    amplitude, length = math.radians(150.0), 0.7
    period = 4.0 * math.sqrt(length / G) * elliptic_k(math.sin(amplitude / 2.0))
    theta0 = -math.pi / 2 + amplitude
    n = 300
    deck = pendulum(tmp_path / "p.mec", "DYN SIM", "MOV_DYN 1 0\nINTTOL 1E-12 1E-12", n, period / n, theta0)
    r = mechfem.run_deck(deck)
    assert r.report.complete and r.simulation is not None
    assert abs(r.buffers[2][-1] - theta0) < 1e-8
    assert abs(r.buffers[2][n // 2] - (-math.pi / 2 - amplitude)) < 1e-8
    energy = r.buffers[5] + r.buffers[6]
    assert np.abs(energy - energy[0]).max() < 1e-9 * np.abs(r.buffers[6]).max()
    # The free input has no drive: the forces alone move it.
    assert np.abs(r.buffers[4]).max() < 1e-6 * 1.5 * G * length


def test_inverse_then_forward_dynamics_through_a_load_table(tmp_path: Path) -> None:
    # DYN ANA finds the torque that swings the pendulum as theta(t) = theta0 + a sin(w t); DYN SIM with that
    # torque as a LOADFUNC on the angle and the same start reproduces the swing.
    theta0, amp, w, n, dt = -1.2, 0.8, 4.0, 4000, 2.5e-4
    t = np.arange(n + 1) * dt
    th = theta0 + amp * np.sin(w * t)
    rows = np.column_stack([t, th, amp * w * np.cos(w * t), -amp * w * w * np.sin(w * t)])
    np.savetxt(tmp_path / "swing.dat", rows, fmt="%.17g")
    ana = mechfem.run_deck(pendulum(tmp_path / "ana.mec", "DYN ANA", "MOV_FUNC 1 swing.dat", n, dt, theta0))
    assert ana.report.complete
    np.savetxt(tmp_path / "torque.dat", np.column_stack([ana.buffers[1], ana.buffers[4]]), fmt="%.17g")
    sim_deck = pendulum(
        tmp_path / "sim.mec",
        "DYN SIM",
        f"MOV_DYN 1 {amp * w!r}\nINTTOL 1E-11 1E-11",
        100,
        n * dt / 100,
        theta0,
        loads="LOADFUNC 2 torque.dat",
    )
    sim = mechfem.run_deck(sim_deck)
    assert sim.report.complete
    want = theta0 + amp * np.sin(w * sim.buffers[1])
    # The torque is linear between its rows: the swing comes back to within that interpolation's error.
    np.testing.assert_allclose(sim.buffers[2], want, atol=1e-7)


def test_supply_mechanism_runs_up_to_its_steady_speed(tmp_path: Path, cli: Cli) -> None:
    proc = cli("run", SUPPLY, "-o", tmp_path)
    assert proc.returncode == 0, proc.stderr
    r = mechfem.run_deck(SUPPLY)
    assert r.report.complete
    speed, time = r.buffers[101], r.buffers[98]
    assert speed[0] == 0.0
    # Steady running: the motor's torque 12 (1 - w/70) N m balances the brakes near 63 rad/s (about 600 strokes
    # a minute), the flywheel holding the speed within a few per cent.
    late = speed[time > 1.5]
    assert 60.0 < late.mean() < 66.0
    assert (late.max() - late.min()) / late.mean() < 0.06
    prt = (tmp_path / "supply_sim.prt").read_text()
    assert "SIMULATION\n  integrator: auto (Dormand-Prince 5(4)" in prt
    assert "tolerances: relative 1e-10, absolute 1e-10" in prt
    assert "energy balance from the first position to the last" in prt


def test_a_very_stiff_spring_stops_the_explicit_integrator_with_its_reason(tmp_path: Path) -> None:
    # A torsion spring of 1e15 N m on the pendulum: oscillations far faster than the outputs. The explicit
    # integrator's steps are held by its stability to far less than the output interval, the motion is found stiff
    # within a few thousand steps, and the simulation stops with that reason instead of running for hours.
    text = RELEASED.read_text().replace("GRAVITY 0 -9.81", "GRAVITY 0 -9.81\nSPRING 2 1E15 0 0.001")
    text = text.replace("MOV_DYN 1 0 ", "INTEGRATOR explicit\nMOV_DYN 1 0 ")
    deck = tmp_path / "stiff.mec"
    deck.write_text(text)
    with pytest.warns(mechfem.IncompleteRunWarning, match="became stiff"):
        r = mechfem.run_deck(deck)
    stop = r.report.stop
    assert stop is not None and stop.kind == "simulation"
    assert "1/2000 of the output interval" in stop.message
    assert r.simulation is not None and r.simulation.steps < 10_000
    assert r.positions == stop.last_good >= 1


@pytest.mark.parametrize(("n", "dt"), [(500, 10.0), (5, 1000.0)])
def test_a_damped_pendulum_rests_to_the_end_of_a_long_simulation(tmp_path: Path, cli: Cli, n: int, dt: float) -> None:
    # Released 1 rad from the bottom with a damper on its angle, the pendulum settles within a minute and then hangs
    # at rest: a motion at rest is not stiff, and the 5000 s run to their end (exit 0) with outputs 10 s or 1000 s
    # apart alike, the pendulum straight down at the end.
    deck = pendulum(tmp_path / "damped.mec", "DYN SIM", "MOV_DYN 1 0", n, dt, -math.pi / 2 + 1.0, "SPRING 2 0 0 0.3")
    proc = cli("run", deck, "-o", tmp_path / "out", "--no-media")
    assert proc.returncode == 0, proc.stderr
    r = mechfem.run_deck(deck)
    assert r.report.complete and r.positions == n + 1
    assert abs(r.buffers[2][-1] + math.pi / 2) < 1e-8
    energy = r.buffers[5] + r.buffers[6]
    assert np.all(np.diff(energy) <= 1e-10 * (energy[0] - energy[-1]))


def test_the_automatic_choice_integrates_a_stiff_spring_damper_implicitly(tmp_path: Path) -> None:
    # A stiff torsion spring with a strong damper on the pendulum (k = 1e6, c = 1e5): the automatic choice goes over
    # to Radau IIA, runs to the end, and the print file says which method ran where.
    text = RELEASED.read_text().replace("GRAVITY 0 -9.81", "GRAVITY 0 -9.81\nSPRING 2 1E6 -1.0 1E5")
    deck = tmp_path / "stiff.mec"
    deck.write_text(text)
    r = mechfem.run_deck(deck)
    assert r.report.complete and r.simulation is not None
    methods = [m for m, *_ in r.simulation.segments]
    assert methods[0].startswith("Dormand-Prince") and any(m.startswith("Radau") for m in methods)
    assert r.simulation.jacobians > 0 and r.simulation.segments[-1][2] == pytest.approx(2.4, abs=1e-12)
    lines = "\n".join(r.simulation.lines(r.dynamic, r.time))
    assert "methods by stretch of time:" in lines and "Radau IIA 5" in lines


def test_stopwhen_ends_the_pendulum_at_the_bottom_and_says_when(tmp_path: Path, cli: Cli) -> None:
    # Released horizontal, the pendulum reaches the bottom (angle -pi/2, buffer 2) after a quarter of its period
    # 4 sqrt(1/9.81) K(sin 45 deg): the simulation ends there, with the crossing as its last position.
    quarter = math.sqrt(1 / 9.81) * 1.8540746773013719
    text = RELEASED.read_text().replace("MOV_DYN 1 0 ", f"STOPWHEN 2 {-math.pi / 2!r}\nMOV_DYN 1 0 ")
    deck = tmp_path / "stop.mec"
    deck.write_text(text)
    r = mechfem.run_deck(deck)
    assert r.report.complete and r.simulation is not None and r.simulation.event is not None
    buffer, value, time, inputs = r.simulation.event
    assert (buffer, value) == (2, -math.pi / 2)
    assert abs(time - quarter) < 1e-8 and abs(inputs[0] + math.pi / 2) < 1e-8
    assert r.positions == math.floor(quarter / 0.01) + 2 and r.time[-1] == time
    proc = cli("run", deck, "-o", tmp_path / "out", "--no-media")
    assert proc.returncode == 0, proc.stderr
    prt = (tmp_path / "out" / "stop.prt").read_text()
    assert "stopped by STOPWHEN: buffer 2 crossed -1.570796327 at time 0.591960" in prt


def test_an_accuracy_far_looser_than_inttol_is_warned_of(tmp_path: Path) -> None:
    text = RELEASED.read_text().replace("ACCURACY 1E-10", "ACCURACY 1E-10\nINTTOL 1E-13 1E-13")
    deck = tmp_path / "loose.mec"
    deck.write_text(text)
    with pytest.warns(UserWarning, match="ACCURACY 1e-10 .* is far looser than INTTOL"):
        r = mechfem.run_deck(deck)
    assert r.simulation is not None and r.simulation.tolerance_warning is not None
    assert "warning: ACCURACY" in "\n".join(r.simulation.lines(r.dynamic, r.time))
