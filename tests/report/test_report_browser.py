"""The interactive report (python/mechfem/report/html.py): one offline HTML file, checked as text and in headless
Chromium.

The browser tests drive Debian's ``chromium`` from the command line, with no Python package: ``--dump-dom`` on
``<stem>.html#selftest`` lets the page check itself (it draws, moves the slider and writes what it saw into
``<pre id="selftest">``), ``--log-net-log`` records every network request, and ``--screenshot`` keeps a picture of
the page as an artifact. ``make browser`` (called by ``make test``) installs Chromium; without it they are skipped.
"""

from __future__ import annotations

import html
import json
import re
import shutil
import subprocess
from collections.abc import Callable
from importlib import resources
from pathlib import Path
from typing import Any, TypeVar

import pytest

import mechfem
import mechfem.report.html
from conftest import SUPPLY, Cli
from mechfem.report.html import report_data, report_positions, write_report
from mechfem.results.result import RunResult


def find_chromium() -> str | None:
    for name in ("chromium", "chromium-browser", "google-chrome", "google-chrome-stable"):
        path = shutil.which(name)
        if path:
            return path
    return None


CHROMIUM = find_chromium()
F = TypeVar("F", bound=Callable[..., Any])
_skip_without_chromium = pytest.mark.skipif(
    CHROMIUM is None,
    reason="no Chromium on the PATH: `make browser` installs Debian's chromium (as root); `make test` calls it",
)


def needs_chromium(test: F) -> F:
    """Marks a test that drives Chromium (``browser``) and skips it, saying why, where there is none."""
    marked: F = pytest.mark.browser(_skip_without_chromium(test))
    return marked


# Headless, no sandbox (root in a container), nothing of the browser's own: no first-run, sync, updates or
# background traffic; host names resolve nowhere and any request that still starts goes to a closed local port.
FLAGS = [
    "--headless",
    "--no-sandbox",
    "--disable-gpu",
    "--disable-quic",
    "--no-first-run",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
    "--disable-default-apps",
    "--disable-extensions",
    "--disable-domain-reliability",
    "--no-pings",
    "--host-resolver-rules=MAP * ~NOTFOUND",
    "--proxy-server=http://127.0.0.1:9",
    "--hide-scrollbars",
]


def chromium(tmp: Path, *args: str) -> subprocess.CompletedProcess[str]:
    assert CHROMIUM is not None
    profile = tmp / f"profile-{len(list(tmp.glob('profile-*')))}"
    return subprocess.run(
        [CHROMIUM, *FLAGS, f"--user-data-dir={profile}", *args],
        capture_output=True,
        text=True,
        timeout=180,
        stdin=subprocess.DEVNULL,
    )


def page_requests(netlog: Path) -> list[tuple[str, str]]:
    """(initiator, url) of every request the netlog saw start, except file:// loads."""
    log = json.loads(netlog.read_text())
    start = log["constants"]["logEventTypes"]["URL_REQUEST_START_JOB"]
    out = []
    for event in log["events"]:
        params = event.get("params") or {}
        if event["type"] == start and "url" in params and not params["url"].startswith("file:"):
            out.append((str(params.get("initiator")), params["url"]))
    return out


def self_test(tmp: Path, page: Path, *args: str) -> tuple[dict[str, Any], list[tuple[str, str]]]:
    """Opens ``page#selftest`` (with Chromium's ``args``, e.g. a window size); returns what the page reported and
    the requests the page itself made."""
    netlog = tmp / f"{page.stem}.netlog.json"
    proc = chromium(
        tmp, f"--log-net-log={netlog}", "--virtual-time-budget=5000", *args, "--dump-dom", page.as_uri() + "#selftest"
    )
    assert proc.returncode == 0, proc.stderr[-2000:]
    found = re.search(r'<pre id="selftest">(.*?)</pre>', proc.stdout, re.S)
    assert found, "the page wrote no self-test result:\n" + proc.stdout[-2000:]
    # The browser's own services ask with no origin ("not an origin"); what the page asks for has its (opaque) origin.
    mine = [(who, url) for who, url in page_requests(netlog) if who != "not an origin"]
    return json.loads(html.unescape(found.group(1))), mine


@pytest.fixture(scope="module")
def supply() -> RunResult:
    return mechfem.run_deck(SUPPLY)


def embedded_data(text: str) -> dict[str, Any]:
    found = re.search(r'<script type="application/json" id="data">(.*?)</script>', text, re.S)
    assert found
    return json.loads(found.group(1))


def test_report_is_one_self_contained_file(supply: RunResult, tmp_path: Path) -> None:
    path = write_report(supply, tmp_path)
    assert path == tmp_path / "supply.html"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["supply.html"]
    text = path.read_text()
    # Nothing to load: no element with a source or a link, no style that fetches; the page forbids itself to.
    assert "default-src 'none'" in text
    assert not re.search(r"<[a-z]+\s[^>]*\b(src|href)\s*=", text, re.I)
    assert not re.search(r"@import|[^.]url\(|<link\b", text)
    # uPlot is inlined with its licence banner, the only address in the page.
    assert "uPlot (v1.6.32)" in text
    assert re.findall(r"https?://[^\s\"')]+", text) == ["https://github.com/leeoniya/uPlot"]
    data = embedded_data(text)
    assert data["positions"] == 73 and len(data["frames"]) == 73
    assert data["subsample_note"] is None
    assert data["table"] == ["b99", "b100", "b101", "b102"]
    cols = data["columns"]
    assert all(len(cols[k]["values"]) == 73 for k in data["table"])
    assert cols["b101"]["header"] == "101 ddelta/dalpha [-]"
    # Picture 1 is the hodograph; picture 2's three PLOTFUNC lines of three units are three charts.
    assert [[c["type"] for c in card["charts"]] for card in data["cards"]] == [["xy"], ["function"] * 3]
    hodo = data["cards"][0]["charts"][0]["hodographs"][0]
    assert (hodo["x"], hodo["y"], hodo["vx"]) == ("c13", "c14", "k13") and len(cols["k13"]["values"]) == 73
    assert [c["ylabel"] for c in data["cards"][1]["charts"]] == [
        "delta [rad]",
        "ddelta/dalpha [-]",
        "d2delta/dalpha^2 [1/rad]",
    ]
    assert [p["x"] for p in data["paths"]] == ["c13"]
    assert len(data["scene"]["frames"]) == 73 and data["scene"]["moving"]
    # det(D^c) is always there, against the input, which turns one way.
    assert data["det"]["x"] == "b99" and data["det"]["limits"] == []
    assert cols["det"]["values"][0] == pytest.approx(supply.det[0], rel=1e-5)
    assert data["stop"] is None


def test_report_parts_are_package_files() -> None:
    # The page is made of files inside the package, found as the template is (so a wheel carries them).
    files = resources.files("mechfem")
    for name in ["report/template.html", *mechfem.report.html.PAGE_PARTS.values(), "report/vendor/uplot/LICENSE"]:
        assert files.joinpath(name).is_file(), name
    assert "Leon Sorokin" in files.joinpath("report/vendor/uplot/LICENSE").read_text()


def test_report_subsamples_long_runs_and_says_so(supply: RunResult, monkeypatch: pytest.MonkeyPatch) -> None:
    assert len(report_positions(20000)) == 2000
    monkeypatch.setattr(mechfem.report.html, "MAX_REPORT_POSITIONS", 20)
    data = report_data(supply)
    assert len(data["frames"]) == 20 and data["frames"][0] == 0 and data["frames"][-1] == 72
    assert "73 positions" in data["subsample_note"] and "show 20 of them" in data["subsample_note"]
    assert all(len(c["values"]) == 20 for c in data["columns"].values())
    assert data["columns"]["b99"]["values"][1] == pytest.approx(supply.buffers[99][data["frames"][1]], rel=1e-5)


def test_report_command_writes_only_the_report(cli: Cli, tmp_path: Path) -> None:
    proc = cli("report", SUPPLY, "-o", tmp_path)
    assert proc.returncode == 0, proc.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == ["supply.html"]
    assert f"wrote {tmp_path / 'supply.html'}" in proc.stdout


def test_run_with_report_writes_it_beside_the_rest(cli: Cli, tmp_path: Path) -> None:
    proc = cli("run", SUPPLY, "-o", tmp_path, "--report")
    assert proc.returncode == 0, proc.stderr
    names = {p.name for p in tmp_path.iterdir()}
    assert {"supply.prt", "supply.csv", "supply.html", "film.gif", "supply_pic1.png"} <= names
    assert "interactive report: supply.html" in (tmp_path / "supply.prt").read_text()


@needs_chromium
def test_report_in_headless_chromium(supply: RunResult, tmp_path: Path) -> None:
    page = write_report(supply, tmp_path / "out")
    result, requests = self_test(tmp_path, page)
    assert result["errors"] == []
    assert requests == [], "the page made network requests"
    assert result["resources"] == []
    # The mechanism is drawn, and moving the slider moves it.
    mech = result["mechanism"]
    assert mech["ink_before"] > 1000 and mech["ink_after"] > 1000
    assert mech["changed_pixels"] > 200
    assert result["slider"] == {"target": 36, "current": 36}
    assert result["position_before"].startswith("position 1 of 73: alpha = -1.03907 rad")
    assert result["position_after"].startswith("position 37 of 73")
    # det(D^c), then every picture as uPlot charts whose marker follows the slider.
    charts = result["charts"]
    assert result["uplots"] == len(charts) == 5
    assert [(c["card"], c["type"]) for c in charts] == [
        ("det", "function"),
        (0, "xy"),
        (1, "function"),
        (1, "function"),
        (1, "function"),
    ]
    for c in charts:
        assert c["uplot"] and c["ink"] > 2000
        assert c["changed_pixels"] > 50
        assert c["cursor_before"] and c["cursor_after"] and c["cursor_before"] != c["cursor_after"]
        assert c["readout"].startswith("at the slider: position 37")
    function = charts[2]
    assert function["curves"] == ["delta"] and function["ylabel"] == "delta [rad]"
    assert function["cursor_after"][0][0] > function["cursor_before"][0][0] + 100  # moved right along the input
    assert "alpha = 2.10252 rad" in function["readout"] and "0.573676 rad" in function["readout"]
    # Clicking a chart's curve moves the slider there; dragging zooms, double-clicking shows everything again.
    click = result["chart_click"]
    assert click["hovered"] == click["want"] == click["slider"] == 18
    assert click["readout"].startswith("under the pointer: position 19")
    zoom = result["zoom"]
    assert zoom["zoomed"][1] - zoom["zoomed"][0] < 0.5 * (zoom["before"][1] - zoom["before"][0])
    assert zoom["reset"] == pytest.approx(zoom["before"])
    # Play and pause at two speeds for the same time: 4x goes eight times as far as 0.5x.
    assert (result["play"], result["pause"]) == ("Pause", "Play")
    assert result["speeds"] == ["0.25", "0.5", "1", "2", "4"]
    fast, slow = result["moved"]
    assert slow > 0 and fast == pytest.approx(8 * slow, abs=4)
    assert result["table_rows"] == 73 and result["current_row"] == "37"


@needs_chromium
def test_netlog_sees_a_request_a_page_makes(tmp_path: Path) -> None:
    # The control for the check above: a page that does load something is caught (a closed local port).
    page = tmp_path / "control.html"
    page.write_text(
        '<!doctype html><img src="http://127.0.0.1:9/probe.png"><pre id="selftest">{"ok": true}</pre>',
        encoding="utf-8",
    )
    result, requests = self_test(tmp_path, page)
    assert result == {"ok": True}
    assert [url for _, url in requests] == ["http://127.0.0.1:9/probe.png"]
