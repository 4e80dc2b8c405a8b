"""A compiled model run with other co-ordinates (a study's variants, ``_core.Model.run`` with changes) starts as the
deck with those co-ordinates would: the angles its elements track are taken from their directions at the new
co-ordinates, and a row the deck gives no value takes the one it has there. Compared to the last bit with the deck
text that says so."""

from __future__ import annotations

import math

import numpy as np

import mechfem
from mechfem import Driven, Keep, Mechanism, Motion, Output, _core
from mechfem.deck import deckio
from mechfem.model.storage import Storage
from run.test_a_topology_is_compiled_once import crossing as kept_models_crossing


def fourbar(b: tuple[float, float] = (3.5, 2.5)) -> Mechanism:
    """A four-bar whose coupler length and crank start are not given: both are those at the co-ordinates."""
    m = Mechanism("fourbar")
    A0, B0 = m.fixed("A0", 0.0, 0.0), m.fixed("B0", 4.0, 0.0)
    A, B = m.point("A", 1.0, 0.3), m.point("B", *b)
    m.bar("crank", A0, A, length=1.0, angle=Driven())
    m.bar("coupler", A, B, length=Keep())
    m.bar("rocker", B0, B, length=3.0, angle=Output("psi"))
    m.motion = Motion.by(72, 2 * math.pi)
    m.storage = Storage().buffer(1, "BUFX0", "B.x").buffer(2, "BUFE0", "psi")
    return m


def crossing(by: float) -> Mechanism:
    """The four-bar of test_kept_models whose rocker points left, just above or below the x axis, recording psi."""
    m = kept_models_crossing(by)
    m.storage = Storage().buffer(1, "BUFE0", "psi")
    return m


def text_run(m: Mechanism) -> _core.Run:
    deck = deckio.write(m, m.motion, m.storage)
    return _core.run_deck_text(deck.text, deck.path, ".")


def moved_run(m: Mechanism, point: str, xy: tuple[float, float]) -> _core.Run:
    """``m`` compiled once, then run with ``point`` at ``xy`` as a change of its co-ordinates."""
    deck = deckio.write(m, m.motion, m.storage)
    number = {c.name: i for i, c in enumerate(deck.numbering.coords, 1)}
    model = _core.Model(deck.text, deck.path, ".")
    return model.run([(0, number[f"{point}.x"], xy[0]), (0, number[f"{point}.y"], xy[1])])


def assert_same(a: _core.Run, b: _core.Run) -> None:
    assert np.array_equal(a.coords, b.coords)
    assert np.array_equal(a.table, b.table, equal_nan=True)
    assert a.model == b.model


def test_a_row_without_value_takes_it_from_the_moved_coordinates() -> None:
    moved = moved_run(fourbar(), "B", (3.4, 2.6))
    assert_same(moved, text_run(fourbar((3.4, 2.6))))
    # Row 2 is the coupler's length, which the deck does not give: the one at the moved co-ordinates.
    assert moved.model.prescribed[1].para is None
    assert abs(moved.model.prescribed[1].value - math.hypot(2.4, 2.3)) < 1e-12


def test_an_element_moved_across_its_branch_tracks_its_angle_from_there() -> None:
    assert_same(moved_run(crossing(0.1), "B", (1.6, -0.1)), text_run(crossing(-0.1)))


def test_a_study_of_point_positions_is_its_variants_run_one_by_one() -> None:
    ys = [0.1, -0.1, 0.05]
    study = mechfem.sweep(crossing(0.1), [{"B": (1.6, y)} for y in ys], workers=1, progress=False, keep_results=True)
    for y, a in zip(ys, study.results, strict=True):
        assert np.array_equal(a.output("psi"), crossing(y).run(progress=False).output("psi"))
