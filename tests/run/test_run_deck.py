"""The public Python API: run_deck, check_deck and the errors."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

import mechfem
from conftest import ROOT, SUPPLY

ROCKER = ROOT / "tests" / "decks" / "rocker.mec"


def test_run_supply_returns_every_position() -> None:
    result = mechfem.run_deck(SUPPLY)
    assert result.report.complete and result.report.stop_reason() is None
    assert result.positions == 73 == result.report.positions
    assert sorted(result.buffers) == [99, 100, 101, 102]
    assert all(b.shape == (73,) for b in result.buffers.values())
    assert result.coords.shape == (73, 20)
    assert result.time.shape == (73,) and result.det.shape == (73,)
    # The input turns once, in equal steps.
    inp = result.buffers[99]
    assert inp[-1] - inp[0] == pytest.approx(2 * math.pi, rel=1e-12)
    assert np.allclose(np.diff(inp), 2 * math.pi / 72)
    # Fixed co-ordinates stay where they are.
    assert np.all(result.coords[:, :8] == result.coords[0, :8])


def test_model_echo_of_supply() -> None:
    model = mechfem.run_deck(SUPPLY).model
    assert [e.type for e in model.elements] == ["BIN"] * 5 + ["TR2", "BIN", "BIN"]
    assert model.elements[5].coords == [5, 6, 17, 18, 15, 16]
    assert [r.dest for r in model.prescribed] == list(range(1, 13))
    assert model.prescribed[4].formula() == "ANGB(2) - ANGB(4)"
    assert [r.dest for r in model.dependent] == [-1]
    assert model.dofs == [12]
    assert model.n_coords == 20 and model.n_moving == 12


def test_storage_of_supply() -> None:
    storage = mechfem.run_deck(SUPPLY).storage
    assert storage.printbuf == [99, 100, 101, 102]
    assert storage.savedata == [99, 100, 101, 102]
    assert storage.animate == "film"
    assert [[p.keyword for p in pic.plots] for pic in storage.pictures] == [["PLOTHODO"], ["PLOTFUNC"] * 3]
    assert storage.buffer(101).label() == "BUFKE1 -1 1"


def test_check_supply_adjusts_position_1() -> None:
    c = mechfem.check_deck(SUPPLY)
    assert (c.n_coords, c.n_moving, c.n_prescribed, c.n_dependent, c.n_dof) == (20, 12, 12, 1, 1)
    assert c.adjust.iterations > 0 and c.adjust.residual < 1e-10
    assert len(c.adjust.initial_deformations) == 12
    assert c.det != 0.0
    assert c.coords.shape == (20,)
    # Position 1 of a check is position 1 of a run.
    assert np.array_equal(c.coords, mechfem.run_deck(SUPPLY).coords[0])


def test_progress_is_reported_up_to_the_last_position() -> None:
    calls: list[tuple[int, int]] = []
    mechfem.run_deck(SUPPLY, progress=lambda done, total: calls.append((done, total)))
    assert calls and calls[-1] == (73, 73)
    assert [d for d, _ in calls] == sorted(d for d, _ in calls)


@pytest.mark.filterwarnings("ignore::mechfem.IncompleteRunWarning")  # the motion stops on purpose
def test_motion_that_stops_returns_what_was_computed() -> None:
    result = mechfem.run_deck(ROCKER)
    stop = result.report.stop
    assert stop is not None
    assert 1 < result.positions < 37
    assert stop.last_good == result.positions
    assert result.buffers[1].shape == (result.positions,)
    reason = result.report.stop_reason()
    assert reason is not None and f"after position {stop.last_good} of 37" in reason and "input 1 =" in reason


def test_deck_error_carries_path_and_line(tmp_path: Path) -> None:
    deck = tmp_path / "bad.mec"
    deck.write_text("KIN ANA\nTOPOLOGY\nELEM 1 BIN 1 2 3 4\nFROM 1 LENL 1 1\n")
    with pytest.raises(mechfem.DeckError) as info:
        mechfem.run_deck(deck)
    assert info.value.line == 4
    assert Path(info.value.path) == deck
    assert "bad.mec:4" in str(info.value)
    assert isinstance(info.value, mechfem.MechfemError)


def test_errors_form_one_hierarchy() -> None:
    for error in (mechfem.DeckError, mechfem.AssemblyError, mechfem.ConvergenceError, mechfem.LimitPositionError):
        assert issubclass(error, mechfem.MechfemError)


def test_singular_position_1_names_the_superfluous_row() -> None:
    with pytest.raises(mechfem.LimitPositionError) as info:
        mechfem.run_deck(ROOT / "tests" / "decks" / "superfluous.mec")
    assert info.value.rows == [3]
    assert "prescribed row 3 is superfluous" in str(info.value)


def test_unreachable_position_1_raises(tmp_path: Path) -> None:
    deck = tmp_path / "far.mec"
    deck.write_text(ROCKER.read_text().replace("PARA 1 1.0", "PARA 1 10.0"))
    with pytest.raises((mechfem.ConvergenceError, mechfem.LimitPositionError)):
        mechfem.run_deck(deck)
