"""Drawing a mechanism: the shapes of every element at one position.

A :class:`MechanismDrawing` looks at the model once (which points are fixed pivots, which binaries are
sliders, where the gear wheels sit) and then turns a vector of co-ordinates into a list of
:class:`Shape` objects. The list has the same length, kinds and roles at every position, so a renderer
makes its artists once and only moves them (:mod:`mechfem.viz.mpl_drawing` for matplotlib, the report, the export).

How each element type is drawn:

* ``BIN``: a bar between its points. A binary whose length is not a constant prescribed row (a free or
  driven length) is a slider: a guide from P through Q and a block at Q (at P when only Q is fixed).
  When P is fixed and the guide keeps its direction, the guide is a hatched rail covering the whole travel.
* ``TR2``: a plate, the triangle P, Q, R. ``TR1``: a plate between P, R and the tip of a short mark at angle beta.
* ``HLF``: an orientation mark: a short line from P at angle beta (left out when a wheel shows the angle).
* ``GR2``: pitch circles of radius ``|R_a|``, ``|R_c|`` at the wheel centres with a radius line at the wheel's
  angle; a ring gear (negative radius, centre distance the difference of the radii) is dashed.
  ``GR1``: the same, with the radii from the ratio i and the distance d between the centres
  (``R_c = d / |1 - i|``, ``|R_a| = |i| R_c``). A wheel centre is the point of the ``HLF`` or ``TR1`` (or
  ``BLT``, ``RK1``, ``RK2``) whose angle co-ordinate is the wheel's; a wheel whose centre is not found is
  left out, and a ``GR1`` with only one centre found gets an orientation mark there.
* ``RK1``, ``RK2``: the pinion's pitch circle (radius ``|i|``) at P and a toothed rack along beta_b (along
  P->Q for ``RK2``), tangent to the pinion on the side where ``v = -i``, long enough for the whole travel.
* ``BLT``: both wheels, the two spans of the belt between the tangent points
  (``phi = beta_b + pi/2 - asin(d / l)``) and the wraps around the wheels.
* ``CRD``: nothing.

Every point is a joint circle when two or more elements share it and a dot otherwise; a point whose two
co-ordinates are both fixed is a fixed pivot with ground hatching, and a point with one fixed co-ordinate is a
slider block on a fixed rail along the other.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass, field

import numpy as np
import numpy.typing as npt

from mechfem.model.echo import Model

FloatArray = npt.NDArray[np.float64]
PointKey = tuple[int, int]
"""A point: the 0-based indices of its x and y co-ordinates."""


@dataclass(frozen=True)
class Shape:
    """One drawn shape. ``data`` is flat and its length depends only on ``kind``.

    * ``line``: a polyline ``x0 y0 x1 y1 ...``; ``polygon``: the same, closed and filled;
    * ``circle``: ``cx cy r``; ``arc``: ``cx cy r a0 a1``, counter-clockwise from angle a0 to a1 (radians);
    * ``segments``: separate segments ``x0 y0 x1 y1`` repeated.

    NaN in ``data`` means the shape is not drawn at this position.
    """

    kind: str
    role: str
    data: list[float]


@dataclass(frozen=True)
class Style:
    """How shapes of one role look, in matplotlib and in the report alike."""

    edge: str
    width: float
    """Line width in points."""
    fill: str | None = None
    dash: bool = False
    layer: int = 2


STYLES: dict[str, Style] = {
    "rail": Style("#3a3a3a", 1.2, layer=1),
    "hatch": Style("#3a3a3a", 0.8, layer=1),
    "ground": Style("#3a3a3a", 1.0, fill="#d9d9d9", layer=1),
    "plate": Style("#1f3b57", 1.6, fill="#a9c8e3", layer=2),
    "wheel": Style("#5b3f8c", 1.3, fill="#eee8f7", layer=0),
    "ring": Style("#5b3f8c", 1.3, dash=True, layer=0),
    "belt": Style("#b35806", 2.0, layer=4),
    "rack": Style("#4d4d4d", 1.3, layer=4),
    "guide": Style("#1f3b57", 1.2, layer=5),
    "bar": Style("#1f3b57", 2.4, layer=6),
    "slider": Style("#1f3b57", 1.4, fill="#fdd49e", layer=7),
    "mark": Style("#c0392b", 1.6, layer=8),
    "joint": Style("#1f3b57", 1.2, fill="#ffffff", layer=9),
    "dot": Style("#1f3b57", 1.0, fill="#1f3b57", layer=9),
}

_NAN = float("nan")
_RACK_TEETH = 24
_HATCHES = 5


def points_of(kind: str, c: Sequence[int]) -> list[PointKey]:
    """The points (x, y co-ordinate indices, 0-based) an element of type ``kind`` has, from its 1-based co-ordinates."""
    i = [n - 1 for n in c]
    match kind:
        case "BIN":
            return [(i[0], i[1]), (i[2], i[3])]
        case "BLT":
            return [(i[0], i[1]), (i[3], i[4])]
        case "HLF":
            return [(i[0], i[1])]
        case "TR1":
            return [(i[0], i[1]), (i[3], i[4])]
        case "TR2" | "RK2":
            return [(i[0], i[1]), (i[2], i[3]), (i[4], i[5])]
        case "RK1":
            return [(i[0], i[1]), (i[3], i[4])]
    return []


def _pt(x: FloatArray, p: PointKey) -> tuple[float, float]:
    return float(x[p[0]]), float(x[p[1]])


def _circle_line(cx: float, cy: float, r: float, angle: float) -> list[float]:
    return [cx, cy, cx + r * math.cos(angle), cy + r * math.sin(angle)]


def _nan_list(n: int) -> list[float]:
    return [_NAN] * n


Part = Callable[[FloatArray], list[Shape]]
"""Draws one thing at a position; returns the same number and kinds of shapes at every position."""


@dataclass
class _Wheel:
    angle: int
    centre: PointKey
    radius: Callable[[FloatArray], float]
    """Signed radius at a position (negative: a ring gear or a crossed belt's wheel)."""
    ring: bool = False


@dataclass
class MechanismDrawing:
    """Turns co-ordinates into shapes; built once per run from the model and every position's co-ordinates."""

    model: Model
    coords: FloatArray
    """positions x co-ordinates (all positions, to size symbols and racks for the whole motion)."""
    notes: list[str] = field(default_factory=list)
    """What could not be drawn as asked, one sentence each."""

    def __post_init__(self) -> None:
        self.coords = np.atleast_2d(np.asarray(self.coords, dtype=np.float64))
        self.fixed = {c.number - 1 for c in self.model.coordinates if not c.moving}
        self._uses: dict[PointKey, int] = {}
        for e in self.model.elements:
            for p in points_of(e.type, e.coords):
                self._uses[p] = self._uses.get(p, 0) + 1
        self.points = list(self._uses)
        self.unit = self._symbol_unit()
        self._centres = self._angle_centres()
        self._parts: list[tuple[int, Part]] = []
        self._wheels: list[_Wheel] = []
        for e in self.model.elements:
            self._add_element(e.number, e.type, [n - 1 for n in e.coords])
        self._add_wheels()
        wheel_angles = {w.angle for w in self._wheels}
        for e in self.model.elements:
            if e.type == "HLF" and e.coords[2] - 1 not in wheel_angles:
                i = [n - 1 for n in e.coords]
                self._add(STYLES["mark"].layer, self._mark_part((i[0], i[1]), i[2]))
        for p in self.points:
            self._add_point(p)
        self._parts.sort(key=lambda lp: lp[0])

    # -- sizes -------------------------------------------------------------------------------------

    def _point_cloud(self, rows: FloatArray) -> FloatArray:
        if not self.points:
            return np.zeros((0, 2))
        ix = [p[0] for p in self.points]
        iy = [p[1] for p in self.points]
        return np.stack([rows[:, ix].ravel(), rows[:, iy].ravel()], axis=1)

    def _symbol_unit(self) -> float:
        """The size of joints, pivots, blocks and marks: small against the mechanism and its shortest links."""
        cloud = self._point_cloud(self.coords)
        cloud = cloud[np.isfinite(cloud).all(axis=1)]
        extent = float(np.hypot(*(cloud.max(axis=0) - cloud.min(axis=0)))) if len(cloud) else 0.0
        x = self.coords[0]
        lengths = []
        for e in self.model.elements:
            pts = points_of(e.type, e.coords)
            if e.type in ("BIN", "TR2", "TR1"):
                for a in range(len(pts)):
                    for b in range(a + 1, len(pts)):
                        pa, pb = _pt(x, pts[a]), _pt(x, pts[b])
                        lengths.append(math.dist(pa, pb))
        lengths = [v for v in lengths if v > 0 and math.isfinite(v)]
        if extent <= 0:
            extent = max(lengths, default=1.0)
        unit = 0.02 * extent
        if lengths:
            unit = min(unit, 0.12 * float(np.median(lengths)))
        return unit

    # -- structure ---------------------------------------------------------------------------------

    def _add(self, layer: int, part: Part) -> None:
        self._parts.append((layer, part))

    def _is_fixed(self, p: PointKey) -> bool:
        return p[0] in self.fixed and p[1] in self.fixed

    def _angle_centres(self) -> dict[int, PointKey]:
        """Angle co-ordinate -> the point it turns about, from the elements that carry an angle co-ordinate."""
        out: dict[int, PointKey] = {}
        # Half beams and ternary-1 elements first: they are what the theory builds wheels from.
        for e in sorted(self.model.elements, key=lambda e: e.type not in ("HLF", "TR1")):
            i = [n - 1 for n in e.coords]
            match e.type:
                case "HLF" | "TR1":
                    out.setdefault(i[2], (i[0], i[1]))
                case "BLT":
                    out.setdefault(i[2], (i[0], i[1]))
                    out.setdefault(i[5], (i[3], i[4]))
                case "RK1":
                    out.setdefault(i[6], (i[0], i[1]))
                case "RK2":
                    out.setdefault(i[7], (i[0], i[1]))
        return out

    def _rigid_length(self, element: int) -> bool:
        """True when the element's LENL is held constant by a prescribed row of its own (not an input)."""
        for row in self.model.prescribed:
            if row.input is None and len(row.terms) == 1:
                t = row.terms[0]
                if t.element == element and t.form == "LENL":
                    return True
        return False

    def _add_element(self, number: int, kind: str, i: list[int]) -> None:
        match kind:
            case "BIN":
                p, q = (i[0], i[1]), (i[2], i[3])
                both_fixed = self._is_fixed(p) and self._is_fixed(q)
                if self._rigid_length(number) or both_fixed:
                    self._add(STYLES["bar"].layer, self._bar_part(p, q))
                else:
                    self._add_slider(p, q)
            case "TR2":
                self._add(STYLES["plate"].layer, self._plate_part([(i[0], i[1]), (i[2], i[3]), (i[4], i[5])]))
            case "TR1":
                self._add(STYLES["plate"].layer, self._tr1_part((i[0], i[1]), i[2], (i[3], i[4])))
            case "GR1":
                self._add_gear(number, i[0], i[2], ratio=i[3])
            case "GR2":
                self._add_gear(number, i[0], i[2], radii=(i[3], i[4]))
            case "RK1":
                self._add_rack((i[0], i[1]), i[5], i[6], rack_point=(i[3], i[4]), rack_angle=i[2])
            case "RK2":
                self._add_rack((i[0], i[1]), i[6], i[7], rack_point=(i[4], i[5]), rack_along=(i[2], i[3]))
            case "BLT":
                p, q, rp, rq = (i[0], i[1]), (i[3], i[4]), i[6], i[7]
                self._add_wheel(_Wheel(i[2], p, lambda x: float(x[rp])))
                self._add_wheel(_Wheel(i[5], q, lambda x: float(x[rq])))
                self._add(STYLES["belt"].layer, self._belt_part(p, q, i[6], i[7]))

    # -- parts -------------------------------------------------------------------------------------

    def _bar_part(self, p: PointKey, q: PointKey) -> Part:
        def draw(x: FloatArray) -> list[Shape]:
            return [Shape("line", "bar", [*_pt(x, p), *_pt(x, q)])]

        return draw

    def _plate_part(self, pts: list[PointKey]) -> Part:
        def draw(x: FloatArray) -> list[Shape]:
            return [Shape("polygon", "plate", [v for p in pts for v in _pt(x, p)])]

        return draw

    def _tr1_part(self, p: PointKey, beta: int, r: PointKey) -> Part:
        u = self.unit

        def draw(x: FloatArray) -> list[Shape]:
            (px, py), (rx, ry) = _pt(x, p), _pt(x, r)
            b = float(x[beta])
            tip = (px + 4.0 * u * math.cos(b), py + 4.0 * u * math.sin(b))
            return [Shape("polygon", "plate", [px, py, *tip, rx, ry])]

        return draw

    def _mark_part(self, p: PointKey, beta: int) -> Part:
        length = 4.0 * self.unit

        def draw(x: FloatArray) -> list[Shape]:
            return [Shape("line", "mark", _circle_line(*_pt(x, p), length, float(x[beta])))]

        return draw

    def _add_rail(self, origin: tuple[float, float], direction: tuple[float, float], lo: float, hi: float) -> None:
        """A fixed, hatched rail along ``direction`` from ``origin``, covering the travel lo..hi of a block on it."""
        u = self.unit
        half_len, half_wid = 1.6 * u, 1.0 * u
        c, s = direction
        lo, hi = min(0.0, lo) - 2.5 * half_len, hi + 2.5 * half_len
        px, py = origin
        nx, ny = s, -c  # the rail lies along the block's side on the right of the direction
        line = [
            px + lo * c + half_wid * nx,
            py + lo * s + half_wid * ny,
            px + hi * c + half_wid * nx,
            py + hi * s + half_wid * ny,
        ]
        hatch: list[float] = []
        count = max(4, min(40, int((hi - lo) / (1.5 * u))))
        for k in range(count):
            t = lo + (hi - lo) * (k + 0.5) / count
            bx, by = px + t * c + half_wid * nx, py + t * s + half_wid * ny
            hatch += [bx, by, bx + 0.8 * u * (nx - c), by + 0.8 * u * (ny - s)]
        self._add(STYLES["rail"].layer, lambda x: [Shape("line", "rail", line)])
        self._add(STYLES["hatch"].layer, lambda x: [Shape("segments", "hatch", hatch)])

    def _block(self, cx: float, cy: float, c: float, s: float) -> list[float]:
        """The corners of a slider block centred at (cx, cy), its long side along (c, s)."""
        half_len, half_wid = 1.6 * self.unit, 1.0 * self.unit
        corners = []
        for a, b in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
            corners += [cx + a * half_len * c - b * half_wid * s, cy + a * half_len * s + b * half_wid * c]
        return corners

    def _add_slider(self, p: PointKey, q: PointKey) -> None:
        """A binary of free (or driven) length: a guide along P->Q and a block that slides on it."""
        if self._is_fixed(q) and not self._is_fixed(p):
            p, q = q, p
        half_len = 1.6 * self.unit
        rows = self.coords
        dx = rows[:, q[0]] - rows[:, p[0]]
        dy = rows[:, q[1]] - rows[:, p[1]]
        angles = np.unwrap(np.arctan2(dy, dx))
        lengths = np.hypot(dx, dy)
        rail = self._is_fixed(p) and bool(np.ptp(angles) < 1e-9) and len(rows) > 1
        if rail:
            # A fixed guide: a hatched rail over the whole travel of the block.
            a = float(angles[0])
            self._add_rail(
                _pt(rows[0], p), (math.cos(a), math.sin(a)), float(np.nanmin(lengths)), float(np.nanmax(lengths))
            )

        def draw(x: FloatArray) -> list[Shape]:
            (px, py), (qx, qy) = _pt(x, p), _pt(x, q)
            length = math.hypot(qx - px, qy - py)
            if length == 0:
                return [Shape("line", "guide", _nan_list(4)), Shape("polygon", "slider", _nan_list(8))]
            c, s = (qx - px) / length, (qy - py) / length
            end = length + 2.0 * half_len
            guide = [px, py, px + end * c, py + end * s]
            corners = self._block(qx, qy, c, s)
            if rail:
                guide = _nan_list(4)
            return [Shape("line", "guide", guide), Shape("polygon", "slider", corners)]

        self._add(STYLES["slider"].layer, draw)

    def _add_gear(
        self, number: int, a: int, c: int, ratio: int | None = None, radii: tuple[int, int] | None = None
    ) -> None:
        ca, cc = self._centres.get(a), self._centres.get(c)
        kind = "GR1" if ratio is not None else "GR2"
        if radii is not None:
            ra, rc = radii
            ring_a = ring_c = False
            if ca is not None and cc is not None:
                x = self.coords[0]
                d = math.dist(_pt(x, ca), _pt(x, cc))
                va, vc = float(x[ra]), float(x[rc])
                internal = va * vc < 0 and abs(d - abs(abs(va) - abs(vc))) <= 1e-3 * max(abs(va), abs(vc))
                ring_a, ring_c = internal and va < 0, internal and vc < 0
            if ca is not None:
                self._add_wheel(_Wheel(a, ca, lambda x: float(x[ra]), ring_a))
            if cc is not None:
                self._add_wheel(_Wheel(c, cc, lambda x: float(x[rc]), ring_c))
        elif ratio is not None and ca is not None and cc is not None:
            pa, pc, ir = ca, cc, ratio

            def radius_c(x: FloatArray) -> float:
                i = float(x[ir])
                d = math.dist(_pt(x, pa), _pt(x, pc))
                if i == 1.0:
                    return _NAN
                # Outer/outer (i < 0) or the ring is the larger wheel: R_c = d / |1 - i|, signed as in GR2.
                rc = d / abs(1.0 - i)
                return -rc if 0.0 < i < 1.0 else rc

            self._add_wheel(_Wheel(c, cc, radius_c, ring=0.0 < float(self.coords[0][ir]) < 1.0))
            self._add_wheel(_Wheel(a, ca, lambda x: -float(x[ir]) * radius_c(x), ring=float(self.coords[0][ir]) > 1.0))
        if ca is None or cc is None:
            missing = [f"angle co-ordinate {n + 1}" for n, cen in ((a, ca), (c, cc)) if cen is None]
            what = "drawn without that wheel"
            if ratio is not None:
                known = [(n, cen) for n, cen in ((a, ca), (c, cc)) if cen is not None]
                for n, cen in known:
                    self._add(STYLES["mark"].layer, self._mark_part(cen, n))
                what = "drawn as an orientation mark at the centre that is known" if known else "not drawn"
            self.notes.append(
                f"element {number} ({kind}): no half beam, ternary-1, belt or rack owns {' and '.join(missing)}, "
                f"so the wheel centre is unknown; {what}."
            )

    def _add_wheel(self, wheel: _Wheel) -> None:
        r0 = wheel.radius(self.coords[0])
        for w in self._wheels:
            if (w.angle, w.centre) == (wheel.angle, wheel.centre):
                same = w.radius(self.coords[0])
                if math.isclose(abs(same), abs(r0), rel_tol=1e-9, abs_tol=1e-12):
                    return
        self._wheels.append(wheel)

    def _add_wheels(self) -> None:
        for w in self._wheels:
            role = "ring" if w.ring else "wheel"

            def draw(x: FloatArray, w: _Wheel = w, role: str = role) -> list[Shape]:
                cx, cy = _pt(x, w.centre)
                r = abs(w.radius(x))
                if not math.isfinite(r) or r == 0:
                    return [Shape("circle", role, _nan_list(3)), Shape("line", "mark", _nan_list(4))]
                return [
                    Shape("circle", role, [cx, cy, r]),
                    Shape("line", "mark", _circle_line(cx, cy, r, float(x[w.angle]))),
                ]

            self._add(STYLES[role].layer, draw)

    def _add_rack(
        self,
        pinion: PointKey,
        ratio: int,
        angle: int,
        rack_point: PointKey,
        rack_angle: int | None = None,
        rack_along: PointKey | None = None,
    ) -> None:
        """Pinion at ``pinion`` (radius |i|); rack pitch line along the rack direction, at v = -i from the pinion."""
        self._add_wheel(_Wheel(angle, pinion, lambda x: float(x[ratio])))

        def direction(x: FloatArray) -> tuple[float, float]:
            if rack_angle is not None:
                b = float(x[rack_angle])
                return math.cos(b), math.sin(b)
            assert rack_along is not None
            (px, py), (qx, qy) = _pt(x, pinion), _pt(x, rack_along)
            length = math.hypot(qx - px, qy - py)
            return ((qx - px) / length, (qy - py) / length) if length > 0 else (_NAN, _NAN)

        # The pinion's travel along the rack, measured from the rack's own point, over the whole motion.
        travel = []
        for x in self.coords:
            c, s = direction(x)
            (px, py), (rx, ry) = _pt(x, pinion), _pt(x, rack_point)
            travel.append((px - rx) * c + (py - ry) * s)
        finite = [t for t in travel if math.isfinite(t)] or [0.0]
        r_max = float(np.nanmax(np.abs(self.coords[:, ratio]))) if len(self.coords) else 0.0
        margin = 1.5 * r_max + 2.0 * self.unit
        lo, hi = min(finite) - margin, max(finite) + margin

        def draw(x: FloatArray) -> list[Shape]:
            c, s = direction(x)
            i = float(x[ratio])
            (px, py), (rx, ry) = _pt(x, pinion), _pt(x, rack_point)
            # The pitch line: through the rack point's projection, at v = -i from the pinion centre.
            nx, ny = -s, c
            v = -i
            u_r = (rx - px) * c + (ry - py) * s
            side = 1.0 if v >= 0 else -1.0
            h = min(0.6 * self.unit + 0.15 * abs(i), 1.5 * self.unit)
            teeth: list[float] = []
            pitch = (hi - lo) / _RACK_TEETH
            for k in range(_RACK_TEETH):
                t0 = lo + k * pitch
                for frac, dv in ((0.0, 0.5), (0.25, -0.5), (0.5, -0.5), (0.75, 0.5)):
                    t = u_r + t0 + frac * pitch
                    vv = v + side * dv * h
                    teeth += [px + t * c + vv * nx, py + t * s + vv * ny]
            vb = v + side * 1.5 * h
            back = [px + (u_r + lo) * c + vb * nx, py + (u_r + lo) * s + vb * ny]
            back += [px + (u_r + hi) * c + vb * nx, py + (u_r + hi) * s + vb * ny]
            return [Shape("line", "rack", teeth), Shape("line", "rack", back)]

        self._add(STYLES["rack"].layer, draw)

    def _belt_part(self, p: PointKey, q: PointKey, rp: int, rq: int) -> Part:
        """The two spans between the tangent points (elements.md, BLT) and the wraps around both wheels."""

        def draw(x: FloatArray) -> list[Shape]:
            (px, py), (qx, qy) = _pt(x, p), _pt(x, q)
            r_p, r_q = float(x[rp]), float(x[rq])
            length = math.hypot(qx - px, qy - py)
            d = r_p - r_q
            if length <= abs(d) or length == 0:
                return [Shape("line", "belt", _nan_list(4))] * 2 + [Shape("arc", "belt", _nan_list(5))] * 2
            beta = math.atan2(qy - py, qx - px)
            tilt = math.pi / 2 - math.asin(d / length)
            phis = (beta + tilt, beta - tilt)
            spans = []
            contact_p, contact_q = [], []
            for phi in phis:
                cp = (px + r_p * math.cos(phi), py + r_p * math.sin(phi))
                cq = (qx + r_q * math.cos(phi), qy + r_q * math.sin(phi))
                spans.append(Shape("line", "belt", [*cp, *cq]))
                contact_p.append(math.atan2(cp[1] - py, cp[0] - px))
                contact_q.append(math.atan2(cq[1] - qy, cq[0] - qx))
            wraps = [
                Shape("arc", "belt", [px, py, abs(r_p), *_wrap(contact_p, beta + math.pi)]),
                Shape("arc", "belt", [qx, qy, abs(r_q), *_wrap(contact_q, beta)]),
            ]
            return spans + wraps

        return draw

    def _add_point(self, p: PointKey) -> None:
        u = self.unit
        if self._is_fixed(p):
            x0 = self.coords[0]
            px, py = _pt(x0, p)
            h, w = 2.0 * u, 1.3 * u
            tri = [px, py, px - w, py - h, px + w, py - h]
            base = py - h
            hatch = [px - 1.6 * w, base, px + 1.6 * w, base]
            for k in range(_HATCHES):
                hx = px - 1.6 * w + (k + 1) * 3.2 * w / (_HATCHES + 1)
                hatch += [hx, base, hx - 0.7 * u, base - 0.9 * u]
            self._add(STYLES["ground"].layer, lambda x: [Shape("polygon", "ground", tri)])
            self._add(STYLES["hatch"].layer, lambda x: [Shape("segments", "hatch", hatch)])
        elif p[0] in self.fixed or p[1] in self.fixed:
            # One co-ordinate fixed: the point slides along a fixed line, a block on a rail.
            horizontal = p[1] in self.fixed
            free = self.coords[:, p[0] if horizontal else p[1]]
            base = float(self.coords[0, p[1] if horizontal else p[0]])
            c, s = (1.0, 0.0) if horizontal else (0.0, 1.0)
            origin = (0.0, base) if horizontal else (base, 0.0)
            self._add_rail(origin, (c, s), float(np.nanmin(free)), float(np.nanmax(free)))
            self._add(STYLES["slider"].layer, lambda x: [Shape("polygon", "slider", self._block(*_pt(x, p), c, s))])
        joint = self._uses.get(p, 0) >= 2 or self._is_fixed(p)
        role = "joint" if joint else "dot"
        radius = 0.55 * u if joint else 0.35 * u

        def draw(x: FloatArray) -> list[Shape]:
            return [Shape("circle", role, [*_pt(x, p), radius])]

        self._add(STYLES[role].layer, draw)

    # -- use ---------------------------------------------------------------------------------------

    def shapes(self, x: FloatArray) -> list[Shape]:
        """Every shape at the position with co-ordinates ``x`` (all co-ordinates, deck order)."""
        out: list[Shape] = []
        for _, part in self._parts:
            out += part(np.asarray(x, dtype=np.float64))
        return out

    def bounds(self, positions: Iterable[int] | None = None) -> tuple[float, float, float, float]:
        """(xmin, xmax, ymin, ymax) of every shape at the given positions (0-based; default: all)."""
        rows = range(len(self.coords)) if positions is None else positions
        lo, hi = np.array([np.inf, np.inf]), np.array([-np.inf, -np.inf])
        for k in rows:
            for s in self.shapes(self.coords[k]):
                for a, b in _extent(s):
                    lo, hi = np.minimum(lo, a), np.maximum(hi, b)
        if not np.isfinite(lo).all():
            return (-1.0, 1.0, -1.0, 1.0)
        return float(lo[0]), float(hi[0]), float(lo[1]), float(hi[1])


def _wrap(contacts: list[float], far: float) -> tuple[float, float]:
    """The counter-clockwise arc between two contact angles that passes the direction ``far``."""
    a, b = contacts
    span = (b - a) % (2 * math.pi)
    if (far - a) % (2 * math.pi) <= span:
        return a, a + span
    return b, b + (a - b) % (2 * math.pi)


def _extent(s: Shape) -> list[tuple[FloatArray, FloatArray]]:
    d = np.asarray(s.data, dtype=np.float64)
    if not np.isfinite(d).all():
        return []
    if s.kind in ("circle", "arc"):
        c = d[:2]
        return [(c - d[2], c + d[2])]
    xy = d.reshape(-1, 2)
    return [(xy.min(axis=0), xy.max(axis=0))]


def arc_points(cx: float, cy: float, r: float, a0: float, a1: float, n: int = 48) -> tuple[FloatArray, FloatArray]:
    """Points along an arc, for renderers without arcs."""
    t = np.linspace(a0, a1, n)
    return cx + r * np.cos(t), cy + r * np.sin(t)
