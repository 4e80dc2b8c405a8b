"""Runs a :class:`~mechfem.Mechanism` and gives the result as a :class:`~mechfem.RunResult`, its errors in the
model's words.

A mechanism runs on its kept compiled model (:mod:`mechfem.run.compiled`), built through the typed builder
(:mod:`mechfem.run.building`) when its topology is new, and one with table motions or load tables is built for each run:
no deck text is written or read. A run that fails (position 1 cannot be computed) is worded from the core's typed
error and the numbering the model was built in (:func:`mechfem.run.building.explain`); so is a mistake the compiler
finds in the items (coincident points, a zero length), from the note of the item it is about, whatever was compiled
before. A value no deck can state raises the deck writer's ``ValueError``, ``KeyError`` or ``TypeError``.

:meth:`Mechanism.run <mechfem.Mechanism.run>` and :meth:`Mechanism.check <mechfem.Mechanism.check>` sit in the model
layer, below the run: they import this module when they are called.
"""

from __future__ import annotations

import mechfem._core as _core
from mechfem._util.limits import memory_limit
from mechfem.deck import deckio
from mechfem.deck.deckio import Progress
from mechfem.errors import MechfemError, RunInterrupted, on_stop
from mechfem.model.mechanism import Mechanism
from mechfem.model.motion import Motion
from mechfem.model.storage import Storage
from mechfem.results.result import RunResult
from mechfem.run import building, compiled
from mechfem.run.namespace import model_result


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
        except (MechfemError, KeyError, ValueError, TypeError):
            # The model built afresh below meets the same mistake and names it.
            kept = None
        if kept is not None:
            model, numbering, changes = kept
            try:
                d = model.run(changes, moving, callback, order, memory_limit())
            except MechfemError:
                # A kept model that only takes new numbers meets a mistake of them (coincident points, a zero
                # length) in the core, where the deck reader checks them when it compiles: the model built
                # afresh names it as its compiler does.
                d = None
        if d is None:
            # A model with tables, a new topology or a kept one that failed. A value no deck can state raises the
            # deck writer's ValueError, KeyError or TypeError in the builder; an item it refuses, a DeckError.
            built = building.builder(mech, motion, storage)
            numbering = built.numbering
            try:
                with deckio.tables_dir(built.tables) as base:
                    model = built.builder.build(base)
                d = model.run([], moving, callback, order, memory_limit())
            except MechfemError as e:
                # The compiler refused an item (coincident points, a point on no element), or the run failed
                # (position 1 cannot be computed): the core's typed error in the model's names.
                raise building.explain(e, built, mech, motion, storage) from None
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


__all__ = ["run"]
