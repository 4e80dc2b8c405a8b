"""The shapes of a :class:`~mechfem.viz.drawing.MechanismDrawing` as matplotlib artists, for the pictures and the
animation. Kept apart from the geometry so that the report and the DXF/SVG export draw the same shapes
without matplotlib."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from mechfem.viz.drawing import STYLES, FloatArray, MechanismDrawing, arc_points

if TYPE_CHECKING:
    from matplotlib.artist import Artist


class MplMechanism:
    """The shapes of a :class:`MechanismDrawing` as matplotlib artists on ``ax``; :meth:`update` moves them."""

    def __init__(self, ax: object, drawing: MechanismDrawing, x: FloatArray, alpha: float = 1.0) -> None:
        from matplotlib.axes import Axes
        from matplotlib.collections import LineCollection
        from matplotlib.lines import Line2D
        from matplotlib.patches import Circle, Polygon

        assert isinstance(ax, Axes)
        self.drawing = drawing
        self.artists: list[Artist] = []
        for s in drawing.shapes(x):
            st = STYLES[s.role]
            z = 2.0 + st.layer * 0.1
            artist: Artist
            if s.kind in ("line", "arc"):
                artist = Line2D([], [], color=st.edge, lw=st.width, ls="--" if st.dash else "-", zorder=z, alpha=alpha)
                ax.add_line(artist)
            elif s.kind == "polygon":
                artist = Polygon(
                    np.zeros((3, 2)), closed=True, fc=st.fill or "none", ec=st.edge, lw=st.width, zorder=z, alpha=alpha
                )
                ax.add_patch(artist)
            elif s.kind == "circle":
                artist = Circle(
                    (0, 0),
                    1,
                    fc=st.fill or "none",
                    ec=st.edge,
                    lw=st.width,
                    ls="--" if st.dash else "-",
                    zorder=z,
                    alpha=alpha,
                )
                ax.add_patch(artist)
            else:
                artist = LineCollection([], colors=st.edge, linewidths=st.width, zorder=z, alpha=alpha)
                ax.add_collection(artist)
            self.artists.append(artist)
        self.update(x)

    def update(self, x: FloatArray) -> list[Artist]:
        """Moves every artist to the position with co-ordinates ``x``; returns the artists."""
        from matplotlib.collections import LineCollection
        from matplotlib.lines import Line2D
        from matplotlib.patches import Circle, Polygon

        for artist, s in zip(self.artists, self.drawing.shapes(x), strict=True):
            d = np.asarray(s.data, dtype=np.float64)
            ok = bool(np.isfinite(d).all())
            if isinstance(artist, Line2D):
                if s.kind == "arc" and ok:
                    artist.set_data(*arc_points(*d))
                elif ok:
                    artist.set_data(d[0::2], d[1::2])
                artist.set_visible(ok)
            elif isinstance(artist, Polygon):
                if ok:
                    artist.set_xy(d.reshape(-1, 2))
                artist.set_visible(ok)
            elif isinstance(artist, Circle):
                if ok:
                    artist.set_center((d[0], d[1]))
                    artist.set_radius(d[2])
                artist.set_visible(ok)
            elif isinstance(artist, LineCollection):
                artist.set_segments(list(d.reshape(-1, 2, 2)) if ok else [])
        return self.artists
