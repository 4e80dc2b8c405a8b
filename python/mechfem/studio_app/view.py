"""What the studio's page draws of a design: the data of the report's page (:func:`mechfem.report.html.report_data`: the
mechanism per position, det(D^c) with its limit positions, the deck's pictures as charts, the paths) for its last
good run, with the transmission angles, the named dimensions and the points to drag.

It is put together from the report's own parts (:mod:`mechfem.report.charts`), with the mechanism's shapes from
:func:`mechfem.studio_app.scene.scene` (the report's shapes, computed for all positions at once) and without what
the page of the studio does not show (the table of buffers, the print file's lines), so that a four-bar's view
takes a few milliseconds."""

from __future__ import annotations

from typing import Any

import numpy as np

from mechfem.model.mechanism import Mechanism
from mechfem.model.parts import Element
from mechfem.report.charts import (
    Columns,
    all_labels,
    function_charts,
    limit_markers,
    main_axis,
    page_cards,
    page_styles,
    paths,
)
from mechfem.results.designer import FRAMED, transmission_angle
from mechfem.results.result import RunResult
from mechfem.results.result_tables import run_units
from mechfem.studio_app.scene import scene
from mechfem.studio_app.session import Session


def six_digits(values: Any) -> np.ndarray:
    """``values`` to 6 significant digits, NaN where not finite (written as null: :func:`mechfem.studio_app.server`
    writes numpy arrays as they are): :func:`mechfem.report.charts.nums` for a whole column at once
    (tests/studio/test_studio.py compares the two)."""
    v = np.asarray(values, dtype=np.float64).ravel()
    finite = np.isfinite(v) & (v != 0.0)
    with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
        exponent = np.floor(np.log10(np.abs(np.where(finite, v, 1.0))))
        scale = 10.0 ** (5.0 - exponent)
        rounded = np.round(v * scale) / scale
    # A number too small for its scale (a subnormal) is kept as it is.
    rounded = np.where(finite & np.isfinite(rounded), rounded, v)
    return np.where(np.isfinite(v), rounded, np.nan)


class StudioColumns(Columns):
    """The report's columns, each rounded at once (:func:`six_digits`): a column per value costs more than a run."""

    def rounded(self, values: np.ndarray) -> Any:
        return six_digits(values)

    def values(self, key: str) -> list[float | None]:
        v = self.table[key]["values"]
        if not np.isnan(v).any():
            return list(v.tolist())
        out: np.ndarray = v.astype(object)
        out[np.isnan(v)] = None
        return list(out.tolist())


def _moving_points(result: RunResult, mech: Mechanism, cols: Columns) -> list[dict[str, Any]]:
    """Paths of the points that are on one element only (a coupler point), or of every moving point."""
    nb = result.numbering
    uses: dict[int, int] = {}
    for e in mech.elements:
        for s in e.points:
            uses[id(s)] = uses.get(id(s), 0) + 1
    moving = [p for p in mech.points if not (p.x.fixed and p.y.fixed)]
    traced = [p for p in moving if uses.get(id(p), 0) == 1] or moving
    out = []
    for p in traced:
        ix, iy = nb.coord_number[p.x], nb.coord_number[p.y]
        out.append(
            {
                "name": p.name,
                "x": cols.coordinate(result, ix),
                "y": cols.coordinate(result, iy),
                "vx": None,
                "vy": None,
                "scale": None,
            }
        )
    return out


def design_data(result: RunResult, mech: Mechanism, kept: dict[str, Any] | None = None) -> dict[str, Any]:
    """The report page's data of ``result`` (the parts the studio shows), every position a frame; ``kept``: what the
    drawing of one design keeps for the next (:func:`mechfem.studio_app.scene.scene`)."""
    frames = np.arange(result.positions)
    labels = all_labels(result)
    cols = StudioColumns(frames, run_units(result))
    xkey = main_axis(result, labels, cols)
    det = cols.add("det", "det(D^c)", "", "det", result.det, text="det(D^c), the determinant of the dependent columns")
    drawn = scene(result, frames, kept)
    x0, x1, y0, y1 = (v if v is not None else 0.0 for v in drawn["bounds"])
    xkey, cards, named = page_cards(result, labels, cols, xkey, float(np.hypot(x1 - x0, y1 - y0)))
    inputs = [f"b{b.number}" for b in result.storage.buffers if b.keyword == "BUFINP" and f"b{b.number}" in cols.table]
    if named:
        inputs = [xkey]
    traced = paths(result, cols) or (_moving_points(result, mech, cols) if result.named else [])
    report = result.report
    return {
        "stem": result.deck.stem,
        "positions": result.positions,
        "asked": report.steps + 1,
        "frames": [int(k) for k in frames],
        "position_columns": inputs,
        "styles": page_styles(),
        "scene": drawn,
        "paths": traced,
        "det": {"x": xkey, "y": det, "limits": limit_markers(result, xkey)},
        "cards": cards,
        "columns": cols.table,
        "warnings": list(report.warnings),
        "stop": report.stop_reason(),
    }


def transmission_pairs(mech: Mechanism) -> list[tuple[Element, Element, str]]:
    """The pairs whose angle is a transmission angle: a link that is not driven, jointed to the frame, and a link
    that is not, meeting at a moving point (a four-bar's coupler and rocker at B); with that point's name."""
    driven = {p.element.name for r in mech.rows if r.kind == "input" for _, p in r.terms}

    def grounded(e: Element) -> bool:
        return any(p.x.fixed and p.y.fixed for p in e.points)

    def points(e: Element) -> list[Any]:
        return list(e.points)

    framed = [e for e in mech.elements if e.type in FRAMED]
    out = []
    for out_link in framed:
        if out_link.name in driven or not grounded(out_link):
            continue
        for coupler in framed:
            if coupler is out_link or grounded(coupler):
                continue
            shared = [p for p in points(out_link) if any(p is q for q in points(coupler)) and not p.x.fixed]
            if shared:
                out.append((coupler, out_link, shared[0].name))
    return out


def _transmission_card(result: RunResult, data: dict[str, Any], mech: Mechanism) -> dict[str, Any] | None:
    if any(b.keyword == "BUFTRA" for b in result.storage.buffers):
        return None  # the deck's own transmission angles are charted already
    xkey = data["det"]["x"]
    frames = np.asarray(data["frames"])
    keys = []
    for coupler, link, at in transmission_pairs(mech):
        mu = transmission_angle(result, coupler, link)
        key = f"mu:{coupler.name}:{link.name}"
        unit = mech.units.angle or "rad"
        data["columns"][key] = {
            "name": f"mu({coupler.name}, {link.name})",
            "unit": unit,
            "kind": "transmission",
            "axis": f"mu at {at} [{unit}]",
            "header": f"mu({coupler.name}, {link.name}) [{unit}]",
            "text": f"the transmission angle between {coupler.name} and {link.name} at {at}",
            "values": np.where(np.isfinite(mu[frames]), mu[frames], np.nan),
        }
        keys.append(key)
    if not keys:
        return None
    return {
        "title": "transmission angles",
        "picture": None,
        "charts": function_charts(xkey, keys, Columns(frames, table=data["columns"])),
    }


def view(session: Session) -> dict[str, Any]:
    """Everything the page shows of ``session``'s last good design, as JSON-ready data."""
    result = session.result
    mech = session.mechanism
    data = design_data(result, mech, session.drawing_kept)
    card = _transmission_card(result, data, mech)
    if card is not None:
        data["cards"].append(card)
    data["studio"] = {
        "name": mech.name,
        "deck": str(session.deck) if session.deck else None,
        "units": {k: v for k, v in mech.units.as_dict().items() if v},
        "dimensions": session.dimensions(),
        "points": session.points(),
        # What an optimisation may aim at: the named outputs and the moving points' co-ordinates (an extremum over
        # the motion), and whether the mechanism has a transmission angle to bound.
        "quantities": [r.name for r in mech.rows if r.kind == "output"]
        + [f"{p['name']}.{a}" for p in session.points() if not p["fixed"] for a in "xy"],
        "transmission": bool(transmission_pairs(mech)),
        "revision": session.revision,
        "can_undo": session.can_undo,
        "can_redo": session.can_redo,
    }
    return data


__all__ = ["transmission_pairs", "view"]
