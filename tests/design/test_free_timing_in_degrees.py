"""Free timing in a model whose angles are in degrees: the ranges and the order of the crank angles are in degrees
too (a varied angle without a range spans half a turn either side, 180 degrees, and an ordered advance at most a
turn, 360 degrees), so the same problem stated in degrees and in radians finds the same four-bar and the same
timing, the one in degrees 180/pi times the other."""

from __future__ import annotations

import math
import warnings
from pathlib import Path

import numpy as np
import pytest

import mechfem
from mechfem.design import optimise_deck
from mechfem.design.optimise import TargetAt

THETAS = (40.0, 75.0, 110.0, 145.0)
"""The crank angles (degrees) at which the known four-bar's coupler point gives the targets."""


def four_bar(unit: str, crank: float = 10.0) -> mechfem.Mechanism:
    """A crank-rocker (frame 40 along x, crank ``crank``, coupler 30, rocker 35, P at u 10, v 15) at its first
    crank angle, B to the left of A -> B0; angles in ``unit``."""
    theta = math.radians(THETAS[0])
    ax, ay = crank * math.cos(theta), crank * math.sin(theta)
    dx, dy = 40.0 - ax, -ay
    d = math.hypot(dx, dy)
    along = (30.0**2 - 35.0**2 + d * d) / (2 * d)
    h = math.sqrt(30.0**2 - along * along)
    bx, by = ax + (along * dx - h * dy) / d, ay + (along * dy + h * dx) / d
    ex, ey = (bx - ax) / 30.0, (by - ay) / 30.0
    m = mechfem.Mechanism("timing", angle=unit)
    a0, b0 = m.fixed("A0", 0.0, 0.0), m.fixed("B0", 40.0, 0.0)
    pa, pb = m.point("A", ax, ay), m.point("B", bx, by)
    p = m.point("P", ax + 10.0 * ex - 15.0 * ey, ay + 10.0 * ey + 15.0 * ex)
    start = THETAS[0] if unit == "deg" else theta
    m.bar("crank", a0, pa, length=crank, angle=mechfem.Driven(start, name="theta"))
    m.ternary2("coupler", pa, pb, p, length=30.0, u=10.0, v=15.0)
    m.bar("rocker", b0, pb, length=35.0)
    span = THETAS[-1] - THETAS[0]
    m.motion = mechfem.Motion.by(len(THETAS) - 1, span if unit == "deg" else math.radians(span))
    return m


def points() -> np.ndarray:
    run = four_bar("deg").run()
    return np.column_stack([run.value("P.x"), run.value("P.y")])


def solve(unit: str) -> mechfem.Optimum:
    """The known points from a crank of 11 and crank angles 4 degrees off, crank and timing free and in order;
    the first point's crank angle also asked for by a TargetAt of the angle."""
    pts = points()
    scale = 1.0 if unit == "deg" else math.pi / 180.0
    starts = [scale * (t + 4.0 * (-1) ** k) for k, t in enumerate(THETAS)]
    targets = [
        mechfem.Target("P.x", pts[:, 0]),
        mechfem.Target("P.y", pts[:, 1]),
        TargetAt("theta", 0, scale * THETAS[0]),
    ]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return mechfem.optimize(
            four_bar(unit, crank=11.0),
            {"crank.length": (5.0, 15.0)},
            targets=targets,
            timing=mechfem.FreeTiming("theta", starts, ordered=True),
            rtol=1e-14,
            atol=1e-24,
        )


@pytest.mark.parametrize("unit", ["deg", "rad"])
def test_free_ordered_timing_finds_the_crank_angles_in_the_models_unit(unit: str) -> None:
    opt = solve(unit)
    scale = 1.0 if unit == "deg" else math.pi / 180.0
    assert opt.objective < 1e-16
    assert opt.values["crank.length"] == pytest.approx(10.0, abs=1e-7)
    assert opt.timing is not None
    assert np.asarray(opt.timing) == pytest.approx(scale * np.array(THETAS), abs=1e-6 * scale)


def test_a_varied_angle_without_a_range_spans_half_a_turn_either_side_in_degrees() -> None:
    from mechfem.design.optimise import _span

    assert _span(four_bar("deg"), "theta", None) == pytest.approx((THETAS[0] - 180.0, THETAS[0] + 180.0))
    assert _span(four_bar("rad"), "theta", None) == pytest.approx(
        (math.radians(THETAS[0]) - math.pi, math.radians(THETAS[0]) + math.pi)
    )


def deck(tmp_path: Path, unit: str) -> Path:
    """The problem above as a KIN OPT deck in ``unit`` (FREETIME 6 ORDERED; the motion's values, the known crank
    angles, are the start values; the crank starts at 11)."""
    pts = points()
    folder = tmp_path / unit
    folder.mkdir()
    for k, c in enumerate("xy"):
        (folder / f"p{c}.dat").write_text("".join(f"{float(v)!r}\n" for v in pts[:, k]))
    block = (
        "OPTIMISE\nVARY 1 5 15\nBUFX0 9 1\nBUFX0 10 2\nTARGET 1 px.dat\nTARGET 2 py.dat\nFREETIME 6 ORDERED\n"
        "OPTFTOL 1E-14 1E-24\n"
    )
    text = four_bar(unit, crank=11.0).to_deck().replace("KIN ANA", "KIN OPT").replace("\nEND", "\n" + block + "END")
    path = folder / "timing.mec"
    path.write_text(text)
    return path


def rocker_target(path: Path, unit: str) -> None:
    """Adds the rocker angle at the known points (B about B0 = (40, 0)) as a third TARGET, in ``unit``."""
    run = four_bar("deg").run()
    phi = np.degrees(np.arctan2(np.asarray(run.value("B.y")), np.asarray(run.value("B.x")) - 40.0))
    values = phi if unit == "deg" else np.radians(phi)
    (path.parent / "phi.dat").write_text("".join(f"{float(v)!r}\n" for v in values))
    text = path.read_text().replace("FORM 6 ANGB 1 6 1.0\n", "FORM 6 ANGB 1 6 1.0\nFORM 7 ANGB 3 -1 1.0\n")
    path.write_text(text.replace("TARGET 2 py.dat\n", "TARGET 2 py.dat\nBUFE0 -1 3\nTARGET 3 phi.dat\n"))


# With the rocker angle as a target too, its values are read in the deck's own angle unit: in degrees they are the
# radian deck's converted, so both decks start and end alike.
@pytest.mark.parametrize("rocker", [False, True], ids=["points", "points and rocker angle"])
def test_free_ordered_timing_in_a_deck_in_degrees_is_the_one_in_radians(tmp_path: Path, rocker: bool) -> None:
    found = {}
    for unit in ("deg", "rad"):
        path = deck(tmp_path, unit)
        if rocker:
            rocker_target(path, unit)
        opt = optimise_deck.describe(path).optimise
        assert opt is not None and len(opt.targets) == (3 if rocker else 2)
        out = optimise_deck.optimise(path, opt)
        assert out.deck.synthesis is not None
        found[unit] = (out, out.deck.synthesis.inputs(out.x))
    (deg, t_deg), (rad, t_rad) = found["deg"], found["rad"]
    assert deg.start_objective == pytest.approx(rad.start_objective, rel=1e-9)
    assert deg.objective < 1e-16 and rad.objective < 1e-16
    assert deg.x[0] == pytest.approx(10.0, abs=1e-7)
    assert np.asarray(t_deg) == pytest.approx(np.degrees(t_rad), abs=1e-6)
    assert np.asarray(t_deg) == pytest.approx(THETAS, abs=1e-6)
