"""Hostile numbers in the modes DYN SIM and KIN OPT, through ``mechfem run``: every case ends with a clear message
(a deck error with its line, or the reason the run stopped), the results computed so far are written, and nothing
hangs or fails internally."""

from __future__ import annotations

import re
import time
import warnings
from pathlib import Path

import pytest

from conftest import ROOT, Cli

SIM = ROOT / "examples" / "supply" / "supply_sim.mec"
OPT = ROOT / "examples" / "supply" / "supply_opt.mec"


def line_of(deck: Path, text: str) -> int:
    """The number of the first line of ``deck`` that holds ``text``."""
    return next(k for k, line in enumerate(deck.read_text().splitlines(), 1) if text in line)


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
    assert f"supply_sim.mec:{line_of(SIM, old)}:" in err and message in err
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


@pytest.mark.large_run
def test_a_very_stiff_spring_stops_the_simulation_with_its_reason_in_bounded_time(tmp_path: Path, cli: Cli):
    # k = 1e12 on the output angle: oscillations of period ~1e-6 s against outputs every 2.5 ms. The integrator
    # gives up after its step budget (2000 steps per output interval, at least 200 000) instead of running for hours.
    deck = variant(
        tmp_path,
        SIM,
        ("SPRING\t-1\t0\t0", "SPRING\t-1\t1e12\t0"),
        ("TSTEPE 800 2.5E-3", "TSTEPE 10 2.5E-3\nINTEGRATOR explicit"),
    )
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
    assert f"supply_opt.mec:{line_of(OPT, 'VARY 5 -5.5 -5.0')}:" in err, err
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


# --- numbers that overflow ------------------------------------------------------------------------------------------

VALID = ROOT / "crates" / "mechfem-deck" / "tests" / "decks" / "valid"
RUNTIME = ROOT / "tests" / "decks"
OVERFLOWS = ("1e308", "-1e308", "1e-320", "nan", "inf")
NON_FINITE = re.compile(r"(?<![\w.])[-+]?(inf|nan|infinity)(?![\w.])", re.IGNORECASE)


def overflowing_variants(text: str) -> list[tuple[int, str]]:
    """``(line, deck)`` for every number of every line of the DYNAMICS and OPTIMISE blocks, and of MOV_DYN and
    INTTOL, replaced by each of :data:`OVERFLOWS`."""
    lines = text.splitlines()
    block = ""
    out: list[tuple[int, str]] = []
    for k, line in enumerate(lines):
        words = line.split(";", 1)[0].split()
        if not words:
            continue
        if words[0] in ("TOPOLOGY", "GEOMETRY", "DYNAMICS", "MOVEMENT", "OPTIMISE", "STORAGE"):
            block = words[0]
            continue
        if block not in ("DYNAMICS", "OPTIMISE") and words[0] not in ("MOV_DYN", "INTTOL"):
            continue
        for w, word in enumerate(words):
            if word[0].isdigit() or word[0] in "+-.":
                for value in OVERFLOWS:
                    changed = [*lines]
                    changed[k] = " ".join([*words[:w], value, *words[w + 1 :]])
                    out.append((k + 1, "\n".join(changed) + "\n"))
    return out


def run_here(deck: Path, out: Path, capsys: pytest.CaptureFixture[str]) -> tuple[int, str]:
    """``mechfem run`` in this process, a RuntimeWarning (numpy's overflow warnings) made an error: it would end
    as an internal error, exit status 4."""
    from mechfem.cli import command as cli

    with warnings.catch_warnings():
        warnings.simplefilter("error", RuntimeWarning)
        status = cli.main(["run", str(deck), "-o", str(out), "--max-frames", "2", "--quiet"])
    return status, capsys.readouterr().err


def assert_finite_outputs(out: Path) -> None:
    for path in out.glob("*"):
        if path.suffix in (".csv", ".prt", ".mec", ".txt"):
            found = NON_FINITE.search(path.read_text())
            assert found is None, f"{path.name}: {found.group(0) if found else ''}"


@pytest.mark.parametrize("name", ["pendulum.mec", "fourbar_optimise.mec"])
def test_overflowing_numbers_end_with_a_message_or_finite_results(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], name: str
) -> None:
    # Every number of the DYNAMICS or OPTIMISE block replaced by 1e308, -1e308, 1e-320, NaN and infinity: each
    # run ends with a deck error (exit 1) or runs with finite results (exit 0, or 3 with the reason), never with an
    # internal error (exit 4), a warning of numpy, or an infinity or NaN in an output file.
    text = (VALID / name).read_text().replace("OPTSTEPS 30", "OPTSTEPS 3")
    for data in VALID.glob("*.dat"):
        (tmp_path / data.name).write_bytes(data.read_bytes())
    variants = overflowing_variants(text)
    assert len(variants) >= 30
    statuses: dict[int, int] = {}
    for k, (line, variant) in enumerate(variants):
        deck = tmp_path / f"v{k}.mec"
        deck.write_text(variant)
        status, err = run_here(deck, tmp_path / f"out{k}", capsys)
        where = f"line {line}: {variant.splitlines()[line - 1]}"
        assert status in (0, 1, 3), f"{where}: exit {status}: {err}"
        assert "Traceback" not in err and "Warning" not in err, f"{where}: {err}"
        if status == 1:
            assert f"v{k}.mec:{line}:" in err or f"v{k}.mec: line {line}:" in err, f"{where}: {err}"
        else:
            assert_finite_outputs(tmp_path / f"out{k}")
        statuses[status] = statuses.get(status, 0) + 1
    assert statuses.get(1, 0) > len(variants) // 2, statuses


@pytest.mark.parametrize(
    ("change", "message"),
    [
        (("GRAVITY 0 -9.81", "GRAVITY 0 -9.81\nLOAD 2 1e308\nLOAD 2 1e308"), "the load 1e308 is too large"),
        (("GRAVITY 0 -9.81", "GRAVITY 0 -9.81\nLOAD 2 1e100\nLOAD 2 1e100"), "already has a LOAD, given at line 18"),
        (("GRAVITY 0 -9.81", "GRAVITY 0 -9.81\nSPRING 2 1e308 -5"), "the spring's stiffness 1e308 is too large"),
        (("MASS 1 2.0 1.0 0.0 0.01", "MASS 1 1e200 1.0 0.0 0.01"), "the mass 1e200 is too large"),
        (("MASS 1 2.0 1.0 0.0 0.01", "MASS 1 1e300 1e300 0 1e308"), "the mass 1e300 is too large"),
        (("GRAVITY 0 -9.81", "GRAVITY 0 -9.81\nFORCE 3 3 1 1"), "FORCE names co-ordinate 3 for both the x and the y"),
        (("GRAVITY 0 -9.81", "GRAVITY 0 -9.81\nPMASS 3 3 1"), "PMASS names co-ordinate 3 for both the x and the y"),
        (("GRAVITY 0 -9.81", "GRAVITY 0 -9.81\nLOADFUNC 2 big.dat"), "big.dat:1:3"),
    ],
    ids=["load-twice", "load-repeated", "spring", "mass-gravity", "mass-no-mass", "force", "pmass", "loadfunc"],
)
def test_overflowing_dynamics_are_refused_with_their_line(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], change: tuple[str, str], message: str
) -> None:
    (tmp_path / "big.dat").write_text("0 1e308\n1 -1e308\n")
    deck = variant(tmp_path, VALID / "pendulum.mec", change)
    status, err = run_here(deck, tmp_path / "out", capsys)
    assert status == 1, err
    assert message in err, err
    assert not (tmp_path / "out").exists()


@pytest.mark.parametrize(
    ("change", "message"),
    [
        (("MOV_DYN 1 0 ", "MOV_DYN 1 1e300 "), "the initial velocity 1e300 is too large"),
        (("PMASS 3 4 2.0", "MASS 1 1 0.5 0 1e308"), "the moment of inertia 1e308 is too large"),
        (("ACCURACY 1E-10", "ACCURACY 1E-10\nINTTOL 1e300 1e300"), "relative error of 1 or more"),
    ],
    ids=["mov-dyn", "inertia", "inttol"],
)
def test_overflowing_simulations_are_refused_with_their_line(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], change: tuple[str, str], message: str
) -> None:
    deck = variant(tmp_path, VALID / "pendulum_released.mec", change)
    status, err = run_here(deck, tmp_path / "out", capsys)
    assert status == 1, err
    assert "pendulum_released.mec:" in err and message in err, err
    assert "XMOV" not in err and "MOV_FREE" not in err


@pytest.mark.parametrize(
    ("change", "message"),
    [
        (("TARGETEXT 102 100 0.0", "TARGETAT 100 10 1e300"), "supply_opt.mec:{line}:"),
        (("TARGETEXT 102 100 0.0", "TARGET 100 huge.dat"), "huge.dat:1:1"),
        (("TARGETEXT 102 100 0.0", "TARGETEXT 102 100 0.0\nOPTSTEPS 2147483648"), "supply_opt.mec:{next}:"),
    ],
    ids=["targetat", "target-file", "optsteps"],
)
def test_overflowing_optimisations_are_refused_with_their_line(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], change: tuple[str, str], message: str
) -> None:
    (tmp_path / "huge.dat").write_text("1e308\n" * 73)
    status, err = run_here(variant(tmp_path, OPT, change), tmp_path / "out", capsys)
    assert status == 1, err
    line = line_of(OPT, change[0])
    assert message.format(line=line, next=line + 1) in err, err
    assert "optimised in" not in err


def test_a_dynamics_result_that_overflows_mid_run_stops_with_the_mass_named(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    status, err = run_here(RUNTIME / "dynamics_overflow.mec", tmp_path / "out", capsys)
    assert status == 3, err
    assert "The motion stopped after position 1 of 11" in err
    # The statement is named with its deck line (line 18 holds `PMASS 3 4 1e100`).
    assert "PMASS 3 4 1e100" in (RUNTIME / "dynamics_overflow.mec").read_text().splitlines()[17]
    assert "the potential energy of the PMASS at co-ordinates 3, 4 given at line 18 is not finite" in err
    assert "XMOV" not in err and "smaller steps" not in err
    rows = (tmp_path / "out" / "dynamics_overflow.csv").read_text().splitlines()
    assert len(rows) == 2  # the header and position 1
    assert_finite_outputs(tmp_path / "out")


def test_an_objective_that_overflows_is_an_error_naming_the_target(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    status, err = run_here(RUNTIME / "objective_overflow.mec", tmp_path / "out", capsys)
    assert status == 1, err
    assert "objective_overflow.mec: line 36: the objective is not finite" in err
    assert "converged" not in err and "infs or NaNs" not in err


def test_a_simulation_whose_forces_overflow_at_the_start_names_the_mass(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    # Each number within the bounds, but the bob's centripetal acceleration (1e100 rad/s)^2 * 1e100 m times its
    # mass 1e100 overflows: refused before anything is integrated, without blaming the XMOV estimates or the mass.
    change = (
        ("PMASS 3 4 2.0", "MASS 1 1e100 1e100 0"),
        ("MOV_DYN 1 0 ", "MOV_DYN 1 1e100 "),
        ("TSTEPE 240", "TSTEPE 10"),
    )
    status, err = run_here(variant(tmp_path, VALID / "pendulum_released.mec", *change), tmp_path / "out", capsys)
    assert status == 1, err
    assert "the inertia force of the MASS on element 1 (BIN) given at line 18 is not finite" in err, err
    assert "XMOV" not in err and "no mass" not in err


def test_a_dynamics_fault_of_a_python_model_is_named_by_its_points_without_deck_lines() -> None:
    # The same overflowing slider as dynamics_overflow.mec, built in Python: the message names the point by the
    # model's names; the line of the deck text the model was written to means nothing to its author.
    from mechfem import Driven, Mechanism, MechfemError, Motion

    m = Mechanism("slider")
    guide_start, slider = m.fixed("O", 0.0, 0.0), m.point("S", 1e100, 0.0)
    m.bar("guide", guide_start, slider, length=Driven(name="travel"), angle=0.0)
    m.point_mass(slider, 1e100)
    m.gravity(-1e100, 0.0)
    with pytest.raises(MechfemError) as caught:
        m.run(Motion.to(10, {"travel": 1e110}))
    message = str(caught.value)
    assert "of the PMASS at point S is not finite" in message, message
    assert "line" not in message, message
