"""The docs' pictures of the report of each mode (scripts/report_screenshots.py) and the DYN ANA report's pin-force
arrows as the page draws them, in headless Chromium (skipped without it, like the other browser tests)."""

from __future__ import annotations

import importlib.util
import sys
import warnings
from pathlib import Path
from types import ModuleType

import numpy as np
from PIL import Image

import mechfem
from conftest import ROOT
from mechfem.report.html import write_report
from report.test_report_browser import needs_chromium, self_test


def script() -> ModuleType:
    spec = importlib.util.spec_from_file_location("report_screenshots", ROOT / "scripts" / "report_screenshots.py")
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module  # dataclasses look their module up
    spec.loader.exec_module(module)
    return module


@needs_chromium
def test_the_screenshot_script_makes_a_picture_of_each_modes_report(tmp_path: Path) -> None:
    shots = script()
    assert shots.main(["--out", str(tmp_path)]) == 0
    for shot in shots.SHOTS:
        image = Image.open(tmp_path / shot.image)
        assert image.size == shot.window, shot.mode
        pixels = np.asarray(image.convert("RGB"), dtype=np.int16)
        # Drawn: dark ink (the mechanism's bars, the charts' text) and the charts' blue curves.
        assert np.mean(np.all(pixels < 100, axis=2)) > 0.002, shot.mode
        blue = np.all(np.abs(pixels - np.array([0, 114, 178])) < 40, axis=2)
        assert np.mean(blue) > 0.0002, shot.mode


@needs_chromium
def test_the_page_draws_the_runs_pin_forces_at_the_slider(tmp_path: Path) -> None:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        result = mechfem.run_deck(ROOT / "examples" / "supply" / "supply_forces.mec")
    page = write_report(result, tmp_path)
    found, requests = self_test(tmp_path, page, "--window-size=1400,1000")
    assert found["errors"] == [] and requests == []
    # The self-test leaves the slider half-way through the motion; the arrows are those of that position.
    position = found["slider"]["target"]
    arrows = next(c["forces"] for c in found["charts"] if c["forces"])
    expected = {
        "crank on A": result.pin_force("crank", "A"),
        "output on M": result.pin_force("output", "M"),
        "reaction at A0": result.reaction("A0"),
    }
    drawn = {a["name"]: a for a in arrows}
    assert len(drawn) == 10
    for name, force in expected.items():
        a = drawn[name]
        np.testing.assert_allclose([a["fx"], a["fy"]], force[position], rtol=6e-6)
    # One scale for every arrow: tip - pin is the force times it.
    scales = [np.hypot(a["tip"][0] - a["x"], a["tip"][1] - a["y"]) / np.hypot(a["fx"], a["fy"]) for a in arrows]
    assert np.ptp(scales) < 1e-9 * max(scales)
