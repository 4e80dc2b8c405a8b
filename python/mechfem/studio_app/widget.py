"""``mechfem.studio(mechanism)`` in Jupyter: the studio's page in the notebook, editing a copy of the mechanism,
which :attr:`StudioWidget.mechanism` gives back as edited.

The widget is an anywidget (``mechfem[studio]``) that shows the page of a studio server started for it on
127.0.0.1 in a thread of the kernel: the page and the server are the command's own, so everything the command does
the widget does. The notebook's browser must therefore run on the same computer as the kernel (as with a local
JupyterLab or VS Code); a remote kernel's server is not reachable from the browser.
"""

from __future__ import annotations

import copy
from typing import Any

import anywidget
import traitlets

from mechfem.model.mechanism import Mechanism
from mechfem.studio_app.server import Running, serve_in_thread
from mechfem.studio_app.session import Session

_ESM = """
function render({ model, el }) {
  const frame = document.createElement("iframe");
  frame.src = model.get("url");
  frame.style.width = "100%";
  frame.style.height = model.get("height") + "px";
  frame.style.border = "1px solid #c9ced6";
  frame.title = "mechfem studio";
  el.appendChild(frame);
}
export default { render };
"""


class StudioWidget(anywidget.AnyWidget):
    """The studio in a notebook cell; :attr:`mechanism` is the design as edited so far."""

    _esm = traitlets.Unicode(_ESM).tag(sync=True)
    url = traitlets.Unicode("").tag(sync=True)
    height = traitlets.Int(900).tag(sync=True)

    def __init__(self, mechanism: Mechanism, height: int = 900, **kwargs: Any) -> None:
        self._running: Running = serve_in_thread(Session(copy.deepcopy(mechanism)))
        super().__init__(url=self._running.url, height=height, **kwargs)

    @property
    def mechanism(self) -> Mechanism:
        """The edited mechanism (a copy of the one given: that one is left as it was)."""
        session = self._running.actions.session
        assert session is not None
        return session.mechanism

    def stop(self) -> None:
        """Stops the widget's server (the page in the cell stops answering)."""
        self._running.stop()


def studio(mechanism: Mechanism, height: int = 900) -> StudioWidget:
    """Shows ``mechanism`` in the studio in a Jupyter notebook; ``.mechanism`` of the widget returned is the edited
    design."""
    return StudioWidget(mechanism, height)


__all__ = ["StudioWidget", "studio"]
