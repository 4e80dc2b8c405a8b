"""A deck bounds a frame length with the language it has: a bar between the two pivots whose length is a dependent
form parameter, recorded by a buffer and bounded (BOUND). On the path-generation four-bar (its exact frame 3.2 long)
a bound of at most 3.0 holds the deck's optimum on the bound, at the design and the error of Python's
``Bound(FrameLength("A0", "B0"), ...)``: the bound through the core's exact sensitivities of a dependent row and the
bound through the frame length's own gradient reach the same optimum."""

from __future__ import annotations

import math
import shutil
import sys
from pathlib import Path

import pytest

import mechfem
from conftest import ROOT
from mechfem.design import optimise_deck
from mechfem.design.frame_length import FrameLength

SYNTHESIS = ROOT / "examples" / "synthesis"
sys.path.insert(0, str(SYNTHESIS))
import path_synthesis as ps  # noqa: E402

#: path.mec's lines with the frame bar, its length a dependent form parameter, and its bound.
FRAME = [
    ("     3 BIN 3 4 7 8            ; rocker B0-B\n", "     3 BIN 3 4 7 8\n     4 BIN 1 2 3 4\n"),
    ("     6 ANGB 1 6               ; row 6: the crank angle, the input\n", "     6 ANGB 1 6\n     7 LENL 4 -1\n"),
    ("BUFX0 10 2                    ; P's y\n", "BUFX0 10 2\nBUFE0 -1 9\nBOUND 9 0 3.0\n"),
]


def test_a_deck_bounds_its_frame_length_by_a_bar_between_the_pivots(tmp_path: Path) -> None:
    text = (SYNTHESIS / "path.mec").read_text()
    for old, new in FRAME:
        assert old in text, old
        text = text.replace(old, new, 1)
    for name in ("path_x.dat", "path_y.dat"):
        shutil.copy(SYNTHESIS / name, tmp_path)
    deck = tmp_path / "path_frame.mec"
    deck.write_text(text)
    opt = optimise_deck.describe(deck).optimise
    assert opt is not None
    found = optimise_deck.optimise(deck, opt)
    frame = math.hypot(found.values["XFIX 3"], found.values["XFIX 4"])
    assert found.method == "SLSQP" and frame == pytest.approx(3.0, abs=1e-8) and found.objective > 1e-6
    vary = {name: (lo, hi) for name, lo, hi in zip(ps.NAMES, ps.LOWER, ps.UPPER, strict=True)}
    bound = mechfem.Bound(FrameLength("A0", "B0"), 1.0, 3.0)
    python = mechfem.optimize(ps.four_bar(), vary, targets=ps.targets(), bounds=[bound], rtol=1e-12, atol=1e-24)
    assert found.objective == pytest.approx(python.objective, rel=1e-8)
    assert found.values["XFIX 3"] == pytest.approx(python.values["B0.x"], abs=1e-6)
    assert found.values["XFIX 4"] == pytest.approx(python.values["B0.y"], abs=1e-6)
