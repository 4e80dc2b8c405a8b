"""mechfem studio: a local web application that edits a :class:`~mechfem.Mechanism` and shows its motion live.

The parts, each importing only the ones above it:

* :mod:`.template`: the four-bar a new design starts from.
* :mod:`.session`: one design being edited (no web at all): its named dimensions and points, an edit that re-runs
  the whole motion on the kept compiled model, the last good design, undo and redo, saving.
* :mod:`.view`: what the page draws of a run, the report's data (:func:`mechfem.report.html.report_data`) and more.
* :mod:`.server`: the Starlette application (HTTP and one websocket) behind a random token, served by uvicorn on
  127.0.0.1 only.
* :mod:`.command`: ``mechfem studio [DECK] [--port N] [--no-browser]``.
* :mod:`.widget`: ``mechfem.studio(mechanism)`` in Jupyter (anywidget).

The web parts need the optional dependencies of ``mechfem[studio]``; :func:`missing` says how to install them.
"""

from __future__ import annotations

import importlib.util

#: The modules ``mechfem studio`` needs beyond mechfem's own, with the distribution that brings each.
NEEDS = {"starlette": "starlette", "uvicorn": "uvicorn", "websockets": "websockets", "orjson": "orjson"}

INSTALL = "pip install 'mechfem[studio]'"


def missing(needs: dict[str, str] | None = None) -> list[str]:
    """The distributions of ``needs`` (default :data:`NEEDS`) that are not installed."""
    return [dist for module, dist in (needs or NEEDS).items() if importlib.util.find_spec(module) is None]


__all__ = ["INSTALL", "NEEDS", "missing"]
