"""A KIN OPT deck in mm and degrees optimises to the metre deck's design converted: the function-generation example
written again with ``UNITS LENGTH mm ANGLE deg`` (every length times 1000, every angle and the TARGET file in
degrees) gives the same objective and the same design, and its print file states the design in mm and degrees."""

from __future__ import annotations

import math
import shutil
from pathlib import Path

import numpy as np
import pytest

from conftest import ROOT
from mechfem.design import optimise_deck

EXAMPLE = ROOT / "examples" / "synthesis"
DEG = math.degrees

#: function.mec's lines as they read in mm and degrees.
IN_MM = [
    ("     3 3.0", "     3 3000.0"),
    ("XMOV 5 0.36", "XMOV 5 360.0"),
    ("     6 0.93", "     6 930.0"),
    ("     7 2.57", "     7 2570.0"),
    ("     8 2.46", "     8 2460.0"),
    ("PARA 1 1.0", "PARA 1 1000.0"),
    ("     2 3.5\n", "     2 3500.0\n"),
    ("     3 2.5\n", "     3 2500.0\n"),
    ("     4 1.2 ", f"     4 {DEG(1.2)!r} "),
    ("VARY 1 0.3 3.0", "VARY 1 300.0 3000.0"),
    ("VARY 2 1.0 8.0", "VARY 2 1000.0 8000.0"),
    ("VARY 3 1.0 6.0", "VARY 3 1000.0 6000.0"),
    ("VARY 4 0.0 2.5", f"VARY 4 0.0 {DEG(2.5)!r}"),
    ("MOV_RELE 1 1.5707963267948966", "MOV_RELE 1 90.0"),
    ("TARGET 1 function.dat", "TARGET 1 function_deg.dat"),
]


def _decks(tmp_path: Path) -> tuple[Path, Path]:
    si = tmp_path / "function.mec"
    shutil.copy(EXAMPLE / "function.mec", si)
    shutil.copy(EXAMPLE / "function.dat", tmp_path / "function.dat")
    text = si.read_text(encoding="utf-8")
    for old, new in IN_MM:
        assert old in text, old
        text = text.replace(old, new, 1)
    mm = tmp_path / "function_mm.mec"
    mm.write_text(text.replace("KIN OPT\n", "KIN OPT\nUNITS LENGTH mm ANGLE deg\n", 1), encoding="utf-8")
    lines = (EXAMPLE / "function.dat").read_text(encoding="utf-8").splitlines()
    degrees = [s if s.startswith("#") or not s.strip() else repr(DEG(float(s))) for s in lines]
    (tmp_path / "function_deg.dat").write_text("\n".join(degrees) + "\n", encoding="utf-8")
    return si, mm


def test_a_deck_in_mm_and_degrees_finds_the_metre_decks_design(tmp_path: Path) -> None:
    found = []
    for deck in _decks(tmp_path):
        opt = optimise_deck.describe(deck).optimise
        assert opt is not None
        outcome = optimise_deck.optimise(deck, opt)
        assert outcome.deck is not None
        scales = optimise_deck.deck_scales(opt, outcome.deck.problem)
        found.append((outcome.objective, np.asarray(outcome.x), scales))
    (f_si, x_si, s_si), (f_mm, x_mm, s_mm) = found
    assert s_si == [1.0] * 4 and s_mm == pytest.approx([1000.0, 1000.0, 1000.0, DEG(1.0)])
    assert f_mm == pytest.approx(f_si, rel=1e-9)
    assert np.allclose(x_mm, x_si, rtol=1e-9, atol=0.0)
    assert f_si < 1e-2
