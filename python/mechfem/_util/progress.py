"""One progress bar on standard error through every phase of a run, and the messages around it.

A run goes through phases: computing the positions, writing the data set, the print file, the pictures,
the animation and the report. :class:`ProgressBar` is a single tqdm bar whose description names the
phase and whose count starts again at each one, so a long run shows where it is until its last file is
written. It is drawn only when its stream is a terminal (or when asked to with ``show=True``): redirected
or captured output gets no bar.

:class:`Console` is what the command line says: lines on standard output and notes on standard error,
written above the bar without breaking it, and nothing but errors when it is quiet.
"""

from __future__ import annotations

import sys
from typing import Any, TextIO

from tqdm import tqdm

#: From this many units on, counts are shown as 1.00M rather than 1000000.
SCALED_FROM = 100_000


class ProgressBar:
    """A progress bar on ``file`` (default standard error) through the phases of a run.

    ``show`` None draws it only when ``file`` is a terminal (tqdm's ``disable=None``), True always, False
    never. Called as ``bar(done, total)`` it reports the current phase's progress, so it can be handed to
    :func:`mechfem.run_deck` or any ``progress`` argument of the API. It is redrawn at most every
    ``mininterval`` seconds.
    """

    def __init__(self, show: bool | None = None, file: TextIO | None = None, mininterval: float = 0.1) -> None:
        self.file = file if file is not None else sys.stderr
        self.show = show
        self.mininterval = mininterval
        self._bar: tqdm[Any] | None = None

    @property
    def active(self) -> bool:
        """Whether the bar is drawn."""
        if self.show is not None:
            return self.show
        isatty = getattr(self.file, "isatty", None)
        return bool(isatty is not None and isatty())

    def phase(self, name: str, total: int | None = None, unit: str | None = None) -> None:
        """Starts the phase ``name``: ``total`` ``unit`` to do (None when not known), counted from 0. A phase
        without a unit is one step (writing one file): the bar shows its name alone."""
        if not self.active:
            return
        fmt = _format(total, unit)
        # tqdm puts the unit straight after the count (``10B``): a word needs a space before it.
        unit = f" {unit or 'steps'}"
        bar = self._bar
        if bar is None:
            self._bar = tqdm(
                total=total,
                desc=name,
                unit=unit,
                unit_scale=_scaled(total),
                bar_format=fmt,
                file=self.file,
                leave=False,
                dynamic_ncols=True,
                mininterval=self.mininterval,
                # Every update is checked against mininterval alone: updates come seldom (every 1 % of the
                # positions, a block of rows, a frame), and the last one of a phase must show.
                miniters=1,
                disable=False,
            )
            return
        bar.unit = unit
        bar.unit_scale = _scaled(total)
        bar.bar_format = fmt
        bar.set_description_str(name, refresh=False)
        # reset() keeps the old total when given None: an open-ended phase sets it itself.
        bar.total = total
        bar.reset(total)

    def __call__(self, done: int, total: int) -> None:
        """``done`` of ``total`` units of the current phase are done."""
        bar = self._bar
        if bar is None:
            return
        if bar.total == total:
            bar.update(done - bar.n)
            return
        # The first report of a phase whose total was not known: show the total at once.
        bar.total = total
        bar.unit_scale = _scaled(total)
        bar.bar_format = _format(total, bar.unit)
        bar.n = done
        bar.refresh()

    def advance(self, n: int = 1) -> None:
        """``n`` more units of the current phase are done."""
        if self._bar is not None:
            self._bar.update(n)

    def write(self, line: str, file: TextIO | None = None) -> None:
        """Writes ``line`` to ``file`` (default standard output) above the bar, which is drawn again below it."""
        out = file if file is not None else sys.stdout
        if self._bar is None:
            print(line, file=out, flush=True)
        else:
            tqdm.write(line, file=out)
            out.flush()

    def close(self) -> None:
        """Clears the bar from the terminal."""
        if self._bar is not None:
            self._bar.close()
            self._bar = None


def _scaled(total: int | None) -> bool:
    return total is not None and total >= SCALED_FROM


def _format(total: int | None, unit: str | None) -> str:
    """tqdm's bar_format for a phase: the bar, the count and the time taken and left when the total is known (no
    rate: tqdm shows a slow one as ``9.10s/ pictures``), the count and the time taken when only the unit is, the
    name alone for a single step."""
    if total is not None:
        return "{l_bar}{bar}| {n_fmt}/{total_fmt}{unit} [{elapsed}<{remaining}]"
    return "{desc}: {n_fmt}{unit} [{elapsed}]" if unit else "{desc}"


class Console:
    """What the command says around its progress ``bar``: nothing but errors when ``quiet``."""

    def __init__(self, bar: ProgressBar, quiet: bool = False) -> None:
        self.bar = bar
        self.quiet = quiet

    def say(self, line: str) -> None:
        """A line of the command's output (standard output)."""
        if not self.quiet:
            self.bar.write(line, sys.stdout)

    def note(self, line: str) -> None:
        """A note or warning on standard error."""
        if not self.quiet:
            self.bar.write(line, sys.stderr)

    def error(self, line: str) -> None:
        """An error on standard error, said even when quiet."""
        self.bar.write(line, sys.stderr)

    def close(self) -> None:
        self.bar.close()
