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

A motion that stops after position 1 is not an error: the run returns what
it computed and says why it stopped (:attr:`mechfem.RunReport.stop`).
"""

from mechfem._core import AssemblyError, ConvergenceError, DeckError, LimitPositionError, MechfemError

__all__ = ["AssemblyError", "ConvergenceError", "DeckError", "LimitPositionError", "MechfemError"]
