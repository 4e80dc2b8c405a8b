"""The STORAGE block of a :class:`~mechfem.Mechanism` with names: buffers and pictures."""

from __future__ import annotations

import warnings
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, TypeAlias, Union

from mechfem._util.checks import name_problem
from mechfem.errors import user_stacklevel
from mechfem.model.echo import BUFFER_ARGS

if TYPE_CHECKING:
    from collections.abc import Callable, Mapping

    import mechfem._core as _core
    from mechfem.model.parts import Coordinate, FormParameter, Point, Row

Ref: TypeAlias = Union[int, str, "Coordinate", "Point", "FormParameter", "Row"]
"""Something a buffer or plot refers to: a deck number, a name, or the object itself."""


@dataclass
class Picture:
    """One picture (BEGINPIC ... ENDPIC): plots ``(keyword, a, b)``; PLOTHODO takes a point or two co-ordinates."""

    title: str = ""
    plots: list[tuple[str, Ref, Ref]] = field(default_factory=list)


@dataclass
class Storage:
    """The STORAGE block: buffers (one value per position), and what to do with them.

    Buffers are ``(number, keyword, args)``; an argument is a name, an object of the model or a deck
    number (see :data:`BUFFER_ARGS`). ``printbuf`` None writes no table, an empty list all buffers.
    """

    buffers: list[tuple[int, str, tuple[Ref, ...]]] = field(default_factory=list)
    printbuf: list[int] | None = None
    savedata: list[int] = field(default_factory=list)
    animate: str | None = None
    pictures: list[Picture] = field(default_factory=list)

    def buffer(self, number: int, keyword: str, *args: Ref) -> Storage:
        """Adds buffer ``number`` holding ``keyword args`` (e.g. ``101, "BUFKE1", "delta", "alpha"``)."""
        kw = keyword.upper()
        if kw not in BUFFER_ARGS:
            raise ValueError(f"unknown buffer keyword {keyword!r}; one of {', '.join(BUFFER_ARGS)}")
        wanted = BUFFER_ARGS[kw]
        if not (len(wanted) == len(args) or (wanted.endswith("m") and len(args) == len(wanted) - 1)):
            raise ValueError(f"{kw} takes {len(wanted)} argument(s) ({' '.join(wanted)}), got {len(args)}")
        if number in (b[0] for b in self.buffers):
            raise ValueError(f"buffer {number} is defined twice")
        self.buffers.append((int(number), kw, tuple(args)))
        return self

    def picture(self, title: str = "", *plots: tuple[str, Ref] | tuple[str, Ref, Ref]) -> Storage:
        """Adds a picture; a plot is ``("PLOTFUNC", bx, by)``, ``("PLOTCURV", bx, by)`` or ``("PLOTHODO", point)``."""
        out: list[tuple[str, Ref, Ref]] = []
        for p in plots:
            kw = p[0].upper()
            if kw == "PLOTHODO" and len(p) == 2:
                pt = p[1]
                out.append((kw, pt, pt))
            elif len(p) == 3 and kw in ("PLOTFUNC", "PLOTCURV", "PLOTHODO"):
                out.append((kw, p[1], p[2]))
            else:
                raise ValueError(f"not a plot: {p!r}")
        if not out:
            raise ValueError(f"picture {title!r} has no plots: give at least one, e.g. ('PLOTFUNC', bx, by)")
        self.pictures.append(Picture(title, out))
        return self


def from_described(s: _core.EchoStorage, name: Callable[[str, int], Ref]) -> tuple[Storage | None, list[int]]:
    """The storage of a deck the reader described (None without one); ``name(kind, number)`` names a deck number of
    a kind of :data:`BUFFER_ARGS` (``i`` co-ordinate, ``r`` row, ``j`` input). Beside it, the buffers of the deck's
    TOLERANCE bands (BUFTOL), which a mechanism does not carry (:func:`mechfem.tolerance_bands` computes them): they
    are left out, and so is every place the storage shows them (PRINTBUF, SAVEDATA, a picture's plot)."""
    bands = sorted({b.number for b in s.buffers if b.keyword == "BUFTOL"})
    if not (s.buffers or s.printbuf is not None or s.savedata or s.animate or s.pictures):
        return None, bands
    buffers: list[tuple[int, str, tuple[Ref, ...]]] = []
    for b in s.buffers:
        if b.part or b.keyword == "BUFTOL":
            # The y (and moment) of a BUFPIN or BUFSHAKE line: its first buffer stands for the line. A band.
            continue
        kinds = BUFFER_ARGS[b.keyword]
        buffers.append((b.number, b.keyword, tuple(name(k, v) for k, v in zip(kinds, b.args, strict=False))))
    left_out = set(bands)
    pictures = []
    for p in s.pictures:
        plots: list[tuple[str, Ref, Ref]] = []
        for q in p.plots:
            if q.keyword == "PLOTHODO":
                plots.append((q.keyword, name("i", q.a), name("i", q.b)))
            elif q.a not in left_out and q.b not in left_out:
                plots.append((q.keyword, q.a, q.b))
        if plots:
            pictures.append(Picture(p.title, plots))
    printbuf = None if s.printbuf is None else [b for b in s.printbuf if b not in left_out]
    if printbuf == [b.number for b in s.buffers if b.number not in left_out]:
        printbuf = []  # every buffer: the PRINTBUF without numbers
    savedata = [b for b in s.savedata if b not in left_out]
    return Storage(buffers, printbuf, savedata, s.animate, pictures), bands


def warn_bands_left_out(deck: str, bands: list[int]) -> None:
    """Warns that the mechanism read from ``deck`` leaves out its TOLERANCE bands ``bands`` (see
    :func:`from_described`); nothing without any."""
    if bands:
        warnings.warn(
            f"{deck}: the TOLERANCE block is left out of the mechanism read from the deck, and with it the buffers "
            f"of its bands ({', '.join(map(str, bands))}) wherever the deck shows them: compute the bands of a "
            "mechanism with mechfem.tolerance_bands, or run the deck itself",
            UserWarning,
            stacklevel=user_stacklevel(),
        )


def check_file_names(mechanism: str, storage: Storage | None, tables: Mapping[str, str]) -> None:
    """Refuses an output name (ANIMATE) or a table file name that is not a plain file name: a run writes into its
    output folder only, and :meth:`Mechanism.save_deck` writes the tables beside the deck only."""
    check_animate_name(mechanism, storage)
    check_table_names(mechanism, tables)


def _file_name_problem(name: str) -> str | None:
    if any(c.isspace() for c in name.strip()):
        return "holds a blank, which a deck cannot write"
    return name_problem(name)


def check_animate_name(mechanism: str, storage: Storage | None) -> None:
    """Refuses an ANIMATE name that is not a plain file name (see :func:`check_file_names`)."""
    if storage is not None and storage.animate is not None:
        problem = _file_name_problem(storage.animate)
        if problem is not None:
            raise ValueError(
                f"the storage of mechanism {mechanism!r}: the ANIMATE name {storage.animate!r} {problem}; give a "
                "plain file name such as 'film' (the animation is written as film.gif into the output folder only)"
            )


def check_table_names(mechanism: str, tables: Mapping[str, str]) -> None:
    """Refuses a table file name that is not a plain file name (see :func:`check_file_names`)."""
    for file in tables:
        problem = _file_name_problem(file)
        if problem is not None:
            raise ValueError(
                f"mechanism {mechanism!r}: the table file name {file!r} {problem}; give a plain file name such as "
                "'input1.dat' (a table is written beside the deck only)"
            )
