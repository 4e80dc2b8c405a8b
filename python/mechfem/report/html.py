"""The interactive report: one self-contained HTML file ``<stem>.html`` that opens offline in any browser.

It holds the mechanism, animated on a canvas with play/pause, a play speed and a position slider, its traced
paths each in a colour of its own; det(D^c) with every located limit position marked and listed; every picture
of the deck (or default charts) as uPlot charts with a readout under the pointer, zoom, a CSV of their numbers
and the slider's marker; the status of the run; and a table of the buffers. Everything (uPlot, the page's style
and scripts from ``report/assets/``, the data as JSON) is inside the file: it loads nothing, and its
Content-Security-Policy forbids it to. Runs with more than :data:`MAX_REPORT_POSITIONS` positions are
subsampled evenly for the slider, the charts and the table; the report says so. What is charted, with which
names and units, is worked out in :mod:`mechfem.report.charts`.

The page's own check, used by the tests: opened as ``<stem>.html#selftest`` it draws, moves the slider, clicks,
zooms, plays, and writes what it saw as JSON into ``<pre id="selftest">``.
"""

from __future__ import annotations

import html
import json
import re
from importlib import resources
from pathlib import Path
from typing import Any

import numpy as np

from mechfem._util.atomic import atomic_path
from mechfem.report.charts import (
    Columns,
    all_labels,
    limit_markers,
    main_axis,
    nums,
    page_cards,
    page_styles,
    paths,
)
from mechfem.results.designer import print_lines as designer_lines
from mechfem.results.result import RunResult
from mechfem.results.result_tables import run_units
from mechfem.viz.drawing import MechanismDrawing

#: Most positions the report shows (slider, charts and table); longer runs are subsampled evenly.
MAX_REPORT_POSITIONS = 2000


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
    data = [[nums(s.data) for s in shapes] for shapes in per_frame]
    moving = [i for i in range(len(first)) if any(d[i] != data[0][i] for d in data)]
    return {
        "kinds": [s.kind for s in first],
        "roles": [s.role for s in first],
        "static": {str(i): data[0][i] for i in range(len(first)) if i not in moving},
        "moving": moving,
        "frames": [[d[i] for i in moving] for d in data],
        "bounds": nums(drawing.bounds(frames)),
    }


def report_data(result: RunResult, optimisation: dict[str, Any] | None = None) -> dict[str, Any]:
    """Everything the page shows, as plain JSON-ready data; ``optimisation`` is a KIN OPT deck's section
    (:func:`mechfem.report.optimum_report.optimisation_section`)."""
    from mechfem._version import __version__

    frames = report_positions(result.positions)
    drawing = MechanismDrawing(result.model, result.coords)
    labels = all_labels(result)
    cols = Columns(frames, run_units(result))
    # The table's columns in the order of the buffers' numbers, whatever the order of the STORAGE lines.
    ordered = sorted(result.storage.buffers, key=lambda b: b.number)
    table = [cols.buffer(result, labels[b.number]) for b in ordered if b.number in labels]
    xkey = main_axis(result, labels, cols)
    det = cols.add("det", "det(D^c)", "", "det", result.det, text="det(D^c), the determinant of the dependent columns")
    scene = _scene(result, drawing, frames)
    x0, x1, y0, y1 = (v if v is not None else 0.0 for v in scene["bounds"])
    size = float(np.hypot(x1 - x0, y1 - y0))
    xkey, cards, _ = page_cards(result, labels, cols, xkey, size)
    subsampled = len(frames) < result.positions
    note = None
    if subsampled:
        every = (result.positions - 1) / max(len(frames) - 1, 1)
        note = (
            f"The run has {result.positions} positions; the slider, the charts and the table show {len(frames)} of "
            f"them, evenly spread (about every {every:.3g}th position)."
        )
    inputs = [f"b{b.number}" for b in result.storage.buffers if b.keyword == "BUFINP" and f"b{b.number}" in table]
    if np.any(result.time != 0.0):
        inputs.append(cols.add("time", "time", "s", "time", result.time))
    report = result.report
    return {
        "deck": str(result.deck),
        "stem": result.deck.stem,
        "version": __version__,
        "positions": result.positions,
        "asked": report.steps + 1,
        "frames": [int(k) for k in frames],
        "subsample_note": note,
        "position_columns": inputs,
        "styles": page_styles(),
        "scene": scene,
        "drawing_notes": drawing.notes,
        "designer": designer_lines(result),
        "paths": paths(result, cols),
        "det": {"x": xkey, "y": det, "limits": limit_markers(result, xkey)},
        "cards": cards,
        "table": table,
        "columns": cols.table,
        "warnings": list(report.warnings),
        "stop": report.stop_reason(),
        "animate": result.storage.animate,
        "optimisation": optimisation,
    }


#: The package files the page is made of, by the template's placeholder: the vendored uPlot chart library
#: (python/mechfem/report/vendor/uplot, MIT licence) and the page's own style and scripts.
PAGE_PARTS = {
    "UPLOT_CSS": "report/vendor/uplot/uPlot.min.css",
    "UPLOT_JS": "report/vendor/uplot/uPlot.iife.min.js",
    "PAGE_CSS": "report/assets/report.css",
    "CHARTS_JS": "report/assets/charts.js",
    "SCENE_JS": "report/assets/scene.js",
    "PAGE_JS": "report/assets/page.js",
    "OPT_JS": "report/assets/optimisation.js",
}


def _part(name: str) -> str:
    text = resources.files("mechfem").joinpath(name).read_text(encoding="utf-8")
    # Inlined into <script> or <style>, a file must not close the element early.
    if re.search(r"</(script|style)", text, re.I):
        raise ValueError(f"the report's part {name} contains a closing </script> or </style>")
    return text


def page_template(name: str) -> str:
    """The template of a page (the report's, the studio's) with the markup they share in place of its placeholders:
    ``{{HEAD}}`` (report/assets/head.html: the page's policy, its title, uPlot's and the page's style) and
    ``{{LIMITS}}`` (report/assets/limits.html: the panel of det(D^c) and the limit positions)."""
    files = resources.files("mechfem")
    text = files.joinpath(name).read_text(encoding="utf-8")
    for key, shared in (("HEAD", "head.html"), ("LIMITS", "limits.html")):
        part = files.joinpath(f"report/assets/{shared}").read_text(encoding="utf-8").rstrip("\n")
        text = text.replace("{{" + key + "}}", part, 1)
    return text


def render_report(result: RunResult, optimisation: dict[str, Any] | None = None) -> str:
    """The report page as text: the template with the scripts, the style and the data inlined."""
    template = page_template("report/template.html")
    data = json.dumps(report_data(result, optimisation), separators=(",", ":"), allow_nan=False)
    parts = {key: _part(name) for key, name in PAGE_PARTS.items()}
    parts["DATA"] = script_safe(data)
    parts["TITLE"] = html.escape(f"{result.deck.stem} - mechfem report")
    parts["CSP_MORE"] = ""
    # One pass, so that nothing inlined is searched for placeholders again.
    return re.sub(r"\{\{([A-Z_]+)\}\}", lambda m: parts[m.group(1)], template)


#: What a JSON text inlined in a <script> element must not hold as it is: ``<`` (it could close the element, ``</``,
#: or open a comment, ``<!--``, which changes how the browser finds the element's end), ``>`` and ``&`` with it, and
#: the line and paragraph separators. Each may stand only inside a JSON string, where its ``\\uXXXX`` escape reads
#: back as the same character.
_SCRIPT_UNSAFE: dict[int, str | int | None] = {ord(c): f"\\u{ord(c):04x}" for c in "<>&\u2028\u2029"}


def script_safe(data: str) -> str:
    """The JSON text ``data`` with every character of :data:`_SCRIPT_UNSAFE` escaped: it parses back equal, and
    inlined in a <script> element it holds no markup."""
    return data.translate(_SCRIPT_UNSAFE)


def report_file(result: RunResult, outdir: Path) -> Path:
    """Where the report goes: ``<outdir>/<stem>.html``."""
    return outdir / f"{result.deck.stem}.html"


def write_report(result: RunResult, outdir: Path, optimisation: dict[str, Any] | None = None) -> Path:
    """Writes ``<stem>.html`` into ``outdir`` (created if needed); returns its path."""
    return save_report(result, report_file(result, outdir), optimisation)


def save_report(result: RunResult, path: Path, optimisation: dict[str, Any] | None = None) -> Path:
    """Writes the report of ``result`` to the file ``path`` (its folder made if needed); returns the path."""
    path.parent.mkdir(parents=True, exist_ok=True)
    text = render_report(result, optimisation)
    with atomic_path(path) as tmp:
        tmp.write_text(text, encoding="utf-8")
    return path
