"""What a designer reads from a run beside the motion: transmission angles, the force each element exerts on each
of its pins, the shaking force and moment on the frame, and how far each input can sweep.

The core records them (deck buffers ``BUFTRA e1 e2 b``, ``BUFPIN e i j b``, ``BUFSHAKE b``; a named model's dynamic
run records every pin force and the shaking in its ``pin`` and ``shaking`` blocks); this module finds them by name
in a :class:`~mechfem.RunResult` and writes the print file's lines on them (docs/designer-outputs.md).
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

import numpy as np
import numpy.typing as npt

from mechfem.model.catalogue import SLOTS

if TYPE_CHECKING:
    from mechfem.model.echo import EchoElement

FloatArray = npt.NDArray[np.float64]

#: Element types with a first side: BIN, TR2 (P->Q) and HLF, TR1 (the angle co-ordinate's direction).
FRAMED = ("BIN", "TR2", "HLF", "TR1")


def element(result: Any, ref: object) -> EchoElement:
    """The element ``ref`` names: its deck number (1, 2, ...), its name, or for a named model the element itself."""
    elements: list[EchoElement] = list(result.model.elements)
    if isinstance(ref, int) and not isinstance(ref, bool):
        if 1 <= ref <= len(elements):
            return elements[ref - 1]
        raise KeyError(f"element {ref} does not exist: the elements are numbered 1..{len(elements)}")
    name = getattr(ref, "name", ref)
    for e in elements:
        if e.name is not None and e.name == name:
            return e
    if result.named:
        for k, e in enumerate(result.numbering.elements):
            if e is ref or getattr(e, "name", None) == name:
                return elements[k]
    known = ", ".join(repr(e.name) for e in elements if e.name) or "none; give the element's number"
    raise KeyError(f"{ref!r} is no element of this model (named elements: {known})")


def points_of(e: EchoElement) -> list[tuple[int, int]]:
    """The points of element ``e`` as (x, y) deck numbers, in the order of its co-ordinates."""
    out, at = [], 0
    for slot in SLOTS[e.type]:
        if slot == "P":
            out.append((e.coords[at], e.coords[at + 1]))
            at += 2
        else:
            at += 1
    return out


def _point(result: Any, e: EchoElement, point: object) -> tuple[int, int]:
    t = result._target(point, "point", ("point",))
    xy = (t.numbers[0], t.numbers[1])
    pins = points_of(e)
    if xy not in pins:
        label = e.name or f"element {e.number}"
        raise KeyError(
            f"{t.name!r} is not a point of {label} ({e.type}): a pin force acts where the element meets a pin"
        )
    return xy


def _buffer(result: Any, keyword: str, args: tuple[int, ...], part: int = 0) -> FloatArray | None:
    """The deck buffer ``keyword args`` (its ``part``-th number), if the run recorded one."""
    for b in result.storage.buffers:
        if b.keyword == keyword and tuple(b.args) == args:
            return result.buffers.get(b.number + part)  # type: ignore[no-any-return]
    return None


def pin_force(result: Any, elem: object, point: object) -> FloatArray:
    """The force element ``elem`` exerts on the pin at ``point``, positions x 2 (x, y), in the model's force unit:
    its stresses and loads minus its inertia and weight (the pin is massless). At a frame pivot it is minus the
    element's share of the reaction."""
    result._dynamic_needed("pin forces")
    e = element(result, elem)
    x, y = _point(result, e, point)
    layout = result._layout
    if "pin" in layout:
        rows = [(k.number, px, py) for k in result.model.elements for px, py in points_of(k)]
        k = rows.index((e.number, x, y))
        return np.asarray(result._block("pin")[:, k, :], dtype=np.float64).copy()
    fx, fy = _buffer(result, "BUFPIN", (e.number, x, y)), _buffer(result, "BUFPIN", (e.number, x, y), 1)
    if fx is None or fy is None:
        raise KeyError(
            f"the run of {result.path} did not record the pin force of element {e.number} at co-ordinates {x} {y}: "
            f"add the buffer `BUFPIN {e.number} {x} {y} <number>` to its STORAGE block"
        )
    return np.column_stack([fx, fy])


def pin_forces(result: Any, point: object) -> dict[str, FloatArray]:
    """The force every element that meets at ``point`` exerts on it, by element name (or number)."""
    t = result._target(point, "point", ("point",))
    xy = (t.numbers[0], t.numbers[1])
    out: dict[str, FloatArray] = {}
    for e in result.model.elements:
        if xy in points_of(e):
            out[e.name or str(e.number)] = pin_force(result, e.number, point)
    if not out:
        raise KeyError(f"no element meets at {t.name!r}")
    return out


def shaking(result: Any) -> FloatArray:
    """Shaking force and moment on the frame, positions x 3 (x, y, moment about the origin): ``-sum m a_G`` and
    ``-sum (r_G x m a_G + J alpha)``, inertia only."""
    result._dynamic_needed("shaking forces")
    if "shaking" in result._layout:
        return np.asarray(result._block("shaking"), dtype=np.float64).copy()
    parts = [p for p in (_buffer(result, "BUFSHAKE", (), k) for k in range(3)) if p is not None]
    if len(parts) < 3:
        raise KeyError(f"the run of {result.path} did not record the shaking: add `BUFSHAKE <number>` to STORAGE")
    return np.column_stack(parts)


def _direction(e: EchoElement, coords: FloatArray) -> FloatArray:
    if e.type not in FRAMED:
        raise KeyError(f"element {e.number} is a {e.type}, which has no side to measure a transmission angle on")
    c = [i - 1 for i in e.coords]
    if e.type in ("HLF", "TR1"):
        beta = coords[:, c[2]]
        return np.column_stack([np.cos(beta), np.sin(beta)])
    return np.column_stack([coords[:, c[2]] - coords[:, c[0]], coords[:, c[3]] - coords[:, c[1]]])


def transmission_angle(result: Any, first: object, second: object, unit: str | None = None) -> FloatArray:
    """The angle between the first sides of two elements (P->Q of BIN and TR2, the angle co-ordinate of HLF and
    TR1) at every position, in [0, pi] (``unit="deg"``: degrees; default the model's angle unit)."""
    a, b = element(result, first), element(result, second)
    x = result.coords
    if not result.named:
        # The co-ordinates of a deck's run are in its own units: only the direction counts, but an angle
        # co-ordinate given in degrees must be turned into radians first.
        x = _radians(result, x)
    ua, ub = _direction(a, x), _direction(b, x)
    cross = ua[:, 0] * ub[:, 1] - ua[:, 1] * ub[:, 0]
    dot = ua[:, 0] * ub[:, 0] + ua[:, 1] * ub[:, 1]
    mu = np.arctan2(np.abs(cross), dot)
    wanted = unit or _angle_unit(result)
    return np.degrees(mu) if wanted == "deg" else mu


def _angle_unit(result: Any) -> str:
    units = getattr(result.model, "units", None)
    angle = getattr(units, "angle", None) if units is not None else None
    if isinstance(units, dict):
        angle = units.get("angle")
    return "deg" if angle == "deg" else "rad"


def _radians(result: Any, x: FloatArray) -> FloatArray:
    if _angle_unit(result) != "deg":
        return x
    out = x.copy()
    for e in result.model.elements:
        if e.type in ("HLF", "TR1"):
            out[:, e.coords[2] - 1] = np.radians(x[:, e.coords[2] - 1])
    return out


# -- the print file


def _where(result: Any, k: int) -> str:
    names = [str(n) for n in getattr(result.report, "input_names", [])] or [
        f"input{j + 1}" for j in range(result.inputs.shape[1])
    ]
    values = ", ".join(f"{n} = {v:.6g}" for n, v in zip(names, result.inputs[k], strict=False))
    return f"position {k + 1} (time {result.time[k]:.6g}{', ' + values if values else ''})"


def transmission_lines(result: Any) -> list[str]:
    """For every BUFTRA buffer: its worst deviation from a right angle over the motion and where."""
    out: list[str] = []
    for b in result.storage.buffers:
        if b.keyword != "BUFTRA" or b.number not in result.buffers:
            continue
        values = np.asarray(result.buffers[b.number], dtype=np.float64)
        deg = values if b.unit == "deg" else np.degrees(values)
        dev = np.abs(deg - 90.0)
        if not np.any(np.isfinite(dev)):
            continue
        k = int(np.nanargmax(dev))
        label = b.name or f"buffer {b.number}"
        lo, hi = float(np.nanmin(deg)), float(np.nanmax(deg))
        out.append(
            f"  {label} (buffer {b.number}, elements {b.args[0]} and {b.args[1]}): between {lo:.4g} and {hi:.4g} deg; "
            f"worst deviation from 90 deg {dev[k]:.4g} deg (mu = {deg[k]:.4g} deg) at {_where(result, k)}"
        )
    return ["TRANSMISSION ANGLES", *out, ""] if out else []


def sweep_lines(result: Any) -> list[str]:
    """For every input: the range it can sweep when limit positions bound it (rocking between the located limits),
    or a full turn when an angle input went all the way round."""
    from mechfem.results.result_tables import NotRecordedError

    limits = result.report.located_limits
    try:
        inputs = result.inputs
    except NotRecordedError:
        # A deck's run records what its STORAGE asks for: without its inputs, the located limits alone tell.
        n = max((len(lim.inputs) for lim in limits), default=0)
        inputs = np.full((0, n), np.nan)
    names = list(getattr(result.report, "input_names", [])) or [f"input{j + 1}" for j in range(inputs.shape[1])]
    out: list[str] = []
    for j in range(inputs.shape[1]):
        name = names[j] if j < len(names) else f"input{j + 1}"
        at = sorted({round(float(lim.inputs[j]), 12) for lim in limits if j < len(lim.inputs)})
        q = inputs[:, j][np.isfinite(inputs[:, j])]
        if at:
            if len(at) >= 2:
                span = at[-1] - at[0]
                out.append(
                    f"  {name}: rocks between the limit positions at {at[0]:.6g} and {at[-1]:.6g} (range {span:.6g})"
                )
            else:
                lo, hi = (float(np.min(q)), float(np.max(q))) if q.size else (at[0], at[0])
                out.append(
                    f"  {name}: a limit position at {at[0]:.6g} bounds it (the run swept {lo:.6g} to {hi:.6g}); "
                    "the limit on the other side was not reached"
                )
        elif q.size and _is_angle_input(result, j) and float(np.ptp(q)) >= _turn(result) * (1 - 1e-9):
            out.append(f"  {name}: full turn (no limit position in {float(np.ptp(q)):.6g})")
    return ["INPUT SWEEP", *out, ""] if out else []


def _turn(result: Any) -> float:
    return 360.0 if _angle_unit(result) == "deg" else 2 * math.pi


def _is_angle_input(result: Any, j: int) -> bool:
    try:
        return bool(result._names.input(j).angle)
    except (KeyError, IndexError, TypeError, AttributeError):
        return False


def print_lines(result: Any) -> list[str]:
    """The print file's lines on transmission angles and input sweep ranges (none when there is nothing to say)."""
    return transmission_lines(result) + sweep_lines(result)


# -- the table of a dynamic run

#: The buffers of the dynamics (and the transmission angle) a deck's run adds to its table under their labels.
TABLED = ("BUFDRV", "BUFSIG", "BUFREA", "BUFPIN", "BUFSHAKE", "BUFEKIN", "BUFEPOT", "BUFPOW", "BUFTRA")


def dynamic_columns(result: Any) -> dict[str, FloatArray]:
    """The columns :meth:`~mechfem.RunResult.table` adds for a run with masses or loads: drive torques, stresses,
    reactions, pin forces, shaking, energies and power (a named model's run: all of them; a deck's run: those its
    buffers record, under their labels, with its transmission angles)."""
    return {k: v for k, (v, _) in _dynamic(result).items()}


def dynamic_units(result: Any) -> dict[str, str]:
    """The unit of each of :func:`dynamic_columns`, in the run's units ("" where the model gives none)."""
    return {k: u for k, (_, u) in _dynamic(result).items()}


def _dynamic(result: Any) -> dict[str, tuple[FloatArray, str]]:
    """:func:`dynamic_columns` with the unit of each."""
    from mechfem.results import labels

    layout = result._layout
    out: dict[str, tuple[FloatArray, str]] = {}
    if result.named and "drive" not in layout:
        return out
    if not result.named:
        names = {b.number: b.name for b in result.storage.buffers}
        for b in result.storage.buffers:
            if b.keyword in TABLED and b.number in result.buffers:
                out[names.get(b.number) or f"{b.keyword}{b.number}"] = (result.buffers[b.number].copy(), b.unit)
        return out
    model = result.model
    names_ = result._names

    def unit(words: str) -> str:
        return labels.display_unit(result, words)

    for j in range(len(model.dofs)):
        out[f"drive({names_.input(j).name})"] = (
            result._series("drive", j).copy(),
            unit(labels.stress_unit(labels.input_unit(result, j + 1))),
        )
    for r, row in enumerate(model.prescribed):
        label = getattr(row, "name", None) or f"row{r + 1}"
        if result.named:
            label = result.numbering.prescribed[r].name
        sigma = unit(labels.stress_unit(labels.row_dest_unit(result, r + 1)))
        out[f"sigma({label})"] = (result._series("sigma", r).copy(), sigma)
    for i, c in enumerate(model.coordinates):
        if not c.moving:
            reaction = unit(labels.stress_unit(labels.coordinate_unit(result, i + 1)))
            out[f"reaction({names_.coordinate(i + 1).name})"] = (result._series("reaction", i).copy(), reaction)
    pins = result._block("pin") if "pin" in layout else None
    if pins is not None:
        k = 0
        for e in model.elements:
            for x, y in points_of(e):
                point = _point_name(result, x, y)
                for c, axis in enumerate(("x", "y")):
                    out[f"pin({e.name or e.number},{point}).{axis}"] = (np.asarray(pins[:, k, c]).copy(), unit("force"))
                k += 1
    if "shaking" in layout:
        for c, axis in enumerate(("x", "y", "M")):
            words = "torque" if axis == "M" else "force"
            out[f"shaking.{axis}"] = (np.asarray(result._block("shaking")[:, c]).copy(), unit(words))
    out["Ekin"] = (result._series("ekin").copy(), unit("energy"))
    out["Epot"] = (result._series("epot").copy(), unit("energy"))
    out["power"] = (result._series("power").copy(), unit("power"))
    return out


def _point_name(result: Any, x: int, y: int) -> str:
    """The name of the point whose co-ordinates are ``x``, ``y`` (deck numbers): ``A`` for ``A.x``, ``A.y``, else
    both co-ordinates' names."""
    cx, cy = str(result._names.coordinate(x).name), str(result._names.coordinate(y).name)
    if cx.endswith(".x") and cy.endswith(".y") and cx[:-2] == cy[:-2]:
        return cx[:-2]
    return f"{cx},{cy}"
