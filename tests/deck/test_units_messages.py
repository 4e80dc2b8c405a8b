"""A deck with UNITS is told about its own numbers in its own units: the messages of the compiled deck (a design
variable that starts outside its range, a length that is not positive, a motion too fast to hold) quote the numbers
as the deck writes them, not as the core computes with them (metres, radians)."""

from __future__ import annotations

from pathlib import Path

import pytest

import mechfem
from deck.test_names_units import fourbar_mm_deg


def deck_error(tmp_path: Path, text: str) -> str:
    deck = tmp_path / "deck.mec"
    deck.write_text(text)
    with pytest.raises(mechfem.DeckError) as e:
        mechfem.check_deck(deck)
    return str(e.value)


def test_a_length_that_is_not_positive_is_quoted_in_millimetres(tmp_path: Path) -> None:
    text = fourbar_mm_deg().replace("PARA 1 1000.0", "PARA 1 -250.0")
    assert "PARA 1 -250.0" in text
    assert "as -250, but a length must be greater than zero" in deck_error(tmp_path, text)


def test_a_design_variable_outside_its_range_is_quoted_in_degrees(tmp_path: Path) -> None:
    # The crank angle phi (row 6) starts at 0 deg; a range of 10 to 20 deg does not hold it.
    block = "OPTIMISE\nVARY 6 10 20\nBUFE0 -1 100\nBUFKE1 -1 1 101\nTARGETEXT 101 100 0.0\n\nSTORAGE"
    text = fourbar_mm_deg().replace("STORAGE", block, 1).replace("KIN ANA", "KIN OPT", 1)
    message = deck_error(tmp_path, text)
    assert "row 6 starts at 0 (its PARA), outside its range [10, 20]" in message


def test_a_motion_too_fast_to_hold_is_quoted_in_degrees_and_seconds(tmp_path: Path) -> None:
    # A change of 1e308 deg is 1.7e306 rad: over 1e-5 s, a speed beyond every double.
    text = fourbar_mm_deg().replace("TSTEPE 144 0.01", "TSTEPE 1 1e-5").replace("MOV_RELE 1 720.0", "MOV_RELE 1 1e308")
    message = deck_error(tmp_path, text)
    assert "to change by 1e308 in a time of 1e-5" in message


def test_a_fault_of_the_dynamics_names_the_point_mass_by_its_point(tmp_path: Path) -> None:
    source = (Path(__file__).parents[1] / "decks" / "dynamics_overflow.mec").read_text()
    deck = tmp_path / "overflow.mec"
    deck.write_text(source.replace("DYNAMICS\n", "NAMES\nPOINT 3 4 S\n\nDYNAMICS\n", 1))
    with pytest.warns(mechfem.IncompleteRunWarning):
        result = mechfem.run_deck(deck)
    reason = result.report.stop_reason() or ""
    assert "the PMASS at point S (co-ordinates 3, 4) given at line" in reason
