"""The Python model API: mechanisms built with names, every element type, roles, motions, results, errors,
pictures, and the python code of the API documents."""

from __future__ import annotations

import math
import sys
from pathlib import Path

import numpy as np
import numpy.typing as npt
import pytest

import mechfem
import mechfem._core as _core
from conftest import ROOT, SUPPLY
from mechfem import Driven, Keep, Mechanism, Motion, Output
from mechfem.model.mechanism import By, Table, To

EXAMPLES = ROOT / "examples"
TURN = 2 * math.pi


def close(a: npt.ArrayLike, b: npt.ArrayLike, rtol: float = 1e-9, atol: float = 1e-12) -> bool:
    return bool(np.allclose(np.asarray(a), np.asarray(b), rtol=rtol, atol=atol, equal_nan=True))


def supply() -> Mechanism:
    """The supply mechanism of theory section 5.6.6, with the names of its figure."""
    m = Mechanism("supply")
    A0 = m.fixed("A0", 0.0, 0.0)
    B0 = m.fixed("B0", 0.55678, -0.9)
    G0 = m.fixed("G0", 1.04091, -6.22864)
    M0 = m.fixed("M0", 0.17488, -6.72864)
    A = m.point("A", 0.2, -0.34)
    B = m.point("B", 1.0, -0.2)
    K = m.point("K", 0.3, 0.3)
    G = m.point("G", 0.55, -6.23)
    H = m.point("H", 0.84, -6.3)
    M = m.point("M", 0.45, -7.2)
    m.bar("crank", A0, A, length=0.4, angle=Driven(name="alpha"))
    coupler = m.bar("coupler", B, A, length=0.8)
    m.bar("rocker", B0, B, length=0.8)
    arm = m.bar("arm", B, K, length=0.8)
    m.fixed_angle("kappa", coupler, arm, -5.17514)
    m.bar("link", K, G, length=6.78543)
    m.ternary2("lever", G0, H, G, length=0.71771, u=0.50120, v=0.0)
    m.bar("rod", H, M, length=0.5)
    m.bar("output", M0, M, length=0.64952, angle=Output("delta"))
    return m


# --- the supply mechanism ----------------------------------------------------------------------------------------


def test_supply_built_by_name_gives_the_deck_results() -> None:
    r = supply().run(Motion.by(72, TURN))
    deck = mechfem.run_deck(SUPPLY)
    assert r.complete and r.positions == 73
    # Same numbering, same rows: the very same deck, so the very same numbers.
    assert np.array_equal(r.input("alpha"), deck.buffers[99])
    assert np.array_equal(r.output("delta"), deck.buffers[100])
    assert np.array_equal(r.output("delta", order=1), deck.buffers[101])
    assert np.array_equal(r.output("delta", order=2), deck.buffers[102])
    assert np.array_equal(r.coords, deck.coords) and np.array_equal(r.det, deck.det)


def test_supply_deck_written_from_the_model_numbers_fixed_points_first() -> None:
    text = supply().to_deck(Motion.by(72, TURN))
    lines = text.splitlines()
    assert "ELEM 1 BIN 1 2 9 10" in lines
    assert "FORM 5 ANGB 2 5 1.0" in lines and "FORM 6 ANGB 4 5 -1.0" in lines
    assert "FORM 14 ANGB 8 -1 1.0" in lines
    assert "XMOV 13 0.3" in lines and "PARA 5 -5.17514" in lines
    assert "MOV_RELE 1 6.283185307179586" in lines
    # The names are in the NAMES block, not in comments.
    assert not any(";" in line for line in lines[1:])
    names = lines[lines.index("NAMES") + 1 : lines.index("MOVEMENT")]
    assert "POINT 1 2 A0" in names and "ELEM 1 crank" in names
    assert "ROW 5 kappa" in names and "ROW 12 alpha" in names and "DEP 1 delta" in names


def test_results_by_name() -> None:
    m = supply()
    r = m.run(Motion.by(72, TURN, dt=0.01))
    p = r.positions
    assert r.x("K").shape == (p,) and r.y("K").shape == (p,)
    assert r.value("K").shape == (p, 2) and np.array_equal(r.value("K")[:, 0], r.x("K"))
    assert np.array_equal(r.value("K.y"), r.y("K"))
    assert np.array_equal(r.value(m["K"]), r.position("K"))
    assert r.transfer("K").shape == (p, 2) and r.transfer("K", 2).shape == (p, 2)
    # Velocity and acceleration under a constant input speed: first order times speed, second times speed^2.
    speed = TURN / (72 * 0.01)
    assert close(r.velocity("K"), r.transfer("K") * speed)
    assert close(r.acceleration("delta"), r.output("delta", 2) * speed**2)
    assert close(r.velocity("alpha"), speed) and close(r.acceleration("alpha"), 0.0)
    # A prescribed row holds its value; its own input's first order is 1.
    assert close(r.value("kappa"), -5.17514) and close(r.output("alpha", 1), 1.0)
    # Form parameters with a row are found through it.
    assert np.array_equal(r.value(m["output"].angle), r.output("delta"))
    assert r.time[-1] == pytest.approx(0.72) and r.det.shape == (p,)
    assert r.limits == [] and r.stop_reason() is None and r.warnings == []


def test_unknown_names_and_free_form_parameters_are_refused() -> None:
    m = supply()
    r = m.check()
    assert r.positions == 1
    with pytest.raises(KeyError, match="no point named 'Q' in the mechanism 'supply'"):
        r.x("Q")
    with pytest.raises(KeyError, match="neither prescribed nor an output"):
        r.value(m["coupler"].angle)
    with pytest.raises(TypeError, match="not a point"):
        r.x("delta")
    with pytest.raises(ValueError, match="order"):
        r.value("delta", order=3)


def test_table_and_pandas() -> None:
    r = supply().run(Motion.by(12, TURN))
    t = r.table()
    assert list(t)[:8] == ["time", "det", "alpha", "alpha_dot", "alpha_ddot", "delta", "delta'", "delta''"]
    assert "K.x'" in t and "K.y_ddot" in t and "A0.x" not in t
    assert all(v.shape == (13,) for v in t.values())
    assert "K.x" not in r.table(coordinates=False)
    pd = pytest.importorskip("pandas")
    frame = r.to_pandas()
    assert isinstance(frame, pd.DataFrame) and frame.shape == (13, len(t)) and frame.index[0] == 1


def test_to_pandas_without_pandas_says_how_to_get_it(monkeypatch: pytest.MonkeyPatch) -> None:
    r = supply().check()
    monkeypatch.setitem(sys.modules, "pandas", None)
    with pytest.raises(ImportError, match=r"mechfem\[pandas\]"):
        r.to_pandas()


def test_progress_and_check() -> None:
    calls: list[tuple[int, int]] = []
    m = supply()
    r = m.run(Motion.by(72, TURN), progress=lambda done, total: calls.append((done, total)))
    assert calls[-1] == (73, 73)
    one = m.check(Motion.by(72, TURN))
    assert one.positions == 1 and np.array_equal(one.coords[0], r.coords[0])


def test_variant_and_set_change_values() -> None:
    m = supply()
    v = m.variant(kappa=-5.2, **{"link.length": 6.8})
    assert m["kappa"].value == -5.17514 and v["kappa"].value == -5.2
    assert "PARA 5 -5.2" in v.to_deck().splitlines() and "PARA 6 6.8" in v.to_deck().splitlines()
    v.set("B0", (0.56, -0.91))
    assert v["B0.x"].value == 0.56
    with pytest.raises(ValueError, match="output"):
        v.set("delta", 1.0)


# --- every element type, compared with the example decks ------------------------------------------------------------


def test_rack_and_ternary1_match_the_geared_slider_crank() -> None:
    m = Mechanism("geared")
    rack = m.angle("rack", 0.0, fixed=True)
    A0 = m.fixed("A0", 0.0, 0.0)
    i = m.scalar("i", -0.4)
    B = m.point("B", 4.4, -0.2)
    pinion = m.angle("pinion", 0.0)
    A = m.point("A", 1.0, 0.1)
    m.bar("crank", A0, A, length=1.0, angle=Driven(start=0.0))
    m.bar("rod", A, B, length=3.5)
    m.ternary1("guide", B, rack, A0, angle=Output("rack_angle"), u=Output("u"), v=0.25)
    m.rack1("mesh", B, rack, A0, i, pinion, gear=4.5)
    r = m.run(Motion.by(48, TURN))
    deck = mechfem.run_deck(EXAMPLES / "gears" / "geared_slider_crank.mec")
    assert close(r.x("B"), deck.buffers[2]) and close(r.transfer("B.x"), deck.buffers[3])
    assert close(r.transfer("B.x", 2), deck.buffers[4])
    assert close(r.value(pinion), deck.buffers[5]) and close(r.transfer(pinion), deck.buffers[6])
    assert close(r.output("rack_angle"), 0.0) and close(r.output("u"), -r.x("B"))


def test_gear_pairs_with_a_ratio_match_the_planetary_gr1() -> None:
    m = Mechanism("planetary")
    O = m.fixed("O", 0.0, 0.0)  # noqa: E741
    A = m.point("A", 45.0, 0.0)
    sun, carrier, planet, ring = (m.angle(n) for n in ("sun", "carrier", "planet", "ring"))
    arm = m.ternary1("arm", O, carrier, A, u=45.0, v=0.0)
    m.half_beam("sun_wheel", O, sun, angle=Driven(0.0, "sun_input"))
    m.half_beam("planet_wheel", A, planet, angle=Output("planet_angle"))
    m.half_beam("ring_wheel", O, ring, angle=Output("ring_angle"))
    m.gear_pair("mesh1", sun, carrier, planet, ratio=-2.0, gear=0.0)
    m.gear_pair("mesh2", planet, carrier, ring, ratio=0.25, gear=0.0)
    m.drive("carrier_input", arm.angle, start=0.0)
    motion = Motion(36, {"sun_input": By(TURN), "carrier_input": By(-TURN / 4)}, dt=0.01)
    r = m.run(motion)
    deck = mechfem.run_deck(EXAMPLES / "gears" / "planetary_gr1.mec")
    assert close(r.output("ring_angle"), deck.buffers[3])
    assert close(r.output("ring_angle", 1, "sun_input"), deck.buffers[4])
    assert close(r.output("ring_angle", 1, wrt="carrier_input"), deck.buffers[5])
    assert close(r.output("ring_angle", 2, "sun_input", "carrier_input"), deck.buffers[6])
    assert close(r.velocity("ring_angle"), deck.buffers[7]) and close(r.output("planet_angle"), deck.buffers[10])
    with pytest.raises(ValueError, match="2 inputs"):
        r.output("ring_angle", 1)


def test_gear_pairs_with_radii_match_the_planetary_gr2() -> None:
    m = Mechanism("planetary2")
    O = m.fixed("O", 0.0, 0.0)  # noqa: E741
    A = m.point("A", 40.0, 5.0)
    Rs, Rp, Rr = m.scalar("Rs", 30.0), m.scalar("Rp", 15.0), m.scalar("Rr", -60.0)
    sun, carrier, planet = m.angle("sun", 0.1), m.angle("carrier", 0.1), m.angle("planet", 0.1)
    ring = m.angle("ring", 0.0, fixed=True)
    m.ternary1("arm", O, carrier, A, angle=Output("carrier_angle"), u=45.0, v=0.0)
    m.half_beam("sun_wheel", O, sun, angle=Driven(0.0))
    m.half_beam("planet_wheel", A, planet, angle=Output("planet_angle"))
    m.half_beam("ring_wheel", O, ring)
    m.gear_pair("mesh1", sun, carrier, planet, radii=(Rs, Rp), gear=0.0)
    m.gear_pair("mesh2", planet, carrier, ring, radii=(Rp, Rr), gear=0.0)
    r = m.run(Motion.by(36, 3 * TURN))
    deck = mechfem.run_deck(EXAMPLES / "gears" / "planetary_gr2.mec")
    assert close(r.output("carrier_angle"), deck.buffers[2]) and close(r.output("carrier_angle", 1), 1 / 3)
    assert close(r.output("planet_angle"), deck.buffers[5]) and close(r.x("A"), deck.buffers[7])


def test_belt_matches_the_crossed_belt() -> None:
    m = Mechanism("belt")
    P, Q = m.fixed("P", 0.0, 0.0), m.fixed("Q", 200.0, 0.0)
    a, c = m.angle("a"), m.angle("c")
    wheel = m.half_beam("wheel_a", P, a)
    m.belt("belt", P, a, Q, c, 50.0, -25.0, belt=Keep())
    m.half_beam("wheel_c", Q, c, angle=Output("driven"))
    m.drive("alpha", wheel.angle)
    r = m.run(Motion.by(24, TURN))
    deck = mechfem.run_deck(EXAMPLES / "gears" / "crossed_belt.mec")
    assert np.array_equal(r.output("driven"), deck.buffers[2])
    assert close(r.output("driven", 1), -2.0) and close(r.output("driven", 2), 0.0)


@pytest.mark.filterwarnings("ignore::mechfem.IncompleteRunWarning")  # the motion stops on purpose
def test_single_coordinate_drives_a_slider_to_its_dead_centre() -> None:
    m = Mechanism("slider")
    A0 = m.fixed("A0", 0.0, 0.0)
    A = m.point("A", 0.5, 0.866)
    B = m.point("B", 3.372, 0.0, fixed="y")
    m.bar("crank", A0, A, length=1.0, angle=Output("theta"))
    m.bar("rod", A, B, length=3.0)
    m.single_coordinate("slider", B.x, value=Driven(3.3722813232690143, "xB"))
    r = m.run(Motion.by(20, 1.0))
    deck = mechfem.run_deck(EXAMPLES / "limits" / "slider_dead_centre.mec")
    assert r.positions == deck.positions < 21 and not r.complete
    assert close(r.output("theta"), deck.buffers[2]) and close(r.input("xB"), deck.buffers[1])
    reason = r.stop_reason()
    assert reason is not None and "the input 'xB' reached its limit position at xB = " in reason


def test_rack2_pinion_rolls_on_a_fixed_rack() -> None:
    m = Mechanism("rack2")
    P, Q = m.fixed("P", 0.0, 0.0), m.fixed("Q", 1.0, 0.0)
    R = m.point("R", 0.2, 0.5, fixed="y")
    pinion = m.angle("pinion", 0.0)
    m.rack2("mesh", P, Q, R, -0.5, pinion, gear=Keep())
    m.single_coordinate("slide", R.x, value=Driven(name="x"))
    r = m.run(Motion.to(10, 2.2))
    assert "ELEM 1 RK2" in m.to_deck() and r.complete
    assert close(r.x("R")[-1], 2.2) and close(r.transfer(pinion), -2.0) and close(r.transfer(pinion, 2), 0.0)


def test_combined_rows_with_factors_make_a_gear_relation() -> None:
    m = Mechanism("relation")
    P, Q = m.fixed("O", 0.0, 0.0), m.fixed("Q", 1.0, 0.0)
    h1 = m.half_beam("h1", P, 0.0)
    h2 = m.half_beam("h2", Q, 0.0, angle=Output("beta2"))
    relation = m.prescribe("gear", 2 * h1.angle + h2.angle, 0.0)
    assert relation.formula() == "2*h1.angle + h2.angle"
    m.drive("beta1", h1.angle - 0.5 * h2.angle, start=0.0)
    assert "FORM 3 ANGV 1 2 1.0" in m.to_deck() and "FORM 4 ANGV 2 2 -0.5" in m.to_deck()
    r = m.run(Motion.by(4, 1.0))
    # beta2 = -2 beta1 and input = beta1 - beta2 / 2 = 2 beta1: d beta2 / d input = -1.
    assert close(r.output("beta2", 1), -1.0) and close(r.output("beta2")[-1], -1.0)
    assert m["h1.beta"] in m.coordinates and not m["h1.beta"].fixed


def test_generic_element_by_deck_type() -> None:
    m = Mechanism("generic")
    A0, A = m.fixed("A0", 0.0, 0.0), m.point("A", 1.0, 0.0)
    e = m.element("crank", "bin", [A0, A], LENL=1.0, angle=Driven())
    assert e.type == "BIN" and e.length.form == "LENL" and e.angle.label == "crank.angle"
    r = m.run(Motion.by(4, TURN))
    assert close(r.x("A")[-1], 1.0)
    with pytest.raises(ValueError, match="takes 2 slots"):
        m.element("bad", "BIN", [A0])
    with pytest.raises(TypeError, match="no form parameter"):
        m.element("bad", "BIN", [A0, A], gear=1.0)


# --- motions ---------------------------------------------------------------------------------------------------------


def test_two_inputs_equidistant_match_the_manipulator() -> None:
    m = Mechanism("manipulator")
    A0, B0 = m.fixed("A0", 0.0, 0.0), m.fixed("B0", 1.2, 0.0)
    M = m.point("M", 0.7, 0.7)
    m.bar("act1", A0, M, length=Driven(1.0, "l1"))
    m.bar("act2", B0, M, length=Driven(0.9, "l2"))
    r = m.run(Motion(50, {"l1": By(0.4), "l2": To(0.6)}, dt=0.02))
    deck = mechfem.run_deck(EXAMPLES / "manipulator" / "manipulator.mec")
    assert np.array_equal(r.x("M"), deck.buffers[4]) and np.array_equal(r.transfer("M.y", 1, "l2"), deck.buffers[14])
    assert np.array_equal(r.transfer("M.x", 2, "l1", "l2"), deck.buffers[23])
    assert np.array_equal(r.acceleration("M")[:, 1], deck.buffers[34]) and np.array_equal(r.time, deck.buffers[1])


def test_table_motion_from_arrays_matches_the_slider_crank() -> None:
    rows = np.loadtxt(EXAMPLES / "slider_crank" / "crank.dat", comments="#")
    m = Mechanism("slider_crank")
    A0, G = m.fixed("A0", 0.0, 0.0), m.fixed("G", -2.0, 0.3)
    A, B = m.point("A", 1.0, 0.2), m.point("B", 3.9, 0.3)
    m.bar("crank", A0, A, length=1.0, angle=Driven())
    m.bar("rod", A, B, length=3.0, angle=Output("rod_angle"))
    m.bar("guide", G, B, angle=0.0)
    motion = Motion.table(rows[:, 1], rows[:, 2], rows[:, 3], time=rows[:, 0], dt=0.005)
    assert motion.steps == 100 and isinstance(motion.inputs[None], Table)
    r = m.run(motion)
    deck = mechfem.run_deck(EXAMPLES / "slider_crank" / "slider_crank.mec")
    assert close(r.time, deck.buffers[1]) and close(r.x("B"), deck.buffers[3])
    assert close(r.velocity("B")[:, 0], deck.buffers[4]) and close(r.acceleration("B.x"), deck.buffers[5])
    assert close(r.acceleration("rod_angle"), deck.buffers[11])


def test_free_motion_from_the_api_matches_the_deck() -> None:
    m = Mechanism.from_deck(EXAMPLES / "limits" / "nongrashof.mec")
    r = m.run(Motion.free(901, 0.02))
    deck = mechfem.run_deck(EXAMPLES / "limits" / "nongrashof.mec")
    assert np.array_equal(r.input(), deck.buffers[1], equal_nan=True) and len(r.limits) == len(deck.report.limits)


def test_motions_that_do_not_fit_are_refused() -> None:
    m = supply()
    with pytest.raises(ValueError, match="no motion for the input"):
        m.run(Motion(4, {}))
    with pytest.raises(KeyError, match="no input named 'beta'"):
        m.run(Motion.by(4, {"beta": 1.0}))
    with pytest.raises(ValueError, match="at least one step"):
        Motion.by(0, 1.0)
    with pytest.raises(ValueError, match="11 values"):
        Motion(4, {None: Table(np.zeros(11))})


# --- mistakes -------------------------------------------------------------------------------------------------------


def test_names_must_be_unique_and_objects_of_this_mechanism() -> None:
    m = Mechanism("x")
    A0 = m.fixed("A0", 0.0, 0.0)
    with pytest.raises(ValueError, match="already used"):
        m.point("A0", 1.0, 1.0)
    with pytest.raises(ValueError, match="already used"):
        m.angle("A0.x")
    other = Mechanism("y").point("A", 1.0, 0.0)
    with pytest.raises(ValueError, match="another mechanism"):
        m.bar("b", A0, other)
    with pytest.raises(TypeError, match="must be a point"):
        m.bar("b", A0, A0.x)  # type: ignore[arg-type]
    with pytest.raises(TypeError, match="Driven"):
        m.bar("b", A0, m.point("A", 1.0, 0.0), length="long")  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="finite"):
        m.point("C", math.nan, 0.0)
    with pytest.raises(ValueError, match="name"):
        m.point("two\nlines", 0.0, 0.0)


def test_deck_mistakes_name_the_model_part() -> None:
    m = supply()
    m.point("Z", 1.0, 1.0)
    with pytest.raises(mechfem.DeckError) as info:
        m.run()
    e = info.value
    assert e.name == "Z.x" and e.deck is None  # type: ignore[attr-defined]
    assert "the point 'Z' of the mechanism 'supply' is used by no element" in str(e)
    assert isinstance(e, mechfem.MechfemError)


def test_too_many_rows_name_the_row() -> None:
    m = supply()
    m.bar("frame", m["A0"], m["B0"], length=Keep())
    with pytest.raises(mechfem.DeckError, match="for 12 moving co-ordinates .*: 1 too many") as info:
        m.run()
    assert info.value.name == "alpha"  # type: ignore[attr-defined]


def test_singular_position_one_names_rows_and_coordinates() -> None:
    m = Mechanism("superfluous")
    A0, B0 = m.fixed("A0", 0.0, 0.0), m.fixed("B0", 4.0, 0.0)
    A, B = m.point("A", 0.5, 0.866), m.point("B", 3.88, 3.0)
    m.bar("crank", A0, A, length=Keep())
    m.bar("coupler", A, B, length=Keep())
    m.bar("rocker", B0, B, angle=Driven())
    m.bar("frame", A0, B0, length=Keep())
    with pytest.raises(mechfem.LimitPositionError) as info:
        m.run()
    e = info.value
    assert e.row_names == ["frame.length"] and set(e.coord_names) == {"A.x", "A.y", "B.x", "B.y"}  # type: ignore[attr-defined]
    assert "the prescribed value 'frame.length' is superfluous" in str(e)


def test_position_one_out_of_reach_is_a_convergence_error() -> None:
    m = supply()
    m.set("rocker.length", 5.0)
    with pytest.raises(mechfem.ConvergenceError):
        m.run()


def test_assembly_errors_get_the_element_name() -> None:
    from mechfem.deck import deckio

    deck = deckio.write(supply())
    err = mechfem.AssemblyError("element 6 (TR2): the points P and Q coincide")
    err.element = 6  # type: ignore[attr-defined]
    # The fields the binding sets: the core's reason in its words and as structure.
    err.detail = "the points P and Q coincide"  # type: ignore[attr-defined]
    err.detail_fields = _core.ElementFault(6, "coincident_points")  # type: ignore[attr-defined]
    new = deckio.translate(err, deck, "supply")
    assert isinstance(new, mechfem.AssemblyError) and new.element_name == "lever"  # type: ignore[attr-defined]
    assert "the ternary-2 'lever' (G0, H, G) cannot be evaluated there: its points G0 and H coincide" in str(new)


# --- pictures --------------------------------------------------------------------------------------------------------


def test_mechanism_and_result_show_as_png() -> None:
    m = supply()
    png = m._repr_png_()
    assert png is not None and png.startswith(b"\x89PNG")
    r = m.run(Motion.by(24, TURN))
    png = r._repr_png_()
    assert png is not None and png.startswith(b"\x89PNG")
    fig = r.plot("delta", points=["K"])
    assert [ax.get_title() for ax in fig.axes][1] == "delta against alpha"


def test_deck_pictures_and_animation_from_the_api(tmp_path: Path) -> None:
    m = Mechanism.from_deck(SUPPLY)
    r = m.run(Motion.by(24, TURN))
    fig = r.plot(picture=1)
    assert len(fig.axes) >= 1
    files = r.animate(tmp_path / "film.gif", points=["K"])
    assert files[0] == tmp_path / "film.gif" and files[0].stat().st_size > 0


# --- the documents ---------------------------------------------------------------------------------------------------


def python_code(doc: Path) -> str:
    """The python blocks of a markdown document, each at its own lines (tracebacks point into the document)."""
    lines = doc.read_text().splitlines()
    out = [""] * len(lines)
    inside = False
    for k, line in enumerate(lines):
        if line.strip() == "```python":
            inside = True
        elif inside and line.strip() == "```":
            inside = False
        elif inside:
            out[k] = line
    return "\n".join(out)


@pytest.mark.parametrize("doc", ["tutorial.md", "design-study.md", "python-api.md", "optimisation.md"])
def test_python_code_of_the_documents_runs(doc: str, monkeypatch: pytest.MonkeyPatch, tmp_path: Path) -> None:
    code = python_code(ROOT / "docs" / doc)
    assert code.strip(), f"docs/{doc} has no python code"
    if "to_pandas" in code:
        pytest.importorskip("pandas")
    monkeypatch.chdir(ROOT)
    monkeypatch.setenv("MECHFEM_DOCS_OUT", str(tmp_path))
    namespace: dict[str, object] = {"__name__": f"docs_{doc.replace('-', '_').replace('.', '_')}"}
    exec(compile(code, f"docs/{doc}", "exec"), namespace)


def test_max_iter_is_bounded_as_in_a_deck() -> None:
    # The deck reader accepts MAXITER 1..1000; a motion that could not be written as a deck is refused at once.
    assert Motion.by(10, 1.0, max_iter=1000).max_iter == 1000
    for bad in (0, 1001):
        with pytest.raises(ValueError, match="max_iter must be from 1 to 1000"):
            Motion.by(10, 1.0, max_iter=bad)
