"""The report's page in headless Chromium for three kinds of run: the supply mechanism (a hodograph and
functions), a geared slider crank and a non-Grashof four-bar moved through its two limit positions.

Each page checks itself (``#selftest``, see tests/report/test_report_browser.py): the charts it built, where it drew
the det(D^c) chart's limit markers and in what colour, where the limit list's entries took the slider, the
CSV text every chart would save. Those are compared here with the run's own numbers. Screenshots taken by
``chromium --screenshot`` are checked pixel by pixel (the page fills the window's width, the mechanism and
every chart in view are drawn); with ``MECHFEM_REPORT_SCREENSHOTS=DIR`` they are also saved into DIR (that is
how docs/images/report_*.png are made).
"""

from __future__ import annotations

import contextlib
import csv
import io
import math
import os
import shutil
import warnings
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from PIL import Image

import mechfem
from bare_examples import BARE_EXAMPLES, bare
from conftest import ROOT, SUPPLY
from mechfem.report.html import write_report
from mechfem.results.result import RunResult
from report.test_report_browser import CHROMIUM, chromium, needs_chromium, self_test

# The examples without their NAMES blocks: the labels of the deck's numbers.
GEARS = bare(ROOT / "examples" / "gears" / "geared_slider_crank.mec")
LIMITS = bare(ROOT / "examples" / "limits" / "nongrashof.mec")
DECKS = {"supply": (bare(SUPPLY), 20), "gears": (GEARS, 13), "limits": (LIMITS, 240)}
WINDOW = (1400, 1000)
LIMIT_RED = (192, 57, 43)

Page = tuple[RunResult, Path, dict[str, Any], list[tuple[str, str]]]


@pytest.fixture(scope="module")
def pages(tmp_path_factory: pytest.TempPathFactory) -> dict[str, Page]:
    if CHROMIUM is None:
        pytest.skip("no Chromium on the PATH")
    tmp = tmp_path_factory.mktemp("report-pages")
    out = {}
    for name, (deck, _) in DECKS.items():
        # Run from the examples' folder, so that the page names the deck by a relative path as the docs do.
        with warnings.catch_warnings(), contextlib.chdir(BARE_EXAMPLES.parent):
            warnings.simplefilter("ignore")
            result = mechfem.run_deck(deck.relative_to(BARE_EXAMPLES.parent))
        if name == "limits":
            # A value the run could not compute (as a transfer function at a singular position) is NaN.
            result.buffers[5][100] = math.nan
        page = write_report(result, tmp / name)
        found, requests = self_test(tmp, page, f"--window-size={WINDOW[0]},{WINDOW[1]}")
        out[name] = (result, page, found, requests)
    return out


def csv_rows(text: str) -> tuple[list[str], list[list[float]]]:
    rows = list(csv.reader(io.StringIO(text)))
    return rows[0], [[float(v) if v else math.nan for v in row] for row in rows[1:]]


def assert_column(values: list[float], expected: np.ndarray) -> None:
    """The page's numbers (6 significant digits; empty where the run has none) against the run's."""
    np.testing.assert_allclose(values, expected, rtol=5.1e-6, atol=1e-12, equal_nan=True)


@needs_chromium
@pytest.mark.parametrize("name", list(DECKS))
def test_the_page_loads_draws_its_charts_and_asks_for_nothing(pages: dict[str, Page], name: str) -> None:
    result, _, found, requests = pages[name]
    assert found["errors"] == []
    assert requests == [] and found["resources"] == []
    charts = found["charts"]
    # det(D^c) first, then every picture's charts (or the default ones): all of them uPlot plots, all drawn.
    assert charts[0]["card"] == "det" and charts[0]["curves"] == ["det(D^c)"]
    assert found["uplots"] == len(charts) >= 2
    for c in charts:
        assert c["uplot"] and c["ink"] > 2000, c
        assert c["changed_pixels"] > 50, c  # the slider's marker moved
    # The page fills the window: the mechanism's stage and the charts' column side by side.
    layout = found["layout"]
    assert layout["page"] == layout["scroll"] == WINDOW[0]
    assert layout["stage"] + layout["side"] > 0.9 * WINDOW[0]
    assert layout["mechanism"][0] > 0.45 * WINDOW[0]


@needs_chromium
def test_a_path_keeps_its_shape(pages: dict[str, Page]) -> None:
    hodograph = pages["supply"][2]["charts"][1]
    assert hodograph["type"] == "xy" and hodograph["curves"] == ["path of (x13, x14)"]
    sx, sy = hodograph["pixels_per_unit"]
    assert sx > 100 and sy == pytest.approx(sx, rel=1e-3)


@needs_chromium
def test_quantities_of_different_units_never_share_an_axis(pages: dict[str, Page]) -> None:
    charts = pages["gears"][2]["charts"]
    # PLOTFUNC 1 2 (the slider, a length) and PLOTFUNC 1 5 (the pinion, an angle) of one picture: two charts.
    assert [(c["card"], c["curves"], c["ylabel"]) for c in charts[1:]] == [
        (0, ["x1"], "x1"),
        (0, ["x7"], "x7 [rad]"),
    ]
    assert {c["xlabel"] for c in charts} == {"ANGB(1) [rad]"}


@needs_chromium
def test_the_det_chart_marks_every_limit_and_the_list_goes_there(pages: dict[str, Page]) -> None:
    result, _, found, _ = pages["limits"]
    limits = result.report.located_limits
    assert [x.kind for x in limits] == ["passed", "passed"]
    det = found["det"]
    assert det["limits"] == len(det["markers"]) == 2
    assert [m["n"] for m in det["markers"]] == [1, 2]
    # Free motion turns the crank back, so det(D^c) is drawn against the position: the limits between
    # positions 238/239 and 697/698 lie at about a quarter and three quarters of the axis.
    width = found["charts"][0]["width"]
    xs = [m["x"] / width for m in det["markers"]]
    assert 0.2 < xs[0] < 0.35 and 0.7 < xs[1] < 0.85
    for colour in det["marker_colours"]:
        assert max(abs(a - b) for a, b in zip(colour, LIMIT_RED, strict=True)) < 30, colour
    # Each entry of the list takes the slider to the position before its limit.
    assert [c["position"] for c in found["limit_clicks"]] == [x.after for x in limits] == [238, 697]
    # The other two runs have no limit positions and no markers.
    for name in ("supply", "gears"):
        assert pages[name][2]["det"] == {"limits": 0, "markers": [], "marker_colours": []}


@needs_chromium
def test_a_click_on_a_chart_moves_the_slider(pages: dict[str, Page]) -> None:
    for name in DECKS:
        click = pages[name][2]["chart_click"]
        assert click["hovered"] == click["want"] == click["slider"], (name, click)


@needs_chromium
def test_every_chart_saves_its_numbers_as_csv(pages: dict[str, Page]) -> None:
    result, _, found, _ = pages["supply"]
    charts = found["charts"]
    position = np.arange(1, 74, dtype=np.float64)
    expected = [
        (["99 ANGB(1) [rad]", "det(D^c)"], [result.buffers[99], result.det]),
        (
            ["x13", "x14", "dx13/dinput1", "dx14/dinput1"],
            [result.coords[:, 12], result.coords[:, 13], result.kx1[13], result.kx1[14]],
        ),
        (["99 ANGB(1) [rad]", "100 ANGB(8) [rad]"], [result.buffers[99], result.buffers[100]]),
        (["99 ANGB(1) [rad]", "101 dANGB(8)/dinput1 [-]"], [result.buffers[99], result.buffers[101]]),
        (["99 ANGB(1) [rad]", "102 d2ANGB(8)/dinput1^2 [1/rad]"], [result.buffers[99], result.buffers[102]]),
    ]
    assert len(charts) == len(expected)
    for chart, (headers, columns) in zip(charts, expected, strict=True):
        header, rows = csv_rows(chart["csv"])
        assert header == ["position", *headers]
        table = np.array(rows)
        assert table.shape == (73, len(headers) + 1)
        assert_column(table[:, 0], position)
        for k, column in enumerate(columns, 1):
            assert_column(table[:, k], column)


@needs_chromium
def test_csv_leaves_empty_what_the_run_could_not_compute(pages: dict[str, Page]) -> None:
    result, _, found, _ = pages["limits"]
    # No picture: the recorded quantities against the position, one chart per kind and unit.
    charts = found["charts"][1:]
    assert [c["ylabel"] for c in charts] == ["ANGB(1) [rad]", "x9, x10", "dx9/dinput1"]
    header, rows = csv_rows(charts[2]["csv"])
    assert header == ["position", "5 dx9/dinput1"]
    assert charts[2]["csv"].splitlines()[101] == "101,"
    table = np.array(rows)
    assert_column(table[:, 0], np.arange(1, result.positions + 1, dtype=np.float64))
    assert_column(table[:, 1], result.buffers[5])


def ink(image: Image.Image, box: list[int]) -> float:
    """The share of pixels in the box (CSS pixels, page coordinates) that are not white or near it."""
    left, top, width, height = box
    crop = np.asarray(image.convert("RGB").crop((left, top, left + width, top + height)), dtype=np.int16)
    return float(np.mean(np.any(crop < 235, axis=2)))


def colour_share(image: Image.Image, box: list[int], colour: tuple[int, int, int]) -> float:
    left, top, width, height = box
    crop = np.asarray(image.convert("RGB").crop((left, top, left + width, top + height)), dtype=np.int16)
    return float(np.mean(np.all(np.abs(crop - np.array(colour)) < 40, axis=2)))


@needs_chromium
@pytest.mark.parametrize("name", list(DECKS))
def test_screenshot_shows_the_mechanism_and_the_charts(pages: dict[str, Page], name: str, tmp_path: Path) -> None:
    _, page, found, _ = pages[name]
    shot = tmp_path / f"report_{name}.png"
    position = DECKS[name][1]
    proc = chromium(
        tmp_path,
        f"--window-size={WINDOW[0]},{WINDOW[1]}",
        "--virtual-time-budget=3000",
        f"--screenshot={shot}",
        page.as_uri() + f"#position={position}",
    )
    assert proc.returncode == 0, proc.stderr[-2000:]
    image = Image.open(shot)
    assert image.size == WINDOW
    pixels = np.asarray(image.convert("RGB"), dtype=np.int16)
    # The page fills the width: white panels from the left margin to the right one, across the first panel row.
    row = pixels[found["rects"]["mechanism"][1] + 20]
    white = np.all(row > 250, axis=1)
    assert white[:40].any() and white[-40:].any() and white.mean() > 0.85
    # The mechanism is drawn, and so is every chart in view.
    assert ink(image, found["rects"]["mechanism"]) > 0.005
    visible = [box for box in found["rects"]["charts"] if box[1] + box[3] <= WINDOW[1]]
    assert visible, "no chart in the window"
    for box in visible:
        assert ink(image, box) > 0.02, box
        assert colour_share(image, box, (0, 114, 178)) > 0.001, box  # the first curve's blue
    if name == "limits":
        assert colour_share(image, found["rects"]["charts"][0], LIMIT_RED) > 0.001  # the limit markers
    assert shot.stat().st_size < 300_000
    keep = os.environ.get("MECHFEM_REPORT_SCREENSHOTS")
    if keep:
        Path(keep).mkdir(parents=True, exist_ok=True)
        shutil.copyfile(shot, Path(keep) / shot.name)
