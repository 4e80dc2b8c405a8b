"""A :class:`~mechfem.Mechanism` carries its units (docs/python-api.md, "Units"): numbers given to it are read in
them, its deck says them on the UNITS line, and a value given in a unit of its own is converted to them."""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest

from mechfem import Driven, Mechanism, Motion, Output
from mechfem.errors import UnitWarning
from mechfem.model.mechanism import Table
from mechfem.model.units import Units, scale


def fourbar(**units: str) -> Mechanism:
    m = Mechanism("fourbar", **units)
    A0, B0 = m.fixed("A0", 0.0, 0.0), m.fixed("B0", 4.0, 0.0)
    A, B = m.point("A", 1.0, 0.0), m.point("B", 3.5, 2.5)
    m.bar("crank", A0, A, length=1.0, angle=Driven(name="phi"))
    m.bar("coupler", A, B, length=3.5)
    m.bar("rocker", B0, B, length=3.0, angle=Output("psi"))
    return m


def lines(deck: str, keyword: str) -> list[str]:
    return [line.split(";")[0].strip() for line in deck.splitlines() if line.startswith(keyword)]


def test_a_model_without_units_writes_the_deck_it_always_wrote() -> None:
    m = fourbar()
    assert m.units == Units() and m.units.default
    assert "UNITS" not in m.to_deck(Motion.by(12, 2 * math.pi))


def test_units_are_set_one_kind_at_a_time_or_all_at_once() -> None:
    assert fourbar(angle="deg").units == Units(angle="deg")
    m = Mechanism("m", units={"length": "mm", "force": "N"}, angle="deg")
    assert m.units == Units(length="mm", angle="deg", force="N")
    assert m.units.deck_line() == "UNITS LENGTH mm ANGLE deg FORCE N"
    with pytest.raises(ValueError, match="the unit of angle must be one of 'rad', 'deg', got 'grad'"):
        Mechanism("m", angle="grad")
    with pytest.raises(ValueError, match="no kind of unit 'speed'"):
        Mechanism("m", units={"speed": "m/s"})


def test_given_values_are_read_in_the_models_units() -> None:
    m = fourbar(angle="deg", length="mm")
    m.set("phi", 90)
    deck = m.to_deck(Motion.by(72, 360))
    assert lines(deck, "UNITS") == ["UNITS LENGTH mm ANGLE deg"]
    assert "PARA 4 90.0" in lines(deck, "PARA")
    assert lines(deck, "MOV_RELE") == ["MOV_RELE 1 360.0"]


def test_an_angle_given_in_a_unit_of_its_own_is_converted_to_the_models() -> None:
    m = fourbar(angle="deg")
    deck = m.to_deck(Motion.by(72, 2 * math.pi, unit="rad"))
    assert lines(deck, "MOV_RELE") == [f"MOV_RELE 1 {math.degrees(2 * math.pi)!r}"]
    # And the other way: degrees for a model in radians, as math.radians gives them.
    assert lines(fourbar().to_deck(Motion.by(72, 360, unit="deg")), "MOV_RELE") == [f"MOV_RELE 1 {math.radians(360)!r}"]
    deg = Mechanism("m", angle="deg")
    a0, a = deg.fixed("A0", 0, 0), deg.point("A", 1, 0)
    deg.bar("crank", a0, a, length=1.0, angle=Driven(start=math.pi / 2, unit="rad", name="phi"))
    assert deg["phi"].value == pytest.approx(90.0, rel=1e-15)
    b0, b = deg.fixed("B0", 4, 0), deg.point("B", 3.5, 2.5)
    deg.drive("theta", deg.bar("rocker", b0, b).angle, start=math.pi, unit="rad")
    assert deg["theta"].value == pytest.approx(180.0, rel=1e-15)


def test_a_table_in_radians_is_written_in_degrees_for_a_model_in_degrees() -> None:
    m = fourbar(angle="deg")
    values = np.linspace(0.0, math.pi, 5)
    deck_tables: dict[str, str] = {}
    from mechfem.deck.deckio import write

    deck = write(m, Motion(4, {"phi": Table(values, unit="rad")}))
    deck_tables = deck.tables
    rows = [line.split() for line in next(iter(deck_tables.values())).splitlines() if not line.startswith("#")]
    assert [float(r[1]) for r in rows] == pytest.approx(np.degrees(values), rel=1e-15)


def test_a_large_angle_warns_only_in_a_model_in_radians() -> None:
    with pytest.warns(UnitWarning):
        fourbar().to_deck(Motion.by(72, 360))
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        fourbar(angle="deg").to_deck(Motion.by(72, 360))


def test_scale_converts_within_one_kind_only() -> None:
    assert scale("mm", "m") == 1e-3 and scale("m", "mm") == 1e3 and scale("in", "mm") == pytest.approx(25.4)
    assert scale("rad", "deg") == 180.0 / math.pi and scale(None, "mm") == 1.0
    with pytest.raises(ValueError, match="not units of one kind"):
        scale("mm", "deg")


def test_the_names_block_names_points_elements_rows_and_outputs_by_deck_number() -> None:
    from mechfem.deck.deckio import number_model
    from mechfem.deck.naming import names_block

    m = fourbar()
    m.scalar("ratio", 2.0)
    m.point("my point", 1.0, 1.0)  # a name the deck language cannot hold stays out
    block = [text for text, _ in names_block(m, number_model(m))]
    # Fixed co-ordinates first, in the order given (A0, B0, ratio), then the moving ones (A, B, my point).
    assert block == [
        "NAMES",
        "POINT 1 2 A0",
        "POINT 3 4 B0",
        "POINT 6 7 A",
        "POINT 8 9 B",
        "COORD 5 ratio",
        "ELEM 1 crank",
        "ELEM 2 coupler",
        "ELEM 3 rocker",
        "ROW 4 phi",
        "DEP 1 psi",
    ]


@pytest.mark.parametrize("units", [{}, {"angle": "deg"}, {"length": "mm", "angle": "deg", "mass": "kg", "force": "N"}])
def test_a_model_read_back_from_its_deck_keeps_every_name_and_unit(units: dict[str, str]) -> None:
    m = fourbar(**units)
    motion = Motion.by(4, 360 if units else 2 * math.pi)
    text = m.to_deck(motion)
    back = Mechanism.from_deck_text(text, "fourbar")
    assert back.units == m.units
    assert set(back.names()) == set(m.names())
    assert back.to_deck(motion) == text


def test_a_model_in_degrees_runs_as_its_twin_in_radians() -> None:
    deg, rad = fourbar(angle="deg"), fourbar()
    a, b = deg.run(Motion.by(12, 360)), rad.run(Motion.by(12, 2 * math.pi))
    assert np.allclose(a.input("phi"), np.degrees(b.input("phi")), rtol=1e-12, atol=1e-12)
    assert np.allclose(a.value("psi"), np.degrees(b.value("psi")), rtol=1e-12)
    assert np.allclose(a.value("psi", 1, "phi"), b.value("psi", 1, "phi"), rtol=1e-9)  # deg/deg = rad/rad
    assert np.allclose(a.value("B"), b.value("B"), rtol=1e-12)  # lengths as they are
    assert np.allclose(a.value("psi", unit="rad"), b.value("psi"), rtol=1e-12)
