"""mechfem studio in headless Chromium (Debian's, as tests/report/test_report_browser.py uses), driven by Playwright
with real mouse and keyboard input: open a deck with the file picker, drag a frame pivot, change a named dimension, see
an impossible edit refused, save, compare what the page shows with ``mechfem run`` of the saved deck, undo.

Skipped without Chromium (``make browser`` installs it) or without the Playwright package (``mechfem[dev]``)."""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from mechfem.cli import command as cli
from report.test_report_browser import CHROMIUM, FLAGS

pytest.importorskip("uvicorn")
sync_api = pytest.importorskip("playwright.sync_api")

from mechfem.studio_app.server import Running, serve_in_thread  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]
FOURBAR = ROOT / "examples" / "fourbar" / "fourbar.mec"
needs_chromium = pytest.mark.skipif(
    CHROMIUM is None,
    reason="no Chromium on the PATH: `make browser` installs Debian's chromium (as root); `make test` calls it",
)
pytestmark = [pytest.mark.browser, needs_chromium]
# The report's flags, but the page's own server on 127.0.0.1 resolves and is reached directly.
STUDIO_FLAGS = [
    "--host-resolver-rules=MAP * ~NOTFOUND, EXCLUDE 127.0.0.1" if f.startswith("--host-resolver-rules") else f
    for f in FLAGS
    if f != "--headless"
] + ["--proxy-bypass-list=127.0.0.1"]


@pytest.fixture(scope="module")
def server(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Running]:
    # The folder the studio is pointed at: the slider-crank, whose crank follows the table crank.dat beside it.
    folder = tmp_path_factory.mktemp("folder")
    for name in ("slider_crank.mec", "crank.dat"):
        (folder / name).write_bytes((ROOT / "examples" / "slider_crank" / name).read_bytes())
    running = serve_in_thread(None, folder=folder)
    yield running
    running.stop()


@pytest.fixture(scope="module")
def page(server: Running) -> Iterator[Any]:
    with sync_api.sync_playwright() as p:
        assert CHROMIUM is not None
        browser = p.chromium.launch(executable_path=CHROMIUM, args=STUDIO_FLAGS)
        # The page's policy forbids eval(); Playwright's waits evaluate their conditions, so only they bypass it.
        pg = browser.new_page(viewport={"width": 1400, "height": 1000}, bypass_csp=True)
        pg.goto(server.url)
        pg.wait_for_function("window.mechfemStudio && window.mechfemStudio.messages >= 1")
        yield pg
        browser.close()


def settled(page: Any, revision: int | None = None) -> None:
    """Waits until the page has its answer (and, given ``revision``, shows at least that revision)."""
    page.wait_for_function(
        "(r) => !window.mechfemStudio.inflight && !window.mechfemStudio.queued && window.mechfemStudio.revision >= r",
        arg=-1 if revision is None else revision,
    )


def shown(page: Any, key: str) -> np.ndarray:
    values = page.evaluate("(k) => window.mechfemStudio.D.columns[k].values", key)
    return np.array([np.nan if v is None else v for v in values])


def test_open_drag_edit_save_compare_undo(page: Any, server: Running, tmp_path: Path) -> None:
    # Open a deck with the file picker.
    page.set_input_files("#file", str(FOURBAR))
    page.wait_for_function("window.mechfemStudio.D && window.mechfemStudio.D.studio.name === 'fourbar'")
    settled(page, 0)
    assert page.text_content("#status").startswith("Opened")
    assert page.evaluate("window.mechfemStudio.D.positions") == 145
    psi0 = shown(page, "b21")

    # Drag the frame pivot B0 40 pixels to the right with the mouse.
    x, y = page.evaluate("window.mechfemStudio.handleAt('B0')")
    left, right = page.evaluate("[window.mechfemStudio.toScreen(0, 0), window.mechfemStudio.toScreen(1, 0)]")
    scale = right[0] - left[0]  # pixels per unit of length
    page.mouse.move(x, y)
    page.mouse.down()
    for k in range(1, 9):
        page.mouse.move(x + 5 * k, y)
    page.mouse.up()
    settled(page, 1)
    b0 = server.actions.session.mechanism["B0"]  # type: ignore[union-attr]
    assert b0.x.value == pytest.approx(4.0 + 40 / scale, abs=1.5 / scale) and b0.y.value == pytest.approx(0, abs=1e-9)
    assert not np.allclose(shown(page, "b21"), psi0)
    after_drag = page.evaluate("window.mechfemStudio.revision")

    # Change a named dimension in its number field.
    field = page.get_by_label("crank_length value")
    field.fill("1.1")
    field.press("Enter")
    settled(page, after_drag + 1)
    assert server.actions.session.mechanism["crank_length"].value == 1.1  # type: ignore[union-attr]
    assert page.text_content("#status").startswith("Recomputed 145 positions")

    # An edit that cannot be assembled is refused, and the design on screen stays.
    revision = page.evaluate("window.mechfemStudio.revision")
    before = shown(page, "b21")
    page.get_by_label("rocker_length value").fill("10")
    page.get_by_label("rocker_length value").press("Enter")
    page.wait_for_function("document.getElementById('status').classList.contains('refused')")
    assert "Not applied" in page.text_content("#status")
    assert page.evaluate("window.mechfemStudio.revision") == revision
    assert np.array_equal(shown(page, "b21"), before)

    # Save, and run the saved deck as `mechfem run` does: the page showed the same numbers.
    deck = tmp_path / "edited.mec"
    page.fill("#savepath", str(deck))
    page.click("#save")
    page.wait_for_function("window.mechfemStudio.lastSaved !== null")
    assert deck.exists() and (tmp_path / "edited.html").exists()
    assert "NAMES" in deck.read_text()
    out = tmp_path / "cli"
    assert cli.main(["run", str(deck), "-o", str(out), "--no-media", "-q"]) == 0
    header = (out / "edited.csv").read_text().splitlines()[0].split(",")
    rows = np.loadtxt(out / "edited.csv", delimiter=",", skiprows=1, ndmin=2)
    column = next(i for i, h in enumerate(header) if h.strip().startswith("21"))
    # The page has 6 significant digits (as the report), the data set 7.
    np.testing.assert_allclose(shown(page, "b21"), rows[:, column], rtol=5e-6, atol=1e-9)

    # Undo twice: the dimension, then the drag; the page shows the deck's own motion again.
    page.click("#undo")
    settled(page, revision + 1)
    assert page.get_by_label("crank_length value").input_value() == "1"
    page.click("#undo")
    settled(page, revision + 2)
    np.testing.assert_allclose(shown(page, "b21"), psi0)
    assert page.evaluate("window.mechfemStudio.errors") == []


def test_new_four_bar_through_three_clicked_points_saved_as_a_deck(page: Any, server: Running, tmp_path: Path) -> None:
    # The acceptance: from the template to a four-bar whose coupler point passes through three clicked points.
    page.click("#template")
    page.wait_for_function("window.mechfemStudio.D && window.mechfemStudio.D.studio.name === 'fourbar'")
    settled(page)
    xs, ys = shown(page, "c9"), shown(page, "c10")
    # Three points near the coupler curve (C's path), but off it.
    wanted = [(xs[k] + 0.1, ys[k] + 0.15) for k in (0, 120, 240)]
    page.click("#optclick")
    for x, y in wanted:
        sx, sy = page.evaluate("([x, y]) => window.mechfemStudio.toScreen(x, y)", [x, y])
        page.mouse.click(sx, sy)
    assert page.evaluate("window.mechfemStudio.targets.length") == 3
    assert page.input_value("#optpoint") == "C"
    page.click("#optrun")
    page.wait_for_function("!window.mechfemStudio.optimising", timeout=60000)
    assert page.evaluate("window.mechfemStudio.lastReply.optimised !== undefined"), page.text_content("#status")
    settled(page)
    assert page.evaluate("window.mechfemStudio.iterations") >= 1, "no iteration was shown while optimising"
    assert "passes within" in page.text_content("#optstatus")
    deck = tmp_path / "through_three.mec"
    page.fill("#savepath", str(deck))
    page.click("#save")
    page.wait_for_function(
        "(p) => window.mechfemStudio.lastSaved && window.mechfemStudio.lastSaved.deck === p", arg=str(deck)
    )
    # The saved deck, run as `mechfem run` runs it: C's path passes through the three points.
    out = tmp_path / "cli"
    assert cli.main(["run", str(deck), "-o", str(out), "--no-media", "-q"]) == 0
    rows = np.loadtxt(out / "through_three.csv", delimiter=",", skiprows=1, ndmin=2)
    cx, cy = rows[:, 4], rows[:, 5]  # buffers 5 and 6: C.x and C.y
    size = float(np.hypot(np.ptp(cx), np.ptp(cy)))
    for x, y in wanted:
        assert float(np.min(np.hypot(cx - x, cy - y))) < 0.01 * size


def test_optimise_an_extremum_and_a_transmission_bound_from_the_page(page: Any, server: Running) -> None:
    page.click("#template")
    page.wait_for_function("window.mechfemStudio.D && window.mechfemStudio.D.studio.name === 'fourbar'")
    settled(page)
    # The rocker angle's maximum over the motion should reach 130 deg.
    page.select_option("#opttarget", "extremum")
    assert page.is_hidden("#optpath") and page.is_visible("#optvalue")
    page.select_option("#optquantity", "psi")
    page.select_option("#optwhich", "max")
    page.select_option("#optgoal", "value")
    page.fill("#optvalue", "130")
    page.click("#optrun")
    page.wait_for_function("!window.mechfemStudio.optimising", timeout=60000)
    settled(page)
    assert page.evaluate("window.mechfemStudio.lastReply.optimised.target") == "extremum", page.text_content("#status")
    assert page.evaluate("window.mechfemStudio.iterations") >= 1, "no iteration was shown while optimising"
    assert "The max of psi over the motion is 130 deg" in page.text_content("#optstatus")
    assert float(np.nanmax(shown(page, "b2"))) == pytest.approx(130.0, abs=1e-3)
    # Then every transmission angle within [60, 120] deg at every position, with the least change.
    page.select_option("#opttarget", "transmission")
    assert page.is_hidden("#optext") and page.is_visible("#opttranslo")
    page.fill("#opttranslo", "60")
    page.click("#optrun")
    page.wait_for_function("!window.mechfemStudio.optimising", timeout=60000)
    settled(page)
    assert page.evaluate("window.mechfemStudio.lastReply.optimised.target") == "transmission"
    mu = shown(page, "b8")
    assert float(np.nanmin(mu)) >= 60.0 - 1e-3 and float(np.nanmax(mu)) <= 120.0 + 1e-3
    assert "stays within 60 to" in page.text_content("#optstatus")
    assert page.evaluate("window.mechfemStudio.errors") == []


def test_a_deck_of_the_folder_that_reads_a_table_beside_it_opens(page: Any) -> None:
    assert page.is_visible("#files")
    page.select_option("#files", "slider_crank.mec")
    page.wait_for_function("window.mechfemStudio.D && window.mechfemStudio.D.studio.name === 'slider_crank'")
    settled(page)
    assert page.text_content("#status").startswith("Opened")
    assert page.evaluate("window.mechfemStudio.D.positions") == 101
