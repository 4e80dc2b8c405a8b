"""Runs a :class:`~mechfem.Mechanism` and gives the result as a :class:`~mechfem.RunResult`, its errors in the
model's words.

A mechanism runs on its kept compiled model (:mod:`mechfem.compiled`), built through the typed builder
(:mod:`mechfem.building`) when its topology is new, and one with table motions or load tables is built for each run:
no deck text is written or read. Only a mistake is worded through the deck text written for the model: the deck
reader then names it as it does for that text (coincident points, a zero length), in the model's words
(:func:`mechfem.explain.translate`), whatever was compiled before.

:meth:`Mechanism.run <mechfem.Mechanism.run>` and :meth:`Mechanism.check <mechfem.Mechanism.check>` sit in the model
layer, below the run: this module fills their hook (:mod:`mechfem.hooks`) when it is imported.
"""

from __future__ import annotations

from collections.abc import Callable

import mechfem._core as _core
from mechfem import building, compiled, deckio
from mechfem import model as _model
from mechfem.deckio import Progress
from mechfem.errors import MechfemError, RunInterrupted, on_stop
from mechfem.explain import translate
from mechfem.limits import memory_limit
from mechfem.model import Mechanism
from mechfem.motion import Motion
from mechfem.namespace import model_result
from mechfem.result import RunResult
from mechfem.storage import Storage


@_model.RUN.register
def run(
    mech: Mechanism,
    motion: Motion | None,
    storage: Storage | None,
    progress: Progress = None,
    with_motion: bool = True,
    order: int | None = 2,
    raise_on_stop: bool | None = None,
) -> RunResult:
    """Runs the mechanism through ``motion`` (position 1 only without one, or with ``with_motion=False``),
    computing the transfer functions of ``order`` (see :meth:`Mechanism.run`). A run that stopped early warns, or
    with ``raise_on_stop`` raises :class:`~mechfem.RunStoppedError`; ``raise_on_stop`` None leaves that to the
    caller."""
    moving = with_motion and motion is not None
    callback = deckio.progress_callback(progress, "positions")
    try:
        d: _core.Run | None = None
        try:
            kept = compiled.kept_model(mech, motion, storage)
            if kept is not None:
                model, numbering, changes = kept
            else:
                # A model with tables, or one the builder refuses (which raises).
                (model, numbering), changes = building.build(mech, motion, storage), []
            d = model.run(changes, moving, callback, order, memory_limit())
        except (MechfemError, KeyError, ValueError, TypeError):
            # A mistake in the model: the deck reader checks the given numbers (coincident points, a zero length)
            # when it compiles, a kept model that only takes new numbers meets them in the core instead, and the
            # deck writer refuses what no deck can say. The deck written for the model names the mistake in the
            # model's words, and so does the run of that deck.
            d = None
        if d is None:
            d, numbering = _run_text(mech, motion, storage, moving, callback, order)
    finally:
        close = getattr(callback, "close", None)
        if close is not None:
            close()
    analysis = model_result(mech, numbering, d, f"{mech.name}.mec")
    analysis.motion = motion if with_motion else None
    if d.interrupted:
        raise RunInterrupted(analysis)
    if raise_on_stop is None:
        return analysis
    return on_stop(analysis, analysis.stop_reason(), raise_on_stop)


def _run_text(
    mech: Mechanism,
    motion: Motion | None,
    storage: Storage | None,
    moving: bool,
    callback: Callable[[int, int], object] | None,
    order: int | None,
) -> tuple[_core.Run, deckio.Numbering]:
    """Runs the deck text written for the mechanism; its errors in the model's words."""
    deck = deckio.write(mech, motion, storage)
    with deckio.tables_dir(deck.tables) as base:
        try:
            d = _core.run_deck_text(deck.text, deck.path, base, moving, callback, order, memory_limit())
        except MechfemError as e:
            raise translate(e, deck, mech.name) from None
    return d, deck.numbering


__all__ = ["run"]
