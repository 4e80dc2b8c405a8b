"""The example decks without their NAMES block and UNITS line, for the tests of what a deck that names nothing says
(``x9``, ``ANGB(8)``, ``dANGB(8)/dinput1``) and of decks given names and units of their own: a copy of examples/ in a
temporary folder, made once per test session, table files included."""

from __future__ import annotations

import shutil
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

#: The keywords that end a NAMES block.
_BLOCKS = ("DYNAMICS", "MOVEMENT", "OPTIMISE", "STORAGE", "END")


def unnamed(text: str) -> str:
    """Deck text without its NAMES block and its UNITS line."""
    kept, skipping = [], False
    for line in text.splitlines():
        word = (line.split(";")[0].split() or [""])[0].upper()
        skipping = (skipping or word == "NAMES") and word not in _BLOCKS
        if not skipping and word != "UNITS":
            kept.append(line)
    return "\n".join(kept) + "\n"


def _copy() -> Path:
    out = Path(tempfile.mkdtemp(prefix="mechfem-bare-examples-"))
    for path in (ROOT / "examples").rglob("*"):
        target = out / path.relative_to(ROOT / "examples")
        if path.is_dir():
            target.mkdir(parents=True, exist_ok=True)
        elif path.suffix == ".mec":
            target.parent.mkdir(parents=True, exist_ok=True)
            target.write_text(unnamed(path.read_text()))
        else:
            target.parent.mkdir(parents=True, exist_ok=True)
            shutil.copyfile(path, target)
    return out


BARE_EXAMPLES = _copy()
"""The copy of examples/ (decks without NAMES and UNITS)."""


def bare(path: Path) -> Path:
    """The bare copy of the example deck ``path``."""
    return BARE_EXAMPLES / path.resolve().relative_to(ROOT / "examples")
