"""The synthesis statements of a deck (FREETIME, FULLROT, VARYFRAME) state the same problems as ``optimize``'s
``timing``, ``full_rotation`` and ``frame``, and give the same results; the written final design runs as a deck."""

from __future__ import annotations

import math
import shutil
import sys
from pathlib import Path

import numpy as np
import pytest

import mechfem
from mechfem.design import optimise_deck
from mechfem.design.frame_angle import FrameAngle

ROOT = Path(__file__).resolve().parents[2]
SYNTHESIS = ROOT / "examples" / "synthesis"
sys.path.insert(0, str(SYNTHESIS))
import path_synthesis as ps  # noqa: E402
import straight_line as sl  # noqa: E402

STEPS = 10
"""Iterations of the straight line in these tests: the deck and Python take the same steps, converged or not."""


def limited(tmp_path: Path) -> Path:
    """straight_line.mec with its data, limited to STEPS iterations."""
    for name in ("line_x.dat", "line_y.dat"):
        shutil.copy(SYNTHESIS / name, tmp_path)
    text = (SYNTHESIS / "straight_line.mec").read_text().replace("OPTSTEPS 50 ", f"OPTSTEPS {STEPS} ")
    deck = tmp_path / "straight_line.mec"
    deck.write_text(text)
    return deck


def solved(deck: Path) -> mechfem.Optimum:
    opt = optimise_deck.describe(deck).optimise
    assert opt is not None
    return optimise_deck.optimise(deck, opt)


def test_free_timing_in_the_deck_is_the_python_problem(tmp_path: Path) -> None:
    out = solved(limited(tmp_path))
    py = sl.synthesise(steps=STEPS)
    s = out
    assert out.deck.synthesis is not None
    assert s.objective == pytest.approx(py.objective, rel=1e-6, abs=1e-18)
    assert s.start_objective == pytest.approx(py.start_objective, rel=1e-12)
    n = len(sl.VARY)
    for x, name in zip(s.x[:n], sl.VARY, strict=True):
        assert x == pytest.approx(py.values[name], rel=1e-6, abs=1e-6)
    assert out.deck.synthesis.inputs(s.x) == pytest.approx(py.timing, abs=1e-6)
    assert py.timing is not None and len(py.timing) == 6


def test_the_written_design_of_a_free_timing_deck_passes_its_points(tmp_path: Path) -> None:
    out = solved(limited(tmp_path))
    written = optimise_deck.write_design_deck(out, tmp_path / "out")
    assert out.deck.synthesis is not None
    inputs = out.deck.synthesis.inputs(out.x)
    assert inputs is not None
    m = mechfem.Mechanism.from_deck(written)
    assert m["theta"].value == pytest.approx(inputs[0], abs=1e-12)
    # The written design turned from the first point's crank angle to each point's: its squared distances from the
    # points add up to the objective the optimiser reported.
    total = 0.0
    for (x, y), theta in zip(sl.POINTS, inputs, strict=True):
        steps = max(1, math.ceil(abs(theta - inputs[0]) / 0.02))
        r = m.run(mechfem.Motion.by(steps, theta - inputs[0] if theta != inputs[0] else 1e-12))
        total += (r.value("P.x")[-1] - x) ** 2 + (r.value("P.y")[-1] - y) ** 2
    assert total == pytest.approx(out.objective, rel=1e-6, abs=1e-12)


def _turned_path_deck(tmp_path: Path, extra: str, phi: float) -> Path:
    """path.mec with B0 fixed, the targets turned by ``phi`` about A0, and ``extra`` in OPTIMISE."""
    c, s = math.cos(phi), math.sin(phi)
    pts = ps.known_points() @ np.array([[c, s], [-s, c]])
    for k, name in enumerate(("path_x.dat", "path_y.dat")):
        rows = ["*"] * (ps.SUBSTEPS * (len(ps.THETAS) - 1) + 1)
        rows[:: ps.SUBSTEPS] = [repr(float(v)) for v in pts[:, k]]
        (tmp_path / name).write_text("\n".join(rows) + "\n")
    text = (SYNTHESIS / "path.mec").read_text()
    text = text.replace("VARYX 3 1.0 5.0\n", "").replace("VARYX 4 -2.0 2.0\n", "")
    # B0 fixed where the known four-bar has it: only the turn is missing.
    text = text.replace("     3 2.8 ", "     3 3.2 ").replace("     4 0.4\n", "     4 0.0\n")
    text = text.replace("TARGET 2 path_y.dat\n", f"TARGET 2 path_y.dat\n{extra}\n")
    deck = tmp_path / "turned.mec"
    deck.write_text(text)
    return deck


def test_a_frame_angle_in_the_deck_is_the_python_problem(tmp_path: Path) -> None:
    phi = 0.4
    deck = _turned_path_deck(tmp_path, "VARYFRAME 1 -3.141592653589793 3.141592653589793", phi)
    out = solved(deck)
    vary = {n: (lo, hi) for n, lo, hi in zip(ps.NAMES, ps.LOWER, ps.UPPER, strict=True) if n[:2] != "B0"}
    targets = []
    for name, file in (("P.x", "path_x.dat"), ("P.y", "path_y.dat")):
        rows = (tmp_path / file).read_text().split()
        targets.append(mechfem.Target(name, np.array([math.nan if r == "*" else float(r) for r in rows])))
    py = mechfem.optimize(ps.four_bar((3.2, 0.0, *ps.START[2:])), vary, targets=targets, frame=FrameAngle("A0"))
    assert out.objective < 1e-18 and py.objective < 1e-18
    assert out.x[len(vary)] == pytest.approx(phi, abs=1e-8)
    assert py.values["frame"] == pytest.approx(phi, abs=1e-8)
    # The written deck holds the turned frame: B0 on the line at phi, the crank starting at phi.
    written = optimise_deck.write_design_deck(out, tmp_path / "out")
    m = mechfem.Mechanism.from_deck(written)
    b0 = (3.2 * math.cos(phi), 3.2 * math.sin(phi))
    assert (m["B0.x"].value, m["B0.y"].value) == pytest.approx(b0)
    assert m["theta"].value == pytest.approx(phi, abs=1e-8)


def test_a_full_turn_in_the_deck_is_the_python_problem(tmp_path: Path) -> None:
    shutil.copy(SYNTHESIS / "path_x.dat", tmp_path)
    shutil.copy(SYNTHESIS / "path_y.dat", tmp_path)
    text = (SYNTHESIS / "path.mec").read_text().replace("TARGET 2 path_y.dat\n", "TARGET 2 path_y.dat\nFULLROT 6\n")
    deck = tmp_path / "fullrot.mec"
    deck.write_text(text)
    out = solved(deck)
    vary = {n: (lo, hi) for n, lo, hi in zip(ps.NAMES, ps.LOWER, ps.UPPER, strict=True)}
    py = mechfem.optimize(ps.four_bar(), vary, targets=ps.targets(), full_rotation=True)
    assert out.objective < 1e-18 and py.objective < 1e-18
    for x, name in zip(out.x, ps.NAMES, strict=True):
        assert x == pytest.approx(py.values[name], abs=1e-8)


def test_free_timing_of_an_input_that_is_not_an_angle_is_refused(tmp_path: Path) -> None:
    deck = ROOT / "tests" / "decks" / "opt_freetime_not_angle.mec"
    with pytest.raises(optimise_deck.OptimisationError, match="FREETIME names row .*, which is not an angle"):
        solved(deck)


def test_a_bound_on_a_transmission_angle_in_the_deck_is_the_python_problem(tmp_path: Path) -> None:
    # The known four-bar's transmission angle between coupler and rocker goes down to 0.8038 rad: a lower bound
    # above that keeps the targets from being met.
    lo = 0.8537662945796817
    shutil.copy(SYNTHESIS / "path_x.dat", tmp_path)
    shutil.copy(SYNTHESIS / "path_y.dat", tmp_path)
    extra = f"BUFTRA 2 3 4\nBOUND 4 {lo!r} 3.0\nOPTFTOL 1E-12 1E-16\nOPTSTEPS 12\n"
    text = (SYNTHESIS / "path.mec").read_text().replace("TARGET 2 path_y.dat\n", f"TARGET 2 path_y.dat\n{extra}")
    deck = tmp_path / "bounded.mec"
    deck.write_text(text)
    out = solved(deck)
    vary = {n: (a, b) for n, a, b in zip(ps.NAMES, ps.LOWER, ps.UPPER, strict=True)}
    bound = mechfem.Bound(mechfem.Transmission("coupler", "rocker"), lo, 3.0)
    py = mechfem.optimize(ps.four_bar(), vary, targets=ps.targets(), bounds=[bound], rtol=1e-12, atol=1e-16, steps=12)
    assert out.method.startswith("SLSQP") and py.method.startswith("SLSQP")
    assert py.objective > 1e-5
    assert out.objective == pytest.approx(py.objective, rel=1e-6)
    for x, name in zip(out.x, ps.NAMES, strict=True):
        assert x == pytest.approx(py.values[name], abs=1e-6)
    # Within its first iterations SLSQP keeps the bound at every position (docs/optimisation.md gives the optimum on
    # the bound, 60 runs on).
    mu = py.run().transmission_angle("coupler", "rocker")
    assert mu.min() >= lo - 1e-6


def test_ordered_free_timing_in_the_deck_is_the_python_problem(tmp_path: Path) -> None:
    deck = limited(tmp_path)
    deck.write_text(deck.read_text().replace("FREETIME 6 ", "FREETIME 6 ORDERED "))
    out = solved(deck)
    targets = [mechfem.Target("P.x", sl.POINTS[:, 0]), mechfem.Target("P.y", sl.POINTS[:, 1])]
    timing = mechfem.FreeTiming("theta", sl.STARTS, ordered=True)
    py = mechfem.optimize(
        sl.four_bar(), sl.VARY, targets=targets, timing=timing, full_rotation=True, rtol=1e-12, atol=1e-20, steps=STEPS
    )
    assert out.deck.synthesis is not None and py.timing is not None
    assert out.objective == pytest.approx(py.objective, rel=1e-6, abs=1e-18)
    inputs = out.deck.synthesis.inputs(out.x)
    assert inputs == pytest.approx(py.timing, abs=1e-6)
    # Ordered: every point's crank angle at or after the one before.
    assert all(b >= a for a, b in zip(inputs, inputs[1:], strict=False))
