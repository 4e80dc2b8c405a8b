"""Stopping tolerances independent of the start objective: ``rtol``/``atol`` of :func:`mechfem.optimize` and
``OPTFTOL rtol atol`` of a KIN OPT deck end either optimiser when an iteration changes the objective f by less than
``atol + rtol |f|``; the classic OPTTOL scales SLSQP's test by the start objective."""

from __future__ import annotations

import shutil
import sys
from pathlib import Path

import numpy as np
import pytest

import mechfem
from mechfem.design import optimise_deck
from mechfem.design import rules as design_rules

ROOT = Path(__file__).resolve().parents[2]
SYNTHESIS = ROOT / "examples" / "synthesis"
sys.path.insert(0, str(SYNTHESIS))
import path_synthesis as ps  # noqa: E402

VARY = {name: (lo, hi) for name, lo, hi in zip(ps.NAMES, ps.LOWER, ps.UPPER, strict=True)}
# An inactive bound: the problem goes to SLSQP.
LOOSE = [mechfem.Bound("crank.length", 0.0, 10.0)]


def test_slsqp_with_the_classic_tolerance_stops_where_the_start_objective_says() -> None:
    # Start objective 17.6: SLSQP's absolute test becomes 1e-10 * 17.6, far above the optimum's 0.
    opt = mechfem.optimize(ps.four_bar(), VARY, targets=ps.targets(), bounds=LOOSE)
    assert opt.method == "SLSQP"
    assert opt.start_objective > 10.0
    assert 1e-14 < opt.objective < 1e-8


@pytest.mark.parametrize("kwargs", [{"rtol": 1e-12}, {"atol": 1e-20}, {"rtol": 1e-12, "atol": 1e-22}])
def test_slsqp_with_rtol_or_atol_goes_on_to_the_optimum(kwargs: dict[str, float]) -> None:
    opt = mechfem.optimize(ps.four_bar(), VARY, targets=ps.targets(), bounds=LOOSE, **kwargs)
    assert opt.success
    assert opt.objective < 1e-18
    np.testing.assert_allclose(
        [opt.values[n] for n in ps.NAMES], [3.2, 0.0, 1.0, 3.0, 2.5, 1.8 * np.cos(0.6), 1.8 * np.sin(0.6)], atol=1e-8
    )


def test_the_same_tolerance_gives_the_same_depth_from_a_far_and_a_near_start() -> None:
    near = (3.1, 0.05, 1.05, 2.95, 2.55, 1.5, 1.0)
    found = []
    for start in (ps.START, near):
        opt = mechfem.optimize(ps.four_bar(start), VARY, targets=ps.targets(), bounds=LOOSE, rtol=1e-12)
        found.append((opt.start_objective, opt.objective))
    assert found[0][0] > 100 * found[1][0]
    assert max(f for _, f in found) < 1e-18


def test_least_squares_with_a_large_atol_stops_early_and_says_why() -> None:
    full = mechfem.optimize(ps.four_bar(), VARY, targets=ps.targets())
    early = mechfem.optimize(ps.four_bar(), VARY, targets=ps.targets(), atol=1e-3)
    assert early.method.startswith("least_squares")
    assert "atol" in early.message and early.success
    assert early.runs < full.runs
    assert full.objective < early.objective < early.start_objective


def test_a_stop_is_refused_with_tol_or_with_bad_numbers() -> None:
    with pytest.raises(ValueError, match="not both"):
        mechfem.optimize(ps.four_bar(), VARY, targets=ps.targets(), tol=1e-8, rtol=1e-8)
    for rtol, atol in [(-1.0, 0.0), (0.0, 0.0), (1.0, 0.0), (0.0, float("inf"))]:
        with pytest.raises(ValueError):
            design_rules.FTol(rtol, atol)


def test_optftol_in_a_deck_reaches_the_optimum_with_a_bound(tmp_path: Path) -> None:
    for name in ("path_x.dat", "path_y.dat"):
        shutil.copy(SYNTHESIS / name, tmp_path / name)
    text = (SYNTHESIS / "path.mec").read_text()
    deck = tmp_path / "path.mec"
    deck.write_text(text.replace("TARGET 2 path_y.dat\n", "TARGET 2 path_y.dat\nBOUND 2 -10 10\nOPTFTOL 1E-12 0\n"))
    opt = optimise_deck.describe(deck).optimise
    assert opt is not None and opt.ftol == (1e-12, 0.0)
    outcome = optimise_deck.optimise(deck, opt)
    assert outcome.method == "SLSQP"
    assert outcome.objective < 1e-18
    # Without OPTFTOL the same deck stops at the start-scaled tolerance.
    deck.write_text(text.replace("TARGET 2 path_y.dat\n", "TARGET 2 path_y.dat\nBOUND 2 -10 10\n"))
    classic = optimise_deck.optimise(deck, optimise_deck.describe(deck).optimise)
    assert classic.objective > 1e-14
