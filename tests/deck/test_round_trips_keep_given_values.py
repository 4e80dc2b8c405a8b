"""A model in millimetres and degrees written as a deck and read back is the same model, number for number: the
values read are those written (not converted to the core's units and back, which misses by an ulp), so that any
number of round trips leaves the deck text as it was."""

from __future__ import annotations

import random
import re
from pathlib import Path

import pytest

from mechfem import Driven, Mechanism, Motion, Output


def fourbar(v: list[float]) -> Mechanism:
    m = Mechanism("fourbar", units={"length": "mm"}, angle="deg")
    A0, B0 = m.fixed("A0", 0.0, 0.0), m.fixed("B0", v[0], v[1])
    A, B = m.point("A", v[2], v[3]), m.point("B", v[4], v[5])
    m.bar("crank", A0, A, length=v[6], angle=Driven(start=v[7], name="phi"))
    m.bar("coupler", A, B, length=v[8])
    m.bar("rocker", B0, B, length=v[9], angle=Output("psi"))
    return m


def trips(m: Mechanism, path: Path, times: int = 3) -> list[str]:
    """The deck texts of ``times`` round trips through ``path`` (the first is ``m``'s own)."""
    texts = [m.to_deck(Motion.by(12, 360))]
    for _ in range(times):
        path.write_text(texts[-1])
        texts.append(Mechanism.from_deck(path).to_deck(Motion.by(12, 360)))
    return texts


@pytest.mark.parametrize("seed", range(6))
def test_a_millimetre_degree_model_survives_round_trips_exactly(seed: int, tmp_path: Path) -> None:
    rng = random.Random(seed)
    # Three decimals, as a designer gives them; some of them miss by an ulp when taken to metres and back.
    v = [round(rng.uniform(-100.0, 100.0), 3) for _ in range(10)]
    v[6], v[8], v[9] = (abs(x) + 1.0 for x in (v[6], v[8], v[9]))  # lengths
    texts = trips(fourbar(v), tmp_path / "fourbar.mec")
    assert all(t == texts[0] for t in texts[1:])
    back = Mechanism.from_deck(tmp_path / "fourbar.mec")
    given = {c.name: c.value for c in fourbar(v).coordinates}
    assert {c.name: c.value for c in back.coordinates} == given


def test_the_values_read_are_those_the_deck_writes(tmp_path: Path) -> None:
    # 26.252 mm is 0.026252 m, and 0.026252 * 1000 is 26.252000000000002: read back, it is 26.252 again.
    assert 0.026252 * 1000 != 26.252
    m = fourbar([40.0, 0.0, 10.0, 0.0, 26.252, 30.0, 10.0, 54.926, 35.0, 30.0])
    path = tmp_path / "fourbar.mec"
    path.write_text(m.to_deck())
    text = Mechanism.from_deck(path).to_deck()
    assert re.search(r"^XMOV 7 26\.252$", text, re.M) and re.search(r"^PARA 4 54\.926$", text, re.M)


def test_masses_in_millimetres_survive_round_trips_exactly(tmp_path: Path) -> None:
    v = [40.0, 0.0, 10.0, 0.0, 26.252, 30.0, 10.0, 54.926, 35.0, 30.0]
    m = Mechanism("fourbar", units={"length": "mm", "mass": "kg", "force": "N"}, angle="deg")
    A0, B0 = m.fixed("A0", 0.0, 0.0), m.fixed("B0", v[0], v[1])
    A, B = m.point("A", v[2], v[3]), m.point("B", v[4], v[5])
    m.bar("crank", A0, A, length=v[6], angle=Driven(start=v[7], name="phi"))
    m.bar("coupler", A, B, length=v[8])
    m.bar("rocker", B0, B, length=v[9], angle=Output("psi"))
    # kg·mm² to kg·m² and back, mm to m and back.
    m.mass("coupler", 0.237, u=12.345, v=-3.217, J=123.457)
    m.mass("rocker", 0.411, u=15.003, J=987.654)
    texts = trips(m, tmp_path / "fourbar.mec")
    assert "DYN ANA" in texts[0] and all(t == texts[0] for t in texts[1:])
    for number in ("12.345", "-3.217", "123.457", "15.003", "987.654", "26.252", "54.926"):
        assert re.search(rf"(^|\s){re.escape(number)}(\s|$)", texts[-1], re.M), number
