"""Files written completely or not at all.

Every output file is written under a temporary name beside its final one and renamed when it is complete, so
a reader (or a run stopped half-way) never sees half a file. The temporary file is created like any other
file (the umask applies), under a name no other writer uses, and never through a link (``x`` mode); the
rename replaces whatever is at the final name, a symbolic link included, so a link already in the output
folder is not followed out of it.
"""

from __future__ import annotations

import os
import secrets
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import BinaryIO, TextIO


def temporary(path: Path) -> Path:
    """A temporary name beside ``path``, new at each call and of the same length for one process: a dot, the stem,
    the process id, eight random hex digits, ``.tmp`` and the suffix (the same, so writers that go by the suffix
    pick the format)."""
    return path.with_name(f".{path.stem}.{os.getpid()}.{secrets.token_hex(4)}.tmp{path.suffix}")


@contextmanager
def atomic_path(path: Path) -> Iterator[Path]:
    """A temporary name beside ``path`` (:func:`temporary`) to write to; renamed to ``path`` when the block
    succeeds, removed when it fails."""
    tmp = temporary(path)
    try:
        yield tmp
        os.replace(tmp, path)
    except BaseException:
        tmp.unlink(missing_ok=True)
        raise


@contextmanager
def atomic_text(path: Path) -> Iterator[TextIO]:
    """``path`` opened for writing UTF-8 text with ``\\n`` line ends, as :func:`atomic_path` writes it."""
    with atomic_path(path) as tmp, open(tmp, "x", encoding="utf-8", newline="\n") as f:
        yield f


@contextmanager
def atomic_binary(path: Path) -> Iterator[BinaryIO]:
    """``path`` opened for writing bytes, as :func:`atomic_path` writes it."""
    with atomic_path(path) as tmp, open(tmp, "xb") as f:
        yield f
