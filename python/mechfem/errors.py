"""The exceptions mechfem raises.

All of them derive from :class:`MechfemError`:

* :class:`DeckError` — the deck has a mistake; ``str(error)`` is the rendered
  diagnostic (file, line, the line's text, a caret and a hint), and the
  attributes ``path``, ``line`` and ``column`` say where (``line`` is 0 when the
  mistake concerns the file as a whole); ``kind`` is a stable code of the
  mistake (``coordinate_unused``), ``text``, ``message`` and ``hint`` the
  line, what is wrong and how to fix it, ``element`` and ``coordinate`` what it
  is about (deck numbers, or None), ``diagnostics`` every mistake's fields.
* :class:`AssemblyError` — the model cannot be evaluated at the given
  co-ordinates (for example two points of a binary coincide).
* :class:`ConvergenceError` — position 1 cannot be reached by Newton iteration.
* :class:`LimitPositionError` — D^c is singular at position 1.
* the errors of position 1 carry ``parts``: the core's message in pieces, the
  things it names (elements, co-ordinates, rows, deck terms) as structure
  (:data:`mechfem.results.words.Part`), which the Python API words with the model's
  names;
* :class:`ResourceError` — the results would take more memory than the limit
  (:mod:`mechfem._util.limits`); the run was refused before it started.

A motion that stops after position 1 is not an error: the run returns what
it computed and says why it stopped (:attr:`mechfem.RunReport.stop`), and
warns with :class:`IncompleteRunWarning` so that a script notices; with
``raise_on_stop=True`` it raises :class:`RunStoppedError` instead, which
carries the positions computed in ``result``.

A number that looks like the wrong unit warns with :class:`UnitWarning`, one class for the deck reader's
warnings and the Python API's: an angle of 720 where angles are radians (a deck's PARA, co-ordinate, motion,
VARY range, target, bound or STOPWHEN value; a ``Mechanism``'s input start value or a motion of more than 100 rad
given without a unit), or 6.2832 where they are degrees.

Ctrl-C during a run raises :class:`RunInterrupted`, a ``KeyboardInterrupt``
that carries the positions computed before it in ``result``, so a script
still stops while the command line writes them.
"""

from __future__ import annotations

import os
import sys
import warnings
from typing import Generic, TypeVar

from mechfem._core import (
    AssemblyError,
    ConvergenceError,
    DeckError,
    LimitPositionError,
    MechfemError,
    ResourceError,
    UnitWarning,
)

R = TypeVar("R")


class RunInterrupted(KeyboardInterrupt, Generic[R]):
    """Ctrl-C stopped a run: ``result`` holds every position computed before it (its report's ``stop`` says
    where, with kind ``interrupted``, unless the run had just finished)."""

    def __init__(self, result: R) -> None:
        super().__init__("the run was interrupted")
        self.result = result


class IncompleteRunWarning(UserWarning):
    """The motion (or simulation) stopped before its last position: the result holds every position up to there,
    and its ``stop_reason()`` says why (the warning's message says it too)."""


class RunStoppedError(MechfemError, Generic[R]):
    """The motion (or simulation) stopped before its last position, and the run was asked to raise then
    (``raise_on_stop=True``): ``result`` holds every position computed up to the stop, ``reason`` says why and
    where (as the result's ``stop_reason()``)."""

    def __init__(self, reason: str, result: R) -> None:
        super().__init__(reason)
        self.reason = reason
        self.result = result

    def __reduce__(self) -> tuple[object, ...]:
        return (type(self), (self.reason, self.result))


_PACKAGE = os.path.dirname(os.path.abspath(__file__)) + os.sep


def user_stacklevel() -> int:
    """The ``stacklevel`` for :func:`warnings.warn`, called by the caller of this function, that points at the
    first line outside mechfem: the user's call, however deep inside mechfem the warning is given."""
    frame = sys._getframe(1)
    level = 1
    while frame.f_back is not None and frame.f_code.co_filename.startswith(_PACKAGE):
        frame = frame.f_back
        level += 1
    return level


def warn_incomplete(reason: str | None, stacklevel: int | None = None) -> None:
    """Warns with :class:`IncompleteRunWarning` when ``reason`` (a run's stop reason) is not None; ``stacklevel``
    counts from the caller of this function, as :func:`warnings.warn` does (default: the user's line)."""
    if reason is not None:
        level = user_stacklevel() if stacklevel is None else stacklevel
        warnings.warn(f"the motion stopped early: {reason}", IncompleteRunWarning, stacklevel=level)


def on_stop(result: R, reason: str | None, raise_on_stop: bool) -> R:
    """``result`` when its run was complete (``reason`` None); for a run that stopped early, raises
    :class:`RunStoppedError` with ``raise_on_stop``, else warns with :class:`IncompleteRunWarning` and returns it."""
    if reason is not None and raise_on_stop:
        raise RunStoppedError(reason, result)
    if reason is not None:
        warnings.warn(f"the motion stopped early: {reason}", IncompleteRunWarning, stacklevel=user_stacklevel())
    return result


__all__ = [
    "AssemblyError",
    "ConvergenceError",
    "DeckError",
    "IncompleteRunWarning",
    "LimitPositionError",
    "MechfemError",
    "ResourceError",
    "RunInterrupted",
    "RunStoppedError",
    "UnitWarning",
]
