"""The mechanism's shapes at every position, fast enough to redraw a whole motion on every edit.

The report's drawing (:class:`mechfem.drawing.MechanismDrawing`) gives the shapes at one position from all the
co-ordinates; for pin-jointed elements (bars, plates, pivots, the frame's hatching) each shape's numbers are an affine
function of the co-ordinates: ``d(x) = A x + b``. :func:`scene` finds ``A`` and ``b`` of each shape from the drawing
itself (the shapes at position 1 and with each co-ordinate moved by one unit), checks that they give the drawing's
own shapes at five positions spread over the motion, and then computes the shape at every position with one matrix
product. A shape that fails the check (a slider's block turned by an angle, a belt's wrap) is drawn at every position
by the drawing as the report does. The result is the report's scene (:func:`mechfem.report._scene`): the same
shapes, the numbers rounded to the 6th digit of the drawing's size.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from mechfem.drawing import MechanismDrawing
from mechfem.report_charts import nums
from mechfem.result import RunResult

#: Relative tolerance of the affinity check.
CHECK = 1e-9

#: A shape's affine map: ``A`` and ``b`` of ``d(x) = A x + b``.
Affine = tuple[np.ndarray, np.ndarray]


def _rounded(a: np.ndarray, decimals: int) -> np.ndarray:
    """``a`` rounded to ``decimals`` (the 6th digit of the drawing's size: far below a pixel, and short in JSON), NaN
    where not finite (written as null by the server's orjson, as numpy arrays are)."""
    a = np.round(a, decimals)
    return np.where(np.isfinite(a), a, np.nan)


def _size(d: np.ndarray) -> float:
    finite = d[np.isfinite(d)]
    return 1.0 + (float(np.abs(finite).max()) if len(finite) else 0.0)


def _same(predicted: np.ndarray, drawn: Any, tol: float) -> bool:
    """Equal within ``tol`` (absolute plus ``CHECK`` relative), NaN where NaN: ``np.allclose`` without its cost."""
    actual = np.asarray(drawn, dtype=np.float64)
    with np.errstate(invalid="ignore"):
        close = np.abs(predicted - actual) <= tol + CHECK * np.abs(actual)
    return bool(np.all(close | (np.isnan(predicted) & np.isnan(actual))))


def _affine_maps(drawing: MechanismDrawing, x0: np.ndarray, d0: list[np.ndarray]) -> list[Affine | None]:
    """``A`` and ``b`` of each shape from the drawing at ``x0`` and with each co-ordinate moved by one unit (None: a
    shape whose number of values changes)."""
    n = len(x0)
    # Column j of A: how each shape moves when co-ordinate j moves by one unit.
    probes = [drawing.shapes(x0 + np.eye(n)[j]) for j in range(n)]
    maps: list[Affine | None] = []
    for i in range(len(d0)):
        cols = [np.asarray(p[i].data, dtype=np.float64) - d0[i] for p in probes]
        if any(len(c) != len(d0[i]) for c in cols):
            maps.append(None)
            continue
        a = np.column_stack(cols) if n else np.zeros((len(d0[i]), 0))
        maps.append((a, d0[i] - a @ x0))
    return maps


def scene(result: RunResult, frames: np.ndarray, kept: dict[str, Any] | None = None) -> dict[str, Any]:
    """The scene of the report's page (kinds, roles, static shapes, moving shapes per frame, bounds).

    ``kept``: a dict the caller keeps between the scenes of one mechanism's designs (the studio's session); the affine
    maps found for one design are tried first on the next, and found anew when the check refuses them."""
    drawing = MechanismDrawing(result.model, result.coords)
    x = np.asarray(result.coords[frames], dtype=np.float64)
    x0 = x[0]
    first = drawing.shapes(x0)
    d0 = [np.asarray(s.data, dtype=np.float64) for s in first]
    checks = sorted({0, len(x) // 4, len(x) // 2, (3 * len(x)) // 4, len(x) - 1})
    seen = {k: drawing.shapes(x[k]) for k in checks}

    def checked(i: int, m: Affine | None) -> np.ndarray | None:
        if m is None or m[0].shape != (len(d0[i]), len(x0)):
            return None
        a, b = m
        tol = CHECK * _size(d0[i])
        ok = all(len(seen[k][i].data) == len(d0[i]) and _same(a @ x[k] + b, seen[k][i].data, tol) for k in checks)
        return x @ a.T + b if ok else None

    shape_of = (len(x0), tuple(s.kind for s in first), tuple(len(d) for d in d0))
    per_shape: list[np.ndarray | None] = []
    if kept is not None and kept.get("shape_of") == shape_of:
        maps = kept["maps"]
        per_shape = [checked(i, m) for i, m in enumerate(maps)]
        if any(m is not None and v is None for m, v in zip(maps, per_shape, strict=True)):
            per_shape = []
    if not per_shape:
        maps = _affine_maps(drawing, x0, d0)
        per_shape = [checked(i, m) for i, m in enumerate(maps)]
        if kept is not None:
            kept.update(shape_of=shape_of, maps=maps)
    slow = [i for i, v in enumerate(per_shape) if v is None]
    if slow:
        rest = [drawing.shapes(row) for row in x]
        for i in slow:
            per_shape[i] = np.array([np.asarray(r[i].data, dtype=np.float64) for r in rest])
    data = [v for v in per_shape if v is not None]
    moving = [i for i, v in enumerate(data) if not np.array_equal(v, np.broadcast_to(v[0], v.shape), equal_nan=True)]
    # The bounds of every shape over the frames: circles and arcs by centre and radius, the rest by their points.
    lo, hi = np.array([np.inf, np.inf]), np.array([-np.inf, -np.inf])
    for s, v in zip(first, data, strict=True):
        good = v[np.isfinite(v).all(axis=1)]
        if not len(good):
            continue
        if s.kind in ("circle", "arc"):
            lo = np.minimum(lo, (good[:, :2] - good[:, 2:3]).min(axis=0))
            hi = np.maximum(hi, (good[:, :2] + good[:, 2:3]).max(axis=0))
        else:
            xy = good.reshape(len(good), -1, 2)
            lo, hi = np.minimum(lo, xy.min(axis=(0, 1))), np.maximum(hi, xy.max(axis=(0, 1)))
    bounds = (lo[0], hi[0], lo[1], hi[1]) if np.isfinite(lo).all() else (-1.0, 1.0, -1.0, 1.0)
    size = max(bounds[1] - bounds[0], bounds[3] - bounds[2], 1e-300)
    decimals = max(0, 6 - int(np.ceil(np.log10(size))))
    per_frame = [_rounded(data[i], decimals) for i in moving]
    return {
        "kinds": [s.kind for s in first],
        "roles": [s.role for s in first],
        "static": {str(i): nums(data[i][0]) for i in range(len(first)) if i not in moving},
        "moving": moving,
        "frames": [list(shapes) for shapes in zip(*per_frame, strict=True)] if moving else [[] for _ in x],
        "bounds": nums(np.asarray(bounds)),
    }


__all__ = ["scene"]
