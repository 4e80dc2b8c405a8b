"""A deck's OPTIMISE block kept through the studio: a ``KIN OPT`` (or ``DYN ANA``) deck opened in the studio is
saved with its OPTIMISE block, so that ``mechfem run`` of the saved deck optimises from the edited design.

The studio edits the deck's :class:`~mechfem.Mechanism`, which holds no OPTIMISE block; the saved deck is written
from the mechanism (:meth:`Mechanism.to_deck`, the deck's own numbering of co-ordinates, rows and elements) and the
block is put back as the deck had it, before STORAGE, with the deck's mode line. The buffers the block defines (the
quantities its targets compare) are read into the mechanism's storage and written there by the mechanism: they are
left out of the written STORAGE, where the block defines them again. The files its TARGET lines read go beside the
saved deck."""

from __future__ import annotations

import os
from pathlib import Path

from mechfem.design.optimise_deck import deck_mode

#: The words that open a block of a deck (and END, which closes the deck).
HEADERS = ("TOPOLOGY", "GEOMETRY", "NAMES", "DYNAMICS", "MOVEMENT", "OPTIMISE", "STORAGE", "TOLERANCE", "END")


def _words(line: str) -> list[str]:
    return line.split(";", 1)[0].split()


def optimise_block(text: str) -> list[str] | None:
    """The lines of ``text``'s OPTIMISE block, its header line first (None: the deck has none)."""
    lines = text.lstrip("\ufeff").splitlines()
    start = next((k for k, line in enumerate(lines) if [w.upper() for w in _words(line)[:1]] == ["OPTIMISE"]), None)
    if start is None:
        return None
    end = next(
        (k for k in range(start + 1, len(lines)) if (_words(lines[k])[:1] or [""])[0].upper() in HEADERS), len(lines)
    )
    return lines[start:end]


def _statements(block: list[str]) -> list[list[str]]:
    """The block's statements, each with its keyword (a line that starts with a number continues the keyword
    above)."""
    out: list[list[str]] = []
    keyword = ""
    for line in block[1:]:
        words = _words(line)
        if not words:
            continue
        if words[0][0].isalpha():
            keyword = words[0].upper()
            out.append([keyword, *words[1:]])
        elif keyword:
            out.append([keyword, *words])
    return out


def target_files(block: list[str]) -> list[str]:
    """The files the block's TARGET lines read (relative to the deck's folder)."""
    return [words[2] for words in _statements(block) if words[0] == "TARGET" and len(words) >= 3]


def with_block(written: str, original: str, block: list[str]) -> str:
    """The deck ``written`` from the mechanism, with ``original``'s mode line and OPTIMISE ``block`` put back; the
    buffer lines the block defines are left out of the written STORAGE."""
    defined = {" ".join(words) for words in _statements(block) if words[0].startswith("BUF")}
    mode = deck_mode(original)
    out: list[str] = []
    placed = moded = False
    for line in written.splitlines():
        words = [w.upper() for w in _words(line)]
        if not moded and words:
            moded = True
            out.append(mode)
            continue
        if not placed and words[:1] and words[0] in ("STORAGE", "TOLERANCE", "END"):
            out += block
            placed = True
        if " ".join(words) in defined:
            continue
        out.append(line)
    return "\n".join(out) + "\n"


def same_numbering(written: str, original: str, folder: Path) -> bool:
    """Whether the two decks number their elements, co-ordinates and rows alike (the block refers to them by
    number); ``folder``: where the original deck's files are (its TARGET files)."""
    from mechfem import _core

    def numbering(text: str) -> tuple[object, ...]:
        d = _core.describe_deck_text(text, "deck.mec", os.fspath(folder))
        return (
            [(e.number, e.type, list(e.coords)) for e in d.elements],
            [(c.number, c.moving) for c in d.coordinates],
            [(r.dest, [(t.element, t.form) for t in r.terms]) for r in d.prescribed],
        )

    return numbering(written) == numbering(original)


def copy_targets(block: list[str], source: Path, target: Path) -> list[Path]:
    """Copies the files of the block's TARGET lines from the folder ``source`` to ``target`` (the saved deck's);
    refuses to replace a different file of the same name there."""
    written = []
    for name in target_files(block):
        src, dst = source / name, target / name
        if src.resolve() == dst.resolve():
            continue
        data = src.read_bytes()
        if dst.exists() and dst.read_bytes() != data:
            raise ValueError(
                f"the deck's OPTIMISE block reads {name}, and {target} has a different {name}: save the deck in "
                "another folder (or beside the deck it came from)"
            )
        dst.parent.mkdir(parents=True, exist_ok=True)
        dst.write_bytes(data)
        written.append(dst)
    return written


__all__ = ["copy_targets", "optimise_block", "same_numbering", "target_files", "with_block"]
