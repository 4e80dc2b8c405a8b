"""Free timing: the input's value at each target point is a design variable (``optimize(timing=FreeTiming(...))``).
The points of a known four-bar at ten crank angles are found again, dimensions and crank angles both, from a poor
start; the points' gradient with respect to the timing is checked against central differences of whole runs."""

from __future__ import annotations

import re
import sys
from pathlib import Path

import numpy as np
import pytest

import mechfem
from mechfem.design.optimise import _Deck, _variable
from mechfem.design.timing import TimedModel, plan
from mechfem.run import building

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "examples" / "synthesis"))
import path_synthesis as ps  # noqa: E402

VARY = {name: (lo, hi) for name, lo, hi in zip(ps.NAMES, ps.LOWER, ps.UPPER, strict=True)}
KNOWN = np.array([3.2, 0.0, 1.0, 3.0, 2.5, 1.8 * np.cos(0.6), 1.8 * np.sin(0.6)])
OFF = np.array([0.1, -0.05, 0.08, 0.02, -0.1, 0.05, 0.0, 0.07, -0.03, 0.04])


def targets() -> list[mechfem.Target]:
    pts = ps.known_points()
    return [mechfem.Target("P.x", pts[:, 0]), mechfem.Target("P.y", pts[:, 1])]


@pytest.mark.parametrize("ordered", [False, True])
def test_free_timing_finds_the_known_four_bar_and_its_crank_angles(ordered: bool) -> None:
    timing = mechfem.FreeTiming("theta", list(ps.THETAS + OFF), ordered=ordered)
    opt = mechfem.optimize(ps.four_bar(), VARY, targets=targets(), timing=timing)
    assert opt.start_objective > 10.0
    assert opt.objective < 1e-18
    np.testing.assert_allclose([opt.values[n] for n in ps.NAMES], KNOWN, atol=1e-8)
    assert opt.timing is not None
    np.testing.assert_allclose(opt.timing, ps.THETAS, atol=1e-8)
    # The optimised mechanism starts at the first point's crank angle and passes the first target there.
    run = opt.mechanism.run(mechfem.Motion.by(1, 1e-9))
    assert run.value("P.x")[0] == pytest.approx(ps.known_points()[0, 0], abs=1e-8)


def test_the_timing_gradient_agrees_with_central_differences() -> None:
    m = ps.four_bar()
    deck = _Deck(m)
    buffers = [deck.buffer("P.x"), deck.buffer("P.y")]
    thetas = list(ps.THETAS[:4] + OFF[:4])
    for ordered in (False, True):
        timing = mechfem.FreeTiming("theta", thetas, ordered=ordered)
        built = building.builder(m, mechfem.Motion.by(1, 1e-9), deck.storage)
        shared = [_variable(m, built.numbering, n)[:2] for n in ("crank.length", "B0.x")]
        p = plan(m, timing, deck.storage, built.numbering)
        points = [b.design("", [*shared, p.input_var], buffers, []) for b in p.builders]
        model = TimedModel(points, len(shared), p.thetas, ordered, True)
        y0 = np.array(model.start())
        d0 = model.start_at(list(y0))
        assert d0.feasible
        h = 1e-6
        for i in range(len(y0)):
            up, down = y0.copy(), y0.copy()
            up[i] += h
            down[i] -= h
            fd = (model.evaluate(list(up)).values - model.evaluate(list(down)).values) / (2 * h)
            np.testing.assert_allclose(d0.gradient[:, :, i], fd, atol=1e-7, rtol=1e-6)


def test_ordered_timing_keeps_the_points_in_order_and_refuses_an_unordered_start() -> None:
    with pytest.raises(ValueError, match="not in order"):
        mechfem.FreeTiming("theta", [0.0, 1.0, 0.5], ordered=True)
    p = mechfem.FreeTiming("theta", list(ps.THETAS + OFF), ordered=True)
    opt = mechfem.optimize(ps.four_bar(), VARY, targets=targets(), timing=p, steps=3)
    assert opt.timing is not None and np.all(np.diff(opt.timing) >= 0.0)


def test_free_timing_is_refused_for_what_is_not_an_input_and_with_extrema() -> None:
    with pytest.raises(ValueError, match="not an input"):
        mechfem.optimize(ps.four_bar(), VARY, targets=targets(), timing=mechfem.FreeTiming("crank.length", [1.0]))
    with pytest.raises(ValueError, match="needs a motion"):
        mechfem.optimize(
            ps.four_bar(),
            VARY,
            targets=[mechfem.TargetExtremum("P.x", "P.y", 0.0)],
            timing=mechfem.FreeTiming("theta", [0.0, 1.0]),
        )
    with pytest.raises(ValueError, match="values for the motion's 3 positions"):
        mechfem.optimize(ps.four_bar(), VARY, targets=targets(), timing=mechfem.FreeTiming("theta", [0.0, 1.0, 2.0]))


def test_an_infeasible_point_names_the_point() -> None:
    # A crank of 5 with a rocker of 2.8 and a frame of 2.8: the dyad cannot be assembled at the points.
    m = ps.four_bar()
    deck = _Deck(m)
    buffers = [deck.buffer("P.x")]
    built = building.builder(m, mechfem.Motion.by(1, 1e-9), deck.storage)
    shared = [_variable(m, built.numbering, "crank.length")[:2]]
    p = plan(m, mechfem.FreeTiming("theta", list(ps.THETAS)), deck.storage, built.numbering)
    points = [b.design("", [*shared, p.input_var], buffers, []) for b in p.builders]
    model = TimedModel(points, 1, p.thetas, False, True)
    d = model.start_at([5.0, *p.thetas])
    assert not d.feasible
    assert re.match(r"at target point \d+: position 1 cannot be computed", str(d.reason))


def test_ordered_points_within_a_sweep_stop_at_it() -> None:
    """The known four-bar passes its ten points over 324 degrees of the crank: kept within 5 rad, the optimum's
    last point lies 5 rad after its first (an active inequality), at an error above 0."""
    timing = mechfem.FreeTiming("theta", list(ps.THETAS + OFF), ordered=True, within=5.0)
    opt = mechfem.optimize(ps.four_bar(), VARY, targets=targets(), timing=timing, rtol=1e-12, atol=1e-24)
    assert opt.method == "SLSQP"
    assert opt.timing is not None
    assert opt.timing[-1] - opt.timing[0] == pytest.approx(5.0, abs=1e-8)
    assert np.all(np.diff(opt.timing) >= 0.0)
    assert opt.objective > 1e-6
    with pytest.raises(ValueError, match="ordered"):
        mechfem.FreeTiming("theta", [0.0, 1.0], within=5.0)
