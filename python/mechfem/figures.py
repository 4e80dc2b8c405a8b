"""Pictures of a :class:`~mechfem.Mechanism` and of a :class:`~mechfem.RunResult`, for scripts and notebooks.

They are drawn with the code of the deck's pictures and animation (:mod:`mechfem.drawing`,
:mod:`mechfem.plots`, :mod:`mechfem.animation`) on the run as the deck written from the mechanism gives
it (:meth:`RunResult.run_result`), with the mechanism's names added. Figures are
``matplotlib.figure.Figure`` objects (no pyplot state); in Jupyter a mechanism and an analysis show
themselves as PNG images.
"""

from __future__ import annotations

import dataclasses
import io
from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from mechfem import model as _model
from mechfem import result as _result
from mechfem.errors import MechfemError

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

    from mechfem.model import Mechanism
    from mechfem.result import RunResult

PATH_COLOURS = ["#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#17becf", "#8c564b", "#e377c2", "#7f7f7f"]


def _draw_mechanism(ax: Axes, a: RunResult, position: int = 0, names: bool = True) -> tuple[float, float, float, float]:
    from mechfem.drawing import MechanismDrawing
    from mechfem.mpl_drawing import MplMechanism

    drawing = MechanismDrawing(a.model, a.coords)
    MplMechanism(ax, drawing, a.coords[position])
    if names:
        x = a.coords[position]
        offset = 0.6 * drawing.unit
        for p in a.mechanism.points:
            try:
                i, j = a.numbering.coord_number[p.x] - 1, a.numbering.coord_number[p.y] - 1
            except KeyError:
                continue
            ax.annotate(
                p.name, (x[i], x[j]), xytext=(x[i] + offset, x[j] + offset), fontsize=8, color="#1f3b57", zorder=10
            )
    box = drawing.bounds([position])
    _limits(ax, box)
    return box


def _limits(ax: Axes, box: tuple[float, float, float, float]) -> None:
    x0, x1, y0, y1 = box
    pad = 0.08 * max(x1 - x0, y1 - y0, 1e-12)
    ax.set_xlim(x0 - pad, x1 + pad)
    ax.set_ylim(y0 - pad, y1 + pad)
    ax.set_aspect("equal", adjustable="box")


def mechanism_figure(mech: Mechanism, names: bool = True) -> Figure:
    """The mechanism at position 1 (after the adjustment of its initial co-ordinates), points named."""
    from matplotlib.figure import Figure

    a = mech.check()
    fig = Figure(figsize=(6.0, 5.0), layout="constrained")
    ax = fig.add_subplot()
    _draw_mechanism(ax, a, 0, names)
    ax.set_title(f"{mech.name}, position 1", fontsize="medium")
    return fig


def result_figure(
    a: RunResult,
    outputs: Sequence[str] = (),
    *,
    picture: int | None = None,
    points: Sequence[str] | None = None,
    against: str | None = None,
    unit: str | None = None,
) -> Figure:
    """The mechanism at position 1 with the paths of its moving points (``points``: which), beside the
    ``outputs`` (default: every output) against the first input (``against``: an input name, or ``time``), with
    every angle (``unit="deg"``) or length (``unit="m"``) of the outputs and the input in ``unit`` when given.

    ``picture=k`` draws picture k (0-based) of the run's storage as the deck's pictures do instead.
    """
    from matplotlib.figure import Figure

    if picture is not None:
        from mechfem.plots import picture_figure

        fig = picture_figure(a, picture)
        assert isinstance(fig, Figure)
        return fig
    names = list(outputs) or [r.name for r in a.numbering.dependent]
    # The outputs are drawn in panels, one per unit, stacked to the right of the mechanism.
    units: dict[str, list[str]] = {}
    for name in names:
        units.setdefault(_unit(a, name), []).append(name)
    height = max(5.0, 1.2 + 2.4 * len(units))
    fig = Figure(figsize=(12.0 if names else 6.5, height), layout="constrained")
    grid = fig.add_gridspec(max(1, len(units)), 2 if names else 1)
    ax = fig.add_subplot(grid[:, 0])
    x0, x1, y0, y1 = _draw_mechanism(ax, a)
    chosen = a._traced_points(points)
    for k, p in enumerate(chosen):
        xy = a.value(p)
        label = f"path of {p.name}"
        ax.plot(xy[:, 0], xy[:, 1], color=PATH_COLOURS[k % len(PATH_COLOURS)], lw=1.0, label=label)
        ok = np.isfinite(xy).all(axis=1)
        if ok.any():
            x0, x1 = min(x0, float(xy[ok, 0].min())), max(x1, float(xy[ok, 0].max()))
            y0, y1 = min(y0, float(xy[ok, 1].min())), max(y1, float(xy[ok, 1].max()))
    _limits(ax, (x0, x1, y0, y1))
    if chosen:
        ax.legend(fontsize="small", loc="best")
    ax.set_title(f"{a.mechanism.name}: position 1 and paths", fontsize="medium")
    if names:
        from mechfem.labels import display_unit, input_unit, with_unit

        if against == "time" or not a.numbering.inputs:
            xs, xname, xlabel = a.time, "time", with_unit("time", display_unit(a, "s"))
        else:
            key = against if against is not None else a.numbering.inputs[0].name
            j = a.numbering.dof(key)
            xname = a.numbering.inputs[j - 1].name
            xs, xlabel = a.input(key, unit=unit), with_unit(xname, _in(a, input_unit(a, j), unit))
        first = None
        k = 0
        for row, (base, group) in enumerate(units.items()):
            shown = _in(a, base, unit)
            ax2 = fig.add_subplot(grid[row, 1], sharex=first)
            first = first or ax2
            for name in group:
                colour = PATH_COLOURS[k % len(PATH_COLOURS)]
                ax2.plot(xs, a.value(name, unit=unit), color=colour, label=with_unit(name, shown))
                k += 1
            ax2.set_ylabel(with_unit(", ".join(group), shown))
            ax2.grid(True, alpha=0.3)
            if len(group) > 1:
                ax2.legend(fontsize="small", loc="best")
            if row < len(units) - 1:
                ax2.tick_params(labelbottom=False)
            else:
                ax2.set_xlabel(xlabel)
            if row == 0:
                state = "" if a.complete else f" (stopped after position {a.positions})"
                ax2.set_title(f"{', '.join(names)} against {xname}{state}", fontsize="medium")
    return fig


def _in(a: RunResult, base: str, unit: str | None) -> str:
    """The unit ``base`` (in the words of the unit algebra) in the run's units, its angles or lengths in ``unit``
    when given."""
    from mechfem.labels import display_unit, shown
    from mechfem.result_tables import run_units
    from mechfem.units import Units, kind_of

    if unit is None:
        return display_unit(a, base)
    kind = kind_of(unit)
    units = run_units(a).as_dict()
    if kind is not None:
        units[kind] = unit
    return shown(base, Units.of(units))


def _unit(a: RunResult, name: str) -> str:
    """The unit of what ``a.value(name)`` gives: an output's or row's, a co-ordinate's, a point's (a length)."""
    from mechfem.labels import coordinate_unit, row_dest_unit

    t = a._any(name)
    if t.kind == "row":
        return row_dest_unit(a, t.numbers[0])
    if t.kind == "coordinate":
        return coordinate_unit(a, t.numbers[0])
    return "length"


def _png(fig: Figure) -> bytes:
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=90)
    return buf.getvalue()


def mechanism_png(mech: Mechanism) -> bytes | None:
    """:func:`mechanism_figure` as PNG bytes, or None when position 1 cannot be computed."""
    try:
        return _png(mechanism_figure(mech))
    except (MechfemError, ValueError):
        return None


def result_png(a: RunResult) -> bytes | None:
    """:func:`result_figure` as PNG bytes, or None when it cannot be drawn."""
    if a.positions == 0:
        return None
    return _png(result_figure(a))


def animate(
    a: RunResult, path: str | Path, points: Sequence[str] | None = None, max_frames: int | None = None
) -> list[Path]:
    """Writes the animation of the motion to ``path`` (``name.gif``, and ``name.mp4`` when ffmpeg is installed),
    with the paths and velocity arrows of ``points`` (default: every moving point); returns the files."""
    from mechfem.animation import MAX_FRAMES, write_animation
    from mechfem.echo import Picture, Plot

    target = Path(path)
    plots = [
        Plot("PLOTHODO", a.numbering.coord_number[p.x], a.numbering.coord_number[p.y]) for p in a._traced_points(points)
    ]
    storage = dataclasses.replace(a.storage, animate=target.stem, pictures=[Picture("", 0, plots)])
    info = write_animation(a.replace(storage=storage), target.parent, max_frames=max_frames or MAX_FRAMES)
    return list(info.files)


_model.FIGURE.register(mechanism_figure)
_model.PNG.register(mechanism_png)
_result.PLOT.register(result_figure)
_result.ANIMATE.register(animate)
