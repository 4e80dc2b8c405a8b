"""The OPTIMISE block of a DYN ANA deck: the exact design sensitivities of the dynamic buffers (drive torque,
shaking force and moment) against central differences of whole runs, for a dimension and every kind of mass
variable; the balancing example (examples/balancing/slider_crank_balance.mec) against the textbook's closed form;
and ``mechfem run`` writing the final design as a DYN ANA deck that runs."""

from __future__ import annotations

import os
import re
from pathlib import Path

import numpy as np
import pytest

from conftest import ROOT
from mechfem import _core
from mechfem.design import optimise_deck

EXAMPLE = ROOT / "examples" / "balancing" / "slider_crank_balance.mec"

# The example's numbers (its DYNAMICS block): crank r, rod l with its centre a from the crank pin A, masses.
R, L, A = 0.1, 0.35, 0.1
M_CRANK, M_ROD, M_PISTON = 2.0, 1.2, 1.5


def without_media(tmp_path: Path) -> Path:
    """The example without its pictures (they take seconds to draw), in a folder of its own."""
    deck = tmp_path / "deck" / EXAMPLE.name
    deck.parent.mkdir(parents=True)
    lines = EXAMPLE.read_text().splitlines(keepends=True)
    deck.write_text("".join(s for s in lines if not re.match(r"\s*(ANIMATE|BEGINPIC|ENDPIC|PLOT)", s)))
    return deck


def model(variables: list[tuple[int, int]], buffers: list[int]) -> _core.DynamicDesignModel:
    text = EXAMPLE.read_text()
    return _core.DynamicDesignModel(text, os.fspath(EXAMPLE), os.fspath(EXAMPLE.parent), variables, buffers, [])


def test_dynamic_gradients_match_central_differences_of_whole_runs() -> None:
    # The crank length (row 1), the crank's mass, centre (u, v) and inertia, the rod's inertia, the piston.
    variables = [(1, 1), (10, 1), (11, 1), (12, 1), (13, 1), (13, 2), (14, 7)]
    buffers = [2, 3, 4, 5]  # drive torque, shaking force x and y, shaking moment
    m = model(variables, buffers)
    x0 = np.array(m.start()) + np.array([0.01, 0.3, -0.05, 0.004, 0.001, 0.002, 0.2])
    d = m.evaluate([float(v) for v in x0])
    assert d.feasible, d.reason
    values, gradient = d.values, d.gradient
    assert gradient.shape == (72, len(buffers), len(variables))
    for k in range(len(variables)):
        h = 1e-6 * max(1.0, abs(x0[k]))
        runs = []
        for sign in (1.0, -1.0):
            x = x0.copy()
            x[k] += sign * h
            e = m.evaluate([float(v) for v in x])
            assert e.feasible, e.reason
            runs.append(e.values)
        fd = (runs[0] - runs[1]) / (2 * h)
        scale = np.maximum(np.abs(values).max(axis=0), 1.0)
        err = np.abs(fd - gradient[:, :, k]) / scale
        assert err.max() < 1e-6, (variables[k], err.max())
    # A mass variable moves no kinematic position; the crank length does.
    assert np.abs(gradient[:, 1:3, 1]).max() > 0


def test_the_balancing_example_finds_the_textbooks_full_balance_of_the_crank() -> None:
    opt = optimise_deck.describe(EXAMPLE).optimise
    assert [(v.item, v.number) for v in opt.mass_vary] == [("U", 1), ("V", 1)]
    outcome = optimise_deck.optimise(EXAMPLE, opt)
    s = outcome
    # The rod as equivalent point masses at A and at the piston B.
    m_a = M_ROD * (L - A) / L
    m_rec = M_PISTON + M_ROD * A / L
    u = -R * (m_a + m_rec / 2) / M_CRANK
    assert s.success, s.message
    assert s.x[0] == pytest.approx(u, abs=1e-9)
    assert s.x[1] == pytest.approx(0.0, abs=1e-9)
    # The half primary force of the reciprocating mass is left, and the secondary (r/l of the primary) on top.
    omega = 50 * np.pi
    primary = m_rec * R * omega**2
    assert primary / 2 < s.objective < primary / 2 + primary * R / L
    assert s.start_objective > 2.5 * s.objective
    assert outcome.deck.problem.names == ["U 1", "V 1"]


@pytest.fixture(scope="module")
def optimised(tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, Path]:
    """The example optimised by ``mechfem run`` once: (deck, output folder)."""
    from mechfem.cli.command import main

    tmp = tmp_path_factory.mktemp("dynopt")
    deck = without_media(tmp)
    out = tmp / "out"
    assert main(["run", str(deck), "-o", str(out)]) == 0
    return deck, out


def test_mechfem_run_writes_the_balanced_design_as_a_dyn_ana_deck(optimised: tuple[Path, Path]) -> None:
    deck, out = optimised
    written = out / f"{deck.stem}_opt.mec"
    text = written.read_text()
    assert text.splitlines()[8] == "DYN ANA"
    assert "VARYM" not in text and "\nOPTIMISE" not in text
    mass = next(line for line in text.splitlines() if line.startswith("MASS  1"))
    u = float(mass.split()[3])
    assert u == pytest.approx(-R * (M_ROD * (L - A) / L + (M_PISTON + M_ROD * A / L) / 2) / M_CRANK, abs=1e-9)
    printed = (out / f"{deck.stem}.prt").read_text()
    assert "OPTIMISATION" in printed and "(mode DYN ANA)" in printed
    assert re.search(r"^\s+U 1\s+m\s+0\.03\s", printed, re.M), printed[:2000]


def test_the_written_deck_runs_to_the_optimum_found(optimised: tuple[Path, Path]) -> None:
    deck, out = optimised
    written = out / f"{deck.stem}_opt.mec"
    m = _core.DynamicDesignModel(written.read_text(), os.fspath(written), os.fspath(out), [(11, 1)], [3, 4], [])
    d = m.evaluate(m.start())
    fx, fy = d.values[:, 0], d.values[:, 1]
    rms = float(np.sqrt(np.mean(fx**2 + fy**2)))
    outcome = optimise_deck.optimise(EXAMPLE, optimise_deck.describe(EXAMPLE).optimise)
    assert rms == pytest.approx(outcome.objective, rel=1e-9)


def test_the_report_shows_the_balancing_as_its_optimisation_section(optimised: tuple[Path, Path]) -> None:
    import mechfem
    from mechfem.report.optimum_report import deck_section

    deck, out = optimised
    outcome = optimise_deck.optimise(deck, optimise_deck.describe(deck).optimise)
    final = mechfem.run_deck(out / f"{deck.stem}_opt.mec")
    section = deck_section(outcome, final)
    assert [(v["name"], v["unit"]) for v in section["variables"]] == [("U 1", "m"), ("V 1", "m")]
    assert section["objective"]["final"] == pytest.approx(outcome.objective)
    assert section["drawing"]["start"] is not None


def test_a_deck_in_grams_varies_and_writes_its_masses_in_grams(tmp_path: Path) -> None:
    # The example with its masses in g (J in g m^2): the counterweight's mass and centre both vary, and the
    # optimum balances the first moment m1 u = -r (m_A + m_rec / 2) in kg m, whatever the unit of the deck.
    text = EXAMPLE.read_text().replace("MASS kg", "MASS g")
    text = text.replace("MASS  1 2.0 0.03 0.0 0.004", "MASS  1 2000 0.03 0.0 4")
    text = text.replace("      2 1.2 0.1  0.0 0.03 ", "      2 1200 0.1  0.0 30 ")
    text = text.replace("PMASS 7 8 1.5 ", "PMASS 7 8 1500 ")
    text = text.replace("VARYM V 1 -0.2 0.2", "VARYM MASS 1 1000 3000")
    deck = tmp_path / "grams.mec"
    deck.write_text("".join(s for s in text.splitlines(keepends=True) if not re.match(r"\s*(BEGINPIC|ENDPIC|PLOT)", s)))
    opt = optimise_deck.describe(deck).optimise
    outcome = optimise_deck.optimise(deck, opt)
    u, m1 = outcome.x  # the core's units: m and kg
    first_moment = -R * (M_ROD * (L - A) / L + (M_PISTON + M_ROD * A / L) / 2)
    assert m1 * u == pytest.approx(first_moment, rel=1e-6)
    written = optimise_deck.write_design_deck(outcome, tmp_path / "out")
    mass = next(line for line in written.read_text().splitlines() if line.startswith("MASS  1")).split()
    assert float(mass[2]) == pytest.approx(1000 * m1, rel=1e-12)
    assert float(mass[3]) == pytest.approx(u, rel=1e-12)
    line = optimise_deck.values_line(outcome.deck.problem, outcome.x, None, opt)
    assert f"MASS 1 = {1000 * m1:.10g}" in line, line


def test_python_optimize_of_the_mechanism_agrees_with_its_deck(tmp_path: Path) -> None:
    import mechfem
    from mechfem.design.dynamic_optimise import Drive, ShakingForce
    from mechfem.model.loads import Body

    mech = mechfem.Mechanism.from_deck(ROOT / "examples" / "balancing" / "slider_crank_dyn.mec")
    vary = {"crank.mass_u": (-0.2, 0.2), "crank.mass_v": (-0.2, 0.2)}
    found = mechfem.optimize(mech, vary, minimize=("rms", ShakingForce()), rtol=1e-13, atol=0.0)
    deck = optimise_deck.optimise(EXAMPLE, optimise_deck.describe(EXAMPLE).optimise)
    assert found.objective == pytest.approx(deck.objective, rel=1e-12)
    assert found.values["crank.mass_u"] == pytest.approx(deck.x[0], abs=1e-10)
    assert found.start["crank.mass_u"] == 0.03
    body = found.mechanism.loads.of(Body)[0] if found.mechanism.loads else None
    assert body is not None and body.u == found.values["crank.mass_u"]
    # The RMS drive torque over the piston's mass, as the deck states it with VARYM PMASS and BUFDRV.
    text = re.sub(r"VARYM V 1 .*\n", "", EXAMPLE.read_text().replace("VARYM U 1 -0.2 0.2", "VARYM PMASS 7 0.5 3"))
    text = text.replace("MINIMISE RMS 3 4 ", "MINIMISE RMS 2 ")
    path = tmp_path / "drive.mec"
    path.write_text(text)
    by_deck = optimise_deck.optimise(path, optimise_deck.describe(path).optimise)
    assert by_deck.deck.problem.names == ["PMASS 7"]
    by_python = mechfem.optimize(mech, {"B.mass": (0.5, 3.0)}, minimize=("rms", Drive("phi")), rtol=1e-13, atol=0.0)
    assert by_python.values["B.mass"] == pytest.approx(by_deck.x[0], abs=1e-9)
    assert by_python.objective == pytest.approx(by_deck.objective, rel=1e-10)


def test_an_interrupted_balancing_writes_the_design_it_had_reached(tmp_path: Path) -> None:
    from mechfem.design.engine import Iteration

    deck = without_media(tmp_path)
    opt = optimise_deck.describe(deck).optimise
    history = [
        Iteration(0, 6363.4, 0.0, 0.0, 1, np.array([0.03, 0.0])),
        Iteration(1, 2460.0, 0.0, 0.1, 3, np.array([-0.05, 0.01])),
    ]
    written = optimise_deck.write_interrupted(deck, opt, history, tmp_path / "out")
    assert [p.name for p in written] == [f"{deck.stem}_opt.mec", f"{deck.stem}.prt"]
    assert "MASS  1 2.0 -0.05 0.01 0.004" in written[0].read_text()
    assert re.search(r"U 1\s+-0.05\n", written[1].read_text())


def test_a_multi_start_of_mass_variables_is_refused_with_a_reason() -> None:
    import mechfem
    from mechfem.design.dynamic_optimise import ShakingForce

    mech = mechfem.Mechanism.from_deck(ROOT / "examples" / "balancing" / "slider_crank_dyn.mec")
    with pytest.raises(ValueError, match="balance a mechanism's masses from one start"):
        mechfem.optimize(mech, {"crank.mass_u": (-0.2, 0.2)}, minimize=("rms", ShakingForce()), starts=3)
