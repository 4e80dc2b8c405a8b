"""DYN ANA decks through `mechfem run` and `mechfem.run_deck`: a pendulum and a static position against closed
forms derived here, the supply mechanism's energy balance at fine steps, and what the print file, the data set
and the report show of the dynamics."""

from __future__ import annotations

import csv
import re
from pathlib import Path

import numpy as np

import mechfem
from conftest import ROOT, Cli

G = 9.81
SUPPLY = ROOT / "examples" / "supply" / "supply_dyn.mec"

PENDULUM = """DYN ANA
TOPOLOGY
ELEM 1 BIN 1 2 3 4
FORM 1 LENL 1 1
     2 ANGB 1 2
NRDOF 1
GEOMETRY
XFIX 1 0.0
     2 0.0
XMOV 3 {x}
     4 {y}
DYNAMICS
PMASS 3 4 {m}
GRAVITY 0 -9.81
{movement}
STORAGE
BUFINP 1 1
BUFSIG 1 2
BUFDRV 1 3
BUFREA 1 4
BUFREA 2 5
BUFEKIN 6
BUFEPOT 7
BUFPOW 8
BUFMRED 1 1 9
"""


def pendulum(tmp_path: Path, movement: str, theta0: float = -np.pi / 2, length: float = 0.7, m: float = 1.5) -> Path:
    deck = tmp_path / "pendulum.mec"
    x, y = float(length * np.cos(theta0)), float(length * np.sin(theta0))
    deck.write_text(PENDULUM.format(x=repr(x), y=repr(y), m=m, movement=movement))
    return deck


def test_pendulum_at_constant_speed_matches_its_closed_form(tmp_path: Path) -> None:
    # A point mass m on a bar of length l turning at speed w: drive m g l cos(theta), bar force
    # -m l w^2 + m g sin(theta) (positive pushing the ends apart), pivot reaction m a - m g.
    length, m, w, n = 0.7, 1.5, 5.0, 90
    dt = 2 * np.pi / w / n
    movement = f"MOVEMENT\nTSTEPE {n} {float(dt)!r}\nMOV_RELE 1 {float(2 * np.pi)!r}"
    deck = pendulum(tmp_path, movement, length=length, m=m)
    r = mechfem.run_deck(deck)
    assert r.report.complete
    th = r.buffers[1]
    scale = m * (G + length * w * w) * length
    np.testing.assert_allclose(r.buffers[3], m * G * length * np.cos(th), atol=1e-10 * scale)
    np.testing.assert_allclose(r.buffers[2], -m * length * w * w + m * G * np.sin(th), atol=1e-10 * scale)
    a = -length * w * w * np.stack([np.cos(th), np.sin(th)])
    np.testing.assert_allclose(r.buffers[4], m * a[0], atol=1e-10 * scale)
    np.testing.assert_allclose(r.buffers[5], m * a[1] + m * G, atol=1e-10 * scale)
    np.testing.assert_allclose(r.buffers[6], 0.5 * m * (length * w) ** 2, rtol=1e-9)
    np.testing.assert_allclose(r.buffers[7], m * G * length * np.sin(th), atol=1e-12 * scale)
    np.testing.assert_allclose(r.buffers[8], r.buffers[3] * w, atol=1e-10 * scale * w)
    np.testing.assert_allclose(r.buffers[9], m * length * length, rtol=1e-9)


def test_a_deck_without_movement_is_a_static_analysis(tmp_path: Path) -> None:
    theta0, length, m = 0.4, 0.7, 1.5
    r = mechfem.run_deck(pendulum(tmp_path, "", theta0=theta0, length=length, m=m))
    assert r.positions == 1
    assert abs(r.buffers[3][0] - m * G * length * np.cos(theta0)) < 1e-12
    assert abs(r.buffers[2][0] - m * G * np.sin(theta0)) < 1e-12
    assert abs(r.buffers[5][0] - m * G) < 1e-12
    assert r.buffers[6][0] == 0.0


def test_supply_mechanism_balances_its_energy_at_fine_steps(tmp_path: Path) -> None:
    # The example deck at 3600 steps a turn: drive power plus the brake's power equals d(T + V)/dt (a central
    # difference of order four in time), and T = M w^2 / 2 with M the reduced inertia.
    text = SUPPLY.read_text()
    text = re.sub(r"TSTEPE 72 \S+", f"TSTEPE 3600 {0.1 / 3600!r}", text)
    text = text.replace("  BUFE0   -1 100", "  BUFE0   -1 100\n  BUFKE1  -1 1 101")
    deck = tmp_path / "supply_dyn.mec"
    deck.write_text(text)
    r = mechfem.run_deck(deck)
    assert r.report.complete
    w, dt = 2 * np.pi / 0.1, 0.1 / 3600
    e = r.buffers[111] + r.buffers[112]
    rate = (-e[4:] + 8 * e[3:-1] - 8 * e[1:-3] + e[:-4]) / (12 * dt)
    brake = -2.0 * r.buffers[101] * w
    balance = (r.buffers[113] + brake)[2:-2]
    scale = np.abs(balance).max()
    assert scale > 100.0
    np.testing.assert_allclose(balance, rate, atol=1e-7 * scale)
    np.testing.assert_allclose(r.buffers[111], 0.5 * r.buffers[117] * w * w, rtol=1e-12)
    np.testing.assert_allclose(r.buffers[113], r.buffers[110] * w, rtol=1e-12, atol=1e-9)
    # One turn later the mechanism and its forces are where they started.
    for b in (110, 111, 114, 115, 116):
        assert abs(r.buffers[b][-1] - r.buffers[b][0]) < 1e-9 * np.abs(r.buffers[b]).max()


def test_the_outputs_show_the_dynamics(tmp_path: Path, cli: Cli) -> None:
    proc = cli("run", SUPPLY, "-o", tmp_path, "--report")
    assert proc.returncode == 0, proc.stderr
    prt = (tmp_path / "supply_dyn.prt").read_text()
    assert "masses and loads (DYNAMICS)" in prt
    assert "MASS      element 5: m 1 kg, centre (u, v) = (0.339, 0) m, J 0.0384 kg·m²" in prt
    assert "LOAD      delta: constant -2 N·m" in prt
    summary = prt[prt.index("\nDYNAMICS\n") :]
    assert "drive of DOF 1: largest" in summary
    assert "a flywheel's energy swing" in summary
    with open(tmp_path / "supply_dyn.csv", newline="") as f:
        header = next(csv.reader(f))
    # Named by the deck's NAMES block (ROW for the input alpha, DEP for the output delta), with its UNITS.
    assert header[:3] == ["99 alpha [rad]", "100 delta [rad]", "110 drive(alpha) [N·m]"]
    report = (tmp_path / "supply_dyn.html").read_text()
    # The deck's first picture charts the drive torque: the report shows it there, not a second time.
    assert "drive torque against the input angle" in report
    assert "drive force or torque against alpha" not in report
    assert "energies against alpha" in report


def test_the_energy_swing_is_the_work_fluctuation_about_the_mean() -> None:
    from mechfem.results.inverse_dynamics import energy_fluctuation

    # A power p(t) = P0 + A sin(w t) over one period: the work above the mean swings by 2 A / w.
    t = np.linspace(0.0, 1.0, 20001)
    w = 2 * np.pi
    p = 3.0 + 5.0 * np.sin(w * t)
    assert abs(energy_fluctuation(t, p) - 2 * 5.0 / w) < 1e-6
