"""``mechfem.studio(mechanism)`` in a real JupyterLab, driven by Playwright in headless Chromium: a notebook shows
the widget, a dimension is changed in the studio inside the cell, and the next cell reads the edited
:class:`~mechfem.Mechanism` back from the widget.

Skipped without JupyterLab (``pip install jupyterlab``: not a dependency of mechfem), Chromium or Playwright."""

from __future__ import annotations

import json
import os
import secrets
import socket
import subprocess
import sys
import time
import urllib.request
from collections.abc import Iterator
from typing import Any

import pytest

from report.test_report_browser import CHROMIUM
from studio.test_studio_browser import STUDIO_FLAGS

pytest.importorskip("jupyterlab")
pytest.importorskip("anywidget")
sync_api = pytest.importorskip("playwright.sync_api")

pytestmark = [
    pytest.mark.browser,
    pytest.mark.skipif(CHROMIUM is None, reason="no Chromium on the PATH: `make browser` installs Debian's chromium"),
]

CELLS = [
    "import mechfem\n"
    "from mechfem.studio_app.template import four_bar\n"
    "w = mechfem.studio(four_bar(steps=36), height=700)\n"
    "w",
    "edited = w.mechanism\n"
    "print('coupler.v =', edited['coupler.v'].value, type(edited).__name__, edited.run().positions)",
]


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


@pytest.fixture(scope="module")
def lab(tmp_path_factory: pytest.TempPathFactory) -> Iterator[str]:
    """A JupyterLab server on 127.0.0.1 with its own settings folders, serving a folder with the notebook."""
    home = tmp_path_factory.mktemp("lab")
    notebook = {
        "cells": [
            {"cell_type": "code", "metadata": {}, "source": c, "outputs": [], "execution_count": None} for c in CELLS
        ],
        "metadata": {"kernelspec": {"name": "python3", "display_name": "Python 3", "language": "python"}},
        "nbformat": 4,
        "nbformat_minor": 5,
    }
    (home / "studio.ipynb").write_text(json.dumps(notebook))
    token, port = secrets.token_hex(16), _free_port()
    env = {
        **os.environ,
        "JUPYTER_CONFIG_DIR": str(home / "config"),
        "JUPYTER_RUNTIME_DIR": str(home / "runtime"),
        "IPYTHONDIR": str(home / "ipython"),
    }
    lab = subprocess.Popen(
        [sys.executable, "-m", "jupyterlab", "--no-browser", f"--port={port}", "--ip=127.0.0.1",
         f"--IdentityProvider.token={token}", f"--ServerApp.root_dir={home}", "--LabApp.news_url=",
         "--LabApp.check_for_updates_class=jupyterlab.NeverCheckForUpdate", "--LabApp.extension_manager=readonly",
         "--ServerApp.terminals_enabled=False", "--allow-root"],
        env=env, stdout=subprocess.DEVNULL, stderr=(home / "lab.log").open("w"),
    )  # fmt: skip
    url = f"http://127.0.0.1:{port}"
    deadline = time.monotonic() + 60
    while True:
        try:
            urllib.request.urlopen(f"{url}/api/status?token={token}", timeout=2)
            break
        except OSError:
            if time.monotonic() > deadline or lab.poll() is not None:
                lab.kill()
                pytest.fail("JupyterLab did not start: " + (home / "lab.log").read_text()[-2000:])
            time.sleep(0.3)
    yield f"{url}/lab/tree/studio.ipynb?token={token}"
    lab.terminate()
    lab.wait(timeout=20)


def _run_cell(page: Any, k: int) -> None:
    page.locator(".jp-Notebook .jp-Cell").nth(k).click()
    page.keyboard.press("Shift+Enter")


def test_the_widget_edits_a_mechanism_in_a_notebook_and_gives_it_back(lab: str) -> None:
    with sync_api.sync_playwright() as p:
        assert CHROMIUM is not None
        browser = p.chromium.launch(executable_path=CHROMIUM, args=STUDIO_FLAGS)
        try:
            # The studio page forbids eval(); Playwright's waits evaluate their conditions, so only they bypass it.
            page = browser.new_page(viewport={"width": 1400, "height": 1100}, bypass_csp=True)
            page.goto(lab)
            page.wait_for_selector(".jp-Notebook .jp-Cell", timeout=60000)
            # The kernel has started and waits (the status bar says so).
            page.wait_for_function("document.body.innerText.includes('(ipykernel) | Idle')", timeout=60000)
            _run_cell(page, 0)
            widget = page.locator("iframe[title='mechfem studio']")
            widget.wait_for(state="attached", timeout=60000)
            studio = widget.element_handle().content_frame()
            assert studio is not None
            studio.wait_for_function("window.mechfemStudio && window.mechfemStudio.revision >= 0", timeout=30000)
            # Change a named dimension in the studio inside the cell, as a user types it.
            field = studio.get_by_label("coupler.v value")
            field.fill("0.8")
            field.press("Enter")
            studio.wait_for_function("window.mechfemStudio.revision >= 1 && !window.mechfemStudio.inflight")
            assert studio.evaluate("window.mechfemStudio.errors") == []
            _run_cell(page, 1)
            output = page.locator(".jp-Notebook .jp-Cell").nth(1).locator(".jp-OutputArea-output")
            output.wait_for(timeout=30000)
            assert output.inner_text().strip() == "coupler.v = 0.8 Mechanism 37"
        finally:
            browser.close()
