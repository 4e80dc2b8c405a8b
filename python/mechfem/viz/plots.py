"""The deck's pictures (``BEGINPIC`` ... ``ENDPIC``), each written as ``<stem>_pic<N>.png`` and ``.svg``.

* ``PLOTFUNC bx by``: buffer by against buffer bx. Lines whose vertical buffers have the same kind and unit
  share one panel, with a legend; lines of other kinds (a transfer function beside the angle it is taken of)
  get panels of their own, stacked and sharing the x axis.
* ``PLOTCURV bx by``: a two-dimensional curve with equal axis scales.
* ``PLOTHODO ix iy``: the path of the point (x_ix, y_iy), the mechanism in its first position and the
  hodograph: the first-order vectors (dx_ix / d input 1, dy_iy / d input 1) drawn as arrows at points
  along the path (theory, fig. 5.6.5). When the path is small against the mechanism a second panel shows
  it enlarged.

A picture with both functions and curves has the functions on the left, the curves on the right. Axes and
legends name the buffers with their units (:mod:`mechfem.results.labels`: ``dANGB(8)/dinput1 [rad/rad]``).
"""

from __future__ import annotations

import math
import textwrap
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import numpy.typing as npt

from mechfem._util.atomic import atomic_path
from mechfem.model.echo import EchoPicture, Plot
from mechfem.results.labels import Label, buffer_labels, coordinate_axis, input_name, label, point_name
from mechfem.results.result import RunResult
from mechfem.viz.drawing import MechanismDrawing
from mechfem.viz.mpl_drawing import MplMechanism

FloatArray = npt.NDArray[np.float64]
IntArray = npt.NDArray[np.int64]

#: Arrows drawn along a hodograph's path (at most).
HODOGRAPH_ARROWS = 24
#: The longest hodograph arrow, as a fraction of the size of the path.
HODOGRAPH_ARROW_SIZE = 0.25
#: Resolution of the PNG pictures.
PNG_DPI = 120

PATH_COLOUR = "#d62728"
ARROW_COLOUR = "#2ca02c"


# -- what the buffers hold ---------------------------------------------------------------------------


def picture_title(result: RunResult, index: int) -> str:
    """The BEGINPIC title, or one made from what the picture shows (the buffers' names,
    :mod:`mechfem.results.labels`)."""
    pic = result.storage.pictures[index]
    if pic.title:
        return pic.title
    labels = buffer_labels(result)
    parts = [
        f"path and hodograph of point {point_name(result, p.a, p.b)}" for p in pic.plots if p.keyword == "PLOTHODO"
    ]
    # Functions and curves grouped by their horizontal buffer: "A, B against X".
    against: dict[int, list[str]] = {}
    for p in pic.plots:
        if p.keyword != "PLOTHODO":
            against.setdefault(p.a, []).append(_name(result, labels, p.b))
    parts += [f"{', '.join(dict.fromkeys(ys))} against {_name(result, labels, x)}" for x, ys in against.items()]
    text = f"{result.deck.stem}, picture {index + 1}: {'; '.join(parts)}"
    return "\n".join(textwrap.wrap(text, 100))


def _label(result: RunResult, labels: dict[int, Label], number: int) -> Label:
    return labels[number] if number in labels else label(result, number)


def _name(result: RunResult, labels: dict[int, Label], number: int) -> str:
    return _label(result, labels, number).name


def picture_files(result: RunResult, outdir: Path) -> list[tuple[Path, Path]]:
    """The PNG and SVG file of every picture, in deck order: ``<stem>_pic<N>.png``, ``.svg``."""
    stem = result.deck.stem
    n = len(result.storage.pictures)
    return [(outdir / f"{stem}_pic{k}.png", outdir / f"{stem}_pic{k}.svg") for k in range(1, n + 1)]


# -- hodographs --------------------------------------------------------------------------------------


@dataclass(frozen=True)
class Hodograph:
    """A PLOTHODO's path and arrows: arrow k starts at (x[at[k]], y[at[k]]) and is (vx[k], vy[k]) * scale long."""

    ix: int
    iy: int
    x: FloatArray
    y: FloatArray
    at: IntArray
    vx: FloatArray
    vy: FloatArray
    scale: float
    """Drawing scale of the arrows: arrow length = scale * |(dx/d input, dy/d input)|."""


def hodograph(result: RunResult, ix: int, iy: int, arrows: int = HODOGRAPH_ARROWS) -> Hodograph:
    """Path and first-order vectors of the point (x_ix, y_iy), with about ``arrows`` arrows spread along the path.

    The scale makes the longest arrow ``HODOGRAPH_ARROW_SIZE`` times the diagonal of the path's bounding box.
    """
    x, y = result.coords[:, ix - 1], result.coords[:, iy - 1]
    n = len(x)
    nan = np.full(n, np.nan)
    kx, ky = result.kx1.get(ix, nan), result.kx1.get(iy, nan)
    ok = np.isfinite(x) & np.isfinite(y) & np.isfinite(kx) & np.isfinite(ky)
    at = _arrow_positions(x, y, ok, arrows)
    vx, vy = kx[at], ky[at]
    size = float(np.hypot(np.ptp(x), np.ptp(y))) if n else 0.0
    longest = float(np.max(np.hypot(vx, vy))) if len(vx) else 0.0
    scale = HODOGRAPH_ARROW_SIZE * size / longest if longest > 0 and size > 0 else 0.0
    return Hodograph(ix, iy, x, y, at, vx, vy, scale)


def _arrow_positions(x: FloatArray, y: FloatArray, ok: npt.NDArray[np.bool_], arrows: int) -> IntArray:
    """Arrows at evenly spread positions (equal steps of the motion, so that they crowd where the point is slow),
    leaving out a position whose point repeats one that already has an arrow (a path run through more than once)."""
    candidates = np.flatnonzero(ok)
    if len(candidates) == 0:
        return np.zeros(0, dtype=np.int64)
    picks = np.unique(np.linspace(0, len(candidates) - 1, min(len(candidates), arrows)).round().astype(np.int64))
    tol = 1e-6 * max(float(np.ptp(x[candidates]) + np.ptp(y[candidates])), 1e-300)
    chosen: list[int] = []
    for k in candidates[picks]:
        if not chosen or np.min(np.hypot(x[chosen] - x[k], y[chosen] - y[k])) > tol:
            chosen.append(int(k))
    return np.asarray(chosen, dtype=np.int64)


# -- figures -----------------------------------------------------------------------------------------


def function_panels(result: RunResult, plots: list[Plot]) -> list[list[Plot]]:
    """The PLOTFUNC lines of a picture grouped into panels: one panel per kind and unit of the vertical buffers
    (:attr:`Label.group`), in the order they first appear, so that no axis mixes quantities of different kinds."""
    labels = buffer_labels(result)
    panels: dict[tuple[str, str], list[Plot]] = {}
    for p in plots:
        panels.setdefault(_label(result, labels, p.b).group, []).append(p)
    return list(panels.values())


#: The longest list of names a vertical axis shows; a longer one gives the kind and the unit instead.
AXIS_NAMES = 48


def _function_axes(ax: object, result: RunResult, plots: list[Plot], xlabel: bool = True) -> None:
    """One panel of functions: every line's vertical buffers share a kind and a unit, which the axis names."""
    from matplotlib.axes import Axes

    assert isinstance(ax, Axes)
    labels = buffer_labels(result)
    for p in plots:
        bx, by = result.buffers.get(p.a), result.buffers.get(p.b)
        if bx is None or by is None:
            continue
        ax.plot(bx, by, lw=1.6, label=_label(result, labels, p.b).axis())
    if xlabel:
        xs = list(dict.fromkeys(p.a for p in plots))
        ax.set_xlabel("; ".join(_label(result, labels, b).axis() for b in xs))
    ys = [_label(result, labels, b) for b in dict.fromkeys(p.b for p in plots)]
    ax.set_ylabel(_y_axis(ys))
    ax.axhline(0.0, color="#888888", lw=0.6, zorder=0)
    ax.grid(True, alpha=0.3)
    if len(plots) > 1:
        ax.legend(loc="best", fontsize="small")


def _y_axis(ys: list[Label]) -> str:
    """The vertical axis of buffers of one kind and unit: their names and the unit, or the kind and the unit."""
    if len(ys) == 1:
        return ys[0].axis()
    unit = f" [{ys[0].unit}]" if ys[0].unit else ""
    names = ", ".join(y.name for y in ys)
    return names + unit if len(names) <= AXIS_NAMES else ys[0].group[0] + unit


def _curve_axes(
    ax: object, result: RunResult, plots: list[Plot], drawing: MechanismDrawing | None, zoom: bool = False
) -> tuple[float, float, float, float] | None:
    """Curves and hodographs with equal axis scales; returns the bounding box of the paths (hodographs only)."""
    from matplotlib.axes import Axes

    assert isinstance(ax, Axes)
    hodos = [p for p in plots if p.keyword == "PLOTHODO"]
    curves = [p for p in plots if p.keyword == "PLOTCURV"]
    labels = buffer_labels(result)
    for p in curves:
        bx, by = result.buffers.get(p.a), result.buffers.get(p.b)
        if bx is None or by is None:
            continue
        ax.plot(bx, by, lw=1.6, label=f"{_name(result, labels, p.b)} against {_name(result, labels, p.a)}")
        ax.plot(bx[:1], by[:1], "o", ms=4, color=ax.lines[-1].get_color())
    if curves:
        xs = list(dict.fromkeys(p.a for p in curves))
        ys = list(dict.fromkeys(p.b for p in curves))
        ax.set_xlabel("; ".join(_label(result, labels, b).axis() for b in xs))
        ax.set_ylabel("; ".join(_label(result, labels, b).axis() for b in ys))
    box = None
    if hodos:
        if drawing is not None:
            MplMechanism(ax, drawing, result.coords[0], alpha=0.45 if zoom else 1.0)
        lo = np.array([np.inf, np.inf])
        hi = -lo
        for p in hodos:
            h = hodograph(result, p.a, p.b)
            point = point_name(result, p.a, p.b)
            ax.plot(h.x, h.y, color=PATH_COLOUR, lw=1.6, zorder=5, label=f"path of {point}")
            ax.plot(h.x[:1], h.y[:1], "o", color=PATH_COLOUR, ms=4, zorder=5)
            if h.scale > 0:
                ax.quiver(
                    h.x[h.at],
                    h.y[h.at],
                    h.vx * h.scale,
                    h.vy * h.scale,
                    angles="xy",
                    scale_units="xy",
                    scale=1.0,
                    color=ARROW_COLOUR,
                    width=0.0032,
                    headwidth=4.0,
                    headlength=5.0,
                    headaxislength=4.5,
                    zorder=6,
                    label=f"d{point}/d{input_name(result, 1)}, drawn x {h.scale:.3g}",
                )
            finite = np.isfinite(h.x) & np.isfinite(h.y)
            if finite.any():
                tips_x = np.concatenate([h.x[finite], h.x[h.at] + h.vx * h.scale])
                tips_y = np.concatenate([h.y[finite], h.y[h.at] + h.vy * h.scale])
                lo = np.minimum(lo, [tips_x.min(), tips_y.min()])
                hi = np.maximum(hi, [tips_x.max(), tips_y.max()])
        if np.isfinite(lo).all():
            box = (float(lo[0]), float(hi[0]), float(lo[1]), float(hi[1]))
        if not curves:
            ax.set_xlabel("; ".join(dict.fromkeys(coordinate_axis(result, p.a) for p in hodos)))
            ax.set_ylabel("; ".join(dict.fromkeys(coordinate_axis(result, p.b) for p in hodos)))
    ax.set_aspect("equal", adjustable="box" if hodos else "datalim")
    ax.grid(True, alpha=0.3)
    return box


def _pad(box: tuple[float, float, float, float], frac: float) -> tuple[float, float, float, float]:
    x0, x1, y0, y1 = box
    d = max(x1 - x0, y1 - y0, 1e-12) * frac
    return x0 - d, x1 + d, y0 - d, y1 + d


def picture_figure(result: RunResult, index: int, drawing: MechanismDrawing | None = None) -> object:
    """The matplotlib figure of picture ``index`` (0-based)."""
    from matplotlib.figure import Figure

    pic: EchoPicture = result.storage.pictures[index]
    funcs = [p for p in pic.plots if p.keyword == "PLOTFUNC"]
    curves = [p for p in pic.plots if p.keyword != "PLOTFUNC"]
    hodos = [p for p in curves if p.keyword == "PLOTHODO"]
    if hodos and drawing is None:
        drawing = MechanismDrawing(result.model, result.coords)

    whole: tuple[float, float, float, float] | None = None
    path_box: tuple[float, float, float, float] | None = None
    zoom = False
    if hodos and drawing is not None:
        whole = drawing.bounds([0])
        path_box = _paths_box(result, hodos)
        if path_box is not None:
            wd = math.hypot(whole[1] - whole[0], whole[3] - whole[2])
            pd = math.hypot(path_box[1] - path_box[0], path_box[3] - path_box[2])
            # A path of (nearly) no size has nothing to enlarge.
            zoom = 1e-6 * wd < pd < 0.35 * wd

    stacked = function_panels(result, funcs) if funcs else []
    panels = (1 if funcs else 0) + (1 if curves else 0) + (1 if zoom else 0)
    widths = []
    if funcs:
        widths.append(8.0)
    aspect_whole = 1.0
    if curves:
        if whole is not None:
            x0, x1, y0, y1 = whole
            aspect_whole = (y1 - y0) / max(x1 - x0, 1e-12)
        widths.append(max(2.2, min(8.0, 5.5 / max(aspect_whole, 1e-6))) if hodos else 7.0)
    if zoom:
        widths.append(7.5)
    height = 6.5 if curves else 5.0
    if len(stacked) > 1:
        height = max(height, 1.2 + 2.4 * len(stacked))
    if panels == 0:
        # A picture without plots (the deck reader refuses one; the Python API may still build one): one empty
        # panel that says so.
        fig = Figure(figsize=(7.0, height), layout="constrained")
        ax = fig.subplots()
        ax.text(0.5, 0.5, "this picture has no plots", ha="center", va="center", transform=ax.transAxes)
        ax.set_axis_off()
        fig.suptitle(picture_title(result, index))
        return fig
    fig = Figure(figsize=(max(sum(widths) + 0.6 * panels, 7.0), height), layout="constrained")
    # Functions of different kinds are stacked in one column, one panel per kind, beside the curves' panels.
    grid = fig.add_gridspec(max(1, len(stacked)), panels, width_ratios=widths)
    k = 0
    if funcs:
        _function_column(fig, grid, result, stacked)
        k += 1
    tips = None
    if curves:
        ax = fig.add_subplot(grid[:, k])
        # The paths with the tips of their arrows, so that no arrow leaves a panel.
        tips = _curve_axes(ax, result, curves, drawing)
        if whole is not None:
            bx0, bx1, by0, by1 = whole
            if tips is not None:
                bx0, bx1 = min(bx0, tips[0]), max(bx1, tips[1])
                by0, by1 = min(by0, tips[2]), max(by1, tips[3])
            x0, x1, y0, y1 = _pad((bx0, bx1, by0, by1), 0.04)
            ax.set_xlim(x0, x1)
            ax.set_ylim(y0, y1)
        if hodos:
            fig.legend(*ax.get_legend_handles_labels(), loc="outside lower center", ncols=2, fontsize="small")
        else:
            ax.legend(loc="best", fontsize="small")
        if zoom:
            ax.set_title("whole mechanism, position 1", fontsize="medium")
        k += 1
    if zoom and path_box is not None:
        ax = fig.add_subplot(grid[:, k])
        _curve_axes(ax, result, curves, drawing, zoom=True)
        ax.set_title("path and hodograph, enlarged", fontsize="medium")
        fig.suptitle(picture_title(result, index))
        # Fill the panel: the path's box, widened to the panel's shape (equal scales).
        fig.canvas.draw()
        fit_equal(ax, _pad(tips or path_box, 0.05))
        return fig
    fig.suptitle(picture_title(result, index))
    return fig


def _function_column(fig: object, grid: object, result: RunResult, stacked: list[list[Plot]]) -> None:
    """The function panels, top to bottom in the first column of ``grid``. Panels that share their horizontal
    buffers share the x axis, which only the bottom panel labels."""
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure
    from matplotlib.gridspec import GridSpec

    assert isinstance(fig, Figure) and isinstance(grid, GridSpec)
    shared = len({tuple(dict.fromkeys(p.a for p in panel)) for panel in stacked}) == 1
    first: Axes | None = None
    for row, panel in enumerate(stacked):
        ax = fig.add_subplot(grid[row, 0], sharex=first if shared else None)
        first = first or ax
        bottom = row == len(stacked) - 1
        _function_axes(ax, result, panel, xlabel=bottom or not shared)
        if shared and not bottom:
            ax.tick_params(labelbottom=False)


def fit_equal(ax: object, box: tuple[float, float, float, float]) -> None:
    """Limits that show ``box`` whole, centred, with equal scales, filling the axes as laid out now."""
    from matplotlib.axes import Axes

    assert isinstance(ax, Axes)
    width, height = ax.bbox.width, ax.bbox.height
    x0, x1, y0, y1 = box
    scale = min(width / max(x1 - x0, 1e-12), height / max(y1 - y0, 1e-12))
    cx, cy = (x0 + x1) / 2, (y0 + y1) / 2
    ax.set_xlim(cx - width / scale / 2, cx + width / scale / 2)
    ax.set_ylim(cy - height / scale / 2, cy + height / scale / 2)


def _paths_box(result: RunResult, hodos: list[Plot]) -> tuple[float, float, float, float] | None:
    xs = np.concatenate([result.coords[:, p.a - 1] for p in hodos])
    ys = np.concatenate([result.coords[:, p.b - 1] for p in hodos])
    ok = np.isfinite(xs) & np.isfinite(ys)
    if not ok.any():
        return None
    return float(xs[ok].min()), float(xs[ok].max()), float(ys[ok].min()), float(ys[ok].max())


def write_pictures(result: RunResult, outdir: Path, on_file: Callable[[Path, int], object] | None = None) -> list[Path]:
    """Writes every picture of the deck as PNG and SVG into ``outdir``; returns the files written.

    ``on_file(path, k)`` is called as soon as each file of picture ``k`` (from 1) is complete.
    """
    from matplotlib.figure import Figure

    if not result.storage.pictures:
        return []
    outdir.mkdir(parents=True, exist_ok=True)
    drawing = None
    if any(p.keyword == "PLOTHODO" for pic in result.storage.pictures for p in pic.plots):
        drawing = MechanismDrawing(result.model, result.coords)
    written = []
    for index, (png, svg) in enumerate(picture_files(result, outdir)):
        fig = picture_figure(result, index, drawing)
        assert isinstance(fig, Figure)
        # dpi=None: matplotlib's default (rc savefig.dpi), as when the keyword is left out.
        for path, fmt, dpi in ((png, "png", PNG_DPI), (svg, "svg", None)):
            with atomic_path(path) as tmp:
                fig.savefig(tmp, format=fmt, dpi=dpi)
            written.append(path)
            if on_file is not None:
                on_file(path, index + 1)
    return written
