"""Every example, written again in millimetres and degrees by a converter that knows nothing of it but the dimensions
the deck reader gives its co-ordinates, rows, inputs and buffers (``Labels``, :mod:`mm_degrees`), gives the SI deck's
results converted: every buffer (drive torques, reactions and energies included), every co-ordinate and det(D^c) at
every position, and the same limit positions. A deck with UNITS other than SI's is left out, and so is one with an
OPTIMISE block (``tests/design/test_every_optimisation_in_mm_and_degrees.py`` has those)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import mechfem
from conftest import ROOT
from mm_degrees import SI_UNITS, factor, in_mm_and_degrees, words


def examples() -> list[Path]:
    """The examples without an OPTIMISE block, without UNITS or with SI's, and a deck with a TOLERANCE block."""
    out = []
    for deck in sorted((ROOT / "examples").rglob("*.mec")):
        lines = [words(line) for line in deck.read_text().splitlines()]
        units = [" ".join(w) for w in lines if w and w[0].upper() == "UNITS"]
        if units in ([], [SI_UNITS]) and not any(w[0].upper() == "OPTIMISE" for w in lines if w):
            out.append(deck)
    # The four-bar with tolerance bands (no example has a TOLERANCE block).
    return [*out, ROOT / "tests" / "decks" / "fourbar_tolerances.mec"]


@pytest.mark.parametrize("deck", examples(), ids=lambda p: p.stem)
def test_an_example_in_mm_and_degrees_gives_the_si_results_converted(deck: Path, tmp_path: Path) -> None:
    labels = mechfem.check_deck(deck).model.labels
    assert labels is not None
    mm = tmp_path / deck.name
    mm.write_text(in_mm_and_degrees(deck.read_text(), labels, deck.parent, tmp_path))
    # A limit position on the way stops both runs alike; the positions up to it are compared.
    with pytest.MonkeyPatch.context() as mp:
        mp.setattr("warnings.showwarning", lambda *a, **k: None)
        si_run, mm_run = mechfem.run_deck(deck), mechfem.run_deck(mm)
    assert mm_run.positions == si_run.positions
    mm_labels = mm_run.model.labels
    assert mm_labels is not None
    # The limit positions located on the way: the same, their inputs and co-ordinates converted.
    assert [(lim.kind, lim.after) for lim in mm_run.report.limits] == [(k.kind, k.after) for k in si_run.report.limits]
    for a, b in zip(si_run.report.limits, mm_run.report.limits, strict=True):
        inputs = [v * factor(mm_labels.input(j + 1)[5]) for j, v in enumerate(a.inputs)]
        coords = [v * factor(mm_labels.coordinate(i + 1)[3]) for i, v in enumerate(a.coords)]
        np.testing.assert_allclose(b.inputs, inputs, rtol=1e-7, atol=1e-7)
        np.testing.assert_allclose(b.coords, coords, rtol=1e-7, atol=1e-6)
    for b in si_run.buffers:
        want = np.asarray(si_run.buffers[b]) * factor(mm_labels.buffer(b)[3])
        scale = max(1.0, float(np.nanmax(np.abs(want)))) if np.isfinite(want).any() else 1.0
        np.testing.assert_allclose(mm_run.buffers[b], want, rtol=1e-8, atol=1e-9 * scale, err_msg=f"buffer {b}")
    for i in range(si_run.coords.shape[1]):
        want = si_run.coords[:, i] * factor(mm_labels.coordinate(i + 1)[3])
        scale = max(1.0, float(np.max(np.abs(want))))
        np.testing.assert_allclose(mm_run.coords[:, i], want, rtol=1e-8, atol=1e-9 * scale, err_msg=f"x{i + 1}")
    want = si_run.det * factor(mm_labels.det()[3])
    np.testing.assert_allclose(mm_run.det, want, rtol=1e-7, atol=1e-9 * float(np.nanmax(np.abs(want))))
