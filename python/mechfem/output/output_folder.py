"""The output folder of a command, checked before the run starts: the files the command will write, none of them
an input of the run and each under a name the file system takes, and a lock on the deck's outputs in the folder.

* :func:`plan` lists a command's inputs (the deck and the tables it names) and every file it may write, from the
  deck's text alone (:func:`mechfem._core.deck_files`: nothing is compiled and no table read).
* :meth:`OutputPlan.check` refuses, with :class:`OutputConflict`, an output that would replace an input (the same path,
  or the same file through a symbolic or hard link: ``deck.prt`` run without ``-o``, a table named ``<stem>.csv``)
  and an output name longer than the folder takes, its temporary name (:func:`mechfem._util.atomic.temporary`)
  included, so that no run writes some of its files and then fails on the next.
* :func:`locked` holds an advisory lock (``flock``) on ``.<stem>.lock`` in the output folder while a command
  runs and writes: a second run that would write the outputs of the same stem into the same folder (the same deck,
  or another deck of the same name) is refused at once instead of mixing its files with the first's. The lock
  file is removed when the command ends; one left by a run that was killed outright is harmless and is taken over
  and removed by the next run.
"""

from __future__ import annotations

import os
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path

import mechfem._core as _core
from mechfem._util.atomic import temporary
from mechfem.errors import MechfemError

try:
    import fcntl
except ImportError:  # not on Windows: no lock is taken there
    fcntl = None  # type: ignore[assignment]

#: The longest file name when the file system does not say: 255 bytes, the limit of every common one.
NAME_MAX = 255


class OutputConflict(MechfemError):
    """An output of a command would replace one of its inputs, cannot be named in its folder, or is being written
    by another run."""


@dataclass(frozen=True)
class OutputPlan:
    """A command's inputs and the files it may write, each with what it is (``print file``, ``the deck``)."""

    deck: Path
    outdir: Path
    inputs: list[tuple[Path, str]]
    outputs: list[tuple[Path, str]]

    def check(self) -> None:
        """Raises :class:`OutputConflict` for an output name too long for the folder, or an output that would
        replace an input."""
        longest = name_max(self.outdir)
        names = [(path, what, len(os.fsencode(temporary(path).name))) for path, what in self.outputs]
        lock = lock_file(self.outdir, self.deck.stem)
        for path, what, size in [*names, (lock, "lock file", len(os.fsencode(lock.name)))]:
            if size > longest:
                raise OutputConflict(
                    f"the {what} {path.name} would need a file name of {size} bytes (written under a temporary "
                    f"name first), more than the {longest} bytes a file name may have in {self.outdir}; nothing has "
                    f"been written. Give the {'ANIMATE name' if what == 'animation' else 'deck'} a shorter name."
                )
        for out, what in self.outputs:
            for source, kind in self.inputs:
                if replaces(out, source):
                    raise OutputConflict(
                        f"the {what} {out} would replace {source}, {kind}; an output never replaces an input of "
                        "its run, and nothing has been written. Write the outputs into another folder with "
                        "-o OUTDIR, or rename the file."
                    )


def plan(
    deck: Path,
    outdir: Path,
    *,
    data_format: str | None = "csv",
    media: bool = True,
    report: bool = False,
    drawings: list[str] | None = None,
) -> OutputPlan:
    """The inputs and outputs of a command on ``deck`` writing into ``outdir``: ``mechfem run`` (``data_format``
    of the data set, ``media`` for the pictures and the animation, ``report`` for the HTML report), ``mechfem
    report`` (``data_format`` None, ``media`` False, ``report`` True) or ``mechfem draw`` (``drawings``: the
    files' names, no print file). Raises the deck's :class:`~mechfem.DeckError` when its text cannot be read."""
    files = _core.deck_files(deck)
    folder = deck.parent
    inputs = [
        (deck, "the deck itself"),
        *((folder / name, f"the table file `{name}` the deck names") for name in files.tables),
    ]
    stem = deck.stem
    outputs: list[tuple[Path, str]] = []
    if drawings is not None:
        outputs += [(outdir / name, "drawing") for name in drawings]
        return OutputPlan(deck, outdir, inputs, outputs)
    if data_format is not None:
        outputs.append((outdir / f"{stem}.prt", "print file"))
        if files.savedata:
            outputs += [(outdir / f"{stem}.{data_format}", "data set"), (outdir / f"{stem}.notes.txt", "notes")]
        if files.mode == "KIN OPT":
            outputs.append((outdir / f"{stem}_opt.mec", "deck of the final design"))
    if media:
        for k in range(1, files.pictures + 1):
            outputs += [(outdir / f"{stem}_pic{k}.png", "picture"), (outdir / f"{stem}_pic{k}.svg", "picture")]
        if files.animate:
            outputs += [(outdir / f"{files.animate}.{ext}", "animation") for ext in ("gif", "mp4")]
    if report:
        outputs.append((outdir / f"{stem}.html", "report"))
    return OutputPlan(deck, outdir, inputs, outputs)


def replaces(out: Path, source: Path) -> bool:
    """Whether writing ``out`` (renamed into place) would replace ``source``: the same name in the same folder
    (folders compared with their links resolved), or the same file through a link (a symbolic link is followed,
    a hard link is the same file)."""
    # A broken link, an input that does not exist or a name with a NUL byte: the deck reader says what is wrong.
    try:
        if not os.path.lexists(out):
            return False
        if out.name == source.name and os.path.realpath(out.parent) == os.path.realpath(source.parent):
            return True
        return os.path.samefile(out, source)
    except (OSError, ValueError):
        return False


def name_max(folder: Path) -> int:
    """The longest file name (bytes) in ``folder``, or in its nearest existing parent while it is to be made."""
    here = folder.absolute()
    while not here.exists() and here != here.parent:
        here = here.parent
    try:
        return int(os.pathconf(here, "PC_NAME_MAX"))
    except (OSError, ValueError, AttributeError):
        return NAME_MAX


def lock_file(outdir: Path, stem: str) -> Path:
    """The lock file of the outputs of ``stem`` in ``outdir``."""
    return outdir / f".{stem}.lock"


@contextmanager
def locked(outdir: Path, stem: str) -> Iterator[None]:
    """Holds the lock on the outputs of ``stem`` in ``outdir`` (made if needed) for the block; raises
    :class:`OutputConflict` at once when another run holds it."""
    if fcntl is None:
        yield
        return
    # The folders made here are removed again when nothing was written into them (a run refused by its deck).
    made = [folder for folder in [outdir, *outdir.parents] if not folder.exists()]
    outdir.mkdir(parents=True, exist_ok=True)
    path = lock_file(outdir, stem)
    while True:
        fd = os.open(path, os.O_RDWR | os.O_CREAT | os.O_CLOEXEC | os.O_NOFOLLOW, 0o644)
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            os.close(fd)
            raise OutputConflict(
                f"another mechfem run is writing the outputs of `{stem}` into {outdir} (it holds {path.name} "
                "there); this run is refused so that the folder does not end with files of both. Wait for the "
                "other run to end, or write into another folder with -o OUTDIR."
            ) from None
        # The run that held the lock removes the file as it ends: the file locked must still be the one there.
        try:
            there = os.stat(path, follow_symlinks=False)
        except FileNotFoundError:
            there = None
        mine = os.fstat(fd)
        if there is not None and (there.st_dev, there.st_ino) == (mine.st_dev, mine.st_ino):
            break
        os.close(fd)
    try:
        yield
    finally:
        # Removed while still locked, so that no other run locks a file that is no longer there.
        path.unlink(missing_ok=True)
        os.close(fd)
        for folder in made:
            try:
                folder.rmdir()
            except OSError:  # not empty: the run wrote into it
                break
