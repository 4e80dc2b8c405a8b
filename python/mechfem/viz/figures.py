"""Pictures of a :class:`~mechfem.Mechanism` and of a :class:`~mechfem.RunResult`, for scripts and notebooks.

They are drawn with the code of the deck's pictures and animation (:mod:`mechfem.viz.drawing`,
:mod:`mechfem.viz.plots`, :mod:`mechfem.viz.animation`) on the run as the deck written from the mechanism gives
it (:meth:`RunResult.run_result`), with the mechanism's names added. Figures are
``matplotlib.figure.Figure`` objects. :meth:`RunResult.plot` registers its figure with pyplot, as
``pandas.DataFrame.plot`` does, so that ``plt.show()`` shows it from a script; under a notebook's inline
backend it leaves pyplot's list at once, so that the notebook shows the returned figure once (by its
display) and not a second time when the cell ends. The PNG images by which a mechanism and a result show
themselves in Jupyter are drawn on figures pyplot never sees.
"""

from __future__ import annotations

import io
from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from mechfem.errors import MechfemError

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

    from mechfem.model.mechanism import Mechanism
    from mechfem.results.result import RunResult

PATH_COLOURS = ["#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#17becf", "#8c564b", "#e377c2", "#7f7f7f"]


def _draw_mechanism(ax: Axes, a: RunResult, position: int = 0, names: bool = True) -> tuple[float, float, float, float]:
    from mechfem.viz.drawing import MechanismDrawing
    from mechfem.viz.mpl_drawing import MplMechanism

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


def new_figure(figsize: tuple[float, float], pyplot: bool) -> Figure:
    """A constrained-layout figure; with ``pyplot``, made by pyplot (see the module's docstring)."""
    if not pyplot:
        from matplotlib.figure import Figure

        return Figure(figsize=figsize, layout="constrained")
    import matplotlib.pyplot as plt

    fig = plt.figure(figsize=figsize, layout="constrained")
    if "inline" in plt.get_backend():
        plt.close(fig)
    return fig


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
    position: int = 1,
    ax: Axes | None = None,
    pyplot: bool = True,
) -> Figure:
    """The mechanism at ``position`` (1-based, default 1) with the paths of its moving points (``points``: which),
    beside the ``outputs`` (default: every output) against the first input (``against``: an input name, or
    ``time``), a dotted line marking ``position``, with every angle (``unit="deg"``) or length (``unit="m"``) of the
    outputs and the input in ``unit`` when given.

    ``ax``: draw into these axes instead of a new figure: the ``outputs`` against the input when outputs are named,
    else the mechanism and its paths; the axes' figure is returned. ``picture=k`` draws picture k (0-based) of the
    run's storage as the deck's pictures do instead.
    """
    from matplotlib.figure import Figure

    if not 1 <= position <= max(a.positions, 1) or a.positions == 0:
        raise ValueError(
            f"position {position} is not one of the run's positions: give a position from 1 to {a.positions}"
        )
    if picture is not None:
        from mechfem.viz.plots import picture_figure

        fig = picture_figure(a, picture)
        assert isinstance(fig, Figure)
        return fig
    if ax is not None:
        if outputs:
            _outputs_axes(ax, a, list(outputs), against, unit, position)
        else:
            _mechanism_axes(ax, a, points, position)
        owner = ax.get_figure(root=True)
        assert isinstance(owner, Figure)
        return owner
    names = list(outputs) or [r.name for r in a.numbering.dependent]
    # The outputs are drawn in panels, one per unit, stacked to the right of the mechanism.
    units: dict[str, list[str]] = {}
    for name in names:
        units.setdefault(_unit(a, name), []).append(name)
    height = max(5.0, 1.2 + 2.4 * len(units))
    fig = new_figure((12.0 if names else 6.5, height), pyplot)
    grid = fig.add_gridspec(max(1, len(units)), 2 if names else 1)
    _mechanism_axes(fig.add_subplot(grid[:, 0]), a, points, position)
    first = None
    for row, group in enumerate(units.values()):
        ax2 = fig.add_subplot(grid[row, 1], sharex=first)
        first = first or ax2
        _outputs_axes(ax2, a, group, against, unit, position, last=row == len(units) - 1)
        if row == 0:
            state = "" if a.complete else f" (stopped after position {a.positions})"
            ax2.set_title(f"{', '.join(names)} against {_against(a, against, unit)[1]}{state}", fontsize="medium")
    return fig


def _mechanism_axes(ax: Axes, a: RunResult, points: Sequence[str] | None, position: int) -> None:
    """The mechanism at ``position`` (1-based) with its points' names, the paths of ``points`` drawn over it."""
    x0, x1, y0, y1 = _draw_mechanism(ax, a, position - 1)
    chosen = a._traced_points(points)
    for k, p in enumerate(chosen):
        xy = a.value(p)
        label = f"path of {p.name}"
        # Over the plates and bars (their zorder is below 3), so that a coupler point's path stays visible.
        ax.plot(xy[:, 0], xy[:, 1], color=PATH_COLOURS[k % len(PATH_COLOURS)], lw=1.0, label=label, zorder=4)
        ok = np.isfinite(xy).all(axis=1)
        if ok.any():
            x0, x1 = min(x0, float(xy[ok, 0].min())), max(x1, float(xy[ok, 0].max()))
            y0, y1 = min(y0, float(xy[ok, 1].min())), max(y1, float(xy[ok, 1].max()))
    _limits(ax, (x0, x1, y0, y1))
    if chosen:
        ax.legend(fontsize="small", loc="best")
    ax.set_title(f"{a.mechanism.name}: position {position} and paths", fontsize="medium")


def _against(a: RunResult, against: str | None, unit: str | None) -> tuple[np.ndarray, str, str]:
    """The abscissa of the outputs: its values, its name and its axis label."""
    from mechfem.results.labels import display_unit, input_unit, with_unit

    if against == "time" or not a.numbering.inputs:
        return a.time, "time", with_unit("time", display_unit(a, "s"))
    key = against if against is not None else a.numbering.inputs[0].name
    j = a.numbering.dof(key)
    name = a.numbering.inputs[j - 1].name
    return a.input(key, unit=unit), name, with_unit(name, _in(a, input_unit(a, j), unit))


def _outputs_axes(
    ax: Axes,
    a: RunResult,
    group: list[str],
    against: str | None,
    unit: str | None,
    position: int,
    last: bool = True,
) -> None:
    """The outputs ``group`` against the abscissa, in the unit of the first of them, ``position`` marked."""
    from mechfem.results.labels import with_unit

    xs, _, xlabel = _against(a, against, unit)
    shown = _in(a, _unit(a, group[0]), unit)
    for k, name in enumerate(group):
        colour = PATH_COLOURS[k % len(PATH_COLOURS)]
        ax.plot(xs, a.value(name, unit=unit), color=colour, label=with_unit(name, shown))
    if np.isfinite(xs[position - 1]):
        ax.axvline(float(xs[position - 1]), color="#7f7f7f", lw=0.8, ls=":")
    ax.set_ylabel(with_unit(", ".join(group), shown))
    ax.grid(True, alpha=0.3)
    if len(group) > 1:
        ax.legend(fontsize="small", loc="best")
    if last:
        ax.set_xlabel(xlabel)
    else:
        ax.tick_params(labelbottom=False)


def _in(a: RunResult, base: str, unit: str | None) -> str:
    """The unit ``base`` (in the words of the unit algebra) in the run's units, its angles or lengths in ``unit``
    when given."""
    from mechfem.results.labels import unit_in

    return unit_in(a, base, unit)


def _unit(a: RunResult, name: str) -> str:
    """The unit of what ``a.value(name)`` gives: an output's or row's, a co-ordinate's, a point's (a length)."""
    from mechfem.results.labels import value_unit

    return value_unit(a, name)


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
    return _png(result_figure(a, pyplot=False))


def animate(
    a: RunResult, path: str | Path, points: Sequence[str] | None = None, max_frames: int | None = None
) -> list[Path]:
    """Writes the animation of the motion to ``path`` (``name.gif``, and ``name.mp4`` when ffmpeg is installed),
    with the paths and velocity arrows of ``points`` (default: every moving point); returns the files."""
    from mechfem.model.echo import EchoPicture, Plot
    from mechfem.viz.animation import MAX_FRAMES, write_animation

    target = Path(path)
    plots = [
        Plot("PLOTHODO", a.numbering.coord_number[p.x], a.numbering.coord_number[p.y]) for p in a._traced_points(points)
    ]
    storage = a.storage.replace(animate=target.stem, pictures=[EchoPicture("", 0, plots)])
    info = write_animation(a.replace(storage=storage), target.parent, max_frames=max_frames or MAX_FRAMES)
    return list(info.files)
