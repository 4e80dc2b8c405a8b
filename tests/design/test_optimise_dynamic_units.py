"""A dynamic optimisation from Python in the model's units: the balancing example (a slider-crank at 1500 rpm,
examples/balancing/slider_crank_balance.mec) stated in mm, g, ms and degrees finds the optimum the deck finds in
SI, converted: the crank's centre of mass in mm, the piston's mass in g, a crank length in mm and a guide angle in
degrees; the RMS shaking force in N and the RMS drive torque in N·mm."""

from __future__ import annotations

import math
import re
from pathlib import Path

import pytest

import mechfem
from conftest import ROOT
from mechfem.design import optimise_deck
from mechfem.design.dynamic_optimise import Drive, ShakingForce

EXAMPLE = ROOT / "examples" / "balancing" / "slider_crank_balance.mec"
Range = tuple[float, float]

#: The example's lines in mm, g, ms and degrees: lengths times 1000, masses times 1000, moments of inertia in
#: g·mm² (times 1e9), the time step in ms, the turn in degrees, gravity in mm/ms².
IN_MM = [
    ("UNITS LENGTH m ANGLE rad MASS kg FORCE N TIME s", "UNITS LENGTH mm ANGLE deg MASS g FORCE N TIME ms"),
    ("     3 -1.0 ", "     3 -1000.0 "),
    ("XMOV 5 0.1 ", "XMOV 5 100.0 "),
    ("     7 0.45 ", "     7 450.0 "),
    ("PARA 1 0.1\n", "PARA 1 100.0\n"),
    ("     2 0.35\n", "     2 350.0\n"),
    ("MASS  1 2.0 0.03 0.0 0.004 ", "MASS  1 2000.0 30.0 0.0 4000000.0 "),
    ("      2 1.2 0.1  0.0 0.03 ", "      2 1200.0 100.0  0.0 30000000.0 "),
    ("PMASS 7 8 1.5 ", "PMASS 7 8 1500.0 "),
    ("GRAVITY 0 -9.81", "GRAVITY 0 -9.81e-3"),
    ("TSTEPE 71 5.5555555555555556E-4", "TSTEPE 71 5.5555555555555556E-1"),
    ("MOV_RELE 1 6.19591884457987", f"MOV_RELE 1 {math.degrees(6.19591884457987)!r}"),
]


def _mechanisms(tmp_path: Path) -> tuple[mechfem.Mechanism, mechfem.Mechanism]:
    """The example's mechanism in SI and in mm, g, ms and degrees (its OPTIMISE block left out)."""
    si = re.sub(r"OPTIMISE\n.*?\n\n", "", EXAMPLE.read_text(), flags=re.S)
    mm = si
    for old, new in IN_MM:
        assert old in mm, old
        mm = mm.replace(old, new, 1)
    out = []
    for name, text in (("si.mec", si), ("mm.mec", mm)):
        lines = text.splitlines(keepends=True)
        (tmp_path / name).write_text("".join(s for s in lines if not re.match(r"\s*(BEGINPIC|ENDPIC|PLOT)", s)))
        out.append(mechfem.Mechanism.from_deck(tmp_path / name))
    return out[0], out[1]


def test_balancing_in_mm_and_grams_finds_the_decks_optimum_converted(tmp_path: Path) -> None:
    si, mm = _mechanisms(tmp_path)
    assert mm.units.mass == "g" and mm.units.length == "mm"
    deck = optimise_deck.optimise(EXAMPLE, optimise_deck.describe(EXAMPLE).optimise)
    found = mechfem.optimize(
        mm,
        {"crank.mass_u": (-200.0, 200.0), "crank.mass_v": (-200.0, 200.0)},
        minimize=("rms", ShakingForce()),
        rtol=1e-13,
        atol=0.0,
    )
    # The shaking force is in N in both; the centre of mass in mm, the deck's in m.
    assert found.objective == pytest.approx(deck.objective, rel=1e-9)
    assert found.start_objective == pytest.approx(deck.start_objective, rel=1e-12)
    assert found.values["crank.mass_u"] == pytest.approx(1000.0 * deck.x[0], rel=1e-7)
    assert found.start["crank.mass_u"] == 30.0
    assert found.mechanism is not None
    body = found.mechanism.loads.items[0] if found.mechanism.loads else None
    assert body is not None and getattr(body, "u", None) == found.values["crank.mass_u"]


@pytest.mark.parametrize(
    ("vary_si", "vary_mm", "factors"),
    [
        # The piston's mass (kg, g) and the rod's moment of inertia (kg·m², g·mm²) against the RMS drive torque.
        (
            {"B.mass": (0.5, 3.0), "rod.mass_J": (0.01, 0.05)},
            {"B.mass": (500.0, 3000.0), "rod.mass_J": (1e7, 5e7)},
            {"B.mass": 1000.0, "rod.mass_J": 1e9},
        ),
        # The crank's length (m, mm) and the guide's direction (rad, deg), dimensions with the masses as they are.
        (
            {"crank_length": (0.05, 0.2), "guide_angle": (-0.3, 0.3)},
            {"crank_length": (50.0, 200.0), "guide_angle": (math.degrees(-0.3), math.degrees(0.3))},
            {"crank_length": 1000.0, "guide_angle": math.degrees(1.0)},
        ),
    ],
)
def test_the_rms_drive_torque_in_newton_millimetres_is_the_si_one_converted(
    tmp_path: Path, vary_si: dict[str, Range], vary_mm: dict[str, Range], factors: dict[str, float]
) -> None:
    si, mm = _mechanisms(tmp_path)
    a = mechfem.optimize(si, vary_si, minimize=("rms", Drive("phi")), rtol=1e-12, atol=0.0)
    b = mechfem.optimize(mm, vary_mm, minimize=("rms", Drive("phi")), rtol=1e-12, atol=0.0)
    # The torque in N·mm is a thousand times the one in N·m, at the start and at the optimum.
    assert b.start_objective == pytest.approx(1000.0 * a.start_objective, rel=1e-9)
    assert b.objective == pytest.approx(1000.0 * a.objective, rel=1e-6)
    for name, f in factors.items():
        assert b.values[name] == pytest.approx(f * a.values[name], rel=1e-5, abs=1e-6 * f)
