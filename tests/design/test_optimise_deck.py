"""``mechfem run`` of a KIN OPT deck: the supply mechanism's coupler angle kappa optimised from its deck
(examples/supply/supply_opt.mec), the final design written as a KIN ANA deck, the print file's OPTIMISATION
section, and the refusals."""

from __future__ import annotations

import math
import os
import re
from pathlib import Path

import numpy as np
import pytest

from conftest import ROOT, Cli
from mechfem import _core

EXAMPLE = ROOT / "examples" / "supply" / "supply_opt.mec"
KAPPA = -5.17514
"""kappa as the theory prints it (section 5.6.6)."""


def without_media(tmp_path: Path) -> Path:
    """The example without its pictures and animation (they take seconds to draw), in a folder of its own."""
    deck = tmp_path / "deck" / "supply_opt.mec"
    deck.parent.mkdir()
    lines = EXAMPLE.read_text().splitlines(keepends=True)
    deck.write_text("".join(s for s in lines if not re.match(r"\s*(ANIMATE|BEGINPIC|ENDPIC|PLOT)", s)))
    return deck


def extrema(deck: Path) -> list[float]:
    """Buffer 102 (the output's second-order transfer function) at the extrema of buffer 100 (the output)."""
    model = _core.DesignModel(deck.read_text(), os.fspath(deck), os.fspath(deck.parent), [(1, 5)], [102], [(102, 100)])
    d = model.evaluate(model.start())
    assert d.feasible, d.reason
    return [x.value for x in d.extrema]


@pytest.fixture(scope="module")
def optimised(tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, Path, str, str]:
    """The example optimised once: (deck, output folder, stdout, stderr)."""
    import subprocess

    from conftest import mechfem_command

    tmp = tmp_path_factory.mktemp("opt")
    deck = without_media(tmp)
    out = tmp / "out"
    p = subprocess.run([*mechfem_command(), "run", str(deck), "-o", str(out)], capture_output=True, text=True)
    assert p.returncode == 0, p.stderr
    return deck, out, p.stdout, p.stderr


def test_the_supply_deck_finds_kappa_of_the_theory(optimised: tuple[Path, Path, str, str]) -> None:
    _, out, stdout, stderr = optimised
    text = (out / "supply_opt_opt.mec").read_text()
    kappa = float(re.search(r"^\s+5 (\S+)\s+; the angle kappa", text, re.M).group(1))  # type: ignore[union-attr]
    assert abs(kappa - KAPPA) < 2e-4
    # The variable by the deck's name, with its unit.
    assert re.search(r"; kappa = -5\.17\d* rad$", stdout, re.M)
    assert re.search(r"^  iteration 1: objective \S+, largest violation 0, step \S+, \d+ runs?$", stderr, re.M)
    # Both dead-position accelerations below 1 % of the largest second-order transfer function.
    data = np.loadtxt(out / "supply_opt.csv", delimiter=",", skiprows=1)
    values = extrema(out / "supply_opt_opt.mec")
    assert len(values) == 2
    assert max(abs(v) for v in values) < 0.01 * np.abs(data[:, 3]).max()


def test_the_optimised_deck_runs_as_kin_ana_and_keeps_the_design(optimised: tuple[Path, Path, str, str]) -> None:
    _, out, _, _ = optimised
    deck = out / "supply_opt_opt.mec"
    d = _core.describe_deck_text(deck.read_text(), os.fspath(deck), os.fspath(out))
    assert d.mode == "KIN ANA" and d.optimise is None
    first = _core.describe_deck_text(EXAMPLE.read_text(), os.fspath(EXAMPLE), os.fspath(EXAMPLE.parent))
    assert d.storage.savedata == first.storage.savedata
    kappa = d.prescribed[4].para
    assert abs(kappa - KAPPA) < 2e-4
    # The data set is the run of that deck.
    import mechfem

    again = mechfem.run_deck(deck)
    data = np.loadtxt(out / "supply_opt.csv", delimiter=",", skiprows=1)
    np.testing.assert_allclose(again.buffers[102], data[:, 3], rtol=0, atol=1e-12)


def test_the_print_file_has_the_history_and_the_variables(optimised: tuple[Path, Path, str, str]) -> None:
    deck, out, _, _ = optimised
    prt = (out / "supply_opt.prt").read_text()
    section = prt[prt.index("OPTIMISATION") :]
    assert "method: least_squares (trf)" in section
    assert re.search(r"^\s+iteration\s+objective\s+violation\s+step\s+runs$", section, re.M)
    assert re.search(r"^\s+0\s+2\.359\d+e-01\s+0\s+0\s+1$", section, re.M)
    row = re.search(r"^\s+kappa\s+rad\s+-5\.25\s+(\S+)\s+-5\.5\s+-5$", section, re.M)
    assert row is not None and abs(float(row.group(1)) - KAPPA) < 2e-4
    assert re.search(r"objective: start 0\.2359\d+, final \S+", section)
    assert re.search(r"\d+ mechanism runs in \S+ s", section)
    assert "converged:" in section
    # Each extremum of delta (buffer 100) with buffer 102 there, by their labels, the input by its name (rad).
    extrema = r"^\s+d2delta/dalpha\^2 at an extremum of delta, alpha = \S+ rad: \S+ 1/rad \(target 0 1/rad\)$"
    assert len(re.findall(extrema, section, re.M)) == 2
    # Nothing was written beside the deck.
    assert sorted(p.name for p in deck.parent.iterdir()) == ["supply_opt.mec"]
    assert sorted(p.name for p in out.iterdir()) == ["supply_opt.csv", "supply_opt.prt", "supply_opt_opt.mec"]


def test_an_infeasible_start_is_refused_with_its_line(cli: Cli, tmp_path: Path) -> None:
    deck = without_media(tmp_path)
    # The crank (row 1) three times longer than the rest of the mechanism allows.
    text = deck.read_text().replace("PARA 1  0.4", "PARA 1  3.0").replace("VARY 5 -5.5 -5.0", "VARY 1 0.1 5.0")
    deck.write_text(text)
    p = cli("run", deck, "-o", tmp_path / "out")
    assert p.returncode == 1, p.stderr
    assert "Traceback" not in p.stderr
    assert f"error: {deck}: the optimisation (OPTIMISE, line 97) cannot start: the start design is infeasible" in (
        p.stderr
    )
    assert "PARA 1 (VARY on line 98)" in p.stderr
    assert not (tmp_path / "out" / "supply_opt_opt.mec").exists()


def test_describe_gives_the_optimise_block_in_deck_numbering() -> None:
    d = _core.describe_deck_text(EXAMPLE.read_text(), os.fspath(EXAMPLE), os.fspath(EXAMPLE.parent))
    assert d.mode == "KIN OPT"
    opt = d.optimise
    assert opt is not None
    ((vary,),) = [opt.vary]
    assert (vary.kind, vary.number, vary.lo, vary.hi, vary.line) == (1, 5, -5.5, -5.0, 98)
    assert (vary.unit, vary.scale) == ("", 1.0)  # no UNITS: the deck's own numbers
    ((target,),) = [opt.targets]
    assert (target.buffer, target.kind, target.reference, target.value, target.weight, target.line) == (
        102,
        "extremum",
        100,
        0.0,
        1.0,
        101,
    )
    assert (target.values, target.file, target.position) == (None, None, None)
    assert (opt.bounds, opt.objective, opt.steps, opt.tol, opt.line) == ([], None, 200, None, 97)
    plain = _core.describe_deck_text(ROOT.joinpath("examples/supply/supply.mec").read_text(), "supply.mec", ".")
    assert plain.optimise is None


def test_the_optimised_deck_text_replaces_para_and_drops_optimise() -> None:
    text = _core.optimised_deck_text(EXAMPLE.read_text(), os.fspath(EXAMPLE), [(5, -5.175)], [(9, 0.2)])
    assert text.splitlines()[8] == "KIN ANA"
    assert "      5 -5.175    ; the angle kappa" in text and "XMOV 9  0.2\n" in text
    assert "\nOPTIMISE\n" not in text and "VARY" not in text and "TARGETEXT" not in text
    assert "STORAGE\nBUFE0  -1 100          ; output angle\n" in text


def test_ctrl_c_writes_the_design_reached(tmp_path: Path) -> None:
    from mechfem.design import engine as design
    from mechfem.design import optimise_deck

    deck = without_media(tmp_path)
    opt = optimise_deck.describe(deck).optimise
    assert opt is not None
    history = [
        design.Iteration(0, 0.2, 0.0, 0.0, 1, np.array([-5.25])),
        design.Iteration(1, 0.01, 0.0, 0.06, 2, np.array([-5.19])),
    ]
    out = tmp_path / "out"
    written = optimise_deck.write_interrupted(deck, opt, history, out)
    assert sorted(p.name for p in written) == ["supply_opt.prt", "supply_opt_opt.mec"]
    assert sorted(p.name for p in out.iterdir()) == ["supply_opt.prt", "supply_opt_opt.mec"]
    prt = (out / "supply_opt.prt").read_text()
    assert "interrupted by Ctrl-C" in prt and "-5.19" in prt
    # The design reached runs as a KIN ANA deck with its kappa.
    run = _core.describe_deck_text((out / "supply_opt_opt.mec").read_text(), "x.mec", os.fspath(deck.parent))
    assert run.mode == "KIN ANA"
    assert [r.para for r in run.prescribed if r.dest == 5] == [-5.19]
    # Before the first iteration there is nothing but the note.
    assert [p.name for p in optimise_deck.write_interrupted(deck, opt, [], tmp_path / "empty")] == ["supply_opt.prt"]


def _final_objective(prt: str) -> float:
    found = re.search(r"objective: start \S+, final (\S+)", prt)
    assert found is not None, prt
    return float(found.group(1))


@pytest.mark.parametrize(("stem", "worst"), [("path", 1e-16), ("function", 31 * math.radians(0.5) ** 2)])
def test_the_synthesis_decks_from_the_command_line(cli: Cli, tmp_path: Path, stem: str, worst: float) -> None:
    # Path generation reaches the known four-bar (error 0); function generation an rms below half a degree.
    src = ROOT / "examples" / "synthesis"
    deck = tmp_path / f"{stem}.mec"
    lines = (src / f"{stem}.mec").read_text().splitlines(keepends=True)
    deck.write_text("".join(s for s in lines if not re.match(r"\s*(BEGINPIC|ENDPIC|PLOT)", s)))
    for dat in src.glob(f"{stem}*.dat"):
        (tmp_path / dat.name).write_text(dat.read_text())
    done = cli("run", deck, "-o", tmp_path / "out")
    assert done.returncode == 0, done.stderr
    assert "iteration 1:" in done.stderr
    assert _final_objective((tmp_path / "out" / f"{stem}.prt").read_text()) < worst


def test_report_of_a_kin_opt_deck_says_it_shows_the_start_design(cli: Cli, tmp_path: Path) -> None:
    deck = without_media(tmp_path)
    done = cli("report", deck, "-o", tmp_path / "out")
    assert done.returncode == 0, done.stderr
    assert "KIN OPT deck: this report shows its start design" in done.stderr


def test_check_of_a_kin_opt_deck_names_the_variables(cli: Cli) -> None:
    done = cli("check", EXAMPLE)
    assert done.returncode == 0, done.stderr
    assert "KIN OPT: position 1 of the start design; the optimisation varies PARA 5 (VARY on line" in done.stdout
