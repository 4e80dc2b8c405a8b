"""Runs a :class:`~mechfem.Mechanism`: writes its deck, runs it (a kept compiled model when it can) and gives the
result as an :class:`~mechfem.Analysis`, its errors in the model's words.

:meth:`Mechanism.run <mechfem.Mechanism.run>` and :meth:`Mechanism.check <mechfem.Mechanism.check>` sit in the model
layer, below the run: this module fills their hook (:mod:`mechfem.hooks`) when it is imported.
"""

from __future__ import annotations

import mechfem._core as _core
from mechfem import deckio
from mechfem import model as _model
from mechfem.analysis import Analysis
from mechfem.deckio import Progress
from mechfem.errors import AssemblyError, MechfemError, RunInterrupted
from mechfem.explain import translate
from mechfem.limits import memory_limit
from mechfem.model import Mechanism
from mechfem.motion import Motion
from mechfem.storage import Storage


@_model.RUN.register
def run(
    mech: Mechanism,
    motion: Motion | None,
    storage: Storage | None,
    progress: Progress = None,
    with_motion: bool = True,
    order: int | None = 2,
) -> Analysis:
    """Runs the mechanism through ``motion`` (position 1 only without one, or with ``with_motion=False``),
    computing the transfer functions of ``order`` (see :meth:`Mechanism.run`)."""
    deck = deckio.write(mech, motion, storage)
    callback = deckio.progress_callback(progress, "positions")
    with deckio.tables_dir(deck.tables) as base:
        try:
            moving = with_motion and motion is not None
            if deck.tables:
                # Tables are read from a directory that lives for this call only: no model is kept.
                d = _core.run_deck_text(deck.text, deck.path, base, moving, callback, order, memory_limit())
            else:
                model, changes = deckio.compiled(deck, base)
                try:
                    d = model.run(changes, moving, callback, order, memory_limit())
                except AssemblyError:
                    # The deck reader checks the given numbers (coincident points, a zero length) when it
                    # compiles; a kept model that only takes new numbers meets them in the core instead. The
                    # text path names the same mistake as the deck reader does, whatever was compiled before.
                    d = _core.run_deck_text(deck.text, deck.path, base, moving, callback, order, memory_limit())
        except MechfemError as e:
            raise translate(e, deck, mech.name) from None
        finally:
            close = getattr(callback, "close", None)
            if close is not None:
                close()
    analysis = Analysis(mech, deck.numbering, d, path=deck.path)
    analysis.motion = motion if with_motion else None
    if d["interrupted"]:
        raise RunInterrupted(analysis)
    return analysis


__all__ = ["run"]
