"""docs/errors.md lists every error message with its deck and is up to date."""

from __future__ import annotations

import importlib.util
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def _render() -> str:
    spec = importlib.util.spec_from_file_location("errors_doc", ROOT / "scripts" / "errors_doc.py")
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    text: str = module.render()
    return text


def test_errors_page_is_up_to_date() -> None:
    expected = _render()
    actual = (ROOT / "docs" / "errors.md").read_text()
    assert actual == expected, "docs/errors.md is stale: run .venv/bin/python scripts/errors_doc.py > docs/errors.md"


def test_every_invalid_deck_is_on_the_page() -> None:
    page = (ROOT / "docs" / "errors.md").read_text()
    for deck in (ROOT / "crates/mechfem-deck/tests/decks/invalid").glob("*.mec"):
        assert f"### {deck.stem}\n" in page, deck.name
