"""Names are unique within their kind (names-units.md): a point and an element, or a co-ordinate and an element,
may share a name, in a deck and in a Python mechanism, and each is still found by its kind."""

from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import mechfem

ROOT = Path(__file__).resolve().parents[2]
FOURBAR = ROOT / "examples" / "fourbar" / "fourbar.mec"


def _shared_deck(tmp_path: Path) -> Path:
    """The four-bar with its rocker element called ``B``, the name of the rocker's moving point."""
    text = FOURBAR.read_text()
    shared = re.sub(r"(?m)^(\s+3 )rocker\b", r"\1B", text, count=1)
    assert shared != text
    deck = tmp_path / "shared.mec"
    deck.write_text(shared)
    return deck


def test_a_deck_whose_point_and_element_share_a_name_runs_as_the_deck_without(tmp_path: Path) -> None:
    deck = _shared_deck(tmp_path)
    out = tmp_path / "out"
    done = subprocess.run(
        [sys.executable, "-m", "mechfem", "run", str(deck), "-o", str(out), "--no-media"],
        capture_output=True,
        text=True,
        check=False,
    )
    assert done.returncode == 0, done.stderr
    assert "internal error" not in done.stderr
    shared = mechfem.run_deck(deck)
    plain = mechfem.run_deck(FOURBAR)
    np.testing.assert_array_equal(shared.x("B"), plain.x("B"))


def test_from_deck_finds_each_part_of_a_shared_name_by_its_kind(tmp_path: Path) -> None:
    m = mechfem.Mechanism.from_deck(_shared_deck(tmp_path))
    point = m.find("B", "point", lambda o: isinstance(o, mechfem.model.mechanism.Point))
    element = m.find("B", "element", lambda o: isinstance(o, mechfem.model.mechanism.Element))
    assert isinstance(point, mechfem.model.mechanism.Point) and isinstance(element, mechfem.model.mechanism.Element)
    again = mechfem.Mechanism.from_deck_text(m.to_deck(), "again", tmp_path)
    assert isinstance(
        again.find("B", "element", lambda o: isinstance(o, mechfem.model.mechanism.Element)),
        mechfem.model.mechanism.Element,
    )


def test_a_python_mechanism_refuses_a_name_twice_within_a_kind_only() -> None:
    m = mechfem.Mechanism("shared")
    a0, a = m.fixed("A0", 0.0, 0.0), m.point("A", 1.0, 0.0)
    m.bar("A", a0, a)
    with pytest.raises(ValueError, match="already used"):
        m.point("A", 2.0, 0.0)
    with pytest.raises(ValueError, match="already used"):
        m.bar("A", a0, a)
