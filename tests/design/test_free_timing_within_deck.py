"""A deck states ordered free timing within a sweep as ``FREETIME r ORDERED WITHIN w``: the problem of Python's
``FreeTiming(..., ordered=True, within=w)``. The known four-bar of the path-generation example passes its ten points
over 324 degrees of the crank; kept within 5.5 rad, the deck's optimum lies on the sweep's bound, at Python's error,
design and crank angles. A deck in degrees reads w in degrees and finds the same four-bar."""

from __future__ import annotations

import math
import sys
from pathlib import Path

import numpy as np
import pytest

import mechfem
from conftest import ROOT
from mechfem.design import optimise_deck

sys.path.insert(0, str(ROOT / "examples" / "synthesis"))
import path_synthesis as ps  # noqa: E402

SWEEP = 5.5
"""Radians: less than the 324 degrees over which the known four-bar passes its points."""
VARY = "VARYX 3 1 5\nVARYX 4 -2 2\nVARY 1 0.5 2\nVARY 2 1.5 5\nVARY 5 1 4\nVARY 3 -1 3\nVARY 4 -1 3\n"
"""The ranges of ``path_synthesis`` (B0, the three lengths, u and v) in the deck's numbers."""


def deck(tmp_path: Path, unit: str) -> Path:
    """The poor start design of ``path_synthesis`` as a KIN OPT deck in ``unit``: one position at each of the ten
    crank angles (the start values of the free timing), P's x and y the targets, ``FREETIME 6 ORDERED WITHIN w``."""
    folder = tmp_path / unit
    folder.mkdir()
    pts = ps.known_points()
    for k, c in enumerate("xy"):
        (folder / f"p{c}.dat").write_text("".join(f"{float(v)!r}\n" for v in pts[:, k]))
    m = ps.four_bar()
    m.motion = mechfem.Motion.by(len(ps.THETAS) - 1, float(ps.THETAS[-1] - ps.THETAS[0]))
    text = m.to_deck().replace("KIN ANA", "KIN OPT")
    sweep = SWEEP
    if unit == "deg":
        turn = f"MOV_RELE 1 {float(ps.THETAS[-1])!r}"
        assert turn in text
        text = text.replace(turn, f"MOV_RELE 1 {math.degrees(float(ps.THETAS[-1]))!r}")
        text = text.replace("KIN OPT\n", "KIN OPT\nUNITS ANGLE deg\n")
        sweep = math.degrees(SWEEP)
    block = (
        f"OPTIMISE\n{VARY}BUFX0 9 1\nBUFX0 10 2\nTARGET 1 px.dat\nTARGET 2 py.dat\n"
        f"FREETIME 6 ORDERED WITHIN {sweep!r}\nOPTFTOL 1E-12 1E-24\n"
    )
    path = folder / "within.mec"
    path.write_text(text.replace("\nEND", "\n" + block + "END"))
    return path


def solved(path: Path) -> tuple[mechfem.Optimum, list[float]]:
    opt = optimise_deck.describe(path).optimise
    assert opt is not None and opt.free_time is not None and opt.free_time.ordered
    out = optimise_deck.optimise(path, opt)
    assert out.deck is not None and out.deck.synthesis is not None
    inputs = out.deck.synthesis.inputs(out.x)
    assert inputs is not None
    return out, inputs


def test_a_decks_ordered_points_within_a_sweep_are_pythons(tmp_path: Path) -> None:
    out, inputs = solved(deck(tmp_path, "rad"))
    vary = {name: (lo, hi) for name, lo, hi in zip(ps.NAMES, ps.LOWER, ps.UPPER, strict=True)}
    targets = [mechfem.Target("P.x", ps.known_points()[:, 0]), mechfem.Target("P.y", ps.known_points()[:, 1])]
    timing = mechfem.FreeTiming("theta", list(ps.THETAS), ordered=True, within=SWEEP)
    py = mechfem.optimize(ps.four_bar(), vary, targets=targets, timing=timing, rtol=1e-12, atol=1e-24)
    assert out.method == py.method == "SLSQP"
    # On the bound: without it the known four-bar (error 0, a sweep of 324 degrees) would be found.
    assert inputs[-1] - inputs[0] == pytest.approx(SWEEP, abs=1e-8) and out.objective > 1e-6
    assert out.objective == pytest.approx(py.objective, rel=1e-8)
    for x, name in zip(out.x[: len(ps.NAMES)], ps.NAMES, strict=True):
        assert x == pytest.approx(py.values[name], abs=1e-6)
    assert py.timing is not None
    assert inputs == pytest.approx(py.timing, abs=1e-6)


def test_within_in_a_deck_in_degrees_is_read_in_degrees(tmp_path: Path) -> None:
    rad, t_rad = solved(deck(tmp_path, "rad"))
    deg, t_deg = solved(deck(tmp_path, "deg"))
    assert t_deg[-1] - t_deg[0] == pytest.approx(math.degrees(SWEEP), abs=1e-6)
    assert deg.objective == pytest.approx(rad.objective, rel=1e-6)
    assert np.asarray(t_deg) == pytest.approx(np.degrees(t_rad), abs=1e-5)
