"""What a run returns, however it was started (a deck, a named :class:`~mechfem.Mechanism`, a study's variant):
one :class:`RunResult`, addressed by names, its buffers also by number.

Arrays have one entry per position (row k is position k + 1). A run's tables arrive from the compiled module as
one table of columns with a layout that names its blocks (``kx1``, ``e0``, ``buffers``, ``time``, ...): a named
model's run records every quantity, a deck's run the buffers its STORAGE block asks for (plus time, det(D^c) and
what its pictures need). A name is resolved to the deck's numbers by the result's :class:`Names`: the model's own
names, or for a deck the names it declares (:mod:`mechfem.run.namespace`).
"""

from __future__ import annotations

import copy
import functools
from collections.abc import Sequence
from dataclasses import dataclass, fields
from pathlib import Path
from typing import Any

import numpy as np
import numpy.typing as npt

import mechfem._core as _core
from mechfem.model.echo import EchoStorage, Model, ModelNames
from mechfem.results.converted import Converted
from mechfem.results.inverse_dynamics import DynamicSeries, Simulation
from mechfem.results.result_tables import Energy, Names, ResultTables
from mechfem.results.run_report import AdjustInfo, Limit, RunReport
from mechfem.results.words import input_names

FloatArray = npt.NDArray[np.float64]


class RunResult(ResultTables):
    """Everything a run computed, position by position, addressed by names.

    ``coords`` holds every co-ordinate (positions x co-ordinates, column i - 1 is co-ordinate i), ``time`` and
    ``det`` (det(D^c)) one value per position, ``buffers`` the deck's buffers by number. :meth:`value`,
    :meth:`velocity`, :meth:`acceleration`, :meth:`input` and the inverse dynamics take names: a named model's
    (``"C"``, ``"rocker.angle"``), or for a deck's run ``x13``, ``P9`` (the point whose x is co-ordinate 9),
    ``ANGB(3)``, a row's formula, ``row6``/``out1`` and the names its comments declare. A deck's run holds what
    its STORAGE block records: asking for anything else says which BUF line records it.
    """

    def __init__(
        self,
        deck: Path,
        raw: _core.Run,
        names: Names | None = None,
        parameters: dict[str, Any] | None = None,
    ) -> None:
        self.deck = deck
        """The deck file run (for a named model, the name of the deck written for it)."""
        self.parameters: dict[str, Any] = parameters or {}
        """The values a design study gave this variant."""
        self.motion: Any = None
        """The :class:`~mechfem.Motion` a named model's run followed (None: position 1 only, a deck, or not known)."""
        self._raw = raw
        self._namespace = names
        if raw.simulation is not None:
            # Converted now: the conversion warns of tolerances that conflict, as the run returns.
            self.__dict__["simulation"] = Simulation(raw.simulation)
        super().__init__(raw)

    # -- what the run was

    @functools.cached_property
    def coords(self) -> FloatArray:  # type: ignore[override]
        """Every co-ordinate at every position: positions x co-ordinates (column i - 1 is co-ordinate i)."""
        return self._raw.coords

    @functools.cached_property
    def simulation(self) -> Simulation | None:
        """What the integrator of a simulation did (method, tolerances, steps, rejected steps, evaluations of the
        equations of motion, the time reached); None for a run of a prescribed motion."""
        sim = self._raw.simulation
        return None if sim is None else Simulation(sim)

    def __getstate__(self) -> dict[str, Any]:
        # The compiled module's run goes into a pickle as its values.
        state = self.__dict__.copy()
        if isinstance(state["_raw"], _core.Run):
            state["_raw"] = PickledRun.of(state["_raw"])
        return state

    @property
    def path(self) -> str:
        """The deck's path as text."""
        return str(self.deck)

    @property
    def _names(self) -> Names:
        if self._namespace is None:
            from mechfem.run import namespace

            self._namespace = namespace.deck_namespace(self)
        return self._namespace

    @property
    def named(self) -> bool:
        """True for the run of a named :class:`~mechfem.Mechanism` (or a study's variant), False for a deck's."""
        return self._namespace is not None and self._namespace.named

    @property
    def mechanism(self) -> Any:
        """The :class:`~mechfem.Mechanism` run; for a deck, the one its topology makes (points ``P5``, co-ordinates
        ``x13``, elements ``E1``, the names the deck declares)."""
        return self._names.mechanism

    @property
    def numbering(self) -> Any:
        """The deck numbers of the mechanism's parts (:class:`~mechfem.deck.naming.Numbering`)."""
        return self._names.numbering

    @functools.cached_property
    def model(self) -> Model:
        """The model as compiled (the print file's echo)."""
        return _model_and_names(self._raw.model)[0]

    @functools.cached_property
    def storage(self) -> EchoStorage:
        """The storage requests: buffers, tables, data set, pictures, animation."""
        return self._raw.storage

    @functools.cached_property
    def report(self) -> RunReport:
        """What the run did: the adjustment of position 1, the limit positions met, why it stopped."""
        d = self._raw.report
        names = _model_and_names(self._raw.model)[1]
        if d.stop is not None:
            return RunReport.from_core(d, names, mean_step(self.coords, self.model))
        return _CONVERTED.get(d, lambda r: RunReport.from_core(r, names))

    @functools.cached_property
    def names(self) -> ModelNames | None:
        """A named model's own names for the deck numbers (None for a deck's run: labels use deck numbers)."""
        return self._namespace.model_names() if self._namespace is not None else None

    @functools.cached_property
    def dynamic(self) -> DynamicSeries | None:
        """Inputs, drive forces, energies and power at every position of a run with masses or loads (None
        otherwise)."""
        if "drive" not in self._layout:
            return None
        return DynamicSeries(*(self._block(b) for b in ("inputs", "drive", "ekin", "epot", "power")))

    @property
    def positions(self) -> int:
        """Positions computed."""
        return self._raw.positions

    @property
    def complete(self) -> bool:
        """True when every position asked for was computed."""
        return self.report.complete

    @property
    def limits(self) -> list[Limit]:
        """Limit positions met on the way."""
        return self.report.limits

    def stop_reason(self) -> str | None:
        """Why the motion stopped early, where, and what to change (in the words of the model or the deck), or
        None."""
        # A run that went to its end needs neither its report nor its names converted for that (a report replaced
        # by ``replace`` is asked itself).
        if "report" not in self.__dict__ and not self._raw.stopped:
            return None
        return self.report.stop_reason(words=self._names.words(self.report))

    @property
    def warnings(self) -> list[str]:
        """The limit positions and singular positions, one sentence each."""
        return self.report.describe_warnings(self._names.words(self.report))

    def replace(self, **fields: Any) -> RunResult:
        """A copy with ``fields`` (``storage``, ``names``, ``report``, ``model``) replaced, e.g. to draw a picture
        the deck does not ask for."""
        out = copy.copy(self)
        out.__dict__.update(fields)
        return out

    # -- names

    def _traced_points(self, names: Sequence[str] | None = None) -> list[Any]:
        """The points whose paths a picture, animation or drawing traces: those called ``names``, or by default
        every moving point whose two co-ordinates the run computed."""
        return self._names.traced(names)

    # -- pictures

    def run_result(self) -> RunResult:
        """The result itself (pictures, print file and report read this same type)."""
        return self

    def sensitivity(self, quantity: Any, wrt: str | Sequence[str]) -> FloatArray:
        """The derivative of ``quantity`` at every position with respect to the design variables ``wrt`` (names of
        prescribed values or fixed co-ordinates, as for :func:`mechfem.optimize`): positions x variables, or one
        value per position for a single name. ``quantity`` is a name (its value) or ``Q(name, order, wrt)`` for a
        transfer function. Exact: from the factorisation of D^c at each position (one more run of the motion).
        For a named model's run."""
        if not self.named:
            raise ValueError(
                "sensitivity() runs the mechanism again with its motion: read the deck into a model with "
                "Mechanism.read_deck and run that, then ask its result"
            )
        names = [wrt] if isinstance(wrt, str) else list(wrt)
        from mechfem.design import optimise

        out = optimise.sensitivity(self, quantity, names)
        return out[:, 0].copy() if isinstance(wrt, str) else out

    def plot(self, *outputs: str, **options: Any) -> Any:
        """A figure (``matplotlib.figure.Figure``): the mechanism at position 1 with the paths of its moving points,
        beside the ``outputs`` (default: every output) against the first input. Options: ``picture=k`` draws
        picture k of the storage as the deck does; ``points=[...]`` chooses the paths; ``against="time"``."""
        from mechfem.viz import figures

        return figures.result_figure(self, outputs, **options)

    def animate(self, path: str | Path, points: Sequence[str] | None = None) -> list[Path]:
        """Writes an animation of the motion to ``path`` (GIF; also MP4 when ffmpeg is installed) with the paths
        of ``points`` (default: every moving point); returns the files written."""
        from mechfem.viz import figures

        return figures.animate(self, path, points)

    def to_dxf(
        self, path: str | Path, position: int = 1, paths: bool | Sequence[str] = True, units: str | None = None
    ) -> Path:
        """Writes the mechanism at ``position`` (1-based) as a DXF file with the paths of its moving points
        (``paths``: True, False or point names) and the points' names, one layer per kind of shape; ``units``
        ("mm", "m", ...) declares the length unit. Needs ezdxf (``pip install 'mechfem[dxf]'``)."""
        from mechfem.viz import export

        return export.analysis_dxf(self, path, position, paths, units)

    def to_svg(self, path: str | Path, position: int = 1, paths: bool | Sequence[str] = True) -> Path:
        """Writes the mechanism at ``position`` (1-based) as an SVG file, as :meth:`to_dxf` does a DXF file."""
        from mechfem.viz import export

        return export.analysis_svg(self, path, position, paths)

    def _repr_png_(self) -> bytes | None:
        from mechfem.viz import notebook

        return notebook.result_png(self)

    def _repr_html_(self) -> str:
        from mechfem.viz import notebook

        return notebook.result_html(self)

    def __repr__(self) -> str:
        name = self.mechanism.name if self.named else self.path
        state = "complete" if self.complete else f"stopped after position {self.positions}"
        return f"RunResult({name!r}: {self.positions} positions, {state}, {len(self.limits)} limit(s))"


Analysis = RunResult


@dataclass(frozen=True)
class PickledRun:
    """The values of a ``_core.Run`` as plain Python objects, with its attributes: what a pickled
    :class:`RunResult` holds."""

    positions: int
    n_coords: int
    n_dof: int
    n_prescribed: int
    n_dependent: int
    dynamic: bool
    interrupted: bool
    stopped: bool
    table: FloatArray
    coords: FloatArray
    buffers: FloatArray
    layout: dict[str, tuple[int, tuple[int, ...]]]
    buffer_numbers: list[int]
    hodograph_coords: list[int]
    report: _core.Report
    model: _core.EchoModel
    storage: _core.EchoStorage
    simulation: _core.Simulation | None

    @classmethod
    def of(cls, run: _core.Run) -> PickledRun:
        return cls(**{f.name: getattr(run, f.name) for f in fields(cls)})

    def column(self, c: int) -> FloatArray:
        """Column ``c`` of the table, as ``_core.Run.column`` gives it."""
        return self.table[:, c]


"""The result of :meth:`Mechanism.run <mechfem.Mechanism.run>`: the same :class:`RunResult` every run returns."""


@dataclass(frozen=True)
class CheckResult:
    """A deck read, compiled and brought to position 1, without motion."""

    deck: Path
    n_coords: int
    n_moving: int
    n_prescribed: int
    n_dependent: int
    n_dof: int
    det: float
    """det(D^c) at position 1."""
    coords: FloatArray
    """The co-ordinates of position 1 (after adjustment)."""
    adjust: AdjustInfo
    model: Model


def mean_step(coords: FloatArray, model: Model) -> float | None:
    """The mean Euclidean distance the moving co-ordinates moved from one position to the next (None for fewer
    than two positions): the natural ds of free motion for this mechanism."""
    if coords.shape[0] < 2:
        return None
    moving = [c.number - 1 for c in model.coordinates if c.moving]
    steps = np.linalg.norm(np.diff(coords[:, moving], axis=0), axis=1)
    mean = float(np.mean(steps))
    return mean if np.isfinite(mean) and mean > 0.0 else None


# The echo, storage requests and report of a deck run again unchanged arrive as the same dictionaries; each is
# converted once (see mechfem.results.converted).
_CONVERTED = Converted()


def _model_and_names(model: Model) -> tuple[Model, list[str]]:
    def make(model: Model) -> tuple[Model, list[str]]:
        return model, input_names(model)

    return _CONVERTED.get(model, make)


def run_result(deck: Path, d: _core.Run) -> RunResult:
    """The result of a run of the deck ``deck`` (``d``: the compiled module's run); runs of one deck file share its
    model echo and storage requests (read them, do not change them)."""
    return RunResult(deck, d)


def check_result(deck: Path, d: _core.Check) -> CheckResult:
    """The :class:`CheckResult` of the deck ``deck`` checked by the compiled module (``d``)."""
    return CheckResult(
        deck=deck,
        n_coords=d.n_coords,
        n_moving=d.n_moving,
        n_prescribed=d.n_prescribed,
        n_dependent=d.n_dependent,
        n_dof=d.n_dof,
        det=d.det,
        coords=d.coords,
        adjust=AdjustInfo.from_core(d.adjust),
        model=_model_and_names(d.model)[0],
    )


__all__ = ["Analysis", "CheckResult", "Energy", "Names", "RunResult", "check_result", "mean_step", "run_result"]
