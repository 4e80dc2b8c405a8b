"""The mechanism's drawing at one position as a DXF or SVG file, for CAD programs and vector editors.

The shapes are those of the pictures, the animation and the report (:class:`~mechfem.viz.drawing.MechanismDrawing`):
bars, plates, sliders, gear wheels, racks, belts, joints and fixed pivots, with the paths of the moving points
over the whole motion. Co-ordinates are written as the run has them, in the deck's own length unit (a DXF file
can declare which unit that is with ``units="mm"``, ``"m"``, ...).

* DXF (needs ezdxf, ``pip install 'mechfem[dxf]'``): one layer per kind of shape, ``LINKS`` (bars, plates,
  sliders and their guides, orientation marks), ``GEARS`` (pitch circles, racks, belts), ``GROUND`` (the fixed
  pivots' triangles, rails and hatching), ``PIVOTS`` (a circle at every joint and point), ``PATHS`` (one
  polyline per moving point) and ``NAMES`` (point names, for a mechanism built in Python). A two-point line is a
  ``LINE``, a longer or closed one an ``LWPOLYLINE``, a wheel a ``CIRCLE``, a belt's wrap an ``ARC``.
* SVG (no dependency): the same shapes in the pictures' colours, y pointing up, one element per shape, each with
  the class of its kind and its layer (``class="bar links"``); strokes keep their width when the picture is
  scaled.

Every file is written under a temporary name beside its target and renamed when it is complete.
"""

from __future__ import annotations

import math
import os
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any
from xml.sax.saxutils import escape, quoteattr

import numpy as np
import numpy.typing as npt

from mechfem._util import optional
from mechfem._util.atomic import atomic_path
from mechfem.results import labels
from mechfem.results.result import RunResult
from mechfem.results.result_tables import run_units
from mechfem.viz.animation import path_sample
from mechfem.viz.drawing import STYLES, MechanismDrawing, Shape, arc_points
from mechfem.viz.figures import PATH_COLOURS

FloatArray = npt.NDArray[np.float64]

FORMATS = ("dxf", "svg")
"""The file formats a drawing is exported to."""

LAYERS: dict[str, str] = {
    "bar": "LINKS",
    "plate": "LINKS",
    "guide": "LINKS",
    "slider": "LINKS",
    "mark": "LINKS",
    "wheel": "GEARS",
    "ring": "GEARS",
    "belt": "GEARS",
    "rack": "GEARS",
    "ground": "GROUND",
    "rail": "GROUND",
    "hatch": "GROUND",
    "joint": "PIVOTS",
    "dot": "PIVOTS",
}
"""The DXF layer (and SVG class) of each role of :data:`mechfem.viz.drawing.STYLES`."""

# AutoCAD colour indices of the layers: blue links, magenta gears, grey ground, black/white pivots, red paths,
# green names; the entities themselves are BYLAYER, so a CAD user recolours a whole kind at once.
LAYER_COLOURS = {"LINKS": 5, "GEARS": 6, "GROUND": 8, "PIVOTS": 7, "PATHS": 1, "NAMES": 3}

DXF_UNITS = {"unitless": 0, "in": 1, "ft": 2, "mm": 4, "cm": 5, "m": 6, "km": 7, "um": 13, "dm": 14}
"""``units=`` of a DXF export: the value of the header's $INSUNITS. Co-ordinates are not scaled."""

SVG_SIZE = 800
"""The longer side of the SVG in pixels; the other follows the drawing's proportions."""


@dataclass(frozen=True)
class Path2D:
    """The path of one point over the motion: ``label`` and its co-ordinates (NaN where it does not exist)."""

    label: str
    x: FloatArray
    y: FloatArray


@dataclass(frozen=True)
class PointLabel:
    """A point's name at its place in the drawn position."""

    text: str
    x: float
    y: float


@dataclass(frozen=True)
class ExportDrawing:
    """What an export writes: the shapes at one position, the paths and the point names."""

    title: str
    position: int
    """1-based."""
    shapes: list[Shape]
    paths: list[Path2D]
    labels: list[PointLabel]
    unit: float
    """The size of the drawing's symbols (joint circles are about half of it); names are written this high."""

    def bounds(self) -> tuple[float, float, float, float]:
        """(xmin, xmax, ymin, ymax) of the shapes and paths."""
        xs: list[float] = []
        ys: list[float] = []
        for s in self.shapes:
            d = np.asarray(s.data, dtype=np.float64)
            if not np.isfinite(d).all():
                continue
            if s.kind in ("circle", "arc"):
                xs += [d[0] - d[2], d[0] + d[2]]
                ys += [d[1] - d[2], d[1] + d[2]]
            else:
                xs += list(d[0::2])
                ys += list(d[1::2])
        for p in self.paths:
            ok = np.isfinite(p.x) & np.isfinite(p.y)
            xs += list(p.x[ok])
            ys += list(p.y[ok])
        if not xs:
            return (-1.0, 1.0, -1.0, 1.0)
        return min(xs), max(xs), min(ys), max(ys)


def check_position(position: object, positions: int) -> int:
    """``position`` (1-based) as an int; a ValueError saying which positions there are when it is not one of them."""
    if isinstance(position, bool) or not isinstance(position, int | np.integer):
        raise ValueError(f"position must be a whole number from 1 to {positions}, not {position!r}")
    if not 1 <= int(position) <= positions:
        raise ValueError(
            f"position {position} does not exist: the run has {positions} position{'s' if positions != 1 else ''}, "
            f"so position must be from 1 to {positions}"
        )
    return int(position)


def _pieces(x: FloatArray, y: FloatArray) -> list[FloatArray]:
    """The runs of finite points of a path (a path is broken where a position has no point)."""
    xy = np.stack([x, y], axis=1)
    ok = np.asarray(np.isfinite(xy).all(axis=1), dtype=bool)
    out: list[FloatArray] = []
    start = None
    flags = [bool(v) for v in ok] + [False]  # the end closes the last run
    for k, good in enumerate(flags):
        if good and start is None:
            start = k
        elif not good and start is not None:
            if k - start >= 2:
                out.append(xy[start:k])
            start = None
    return out


def result_drawing(
    result: RunResult, position: int = 1, paths: bool | Sequence[tuple[int, int]] = True
) -> ExportDrawing:
    """The drawing of a deck's run at ``position`` (1-based). ``paths``: True for the path of every moving point,
    False for none, or the points (x and y co-ordinate numbers of the deck) whose paths to draw."""
    k = check_position(position, result.positions) - 1
    drawing = MechanismDrawing(result.model, result.coords)
    if paths is True:
        keys = [p for p in drawing.points if not (p[0] in drawing.fixed and p[1] in drawing.fixed)]
    elif paths is False:
        keys = []
    else:
        n = result.model.n_coords
        keys = []
        for ix, iy in paths:
            if not (1 <= ix <= n and 1 <= iy <= n):
                raise ValueError(f"a point is two co-ordinate numbers from 1 to {n}, not ({ix}, {iy})")
            keys.append((ix - 1, iy - 1))
    sample = path_sample(result.positions)
    tracks = [
        Path2D(labels.point_name(result, ix + 1, iy + 1), result.coords[sample, ix], result.coords[sample, iy])
        for ix, iy in keys
    ]
    return ExportDrawing(
        title=f"{result.deck.stem}, position {k + 1}",
        position=k + 1,
        shapes=drawing.shapes(result.coords[k]),
        paths=tracks,
        # The points the deck's NAMES block names, by name.
        labels=[
            PointLabel(p.name, float(result.coords[k, p.x - 1]), float(result.coords[k, p.y - 1]))
            for p in result.model.points
            if math.isfinite(result.coords[k, p.x - 1]) and math.isfinite(result.coords[k, p.y - 1])
        ],
        unit=drawing.unit,
    )


def analysis_drawing(
    a: RunResult, position: int = 1, paths: bool | Sequence[str] = True, names: bool = True
) -> ExportDrawing:
    """The drawing of a :class:`~mechfem.RunResult` at ``position``; ``paths``: True for every moving point, False
    for none, or the names of the points whose paths to draw; ``names`` writes the points' names."""

    k = check_position(position, a.positions) - 1
    cols = a.numbering.coord_number
    chosen = [] if paths is False else a._traced_points(None if paths is True else paths)
    keys = [(cols[p.x], cols[p.y]) for p in chosen]
    base = result_drawing(a, k + 1, keys)
    tracks = [Path2D(p.name, t.x, t.y) for p, t in zip(chosen, base.paths, strict=True)]
    labels = []
    if names:
        x = a.coords[k]
        for p in a.mechanism.points:
            if p.x in cols and p.y in cols:
                px, py = float(x[cols[p.x] - 1]), float(x[cols[p.y] - 1])
                if math.isfinite(px) and math.isfinite(py):
                    labels.append(PointLabel(p.name, px, py))
    title = f"{a.mechanism.name}, position {k + 1}"
    return ExportDrawing(title, k + 1, base.shapes, tracks, labels, base.unit)


# -- DXF --------------------------------------------------------------------------------------------


def _ezdxf() -> Any:
    return optional.module(
        "ezdxf",
        "writing DXF needs ezdxf, which mechfem does not install by itself: pip install 'mechfem[dxf]' "
        "(or pip install ezdxf); SVG needs nothing more",
    )


def dxf_available() -> bool:
    """True when ezdxf can be imported."""
    try:
        _ezdxf()
    except ImportError:
        return False
    return True


def write_dxf(d: ExportDrawing, path: str | os.PathLike[str], units: str | None = None) -> Path:
    """Writes ``d`` as a DXF file (R2010) at ``path``; ``units`` names the deck's length unit (:data:`DXF_UNITS`)."""
    ezdxf = _ezdxf()
    code = _units_code(units)
    target = Path(path)
    doc = ezdxf.new("R2010", setup=True)
    doc.header["$INSUNITS"] = code
    for name, colour in LAYER_COLOURS.items():
        doc.layers.add(name, color=colour)
    msp = doc.modelspace()
    for s in d.shapes:
        _dxf_shape(msp, s)
    for p in d.paths:
        for piece in _pieces(p.x, p.y):
            msp.add_lwpolyline([(float(a), float(b)) for a, b in piece], dxfattribs={"layer": "PATHS"})
    for lab in d.labels:
        offset = 0.6 * d.unit
        msp.add_text(
            lab.text, height=1.5 * d.unit, dxfattribs={"layer": "NAMES", "insert": (lab.x + offset, lab.y + offset)}
        )
    with atomic_path(target) as tmp:
        doc.saveas(tmp)
    return target


def _units_code(units: str | None) -> int:
    if units is None:
        return 0
    code = DXF_UNITS.get(str(units).strip().lower())
    if code is None:
        raise ValueError(f"unknown length unit {units!r} for a DXF file: one of {', '.join(DXF_UNITS)}")
    return code


def _dxf_shape(msp: Any, s: Shape) -> None:
    d = [float(v) for v in s.data]
    if not all(math.isfinite(v) for v in d):
        return
    attribs: dict[str, Any] = {"layer": LAYERS.get(s.role, "LINKS")}
    if STYLES[s.role].dash:
        attribs["linetype"] = "DASHED"
    pts = list(zip(d[0::2], d[1::2], strict=False))
    match s.kind:
        case "line" if len(pts) == 2:
            msp.add_line(pts[0], pts[1], dxfattribs=attribs)
        case "line":
            msp.add_lwpolyline(pts, dxfattribs=attribs)
        case "polygon":
            msp.add_lwpolyline(pts, close=True, dxfattribs=attribs)
        case "segments":
            for a, b in zip(pts[0::2], pts[1::2], strict=True):
                msp.add_line(a, b, dxfattribs=attribs)
        case "circle":
            msp.add_circle((d[0], d[1]), d[2], dxfattribs=attribs)
        case "arc":
            cx, cy, r, a0, a1 = d
            if a1 - a0 >= 2 * math.pi - 1e-12:
                msp.add_circle((cx, cy), r, dxfattribs=attribs)
            else:
                msp.add_arc((cx, cy), r, math.degrees(a0), math.degrees(a1), dxfattribs=attribs)


# -- SVG --------------------------------------------------------------------------------------------


def _num(v: float) -> str:
    return f"{v:.9g}"


def _xy(x: float, y: float) -> str:
    # SVG's y points down: the drawing is mirrored so that the mechanism's y points up.
    return f"{_num(x)},{_num(-y)}"


def _svg_shape(s: Shape) -> str | None:
    d = [float(v) for v in s.data]
    if not all(math.isfinite(v) for v in d):
        return None
    cls = quoteattr(f"{s.role} {LAYERS.get(s.role, 'LINKS').lower()}")
    pts = list(zip(d[0::2], d[1::2], strict=False))
    match s.kind:
        case "line" if len(pts) == 2:
            (x0, y0), (x1, y1) = pts
            return f'<line class={cls} x1="{_num(x0)}" y1="{_num(-y0)}" x2="{_num(x1)}" y2="{_num(-y1)}"/>'
        case "line":
            return f'<polyline class={cls} points="{" ".join(_xy(x, y) for x, y in pts)}"/>'
        case "polygon":
            return f'<polygon class={cls} points="{" ".join(_xy(x, y) for x, y in pts)}"/>'
        case "segments":
            moves = " ".join(f"M{_xy(*a)} L{_xy(*b)}" for a, b in zip(pts[0::2], pts[1::2], strict=True))
            return f'<path class={cls} d="{moves}"/>'
        case "circle":
            return f'<circle class={cls} cx="{_num(d[0])}" cy="{_num(-d[1])}" r="{_num(d[2])}"/>'
        case "arc":
            cx, cy, r, a0, a1 = d
            xs, ys = arc_points(cx, cy, r, a0, a1, n=max(8, int(abs(a1 - a0) / (2 * math.pi) * 96)))
            return f'<polyline class={cls} points="{" ".join(_xy(x, y) for x, y in zip(xs, ys, strict=True))}"/>'
    return None


def svg_text(d: ExportDrawing) -> str:
    """The SVG document of ``d``."""
    x0, x1, y0, y1 = d.bounds()
    pad = 0.05 * max(x1 - x0, y1 - y0, 1e-12) + 2.0 * d.unit
    w, h = (x1 - x0) + 2 * pad, (y1 - y0) + 2 * pad
    scale = SVG_SIZE / max(w, h)
    width, height = max(1, round(w * scale)), max(1, round(h * scale))
    styles = [".path{stroke-width:1;fill:none}", ".name{fill:#1f3b57}"]
    for role, st in STYLES.items():
        dash = ";stroke-dasharray:6 4" if st.dash else ""
        styles.append(f".{role}{{stroke:{st.edge};stroke-width:{st.width * 4 / 3:.3g};fill:{st.fill or 'none'}{dash}}}")
    out = [
        '<?xml version="1.0" encoding="UTF-8"?>',
        f'<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" '
        f'viewBox="{_num(x0 - pad)} {_num(-(y1 + pad))} {_num(w)} {_num(h)}">',
        f"<title>{escape(d.title)}</title>",
        "<style>line,polyline,polygon,path,circle{vector-effect:non-scaling-stroke;stroke-linejoin:round}"
        + "".join(styles)
        + "</style>",
        '<g id="mechanism">',
    ]
    out += [e for e in map(_svg_shape, d.shapes) if e is not None]
    # The paths over the mechanism: a coupler point's path runs across its plate.
    out += ["</g>", '<g id="paths">']
    for k, p in enumerate(d.paths):
        colour = PATH_COLOURS[k % len(PATH_COLOURS)]
        for piece in _pieces(p.x, p.y):
            points = " ".join(_xy(float(a), float(b)) for a, b in piece)
            out.append(f'<polyline class="path" stroke="{colour}" data-point={quoteattr(p.label)} points="{points}"/>')
    out += ["</g>", '<g id="names">']
    offset = 0.6 * d.unit
    for lab in d.labels:
        out.append(
            f'<text class="name" x="{_num(lab.x + offset)}" y="{_num(-(lab.y + offset))}" '
            f'font-size="{_num(1.5 * d.unit)}" font-family="sans-serif">{escape(lab.text)}</text>'
        )
    out += ["</g>", "</svg>", ""]
    return "\n".join(out)


def write_svg(d: ExportDrawing, path: str | os.PathLike[str]) -> Path:
    """Writes ``d`` as an SVG file at ``path``."""
    target = Path(path)
    text = svg_text(d)
    with atomic_path(target) as tmp:
        tmp.write_text(text, encoding="utf-8")
    return target


# -- the API ----------------------------------------------------------------------------------------


def file_format(path: str | os.PathLike[str], format: str | None) -> str:
    """``format`` checked, or the format the file name's suffix names."""
    if format is None:
        suffix = Path(path).suffix.lower().lstrip(".")
        if suffix not in FORMATS:
            raise ValueError(
                f"cannot tell the format of {os.fspath(path)!r} from its suffix: name it .dxf or .svg, "
                "or give format='dxf' or 'svg'"
            )
        return suffix
    fmt = str(format).lower()
    if fmt not in FORMATS:
        raise ValueError(f"unknown drawing format {format!r}: one of {', '.join(FORMATS)}")
    return fmt


def write(d: ExportDrawing, path: str | os.PathLike[str], format: str | None = None, units: str | None = None) -> Path:
    """Writes ``d`` as DXF or SVG (``format``, default from the suffix of ``path``); returns the file written."""
    fmt = file_format(path, format)
    if fmt == "dxf":
        return write_dxf(d, path, units)
    if units is not None:
        _units_code(units)
    return write_svg(d, path)


def export_drawing(
    result: RunResult,
    path: str | os.PathLike[str],
    position: int = 1,
    *,
    paths: bool | Sequence[Any] = True,
    format: str | None = None,
    units: str | None = None,
) -> Path:
    """Writes the mechanism of ``result`` (a deck's run or a named model's) at ``position`` (1-based) to ``path``
    as DXF or SVG (``format``, default from the suffix) with the paths of its moving points (``paths``: True, False,
    or which points: co-ordinate number pairs for a deck's run, names for a named model's). ``units`` ("mm", "m",
    ...) declares the deck's length unit in a DXF file (default the model's own, from its UNITS). Returns the file
    written."""
    fmt = file_format(path, format)
    if result.named:
        d = analysis_drawing(result, position, paths)
    else:
        d = result_drawing(result, position, paths)
    return write(d, path, fmt, units or run_units(result).length)


def draw_files(
    result: RunResult,
    outdir: Path,
    position: int = 1,
    formats: Sequence[str] = FORMATS,
    paths: bool = True,
    units: str | None = None,
) -> list[Path]:
    """Writes ``<deck stem>_pos<position>.<format>`` into ``outdir`` (created if needed) for every format; returns
    the files. Nothing is written outside ``outdir``."""
    d = result_drawing(result, position, paths)
    outdir.mkdir(parents=True, exist_ok=True)
    name = f"{result.deck.stem}_pos{d.position}"
    return [write(d, outdir / f"{name}.{fmt}", fmt, units or run_units(result).length) for fmt in formats]


def analysis_dxf(
    a: RunResult, path: str | os.PathLike[str], position: int, paths: bool | Sequence[str], units: str | None
) -> Path:
    """:meth:`RunResult.to_dxf`: the mechanism at ``position`` with the paths of its moving points as a DXF file,
    its length unit ``units`` or the run's (its deck's UNITS LENGTH)."""
    return write_dxf(analysis_drawing(a, position, paths), path, units or run_units(a).length)


def analysis_svg(a: RunResult, path: str | os.PathLike[str], position: int, paths: bool | Sequence[str]) -> Path:
    """:meth:`RunResult.to_svg`: as :func:`analysis_dxf`, an SVG file."""
    return write_svg(analysis_drawing(a, position, paths), path)
