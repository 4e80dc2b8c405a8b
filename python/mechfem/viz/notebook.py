"""How results show themselves in Jupyter: the HTML behind ``_repr_html_``.

* A :class:`~mechfem.RunResult`: a summary table (mechanism, positions, complete or why it stopped, limit
  positions, parameters of a study's variant), its outputs with their smallest and largest values and units, and
  the picture of :meth:`~mechfem.RunResult.plot` (the mechanism with the paths of its moving points beside the
  outputs) as an inline PNG.
* A :class:`~mechfem.RunResult` of a deck: the same summary, its buffers with their labels
  (:mod:`mechfem.results.labels`), extrema and units, and the mechanism at position 1 with the paths of its moving
  points as an inline SVG (:mod:`mechfem.viz.export`).
* A :class:`~mechfem.Study`: how many variants ran, how many are complete, the parameters and measures, and the
  first rows of its table.

Every name and text that comes from a model, a deck or an error is HTML-escaped. The pictures are data URIs, so
the HTML stands alone (a notebook saved as HTML keeps them).
"""

from __future__ import annotations

import base64
import html
import math
import weakref
from collections.abc import Iterable, Sequence
from typing import TYPE_CHECKING, Any

import numpy as np

from mechfem.results import labels
from mechfem.results.result import RunResult

if TYPE_CHECKING:
    from mechfem.studies.batch import Study

#: Rows of a study's table shown in a notebook; the rest are counted.
STUDY_ROWS = 10
#: Columns of a study's table shown; the rest are named.
STUDY_COLUMNS = 12

_TABLE = 'style="border-collapse:collapse;margin:0.3em 0"'
_CELL = 'style="border:1px solid #ccc;padding:2px 8px;text-align:{align}"'

# Jupyter asks an object for every representation it has (HTML and PNG), so a RunResult's picture is rendered once
# and kept while the RunResult lives.
_PNG_CACHE: weakref.WeakKeyDictionary[Any, bytes | None] = weakref.WeakKeyDictionary()


def esc(value: object) -> str:
    """``value`` as text, escaped for HTML (quotes too, so it is safe in attributes)."""
    return html.escape(str(value), quote=True)


def number(v: object) -> str:
    """A number for a table: 6 significant digits; NaN and infinities as words."""
    if isinstance(v, bool | np.bool_):
        return "yes" if v else "no"
    if isinstance(v, int | np.integer):
        return str(int(v))
    if isinstance(v, float | np.floating):
        f = float(v)
        if math.isnan(f):
            return "NaN"
        return f"{f:.6g}"
    return str(v)


def _cell(tag: str, text: str, align: str = "left") -> str:
    return f"<{tag} {_CELL.format(align=align)}>{text}</{tag}>"


def table(header: Sequence[str], rows: Iterable[Sequence[str]], numeric: Sequence[bool] | None = None) -> str:
    """An HTML table; ``header`` and ``rows`` are escaped here. ``numeric`` columns are right-aligned."""
    right = list(numeric) if numeric is not None else [False] * len(header)
    head = "".join(_cell("th", esc(h)) for h in header)
    body = [
        "<tr>"
        + "".join(_cell("td", esc(c), "right" if r else "left") for c, r in zip(row, right, strict=False))
        + "</tr>"
        for row in rows
    ]
    return f"<table {_TABLE}><thead><tr>{head}</tr></thead><tbody>{''.join(body)}</tbody></table>"


def fields(pairs: Sequence[tuple[str, str]]) -> str:
    """A two-column table of what and value (both escaped here)."""
    rows = "".join("<tr>" + _cell("th", esc(k)) + _cell("td", esc(v).replace("\n", "<br>")) + "</tr>" for k, v in pairs)
    return f"<table {_TABLE}><tbody>{rows}</tbody></table>"


def extrema(values: Any) -> tuple[str, str]:
    """The smallest and largest finite value as text (``–`` when there is none)."""
    v = np.asarray(values, dtype=np.float64)
    v = v[np.isfinite(v)]
    if v.size == 0:
        return "–", "–"
    return number(float(v.min())), number(float(v.max()))


def state(complete: bool, positions: int, asked: int, reason: str | None) -> str:
    """``complete``, or why the motion stopped (the report's paragraph, which says where)."""
    if complete:
        return "complete"
    return reason or f"stopped after position {positions} of {asked}"


def png_uri(png: bytes) -> str:
    return "data:image/png;base64," + base64.b64encode(png).decode("ascii")


def svg_uri(svg: str) -> str:
    return "data:image/svg+xml;base64," + base64.b64encode(svg.encode("utf-8")).decode("ascii")


def image(uri: str, alt: str, width: int, height: int) -> str:
    """An image that keeps its proportions within ``width`` x ``height`` pixels."""
    return f'<img src="{uri}" alt="{esc(alt)}" style="max-width:{width}px;max-height:{height}px;height:auto">'


def block(title: str, *parts: str) -> str:
    """The whole representation: a title (escaped here) and the parts (already HTML)."""
    return f'<div class="mechfem"><strong>{esc(title)}</strong>{"".join(parts)}</div>'


# -- a RunResult ----------------------------------------------------------------------------------------


def analysis_png(a: RunResult) -> bytes | None:
    """The picture of ``a`` (:func:`mechfem.viz.figures.result_png`), rendered once per RunResult."""
    try:
        return _PNG_CACHE[a]
    except (KeyError, TypeError):
        pass
    from mechfem.viz import figures

    png = figures.result_png(a)
    try:
        _PNG_CACHE[a] = png
    except TypeError:  # not weakly referenceable: render again next time
        pass
    return png


def analysis_outputs(a: RunResult) -> list[list[str]]:
    """One row per output: name, smallest value, largest value, unit."""
    by_dest = {r.dest: r for r in a.model.dependent}
    rows = []
    for k, row in enumerate(a.numbering.dependent, 1):
        lo, hi = extrema(a.value(row))
        core = by_dest.get(-k)
        unit = labels.row_unit(a.model, core) if core is not None else ""
        rows.append([row.name, lo, hi, unit])
    return rows


def analysis_html(a: RunResult) -> str:
    """The HTML of a :class:`~mechfem.RunResult` in a notebook."""
    report = a.report
    summary = [
        ("mechanism", a.mechanism.name),
        ("positions", str(a.positions)),
        ("state", state(a.complete, a.positions, report.steps + 1, a.stop_reason())),
        ("limit positions", _limits_text(a.limits, report.input_names)),
    ]
    if a.simulation is not None:
        summary.append(("simulation", "integrated by the forces (DYN SIM)"))
    elif a.dynamic:
        summary.append(("dynamics", "inverse dynamics of the prescribed motion"))
    if a.parameters:
        summary.append(("parameters", ", ".join(f"{k} = {number(v)}" for k, v in a.parameters.items())))
    warnings = a.warnings
    if warnings:
        summary.append(("warnings", "\n".join(warnings)))
    parts = [fields(summary)]
    outputs = analysis_outputs(a)
    if outputs:
        parts.append(table(["output", "min", "max", "unit"], outputs, [False, True, True, False]))
    png = analysis_png(a) if a.positions else None
    if png is not None:
        parts.append(f"<div>{image(png_uri(png), f'{a.mechanism.name}: the mechanism and its paths', 900, 600)}</div>")
    return block(f"Analysis of {a.mechanism.name}", *parts)


def _limits_text(limits: Sequence[Any], names: Sequence[str]) -> str:
    if not limits:
        return "none"
    return "\n".join(x.describe(names) for x in limits)


# -- a RunResult ----------------------------------------------------------------------------------------


def run_result_buffers(result: RunResult) -> list[list[str]]:
    """One row per buffer of the storage: number, name, smallest value, largest value, unit."""
    rows = []
    for number_, lab in labels.buffer_labels(result).items():
        values = result.buffers.get(number_)
        lo, hi = extrema(values) if values is not None else ("–", "–")
        rows.append([str(number_), lab.name, lo, hi, lab.unit])
    return rows


def run_result_svg(result: RunResult) -> str | None:
    """The mechanism at position 1 with the paths of its moving points as SVG, or None without a position."""
    from mechfem.viz import export

    if result.positions == 0:
        return None
    return export.svg_text(export.result_drawing(result, 1, True))


def run_result_html(result: RunResult) -> str:
    """The HTML of a deck's :class:`~mechfem.RunResult` in a notebook."""
    report = result.report
    summary = [
        ("deck", str(result.deck)),
        ("mode", result.model.mode),
        ("positions", str(result.positions)),
        ("state", state(report.complete, result.positions, report.steps + 1, report.stop_reason())),
        ("limit positions", _limits_text(report.located_limits, report.input_names)),
    ]
    if report.warnings:
        summary.append(("warnings", "\n".join(report.warnings)))
    parts = [fields(summary)]
    buffers = run_result_buffers(result)
    if buffers:
        parts.append(table(["buffer", "name", "min", "max", "unit"], buffers, [True, False, True, True, False]))
    svg = run_result_svg(result)
    if svg is not None:
        alt = f"{result.deck.stem}: the mechanism at position 1 and the paths of its moving points"
        parts.append(f"<div>{image(svg_uri(svg), alt, 600, 450)}</div>")
    return block(f"Run of {result.deck.name}", *parts)


# -- a Study --------------------------------------------------------------------------------------------


def study_html(study: Study) -> str:
    """The HTML of a :class:`~mechfem.Study` in a notebook: a summary and its first rows."""
    n = len(study)
    cols = study.columns
    ok = int(np.sum(cols["ok"])) if "ok" in cols else n
    complete = int(np.sum(cols["complete"])) if "complete" in cols else ok
    summary = [
        ("variants", str(n)),
        ("position 1 computed", f"{ok} of {n}"),
        ("every position computed", f"{complete} of {n}"),
        ("parameters", ", ".join(study.parameters) or "none"),
        ("measures", ", ".join(study.measures) or "none"),
    ]
    for m in study.measures[:4]:
        lo, hi = extrema(cols[m])
        summary.append((f"{m} (min to max)", f"{lo} to {hi}"))
    names = list(cols)
    shown = names[:STUDY_COLUMNS]
    numeric = [np.asarray(cols[c]).dtype.kind in "iufb" for c in shown]
    rows = [[number(cols[c][k]) for c in shown] for k in range(min(n, STUDY_ROWS))]
    parts = [fields(summary), table(shown, rows, numeric)]
    more = []
    if n > STUDY_ROWS:
        more.append(f"the first {STUDY_ROWS} of {n} rows")
    if len(names) > len(shown):
        more.append(f"{len(names) - len(shown)} more columns: {', '.join(names[len(shown) :])}")
    if more:
        parts.append(f"<div><em>{esc('; '.join(more))} (Study.to_pandas() has them all)</em></div>")
    return block(f"Study of {n} variant{'s' if n != 1 else ''}", *parts)


def result_png(result: RunResult) -> bytes | None:
    """A named model's run shows its picture; a deck's run shows its summary only (its pictures are the deck's)."""
    return analysis_png(result) if result.named else None


def result_html(result: RunResult) -> str:
    """The summary of a named model's run (:func:`analysis_html`) or of a deck's run (:func:`run_result_html`)."""
    return analysis_html(result) if result.named else run_result_html(result)
