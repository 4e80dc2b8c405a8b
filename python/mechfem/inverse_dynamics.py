"""What a DYN ANA or DYN SIM deck's run adds to its result: the mass and load model as compiled, the drive forces,
energies and power at every position, the figures a designer sizes a motor and a flywheel with, and what a
simulation's integrator did.

Numbers that name things are the deck's own (1-based, destinations signed).
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import numpy.typing as npt

FloatArray = npt.NDArray[np.float64]


@dataclass(frozen=True)
class DynamicsModel:
    """The DYNAMICS block as compiled: every item as a dict in deck numbering (``bodies``: element, mass, u, v,
    inertia; ``point_masses``: x, y, mass; ``inertias``: coord, inertia; ``forces``: x, y, fx, fy; ``loads``: dest,
    kind (LOAD, LOADFUNC, SPRING or MOTOR) and its numbers)."""

    gravity: tuple[float, float]
    bodies: list[dict[str, float]]
    point_masses: list[dict[str, float]]
    inertias: list[dict[str, float]]
    forces: list[dict[str, float]]
    loads: list[dict[str, Any]]

    @classmethod
    def from_core(cls, d: dict[str, Any]) -> DynamicsModel:
        g = d["gravity"]
        return cls(
            gravity=(float(g[0]), float(g[1])),
            bodies=list(d["bodies"]),
            point_masses=list(d["point_masses"]),
            inertias=list(d["inertias"]),
            forces=list(d["forces"]),
            loads=list(d["loads"]),
        )

    def lines(self) -> list[str]:
        """The echo of the masses and loads in the print file."""
        out = ["", "  masses and loads (DYNAMICS)"]
        if self.gravity != (0.0, 0.0):
            out.append(f"    GRAVITY   ({self.gravity[0]:.10g}, {self.gravity[1]:.10g})")
        for b in self.bodies:
            out.append(
                f"    MASS      element {int(b['element'])}: m {b['mass']:.10g}, centre (u, v) = "
                f"({b['u']:.10g}, {b['v']:.10g}), J {b['inertia']:.10g}"
            )
        for p in self.point_masses:
            out.append(f"    PMASS     point (x{int(p['x'])}, y{int(p['y'])}): m {p['mass']:.10g}")
        for i in self.inertias:
            out.append(f"    INERTIA   co-ordinate {int(i['coord'])}: J {i['inertia']:.10g}")
        for f in self.forces:
            out.append(f"    FORCE     point (x{int(f['x'])}, y{int(f['y'])}): ({f['fx']:.10g}, {f['fy']:.10g})")
        for ld in self.loads:
            out.append(f"    {ld['kind']:<9} eps({ld['dest']}): {_load_text(ld)}")
        return out


def _load_text(ld: dict[str, Any]) -> str:
    match ld["kind"]:
        case "LOAD":
            return f"constant {ld['value']:.10g}"
        case "LOADFUNC":
            return f"table of {len(ld['rows'])} rows, linear in time"
        case "SPRING":
            return f"stiffness {ld['k']:.10g}, free value {ld['e0']:.10g}, damping {ld['c']:.10g}"
        case _:
            return f"stall torque {ld['t0']:.10g}, no-load speed {ld['w0']:.10g}"


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


def number(v: float) -> str:
    """A summary number with ten digits; one that overflows a double (a sum or a difference of finite results) is
    said so instead of printed as an infinity."""
    return f"{v:.10g}" if math.isfinite(v) else "too large for a double"


def energy_fluctuation(time: FloatArray, power: FloatArray) -> float:
    """The largest fluctuation of the work the drives deliver about its mean rate: the energy a flywheel must
    absorb and give back to keep the drive at the mean power (NaN with fewer than two finite positions)."""
    t, work = drive_work(time, power)
    if t.size < 2 or t[-1] <= t[0]:
        return float("nan")
    with np.errstate(over="ignore", invalid="ignore"):
        excess = work - work[-1] * ((t - t[0]) / (t[-1] - t[0]))
        return float(excess.max() - excess.min())


def summary_lines(series: DynamicSeries, time: FloatArray) -> list[str]:
    """The print file's DYNAMICS section: the extreme drive forces and where they occur, the drives' work and mean
    power, the energy a flywheel must absorb, and the range of the kinetic and potential energy."""
    if series.drive.shape[0] == 0:
        return []
    out = ["DYNAMICS"]
    for j in range(series.drive.shape[1]):
        d = series.drive[:, j]
        ok = np.isfinite(d)
        if not ok.any():
            out.append(f"  drive of DOF {j + 1}: not known at any position (limit positions only)")
            continue
        k_max, k_min = int(np.nanargmax(d)), int(np.nanargmin(d))
        rms = root_mean_square(d[ok])
        out += [
            f"  drive of DOF {j + 1}: largest {d[k_max]:.10g} at position {k_max + 1} "
            f"(input {series.inputs[k_max, j]:.10g}),",
            f"    smallest {d[k_min]:.10g} at position {k_min + 1} (input {series.inputs[k_min, j]:.10g}), "
            f"root mean square {rms:.10g}",
        ]
    t, w = drive_work(time, series.power)
    if t.size > 1 and t[-1] > t[0]:
        work = float(w[-1])
        with np.errstate(over="ignore", invalid="ignore"):
            mean = work / float(t[-1] - t[0])
        out.append(f"  work of the drives: {number(work)}, mean drive power {number(mean)}")
        out.append(
            "  largest fluctuation of the drives' work about its mean (a flywheel's energy swing): "
            f"{number(energy_fluctuation(time, series.power))}"
        )
    for name, values in (("kinetic", series.kinetic), ("potential", series.potential)):
        v = values[np.isfinite(values)]
        if v.size:
            out.append(f"  {name} energy: from {v.min():.10g} to {v.max():.10g}")
    out.append("")
    return out


@dataclass(frozen=True)
class Simulation:
    """What the integrator of a DYN SIM run did."""

    method: str
    rtol: float
    atol: float
    steps: int
    """Steps accepted."""
    rejected: int
    """Steps rejected (error estimate too large, or no position found)."""
    evaluations: int
    """Evaluations of the equations of motion (each one Newton position)."""
    reached: float
    """The time the simulation reached."""
    jacobians: int = 0
    """Jacobians the implicit method computed (each ``2 nf + 1`` of the evaluations, nf the inputs moving under the
    forces)."""
    segments: list[tuple[str, float, float, int, int]] = field(default_factory=list)
    """Which method integrated which stretch: ``(method, from, to, steps, evaluations)`` in order."""
    event: tuple[int, float, float, list[float]] | None = None
    """Where STOPWHEN ended the simulation: ``(buffer, value, time, inputs)``; None when it did not."""
    tolerance_warning: str | None = None
    """Why ACCURACY and INTTOL conflict, if they do."""

    @classmethod
    def from_core(cls, d: dict[str, Any]) -> Simulation:
        warning = d.get("tolerance_warning")
        if warning:
            warnings.warn(warning, UserWarning, stacklevel=3)
        event = d.get("event")
        return cls(
            str(d["method"]),
            float(d["rtol"]),
            float(d["atol"]),
            int(d["steps"]),
            int(d["rejected"]),
            int(d["evaluations"]),
            float(d["reached"]),
            int(d.get("jacobians", 0)),
            [(str(m), float(a), float(b), int(s), int(e)) for m, a, b, s, e in d.get("segments", [])],
            None if event is None else (int(event[0]), float(event[1]), float(event[2]), [float(x) for x in event[3]]),
            None if warning is None else str(warning),
        )

    def lines(self, series: DynamicSeries | None, time: FloatArray) -> list[str]:
        """The print file's SIMULATION section: the integrator and its work, and the energy balance at the end."""
        out = [
            "SIMULATION",
            f"  integrator: {self.method}",
            f"  tolerances: relative {self.rtol:.3g}, absolute {self.atol:.3g}",
            f"  steps: {self.steps} accepted, {self.rejected} rejected; {self.evaluations} evaluations of the "
            "equations of motion",
            f"  time reached: {self.reached:.10g}",
        ]
        if self.jacobians:
            out.append(f"  Jacobians of the equations of motion: {self.jacobians}")
        if len(self.segments) > 1 or (self.segments and not self.method.startswith(self.segments[0][0])):
            out.append("  methods by stretch of time:")
            out += [
                f"    {method}: from {a:.10g} to {b:.10g}, {s} steps, {e} evaluations"
                for method, a, b, s, e in self.segments
            ]
        if self.event is not None:
            b, v, t, q = self.event
            at = ", ".join(f"{x:.10g}" for x in q)
            out.append(f"  stopped by STOPWHEN: buffer {b} crossed {v:.10g} at time {t:.10g} (inputs {at})")
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
                f"    T + V: {number(float(e[0]))} -> {number(float(e[-1]))} (change {number(change)})",
                f"    work of the driven inputs (trapezoidal rule over the positions): {number(work)}",
                f"    work of the other loads (motors, dampers, forces, tables), the remainder: {number(rest)}",
            ]
        out.append("")
        return out
