"""BUFTOL's buffers b (worst case) and b + 1 (RSS) are buffers of the run like any other: their columns are the bands
of the TOLERANCE block at every position (which tests/studies/test_tolerance_bands.py checks against central differences
of whole runs), in ``RunResult.buffers``, the data set and the print file's buffer table; PRINTBUF and SAVEDATA name
them."""

from __future__ import annotations

import csv
from pathlib import Path

import numpy as np
import pytest

import mechfem
from conftest import ROOT, Cli
from mechfem import _core
from mechfem.output.files import print_file_lines
from mechfem.studies.bands import deck_bands

DECK = ROOT / "crates/mechfem-deck/tests/decks/valid/tolerance_fourbar.mec"
# BUFTOL 100 200, 101 202, 102 204: the source's label, the band's buffers.
SOURCES = {"psi": (100, 200), "C.y": (101, 202), "dpsi/dphi": (102, 204)}


def _with_outputs(tmp_path: Path) -> Path:
    path = tmp_path / "bands.mec"
    outputs = "PRINTBUF 100 200 201\nSAVEDATA 100 200 201 205\nBEGINPIC band\nPLOTFUNC 1 200\nENDPIC"
    path.write_text(DECK.read_text().replace("PRINTBUF 100 101", outputs))
    return path


def test_band_columns_are_the_bands_at_every_position() -> None:
    result = mechfem.run_deck(DECK)
    bands = deck_bands(result)
    assert bands is not None
    for name, (source, b) in SOURCES.items():
        band = bands[name]
        assert np.allclose(result.buffers[b], band.worst, rtol=1e-12, atol=0.0), name
        assert np.allclose(result.buffers[b + 1], band.rss, rtol=1e-12, atol=0.0), name
        assert (band.worst > 0).all() and (band.rss <= band.worst * (1 + 1e-12)).all()
        # The source's own column is the run's, not touched by the band.
        assert np.allclose(result.buffers[source], band.value, rtol=1e-8, atol=1e-8)


def test_printbuf_and_the_data_set_of_mechfem_run_hold_the_bands(cli: Cli, tmp_path: Path) -> None:
    deck = _with_outputs(tmp_path)
    result = mechfem.run_deck(deck)
    bands = deck_bands(result)
    assert bands is not None
    lines = print_file_lines(result)
    assert any("psi worst" in line and "deg" in line for line in lines)
    out = tmp_path / "out"
    proc = cli("run", deck, "-o", out)
    assert proc.returncode == 0, proc.stderr
    assert (out / "bands_pic1.png").is_file()
    rows = list(csv.reader((out / "bands.csv").read_text().splitlines()))
    assert rows[0] == ["100 psi [deg]", "200 psi worst [deg]", "201 psi rss [deg]", "205 dpsi/dphi rss [-]"]
    data = np.array(rows[1:], dtype=float)
    assert data.shape == (37, 4)
    assert np.allclose(data[:, 1], bands["psi"].worst, rtol=1e-6)
    assert np.allclose(data[:, 2], bands["psi"].rss, rtol=1e-6)
    assert np.allclose(data[:, 3], bands["dpsi/dphi"].rss, rtol=1e-6)


def test_a_deck_read_into_a_model_leaves_the_bands_out_and_runs() -> None:
    # The model carries no TOLERANCE block: BUFTOL's buffers are not turned into buffers of their source's quantity.
    with pytest.warns(UserWarning, match=r"TOLERANCE block is left out .* \(200, 201, 202, 203, 204, 205\)"):
        mech = mechfem.Mechanism.from_deck(DECK)
    assert mech.storage is not None
    numbers = sorted(b[0] for b in mech.storage.buffers)
    assert numbers == [1, 100, 101, 102, 103]
    result = mech.run()
    assert sorted(result.buffers) == numbers
    assert np.allclose(result.buffers[100], mechfem.run_deck(DECK).buffers[100], rtol=1e-8, atol=1e-8)


def test_a_compiled_model_run_fills_the_bands_as_the_deck_run() -> None:
    # The path of deck text and of a model's numbers changed (run_deck_text, Model.run, batches).
    deck = mechfem.run_deck(DECK)
    run = _core.Model.from_path(DECK).run()
    numbers = list(run.buffer_numbers)
    table = np.asarray(run.buffers)
    for b in (200, 201, 202, 203, 204, 205):
        assert np.allclose(table[:, numbers.index(b)], deck.buffers[b], rtol=1e-12, atol=0.0), b
