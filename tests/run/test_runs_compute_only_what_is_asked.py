"""Runs that compute only what is asked (``run_deck(det=False)``) and the compiled decks ``run_deck`` keeps between
calls: what such a run says about det(D^c), that a limit position still stops it, and that a changed deck file is
read again."""

from __future__ import annotations

import math
import os
from pathlib import Path

import numpy as np
import pytest

import mechfem
from conftest import FOURBAR
from mechfem.output.files import write_print_file

ROOT = Path(__file__).resolve().parents[2]
LIMITS = ROOT / "examples" / "limits"


def deck(tmp_path: Path, text: str, name: str = "deck.mec") -> Path:
    path = tmp_path / name
    path.write_text(text)
    return path


def without(text: str, *keywords: str) -> str:
    """``text`` without its lines that start with one of ``keywords``."""
    return "".join(line for line in text.splitlines(keepends=True) if not line.lstrip().startswith(keywords))


def test_positions_only_run_has_no_det_and_the_same_positions(tmp_path: Path) -> None:
    path = deck(tmp_path, FOURBAR)
    fast = mechfem.run_deck(path, det=False)
    full = mechfem.run_deck(path)
    assert fast.report.complete and fast.positions == 361
    # Position 1 is found by the adjustment, which gives det(D^c) there; no other position has it.
    assert np.isnan(fast.det[1:]).all() and np.isfinite(fast.det[0]) and np.isfinite(full.det).all()
    assert fast.det[0] == full.det[0]
    # The crank pin is on the unit circle at the prescribed angle, whatever was computed beside it.
    angle = np.linspace(0.0, 2.0 * math.pi, 361)
    assert np.allclose(fast.buffers[1], np.cos(angle), atol=1e-9)
    assert np.allclose(fast.buffers[2], np.sin(angle), atol=1e-9)
    for b in (3, 4):
        assert np.allclose(fast.buffers[b], full.buffers[b], rtol=0.0, atol=1e-9)


def test_a_deck_recording_det_computes_it_as_before(tmp_path: Path) -> None:
    path = deck(tmp_path, FOURBAR + "BUFDET 5\n")
    fast, full = mechfem.run_deck(path, det=False), mechfem.run_deck(path)
    assert np.array_equal(fast.det, full.det) and np.array_equal(fast.buffers[5], full.det)
    assert np.array_equal(fast.coords, full.coords)


def test_a_driven_input_still_stops_at_its_limit_position(tmp_path: Path) -> None:
    # The slider-crank driven by its slider towards a dead centre, recording positions and values only.
    text = without((LIMITS / "slider_dead_centre.mec").read_text(), "BUFKE1", "BUFDET", "PRINTBUF", "SAVEDATA")
    path = deck(tmp_path, text)
    with pytest.warns(mechfem.IncompleteRunWarning):
        fast = mechfem.run_deck(path, det=False)
    with pytest.warns(mechfem.IncompleteRunWarning):
        full = mechfem.run_deck(path)
    assert np.isnan(fast.det[1:]).all()
    assert fast.report.stop is not None and full.report.stop is not None
    assert fast.report.stop.limit is not None and full.report.stop.limit is not None
    assert fast.positions == full.positions
    assert fast.report.stop.limit.inputs == pytest.approx(full.report.stop.limit.inputs, abs=1e-9)


def test_free_motion_passes_its_limit_positions_without_det_asked(tmp_path: Path) -> None:
    # The non-Grashof four-bar under free motion, recording positions only: free motion steers by det(D^c), so it
    # computes it whatever is asked, and passes both limit positions of the crank as always.
    text = without((LIMITS / "nongrashof.mec").read_text(), "BUFDET", "BUFKX1", "SAVEDATA")
    path = deck(tmp_path, text)
    fast, full = mechfem.run_deck(path, det=False), mechfem.run_deck(path)
    assert [x.kind for x in fast.report.limits] == ["passed", "passed"]
    assert np.array_equal(fast.coords, full.coords) and np.isfinite(fast.det).all()


def test_print_file_of_a_run_without_det_says_so(tmp_path: Path) -> None:
    result = mechfem.run_deck(deck(tmp_path, FOURBAR), det=False)
    text = write_print_file(result, tmp_path / "out.prt").read_text()
    assert "det(D^c) was not computed" in text


def test_repeated_runs_of_a_kept_deck_are_identical(tmp_path: Path) -> None:
    path = deck(tmp_path, FOURBAR)
    first, again = mechfem.run_deck(path), mechfem.run_deck(path)
    assert np.array_equal(first.coords, again.coords) and np.array_equal(first.det, again.det)
    assert first.model == again.model


def test_a_changed_deck_file_is_read_again(tmp_path: Path) -> None:
    path = deck(tmp_path, FOURBAR)
    before = mechfem.run_deck(path)
    mtime = path.stat().st_mtime_ns
    # The same size and time stamp: only the text tells the versions apart. A crank of 1.1 instead of 1.0.
    path.write_text(FOURBAR.replace("PARA 1 1.0", "PARA 1 1.1"))
    os.utime(path, ns=(mtime, mtime))
    after = mechfem.run_deck(path)
    assert np.hypot(before.buffers[1], before.buffers[2]) == pytest.approx(1.0)
    assert np.hypot(after.buffers[1], after.buffers[2]) == pytest.approx(1.1)


def test_a_settled_deck_edited_behind_its_time_stamp_is_read_again(tmp_path: Path) -> None:
    # A deck last changed an hour ago is known by its file's stamp, without being read. An edit of the same size
    # with its modification time put back still changes the file's change time (which no one can set).
    path = deck(tmp_path, FOURBAR)
    hour_ago = path.stat().st_mtime_ns - 3600 * 10**9
    os.utime(path, ns=(hour_ago, hour_ago))
    before, again = mechfem.run_deck(path), mechfem.run_deck(path)
    assert again.model is before.model
    path.write_text(FOURBAR.replace("PARA 1 1.0", "PARA 1 1.1"))
    os.utime(path, ns=(hour_ago, hour_ago))
    after = mechfem.run_deck(path)
    assert np.hypot(before.buffers[1], before.buffers[2]) == pytest.approx(1.0)
    assert np.hypot(after.buffers[1], after.buffers[2]) == pytest.approx(1.1)


def test_a_deck_that_is_gone_is_an_error_not_the_kept_model(tmp_path: Path) -> None:
    path = deck(tmp_path, FOURBAR)
    mechfem.run_deck(path)
    path.unlink()
    with pytest.raises(mechfem.DeckError, match="cannot read the deck"):
        mechfem.run_deck(path)


def test_a_compiled_model_run_with_changes_is_the_deck_that_says_so(tmp_path: Path) -> None:
    from mechfem import _core

    model = _core.Model(FOURBAR, "fourbar.mec", str(tmp_path))
    # The crank 1.1 long and its pin started at (1.1, 0), as a change and as deck text.
    changed = model.run([(1, 1, 1.1), (0, 5, 1.1)])
    text = FOURBAR.replace("PARA 1 1.0", "PARA 1 1.1").replace("XMOV 5 1.0", "XMOV 5 1.1")
    want = _core.run_deck_text(text, "fourbar.mec", str(tmp_path))
    assert np.array_equal(changed.coords, want.coords) and np.array_equal(changed.table, want.table)
    again = model.run()
    plain = _core.run_deck_text(FOURBAR, "fourbar.mec", str(tmp_path))
    assert np.array_equal(again.coords, plain.coords) and np.array_equal(again.table, plain.table)
    with pytest.raises(ValueError, match="no prescribed row 99"):
        model.run([(1, 99, 1.0)])


def test_a_named_model_compiles_once_per_topology(tmp_path: Path) -> None:
    from mechfem.deck import deckio
    from mechfem.run import compiled

    mech = mechfem.Mechanism.from_deck(str(deck(tmp_path, FOURBAR)))
    assert compiled.kept(mech).models() == []
    first = mech.run(progress=False)
    (kept,) = compiled.kept(mech).models()
    # Other numbers: the same compiled model, and to the last bit the results of the deck text path.
    other = mech.variant({"E1.length": 1.1})
    second = other.run(progress=False)
    # The variant (a copy of the mechanism) starts with its original's compiled model.
    assert compiled.kept(other).models() == [kept]
    text = deckio.write(other, other.motion, other.storage)
    want = mechfem._core.run_deck_text(text.text, text.path, ".")
    assert np.array_equal(second.coords, want.coords) and not np.array_equal(second.coords, first.coords)
    # Another deck (one more buffer): compiled anew.
    det = mechfem.Mechanism.from_deck(str(deck(tmp_path, FOURBAR + "BUFDET 5\n", "det.mec")))
    det.run(progress=False)
    (det_kept,) = compiled.kept(det).models()
    assert det_kept is not kept
