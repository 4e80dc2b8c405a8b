"""The one result of an optimisation, whoever asked for it: :func:`mechfem.optimize` of a :class:`Mechanism`, the
OPTIMISE block of a ``KIN OPT`` or ``DYN ANA`` deck (:mod:`mechfem.design.optimise_deck`) and the engine itself
(:func:`mechfem.design.engine.solve`) all give an :class:`Optimum`. Each fills in what it knows: the engine the
numbers of the problem it solved, ``optimize`` the optimised mechanism and its starts, a deck's optimisation the deck
and its block. Every start's outcome is a :class:`Start`; the summary table and history chart of
:mod:`mechfem.design.optimum_view` are a method away."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np
import numpy.typing as npt

if TYPE_CHECKING:
    import os
    from pathlib import Path

    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

    from mechfem.design.engine import Evaluation, ExtremumTerm, Iteration
    from mechfem.design.optimise_deck import DeckProblem
    from mechfem.model.mechanism import Mechanism
    from mechfem.model.motion import Motion
    from mechfem.results.result import RunResult

FloatArray = npt.NDArray[np.float64]


@dataclass
class Optimum:
    """What an optimisation found: the variables' start and final values by name, the objective there, the history
    and the optimiser's verdict; from :func:`optimize` also the optimised mechanism, from a deck the deck's
    problem (``deck``)."""

    mechanism: Mechanism | None
    """The optimised mechanism (:func:`optimize`); None for a deck's optimisation, whose final design is written
    as a deck (``<stem>_opt.mec``) instead."""
    start: dict[str, float]
    """Every design variable's start value, by name (a deck's: ``PARA 5``, ``XFIX 3``, in the engine's order)."""
    values: dict[str, float]
    """Its final value."""
    objective: float
    start_objective: float
    history: list[Iteration]
    runs: int
    """Mechanism runs (designs evaluated), the start design's included."""
    infeasible: int
    """How many of them met a design that could not be assembled or moved (stepped back from)."""
    success: bool
    message: str
    seconds: float
    method: str
    motion: Motion | None = field(default=None, repr=False)
    starts: list[Start] = field(default_factory=list, repr=False)
    """Every start's outcome (one for a single start); this optimum is the best of them."""
    usable: float = 1.0
    """The fraction of the starts that could be optimised (assembled, and feasible through the motion)."""
    timing: list[float] | None = None
    """With free timing, the input's value at each target point of the optimised design."""
    drawn: int = 0
    """With ``starts`` a number: the draws of the start box looked at to find the drawn starts (those that assemble
    and can do the problem's motion; :mod:`mechfem.design.multistart`)."""
    rejected: list[Start] = field(default_factory=list, repr=False)
    """The draws passed over, each with its reason (``message``)."""
    reasons: dict[str, tuple[int, str]] = field(default_factory=dict)
    """Those infeasible designs by kind of reason: ``"other_branch"`` (position 1 assembles only on another branch
    than the start design's), ``"left_branch"`` (the motion changes branch), ``"stopped"`` (the motion stops at a
    limit position), ``"position_one"`` (position 1 cannot be computed), ``"extrema"`` (a TARGETEXT's reference has
    another number of extrema); for each, how many and the first one's reason."""
    misses: list[tuple[float, int | None]] = field(default_factory=list)
    """How far each target (in the order given) is from its value at the final design: the largest difference,
    unweighted, and the position (0-based) where it is, None for an extremum target. In the units the targets are
    given in: the mechanism's for :func:`optimize`, the core's (SI) for a deck."""
    extrema: list[tuple[ExtremumTerm, float, float]] = field(default_factory=list, repr=False)
    """``(term, input, buffer value)`` of every extremum an extremum target compares, at the final design."""
    final: Evaluation | None = field(default=None, repr=False)
    """The final design evaluated by the engine: every buffer the problem reads at every position, and position 1
    (in the engine's units and order of variables)."""
    deck: DeckProblem | None = field(default=None, repr=False)
    """A deck's optimisation: the deck, its OPTIMISE block and the problem the engine solved."""

    @property
    def usable_draws(self) -> float:
        """With ``starts`` a number: the fraction of the draws looked at that became starts (assembled and able to
        do the problem's motion), ``(len(starts) - 1) / drawn``; NaN when nothing was drawn."""
        return (len(self.starts) - 1) / self.drawn if self.drawn else math.nan

    @property
    def x(self) -> FloatArray:
        """:attr:`values` as an array, in their order (a deck's optimum: the engine's order of variables)."""
        return np.fromiter(self.values.values(), dtype=np.float64, count=len(self.values))

    @property
    def x_start(self) -> FloatArray:
        """:attr:`start` as an array, in its order."""
        return np.fromiter(self.start.values(), dtype=np.float64, count=len(self.start))

    @property
    def position_one(self) -> list[float]:
        """The co-ordinates at position 1 of the final design, in deck order (empty without ``final``)."""
        return [] if self.final is None else self.final.position_one

    def run(self) -> RunResult:
        """The optimised mechanism run through the motion the optimisation used."""
        if self.mechanism is None:
            raise ValueError("a deck's optimisation has no mechanism: run the deck it wrote (<stem>_opt.mec)")
        return self.mechanism.run(self.motion)

    # The views live in mechfem.design.optimum_view, imported when asked for (it needs matplotlib for the chart).
    def _repr_html_(self) -> str:
        """Jupyter's summary table: the variables' start and final values, the objective, the verdict."""
        from mechfem.design import optimum_view

        return optimum_view.summary_html(optimum_view.optimum_summary(self))

    def plot_history(self, ax: Axes | None = None) -> Figure:
        """The objective per iteration on a logarithmic axis (on ``ax``, default a new figure); the figure."""
        from mechfem.design import optimum_view

        return optimum_view.plot_history(self.history, ax)

    def to_html(self) -> str:
        """The summary table and the chart of :meth:`plot_history` as one self-contained HTML page."""
        from mechfem.design import optimum_view

        return optimum_view.page(optimum_view.optimum_summary(self), self.history)

    def save_report(self, path: str | os.PathLike[str]) -> Path:
        """Writes :meth:`to_html` to ``path``; returns its path."""
        from mechfem.design import optimum_view

        return optimum_view.save_page(optimum_view.optimum_summary(self), self.history, path)


@dataclass
class Start:
    """One start of :func:`optimize`: the variables' start values, where the optimiser took them (None when the
    start failed) and the objective there (NaN when it failed), its runs and time, and ``message``: the
    optimiser's word, or why the start failed (e.g. its design cannot be assembled). With free timing also the
    input's value at each target point it started from and where the optimiser took them."""

    start: dict[str, float]
    values: dict[str, float] | None
    objective: float
    runs: int
    success: bool
    message: str
    seconds: float
    start_timing: list[float] | None = None
    """With free timing, the input's value at each target point this start began from, in the model's units: a
    fitted start's own (the crank angles of its coupler curve laid on the points), else the ``FreeTiming``'s
    ``starts``; None without free timing."""
    timing: list[float] | None = None
    """With free timing, the input's value at each target point where this start ended (None when it failed)."""
