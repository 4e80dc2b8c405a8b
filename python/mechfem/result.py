"""What a run or a check returns: plain, typed data built from the compiled module's dictionaries.

Numbers that name things (co-ordinates, elements, rows, DOFs, buffers, positions) are the deck's own,
1-based and signed, never 0-based indices.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import numpy.typing as npt

import mechfem._core as _core
from mechfem.converted import Converted
from mechfem.hooks import Hook
from mechfem.inverse_dynamics import DynamicSeries, DynamicsModel, Simulation
from mechfem.words import Part, Words, words_of
from mechfem.words import free_motion_line as free_motion_line  # named here as before
from mechfem.words import input_name as input_name

FloatArray = npt.NDArray[np.float64]


@dataclass(frozen=True)
class AdjustInfo:
    """The Newton adjustment of the initial co-ordinates that makes position 1."""

    iterations: int
    """Newton iterations made."""
    stages: int
    """Stages the prescribed changes were applied in (more than 1 when they had to be split)."""
    initial_deformations: list[float]
    """Deformation of every prescribed row before the adjustment (value at the given co-ordinates minus PARA value)."""
    residual: float
    """Largest deformation after the adjustment."""

    @classmethod
    def from_core(cls, d: _core.AdjustDict) -> AdjustInfo:
        return cls(d["iterations"], d["stages"], list(d["initial_deformations"]), d["residual"])

    def largest(self) -> tuple[int, float] | None:
        """The row (1-based) with the largest initial deformation and that deformation, or None without rows."""
        if not self.initial_deformations:
            return None
        k = max(range(len(self.initial_deformations)), key=lambda r: abs(self.initial_deformations[r]))
        return k + 1, self.initial_deformations[k]


@dataclass(frozen=True)
class Limit:
    """A limit position met during the motion (theory, section 5.5), located between two positions."""

    kind: str
    """``sign_change``: det(D^c) changed sign between two positions of a driven motion; ``near_zero``: |det(D^c)|
    has a local minimum near zero; ``input_limit``: a driven input reached its extreme value, and the motion stopped
    there; ``passed``: free motion passed an extreme value of the input."""
    after: int
    """The position before it (the position itself for ``near_zero``)."""
    inputs: list[float]
    """The input values there; for ``input_limit`` and ``passed`` the input's extreme value."""
    coords: list[float]
    """All co-ordinates there (index i - 1 for co-ordinate i)."""
    det: float
    """det(D^c) there: zero up to rounding, except at a ``near_zero`` minimum."""

    @classmethod
    def from_core(cls, d: _core.LimitDict) -> Limit:
        return cls(d["kind"], d["after"], list(d["inputs"]), list(d["coords"]), d["det"])

    @property
    def where(self) -> str:
        """``between positions k and k+1``, or ``at position k`` for a near-zero minimum."""
        if self.kind == "near_zero":
            return f"at position {self.after}"
        return f"between positions {self.after} and {self.after + 1}"

    def what(self, names: Sequence[str] | Words = ()) -> str:
        """The kind in words; ``names`` are the inputs' rows (:attr:`RunReport.input_names`), or the :class:`Words`
        to name things with."""
        inp = words_of(names).input(1) if len(self.inputs) == 1 else "an input"
        return {
            "sign_change": "det(D^c) changes sign: the driven motion passed a singular position",
            "near_zero": "det(D^c) has a minimum near zero: close to a limit position, the transfer quality is poor",
            "input_limit": f"{inp} reaches its limit position: the driven motion cannot go on",
            "passed": f"free motion passes a limit position of {inp}, which turns back there",
        }.get(self.kind, "a limit position")

    def values(self, names: Sequence[str] | Words = ()) -> str:
        """``input 1 = ..., det(D^c) = ...``."""
        at = [words_of(names).at(j, v, 12) for j, v in enumerate(self.inputs, 1)]
        return ", ".join([*at, f"det(D^c) = {self.det:.3g}"])

    def describe(self, names: Sequence[str] | Words = ()) -> str:
        """One sentence: what, where, the input values and det(D^c)."""
        return f"{self.what(names)}, {self.where} ({self.values(names)})."


@dataclass(frozen=True)
class Stop:
    """Why a motion stopped before its last position."""

    last_good: int
    """The last position that was computed (1-based)."""
    inputs: list[float]
    """Input values that could not be reached (empty under free motion)."""
    last_inputs: list[float]
    """Input values at the last good position."""
    kind: str
    """What failed: ``singular``, ``no_convergence``, ``branch_jump``, ``element``, ``non_finite``, ``unsupported``,
    ``interrupted``, ``simulation`` (a simulation's integrator could not go on)."""
    message: str
    """The solver's own words, as the deck says them."""
    limit: Limit | None
    """The limit position the input ran into, when one was located."""
    parts: list[Part] = field(default_factory=list)
    """The solver's message in parts, the things it names as structure (:data:`mechfem.words.Part`): what
    :meth:`describe` words it from (from ``message`` alone when empty)."""

    @classmethod
    def from_core(cls, d: _core.StopDict) -> Stop:
        limit = None if d["limit"] is None else Limit.from_core(d["limit"])
        return cls(
            d["last_good"], list(d["inputs"]), list(d["last_inputs"]), d["kind"], d["message"], limit, list(d["parts"])
        )

    def describe(
        self,
        total: int,
        names: Sequence[str] | Words = (),
        free_step: float | None = None,
        written: bool = False,
    ) -> str:
        """One paragraph: where the motion stopped, why, and what to change.

        ``names`` are the inputs' rows (:attr:`RunReport.input_names`), or the :class:`Words` to say it with;
        ``free_step`` the ds to suggest for free motion, and ``written`` says whether the positions computed
        have been written to output files.
        """
        words = words_of(names)
        message = words.render(self.parts or [self.message])
        k = self.last_good
        kept = "written to the output files" if written else "kept in the result"
        kept = (
            f"Position 1 was computed and is {kept}."
            if k == 1
            else f"Positions 1 to {k} were computed and are all {kept}."
        )
        if self.kind == "interrupted":
            return f"The motion was interrupted after position {k} of {total}. {kept}"
        if self.kind == "simulation":
            return (
                f"The simulation stopped after position {k} of {total}: {message}. {kept} "
                "A collapsing step usually means a limit position (no position exists beyond it); a very stiff "
                f"spring or damper needs far more steps than its outputs: soften it, or loosen {words.tolerances}."
            )
        limit = self.limit
        if limit is not None and limit.kind == "input_limit" and len(self.inputs) == 1 == len(limit.inputs):
            return (
                f"The motion stopped after position {k} of {total}: {words.input(1)} reached its limit "
                f"position at {words.at(1, limit.inputs[0], 12)}, located between positions {k} and {k + 1} "
                f"(det(D^c) = {limit.det:.2g} there), and cannot be driven on to {self.inputs[0]:.10g}. {kept} A "
                "driven input cannot move the mechanism through its limit position; free motion can. "
                f"{self._free_advice(free_step, words, total)} (At the smallest step the solver reported: "
                f"{message}.)"
            )
        frm = ", ".join(words.at(j, v, 10) for j, v in enumerate(self.last_inputs, 1))
        to = ", ".join(words.at(j, v, 10) for j, v in enumerate(self.inputs, 1))
        step = f"the step from {frm} to {to}" if to else f"the free-motion step from {frm}"
        located = "" if limit is None else f" Located: {limit.describe(words)}"
        hint = _hint(self.kind, words)
        if not self.inputs and self.kind != "element":
            hint = words.smaller_free_step
        elif len(self.inputs) == 1 and self.kind != "element":
            advice = self._free_advice(free_step, words, total)
            hint += f" If the input is near a limit position, use free motion. {advice}"
        elif self.kind != "element":
            hint += (
                " Near a limit position, drive the mechanism with other inputs or stop the motion before it "
                f"({words.free_needs_one_input})."
            )
        return (
            f"The motion stopped after position {k} of {total}: {step} failed, even with smaller steps: "
            f"{message}.{located} {kept} {hint}"
        )

    def _free_advice(self, free_step: float | None, words: Words, total: int) -> str:
        """The free motion to use instead of the driven one, for a one-DOF driven motion of ``total`` positions."""
        direction = -1.0 if self.inputs and self.inputs[0] < self.last_inputs[0] else 1.0
        ds = abs(free_step) if free_step else 0.01
        return words.free_advice(direction * ds, bool(free_step), total - 1)


def _hint(kind: str, words: Words) -> str:
    """What to change after a stop of ``kind``."""
    more = f"Try more, smaller steps ({words.more_steps})."
    return {
        "singular": "D^c became singular: an input is in a limit position and cannot drive the mechanism through "
        "it. Stop the motion before it, or drive the mechanism with another input.",
        "branch_jump": f"The corrector kept jumping to another assembly branch. {more}",
        "element": "An element could not be evaluated (two of its points coincide, or a belt lost its free span); "
        "check the dimensions or stop the motion earlier.",
    }.get(kind, more)


@dataclass(frozen=True)
class RunReport:
    """What a run did."""

    adjust: AdjustInfo
    """The adjustment of position 1."""
    positions: int
    """Positions computed (1 without a MOVEMENT block)."""
    steps: int
    """Steps the motion asked for (positions asked for: ``steps + 1``)."""
    subdivided_steps: int
    """Steps that had to be subdivided to converge."""
    limits: list[Limit]
    """Limit positions met on the way, in order (the one a driven motion stopped at is ``stop.limit``)."""
    singular_positions: list[int]
    """Positions where D^c was singular, so that no transfer functions exist there (free motion only): buffers made
    from transfer functions hold NaN at exactly these positions."""
    stop: Stop | None
    """Set when the motion stopped early."""
    input_names: list[str] = field(default_factory=list)
    """For DOF j (list index j - 1): the input's row and its form parameters, e.g. ``row 6: ANGB(1)``."""
    free_step: float | None = None
    """The mean distance the moving co-ordinates moved per step: the ds a stop message suggests for MOV_FREE."""

    @classmethod
    def from_core(
        cls, d: _core.ReportDict, input_names: Sequence[str] = (), free_step: float | None = None
    ) -> RunReport:
        return cls(
            adjust=AdjustInfo.from_core(d["adjust"]),
            positions=d["positions"],
            steps=d["steps"],
            subdivided_steps=d["subdivided_steps"],
            limits=[Limit.from_core(x) for x in d["limits"]],
            singular_positions=list(d["singular_positions"]),
            stop=None if d["stop"] is None else Stop.from_core(d["stop"]),
            input_names=list(input_names),
            free_step=free_step,
        )

    @property
    def located_limits(self) -> list[Limit]:
        """Every located limit position, in order: those met on the way, then the one the motion stopped at."""
        out = list(self.limits)
        if self.stop is not None and self.stop.limit is not None:
            out.append(self.stop.limit)
        return out

    @property
    def warnings(self) -> list[str]:
        """What deserves a second look, one sentence each: sign changes and near-zero minima of det(D^c) in a
        driven motion, and positions where no transfer functions exist."""
        return self.describe_warnings()

    def describe_warnings(self, words: Words | None = None) -> list[str]:
        """:attr:`warnings`, said with ``words`` (default: the deck's)."""
        w = words or Words(self.input_names)
        out = [x.describe(w) for x in self.limits if x.kind in ("sign_change", "near_zero")]
        if self.singular_positions:
            at = ", ".join(map(str, self.singular_positions))
            out.append(
                f"D^c is singular at position{'s' if len(self.singular_positions) > 1 else ''} {at}: the mechanism "
                f"is in a limit position of its input there, no transfer functions exist, and {w.singular_results}."
            )
        return out

    @property
    def complete(self) -> bool:
        """True when every position asked for was computed."""
        return self.stop is None

    def stop_reason(self, written: bool = False, words: Words | None = None) -> str | None:
        """The paragraph saying why the motion stopped, or None when it did not; ``written`` says that the
        positions computed have been written to output files, ``words`` how to say it (default: the deck's)."""
        if self.stop is None:
            return None
        return self.stop.describe(self.steps + 1, words or self.input_names, self.free_step, written)


@dataclass(frozen=True)
class Element:
    """One ELEM line."""

    number: int
    type: str
    coords: list[int]
    coord_names: list[str]
    line: int


@dataclass(frozen=True)
class Term:
    """One FORM line: ``factor * form`` of element ``element``."""

    element: int
    form: str
    factor: float
    seq: int
    """The FORM line's sequence number."""
    line: int


@dataclass(frozen=True)
class Row:
    """A prescribed row of D^c (``dest > 0``) or a dependent form parameter (``dest < 0``)."""

    dest: int
    terms: list[Term]
    para: float | None
    """The value PARA prescribes, if any."""
    input: int | None
    """The DOF whose input this row is, if it is one."""
    value: float
    """Value at position 1."""

    def formula(self) -> str:
        """The combination, e.g. ``ANGB(2) - ANGB(4)``."""
        out = ""
        for t in self.terms:
            mag = abs(t.factor)
            text = f"{t.form}({t.element})" if mag == 1.0 else f"{mag:g}*{t.form}({t.element})"
            if not out:
                out = ("-" if t.factor < 0 else "") + text
            else:
                out += (" - " if t.factor < 0 else " + ") + text
        return out


@dataclass(frozen=True)
class Coordinate:
    """One co-ordinate: fixed or moving, its given value and its value at position 1."""

    number: int
    moving: bool
    given: float
    adjusted: float


@dataclass(frozen=True)
class Model:
    """The model as compiled from the deck, for the echo in the print file."""

    elements: list[Element]
    prescribed: list[Row]
    dependent: list[Row]
    dofs: list[int]
    """For DOF j (1-based, list index j - 1): the prescribed row that is its input."""
    coordinates: list[Coordinate]
    mode: str = "KIN ANA"
    """The deck's mode line."""
    dynamics: DynamicsModel | None = None
    """The masses and loads of a DYN deck."""

    @classmethod
    def from_core(cls, d: _core.ModelDict) -> Model:
        def row(r: _core.RowDict) -> Row:
            terms = [Term(t["element"], t["form"], t["factor"], t["seq"], t["line"]) for t in r["terms"]]
            return Row(r["dest"], terms, r["para"], r["input"], r["value"])

        return cls(
            elements=[
                Element(e["number"], e["type"], list(e["coords"]), list(e["coord_names"]), e["line"])
                for e in d["elements"]
            ],
            prescribed=[row(r) for r in d["prescribed"]],
            dependent=[row(r) for r in d["dependent"]],
            dofs=list(d["dofs"]),
            coordinates=[Coordinate(c["number"], c["moving"], c["given"], c["adjusted"]) for c in d["coordinates"]],
            mode=d.get("mode", "KIN ANA"),
            dynamics=None if d.get("dynamics") is None else DynamicsModel.from_core(d["dynamics"]),  # type: ignore[arg-type]
        )

    @property
    def n_coords(self) -> int:
        return len(self.coordinates)

    @property
    def n_moving(self) -> int:
        return sum(c.moving for c in self.coordinates)


@dataclass(frozen=True)
class Buffer:
    """One BUF... line: buffer ``number`` holds the quantity ``keyword args``."""

    number: int
    keyword: str
    args: list[int]
    line: int

    def label(self) -> str:
        """The definition as written in a deck, e.g. ``BUFKE1 -1 1``."""
        return " ".join([self.keyword, *map(str, self.args)])


@dataclass(frozen=True)
class Plot:
    """One PLOTFUNC, PLOTCURV or PLOTHODO line."""

    keyword: str
    a: int
    b: int


@dataclass(frozen=True)
class Picture:
    """One BEGINPIC ... ENDPIC block."""

    title: str
    line: int
    plots: list[Plot]


@dataclass(frozen=True)
class Storage:
    """What the STORAGE block asks to be done with the buffers."""

    buffers: list[Buffer]
    printbuf: list[int] | None
    """Buffers to tabulate in the print file (all of them for a PRINTBUF without numbers); None without PRINTBUF."""
    savedata: list[int]
    """Buffers of the data set, in column order (empty: no data set)."""
    animate: str | None
    pictures: list[Picture]

    @classmethod
    def from_core(cls, d: _core.StorageDict) -> Storage:
        buffers = [Buffer(b["number"], b["keyword"], list(b["args"]), b["line"]) for b in d["buffers"]]
        printbuf = d["printbuf"]
        if printbuf is not None and not printbuf:
            printbuf = [b.number for b in buffers]
        return cls(
            buffers=buffers,
            printbuf=None if printbuf is None else list(printbuf),
            savedata=list(d["savedata"]),
            animate=d["animate"],
            pictures=[
                Picture(p["title"], p["line"], [Plot(q["keyword"], q["a"], q["b"]) for q in p["plots"]])
                for p in d["pictures"]
            ],
        )

    def buffer(self, number: int) -> Buffer:
        """The definition of buffer ``number``."""
        for b in self.buffers:
            if b.number == number:
                return b
        raise KeyError(number)


@dataclass(frozen=True)
class ModelNames:
    """A named model's own names for the deck numbers of its run (:class:`mechfem.Mechanism`), so that labels
    (:mod:`mechfem.labels`) speak the model's language instead of the deck's."""

    coordinates: list[str]
    """Co-ordinate i is ``coordinates[i - 1]``, e.g. ``P.x``."""
    prescribed: list[str]
    """Prescribed row r is ``prescribed[r - 1]``."""
    dependent: list[str]
    """Dependent form parameter -k (an output) is ``dependent[k - 1]``."""
    inputs: list[str]
    """The input of DOF j is ``inputs[j - 1]``."""


@dataclass(frozen=True)
class RunResult:
    """Everything a run computed, position by position (row k is position k + 1)."""

    deck: Path
    buffers: dict[int, FloatArray]
    """Buffer number -> its value at every position."""
    coords: FloatArray
    """All co-ordinates, positions x co-ordinates (column i - 1 is co-ordinate i)."""
    time: FloatArray
    det: FloatArray
    """det(D^c) at every position."""
    report: RunReport
    model: Model
    storage: Storage
    kx1: dict[int, FloatArray] = field(default_factory=dict)
    """d x_i / d input 1 at every position, for the co-ordinates i named by PLOTHODO lines (for the hodographs;
    NaN where D^c is singular)."""
    dynamic: DynamicSeries | None = None
    """Drive forces, energies and power at every position of a DYN deck's run."""
    simulation: Simulation | None = None
    """What the integrator of a DYN SIM run did."""
    names: ModelNames | None = None
    """The model's own names, for the run of a named model (None for a deck's run: labels use deck numbers)."""

    @property
    def positions(self) -> int:
        return int(self.coords.shape[0])

    def _repr_html_(self) -> str:
        return HTML.call(self)


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


_CONVERTED = Converted()


def _model_and_names(d: _core.ModelDict) -> tuple[Model, list[str]]:
    model = Model.from_core(d)
    return model, [f"row {row}: {model.prescribed[row - 1].formula()}" for row in model.dofs]


def _report(d: _core.ReportDict, names: list[str], coords: FloatArray, model: Model) -> RunReport:
    """The run's report. One of a run that stopped gets the mean step for its advice (a pass over every position,
    saved when none stopped); one with nothing to report is converted once for every run of its deck that hands
    the same dictionary over again (see :class:`mechfem.converted.Converted`)."""
    if d["stop"] is not None:
        return RunReport.from_core(d, names, mean_step(coords, model))
    return _CONVERTED.get(d, lambda r: RunReport.from_core(r, names))


def run_result(deck: Path, d: _core.RunDict) -> RunResult:
    """Builds a :class:`RunResult` from the compiled module's dictionary. Runs of one deck file share its
    :class:`Model` and :class:`Storage` (read them, do not change them)."""
    table = np.asarray(d["table"], dtype=np.float64)

    def block(name: str) -> FloatArray:
        # The core names the table's blocks: block name -> (first column, shape at one position).
        start, shape = d["layout"][name]
        return table[:, start : start + math.prod(shape)].reshape(table.shape[0], *shape)

    values, kx1, dynamic = block("buffers"), block("hodograph"), ("inputs", "drive", "ekin", "epot", "power")
    buffers = {n: values[:, k] for k, n in enumerate(d["buffer_numbers"])}
    coords = np.asarray(d["coords"], dtype=np.float64)
    model, names = _CONVERTED.get(d["model"], _model_and_names)
    return RunResult(
        deck=deck,
        buffers=buffers,
        coords=coords,
        time=block("time"),
        det=block("det"),
        report=_report(d["report"], names, coords, model),
        model=model,
        storage=_CONVERTED.get(d["storage"], Storage.from_core),
        kx1={n: kx1[:, k] for k, n in enumerate(d["hodograph_coords"])},
        dynamic=DynamicSeries.from_core({n: block(n) for n in dynamic}) if "ekin" in d["layout"] else None,
        simulation=None if d.get("simulation") is None else Simulation.from_core(d["simulation"]),  # type: ignore[arg-type]
    )


def check_result(deck: Path, d: _core.CheckDict) -> CheckResult:
    """Builds a :class:`CheckResult` from the compiled module's dictionary."""
    return CheckResult(
        deck=deck,
        n_coords=d["n_coords"],
        n_moving=d["n_moving"],
        n_prescribed=d["n_prescribed"],
        n_dependent=d["n_dependent"],
        n_dof=d["n_dof"],
        det=d["det"],
        coords=np.asarray(d["coords"], dtype=np.float64),
        adjust=AdjustInfo.from_core(d["adjust"]),
        model=_CONVERTED.get(d["model"], _model_and_names)[0],
    )


# RunResult._repr_html_ is drawn by mechfem.notebook, a layer above (docs/architecture.md), which fills this hook.
HTML: Hook[Callable[[RunResult], str]] = Hook("RunResult._repr_html_", "mechfem.notebook")
