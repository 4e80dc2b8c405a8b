"""Periodic angle variables: an angle without a range, or with a range of one whole turn, wraps; the optimum of
a crank's start angle just below 0 is found from [0, 2 pi] (no wall at 0), where a range a little short of a turn
stops at its end."""

from __future__ import annotations

import math
import re
import sys
from pathlib import Path

import numpy as np
import pytest

import mechfem
from mechfem.design import optimise_deck

ROOT = Path(__file__).resolve().parents[2]
SYNTHESIS = ROOT / "examples" / "synthesis"
sys.path.insert(0, str(SYNTHESIS))
import path_synthesis as ps  # noqa: E402

KNOWN = (3.2, 0.0, 1.0, 3.0, 2.5, 1.8 * math.cos(0.6), 1.8 * math.sin(0.6))
SHIFT = -0.067
"""The crank's start angle of the targets: just below the wall at 0 of [0, 2 pi]."""
SWEEP = math.radians(324.0)


def shifted_points() -> np.ndarray:
    old = ps.THETAS
    try:
        ps.THETAS = old + SHIFT
        return ps.known_points()
    finally:
        ps.THETAS = old


def problem() -> tuple[mechfem.Mechanism, list[mechfem.Target]]:
    m = ps.four_bar(KNOWN)
    m.set("theta", 0.3)
    m.motion = mechfem.Motion.by(ps.SUBSTEPS * 9, SWEEP)
    pts = shifted_points()
    n = ps.SUBSTEPS * 9 + 1
    targets = []
    for k, name in enumerate(("P.x", "P.y")):
        values = np.full(n, np.nan)
        values[:: ps.SUBSTEPS] = pts[:, k]
        targets.append(mechfem.Target(name, values))
    return m, targets


@pytest.mark.parametrize("span", [(0.0, 2.0 * math.pi), None])
def test_a_periodic_crank_angle_crosses_zero_to_its_optimum(span: tuple[float, float] | None) -> None:
    m, targets = problem()
    opt = mechfem.optimize(m, {"theta": span}, targets=targets)
    assert opt.objective < 1e-18
    theta = opt.values["theta"]
    if span is None:
        # Reported within half a turn of the start value 0.3.
        assert theta == pytest.approx(SHIFT, abs=1e-9)
    else:
        assert theta == pytest.approx(2.0 * math.pi + SHIFT, abs=1e-9)
        assert 0.0 <= theta < 2.0 * math.pi


@pytest.mark.parametrize("starts_with_bounds", [True, False])
def test_a_range_short_of_a_turn_is_a_wall(starts_with_bounds: bool) -> None:
    m, targets = problem()
    span = (0.0, 6.2) if starts_with_bounds else (0.0, 2.0 * math.pi - 1e-3)
    opt = mechfem.optimize(m, {"theta": span}, targets=targets)
    assert opt.values["theta"] == pytest.approx(0.0, abs=1e-9)
    assert opt.objective > 1e-2


def test_a_length_without_a_range_is_refused() -> None:
    m, targets = problem()
    with pytest.raises(ValueError, match="not an angle"):
        mechfem.optimize(m, {"crank.length": None}, targets=targets)


def test_a_full_turn_vary_in_a_deck_wraps(tmp_path: Path) -> None:
    pts = shifted_points()
    n = ps.SUBSTEPS * 9 + 1
    for k, name in enumerate(("path_x.dat", "path_y.dat")):
        rows = ["*"] * n
        rows[:: ps.SUBSTEPS] = [repr(float(v)) for v in pts[:, k]]
        (tmp_path / name).write_text("\n".join(rows) + "\n")
    text = (SYNTHESIS / "path.mec").read_text()
    xb, yb, a, b, c, u, v = KNOWN
    for key, value in {"XFIX 1 0.0": None, "     3 2.8": f"     3 {xb}", "     4 0.4": f"     4 {yb}"}.items():
        if value is not None:
            text = text.replace(key, value, 1)
    paras = {1: a, 2: b, 3: u, 4: v, 5: c, 6: 0.3}
    text = re.sub(
        r"PARA 1 1.2\n     2 2.6\n     3 1.0\n     4 1.4\n     5 2.8\n     6 0.0\n",
        "".join(f"PARA {r} {paras[r]!r}\n" for r in paras),
        text,
    )
    text = re.sub(r"VARYX 3[^\n]*\n(?:VARYX?[^\n]*\n)*", f"VARY 6 0.0 {2.0 * math.pi!r}\n", text)
    deck = tmp_path / "path.mec"
    deck.write_text(text)
    opt = optimise_deck.describe(deck).optimise
    assert opt is not None and [v.number for v in opt.vary] == [6]
    outcome = optimise_deck.optimise(deck, opt)
    assert outcome.deck.problem.periodic == [True]
    assert outcome.objective < 1e-18
    assert outcome.x[0] == pytest.approx(2.0 * math.pi + SHIFT, abs=1e-9)
