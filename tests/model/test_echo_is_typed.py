"""What a run echoes of its model, and what a deck describes, cross the binding as the compiled module's own objects:
read through attributes, equal when they hold the same, the same after a pickle; a row's formula writes a factor as
Python's ``format(v, "g")`` does."""

from __future__ import annotations

import pickle

import pytest

import mechfem
from conftest import ROOT
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
