"""What a run or a check returns: plain, typed data built from the compiled module's dictionaries.

Numbers that name things (co-ordinates, elements, rows, DOFs, buffers, positions) are the deck's own,
1-based and signed, never 0-based indices.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np
import numpy.typing as npt

from mechfem import _core

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
    """A limit position met during the motion (theory, section 5.5)."""

    kind: str
    """``sign_change``: det(D^c) changed sign; ``near_zero``: |det(D^c)| has a local minimum near zero;
    ``input_limit``: a driven input reached its extreme value; ``passed``: free motion passed such an extreme."""
    after: int
    """The position before it (the position itself for ``near_zero``)."""
    inputs: list[float]
    coords: list[float]
    det: float

    @classmethod
    def from_core(cls, d: _core.LimitDict) -> Limit:
        return cls(d["kind"], d["after"], list(d["inputs"]), list(d["coords"]), d["det"])

    def describe(self) -> str:
        """One sentence: what and where."""
        at = ", ".join(f"input {j} = {v:.10g}" for j, v in enumerate(self.inputs, 1))
        at = f" (at {at}, det(D^c) = {self.det:.3g})" if at else f" (det(D^c) = {self.det:.3g})"
        if self.kind == "near_zero":
            return f"det(D^c) comes near zero at position {self.after}{at}: close to a limit position."
        what = {
            "sign_change": "det(D^c) changes sign",
            "input_limit": "the input reaches its extreme value",
            "passed": "free motion passes an extreme value of the input",
        }.get(self.kind, "a limit position")
        return f"{what} between positions {self.after} and {self.after + 1}{at}."


@dataclass(frozen=True)
class Stop:
    """Why a motion stopped before its last position."""

    last_good: int
    """The last position that was computed (1-based)."""
    inputs: list[float]
    """Input values that could not be reached."""
    last_inputs: list[float]
    """Input values at the last good position."""
    kind: str
    """What failed: ``singular``, ``no_convergence``, ``branch_jump``, ``element``, ``non_finite``, ``unsupported``."""
    message: str
    """The solver's own words."""
    limit: Limit | None
    """The limit position the input ran into, when one was located."""

    @classmethod
    def from_core(cls, d: _core.StopDict) -> Stop:
        limit = None if d["limit"] is None else Limit.from_core(d["limit"])
        return cls(d["last_good"], list(d["inputs"]), list(d["last_inputs"]), d["kind"], d["message"], limit)

    def describe(self, total: int) -> str:
        """One paragraph: where the motion stopped, why, and what to change."""
        frm = ", ".join(f"input {j} = {v:.10g}" for j, v in enumerate(self.last_inputs, 1))
        to = ", ".join(f"input {j} = {v:.10g}" for j, v in enumerate(self.inputs, 1))
        step = f"the step from {frm} to {to}" if to else f"the step from {frm}"
        limit = "" if self.limit is None else f" Located: {self.limit.describe()}"
        # A located limit position of the input explains the failure better than the solver's symptom.
        located = self.limit is not None and self.limit.kind in ("input_limit", "sign_change")
        hint = _HINTS["singular"] if located else _HINTS.get(self.kind, _HINTS["other"])
        return (
            f"The motion stopped after position {self.last_good} of {total}: {step} failed, even with smaller "
            f"steps: {self.message}.{limit} Every result up to position {self.last_good} is kept. {hint}"
        )


_HINTS = {
    "singular": "D^c became singular: this is a limit position of the input, which cannot drive the mechanism "
    "through it. Stop the motion before it, drive the mechanism with another input, or use MOV_FREE "
    "(free motion through limit positions).",
    "no_convergence": "Try more, smaller steps (a larger n in TSTEPE); if the mechanism is near a limit position, "
    "use MOV_FREE.",
    "branch_jump": "The corrector kept jumping to another assembly branch. Try more, smaller steps (a larger n in "
    "TSTEPE); near a limit position use MOV_FREE.",
    "element": "An element could not be evaluated (two of its points coincide, or a belt lost its free span); "
    "check the dimensions or stop the motion earlier.",
    "other": "Try more, smaller steps (a larger n in TSTEPE), or MOV_FREE near a limit position.",
}


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
    """Limit positions met on the way, in order."""
    singular_positions: list[int]
    """Positions where D^c was singular, so that no transfer functions exist there (free motion only)."""
    stop: Stop | None
    """Set when the motion stopped early."""

    @classmethod
    def from_core(cls, d: _core.ReportDict) -> RunReport:
        return cls(
            adjust=AdjustInfo.from_core(d["adjust"]),
            positions=d["positions"],
            steps=d["steps"],
            subdivided_steps=d["subdivided_steps"],
            limits=[Limit.from_core(x) for x in d["limits"]],
            singular_positions=list(d["singular_positions"]),
            stop=None if d["stop"] is None else Stop.from_core(d["stop"]),
        )

    @property
    def warnings(self) -> list[str]:
        """The limit positions and singular positions, one sentence each."""
        out = [x.describe() for x in self.limits]
        if self.singular_positions:
            at = ", ".join(map(str, self.singular_positions))
            out.append(f"D^c is singular at position(s) {at}: transfer functions there are not defined.")
        return out

    @property
    def complete(self) -> bool:
        """True when every position asked for was computed."""
        return self.stop is None

    def stop_reason(self) -> str | None:
        """The paragraph saying why the motion stopped, or None when it did not."""
        return None if self.stop is None else self.stop.describe(self.steps + 1)


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

    @property
    def positions(self) -> int:
        return int(self.coords.shape[0])


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


def run_result(deck: Path, d: _core.RunDict) -> RunResult:
    """Builds a :class:`RunResult` from the compiled module's dictionary."""
    values = np.asarray(d["buffer_values"], dtype=np.float64)
    buffers = {n: np.ascontiguousarray(values[:, k]) for k, n in enumerate(d["buffer_numbers"])}
    return RunResult(
        deck=deck,
        buffers=buffers,
        coords=np.asarray(d["coords"], dtype=np.float64),
        time=np.asarray(d["time"], dtype=np.float64),
        det=np.asarray(d["det"], dtype=np.float64),
        report=RunReport.from_core(d["report"]),
        model=Model.from_core(d["model"]),
        storage=Storage.from_core(d["storage"]),
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
        model=Model.from_core(d["model"]),
    )
