"""Every example with an OPTIMISE block, written again in millimetres and degrees (:mod:`mm_degrees`: a converter that
knows nothing of a deck but the dimensions the deck reader gives its numbers), optimises as the SI deck does: the same
objective at the start and at every iteration, and a final design that is the SI deck's converted, as the written
``<stem>_opt.mec`` states it (every co-ordinate of its run).

A deck's optimiser works in the core's units whatever the deck's UNITS (a VARY's, VARYX's, VARYM's and VARYFRAME's
variable, and the input at a FREETIME point), so the two decks take the same steps to the last digits. Both stop after
a few iterations: a long search of a problem with many local optima (the closed curve) amplifies the last bits in
which the converted deck's numbers differ from the SI deck's into another local optimum, which says nothing of
units."""

from __future__ import annotations

import re
import shutil
from pathlib import Path

import numpy as np
import pytest

import mechfem
from conftest import ROOT
from mechfem.design import optimise_deck
from mm_degrees import SI_UNITS, factor, in_mm_and_degrees, words

ITERATIONS = 5


def examples() -> list[Path]:
    """The examples with an OPTIMISE block, without UNITS or with SI's."""
    out = []
    for deck in sorted((ROOT / "examples").rglob("*.mec")):
        lines = [words(line) for line in deck.read_text().splitlines()]
        units = [" ".join(w) for w in lines if w and w[0].upper() == "UNITS"]
        if units in ([], [SI_UNITS]) and any(w[0].upper() == "OPTIMISE" for w in lines if w):
            out.append(deck)
    return out


def few_iterations(text: str) -> str:
    """The deck with its optimiser stopped after :data:`ITERATIONS` iterations."""
    text = re.sub(r"(?im)^OPTSTEPS\s+\d+.*$", "", text)
    return re.sub(r"(?im)^OPTIMISE\s*$", f"OPTIMISE\nOPTSTEPS {ITERATIONS}", text, count=1)


def optimised(deck: Path, out: Path) -> tuple[optimise_deck.Optimum, mechfem.RunResult]:
    opt = optimise_deck.describe(deck).optimise
    assert opt is not None
    optimum = optimise_deck.optimise(deck, opt)
    with pytest.MonkeyPatch.context() as mp:
        mp.setattr("warnings.showwarning", lambda *a, **k: None)
        return optimum, mechfem.run_deck(optimise_deck.write_design_deck(optimum, out))


@pytest.mark.parametrize("deck", examples(), ids=lambda p: p.stem)
def test_an_optimisation_in_mm_and_degrees_is_the_si_one_converted(deck: Path, tmp_path: Path) -> None:
    si_dir, mm_dir = tmp_path / "si", tmp_path / "mm"
    si_dir.mkdir()
    mm_dir.mkdir()
    for data in deck.parent.iterdir():
        if data.is_file() and data.suffix != ".mec":
            shutil.copy(data, si_dir)
            shutil.copy(data, mm_dir)
    labels = mechfem.check_deck(deck).model.labels
    assert labels is not None
    si, mm = si_dir / deck.name, mm_dir / deck.name
    si.write_text(few_iterations(deck.read_text()))
    # The converted TARGET files overwrite the copies.
    mm.write_text(few_iterations(in_mm_and_degrees(deck.read_text(), labels, deck.parent, mm_dir)))
    (si_opt, si_run), (mm_opt, mm_run) = optimised(si, si_dir / "out"), optimised(mm, mm_dir / "out")
    # The objective is the sum of the squared misses in the core's units: the same number in both.
    assert mm_opt.start_objective == pytest.approx(si_opt.start_objective, rel=1e-9)
    assert len(mm_opt.history) == len(si_opt.history)
    for a, b in zip(si_opt.history, mm_opt.history, strict=True):
        assert b.objective == pytest.approx(a.objective, rel=1e-4, abs=1e-18)
    assert mm_opt.objective == pytest.approx(si_opt.objective, rel=1e-4, abs=1e-18)
    # The final design as written: its run's co-ordinates are the SI design's converted.
    mm_labels = mm_run.model.labels
    assert mm_labels is not None and mm_run.positions == si_run.positions
    for i in range(si_run.coords.shape[1]):
        want = si_run.coords[:, i] * factor(mm_labels.coordinate(i + 1)[3])
        scale = max(1.0, float(np.max(np.abs(want))))
        np.testing.assert_allclose(mm_run.coords[:, i], want, rtol=1e-4, atol=1e-4 * scale, err_msg=f"x{i + 1}")
