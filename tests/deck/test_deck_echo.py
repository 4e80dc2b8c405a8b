"""A deck file run again unchanged hands Python the model echo and storage it gave before, converted once; an
edited deck, or the same text at another path, gets its own."""

from __future__ import annotations

import shutil
from pathlib import Path

import numpy as np
import pytest

import mechfem

SUPPLY = Path(__file__).resolve().parents[2] / "examples" / "supply" / "supply.mec"


def test_runs_of_one_deck_share_its_model_and_storage(tmp_path: Path) -> None:
    deck = tmp_path / "supply.mec"
    shutil.copy(SUPPLY, deck)
    a, b = mechfem.run_deck(deck), mechfem.run_deck(deck)
    assert a.model is b.model and a.storage is b.storage
    # Nothing to report but the numbers of the run: the same report.
    assert a.report.complete and a.report is b.report
    assert mechfem.check_deck(deck).model is a.model
    np.testing.assert_array_equal(a.coords, b.coords)


def test_an_edited_deck_gets_a_model_of_its_own(tmp_path: Path) -> None:
    deck = tmp_path / "supply.mec"
    shutil.copy(SUPPLY, deck)
    before = mechfem.run_deck(deck)
    text = SUPPLY.read_text()
    deck.write_text(text + "\n")
    after = mechfem.run_deck(deck)
    assert after.model is not before.model
    assert after.model == before.model


def test_the_same_text_at_another_path_is_another_deck(tmp_path: Path) -> None:
    deck = tmp_path / "supply.mec"
    shutil.copy(SUPPLY, deck)
    first = mechfem.run_deck(deck)
    other = tmp_path / "other.mec"
    shutil.copy(SUPPLY, other)
    second = mechfem.run_deck(other)
    assert second.model is not first.model
    assert [c.adjusted for c in second.model.coordinates] == [c.adjusted for c in first.model.coordinates]


def test_a_run_that_stops_gets_a_report_of_its_own() -> None:
    deck = Path(__file__).resolve().parents[1] / "decks" / "rocker.mec"
    with pytest.warns(mechfem.IncompleteRunWarning):
        first, second = mechfem.run_deck(deck), mechfem.run_deck(deck)
    assert not first.report.complete
    assert first.report is not second.report and first.report == second.report
