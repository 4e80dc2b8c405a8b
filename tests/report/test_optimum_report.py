"""The optimisation in the report of a KIN OPT run, and the summary table and history chart of an optimisation in
Python: every number is compared with the run's own (the print file, the final design's deck and its run, the
target files), not with numbers written here."""

from __future__ import annotations

import dataclasses
import html
import json
import math
import re
from pathlib import Path
from typing import Any

import pytest
from matplotlib.figure import Figure

import mechfem
from mechfem.cli import command as cli
from mechfem.design import optimise_deck
from mechfem.report.optimum_report import active_bound, optimisation_section
from report.test_report_browser import chromium, needs_chromium

ROOT = Path(__file__).resolve().parents[2]
SYNTHESIS = ROOT / "examples" / "synthesis"
NUMBER = r"[-+0-9.eE]+"


def page_data(page: Path) -> dict[str, Any]:
    text = page.read_text(encoding="utf-8")
    found = re.search(r'<script type="application/json" id="data">(.*?)</script>', text, re.S)
    assert found
    data: dict[str, Any] = json.loads(found.group(1))
    return data


def printed_variables(prt: Path) -> dict[str, tuple[float, float, float, float]]:
    """The print file's table of design variables: name -> (start, final, lower, upper)."""
    lines = prt.read_text(encoding="utf-8").splitlines()
    k = next(i for i, line in enumerate(lines) if line.strip() == "design variables:")
    out = {}
    for line in lines[k + 2 :]:
        words = line.split()
        if not words:
            break
        # name, unit (may be absent without UNITS), start, final, lower, upper
        start, final, lo, hi = (float(w) for w in words[-4:])
        out[words[0]] = (start, final, lo, hi)
    return out


def target_file(path: Path) -> list[str]:
    """A TARGET file's values, one a position (``*``: not compared), its comment lines left out."""
    return [line.split()[0] for line in path.read_text(encoding="utf-8").splitlines() if line.strip()[:1] not in "#"]


def optimised(deck: Path, outdir: Path) -> tuple[dict[str, Any], Path]:
    assert cli.main(["run", str(deck), "-o", str(outdir), "--report", "--max-frames", "2"]) == 0
    return page_data(outdir / f"{deck.stem}.html")["optimisation"], outdir


@pytest.fixture(scope="module")
def path_run(tmp_path_factory: pytest.TempPathFactory) -> tuple[dict[str, Any], Path]:
    return optimised(SYNTHESIS / "path.mec", tmp_path_factory.mktemp("path"))


def test_variables_by_name_with_the_print_files_start_and_final_values(path_run: tuple[dict[str, Any], Path]) -> None:
    opt, outdir = path_run
    printed = printed_variables(outdir / "path.prt")
    names = ["B0.x", "B0.y", "crank_length", "coupler_length", "rocker_length", "u_P", "v_P"]
    assert [v["name"] for v in opt["variables"]] == names
    page = (outdir / "path.html").read_text(encoding="utf-8")
    for v in opt["variables"]:
        assert f'"{v["name"]}"' in page
        start, final, lo, hi = printed[v["name"]]
        assert v["start"] == pytest.approx(start, rel=1e-11, abs=1e-12)
        assert v["final"] == pytest.approx(final, rel=1e-11, abs=1e-12)
        assert (v["lo"], v["hi"]) == (lo, hi)
        assert v["active"] == "" and not v["periodic"]
    # The final values are the design the run was made with: the written deck's PARA and XFIX values.
    written = (outdir / "path_opt.mec").read_text(encoding="utf-8")
    crank = re.search(rf"^PARA\s+1\s+({NUMBER})", written, re.M)
    assert crank and float(crank.group(1)) == pytest.approx(opt["variables"][2]["final"], rel=1e-12)


def test_targets_residuals_are_target_minus_the_final_runs_values(path_run: tuple[dict[str, Any], Path]) -> None:
    opt, outdir = path_run
    final = mechfem.run_deck(outdir / "path_opt.mec")
    wanted = {b: target_file(SYNTHESIS / f"path_{c}.dat") for b, c in [(1, "x"), (2, "y")]}
    rows = opt["targets"]
    assert len(rows) == 20 and {r["name"] for r in rows} == {"P.x", "P.y"}
    for r in rows:
        b = 1 if r["name"] == "P.x" else 2
        k = int(r["where"].removeprefix("position ")) - 1
        assert wanted[b][k] != "*"
        assert r["target"] == float(wanted[b][k])
        assert r["achieved"] == pytest.approx(final.buffers[b][k], abs=1e-9)
        assert r["residual"] == r["target"] - r["achieved"]
        assert abs(r["residual"]) < 1e-9
    # The targets' points are drawn where the files put them; the final path passes through them.
    (point,) = opt["drawing"]["points"]
    assert point["name"] == "P" and len(point["target"]) == 10
    assert len(point["final"]) == final.positions


def test_history_ends_at_the_final_objective(path_run: tuple[dict[str, Any], Path]) -> None:
    opt, outdir = path_run
    h = opt["history"]
    assert h["iteration"] == list(range(len(h["iteration"])))
    assert h["objective"][0] == opt["objective"]["start"]
    assert h["objective"][-1] == opt["objective"]["final"]
    printed = (outdir / "path.prt").read_text(encoding="utf-8")
    found = re.search(rf"objective: start ({NUMBER}), final ({NUMBER})", printed)
    assert found
    assert opt["objective"]["start"] == pytest.approx(float(found.group(1)), rel=1e-9)
    assert opt["objective"]["final"] == pytest.approx(float(found.group(2)), rel=1e-9)
    # Least squares only moves to a better design: the history falls.
    assert all(b < a for a, b in zip(h["objective"], h["objective"][1:], strict=False))


def test_a_variable_on_its_bound_is_marked_active(tmp_path: Path) -> None:
    opt, outdir = optimised(SYNTHESIS / "function.mec", tmp_path)
    printed = printed_variables(outdir / "function.prt")
    by_name = {v["name"]: v for v in opt["variables"]}
    # The crank ends at its upper limit (docs/optimisation.md); the others inside their ranges.
    assert by_name["crank_length"]["active"] == "upper"
    for name, v in by_name.items():
        start, final, lo, hi = printed[name]
        assert v["final"] == pytest.approx(final, rel=1e-11)
        assert v["active"] == active_bound(final, lo, hi)
    assert [n for n, v in by_name.items() if v["active"]] == ["crank_length"]
    assert by_name["theta"]["unit"] == "rad"


def test_active_bound() -> None:
    assert active_bound(3.0, 0.3, 3.0) == "upper"
    assert active_bound(0.3 + 1e-9, 0.3, 3.0) == "lower"
    assert active_bound(1.0, 0.3, 3.0) == ""
    assert active_bound(2.9, 0.3, 3.0) == ""


@needs_chromium
def test_the_page_draws_the_optimisation(path_run: tuple[dict[str, Any], Path], tmp_path: Path) -> None:
    opt, outdir = path_run
    page = outdir / "path.html"
    proc = chromium(
        tmp_path, "--virtual-time-budget=5000", "--window-size=1400,1000", "--dump-dom", f"{page.as_uri()}#selftest"
    )
    whole = re.search(r'<pre id="selftest">(.*?)</pre>', proc.stdout, re.S)
    mine = re.search(r'<pre id="optselftest"[^>]*>(.*?)</pre>', proc.stdout, re.S)
    assert whole and mine, proc.stdout[-2000:]
    # The path deck's page (without the optimisation as well) meets a ResizeObserver loop in its charts: not an
    # error of the optimisation's section.
    errors = json.loads(html.unescape(whole.group(1)))["errors"]
    assert [e for e in errors if not e.startswith("ResizeObserver loop")] == []
    seen = json.loads(html.unescape(mine.group(1)))
    assert seen["log"] and seen["points"] == len(opt["history"]["objective"])
    assert seen["variables"] == 7 and seen["targets"] == 20 and seen["targets_drawn"] == 10
    assert seen["ink"] > 1000


# --- Python ------------------------------------------------------------------------------------------------------


@pytest.fixture(scope="module")
def function_optimum() -> mechfem.Optimum:
    m = mechfem.Mechanism.from_deck(SYNTHESIS / "function.mec")
    return mechfem.optimize(
        m, {"coupler_length": (1.0, 8.0), "theta": (0.0, 2.5)}, targets=[mechfem.TargetAt("phi", 30, 1.9)]
    )


def test_optimum_summary_table(function_optimum: mechfem.Optimum) -> None:
    opt = function_optimum
    table = opt._repr_html_()
    rows = re.findall(
        r"<tr><td style='text-align:left'>(.*?)</td><td>(.*?)</td><td>(.*?)</td><td>(.*?)</td></tr>", table
    )
    assert [r[0] for r in rows] == ["coupler_length", "theta"]
    assert [r[1] for r in rows] == ["", "rad"]
    for name, _, start, final in rows:
        assert float(start) == pytest.approx(opt.start[name], rel=1e-9)
        assert float(final) == pytest.approx(opt.values[name], rel=1e-9)
    assert f"{len(opt.history) - 1}</td>" in table and f"{opt.runs}</td>" in table
    assert ("converged:" in table) == opt.success
    assert "usable" not in table  # one start


def test_optimum_plot_history(function_optimum: mechfem.Optimum) -> None:
    import matplotlib.pyplot as plt

    opt = function_optimum
    fig = opt.plot_history()
    assert isinstance(fig, Figure)
    (ax,) = fig.axes
    assert ax.get_yscale() == "log"
    (line,) = ax.get_lines()
    assert list(line.get_ydata()) == [it.objective for it in opt.history]
    assert line.get_ydata()[-1] == opt.objective
    plt.close(fig)
    other, given = plt.subplots()
    assert opt.plot_history(given) is other
    plt.close(other)


def test_optimum_page(function_optimum: mechfem.Optimum, tmp_path: Path) -> None:
    path = function_optimum.save_report(tmp_path / "opt" / "optimum.html")
    text = path.read_text(encoding="utf-8")
    assert text.startswith("<!doctype html>") and "<svg" in text and "coupler_length" in text
    assert "Content-Security-Policy" in text and "<script" not in text


def test_deck_outcome_summary_names_the_decks_variables(tmp_path: Path) -> None:
    deck = SYNTHESIS / "function.mec"
    opt = optimise_deck.describe(deck).optimise
    assert opt is not None
    outcome = optimise_deck.optimise(deck, opt)
    table = outcome._repr_html_()
    for name in ["crank_length", "coupler_length", "rocker_length", "theta"]:
        assert f">{name}</td>" in table
    s = outcome
    assert f"{s.x[0]:.10g}" in table and f"{s.start_objective:.10g}" in table
    fig = outcome.plot_history()
    assert fig.axes[0].get_lines()[0].get_ydata()[-1] == s.objective
    assert math.isfinite(s.objective)
    # Without the start design's run the section draws the final design alone, and says the same numbers.
    final = mechfem.run_deck(optimise_deck.write_design_deck(outcome, tmp_path))
    alone = optimisation_section(outcome, None, final)
    assert alone["drawing"]["start"] is None and alone["drawing"]["final"]["kinds"]
    assert [v["final"] for v in alone["variables"]] == pytest.approx([x for x in s.x], rel=1e-15)


def test_multi_start_summary_says_the_usable_starts(function_optimum: mechfem.Optimum) -> None:
    two = dataclasses.replace(function_optimum, starts=function_optimum.starts * 2, usable=0.5)
    assert "<th style='text-align:left'>usable starts</th><td colspan='3'>50%</td>" in two._repr_html_()
