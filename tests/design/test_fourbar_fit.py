"""Starts of a four-bar with free timing fitted to the targets (mechfem.design.fourbar_fit): a drawn coupler curve
placed on the points by a similarity, its timing the crank angles of the laid samples; the published straight line
reached from four such starts."""

from __future__ import annotations

import math
import sys
import warnings
from pathlib import Path

import numpy as np
import pytest

import mechfem
from mechfem.design import fourbar_fit, fourbar_starts, multistart

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "examples" / "synthesis"))
import benchmarks as bm  # noqa: E402

LINE = bm.BENCHMARKS["straight_line"]


def test_a_placed_start_passes_its_laid_points_in_mechfems_kinematics() -> None:
    """The placed design, assembled at its first crank angle and run to each point's angle by mechfem, has the sum
    of squared distances of its laying: the curve, the similarity carried to the pivots, lengths and u, v, and the
    crank angles turned with it are the mechanism's."""
    mech, vary, kwargs = bm.problem(LINE)
    fb = fourbar_starts.recognised(mech)
    assert fb is not None
    fit = fourbar_fit.applicable(fb, vary, kwargs)
    assert fit is not None and fit.ordered and fit.frame == (0.0, LINE.length)
    branch = fourbar_starts.side(fb, multistart.assembled(mech, {}))  # type: ignore[arg-type]
    kept, left = fourbar_fit.starts(fb, mech, {k: v for k, v in vary.items() if v}, fit, branch, 3, seed=1)
    assert len(kept) + len(left) == fourbar_fit.POOL * 3 and len(kept) >= 3
    assert [k[0] for k in kept] == sorted(k[0] for k in kept)
    for err, design, angles in kept[:3]:
        assert np.all(np.diff(angles) >= 0.0)
        frame = math.hypot(design["B0.x"] - design["A0.x"], design["B0.y"] - design["A0.y"])
        assert frame <= LINE.length
        at = fourbar_starts.assembled(fb, mech, branch, {**design, "theta": angles[0]})
        assert not isinstance(at, str)
        timing = mechfem.FreeTiming("theta", angles, ordered=True)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            opt = mechfem.optimize(at, vary, **{**kwargs, "timing": timing, "steps": 1, "bounds": []})
        assert opt.start_objective == pytest.approx(err, rel=1e-9)
    # The laying is far better than the problem's own start angles (0.5 to 2.5 rad) on the same design.
    _, design, _ = kept[0]
    at = fourbar_starts.assembled(fb, mech, branch, {**design, "theta": float(LINE.thetas[0])})
    assert not isinstance(at, str)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        own = mechfem.optimize(at, vary, **{**kwargs, "steps": 1, "bounds": []})
    assert own.start_objective > 100.0 * kept[0][0]


@pytest.mark.large_run
def test_four_fitted_starts_reach_the_published_straight_line() -> None:
    """Seed 1, four starts: an exact straight line (the published design's error is 1.31e-11), inside every
    published range, Grashof with the crank the shortest, the points in order; the frame length within its bound."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        opt = bm.solve(LINE, 4, 1)
    d = bm.published_design(LINE, opt)
    assert bm.published_error(LINE, d) < 1.31e-11
    assert bm.within_published_ranges(LINE, d) and bm.grashof(d) == (True, True) and bm.ordered(d)
    assert opt.usable == 1.0 and len(opt.starts) == 4


def test_each_fitted_start_is_optimised_from_its_own_start_angles() -> None:
    mech, vary, kwargs = bm.problem(LINE)
    box = {k: v for k, v in vary.items() if v}
    base = {k: float(mech[k].value) for k in box}
    got = multistart._fitted(mech, vary, base, box, 3, 1, kwargs)
    assert got is not None
    begins, reached, rejected, looked, timings = got
    assert len(begins) == len(reached) == len(timings) == 3 and looked == 3 + len(rejected)
    firsts = set()
    for at, timing in zip(reached, timings, strict=True):
        assert isinstance(timing, mechfem.FreeTiming) and timing.ordered and timing.within == bm.ONE_TURN
        assert not np.allclose(timing.starts, LINE.thetas)
        assert at["theta"].value == pytest.approx(timing.starts[0])
        firsts.add(round(timing.starts[0], 9))
    assert len(firsts) == 3


def test_every_start_records_the_timing_it_started_from() -> None:
    """``Optimum.starts`` keeps each start's start timing: the problem's start angles for the given design and a
    plain draw, a fitted start's own (the crank angles of its laid points); and the timing where each ended, the
    best start's being the optimum's."""
    mech, vary, kwargs = bm.problem(LINE)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        opt = mechfem.optimize(mech, vary, starts=3, seed=1, **{**kwargs, "steps": 3})
    box = {k: v for k, v in vary.items() if v}
    got = multistart._fitted(mech, vary, {k: float(mech[k].value) for k in box}, box, 2, 1, kwargs)
    assert got is not None and len(opt.starts) == 3
    own = [None, *got[4]]
    assert any(t is not None for t in own)
    for start, timing in zip(opt.starts, own, strict=True):
        assert start.start_timing is not None and start.values is not None
        expected = LINE.thetas if timing is None else timing.starts
        assert start.start_timing == pytest.approx(expected, abs=1e-12)
        assert timing is None or not np.allclose(start.start_timing, LINE.thetas)
        assert start.timing is not None and len(start.timing) == len(LINE.thetas)
    best = min(opt.starts, key=lambda s: s.objective)
    assert best.timing == pytest.approx(opt.timing, abs=1e-12)
