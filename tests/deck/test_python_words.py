"""The Python API speaks Python: every error, warning and stop reason of a named model names its points, elements,
form parameters and Motion calls, never deck keywords or deck line numbers; unknown names get the closest names
the model has; a run that stops early warns or raises; angles may be given and read in degrees."""

from __future__ import annotations

import math
import pickle
import re
import warnings
from collections.abc import Callable

import numpy as np
import pytest

import mechfem
import mechfem._core as _core
from conftest import ROOT
from mechfem import Driven, Keep, Mechanism, Motion, Output
from mechfem.model.mechanism import By, Table, To

DECKS = ROOT / "tests" / "decks"
LIMITS = ROOT / "examples" / "limits"

# The deck's vocabulary, written out by hand from docs/deck.md: keywords, block and mode names, form parameters
# and element types, and the deck's numbering of lines, rows, DOFs, elements, co-ordinates and inputs.
KEYWORDS = """
    ELEM FORM NRDOF XFIX XMOV PARA TSTEPE MOV_RELE MOV_ABSE MOV_FUNC MOV_FREE MOV_DYN ACCURACY MAXITER INTTOL
    TOPOLOGY GEOMETRY MOVEMENT STORAGE DYNAMICS MASS PMASS INERTIA GRAVITY FORCE LOAD LOADFUNC SPRING MOTOR
    BUFINP BUFX0 BUFKX1 BUFKX2 BUFE0 BUFKE1 BUFKE2 BUFVX BUFAX BUFVE BUFAE BUFDET BUFTIME PRINTBUF SAVEDATA
    LENL ANGB ANGV LENU LENV GEAR BELT COOR BIN HLF TR1 TR2 GR1 GR2 RK1 RK2 BLT CRD
""".split()
DECK_WORDS = re.compile(
    r"\b(" + "|".join(KEYWORDS) + r")\b"
    r"|KIN ANA|DYN ANA|DYN SIM|MOV_"
    r"|\bDOF\b|\bline \d|\brows? \d|\belements? \d|\bco-ordinates? \d|\binputs? \d|\.mec\b"
)


def speaks_python(text: str) -> None:
    """``text`` holds no deck keyword and no deck number."""
    found = DECK_WORDS.search(text)
    assert found is None, f"deck words {found.group(0)!r} in: {text}"


def fourbar(drive: str = "crank", crank: float = 1.0, coupler: float = 3.5, rocker: float = 3.0) -> Mechanism:
    """A crank-rocker four-bar (Grashof: the crank turns fully, the rocker swings between two limit positions)."""
    m = Mechanism("fourbar")
    A0, B0 = m.fixed("A0", 0.0, 0.0), m.fixed("B0", 4.0, 0.0)
    A, B = m.point("A", 1.0, 0.0), m.point("B", 3.5, 2.5)
    m.bar("crank", A0, A, length=crank, angle=Driven() if drive == "crank" else None)
    m.bar("coupler", A, B, length=coupler)
    m.bar("rocker", B0, B, length=rocker, angle=Driven() if drive == "rocker" else Output("psi"))
    return m


def rocker_driven() -> Mechanism:
    """The four-bar driven at its rocker, from a position of the crank-rocker near one of the rocker's limits."""
    r = fourbar().check()
    angle = float(r.output("psi")[0])
    driven = Mechanism("rocker")
    A0, B0 = driven.fixed("A0", 0.0, 0.0), driven.fixed("B0", 4.0, 0.0)
    A, B = driven.point("A", *r.value("A")[0]), driven.point("B", *r.value("B")[0])
    driven.bar("crank", A0, A, length=1.0, angle=Output("phi"))
    driven.bar("coupler", A, B, length=3.5)
    driven.bar("rocker", B0, B, length=3.0, angle=Driven(angle, "psi"))
    return driven


def messages(call: Callable[[], object]) -> list[str]:
    """Every message ``call`` gives: its exception's, its warnings', and the stop reason and warnings of the
    Analysis it returns."""
    out: list[str] = []
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        try:
            result = call()
        except (mechfem.MechfemError, ValueError, TypeError, KeyError, AttributeError) as e:
            out.append(str(e))
        else:
            if isinstance(result, mechfem.Analysis):
                out += [result.stop_reason() or "", *result.warnings]
    return out + [str(w.message) for w in caught]


def coincident() -> Mechanism:
    m = Mechanism("coincident")
    m.bar("crank", m.fixed("A0", 0.0, 0.0), m.point("A", 0.0, 0.0), length=1.0, angle=Driven())
    return m


def with_extra_row() -> Mechanism:
    m = fourbar()
    m.bar("frame", m["A0"], m["B0"], length=Keep())
    return m


def with_free_coupler() -> Mechanism:
    m = Mechanism("loose")
    A0, B0 = m.fixed("A0", 0.0, 0.0), m.fixed("B0", 4.0, 0.0)
    A, B = m.point("A", 1.0, 0.0), m.point("B", 3.5, 2.5)
    m.bar("crank", A0, A, length=1.0, angle=Driven())
    m.bar("coupler", A, B)
    m.bar("rocker", B0, B, length=3.0)
    return m


def superfluous() -> Mechanism:
    m = Mechanism("superfluous")
    A0, B0 = m.fixed("A0", 0.0, 0.0), m.fixed("B0", 4.0, 0.0)
    A, B = m.point("A", 0.5, 0.866), m.point("B", 3.88, 3.0)
    m.bar("crank", A0, A, length=Keep())
    m.bar("coupler", A, B, length=Keep())
    m.bar("rocker", B0, B, angle=Driven())
    m.bar("frame", A0, B0, length=Keep())
    return m


def without_inputs() -> Mechanism:
    m = Mechanism("still")
    m.bar("bar", m.fixed("A0", 0.0, 0.0), m.point("A", 1.0, 0.0), length=1.0, angle=0.0)
    return m


def two_inputs() -> Mechanism:
    m = Mechanism("two")
    m.bar("a", m.fixed("O", 0.0, 0.0), m.point("A", 1.0, 0.0), length=1.0, angle=Driven())
    m.bar("b", m.fixed("P", 0.0, 2.0), m.point("B", 1.0, 2.0), length=1.0, angle=Driven())
    return m


def pendulum() -> Mechanism:
    m = Mechanism("pendulum")
    bar = m.bar("bar", m.fixed("O", 0.0, 0.0), m.point("A", 1.0, 0.0), length=1.0, angle=Driven(name="theta"))
    m.mass(bar, 1.0, 0.5)
    m.gravity(0.0, -9.81)
    return m


def gears() -> Mechanism:
    m = Mechanism("gears")
    m.gear_pair("mesh", m.angle("a", 0.0), m.angle("carrier", 0.0, fixed=True), m.angle("b", 0.0), ratio=-2.0)
    return m


def unused_point() -> Mechanism:
    m = fourbar()
    m.point("C", 5.0, 5.0)
    return m


BATTERY: dict[str, Callable[[], object]] = {
    "unknown point": lambda: fourbar()["Cc"],
    "unknown element slot": lambda: fourbar().bar("b", "A0", "Aa"),
    "unknown form parameter": lambda: fourbar()["crank"].form("lenght"),
    "unknown form parameter of element()": lambda: fourbar().element("b", "BIN", ["A", "B"], lenght=1.0),
    "unknown value to set": lambda: fourbar().variant({"crank.lenght": 1.1}),
    "coincident points": lambda: coincident().run(),
    "unused point": lambda: unused_point().run(),
    "too many prescribed": lambda: with_extra_row().run(),
    "too few prescribed": lambda: with_free_coupler().run(),
    "no inputs": lambda: without_inputs().run(),
    "zero length": lambda: fourbar(crank=0.0).run(),
    "unreachable position": lambda: fourbar(coupler=1.5, rocker=0.5).run(),
    "unreachable position, check": lambda: fourbar(coupler=1.5, rocker=0.5).check(),
    "superfluous row": lambda: superfluous().run(),
    "limit position at the start": lambda: rocker_driven().run(Motion.by(8, -0.4)),
    "a motion that stops at a limit": lambda: Mechanism.from_deck(DECKS / "rocker.mec").run(),
    "a belt that loses its span": lambda: Mechanism.from_deck(DECKS / "belt_loses_span.mec").run(),
    "a driven slider at its dead centre": lambda: Mechanism.from_deck(LIMITS / "slider_dead_centre.mec").run(),
    "free motion of two inputs": lambda: two_inputs().run(Motion.free(10, 0.1)),
    "free motion, one of two inputs": lambda: two_inputs().run(
        Motion(4, {1: mechfem.model.mechanism.Free(0.1), 2: By(1.0)})
    ),
    "free motion with masses": lambda: pendulum().run(Motion.free(10, 0.01)),
    "free motion of step 0": lambda: Motion.free(10, 0.0),
    "no steps": lambda: Motion.by(0, 1.0),
    "too many steps": lambda: Motion.by(20_000_000, 1.0),
    "a time that overflows": lambda: Motion.by(10, 1.0, dt=1e308),
    "max_iter": lambda: Motion.by(10, 1.0, max_iter=5000),
    "negative rtol": lambda: pendulum().simulate(1.0, 10, rtol=-1.0),
    "unknown unit": lambda: Motion.by(10, 1.0, unit="grad"),  # type: ignore[arg-type]
    "degrees for a length": lambda: Mechanism.from_deck(LIMITS / "slider_dead_centre.mec").run(
        Motion.by(4, 0.1, unit="deg")
    ),
    "unknown input": lambda: fourbar().run(Motion.by(4, {"cranck.angle": 1.0})),
    "input number out of range": lambda: fourbar().run(Motion.by(4, {2: 1.0})),
    "a table of the wrong length": lambda: Motion(4, {None: Table(np.zeros(3))}),
    "a simulation without masses": lambda: fourbar().simulate(1.0, 10),
    "a table file name with blanks": lambda: fourbar().to_deck(Motion(2, {None: Table(np.zeros(3), file="a b")})),
    "a run too large for the memory limit": lambda: fourbar().run(Motion.by(2_000_000, 1.0)),
    "a name used twice": lambda: fourbar().point("A", 0.0, 0.0),
    "a form parameter of another mechanism": lambda: fourbar().output("other", fourbar()["crank"].angle),
    "a mass on a gear pair": lambda: gears().mass("mesh", 1.0),
    "a change faster than a number can hold": lambda: fourbar().run(Motion.by(3, 1e300, dt=1e-300, unit="rad")),
    "unknown output": lambda: fourbar().run(Motion.by(4, 0.5)).output("psii"),
    "unknown point of a result": lambda: fourbar().run(Motion.by(4, 0.5)).x("Aa"),
    "unknown input of a result": lambda: fourbar().run(Motion.by(4, 0.5)).input("crank.angel"),
}


@pytest.mark.parametrize("case", list(BATTERY))
def test_no_message_of_the_named_api_speaks_deck(case: str, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("MECHFEM_MEMORY_LIMIT", "64M")
    found = [m for m in messages(BATTERY[case]) if m]
    assert found, f"{case}: no message at all"
    for text in found:
        speaks_python(text)


def test_the_deck_path_keeps_speaking_deck() -> None:
    # The same stop, run as a deck, says MOV_FREE and DOF: that is the deck's language.
    with pytest.warns(mechfem.IncompleteRunWarning, match="MOV_FREE 1"):
        deck = mechfem.run_deck(DECKS / "rocker.mec")
    assert "the input of DOF 1" in (deck.report.stop_reason() or "")
    with pytest.warns(mechfem.IncompleteRunWarning):
        named = Mechanism.from_deck(DECKS / "rocker.mec").run()
    reason = named.stop_reason() or ""
    assert named.positions == deck.positions == 4
    assert "the input 'E3.angle' reached its limit position at E3.angle = 2.30052398302" in reason
    assert "`Motion.free(36, ds=0.78)`" in reason and "Analysis.input()" in reason


# --- the words of each kind of message ------------------------------------------------------------------------------


def test_deck_mistakes_name_the_model_parts_and_keep_their_attributes() -> None:
    with pytest.raises(mechfem.DeckError) as info:
        unused_point().run()
    e = info.value
    assert (
        str(e)
        == "the point 'C' of the mechanism 'fourbar' is used by no element; connect it to an element, or leave it out"
    )
    assert e.name == "C.x" and e.what == "co-ordinate"  # type: ignore[attr-defined]
    assert e.kind == "coordinate_unused" and e.deck is None and e.line is None  # type: ignore[attr-defined]

    with pytest.raises(mechfem.DeckError) as info:
        coincident().run()
    assert str(info.value).startswith(
        "the bar 'crank' (A0, A) cannot be evaluated at the given co-ordinates: its points A0 and A coincide, so the "
        "direction A0->A is undefined"
    )
    with pytest.raises(
        mechfem.DeckError,
        match=r"prescribes 3 form parameters or combinations, inputs included "
        r"\(crank.length, rocker.length, crank.angle\), for 4 moving co-ordinates "
        r"\(A.x, A.y, B.x, B.y\): 1 too few",
    ):
        with_free_coupler().run()
    with pytest.raises(
        mechfem.DeckError,
        match="'crank.length' prescribes the length of the bar 'crank' "
        r"\(A0, A\) as 0, but a length must be greater than zero",
    ):
        fourbar(crank=0.0).run()
    with pytest.raises(mechfem.DeckError, match="the mechanism 'still' has no inputs; make a form parameter an input"):
        without_inputs().run()


def test_position_one_errors_name_points_rows_and_coordinates() -> None:
    with pytest.raises(mechfem.ConvergenceError) as conv:
        fourbar(coupler=1.5, rocker=0.5).run()
    assert str(conv.value).startswith("position 1 of the mechanism 'fourbar' cannot be computed: Newton iteration")
    assert "give the moving points (A, B) estimates near a position that fits" in str(conv.value)

    with pytest.raises(mechfem.LimitPositionError) as lim:
        superfluous().run()
    e = lim.value
    assert e.rows == [3] and e.row_names == ["frame.length"]  # type: ignore[attr-defined]
    assert set(e.coord_names) == {"A.x", "A.y", "B.x", "B.y"} and len(e.coords) == 4  # type: ignore[attr-defined]
    assert "the prescribed value 'frame.length' is superfluous" in str(e)


def test_assembly_errors_name_the_element_and_its_points() -> None:
    from mechfem.deck import deckio

    deck = deckio.write(fourbar())
    err = mechfem.AssemblyError("element 2 (BIN): the points P and Q coincide, so the direction P->Q is undefined")
    err.element = 2
    # The fields the binding sets: the core's reason in its words and as structure.
    err.detail = "the points P and Q coincide, so the direction P->Q is undefined"
    err.detail_fields = _core.ElementFault(2, "coincident_points")
    new = deckio.translate(err, deck, "fourbar")
    assert isinstance(new, mechfem.AssemblyError)
    assert new.element == 2 and new.element_name == "coupler"  # type: ignore[attr-defined]
    assert "the bar 'coupler' (A, B) cannot be evaluated there: its points A and B coincide" in str(new)
    speaks_python(str(new))


def test_a_stop_in_the_middle_names_the_element_that_failed() -> None:
    with pytest.warns(mechfem.IncompleteRunWarning) as caught:
        r = Mechanism.from_deck(DECKS / "belt_loses_span.mec").run()
    reason = r.stop_reason() or ""
    assert "the step from E1.angle = 2.967059728 rad to E1.angle = 3.141592654 rad failed" in reason
    assert "the belt 'E2' (P5, x7, P3, x8, x9, x10): the belt has no free span" in reason
    assert reason in str(caught[0].message)


def test_singular_positions_are_warned_in_python_words() -> None:
    m = Mechanism("slider")
    A0, A, B = m.fixed("A0", 0.0, 0.0), m.point("A", 1.0, 0.0), m.point("B", 4.0, 0.0, fixed="y")
    m.bar("crank", A0, A, length=1.0, angle=Output("theta"))
    m.bar("rod", A, B, length=3.0)
    m.single_coordinate("slider", B.x, value=Driven(4.0, "xB"))
    r = m.run(Motion.free(40, -0.05))
    assert r.complete and r.warnings == [
        "D^c is singular at position 1: the mechanism is in a limit position of its input there, no transfer "
        "functions exist, and every result made from them (transfer functions of first and second order, "
        "velocities, accelerations) is NaN there."
    ]


# --- did you mean ---------------------------------------------------------------------------------------------------


def four_points() -> Mechanism:
    m = Mechanism("fourbar")
    A, B, C, D = m.fixed("A", 0.0, 0.0), m.point("B", 1.0, 0.0), m.point("C", 3.5, 2.5), m.fixed("D", 4.0, 0.0)
    m.bar("crank", A, B, length=1.0, angle=Driven())
    m.bar("coupler", B, C, length=3.5)
    m.bar("rocker", D, C, length=3.0, angle=Output("psi"))
    return m


def test_an_unknown_point_gets_the_closest_point() -> None:
    r = four_points().run(Motion.by(4, 0.5))
    with pytest.raises(KeyError) as info:
        r.x("Cc")
    assert str(info.value) == "no point named 'Cc' in the mechanism 'fourbar'; did you mean 'C'? (points: A, B, C, D)"


@pytest.mark.parametrize(
    ("call", "expected"),
    [
        (
            lambda m: m["cranck"],
            "no part named 'cranck' in the mechanism 'fourbar'; did you mean 'crank'? (elements: "
            "crank, coupler, rocker)",
        ),
        (
            lambda m: m.bar("b", "A", "Bb"),
            "no point named 'Bb' in the mechanism 'fourbar'; did you mean 'B'? (points: A, B, C, D)",
        ),
        (
            lambda m: m.set("crank.lenght", 1.1),
            "did you mean 'crank.length'? (prescribed values: crank.length, coupler.length, rocker.length)",
        ),
        (
            lambda m: m.run(Motion.by(4, {"crank.angel": 0.5})),
            "no input named 'crank.angel'; did you mean 'crank.angle'? (inputs: crank.angle)",
        ),
        (
            lambda m: m.run(Motion.by(4, 0.5)).output("pis"),
            "no output or row named 'pis' in the mechanism 'fourbar'; did you mean 'psi'? (outputs: psi)",
        ),
        (lambda m: m.run(Motion.by(4, 0.5)).input("angle"), "no input named 'angle'; did you mean 'crank.angle'?"),
        (lambda m: m.run(Motion.by(4, 0.5)).value("C.xx"), "did you mean 'C.x'?"),
        (
            lambda m: mechfem.sweep(m, {"coupler.lenght": [3.5]}, motion=Motion.by(4, 0.5), progress=False),
            "did you mean 'coupler.length'?",
        ),
    ],
)
def test_every_lookup_suggests_the_closest_name(call: Callable[[Mechanism], object], expected: str) -> None:
    with pytest.raises(KeyError) as info:
        call(four_points())
    assert expected in str(info.value)


def test_form_parameters_and_study_parameters_get_the_closest_name() -> None:
    m = four_points()
    with pytest.raises(
        AttributeError,
        match=re.escape(
            "no form parameter named 'lenght' on the bar 'crank'; did you mean 'length'? (its form parameters: length, "
            "angle)"
        ),
    ):
        m["crank"].form("lenght")
    with pytest.raises(TypeError, match="did you mean 'angle'"):
        m.element("extra", "BIN", ["A", "D"], angel=Keep())

    def model(coupler: float = 3.5) -> Mechanism:
        return fourbar(coupler=coupler)

    with pytest.raises(
        KeyError, match="no parameter named 'couple' of the model function 'model'; did you mean 'coupler'"
    ):
        mechfem.sweep(model, {"couple": [3.5]}, motion=Motion.by(4, 0.5), progress=False)


def test_element_slots_may_be_given_by_name() -> None:
    m = Mechanism("named")
    m.fixed("A0", 0.0, 0.0)
    m.point("A", 1.0, 0.0)
    bar = m.bar("crank", "A0", "A", length=1.0, angle=Driven())
    assert bar.points == (m["A0"], m["A"])
    with pytest.raises(TypeError, match="'crank' is an element of the mechanism 'named', not a point"):
        m.bar("other", "A0", "crank")


# --- early stops ----------------------------------------------------------------------------------------------------


def test_an_early_stop_warns_at_the_callers_line_in_python_words() -> None:
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        r = rocker_driven().run(Motion.by(8, -0.4))
    stops = [w for w in caught if issubclass(w.category, mechfem.IncompleteRunWarning)]
    assert len(stops) == 1 and stops[0].filename == __file__
    text = str(stops[0].message)
    assert text.startswith(f"the motion stopped early: The motion stopped after position {r.positions} of 9")
    assert "the input 'psi' reached its limit position" in text
    speaks_python(text)


def test_raise_on_stop_raises_with_the_partial_result() -> None:
    m = rocker_driven()
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        with pytest.raises(mechfem.RunStoppedError) as info:
            m.run(Motion.by(8, -0.4), raise_on_stop=True)
    e = info.value
    assert isinstance(e, mechfem.MechfemError) and isinstance(e.result, mechfem.Analysis)
    assert 1 <= e.result.positions < 9 and not e.result.complete
    assert str(e) == e.reason == e.result.stop_reason()
    speaks_python(str(e))
    copy = pickle.loads(pickle.dumps(e))
    assert copy.reason == e.reason and copy.result.positions == e.result.positions
    # A complete run does not raise.
    assert m.run(Motion.by(2, 0.01), raise_on_stop=True).complete


def test_raise_on_stop_for_decks_simulations_and_batches() -> None:
    with pytest.raises(mechfem.RunStoppedError) as info:
        mechfem.run_deck(DECKS / "rocker.mec", raise_on_stop=True)
    assert isinstance(info.value.result, mechfem.RunResult) and "MOV_FREE 1" in info.value.reason

    mechanisms = [fourbar(), rocker_driven()]
    motion = Motion.by(8, -0.4)
    with pytest.warns(mechfem.IncompleteRunWarning, match="1 of 2 runs stopped before their last position"):
        results = mechfem.run_many(mechanisms, motion, progress=False)
    assert isinstance(results[1], mechfem.Analysis) and not results[1].complete
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        results = mechfem.run_many(mechanisms, motion, progress=False, raise_on_stop=True)
    assert isinstance(results[0], mechfem.Analysis) and results[0].complete
    assert isinstance(results[1], mechfem.RunStoppedError) and results[1].result.positions < 9

    def model(length: float) -> Mechanism:
        return rocker_driven() if length > 3.0 else fourbar()

    sets = [{"length": 3.0}, {"length": 3.5}]
    with pytest.warns(mechfem.IncompleteRunWarning, match="1 of 2 variants stopped"):
        study = mechfem.sweep(model, sets, {"n": lambda a: a.positions}, motion=motion, progress=False)
    assert list(study["ok"]) == [True, True] and list(study["complete"]) == [True, False]
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        study = mechfem.sweep(
            model,
            sets,
            {"n": lambda a: a.positions},
            motion=motion,
            progress=False,
            raise_on_stop=True,
            keep_results=True,
        )
    assert list(study["ok"]) == [True, False] and math.isnan(study["n"][1])
    assert study["error"][1].startswith("The motion stopped after position")
    assert study.results is not None and isinstance(study.results[1], mechfem.RunStoppedError)


# --- degrees --------------------------------------------------------------------------------------------------------


def test_degrees_give_the_radians_they_convert_to_to_the_last_bit() -> None:
    m = fourbar()
    rad = m.run(Motion.by(36, math.radians(360)))
    deg = m.run(Motion.by(36, 360, unit="deg"))
    assert math.radians(360) == 2 * math.pi
    assert np.array_equal(rad.coords, deg.coords) and np.array_equal(rad.output("psi", 2), deg.output("psi", 2))
    # The deck gets exactly the radians.
    assert m.to_deck(Motion.to(4, 90, unit="deg")) == m.to_deck(Motion.to(4, math.pi / 2))
    assert m.to_deck(Motion(4, {None: To(-30.0, "deg")})) == m.to_deck(Motion.to(4, math.radians(-30.0)))
    values = np.linspace(0.0, 90.0, 5)
    assert np.array_equal(
        m.run(Motion.table(values, unit="deg")).coords, m.run(Motion.table(np.radians(values))).coords
    )
    # A start value in degrees.
    a = Mechanism("a")
    a.bar("bar", a.fixed("O", 0.0, 0.0), a.point("P", 1.0, 0.1), length=1.0, angle=Driven(30.0, unit="deg"))
    b = Mechanism("a")
    b.bar("bar", b.fixed("O", 0.0, 0.0), b.point("P", 1.0, 0.1), length=1.0, angle=Driven(math.radians(30.0)))
    assert a.to_deck() == b.to_deck()
    assert a["bar.angle"].value == math.pi / 6


def test_results_in_degrees() -> None:
    r = fourbar().run(Motion.by(12, 360, unit="deg"))
    assert np.array_equal(r.input(unit="deg"), np.degrees(r.input()))
    assert np.array_equal(r.position("psi", unit="deg"), np.degrees(r.output("psi")))
    assert np.array_equal(r.output("psi", unit="deg"), np.degrees(r.output("psi")))
    # d psi / d crank of two angles is the same number in either unit; per degree of the crank, a length's is smaller.
    assert np.array_equal(r.output("psi", 1, unit="deg"), r.output("psi", 1))
    assert np.allclose(r.transfer("B.x", unit="deg"), r.transfer("B.x") * math.pi / 180, rtol=1e-15, atol=0)
    assert np.allclose(r.output("psi", 2, unit="deg"), r.output("psi", 2) * math.pi / 180, rtol=1e-15, atol=0)
    assert np.array_equal(r.velocity("psi", unit="deg"), np.degrees(r.velocity("psi")))
    with pytest.raises(ValueError, match="'B.x' is not an angle"):
        r.value("B.x", unit="deg")
    with pytest.raises(ValueError, match="unit must be one of 'm', 'mm', 'cm', 'in', 'rad', 'deg'"):
        r.input(unit="grad")  # type: ignore[arg-type]


def test_a_large_angle_without_a_unit_warns() -> None:
    m = fourbar()
    with pytest.warns(mechfem.UnitWarning, match="'crank.angle' by 360 rad .*unit='deg'") as caught:
        m.to_deck(Motion.by(72, 360))
    assert caught[0].filename == __file__ and issubclass(mechfem.UnitWarning, UserWarning)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        m.to_deck(Motion.by(72, 360, unit="rad"))  # many turns, on purpose
        m.to_deck(Motion.by(72, 360, unit="deg"))
        m.to_deck(Motion.by(72, 100.0))  # at the limit, not beyond it
        slider = Mechanism.from_deck(LIMITS / "slider_dead_centre.mec")
        slider.to_deck(Motion.by(20, 360.0))  # a length input: no angle, no warning
    with pytest.warns(mechfem.UnitWarning):
        m.to_deck(Motion.to(72, 720))
    with pytest.warns(mechfem.UnitWarning):
        m.to_deck(Motion.table(np.linspace(0.0, 720.0, 73)))


def test_degrees_for_an_input_that_is_not_an_angle_are_refused() -> None:
    slider = Mechanism.from_deck(LIMITS / "slider_dead_centre.mec")
    with pytest.raises(ValueError, match="gives the input 's' in degrees .* but it is not an angle"):
        slider.run(Motion.by(4, 0.1, unit="deg"))
    m = Mechanism("slider")
    B = m.point("B", 1.0, 0.0, fixed="y")
    with pytest.raises(ValueError, match="not an angle"):
        m.single_coordinate("slide", B.x, value=Driven(1.0, unit="deg"))


def test_free_motion_has_no_unit_and_a_zero_step_is_refused() -> None:
    with pytest.raises(ValueError, match="must not be 0"):
        Motion.free(10, 0.0)
    with pytest.raises(TypeError):
        Motion.free(10, 0.1, unit="deg")  # type: ignore[call-arg]


def test_a_name_passed_where_a_number_belongs_is_named_in_the_error() -> None:
    # Driven's first argument is the start value; a name there must not surface as float()'s own message.
    m = Mechanism("f")
    a0, a = m.fixed("A0", 0.0, 0.0), m.point("A", 0.0, 1.0)
    with pytest.raises(ValueError, match=r"the start value of crank\.angle must be a number, not 'phi'"):
        m.bar("crank", a0, a, length=1.0, angle=Driven("phi"))  # type: ignore[arg-type]
