"""What the interactive report charts: named columns of values and the charts drawn from them.

Every quantity the page shows is a *column* (a buffer, det(D^c), the time, the position number, a co-ordinate,
a drive force...) with its name, unit and CSV header from :mod:`mechfem.results.labels`, sent once and referred to by
key. A *card* is one picture of the deck (or a default one) holding one or more charts; a chart draws columns against
one horizontal column (``function``), or as curves in the plane (``xy``). Quantities of different kind or unit
never share a vertical axis: a picture whose PLOTFUNC lines mix them becomes a stack of charts, one per kind.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from mechfem.model.units import Units
from mechfem.results.labels import (
    Label,
    axis_group,
    buffer_labels,
    coordinate_name,
    input_name,
    over,
    point_name,
    row_dest_unit,
    row_unit,
    shown,
    stress_unit,
    with_unit,
)
from mechfem.results.result import RunResult
from mechfem.viz.drawing import STYLES, points_of
from mechfem.viz.plots import hodograph, picture_title


def num(v: float) -> float | None:
    """A number for JSON: 6 significant digits; NaN and infinities become null."""
    v = float(v)
    if not math.isfinite(v):
        return None
    return float(f"{v:.6g}")


def nums(values: Any) -> list[float | None]:
    return [num(v) for v in np.asarray(values, dtype=np.float64).ravel()]


@dataclass
class Columns:
    """The columns of a report, by key, each sampled at the report's frames."""

    frames: np.ndarray
    units: Units = field(default_factory=Units)
    """The run's units, in which every column's unit is said."""
    table: dict[str, dict[str, Any]] = field(default_factory=dict)

    def shown(self, unit: str) -> str:
        """``unit`` (in the words of the unit algebra, or already said in the run's units) in the run's units."""
        return shown(unit, self.units)

    def add(
        self, key: str, name: str, unit: str, kind: str, values: Any, header: str | None = None, text: str = ""
    ) -> str:
        unit = self.shown(unit)
        if key not in self.table:
            self.table[key] = {
                "name": name,
                "unit": unit,
                "kind": kind,
                "axis": with_unit(name, unit),
                "header": with_unit(header or name, unit),
                "text": text or name,
                "values": self.rounded(np.asarray(values, dtype=np.float64)[self.frames]),
            }
        return key

    def rounded(self, values: np.ndarray) -> Any:
        """A column's values as the page is sent them (:func:`nums`)."""
        return nums(values)

    def buffer(self, result: RunResult, lab: Label) -> str:
        return self.add(
            f"b{lab.number}",
            lab.name,
            lab.unit,
            lab.kind,
            result.buffers[lab.number],
            f"{lab.number} {lab.name}",
            lab.text,
        )

    def coordinate(self, result: RunResult, i: int, unit: str = "length") -> str:
        return self.add(f"c{i}", coordinate_name(result, i), unit, "position", result.coords[:, i - 1])

    def derivative(self, result: RunResult, i: int, unit: str) -> str | None:
        """d x_i / d input 1, recorded for the co-ordinates a PLOTHODO names."""
        if i not in result.kx1:
            return None
        name = f"d{coordinate_name(result, i)}/d{input_name(result, 1)}"
        return self.add(f"k{i}", name, unit, "first order", result.kx1[i])

    def values(self, key: str) -> list[float | None]:
        return list(self.table[key]["values"])


def _monotonic(values: list[float | None]) -> bool:
    """Strictly increasing or strictly decreasing, with every value known."""
    if len(values) < 2 or any(v is None for v in values):
        return False
    d = np.diff(np.asarray(values, dtype=np.float64))
    return bool(np.all(d > 0) or np.all(d < 0))


def input_buffer(result: RunResult, labels: dict[int, Label], j: int = 1) -> Label | None:
    """The label of the first BUFINP buffer of input ``j``."""
    for b in result.storage.buffers:
        if b.keyword == "BUFINP" and b.args[:1] == [j]:
            return labels[b.number]
    return None


def main_axis(result: RunResult, labels: dict[int, Label], cols: Columns) -> str:
    """The horizontal column of the det(D^c) chart and of the default charts: input 1 when it moves one way
    through the run, else the time of a dynamics run, else the position number (free motion turns its input
    back)."""
    inp = input_buffer(result, labels)
    if inp is not None:
        key = cols.buffer(result, inp)
        if _monotonic(cols.values(key)):
            return key
    if result.model.mode.startswith("DYN"):
        time = cols.add("time", "time", "s", "time", result.time)
        if _monotonic(cols.values(time)):
            return time
    return cols.add("pos", "position", "", "position", np.arange(1, result.positions + 1, dtype=np.float64))


def function_charts(xkey: str, ys: list[str], cols: Columns) -> list[dict[str, Any]]:
    """The columns ``ys`` against ``xkey``, one chart per kind and unit (in order of first appearance)."""
    groups: dict[tuple[str, str], list[str]] = {}
    for y in ys:
        c = cols.table[y]
        groups.setdefault(axis_group(c["kind"], c["unit"]), []).append(y)
    charts = []
    for (kind, unit), members in groups.items():
        names = [cols.table[y]["name"] for y in members]
        ylabel = with_unit(", ".join(names), unit) if len(members) <= 3 else with_unit(kind, unit)
        chart: dict[str, Any] = {"ylabel": ylabel, "xlabel": cols.table[xkey]["axis"]}
        if _monotonic(cols.values(xkey)):
            chart.update(type="function", x=xkey, series=[{"y": y} for y in members])
        else:
            chart.update(type="xy", equal=False, series=[{"x": xkey, "y": y} for y in members])
        charts.append(chart)
    return charts


def _buffer_points(result: RunResult) -> list[tuple[int, int]]:
    """(x, y) co-ordinate numbers of every point of the mechanism."""
    out: list[tuple[int, int]] = []
    for e in result.model.elements:
        for px, py in points_of(e.type, e.coords):
            if (px + 1, py + 1) not in out:
                out.append((px + 1, py + 1))
    return out


def traced_points(result: RunResult) -> list[tuple[int, int]]:
    """The points whose paths the mechanism drawing traces: those a PLOTHODO names, then those whose x and y the
    deck records (BUFX0 buffers, as in a PLOTCURV of a coupler curve)."""
    out: list[tuple[int, int]] = []
    for pic in result.storage.pictures:
        for p in pic.plots:
            if p.keyword == "PLOTHODO" and (p.a, p.b) not in out:
                out.append((p.a, p.b))
    recorded = {b.args[0] for b in result.storage.buffers if b.keyword == "BUFX0" and b.args}
    for px, py in _buffer_points(result):
        moving = result.model.coordinates[px - 1].moving or result.model.coordinates[py - 1].moving
        if px in recorded and py in recorded and moving and (px, py) not in out:
            out.append((px, py))
    return out


def paths(result: RunResult, cols: Columns) -> list[dict[str, Any]]:
    """The traced points with their paths and, for PLOTHODO points, their first-order vectors."""
    out = []
    for ix, iy in traced_points(result):
        h = hodograph(result, ix, iy)
        out.append(
            {
                "name": point_name(result, ix, iy),
                "x": cols.coordinate(result, ix),
                "y": cols.coordinate(result, iy),
                "vx": cols.derivative(result, ix, _per_input(result, "length")),
                "vy": cols.derivative(result, iy, _per_input(result, "length")),
                "scale": num(h.scale),
            }
        )
    return out


def _per_input(result: RunResult, unit: str) -> str:
    """``unit`` per unit of input 1: ``length/rad`` for a crank."""
    if not result.model.dofs:
        return unit
    den = row_unit(result.model, result.model.prescribed[result.model.dofs[0] - 1])
    return f"{unit}/{den}" if den else unit


def _hodograph(result: RunResult, ix: int, iy: int, cols: Columns) -> dict[str, Any]:
    h = hodograph(result, ix, iy)
    return {
        "name": f"path of {point_name(result, ix, iy)}",
        "arrows": f"(d{coordinate_name(result, ix)}, d{coordinate_name(result, iy)})/d{input_name(result, 1)}, "
        f"drawn x {h.scale:.3g}",
        "x": cols.coordinate(result, ix),
        "y": cols.coordinate(result, iy),
        "vx": cols.derivative(result, ix, _per_input(result, "length")),
        "vy": cols.derivative(result, iy, _per_input(result, "length")),
        "at": [int(k) for k in h.at],
        "ax": nums(h.x[h.at]),
        "ay": nums(h.y[h.at]),
        "avx": nums(h.vx),
        "avy": nums(h.vy),
        "scale": num(h.scale),
    }


def picture_cards(result: RunResult, labels: dict[int, Label], cols: Columns) -> list[dict[str, Any]]:
    """One card per picture of the deck."""
    cards = []
    for index, pic in enumerate(result.storage.pictures):
        charts: list[dict[str, Any]] = []
        funcs = [p for p in pic.plots if p.keyword == "PLOTFUNC" and p.a in labels and p.b in labels]
        for xb in dict.fromkeys(p.a for p in funcs):
            xkey = cols.buffer(result, labels[xb])
            ys = [cols.buffer(result, labels[p.b]) for p in funcs if p.a == xb]
            charts += function_charts(xkey, list(dict.fromkeys(ys)), cols)
        hodos = [_hodograph(result, p.a, p.b, cols) for p in pic.plots if p.keyword == "PLOTHODO"]
        curves: dict[tuple[str, str], list[dict[str, str]]] = {}
        for p in pic.plots:
            if p.keyword == "PLOTCURV" and p.a in labels and p.b in labels:
                la, lb = labels[p.a], labels[p.b]
                curves.setdefault((la.base, lb.base), []).append(
                    {"x": cols.buffer(result, la), "y": cols.buffer(result, lb), "name": f"{lb.name} against {la.name}"}
                )
        if hodos:
            # Curves in the plane of the mechanism join the hodographs, over the mechanism drawn faintly.
            series = curves.pop(("length", "length"), [])
            charts.append(
                {
                    "type": "xy",
                    "equal": True,
                    "mechanism": True,
                    "xlabel": with_unit("x", cols.shown("length")),
                    "ylabel": with_unit("y", cols.shown("length")),
                    "series": series,
                    "hodographs": hodos,
                }
            )
        for (ux, uy), series in curves.items():
            xs = list(dict.fromkeys(cols.table[s["x"]]["name"] for s in series))
            ys = list(dict.fromkeys(cols.table[s["y"]]["name"] for s in series))
            charts.append(
                {
                    "type": "xy",
                    "equal": ux == uy,
                    "xlabel": with_unit(", ".join(xs), cols.shown(ux)),
                    "ylabel": with_unit(", ".join(ys), cols.shown(uy)),
                    "series": series,
                }
            )
        cards.append({"title": picture_title(result, index).replace("\n", " "), "picture": index + 1, "charts": charts})
    return cards


def default_card(result: RunResult, labels: dict[int, Label], cols: Columns, xkey: str) -> dict[str, Any] | None:
    """For a deck that asks for no picture: every recorded quantity against the main axis, one chart per kind."""
    ys = [cols.buffer(result, lab) for lab in labels.values() if lab.kind != "det" and f"b{lab.number}" != xkey]
    if not ys:
        return None
    return {
        "title": f"recorded quantities against {cols.table[xkey]['name']}",
        "picture": None,
        "charts": function_charts(xkey, ys, cols),
    }


def model_card(result: RunResult, cols: Columns) -> tuple[str, dict[str, Any]] | None:
    """For the run of a named model that records no buffers: its outputs and their first-order transfer functions
    against its first input, by the model's names and in its units; with the input's column key."""
    nb = result.numbering
    if not result.named or not nb.inputs:
        return None
    phi = nb.inputs[0]
    phi_unit = row_dest_unit(result, nb.row_dest[phi])
    x = cols.add(f"n:{phi.name}", phi.name, phi_unit, "input", result.input(phi))
    ys = []
    for r in nb.dependent:
        unit = row_dest_unit(result, nb.row_dest[r])
        ys.append(cols.add(f"n:{r.name}", r.name, unit, "position", result.value(r)))
        per = over(unit, phi_unit)
        ys.append(cols.add(f"n:{r.name}'", f"d{r.name}/d{phi.name}", per, "first order", result.value(r, 1, phi)))
    if not ys:
        return None
    return x, {"title": f"outputs against {phi.name}", "picture": None, "charts": function_charts(x, ys, cols)}


def limit_markers(result: RunResult, xkey: str) -> list[dict[str, Any]]:
    """Every located limit position: where the page's slider goes (0-based position) and where on the det chart."""
    report = result.report
    xs = np.asarray(_full(result, xkey), dtype=np.float64)
    out = []
    for lim in report.located_limits:
        k = min(max(lim.after - 1, 0), result.positions - 1)
        if lim.kind == "near_zero" or k + 1 >= result.positions:
            nxt = k
        else:
            nxt = k + 1
        if xkey.startswith("b") and _is_input(result, xkey) and lim.inputs:
            x = lim.inputs[0]
        elif nxt == k and lim.kind != "near_zero":
            # The motion stopped there: the limit lies half a step beyond the last position.
            x = xs[k] + 0.5 * (xs[k] - xs[k - 1]) if k > 0 else xs[k]
        else:
            x = 0.5 * (xs[k] + xs[nxt])
        out.append(
            {
                "kind": lim.kind,
                "position": k,
                "where": lim.where,
                "text": lim.describe(report.input_names),
                "x": num(x),
                "det": num(lim.det),
            }
        )
    return out


def _is_input(result: RunResult, key: str) -> bool:
    number = int(key[1:])
    return any(b.number == number and b.keyword == "BUFINP" for b in result.storage.buffers)


def _full(result: RunResult, key: str) -> np.ndarray:
    """A column at every position (the limits fall between positions the report may not show)."""
    if key == "time":
        return result.time
    if key == "pos":
        return np.arange(1, result.positions + 1, dtype=np.float64)
    if key.startswith("n:"):
        return result.input(key[2:])
    return result.buffers[int(key[1:])]


def dynamics_cards(
    result: RunResult, cols: Columns, labels: dict[int, Label] | None = None, size: float = 0.0
) -> list[dict[str, Any]]:
    """A DYN deck's report shows the drive forces (unless its own pictures chart them), the energies, the power of
    each input's drive or motor, the energy balance, the pin forces at the slider's position (``size``: the
    diagonal of the mechanism's bounding box, for the arrows' scale) and the shaking force and moment: against input
    1 for one input of DYN ANA and against time for several inputs or a simulation (:mod:`mechfem.report.dynamics`).
    """
    from mechfem.report import dynamics as rd

    dyn = result.dynamic
    if dyn is None or dyn.drive.shape[1] == 0:
        return []
    labels = labels if labels is not None else all_labels(result)
    nd = dyn.drive.shape[1]
    model = result.model
    simulated = result.simulation is not None
    if nd == 1 and not simulated:
        unit = row_unit(model, model.prescribed[model.dofs[0] - 1]) if model.dofs else ""
        xkey = cols.add("in1", input_name(result, 1), unit, "input", dyn.inputs[:, 0])
    else:
        xkey = cols.add("time", "time", "s", "time", result.time)
    drives = []
    for j in range(nd):
        unit = stress_unit(row_unit(model, model.prescribed[model.dofs[j] - 1])) if j < len(model.dofs) else ""
        drives.append(cols.add(f"drv{j + 1}", f"drive of {input_name(result, j + 1)}", unit, "force", dyn.drive[:, j]))
    energies = [
        cols.add("ekin", "T", "energy", "energy", dyn.kinetic, text="kinetic energy T"),
        cols.add("epot", "V", "energy", "energy", dyn.potential, text="potential energy V"),
        cols.add("etot", "T+V", "energy", "energy", dyn.kinetic + dyn.potential, text="T + V"),
    ]
    per_input = rd.input_power(result)
    if per_input is None:
        powers = [cols.add("power", "drive power", "power", "power", dyn.power)]
    else:
        # drive x speed per input: in DYN SIM the drive of an input a MOTOR moves is the motor's torque.
        powers = [
            cols.add(f"pin{j + 1}", f"power on {input_name(result, j + 1)}", "power", "power", per_input[:, j])
            for j in range(nd)
        ]
    # A simulation is a motion in time: its charts run against time, whatever its inputs do.
    against = "time" if nd > 1 or simulated else _input_words(result, 1)
    motor = any(ld.kind == "MOTOR" for ld in (model.dynamics.loads if model.dynamics else []))
    torque = "drive or motor force or torque" if motor else "drive force or torque"
    cards = [
        (f"energies against {against}", energies),
        (f"power of the {'drives and motors' if motor else 'drives'} against {against}", powers),
    ]
    # The drive torque a picture of the deck charts already is not charted a second time.
    if "BUFDRV" not in _charted_keywords(result):
        cards.insert(0, (f"{torque} against {against}", drives))
    out = [{"title": title, "picture": None, "charts": function_charts(xkey, keys, cols)} for title, keys in cards]
    extra = [
        rd.energy_card(result, cols, xkey, against),
        rd.pin_force_card(result, labels, cols, size),
        rd.shaking_card(result, labels, cols, xkey, against),
    ]
    return out + [card for card in extra if card is not None]


def _charted_keywords(result: RunResult) -> set[str]:
    """The buffer keywords whose quantities a picture of the deck charts (PLOTFUNC's ordinate)."""
    keyword = {b.number: b.keyword for b in result.storage.buffers}
    return {
        keyword[p.b] for pic in result.storage.pictures for p in pic.plots if p.keyword == "PLOTFUNC" and p.b in keyword
    }


def _input_words(result: RunResult, j: int) -> str:
    """``input 1`` for a deck, the model's own name for a named model's input."""
    name = input_name(result, j)
    return f"input {j}" if name == f"input{j}" else name


def all_labels(result: RunResult) -> dict[int, Label]:
    """Every buffer's label (the buffers the storage defines but the run did not record are left out)."""
    return {n: lab for n, lab in buffer_labels(result).items() if n in result.buffers}


def page_cards(
    result: RunResult, labels: dict[int, Label], cols: Columns, xkey: str, size: float
) -> tuple[str, list[dict[str, Any]], bool]:
    """The page's cards (the deck's pictures, the dynamics', and else the model's named input's card or a default
    one), with the column of the page's x axis and whether that is the model's named input (a model without
    buffers). The report's page and the studio's both show these."""
    cards = picture_cards(result, labels, cols) + dynamics_cards(result, cols, labels, size)
    named = model_card(result, cols) if not result.storage.buffers else None
    if named is not None:
        xkey, card = named
        return xkey, [card, *cards], True
    if not result.storage.pictures:
        default = default_card(result, labels, cols, xkey)
        cards = ([default] if default else []) + cards
    return xkey, cards, False


def page_styles() -> dict[str, dict[str, Any]]:
    """The drawing's styles by role, as the page draws them."""
    return {
        role: {"edge": s.edge, "width": s.width, "fill": s.fill, "dash": s.dash, "layer": s.layer}
        for role, s in STYLES.items()
    }
