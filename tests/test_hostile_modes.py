"""Hostile numbers in the modes DYN SIM and KIN OPT, through ``mechfem run``: every case ends with a clear message
(a deck error with its line, or the reason the run stopped), the results computed so far are written, and nothing
hangs or fails internally."""

from __future__ import annotations

import time
from pathlib import Path

import pytest

from conftest import ROOT, Cli

SIM = ROOT / "examples" / "supply" / "supply_sim.mec"
OPT = ROOT / "examples" / "supply" / "supply_opt.mec"


def variant(tmp_path: Path, deck: Path, *changes: tuple[str, str]) -> Path:
    text = deck.read_text()
    for old, new in changes:
        assert old in text, old
        text = text.replace(old, new)
    path = tmp_path / deck.name
    path.write_text(text)
    return path


def run(cli: Cli, deck: Path) -> tuple[int, str, Path]:
    out = deck.parent / "out"
    p = cli("run", deck, "-o", out, "--max-frames", "2")
    assert "internal error" not in p.stderr and "Traceback" not in p.stderr, p.stderr
    return p.returncode, p.stderr, out


@pytest.mark.parametrize(
    ("old", "new", "message"),
    [
        ("MASS\t1\t0.30", "MASS\t1\t-0.30", "give the body's mass, 0 or more"),
        ("0.020\t0\t3.0E-2", "0.020\t0\t-3.0E-2", "moment of inertia about the centre of mass, 0 or more"),
    ],
)
def test_negative_masses_and_inertias_are_deck_errors(tmp_path: Path, cli: Cli, old: str, new: str, message: str):
    status, err, out = run(cli, variant(tmp_path, SIM, (old, new)))
    assert status == 1
    assert "supply_sim.mec:74:" in err and message in err
    assert not out.exists()


def test_a_simulated_dof_without_any_mass_is_refused_clearly(tmp_path: Path, cli: Cli) -> None:
    text = SIM.read_text()
    lines = [line for line in text.splitlines()]
    # Every MASS line (the keyword line and its continuation lines) with mass and inertia 0.
    start = next(i for i, line in enumerate(lines) if line.startswith("MASS"))
    for i in range(start, start + 8):
        words = lines[i].split(";")[0].split()
        k = 1 if words[0] == "MASS" else 0
        words[k + 1] = "0"
        words[k + 4] = "0"
        lines[i] = " ".join(words)
    deck = tmp_path / "massless.mec"
    deck.write_text("\n".join(lines) + "\n")
    status, err, _ = run(cli, deck)
    assert status == 1
    assert "massless.mec" in err and "no mass or inertia" in err


def test_a_very_stiff_spring_stops_the_simulation_with_its_reason_in_bounded_time(tmp_path: Path, cli: Cli):
    # k = 1e12 on the output angle: oscillations of period ~1e-6 s against outputs every 2.5 ms. The integrator
    # gives up after its step budget (2000 steps per output interval, at least 200 000) instead of running for hours.
    deck = variant(tmp_path, SIM, ("SPRING\t-1\t0\t0", "SPRING\t-1\t1e12\t0"), ("TSTEPE 800", "TSTEPE 10"))
    t0 = time.monotonic()
    status, err, out = run(cli, deck)
    assert time.monotonic() - t0 < 240
    assert status == 3
    assert "stiff spring" in err
    assert (out / "supply_sim.prt").exists() and (out / "supply_sim.csv").exists()


def test_a_huge_motor_torque_ends_the_simulation_with_a_reason(tmp_path: Path, cli: Cli) -> None:
    deck = variant(tmp_path, SIM, ("MOTOR\t12\t12.0", "MOTOR\t12\t1e12"), ("TSTEPE 800", "TSTEPE 40"))
    status, err, out = run(cli, deck)
    assert status in (0, 3)
    if status == 3:
        assert "The simulation stopped" in err
    assert (out / "supply_sim.prt").exists()


@pytest.mark.parametrize(
    ("vary", "message"),
    [
        ("VARY 5 -5.0 -4.9", "outside its range"),
        ("VARY 5 nan -5.0", "expected a number"),
        ("VARY 5 -inf inf", "expected a number"),
        ("VARY 5 -5.5 1e999", "is too large"),
        ("VARY 5 -1e308 1e308", "wider than a number can hold"),
    ],
)
def test_design_variable_ranges_that_cannot_be_used_are_deck_errors(
    tmp_path: Path, cli: Cli, vary: str, message: str
) -> None:
    status, err, out = run(cli, variant(tmp_path, OPT, ("VARY 5 -5.5 -5.0", vary)))
    assert status == 1
    assert "supply_opt.mec:75:" in err, err
    assert message in err
    assert not out.exists()


@pytest.mark.parametrize(
    "change",
    [
        # A target the mechanism cannot reach: the output angle 100 rad at position 10.
        ("TARGETEXT 102 100 0.0", "TARGETAT 100 10 100.0"),
        ("TARGETEXT 102 100 0.0", "TARGETEXT 102 100 0.0\nOPTSTEPS 1"),
        ("TARGETEXT 102 100 0.0", "TARGETEXT 102 100 0.0\nOPTTOL 1e-300"),
    ],
    ids=["unreachable", "optsteps-1", "opttol-1e-300"],
)
def test_optimisations_that_cannot_do_well_end_with_their_results(tmp_path: Path, cli: Cli, change) -> None:
    status, err, out = run(cli, variant(tmp_path, OPT, change))
    assert status == 0, err
    prt = (out / "supply_opt.prt").read_text()
    assert "objective: start" in prt and ("converged:" in prt or "did not converge:" in prt)
    assert (out / "supply_opt_opt.mec").exists()
    assert "targets at the final design (the largest difference from the value asked for):" in prt
    if change[1].startswith("TARGETAT"):
        # Said plainly: the target is out of reach, how far, and which line.
        assert "the targets are not all reached: the largest difference left is" in err
        assert "(the target on line" in err


def test_a_targetext_without_extrema_is_said_to_contribute_nothing(tmp_path: Path, cli: Cli) -> None:
    # A tenth of a radian of the input: the output angle moves steadily, with no extremum.
    deck = variant(tmp_path, OPT, ("MOV_RELE 1 6.283185307179586", "MOV_RELE 1 0.1"))
    status, _, out = run(cli, deck)
    assert status == 0
    prt = (out / "supply_opt.prt").read_text()
    assert "TARGETEXT 102 100: buffer 100 has no extremum along the motion" in prt
    assert "contributes nothing to the objective" in prt
