"""What a DYN ANA or DYN SIM deck's run adds to its result: the drive forces,
energies and power at every position, the figures a designer sizes a motor and a flywheel with, and what a
simulation's integrator did.

Numbers that name things are the deck's own (1-based, destinations signed).
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass
from typing import Any

import numpy as np
import numpy.typing as npt

import mechfem._core as _core
from mechfem.model.masses import ENERGY, TIME, Said, generalised_force, over

FloatArray = npt.NDArray[np.float64]


@dataclass(frozen=True)
class DynamicSeries:
    """Inverse dynamics along the run, one row per position."""

    inputs: FloatArray
    """Input values, positions x DOFs."""
    drive: FloatArray
    """Drive force or torque of every DOF (the stress of its input row), positions x DOFs."""
    kinetic: FloatArray
    potential: FloatArray
    """Potential energy of gravity and springs."""
    power: FloatArray
    """Power the drives deliver."""

    @classmethod
    def from_core(cls, d: dict[str, Any]) -> DynamicSeries:
        def arr(key: str) -> FloatArray:
            return np.asarray(d[key], dtype=np.float64)

        return cls(arr("inputs"), arr("drive"), arr("ekin"), arr("epot"), arr("power"))


def drive_work(time: FloatArray, power: FloatArray) -> tuple[FloatArray, FloatArray]:
    """The times where the drive power is known and the drives' work from the first of them to each, by the
    trapezoidal rule (infinite where the work overflows a double, without a warning)."""
    ok = np.isfinite(power) & np.isfinite(time)
    t, p = time[ok], power[ok]
    # Halves added rather than the sum halved: the same number, and no overflow of the sum.
    with np.errstate(over="ignore", invalid="ignore"):
        work = np.cumsum((0.5 * p[1:] + 0.5 * p[:-1]) * np.diff(t))
    return t, np.concatenate([[0.0], work])[: t.size]


def root_mean_square(v: FloatArray) -> float:
    """The root mean square of finite values, scaled by the largest so that no square overflows."""
    scale = float(np.max(np.abs(v)))
    if scale == 0.0:
        return 0.0
    return scale * float(np.sqrt(np.mean((v / scale) ** 2)))


def number(v: float, unit: str = "") -> str:
    """A summary number with ten digits and its ``unit`` (`` mm``, with its space); one that overflows a double (a
    sum or a difference of finite results) is said so instead of printed as an infinity."""
    return f"{v:.10g}{unit}" if math.isfinite(v) else "too large for a double"


def energy_fluctuation(time: FloatArray, power: FloatArray) -> float:
    """The largest fluctuation of the work the drives deliver about its mean rate: the energy a flywheel must
    absorb and give back to keep the drive at the mean power (NaN with fewer than two finite positions)."""
    t, work = drive_work(time, power)
    if t.size < 2 or t[-1] <= t[0]:
        return float("nan")
    with np.errstate(over="ignore", invalid="ignore"):
        excess = work - work[-1] * ((t - t[0]) / (t[-1] - t[0]))
        return float(excess.max() - excess.min())


def summary_lines(series: DynamicSeries, time: FloatArray, said: Said | None = None) -> list[str]:
    """The print file's DYNAMICS section: the extreme drive forces and where they occur, the drives' work and mean
    power, the energy a flywheel must absorb, and the range of the kinetic and potential energy; every number with
    its unit (``said``; the series are in the deck's units already)."""
    if series.drive.shape[0] == 0:
        return []
    said = said or Said()
    u = said.unit
    energy, power = u(ENERGY, True), u(over(ENERGY, TIME))
    out = ["DYNAMICS"]
    for j in range(series.drive.shape[1]):
        d = series.drive[:, j]
        ok = np.isfinite(d)
        if not ok.any():
            out.append(f"  drive of DOF {j + 1}: not known at any position (limit positions only)")
            continue
        e = said.inputs[j] if j < len(said.inputs) else {}
        f, x = u(generalised_force(e)), u(e)
        k_max, k_min = int(np.nanargmax(d)), int(np.nanargmin(d))
        rms = root_mean_square(d[ok])
        out += [
            f"  drive of DOF {j + 1}: largest {d[k_max]:.10g}{f} at position {k_max + 1} "
            f"(input {series.inputs[k_max, j]:.10g}{x}),",
            f"    smallest {d[k_min]:.10g}{f} at position {k_min + 1} (input {series.inputs[k_min, j]:.10g}{x}), "
            f"root mean square {rms:.10g}{f}",
        ]
    t, w = drive_work(time, series.power)
    if t.size > 1 and t[-1] > t[0]:
        work = float(w[-1])
        with np.errstate(over="ignore", invalid="ignore"):
            mean = work / float(t[-1] - t[0])
        out.append(f"  work of the drives: {number(work, energy)}, mean drive power {number(mean, power)}")
        out.append(
            "  largest fluctuation of the drives' work about its mean (a flywheel's energy swing): "
            f"{number(energy_fluctuation(time, series.power), energy)}"
        )
    for name, values in (("kinetic", series.kinetic), ("potential", series.potential)):
        v = values[np.isfinite(values)]
        if v.size:
            out.append(f"  {name} energy: from {v.min():.10g}{energy} to {v.max():.10g}{energy}")
    out.append("")
    return out


class Simulation:
    """What the integrator of a DYN SIM run did: the compiled module's record (``_core.Simulation``, owned by Rust),
    read through its attributes, with the print file's section (:meth:`lines`). Made, it warns of tolerances that
    conflict (ACCURACY and INTTOL)."""

    __slots__ = ("_run",)

    def __init__(self, run: _core.Simulation) -> None:
        self._run = run
        if run.tolerance_warning:
            warnings.warn(run.tolerance_warning, UserWarning, stacklevel=3)

    def __repr__(self) -> str:
        return (
            f"Simulation(method={self.method!r}, rtol={self.rtol!r}, atol={self.atol!r}, steps={self.steps}, "
            f"rejected={self.rejected}, evaluations={self.evaluations}, reached={self.reached!r})"
        )

    def __eq__(self, other: object) -> bool:
        return isinstance(other, Simulation) and self._run == other._run

    def __getstate__(self) -> _core.Simulation:
        return self._run

    def __setstate__(self, run: _core.Simulation) -> None:
        self._run = run

    @property
    def method(self) -> str:
        """The integrator, e.g. ``auto (Dormand-Prince 8(5,3) ...)``."""
        return self._run.method

    @property
    def rtol(self) -> float:
        """The relative tolerance."""
        return self._run.rtol

    @property
    def atol(self) -> float:
        """The absolute tolerance."""
        return self._run.atol

    @property
    def steps(self) -> int:
        """Steps accepted."""
        return self._run.steps

    @property
    def rejected(self) -> int:
        """Steps rejected (error estimate too large, or no position found)."""
        return self._run.rejected

    @property
    def evaluations(self) -> int:
        """Evaluations of the equations of motion (each one Newton position)."""
        return self._run.evaluations

    @property
    def reached(self) -> float:
        """The time the simulation reached."""
        return self._run.reached

    @property
    def jacobians(self) -> int:
        """Jacobians the implicit method computed (each ``2 nf + 1`` of the evaluations, nf the inputs moving under
        the forces)."""
        return self._run.jacobians

    @property
    def segments(self) -> list[tuple[str, float, float, int, int]]:
        """Which method integrated which stretch: ``(method, from, to, steps, evaluations)`` in order."""
        return self._run.segments

    @property
    def event(self) -> tuple[int, float, float, list[float]] | None:
        """Where STOPWHEN ended the simulation: ``(buffer, value, time, inputs)``; None when it did not."""
        return self._run.event

    @property
    def tolerance_warning(self) -> str | None:
        """Why ACCURACY and INTTOL conflict, if they do."""
        return self._run.tolerance_warning

    def lines(self, series: DynamicSeries | None, time: FloatArray, said: Said | None = None) -> list[str]:
        """The print file's SIMULATION section: the integrator and its work, and the energy balance at the end, with
        the units of the deck (``said``; the numbers are in them already)."""
        said = said or Said()
        s = said.unit(TIME)
        energy = said.unit(ENERGY, True)
        out = [
            "SIMULATION",
            f"  integrator: {self.method}",
            f"  tolerances: relative {self.rtol:.3g}, absolute {self.atol:.3g}",
            f"  steps: {self.steps} accepted, {self.rejected} rejected; {self.evaluations} evaluations of the "
            "equations of motion",
            f"  time reached: {self.reached:.10g}{s}",
        ]
        if self.jacobians:
            out.append(f"  Jacobians of the equations of motion: {self.jacobians}")
        if len(self.segments) > 1 or (self.segments and not self.method.startswith(self.segments[0][0])):
            out.append("  methods by stretch of time:")
            out += [
                f"    {method}: from {a:.10g}{s} to {b:.10g}{s}, {n} steps, {e} evaluations"
                for method, a, b, n, e in self.segments
            ]
        if self.event is not None:
            b, v, t, q = self.event
            at = ", ".join(f"{x:.10g}{said.unit(e)}" for x, e in zip(q, [*said.inputs, *[{}] * len(q)], strict=False))
            out.append(f"  stopped by STOPWHEN: buffer {b} crossed {v:.10g} at time {t:.10g}{s} (inputs {at})")
        if self.tolerance_warning:
            out.append(f"  warning: {self.tolerance_warning}")
        if series is not None and time.size > 1:
            with np.errstate(over="ignore", invalid="ignore"):
                e = series.kinetic + series.potential
                w = drive_work(time, series.power)[1]
                work = float(w[-1]) if w.size else 0.0
                change = float(e[-1] - e[0])
                rest = change - work
            out += [
                "  energy balance from the first position to the last:",
                f"    T + V: {number(float(e[0]), energy)} -> {number(float(e[-1]), energy)} "
                f"(change {number(change, energy)})",
                f"    work of the driven inputs (trapezoidal rule over the positions): {number(work, energy)}",
                f"    work of the other loads (motors, dampers, forces, tables), the remainder: {number(rest, energy)}",
            ]
        out.append("")
        return out
