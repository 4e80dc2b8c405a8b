"""What :func:`mechfem.optimize` returns: the best design found (:class:`Optimum`) and every start's outcome
(:class:`Start`), with the summary table and history chart of :mod:`mechfem.design.optimum_view` a method away."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    import os
    from pathlib import Path

    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

    from mechfem.design.engine import Iteration
    from mechfem.model.mechanism import Mechanism
    from mechfem.model.motion import Motion
    from mechfem.results.result import RunResult


@dataclass
class Optimum:
    """What :func:`optimize` found: the optimised mechanism, the variables' start and final values, the history."""

    mechanism: Mechanism
    start: dict[str, float]
    values: dict[str, float]
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
    """Those infeasible designs by kind of reason (see :attr:`mechfem.design.engine.Solution.reasons`): how many, and
    the first one's reason; ``"left_branch"`` counts the designs whose motion changes assembly branch."""

    @property
    def usable_draws(self) -> float:
        """With ``starts`` a number: the fraction of the draws looked at that became starts (assembled and able to
        do the problem's motion), ``(len(starts) - 1) / drawn``; NaN when nothing was drawn."""
        return (len(self.starts) - 1) / self.drawn if self.drawn else math.nan

    def run(self) -> RunResult:
        """The optimised mechanism run through the motion the optimisation used."""
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
    optimiser's word, or why the start failed (e.g. its design cannot be assembled)."""

    start: dict[str, float]
    values: dict[str, float] | None
    objective: float
    runs: int
    success: bool
    message: str
    seconds: float
