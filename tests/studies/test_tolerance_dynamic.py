"""Tolerance bands of the results of inverse dynamics (DYN ANA): each band's sensitivity to each toleranced
dimension against central differences of whole runs of the deck, the dimension perturbed and the mechanism run
again. The deck is the balancing example's slider-crank with its masses and gravity, held to a tight ACCURACY so
that the differences are accurate to far below the tolerance of the comparison."""

from __future__ import annotations

from pathlib import Path

import numpy as np

import mechfem
from conftest import ROOT
from mechfem.studies.bands import deck_bands

DECK = ROOT / "examples/balancing/slider_crank_dyn.mec"

# Drive torque, shaking force x, kinetic energy, reaction y at A0, the rod's force on the crank pin A (x), the
# stress of the rod's length row, the reduced inertia at the crank.
EXTRA = """  BUFREA   2  7
  BUFPIN 2 5 6 8
  BUFSIG   2 10
  BUFMRED 1 1 11
"""
SOURCES = [2, 3, 6, 7, 8, 10, 11]
TOLERANCE = "TOLERANCE\nTOL 1 0.001\nTOL 2 0.002\nTOLX 4 0.001\n" + "".join(
    f"BUFTOL {b} {200 + 2 * k}\n" for k, b in enumerate(SOURCES)
)


def _deck(crank: float = 0.1, rod: float = 0.35, offset: float = 0.0, tolerance: bool = True) -> str:
    text = DECK.read_text()
    text = text.replace("PARA 1 0.1\n     2 0.35\n", f"PARA 1 {crank!r}\n     2 {rod!r}\n")
    text = text.replace("     4 0.0\nXMOV", f"     4 {offset!r}\nXMOV")
    text = text.replace("MOV_RELE 1 6.19591884457987\n", "MOV_RELE 1 6.19591884457987\nACCURACY 1E-13\n")
    text = text.replace("  PRINTBUF 1 2 3 4 5\n", EXTRA + "  PRINTBUF 1 2 3 4 5\n")
    return text + (TOLERANCE if tolerance else "") + "END\n"


def _run(tmp_path: Path, name: str, text: str) -> mechfem.RunResult:
    path = tmp_path / name
    path.write_text(text)
    return mechfem.run_deck(path)


def test_dynamic_bands_are_the_central_differences_of_whole_runs(tmp_path: Path) -> None:
    result = _run(tmp_path, "nominal.mec", _deck())
    bands = deck_bands(result)
    assert bands is not None and bands.positions == 72
    assert list(bands.tolerances.values()) == [0.001, 0.002, 0.001]
    nominal = {"crank": 0.1, "rod": 0.35, "offset": 0.0}
    h = 1e-5
    for k, name in enumerate(nominal):
        runs = []
        for sign in (1.0, -1.0):
            changed = dict(nominal)
            changed[name] += sign * h
            runs.append(_run(tmp_path, f"{name}{sign:+}.mec", _deck(**changed, tolerance=False)))
        for band, b in zip(bands.bands.values(), SOURCES, strict=True):
            fd = (runs[0].buffers[b] - runs[1].buffers[b]) / (2 * h)
            exact = band.sensitivity[:, k]
            # Relative to the band's largest sensitivity along the motion.
            scale = float(np.abs(exact).max())
            assert scale > 0.0
            assert np.abs(exact - fd).max() < 1e-6 * scale, (name, b, np.abs(exact - fd).max() / scale)
            assert np.allclose(band.value, result.buffers[b], rtol=1e-12, atol=1e-9 * np.abs(result.buffers[b]).max())
