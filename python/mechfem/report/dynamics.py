"""What the interactive report adds for a DYN deck: the drives' and motors' power, the energy balance, the pin
forces as arrows on the mechanism and the shaking force as a polar plot.

* **Power of each input.** ``drive_j x qdot_j``: the drive force or torque of input j (``BUFDRV``; for an input a
  ``MOTOR`` moves in DYN SIM, the motor's torque ``T0 (1 - qdot / w0)``) times the input's speed. In DYN ANA their
  sum is the drives' power ``BUFPOW``; in DYN SIM ``BUFPOW`` is the power of the input rows' stresses, which for an
  input moved by the forces is only the rounding of the equations of motion, so the report charts the motor's.
* **The energy balance.** From the first position to each: the change of T + V against the work done on the inputs
  (the integral of ``sum_j drive_j qdot_j``) and by the other loads (forces, loads, tables, dampers and brakes, and a
  motor on a prescribed input), and the residual ``change - work``. The core records the loads' power
  (``loadpow``) and the inputs' speeds (``vin``) with every DYN deck's run; the work is their integral over time by
  Simpson's rule on the positions, so the residual is the quadrature's error plus that of the run (the integrator's
  and the Newton tolerance's).
* **Pin forces.** Every ``BUFPIN e i j`` the deck records (the force element e exerts on the pin at co-ordinates i,
  j) and every frame reaction recorded for both co-ordinates of a fixed point (``BUFREA``): arrows at the pins, all
  on one scale (the longest over the whole motion a quarter of the mechanism's size), at the slider's position.
* **Shaking.** ``BUFSHAKE``: the locus of the shaking force vector over the motion (x against y, equal scales, the
  vector drawn from the origin at the slider's position) and the shaking moment against the dynamics' axis.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np
import numpy.typing as npt
from scipy.integrate import cumulative_simpson

from mechfem.results.designer import points_of
from mechfem.results.labels import Label, point_name, with_unit

if TYPE_CHECKING:
    from mechfem.report.charts import Columns
    from mechfem.results.result import RunResult

FloatArray = npt.NDArray[np.float64]

#: The longest pin-force arrow over the whole motion, as a share of the diagonal of the mechanism's bounding box.
ARROW_SHARE = 0.25


def input_power(result: RunResult) -> FloatArray | None:
    """``drive_j x qdot_j`` of every input (positions x inputs): the power of its drive, or of the motor that moves
    it in DYN SIM; None without the inputs' speeds (a deck's run has them in its ``vin`` block, a named model's run
    as the velocities of its inputs)."""
    dyn = result.dynamic
    if dyn is None:
        return None
    if "vin" in result._layout:
        speed = np.asarray(result._block("vin"), dtype=np.float64)
    elif result.named and result.numbering.inputs:
        speed = np.column_stack([result.velocity(phi) for phi in result.numbering.inputs])
    else:
        return None
    return np.asarray(dyn.drive * speed * _radians_per_unit(result), dtype=np.float64)


def _radians_per_unit(result: RunResult) -> FloatArray:
    """What each input's speed is multiplied by so that drive x speed is a power: a torque is per radian, so the
    speed of an angular input given in degrees is turned into radians; any other input's speed stays as it is."""
    from mechfem.results.labels import ANGLE, row_unit

    model = result.model
    per_degree = math.pi / 180.0 if model.units.get("angle") == "deg" else 1.0
    return np.array(
        [per_degree if row_unit(model, model.prescribed[d - 1]) == ANGLE else 1.0 for d in model.dofs],
        dtype=np.float64,
    )


@dataclass(frozen=True)
class EnergyBalance:
    """The energy balance from the first position to each, positions long (NaN where a term is not known)."""

    time: FloatArray
    change: FloatArray
    """(T + V) minus its value at the first position."""
    inputs_work: FloatArray
    """Work done on the inputs by their drives or motors (the integral of ``sum_j drive_j qdot_j``)."""
    loads_work: FloatArray
    """Work of the other loads: forces, loads, tables, dampers and brakes (negative where they dissipate)."""

    @property
    def residual(self) -> FloatArray:
        """``change - inputs_work - loads_work``: zero up to the quadrature's and the run's errors."""
        return np.asarray(self.change - self.inputs_work - self.loads_work, dtype=np.float64)

    def scale(self) -> float:
        """The largest magnitude of the balance's terms: what the residual is small against."""
        terms = np.concatenate([self.change, self.inputs_work, self.loads_work])
        terms = terms[np.isfinite(terms)]
        return float(np.max(np.abs(terms))) if terms.size else 0.0

    def relative_residual(self) -> float:
        """The largest |residual| over :meth:`scale` (0 when nothing moves; NaN when no residual is known)."""
        r = self.residual[np.isfinite(self.residual)]
        if not r.size:
            return float("nan")
        scale = self.scale()
        return float(np.max(np.abs(r)) / scale) if scale > 0.0 else 0.0


def _work(time: FloatArray, power: FloatArray) -> FloatArray:
    """The integral of ``power`` over time from the first position to each, by Simpson's rule on the positions
    (scipy's ``cumulative_simpson``: the power is smooth between outputs, and on the supply mechanism's run-up the
    balance's residual is 2.4e-5 of its largest term with it, 1.1e-4 with the trapezoidal rule); NaN from the first
    position where the power or the time is not known."""
    out = np.full(time.shape, np.nan)
    known = np.isfinite(power) & np.isfinite(time)
    n = int(np.argmin(known)) if not known.all() else known.size
    if n == 1:
        out[0] = 0.0
    elif n > 1:
        with np.errstate(over="ignore", invalid="ignore"):
            out[:n] = cumulative_simpson(power[:n], x=time[:n], initial=0.0)
    return out


def energy_balance(result: RunResult) -> EnergyBalance | None:
    """The energy balance of a run with masses or loads (None without the loads' power or the inputs' speeds)."""
    dyn = result.dynamic
    inputs = input_power(result)
    if dyn is None or inputs is None or "loadpow" not in result._layout:
        return None
    time = np.asarray(result.time, dtype=np.float64)
    loads = np.asarray(result._block("loadpow"), dtype=np.float64).reshape(-1)
    on_inputs = inputs.sum(axis=1)
    total = dyn.kinetic + dyn.potential
    # The stresses' power and the loads' power make d(T + V)/dt; the inputs' share is charted on its own.
    other = dyn.power + loads - on_inputs
    return EnergyBalance(time, total - total[0], _work(time, on_inputs), _work(time, other))


def energy_card(result: RunResult, cols: Columns, xkey: str, against: str) -> dict[str, Any] | None:
    """The energy balance as a card: the change of T + V and the two works in one chart, the residual in one below."""
    from mechfem.report.charts import function_charts

    bal = energy_balance(result)
    if bal is None:
        return None
    terms = [
        cols.add("dE", "change of T+V", "energy", "energy", bal.change, text="T + V minus its first value"),
        cols.add(
            "Win", "work on the inputs", "energy", "energy", bal.inputs_work, text="work of the drives and motors"
        ),
        cols.add(
            "Wload", "work of the loads", "energy", "energy", bal.loads_work, text="work of forces, loads and dampers"
        ),
    ]
    c_unit = cols.table[terms[0]]["unit"]
    res = cols.add("Eres", "residual", "energy", "residual", bal.residual, text="change of T+V minus the work done")
    return {
        "title": f"energy balance against {against}",
        "picture": None,
        "note": f"largest residual {bal.relative_residual():.2g} of the largest term",
        "charts": [{**c, "ylabel": with_unit("energy", c_unit)} for c in function_charts(xkey, terms, cols)]
        + function_charts(xkey, [res], cols),
    }


@dataclass(frozen=True)
class PinForce:
    """One force the report draws as an arrow: where (the pin's co-ordinates) and what (two buffers)."""

    name: str
    """``crank on A``, ``reaction at A0``: in the chart's legend."""
    short: str
    """The pin's name, by its arrow."""
    x: int
    """The pin's x co-ordinate (1-based); y is its own."""
    y: int
    fx: Label
    fy: Label


def pin_forces(result: RunResult, labels: dict[int, Label]) -> list[PinForce]:
    """The pin forces the deck records (``BUFPIN``), then the frame's reactions at fixed points whose x and y it both
    records (``BUFREA``), in the order of the STORAGE block."""
    out: list[PinForce] = []
    pins: dict[tuple[int, ...], list[int]] = {}
    reactions: dict[int, int] = {}
    for b in result.storage.buffers:
        if b.keyword == "BUFPIN":
            pins.setdefault(tuple(b.args), []).append(b.number)
        elif b.keyword == "BUFREA" and b.args:
            reactions.setdefault(b.args[0], b.number)
    elements = list(result.model.elements)
    for (e, x, y), numbers in pins.items():
        first = min(numbers)
        if first in labels and first + 1 in labels:
            el = elements[e - 1] if 1 <= e <= len(elements) else None
            by = el.name if el is not None and el.name else f"element {e}"
            pin = point_name(result, x, y)
            out.append(PinForce(f"{by} on {pin}", pin, x, y, labels[first], labels[first + 1]))
    done: set[tuple[int, int]] = set()
    for element in elements:
        for x, y in points_of(element):
            fixed = not result.model.coordinates[x - 1].moving and not result.model.coordinates[y - 1].moving
            if fixed and x in reactions and y in reactions and (x, y) not in done:
                done.add((x, y))
                bx, by_ = reactions[x], reactions[y]
                if bx in labels and by_ in labels:
                    pin = point_name(result, x, y)
                    out.append(PinForce(f"reaction at {pin}", pin, x, y, labels[bx], labels[by_]))
    return out


def _magnitudes(result: RunResult, forces: list[PinForce]) -> FloatArray:
    """|F| of every force at every position (positions x forces)."""
    return np.column_stack([np.hypot(result.buffers[f.fx.number], result.buffers[f.fy.number]) for f in forces]).astype(
        np.float64
    )


def pin_force_card(result: RunResult, labels: dict[int, Label], cols: Columns, size: float) -> dict[str, Any] | None:
    """The pin forces as arrows on the mechanism at the slider's position, one scale for all (``size``: the diagonal
    of the mechanism's bounding box), with where the largest occurs among the report's positions."""
    forces = pin_forces(result, labels)
    if not forces:
        return None
    shown = cols.frames
    mags = _magnitudes(result, forces)[shown]
    known = np.where(np.isfinite(mags), mags, -1.0)
    largest = float(known.max())
    if largest <= 0.0:
        return None
    frame, which = np.unravel_index(int(np.argmax(known)), known.shape)
    scale = ARROW_SHARE * size / largest
    unit = cols.shown(forces[0].fx.unit)
    # Each pin's path is a curve of the chart; its force is drawn at the slider's position.
    arrows = [
        {
            "name": f.name,
            "short": f.short,
            "x": cols.coordinate(result, f.x),
            "y": cols.coordinate(result, f.y),
            "fx": cols.buffer(result, f.fx),
            "fy": cols.buffer(result, f.fy),
        }
        for f in forces
    ]
    position = int(shown[int(frame)]) + 1
    length = cols.shown("length")
    return {
        "title": "pin forces at the slider's position",
        "picture": None,
        "note": f"arrows drawn at {scale:.3g} {length} per {unit or 'unit of force'}; the largest, "
        f"{largest:.4g} {unit} ({forces[int(which)].name}), is at position {position}",
        "jump": {"frame": int(frame), "text": f"go to position {position}, the largest pin force"},
        "charts": [
            {
                "type": "xy",
                "equal": True,
                "mechanism": True,
                "mechanism_alpha": 0.7,
                "height": 560,
                "xlabel": with_unit("x", length),
                "ylabel": with_unit("y", length),
                "series": arrows,
                "force_scale": scale,
                "force_unit": unit,
            }
        ],
    }


def shaking_card(
    result: RunResult, labels: dict[int, Label], cols: Columns, xkey: str, against: str
) -> dict[str, Any] | None:
    """The shaking force's locus (a polar plot: the vector from the origin, equal scales) and the shaking moment
    against ``xkey``, from the deck's ``BUFSHAKE``."""
    from mechfem.report.charts import function_charts

    first = min((b.number for b in result.storage.buffers if b.keyword == "BUFSHAKE"), default=None)
    if first is None or any(first + k not in labels for k in range(3)):
        return None
    fx, fy, m = (cols.buffer(result, labels[first + k]) for k in range(3))
    polar = {
        "type": "xy",
        "equal": True,
        "origin": True,
        "xlabel": cols.table[fx]["axis"],
        "ylabel": cols.table[fy]["axis"],
        "series": [{"x": fx, "y": fy, "name": "shaking force"}],
    }
    return {
        "title": f"shaking force (polar) and moment against {against}",
        "picture": None,
        "charts": [polar, *function_charts(xkey, [m], cols)],
    }
