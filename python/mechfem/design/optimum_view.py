"""An optimisation seen in Jupyter and on a page: the summary table of a :class:`mechfem.Optimum` (of a mechanism,
or of a ``KIN OPT`` deck's OPTIMISE block), and the chart of the objective per iteration.

The table holds every design variable by name with its unit, start and final value, then the objective at the
start and at the end, the iterations, the mechanism runs, the optimiser's verdict and, for a multi-start, the
fraction of starts that could be optimised. Every name is HTML-escaped. The chart is matplotlib's, the objective
on a logarithmic axis, iteration 0 being the start design.
"""

from __future__ import annotations

import html
import io
import math
import os
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

from mechfem.design.engine import Iteration
from mechfem.model.catalogue import form_dimension
from mechfem.model.parts import Coordinate, FormParameter, Row

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

    from mechfem.design.optimum import Optimum
    from mechfem.model.mechanism import Mechanism
    from mechfem.report.optimum_report import VariableRow


@dataclass(frozen=True)
class Summary:
    """What the table shows, whatever optimised."""

    title: str
    variables: list[tuple[str, str, float, float]]
    """``(name, unit, start, final)`` of every design variable ("" where it has no unit)."""
    start_objective: float
    objective: float
    iterations: int
    runs: int
    success: bool
    message: str
    method: str
    usable: float | None = None
    """The fraction of starts optimised (a multi-start's); None for one start."""


def variable_unit(mechanism: Mechanism, name: str) -> str:
    """The unit of the design variable ``name`` in the mechanism's units: its length unit (or "" where the model
    has none), its angle unit, or "" for a number without dimension (a gear ratio)."""
    try:
        obj = mechanism[name]
    except KeyError:
        return ""
    units = mechanism.units
    if isinstance(obj, Coordinate):
        kind = {"x": "length", "y": "length", "angle": "angle"}.get(obj.kind, "")
    else:
        forms = [obj] if isinstance(obj, FormParameter) else [f for _, f in obj.terms] if isinstance(obj, Row) else []
        kinds = {"angle" if f.is_angle else str(form_dimension(f.element.type, f.form)) for f in forms}
        kind = kinds.pop() if len(kinds) == 1 else ""
    if kind == "angle":
        return units.angle
    if kind == "length":
        return units.length or ""
    return ""


def optimum_summary(optimum: Optimum) -> Summary:
    """The summary of an optimum: the variables of a mechanism by their names and in its units, a deck's by the
    deck's NAMES and in its units."""
    if optimum.deck is not None:
        title = f"Optimisation of {optimum.deck.path.name}"
        rows = [(v.name, v.unit, v.start, v.final) for v in _deck_rows(optimum)]
    else:
        mech = optimum.mechanism
        title = "Optimum"
        rows = [
            (name, "" if mech is None else variable_unit(mech, name), optimum.start[name], optimum.values[name])
            for name in optimum.values
        ]
    return Summary(
        title=title,
        variables=rows,
        start_objective=optimum.start_objective,
        objective=optimum.objective,
        iterations=max(len(optimum.history) - 1, 0),
        runs=optimum.runs,
        success=optimum.success,
        message=optimum.message,
        method=optimum.method,
        usable=optimum.usable if len(optimum.starts) > 1 else None,
    )


def _deck_rows(optimum: Optimum) -> list[VariableRow]:
    """A deck's variables as its report names and scales them, from the deck's own model."""
    import mechfem
    from mechfem.design.optimise_deck import stated
    from mechfem.report.optimum_report import variable_rows

    try:
        model = mechfem.check_deck(stated(optimum).path).model
    except mechfem.MechfemError:
        model = None
    return variable_rows(optimum, model)


def _num(v: float) -> str:
    return "-" if not math.isfinite(v) else f"{v:.10g}"


def summary_html(summary: Summary) -> str:
    """The table, as HTML for Jupyter."""
    e = html.escape
    rows = "".join(
        f"<tr><td style='text-align:left'>{e(name)}</td><td>{e(unit if unit != '-' else '')}</td>"
        f"<td>{_num(start)}</td><td>{_num(final)}</td></tr>"
        for name, unit, start, final in summary.variables
    )
    verdict = "converged" if summary.success else "did not converge"
    facts = [
        ("objective", f"{_num(summary.start_objective)} &rarr; {_num(summary.objective)}"),
        ("iterations", str(summary.iterations)),
        ("mechanism runs", str(summary.runs)),
        ("status", f"{e(summary.method)}, {verdict}: {e(summary.message)}"),
    ]
    if summary.usable is not None:
        facts.append(("usable starts", f"{summary.usable:.0%}"))
    facts_html = "".join(f"<tr><th style='text-align:left'>{k}</th><td colspan='3'>{v}</td></tr>" for k, v in facts)
    return (
        f"<div class='mechfem-optimum'><b>{e(summary.title)}</b>"
        "<table><thead><tr><th style='text-align:left'>variable</th><th>unit</th><th>start</th><th>final</th></tr>"
        f"</thead><tbody>{rows}</tbody><tbody>{facts_html}</tbody></table></div>"
    )


def plot_history(history: Sequence[Iteration], ax: Axes | None = None, title: str = "") -> Figure:
    """The objective per iteration on a logarithmic axis, on ``ax`` (default: a new figure, registered with pyplot
    so that ``plt.show()`` shows it); returns the figure. An objective of exactly 0 (a target met to the last digit)
    has no place on a logarithmic axis and is left out."""
    if ax is None:
        import matplotlib.pyplot as plt

        fig, ax = plt.subplots(figsize=(6.0, 3.6), layout="constrained")
    else:
        root = ax.get_figure(root=True)
        if root is None:
            raise ValueError("ax belongs to no figure")
        fig = root
    n = [it.number for it in history]
    f = [it.objective if it.objective > 0 and math.isfinite(it.objective) else math.nan for it in history]
    ax.plot(n, f, marker="o", markersize=3.5, linewidth=1.4)
    ax.set_yscale("log")
    ax.set_xlabel("iteration (0: the start design)")
    ax.set_ylabel("objective")
    ax.grid(True, which="major", alpha=0.3)
    if title:
        ax.set_title(title)
    return fig


def page(summary: Summary, history: Sequence[Iteration]) -> str:
    """A self-contained HTML page: the table and the chart of the objective as inline SVG."""
    from matplotlib.figure import Figure

    fig = Figure(figsize=(6.0, 3.6), layout="constrained")
    plot_history(history, fig.add_subplot())
    svg = io.StringIO()
    fig.savefig(svg, format="svg")
    chart = svg.getvalue()
    chart = chart[chart.index("<svg") :]
    title = html.escape(summary.title)
    return (
        "<!doctype html>\n<html lang='en'><head><meta charset='utf-8'>"
        "<meta http-equiv='Content-Security-Policy' content=\"default-src 'none'; style-src 'unsafe-inline'\">"
        f"<title>{title} - mechfem</title><style>body{{font:14px system-ui,sans-serif;margin:16px}}"
        "table{border-collapse:collapse}td,th{border:1px solid #d5dbe3;padding:2px 8px;text-align:right}</style>"
        f"</head><body>{summary_html(summary)}<h3>Objective per iteration</h3>{chart}</body></html>\n"
    )


def save_page(summary: Summary, history: Sequence[Iteration], path: str | os.PathLike[str]) -> Path:
    """Writes :func:`page` to ``path``; returns it."""
    from mechfem._util.atomic import atomic_path

    out = Path(path)
    out.parent.mkdir(parents=True, exist_ok=True)
    text = page(summary, history)
    with atomic_path(out) as tmp:
        tmp.write_text(text, encoding="utf-8")
    return out
