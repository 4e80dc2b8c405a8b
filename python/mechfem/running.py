"""Runs a :class:`~mechfem.Mechanism` and gives the result as a :class:`~mechfem.RunResult`, its errors in the
model's words.

A mechanism runs on its kept compiled model (:mod:`mechfem.compiled`), built through the typed builder
(:mod:`mechfem.building`) when its topology is new, and one with table motions or load tables is built for each run:
no deck text is written or read. A run that fails (position 1 cannot be computed) is worded from the core's typed
error and the numbering the model was built in (:func:`mechfem.building.explain`). Only a mistake the deck reader or
writer refuses is worded through the deck text written for the model: the deck reader then names it as it does for
that text (coincident points, a zero length), in the model's words (:func:`mechfem.explain.translate`), whatever was
compiled before.

:meth:`Mechanism.run <mechfem.Mechanism.run>` and :meth:`Mechanism.check <mechfem.Mechanism.check>` sit in the model
layer, below the run: this module fills their hook (:mod:`mechfem.hooks`) when it is imported.
"""

from __future__ import annotations

from collections.abc import Callable

import mechfem._core as _core
from mechfem import building, compiled, deckio
from mechfem import model as _model
from mechfem.deckio import Progress
from mechfem.errors import DeckError, MechfemError, RunInterrupted, on_stop
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
        d: _core.TextRunDict | None = None
        failed: tuple[MechfemError, building.Built] | None = None
        try:
            kept = compiled.kept_model(mech, motion, storage)
            if kept is not None:
                model, numbering, changes = kept
                try:
                    d = model.run(changes, moving, callback, order, memory_limit())
                except MechfemError:
                    # A kept model that only takes new numbers meets a mistake of them (coincident points, a zero
                    # length) in the core, where the deck reader checks them when it compiles: the model built
                    # afresh names it as its deck would.
                    d = None
            if d is None:
                # A model with tables, one the builder refuses (which raises) or a kept one that failed.
                built = building.builder(mech, motion, storage)
                with deckio.tables_dir(built.tables) as base:
                    model, numbering = built.builder.build(base), built.numbering
                try:
                    d = model.run([], moving, callback, order, memory_limit())
                except DeckError:
                    raise
                except MechfemError as e:
                    # The run of the built model failed (position 1 cannot be computed): the core's typed error
                    # in the model's names, from the numbering the model was built in.
                    failed = (e, built)
        except (MechfemError, KeyError, ValueError, TypeError):
            # A mistake the deck reader or writer refuses: the deck written for the model names the mistake in
            # the model's words (the line of the deck, its text), and so does the run of that deck.
            d = None
        if failed is not None:
            raise building.explain(failed[0], failed[1], mech, motion, storage) from None
        if d is None:
            d, numbering = _run_text(mech, motion, storage, moving, callback, order)
    finally:
        close = getattr(callback, "close", None)
        if close is not None:
            close()
    analysis = model_result(mech, numbering, d, f"{mech.name}.mec")
    analysis.motion = motion if with_motion else None
    if d["interrupted"]:
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
) -> tuple[_core.TextRunDict, deckio.Numbering]:
    """Runs the deck text written for the mechanism; its errors in the model's words."""
    deck = deckio.write(mech, motion, storage)
    with deckio.tables_dir(deck.tables) as base:
        try:
            d = _core.run_deck_text(deck.text, deck.path, base, moving, callback, order, memory_limit())
        except MechfemError as e:
            raise translate(e, deck, mech.name) from None
    return d, deck.numbering


__all__ = ["run"]
