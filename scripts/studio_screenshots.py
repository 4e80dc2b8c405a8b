"""Takes the pictures of docs/studio.md (docs/images/studio_*.png) in headless Chromium: the four-bar template as
opened, an edit refused (the design on screen stays), a drag that assembles the other branch, an optimisation of the
coupler point through three clicked points, and one of the rocker angle's maximum with a transmission-angle bound.

    .venv/bin/python scripts/studio_screenshots.py

Needs Debian's chromium and playwright (the dev extra)."""

from __future__ import annotations

import shutil
import sys
from pathlib import Path

from playwright.sync_api import Page, sync_playwright

from mechfem.studio_app.server import serve_in_thread

IMAGES = Path(__file__).resolve().parents[1] / "docs" / "images"
FLAGS = ["--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run", "--disable-background-networking"]


def settle(page: Page) -> None:
    page.wait_for_function("!window.mechfemStudio.inflight && !window.mechfemStudio.queued")
    page.wait_for_timeout(300)


def shot(page: Page, name: str) -> None:
    page.screenshot(path=str(IMAGES / f"studio_{name}.png"), clip={"x": 0, "y": 0, "width": 1400, "height": 900})
    print(f"wrote {IMAGES / f'studio_{name}.png'}")


def main() -> int:
    chromium = shutil.which("chromium")
    if chromium is None:
        print("no chromium on the PATH", file=sys.stderr)
        return 1
    running = serve_in_thread(None)
    try:
        with sync_playwright() as p:
            browser = p.chromium.launch(executable_path=chromium, args=FLAGS)
            page = browser.new_page(viewport={"width": 1400, "height": 900}, bypass_csp=True)
            page.goto(running.url)
            page.wait_for_function("window.mechfemStudio && window.mechfemStudio.messages >= 1")
            page.click("#template")
            page.wait_for_function("window.mechfemStudio.D !== null")
            settle(page)
            page.evaluate("window.mechfemStudio.send({op: 'edit', changes: {'crank.length': 1.0}})")
            settle(page)
            shot(page, "template")
            page.get_by_label("rocker.length value").fill("10")
            page.get_by_label("rocker.length value").press("Enter")
            settle(page)
            shot(page, "refused")
            x, y = page.evaluate("window.mechfemStudio.handleAt('B')")
            tx, ty = page.evaluate("window.mechfemStudio.toScreen(3.0, -2.6)")
            page.mouse.move(x, y)
            page.mouse.down()
            for k in range(1, 21):
                page.mouse.move(x + (tx - x) * k / 20, y + (ty - y) * k / 20)
                page.wait_for_timeout(30)
            page.mouse.up()
            settle(page)
            shot(page, "branch")
            page.click("#undo")
            settle(page)
            page.click("#optclick")
            xs = page.evaluate("window.mechfemStudio.D.columns.c9.values")
            ys = page.evaluate("window.mechfemStudio.D.columns.c10.values")
            for k in (0, 120, 240):
                sx, sy = page.evaluate("([x, y]) => window.mechfemStudio.toScreen(x, y)", [xs[k] + 0.1, ys[k] + 0.15])
                page.mouse.click(sx, sy)
            page.click("#optrun")
            page.wait_for_function("!window.mechfemStudio.optimising", timeout=120000)
            settle(page)
            page.evaluate("document.getElementById('optimise').scrollIntoView()")
            page.evaluate("window.scrollTo(0, 0)")
            shot(page, "optimised")
            # The rocker angle's maximum to 130 deg, every transmission angle within [40, 140] deg.
            page.click("#undo")
            settle(page)
            page.select_option("#opttarget", "extremum")
            page.select_option("#optquantity", "psi")
            page.fill("#optvalue", "130")
            page.check("#opttransok")
            page.click("#optrun")
            page.wait_for_function("!window.mechfemStudio.optimising", timeout=120000)
            settle(page)
            page.evaluate("document.getElementById('optimise').scrollIntoView()")
            page.screenshot(path=str(IMAGES / "studio_extremum.png"), full_page=False)
            print(f"wrote {IMAGES / 'studio_extremum.png'}")
            browser.close()
    finally:
        running.stop()
    return 0


if __name__ == "__main__":
    sys.exit(main())
