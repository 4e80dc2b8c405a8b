"""A named model is told its mistakes by its names, once: the core words them, from a deck and from Python alike."""

from __future__ import annotations

from pathlib import Path

import pytest

import mechfem
from conftest import ROOT
from mechfem import Mechanism, MechfemError

NAMES = "NAMES\nPOINT 1 2 A0\n      3 4 B0\n      5 6 A\n      7 8 B\nELEM 2 coupler\nROW 3 frame\n"


def named_deck(tmp_path: Path) -> Path:
    deck = tmp_path / "named.mec"
    deck.write_text((ROOT / "tests" / "decks" / "superfluous.mec").read_text() + NAMES)
    return deck


def test_a_named_decks_error_at_position_one_says_its_names_once(tmp_path: Path) -> None:
    with pytest.raises(MechfemError) as caught:
        mechfem.run_deck(named_deck(tmp_path))
    message = str(caught.value)
    assert "row 3 (frame) is superfluous" in message, message
    assert "(frame) (frame)" not in message and "(B.x, B.y) (B.x, B.y)" not in message, message
    # The co-ordinates that can move are said with their names beside their numbers.
    assert "co-ordinates 8, 5, 6, 7 (B.y, A.x, A.y, B.x) can move" in message, message


def test_an_unnamed_decks_error_is_said_in_numbers(tmp_path: Path) -> None:
    with pytest.raises(MechfemError) as caught:
        mechfem.run_deck(ROOT / "tests" / "decks" / "superfluous.mec")
    message = str(caught.value)
    assert "row 3 is superfluous" in message and "(frame)" not in message, message


def test_the_named_deck_through_python_says_the_models_names(tmp_path: Path) -> None:
    m = Mechanism.from_deck(named_deck(tmp_path))
    with pytest.raises(MechfemError) as caught:
        m.run()
    message = str(caught.value)
    assert "'frame'" in message or "frame" in message, message
    assert "co-ordinate 7" not in message and "row 3" not in message, message
