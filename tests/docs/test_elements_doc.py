"""docs/elements.md: every complete deck in it runs, every element type has its section and a deck
that uses it, and its links lead to files that exist."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

import mechfem
from conftest import ROOT

DOC = ROOT / "docs" / "elements.md"
TYPES = ["BIN", "HLF", "TR1", "TR2", "GR1", "GR2", "RK1", "RK2", "BLT", "CRD"]


def deck_blocks() -> list[str]:
    """The ```deck fenced blocks of the page, in order."""
    return re.findall(r"^```deck\n(.*?)^```", DOC.read_text(), re.S | re.M)


def is_complete(block: str) -> bool:
    """A complete deck: its first line that is not blank or a comment is the mode KIN ANA."""
    for line in block.splitlines():
        text = line.split(";", 1)[0].strip()
        if text:
            return text.split() == ["KIN", "ANA"]
    return False


COMPLETE = [b for b in deck_blocks() if is_complete(b)]


def test_the_page_has_complete_decks() -> None:
    assert len(COMPLETE) >= len(TYPES)


@pytest.mark.parametrize("block", COMPLETE, ids=lambda b: b.splitlines()[1].strip("; ")[:40])
def test_complete_deck_runs(block: str, tmp_path: Path) -> None:
    deck = tmp_path / "doc.mec"
    deck.write_text(block)
    result = mechfem.run_deck(deck)
    assert result.report.complete, result.report.stop_reason()
    assert result.positions == result.report.steps + 1
    assert result.report.warnings == []


@pytest.mark.parametrize("ty", TYPES)
def test_every_element_type_has_a_section_and_a_deck(ty: str) -> None:
    assert re.search(rf"^## {ty}: ", DOC.read_text(), re.M), f"no section for {ty}"
    assert any(re.search(rf"^\s*(?:ELEM\s+)?\d+\s+{ty}\s", b, re.M) for b in COMPLETE), f"no deck uses {ty}"


def test_links_exist() -> None:
    for target in re.findall(r"\]\(([^)#:]+)(?:#[^)]*)?\)", DOC.read_text()):
        assert (DOC.parent / target).exists(), target
