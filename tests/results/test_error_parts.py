"""Solver errors and stop reasons cross from the core with the things they name as structure (``parts``): a deck's
messages are exactly the core's words with deck numbers, a named model's name its elements, co-ordinates, rows and
the Python API's terms from those parts, and no message text is ever rewritten."""

from __future__ import annotations

import warnings

import pytest

import mechfem
import mechfem._core as _core
from conftest import ROOT
from deck.test_python_words import superfluous
from mechfem import Driven, Mechanism
from mechfem.deck import deckio
from mechfem.deck.explain import PythonWords, parts_of
from mechfem.results.words import Part, Words

DECKS = ROOT / "tests" / "decks"


def position_one(m: Mechanism, **moved: tuple[float, float]) -> mechfem.MechfemError:
    """The error of the core at position 1 of ``m``'s compiled model with the points ``moved`` to other (x, y),
    untranslated: a compiled model meets the given numbers in the core, not in the deck reader."""
    deck = deckio.write(m)
    model = _core.Model(deck.text, deck.path, str(DECKS))
    changes: list[tuple[int, int, float]] = []
    number = {c.name: i for i, c in enumerate(deck.numbering.coords, 1)}
    for point, (x, y) in moved.items():
        changes += [(0, number[f"{point}.x"], x), (0, number[f"{point}.y"], y)]
    with pytest.raises(mechfem.MechfemError) as info:
        model.run(changes, False)
    return info.value


def fourbar(names: dict[str, str] | None = None) -> Mechanism:
    """A crank-rocker four-bar; ``names`` renames its points and elements."""
    n = {k: k for k in ("A0", "B0", "A", "B", "crank", "coupler", "rocker")} | (names or {})
    m = Mechanism("fourbar")
    A0, B0 = m.fixed(n["A0"], 0.0, 0.0), m.fixed(n["B0"], 4.0, 0.0)
    A, B = m.point(n["A"], 1.0, 0.0), m.point(n["B"], 3.5, 2.5)
    m.bar(n["crank"], A0, A, length=1.0, angle=Driven())
    m.bar(n["coupler"], A, B, length=3.5)
    m.bar(n["rocker"], B0, B, length=3.0)
    return m


# --- decks: the core's words, deck numbers ----------------------------------------------------------------------------


def test_a_decks_position_one_failure_keeps_its_message_and_carries_its_parts() -> None:
    with pytest.raises(mechfem.LimitPositionError) as info:
        mechfem.run_deck(DECKS / "superfluous.mec")
    e = info.value
    assert str(e) == (
        "D^c is singular (pivot 0.00e0 at the column of co-ordinate 8); D^c has rank 3 of 4: prescribed row 3 is "
        "superfluous, and co-ordinates 8, 5, 6, 7 can move with every prescribed value held"
    )
    assert ("coordinate", 8, "co-ordinate 8") in e.parts
    assert ("row", 3, "row 3") in e.parts and ("coords", [8, 5, 6, 7], "co-ordinates 8, 5, 6, 7") in e.parts
    assert Words().render(e.parts) == str(e)


def test_a_decks_stop_keeps_the_cores_words_with_deck_numbers() -> None:
    with pytest.warns(mechfem.IncompleteRunWarning):
        r = mechfem.run_deck(DECKS / "belt_loses_span.mec")
    stop = r.report.stop
    assert stop is not None and stop.kind == "element"
    assert stop.message == "element 2 (BLT): the belt has no free span: centre distance 20 <= |R_P - R_Q| = 20"
    assert stop.parts[0] == ("element", 2, "element 2 (BLT)")
    assert Words().render(stop.parts) == stop.message
    assert stop.message in (r.report.stop_reason() or "")


# --- named models: the model's names, from the parts ----------------------------------------------------------------


def test_a_named_position_one_failure_names_the_element_and_its_points() -> None:
    err = position_one(fourbar(), A=(3.5, 2.5))
    assert isinstance(err, mechfem.AssemblyError)
    assert str(err) == "element 2 (coupler, BIN): the points P and Q coincide, so the direction P->Q is undefined"
    assert err.detail_fields == _core.ElementFault(2, "coincident_points")
    deck = deckio.write(fourbar())
    assert PythonWords(deck.numbering).render(err.parts) == (
        "the bar 'coupler' (A, B): its points A and B coincide, so the direction A->B is undefined"
    )
    new = deckio.translate(err, deck, "fourbar")
    assert str(new).startswith(
        "position 1 of the mechanism 'fourbar' cannot be computed: the bar 'coupler' (A, B) cannot be evaluated "
        "there: its points A and B coincide, so the direction A->B is undefined; give the moving points (A, B)"
    )
    assert new.parts == err.parts  # type: ignore[attr-defined]


def test_a_named_singular_start_names_coordinates_and_rows() -> None:
    m = superfluous()
    err = position_one(m)
    assert isinstance(err, mechfem.LimitPositionError)
    rendered = PythonWords(deckio.write(m).numbering).render(err.parts)
    assert rendered.startswith("D^c is singular (pivot 0.00e0 at the column of co-ordinate B.y); D^c has rank 3 of")
    assert "prescribed row 'frame.length' is superfluous, and co-ordinates B.y, A.x, A.y, B.x can move" in rendered


def test_a_named_stop_names_the_element_from_the_parts() -> None:
    with pytest.warns(mechfem.IncompleteRunWarning):
        a = Mechanism.from_deck(DECKS / "belt_loses_span.mec").run()
    stop = a.report.stop
    assert stop is not None and stop.parts[0] == ("element", 2, "element 2 (BLT)")
    words = PythonWords(a.numbering)
    said = (
        "the belt 'E2' (P5, x7, P3, x8, x9, x10): the belt has no free span: the distance 20 between the wheel "
        "centres P5 and P3 is not larger than |x9 - x10| = 20"
    )
    assert words.render(stop.parts) == said
    assert said in (a.stop_reason() or "")


def test_deck_terms_are_said_in_the_python_apis_terms() -> None:
    m = Mechanism("bare")
    m.bar("bar", m.fixed("O", 0.0, 0.0), m.point("A", 1.0, 0.0), length=1.0, angle=Driven(name="theta"))
    m.spring("theta", 1.0, 0.5)
    with pytest.raises(mechfem.MechfemError) as info:
        m.simulate(1.0, 10)
    assert str(info.value) == (
        "an input that moves under the forces (Dynamic) has no mass or inertia to move (the inputs that move under "
        "the forces: 'theta')"
    )
    deck = deckio.write(m)
    words = PythonWords(deck.numbering)
    parts: list[Part] = [
        "free motion (",
        ("term", "free_motion", "MOV_FREE"),
        ") needs ",
        ("term", "simulation", "DYN SIM"),
    ]
    assert words.render(parts) == "free motion (Motion.free) needs Mechanism.simulate"
    assert Words().render(parts) == "free motion (MOV_FREE) needs DYN SIM"


# --- no rewriting of message text -----------------------------------------------------------------------------------

LOOKALIKES = {"A": "co-ordinate 5", "B": "DOF 2", "coupler": "element 1 (BIN)", "crank": "input 1"}
"""Names that look like the deck's numbering: a message that rewrote its text would rename them."""


def test_names_that_look_like_deck_numbers_are_said_as_they_are() -> None:
    m = fourbar(LOOKALIKES)
    err = position_one(m, **{"co-ordinate 5": (3.5, 2.5)})
    new = deckio.translate(err, deckio.write(m), "fourbar")
    assert str(new).startswith(
        "position 1 of the mechanism 'fourbar' cannot be computed: the bar 'element 1 (BIN)' (co-ordinate 5, DOF 2) "
        "cannot be evaluated there: its points co-ordinate 5 and DOF 2 coincide, so the direction "
        "co-ordinate 5->DOF 2 is undefined; give the moving points (co-ordinate 5, DOF 2) estimates"
    )


def test_plain_words_of_a_message_are_never_rewritten() -> None:
    deck = deckio.write(fourbar(LOOKALIKES))
    words = PythonWords(deck.numbering)
    text = "element 1 (BIN): co-ordinates 1, 2, co-ordinate 3, input 1, DOF 1 (MOV_FREE) and a degree of freedom"
    assert words.render([text]) == text
    assert words.render(parts_of(mechfem.MechfemError(text))) == text
    # Only the parts that name things are the model's words.
    assert words.render([("element", 3, "element 3 (BIN)"), ": ", text]) == f"the bar 'rocker' (B0, DOF 2): {text}"


def test_a_stop_built_without_parts_says_its_message() -> None:
    from mechfem.results.run_report import Stop

    stop = Stop(3, [1.0], [0.9], "no_convergence", "element 1 (BIN) stays as written", None)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        deck = deckio.write(fourbar())
        assert "element 1 (BIN) stays as written" in stop.describe(5, PythonWords(deck.numbering))
