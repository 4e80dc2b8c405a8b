"""What a run did: the adjustment of position 1, the limit positions met, and why a motion stopped, built from
the compiled module's typed report (``_core.Report``) and said in words.

Numbers that name things (co-ordinates, rows, positions) are the deck's own, 1-based and signed.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field

import mechfem._core as _core
from mechfem.results.words import Part, Words, with_unit, words_of


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
    def from_core(cls, a: _core.Adjust) -> AdjustInfo:
        return cls(a.iterations, a.stages, a.initial_deformations, a.residual)

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
    """``near_zero``: |det(D^c)| has a local minimum near zero; ``input_limit``: a driven input reached its extreme
    value, and the motion stopped there; ``passed``: free motion passed an extreme value of the input."""
    after: int
    """The position before it (the position itself for ``near_zero``)."""
    inputs: list[float]
    """The input values there; for ``input_limit`` and ``passed`` the input's extreme value."""
    coords: list[float]
    """All co-ordinates there (index i - 1 for co-ordinate i)."""
    det: float
    """det(D^c) there: zero up to rounding, except at a ``near_zero`` minimum."""

    @classmethod
    def from_core(cls, x: _core.Limit) -> Limit:
        return cls(x.kind, x.after, x.inputs, x.coords, x.det)

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
            "near_zero": "det(D^c) has a minimum near zero: close to a limit position, the transfer quality is poor",
            "input_limit": f"{inp} reaches its limit position: the driven motion cannot go on",
            "passed": f"free motion passes a limit position of {inp}, which turns back there",
        }.get(self.kind, "a limit position")

    def values(self, names: Sequence[str] | Words = ()) -> str:
        """``input 1 = ..., det(D^c) = ...``."""
        at = [words_of(names).at(j, v, 12) for j, v in enumerate(self.inputs, 1)]
        return ", ".join([*at, words_of(names).det(self.det, 3)])

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
    ``interrupted``, ``simulation`` (a simulation's integrator could not go on), ``non_finite_dynamics`` (a result
    of the dynamics is not finite: the message names the mass or load)."""
    message: str
    """The solver's own words, as the deck says them."""
    limit: Limit | None
    """The limit position the input ran into, when one was located."""
    parts: list[Part] = field(default_factory=list)
    """The solver's message in parts, the things it names as structure (:data:`mechfem.results.words.Part`): what
    :meth:`describe` words it from (from ``message`` alone when empty)."""

    @classmethod
    def from_core(cls, s: _core.Stop) -> Stop:
        limit = None if s.limit is None else Limit.from_core(s.limit)
        return cls(s.last_good, s.inputs, s.last_inputs, s.kind, s.message, limit, list(s.parts))

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
        if self.kind == "non_finite_dynamics":
            return f"The motion stopped after position {k} of {total}: at the next position {message}. {kept}"
        if self.kind == "simulation":
            return (
                f"The simulation stopped after position {k} of {total}: {message}. {kept} "
                "A collapsing step usually means a limit position (no position exists beyond it); a very stiff "
                f"spring or damper needs far more steps than its outputs: soften it, or loosen {words.tolerances}."
            )
        limit = self.limit
        if limit is not None and limit.kind == "input_limit" and len(self.inputs) == 1 == len(limit.inputs):
            target = with_unit(f"{self.inputs[0]:.10g}", words.unit(1))
            return (
                f"The motion stopped after position {k} of {total}: {words.input(1)} reached its limit "
                f"position at {words.at(1, limit.inputs[0], 12)}, located between positions {k} and {k + 1} "
                f"({words.det(limit.det, 2)} there), and cannot be driven on to {target}. {kept} A "
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
    def from_core(cls, r: _core.Report, input_names: Sequence[str] = (), free_step: float | None = None) -> RunReport:
        return cls(
            adjust=AdjustInfo.from_core(r.adjust),
            positions=r.positions,
            steps=r.steps,
            subdivided_steps=r.subdivided_steps,
            limits=[Limit.from_core(x) for x in r.limits],
            singular_positions=r.singular_positions,
            stop=None if r.stop is None else Stop.from_core(r.stop),
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
        """What deserves a second look, one sentence each: near-zero minima of det(D^c) in a driven motion, and
        positions where no transfer functions exist."""
        return self.describe_warnings()

    def describe_warnings(self, words: Words | None = None) -> list[str]:
        """:attr:`warnings`, said with ``words`` (default: the deck's)."""
        w = words or Words(self.input_names)
        out = [x.describe(w) for x in self.limits if x.kind == "near_zero"]
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
