"""What a run echoes of its model, and what a deck describes, cross the binding as the compiled module's own objects:
read through attributes, equal when they hold the same, the same after a pickle; a row's formula writes a factor as
Python's ``format(v, "g")`` does."""

from __future__ import annotations

import pickle
from pathlib import Path

import numpy as np
import pytest

import mechfem
from conftest import FOURBAR, ROOT
from mechfem import _core
from mechfem.design import optimise_deck

SUPPLY = ROOT / "examples" / "supply"


def test_a_runs_model_echo_is_typed_and_survives_a_pickle() -> None:
    model = mechfem.run_deck(SUPPLY / "supply_dyn.mec").model
    assert isinstance(model, _core.EchoModel)
    assert isinstance(model.elements[0], _core.EchoElement) and model.elements[0].type == "BIN"
    assert isinstance(model.prescribed[0].terms[0], mechfem.Term)
    assert model.n_moving == sum(c.moving for c in model.coordinates) and model.n_coords == len(model.coordinates)
    assert isinstance(model.dynamics, _core.EchoDynamics) and model.dynamics.bodies[0].element == 1
    again = pickle.loads(pickle.dumps(model))
    assert again == model and again.dynamics == model.dynamics and again.labels is not None


@pytest.mark.parametrize("factor", [0.5, 1e-7, 1234567.0, 0.333333333, 2.0, 123456.0, 1e-4])
def test_a_rows_formula_writes_a_factor_as_python_does(factor: float) -> None:
    terms = [_core.Term(2, "ANGB", factor, 1, 3), _core.Term(4, "ANGB", -factor, 2, 4)]
    row = _core.EchoRow(1, terms, None, None, 0.0)
    assert row.formula() == f"{factor:g}*ANGB(2) - {factor:g}*ANGB(4)"
    assert _core.EchoRow(2, [_core.Term(1, "LENL", 1.0, 1, 1)], None, None, 0.0).formula() == "LENL(1)"


def test_a_decks_description_and_optimise_block_are_typed() -> None:
    d = optimise_deck.describe(SUPPLY / "supply_opt.mec")
    assert isinstance(d, _core.DeckDescription) and d.mode == "KIN OPT"
    assert d.motion is not None and isinstance(d.motion.inputs[0], _core.DeckInput)
    assert [c.given for c in d.coordinates[:2]] == [0.0, 0.0]
    assert isinstance(d.optimise, _core.OptimiseBlock) and d.optimise.vary[0].number == 5


def test_a_deck_errors_diagnostics_and_element_fault_are_typed_and_survive_a_pickle(tmp_path: Path) -> None:
    # The rocker's pin put on its pivot: the deck reader refuses the element, with the core's reason as a fault.
    deck = tmp_path / "coincident.mec"
    deck.write_text(FOURBAR.replace("XMOV 5 1.0\n 6 0.0\n 7 2.725\n 8 2.4545", "XMOV 5 1.0\n 6 0.0\n 7 3.2\n 8 0.0"))
    with pytest.raises(mechfem.DeckError) as caught:
        mechfem.check_deck(deck)
    err = caught.value
    (d,) = err.diagnostics
    assert isinstance(d, _core.Diagnostic) and d.kind == err.kind and d.line == err.line > 0 and d.element == 3
    assert d.detail_fields == err.detail_fields == _core.ElementFault(3, "coincident_points")
    assert d.text in deck.read_text() and d.message == err.message
    assert pickle.loads(pickle.dumps(d)) == d


def test_a_design_evaluation_is_typed_and_survives_a_pickle(tmp_path: Path) -> None:
    deck = tmp_path / "fourbar.mec"
    deck.write_text(FOURBAR)
    model = _core.DesignModel(FOURBAR, str(deck), str(tmp_path), [(1, 1)], [3, 4], [(4, 3)])
    ev = model.evaluate([1.05])
    assert isinstance(ev, _core.Evaluation) and ev.feasible and ev.reason is None and ev.positions == 361
    assert ev.values.shape == (361, 2) and ev.gradient.shape == (361, 2, 1)
    assert ev.extrema and all(isinstance(x, _core.Extremum) and x.spec == 0 for x in ev.extrema)
    again = pickle.loads(pickle.dumps(ev))
    assert np.array_equal(again.gradient, ev.gradient) and again.extrema[0].value == ev.extrema[0].value
    bad = model.evaluate([-1.0])
    assert not bad.feasible and bad.reason and bad.positions == 0 and bad.gradient.shape == (0, 2, 1)
