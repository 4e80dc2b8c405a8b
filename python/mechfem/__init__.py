"""mechfem: finite-element kinematics of planar mechanisms.

Read a deck (the keyword language of the classic RUNMEC program), bring the
mechanism to its first position, move it through the input motion and get
every recorded buffer back as numpy arrays::

    import mechfem

    result = mechfem.run_deck("examples/supply/supply.mec")
    result.buffers[101]          # first-order transfer function, one value per position
    result.report.stop_reason()  # None when every position was computed

or build a mechanism in Python with named points and elements (:class:`Mechanism`), run it
(:class:`Analysis`) and run many variants of it on every core (:func:`sweep`), or on a Dask cluster
(``executor=client``; :func:`tolerance_study`, :func:`optimize` with ``starts``)::

    m = mechfem.Mechanism.from_deck("examples/supply/supply.mec")
    r = m.run()
    r.output("out1", order=1)

Masses and loads on a mechanism (:meth:`Mechanism.mass`, :meth:`Mechanism.gravity`, ...; see
:mod:`mechfem.model.loads`) make its run an inverse dynamics: ``r.drive_torque()``, ``r.stress(row)``,
``r.reaction(point)``, ``r.energy()``, ``r.power()``, ``r.mass_matrix()``; with them,
:meth:`Mechanism.simulate` finds the motion the forces make (a simulation, ``r.simulation``).

Deck mistakes raise :class:`DeckError`; a model that cannot reach position 1
raises :class:`AssemblyError`, :class:`ConvergenceError` or
:class:`LimitPositionError`; a run whose results would not fit in the memory
limit (:mod:`mechfem._util.limits`) raises :class:`ResourceError` before it starts.
A motion that stops later is not an error: the result holds every position up
to the last good one, says why it stopped and warns with
:class:`IncompleteRunWarning` (or, with ``raise_on_stop=True``, raises
:class:`RunStoppedError` carrying it). Ctrl-C raises
:class:`RunInterrupted` carrying the positions computed before it.
"""

from __future__ import annotations

import os as _os
from collections.abc import Callable as _Callable
from pathlib import Path as _Path
from typing import Any as _Any

from mechfem import _core
from mechfem._util import limits
from mechfem._version import __version__
from mechfem.design.dynamic_optimise import Drive, Shaking, ShakingForce
from mechfem.design.engine import Infeasible
from mechfem.design.frame_angle import FrameAngle
from mechfem.design.frame_length import FrameLength
from mechfem.design.optimise import (
    Bound,
    Evaluated,
    Optimum,
    Q,
    Start,
    Target,
    TargetAt,
    TargetExtremum,
    Transmission,
    optimize,
)
from mechfem.design.timing import FreeTiming
from mechfem.errors import (
    AssemblyError,
    ConvergenceError,
    DeckError,
    IncompleteRunWarning,
    LimitPositionError,
    MechfemError,
    ResourceError,
    RunInterrupted,
    RunStoppedError,
    UnitWarning,
    on_stop,
)
from mechfem.model.echo import Buffer, Model, Plot, Term
from mechfem.model.mechanism import Driven, Keep, Mechanism, Motion, Output
from mechfem.model.parts import Coordinate, Element, Row
from mechfem.model.storage import Picture, Storage
from mechfem.results.result import Analysis, CheckResult, RunResult, check_result, run_result
from mechfem.results.run_report import AdjustInfo, Limit, RunReport, Stop
from mechfem.studies.batch import Study, run_many, sweep
from mechfem.studies.tolerance import Spread, ToleranceBands, ToleranceStudy, tolerance_bands, tolerance_study
from mechfem.viz.export import export_drawing

Progress = _Callable[[int, int], object]
"""Called as ``progress(done, total)`` with the number of positions computed so far."""


def run_deck(
    path: str | _os.PathLike[str],
    progress: Progress | None = None,
    memory_limit: int | str | None = None,
    *,
    raise_on_stop: bool = False,
    det: bool = True,
) -> RunResult:
    """Reads the deck at ``path`` and runs it through its whole motion.

    ``progress``, if given, is called about every 1% of the positions. ``memory_limit`` (bytes, or a size
    such as ``"4G"``; default :func:`mechfem._util.limits.memory_limit`) bounds the memory the results may take:
    a run that would need more raises :class:`ResourceError` before it starts. Ctrl-C raises
    :class:`RunInterrupted` with the positions computed so far in its ``result``. A motion that stops early
    returns the positions up to there and warns with :class:`IncompleteRunWarning`, or with ``raise_on_stop``
    raises :class:`RunStoppedError` carrying them in its ``result``.

    ``det=False`` computes det(D^c) only when a buffer records it (BUFDET): ``result.det`` is NaN after position
    1 otherwise, the run does not watch det(D^c) change sign (``report.limits`` lists no limit position passed on
    the way), and a deck whose buffers are all positions and values computes positions only, the fastest run. A
    driven input that reaches its limit position still stops the run there, located as always. A deck file run
    again unchanged is not read into a model again.
    """
    deck = path if isinstance(path, _Path) else _Path(path)
    try:
        d = _core.run_deck(deck, progress, limits.memory_limit(memory_limit), det)
    except ResourceError as e:
        # The core words the refusal; how to raise a deck's limit is the deck path's to say.
        refused = ResourceError(f"{e} {limits.RAISE_DECK_LIMIT}")
        refused.__dict__.update(vars(e))
        raise refused from None
    result = run_result(deck, d)
    if d.interrupted:
        raise RunInterrupted(result)
    return on_stop(result, result.stop_reason(), raise_on_stop)


def check_deck(path: str | _os.PathLike[str]) -> CheckResult:
    """Reads the deck at ``path``, compiles it and computes position 1, without any motion."""
    deck = _Path(path)
    return check_result(deck, _core.check_deck(_os.fspath(deck)))


def studio(mechanism: Mechanism, height: int = 900) -> _Any:
    """Edits ``mechanism`` in a Jupyter notebook with mechfem studio (needs ``mechfem[studio]``); the widget's
    ``.mechanism`` is the edited design (docs/studio.md)."""
    from mechfem.studio_app import INSTALL, NEEDS, missing

    absent = missing({**NEEDS, "anywidget": "anywidget"})
    if absent:
        raise ImportError(f"mechfem.studio needs {', '.join(absent)}: {INSTALL}")
    from mechfem.studio_app.widget import studio as _studio

    return _studio(mechanism, height)


__all__ = [
    "AdjustInfo",
    "Analysis",
    "AssemblyError",
    "Bound",
    "Buffer",
    "CheckResult",
    "ConvergenceError",
    "Coordinate",
    "DeckError",
    "Drive",
    "Driven",
    "Element",
    "Evaluated",
    "FrameAngle",
    "FrameLength",
    "FreeTiming",
    "IncompleteRunWarning",
    "Infeasible",
    "Keep",
    "Limit",
    "LimitPositionError",
    "MechfemError",
    "Mechanism",
    "Model",
    "Motion",
    "Optimum",
    "Output",
    "Picture",
    "Plot",
    "Progress",
    "Q",
    "Row",
    "ResourceError",
    "RunInterrupted",
    "RunReport",
    "RunStoppedError",
    "RunResult",
    "Shaking",
    "ShakingForce",
    "Spread",
    "Start",
    "Stop",
    "Storage",
    "Study",
    "Target",
    "TargetAt",
    "TargetExtremum",
    "Transmission",
    "Term",
    "ToleranceBands",
    "ToleranceStudy",
    "UnitWarning",
    "__version__",
    "check_deck",
    "export_drawing",
    "optimize",
    "run_many",
    "run_deck",
    "studio",
    "sweep",
    "tolerance_bands",
    "tolerance_study",
]
