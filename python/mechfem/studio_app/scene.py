"""The mechanism's shapes at every position, fast enough to redraw a whole motion on every edit.

The report's drawing (:class:`mechfem.viz.drawing.MechanismDrawing`) gives the shapes at one position from all the
co-ordinates; for pin-jointed elements (bars, plates, pivots, the frame's hatching) each shape's numbers are an affine
function of the co-ordinates: ``d(x) = A x + b``. :func:`scene` finds ``A`` of all the shapes at once from the
drawing itself (the shapes at position 1 and with each co-ordinate moved by one unit; a design edited keeps its
mechanism's ``A``), ``b`` from the shapes at position 1, checks that they give the drawing's own shapes at three
positions spread over the motion, and then computes every shape at every position with one matrix product. A shape
that fails the check (a slider's block turned by an angle, a belt's wrap) is drawn at every position
by the drawing as the report does. The result is the report's scene (:func:`mechfem.report.html._scene`): the same
shapes, the numbers rounded to the 6th digit of the drawing's size.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from mechfem.report.charts import nums
from mechfem.results.result import RunResult
from mechfem.viz.drawing import MechanismDrawing

#: Relative tolerance of the affinity check.
CHECK = 1e-9


def _rounded(a: np.ndarray, decimals: int) -> np.ndarray:
    """``a`` rounded to ``decimals`` (the 6th digit of the drawing's size: far below a pixel, and short in JSON), NaN
    where not finite (written as null by the server's orjson, as numpy arrays are)."""
    a = np.round(a, decimals)
    return np.where(np.isfinite(a), a, np.nan)


def _size(d: np.ndarray) -> float:
    finite = d[np.isfinite(d)]
    return 1.0 + (float(np.abs(finite).max()) if len(finite) else 0.0)


def _affine_part(drawing: MechanismDrawing, x0: np.ndarray, flat0: np.ndarray, sizes: list[int]) -> np.ndarray:
    """``A`` of the stacked shapes from the drawing at ``x0`` and with each co-ordinate moved by one unit (NaN rows:
    a shape whose number of values changes)."""
    n = len(x0)
    a = np.full((len(flat0), n), np.nan)
    # Column j of A: how each shape moves when co-ordinate j moves by one unit.
    for j in range(n):
        probe = drawing.shapes(x0 + np.eye(n)[j])
        if [len(s.data) for s in probe] == sizes:
            a[:, j] = np.concatenate([np.asarray(s.data, dtype=np.float64) for s in probe]) - flat0
    return a


def _refused(
    drawing: MechanismDrawing,
    x: np.ndarray,
    checks: list[int],
    predicted: np.ndarray,
    sizes: list[int],
    tol: np.ndarray,
) -> np.ndarray:
    """Per shape: True where the drawing at a position of ``checks`` differs from ``predicted`` (positions x values)
    beyond ``tol`` (absolute plus ``CHECK`` relative), NaN where NaN."""
    edges = np.cumsum([0, *sizes])
    bad = np.zeros(len(sizes), dtype=bool)
    for k in checks:
        drawn = drawing.shapes(x[k])
        lengths = [len(s.data) for s in drawn]
        if lengths != sizes:
            bad |= np.array(lengths) != np.array(sizes)
            continue
        actual = np.concatenate([np.asarray(s.data, dtype=np.float64) for s in drawn]) if sizes else np.zeros(0)
        with np.errstate(invalid="ignore"):
            close = np.abs(predicted[k] - actual) <= tol + CHECK * np.abs(actual)
        close |= np.isnan(predicted[k]) & np.isnan(actual)
        bad |= [not close[edges[i] : edges[i + 1]].all() for i in range(len(sizes))]
    return bad


def scene(result: RunResult, frames: np.ndarray, kept: dict[str, Any] | None = None) -> dict[str, Any]:
    """The scene of the report's page (kinds, roles, static shapes, moving shapes per frame, bounds).

    ``kept``: a dict the caller keeps between the scenes of one mechanism's designs (the studio's session): the
    linear part ``A`` found for one design is tried first on the next (with its own ``b`` from position 1), and found
    anew when the check refuses it."""
    drawing = MechanismDrawing(result.model, result.coords)
    x = np.asarray(result.coords[frames], dtype=np.float64)
    x0 = x[0]
    first = drawing.shapes(x0)
    d0 = [np.asarray(s.data, dtype=np.float64) for s in first]
    sizes = [len(d) for d in d0]
    # Every shape's numbers one after the other: one map d(x) = A x + b for all of them, one product for all positions.
    flat0 = np.concatenate(d0) if d0 else np.zeros(0)
    tol = np.repeat([CHECK * _size(d) for d in d0], sizes)
    # Position 1 gives b; three more (spread over the motion) check the map.
    checks = sorted({len(x) // 3, (2 * len(x)) // 3, len(x) - 1} - {0})
    shape_of = (len(x0), tuple(s.kind for s in first), tuple(sizes))

    def mapped(a: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        with np.errstate(invalid="ignore"):
            predicted = x @ a.T + (flat0 - a @ x0)
        return predicted, _refused(drawing, x, checks, predicted, sizes, tol)

    reused = kept is not None and kept.get("shape_of") == shape_of
    a = kept["a"] if reused and kept is not None else _affine_part(drawing, x0, flat0, sizes)
    predicted, bad = mapped(a)
    # A kept map that refuses a shape its mechanism's own map drew (not a slider's block, which no map draws) is
    # found anew.
    if reused and kept is not None and (bad & ~kept["slow"]).any():
        a = _affine_part(drawing, x0, flat0, sizes)
        predicted, bad = mapped(a)
    if kept is not None:
        kept.update(shape_of=shape_of, a=a, slow=bad)
    edges = np.cumsum([0, *sizes])
    slow = [i for i in range(len(first)) if bad[i]]
    if slow:
        # A shape the map does not draw (a slider's block turned by an angle, a belt's wrap) is drawn at every
        # position by the drawing, as the report draws it.
        rest = [drawing.shapes(row) for row in x]
        for i in slow:
            predicted[:, edges[i] : edges[i + 1]] = [r[i].data for r in rest]
    return _scene_data(first, predicted, edges, len(x))


def _scene_data(first: list[Any], d: np.ndarray, edges: np.ndarray, n: int) -> dict[str, Any]:
    """The scene of the shapes ``first`` whose numbers at every position are the columns ``edges[i]:edges[i+1]`` of
    ``d`` (positions x values)."""
    shapes = range(len(first))
    if not len(first) or not d.shape[1]:
        return {
            "kinds": [s.kind for s in first],
            "roles": [s.role for s in first],
            "static": {str(i): nums(d[0, edges[i] : edges[i + 1]]) for i in shapes},
            "moving": [],
            "frames": [[] for _ in range(n)],
            "bounds": nums(np.asarray((-1.0, 1.0, -1.0, 1.0))),
        }
    # A shape moves when any of its numbers differs from position 1's (NaN equal to NaN).
    same = (d == d[0]) | (np.isnan(d) & np.isnan(d[0]))
    moving = [i for i in shapes if edges[i + 1] > edges[i] and not same[:, edges[i] : edges[i + 1]].all()]
    # The bounds over the positions where a shape is drawn whole: circles and arcs by centre and radius, the rest by
    # their points.
    finite = np.isfinite(d)
    whole = np.column_stack([finite[:, edges[i] : edges[i + 1]].all(axis=1) for i in shapes])
    shown = np.where(np.repeat(whole, np.diff(edges), axis=1), d, np.nan)
    xs, ys = [], []
    for i, s in enumerate(first):
        v = shown[:, edges[i] : edges[i + 1]]
        if s.kind in ("circle", "arc"):
            xs += [v[:, 0] - v[:, 2], v[:, 0] + v[:, 2]]
            ys += [v[:, 1] - v[:, 2], v[:, 1] + v[:, 2]]
        else:
            xs.append(v[:, 0::2].ravel())
            ys.append(v[:, 1::2].ravel())
    bx, by = np.concatenate(xs), np.concatenate(ys)
    lo = np.array([np.fmin.reduce(bx, initial=np.inf), np.fmin.reduce(by, initial=np.inf)])
    hi = np.array([np.fmax.reduce(bx, initial=-np.inf), np.fmax.reduce(by, initial=-np.inf)])
    bounds = (lo[0], hi[0], lo[1], hi[1]) if np.isfinite(lo).all() else (-1.0, 1.0, -1.0, 1.0)
    size = max(bounds[1] - bounds[0], bounds[3] - bounds[2], 1e-300)
    decimals = max(0, 6 - int(np.ceil(np.log10(size))))
    rounded = _rounded(d, decimals)
    per_frame = [rounded[:, edges[i] : edges[i + 1]] for i in moving]
    return {
        "kinds": [s.kind for s in first],
        "roles": [s.role for s in first],
        "static": {str(i): nums(d[0, edges[i] : edges[i + 1]]) for i in shapes if i not in moving},
        "moving": moving,
        "frames": [list(frame) for frame in zip(*per_frame, strict=True)] if moving else [[] for _ in range(n)],
        "bounds": nums(np.asarray(bounds)),
    }


__all__ = ["scene"]
