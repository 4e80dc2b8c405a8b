"""The exceptions mechfem raises.

All of them derive from :class:`MechfemError`:

* :class:`DeckError` — the deck has a mistake; ``str(error)`` is the rendered
  diagnostic (file, line, the line's text, a caret and a hint), and the
  attributes ``path`` and ``line`` say where (``line`` is 0 when the mistake
  concerns the file as a whole).
* :class:`AssemblyError` — the model cannot be evaluated at the given
  co-ordinates (for example two points of a binary coincide).
* :class:`ConvergenceError` — position 1 cannot be reached by Newton iteration.
* :class:`LimitPositionError` — D^c is singular at position 1.
* :class:`ResourceError` — the results would take more memory than the limit
  (:mod:`mechfem.limits`); the run was refused before it started.

A motion that stops after position 1 is not an error: the run returns what
it computed and says why it stopped (:attr:`mechfem.RunReport.stop`), and
warns with :class:`IncompleteRunWarning` so that a script notices.

Ctrl-C during a run raises :class:`RunInterrupted`, a ``KeyboardInterrupt``
that carries the positions computed before it in ``result``, so a script
still stops while the command line writes them.
"""

from __future__ import annotations

import warnings
from typing import Generic, TypeVar

from mechfem._core import AssemblyError, ConvergenceError, DeckError, LimitPositionError, MechfemError, ResourceError

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


def warn_incomplete(reason: str | None, stacklevel: int = 3) -> None:
    """Warns with :class:`IncompleteRunWarning` when ``reason`` (a run's stop reason) is not None; ``stacklevel``
    counts from the caller of this function, as :func:`warnings.warn` does."""
    if reason is not None:
        warnings.warn(f"the motion stopped early: {reason}", IncompleteRunWarning, stacklevel=stacklevel)


__all__ = [
    "AssemblyError",
    "ConvergenceError",
    "DeckError",
    "IncompleteRunWarning",
    "LimitPositionError",
    "MechfemError",
    "ResourceError",
    "RunInterrupted",
]
