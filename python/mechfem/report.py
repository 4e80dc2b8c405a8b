"""The interactive report: one self-contained HTML file ``<stem>.html`` that opens offline in any browser.

It holds the mechanism, animated on a canvas with play/pause and a position slider; every picture of the
deck as a chart whose cursor follows the slider; the limit positions, warnings and stop reason of the run;
and a table of the buffers. Everything (script, style, data as JSON) is inside the file: it loads nothing,
and its Content-Security-Policy forbids it to. Runs with more than :data:`MAX_REPORT_POSITIONS` positions
are subsampled evenly for the slider, the charts and the table; the report says so.

The page's own check, used by the tests: opened as ``<stem>.html#selftest`` it draws, moves the slider and
writes what it saw as JSON into ``<pre id="selftest">``.
"""

from __future__ import annotations

import html
import json
import math
from importlib import resources
from pathlib import Path
from typing import Any

import numpy as np

from mechfem.drawing import STYLES, MechanismDrawing
from mechfem.plots import (
    atomic_path,
    buffer_label,
    describe_buffer,
    hodograph,
    picture_title,
)
from mechfem.result import RunResult

#: Most positions the report shows (slider, charts and table); longer runs are subsampled evenly.
MAX_REPORT_POSITIONS = 2000


def _num(v: float) -> float | None:
    """A number for JSON: 6 significant digits; NaN and infinities become null."""
    v = float(v)
    if not math.isfinite(v):
        return None
    return float(f"{v:.6g}")


def _nums(values: Any) -> list[float | None]:
    return [_num(v) for v in np.asarray(values, dtype=np.float64).ravel()]


def report_positions(positions: int, limit: int | None = None) -> np.ndarray:
    """The 0-based positions the report shows: all of them, or ``limit`` (default :data:`MAX_REPORT_POSITIONS`)
    evenly spread ones, the first and last included."""
    if limit is None:
        limit = MAX_REPORT_POSITIONS
    if positions <= limit:
        return np.arange(positions)
    return np.unique(np.linspace(0, positions - 1, limit).round().astype(np.int64))


def _scene(result: RunResult, drawing: MechanismDrawing, frames: np.ndarray) -> dict[str, Any]:
    """The mechanism's shapes per frame; shapes that never move are sent once."""
    per_frame = [drawing.shapes(result.coords[k]) for k in frames]
    first = per_frame[0]
    data = [[_nums(s.data) for s in shapes] for shapes in per_frame]
    moving = [i for i in range(len(first)) if any(d[i] != data[0][i] for d in data)]
    return {
        "kinds": [s.kind for s in first],
        "roles": [s.role for s in first],
        "static": {str(i): data[0][i] for i in range(len(first)) if i not in moving},
        "moving": moving,
        "frames": [[d[i] for i in moving] for d in data],
        "bounds": [_num(v) for v in drawing.bounds(frames)],
    }


def _pictures(result: RunResult, frames: np.ndarray) -> list[dict[str, Any]]:
    out = []
    for index, pic in enumerate(result.storage.pictures):
        funcs = [p for p in pic.plots if p.keyword == "PLOTFUNC"]
        curves = [p for p in pic.plots if p.keyword != "PLOTFUNC"]
        panels = []
        if funcs:
            series = []
            for p in funcs:
                if p.a in result.buffers and p.b in result.buffers:
                    series.append(
                        {
                            "label": f"{p.b}: {buffer_label(result, p.b)}",
                            "x": _nums(result.buffers[p.a][frames]),
                            "y": _nums(result.buffers[p.b][frames]),
                        }
                    )
            xs = list(dict.fromkeys(p.a for p in funcs))
            ys = list(dict.fromkeys(p.b for p in funcs))
            panels.append(
                {
                    "type": "function",
                    "xlabel": "; ".join(buffer_label(result, b) for b in xs),
                    "ylabel": buffer_label(result, ys[0]) if len(ys) == 1 else "value of the buffers in the legend",
                    "series": series,
                    "hodographs": [],
                }
            )
        if curves:
            series = []
            hodos = []
            for p in curves:
                if p.keyword == "PLOTCURV" and p.a in result.buffers and p.b in result.buffers:
                    series.append(
                        {
                            "label": f"{describe_buffer(result, result.storage.buffer(p.b))} against "
                            f"{describe_buffer(result, result.storage.buffer(p.a))}",
                            "x": _nums(result.buffers[p.a][frames]),
                            "y": _nums(result.buffers[p.b][frames]),
                        }
                    )
                elif p.keyword == "PLOTHODO":
                    h = hodograph(result, p.a, p.b)
                    nan = np.full(result.positions, np.nan)
                    vx, vy = result.kx1.get(p.a, nan), result.kx1.get(p.b, nan)
                    hodos.append(
                        {
                            "label": f"path of (x{p.a}, y{p.b})",
                            "arrows_label": f"(dx{p.a}, dy{p.b}) / d input 1, drawn x {h.scale:.3g}",
                            "x": _nums(h.x[frames]),
                            "y": _nums(h.y[frames]),
                            "vx": _nums(vx[frames]),
                            "vy": _nums(vy[frames]),
                            "at": [int(k) for k in h.at],
                            "ax": _nums(h.x[h.at]),
                            "ay": _nums(h.y[h.at]),
                            "avx": _nums(h.vx),
                            "avy": _nums(h.vy),
                            "scale": _num(h.scale),
                        }
                    )
            labels = [p for p in curves if p.keyword == "PLOTCURV"]
            panels.append(
                {
                    "type": "curve",
                    "xlabel": "; ".join(buffer_label(result, p.a) for p in labels) if labels else "x",
                    "ylabel": "; ".join(buffer_label(result, p.b) for p in labels) if labels else "y",
                    "series": series,
                    "hodographs": hodos,
                }
            )
        out.append({"title": picture_title(result, index).replace("\n", " "), "panels": panels})
    return out + _dynamics_pictures(result, frames)


def _dynamics_pictures(result: RunResult, frames: np.ndarray) -> list[dict[str, Any]]:
    """A DYN deck's report always shows the drive forces and the energies, against input 1 for one input and
    against time for several."""
    dyn = result.dynamic
    if dyn is None or dyn.drive.shape[1] == 0:
        return []
    nd = dyn.drive.shape[1]
    x, xlabel = (dyn.inputs[:, 0], "input 1") if nd == 1 else (result.time, "time")

    def panel(ylabel: str, series: list[tuple[str, Any]]) -> dict[str, Any]:
        return {
            "type": "function",
            "xlabel": xlabel,
            "ylabel": ylabel,
            "series": [{"label": label, "x": _nums(x[frames]), "y": _nums(y[frames])} for label, y in series],
            "hodographs": [],
        }

    drives = [(f"drive of input {j + 1}", dyn.drive[:, j]) for j in range(nd)]
    energies = [
        ("kinetic energy T", dyn.kinetic),
        ("potential energy V", dyn.potential),
        ("T + V", dyn.kinetic + dyn.potential),
    ]
    return [
        {"title": f"drive force or torque against {xlabel}", "panels": [panel("drive force or torque", drives)]},
        {"title": f"energies against {xlabel}", "panels": [panel("energy", energies)]},
        {"title": f"drive power against {xlabel}", "panels": [panel("drive power", [("power", dyn.power)])]},
    ]


def report_data(result: RunResult) -> dict[str, Any]:
    """Everything the page shows, as plain JSON-ready data."""
    from mechfem import __version__

    frames = report_positions(result.positions)
    drawing = MechanismDrawing(result.model, result.coords)
    hodos = [p for pic in result.storage.pictures for p in pic.plots if p.keyword == "PLOTHODO"]
    traces = []
    for p in {(p.a, p.b): p for p in hodos}.values():
        h = hodograph(result, p.a, p.b)
        nan = np.full(result.positions, np.nan)
        traces.append(
            {
                "x": _nums(h.x[frames]),
                "y": _nums(h.y[frames]),
                "vx": _nums(result.kx1.get(p.a, nan)[frames]),
                "vy": _nums(result.kx1.get(p.b, nan)[frames]),
                "scale": _num(h.scale),
            }
        )
    subsampled = len(frames) < result.positions
    note = None
    if subsampled:
        every = (result.positions - 1) / max(len(frames) - 1, 1)
        note = (
            f"The run has {result.positions} positions; the slider, the charts and the table show {len(frames)} of "
            f"them, evenly spread (about every {every:.3g}th position)."
        )
    buffers = [
        {
            "number": b.number,
            "label": b.label(),
            "what": describe_buffer(result, b),
            "values": _nums(result.buffers[b.number][frames]),
        }
        for b in result.storage.buffers
    ]
    inputs = [b for b in buffers if b["label"].startswith("BUFINP")]
    report = result.report
    limits = [{"kind": x.kind, "after": x.after, "text": x.describe(report.input_names)} for x in report.limits]
    return {
        "deck": str(result.deck),
        "stem": result.deck.stem,
        "version": __version__,
        "positions": result.positions,
        "asked": report.steps + 1,
        "frames": [int(k) for k in frames],
        "time": _nums(result.time[frames]),
        "inputs": [b["number"] for b in inputs],
        "subsample_note": note,
        "styles": {
            role: {"edge": s.edge, "width": s.width, "fill": s.fill, "dash": s.dash, "layer": s.layer}
            for role, s in STYLES.items()
        },
        "scene": _scene(result, drawing, frames),
        "drawing_notes": drawing.notes,
        "traces": traces,
        "pictures": _pictures(result, frames),
        "buffers": buffers,
        "limits": limits,
        "warnings": list(report.warnings),
        "stop": report.stop_reason(),
        "animate": result.storage.animate,
    }


def render_report(result: RunResult) -> str:
    """The report page as text."""
    template = resources.files("mechfem").joinpath("report_template.html").read_text(encoding="utf-8")
    data = json.dumps(report_data(result), separators=(",", ":"), allow_nan=False)
    # Inside <script> the only sequence to avoid is "</"; JSON allows "<\/" for it.
    data = data.replace("</", "<\\/")
    title = html.escape(f"{result.deck.stem} - mechfem report")
    return template.replace("{{TITLE}}", title).replace("{{DATA}}", data)


def report_file(result: RunResult, outdir: Path) -> Path:
    """Where the report goes: ``<outdir>/<stem>.html``."""
    return outdir / f"{result.deck.stem}.html"


def write_report(result: RunResult, outdir: Path) -> Path:
    """Writes ``<stem>.html`` into ``outdir`` (created if needed); returns its path."""
    outdir.mkdir(parents=True, exist_ok=True)
    path = report_file(result, outdir)
    text = render_report(result)
    with atomic_path(path) as tmp:
        tmp.write_text(text, encoding="utf-8")
    return path
