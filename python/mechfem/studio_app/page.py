"""The studio's page: one HTML document with uPlot, the report's chart and drawing scripts and the studio's own
script inlined (as the report is), allowed to connect to its own server's websocket only. Its head is the report's
(:func:`mechfem.report.html.page_template`)."""

from __future__ import annotations

import re

from mechfem.report.html import PAGE_PARTS, _part, page_template

#: The page's parts, by the template's placeholder: the report's (uPlot, its style, its charts, the drawing) and the
#: studio's own (python/mechfem/studio_app/assets).
PARTS = {
    "UPLOT_CSS": PAGE_PARTS["UPLOT_CSS"],
    "UPLOT_JS": PAGE_PARTS["UPLOT_JS"],
    "PAGE_CSS": PAGE_PARTS["PAGE_CSS"],
    "CHARTS_JS": PAGE_PARTS["CHARTS_JS"],
    "SCENE_JS": PAGE_PARTS["SCENE_JS"],
    "STUDIO_CSS": "studio_app/assets/studio.css",
    "STUDIO_JS": "studio_app/assets/studio.js",
}


def render_page(host: str) -> str:
    """The page, allowed to open a websocket to ``host`` (``127.0.0.1:PORT``) only."""
    from mechfem._version import __version__

    parts = {key: _part(name) for key, name in PARTS.items()}
    parts["TITLE"] = "mechfem studio"
    # The report's policy, and: the charts' CSV downloads are blob: links; the websocket to this server only.
    parts["CSP_MORE"] = f" blob:; connect-src ws://{host}"
    parts["VERSION"] = __version__
    return re.sub(r"\{\{([A-Z_]+)\}\}", lambda m: parts[m.group(1)], page_template("studio_app/assets/studio.html"))


__all__ = ["PARTS", "render_page"]
