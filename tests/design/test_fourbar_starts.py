"""Start designs of a four-bar drawn so that its crank turns fully, assembled from a closed-form position 1."""

from __future__ import annotations

import math
import sys
from pathlib import Path

import numpy as np
import pytest

import mechfem
from mechfem.design import fourbar_starts, multistart

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "examples" / "synthesis"))
import path_synthesis as ps  # noqa: E402
import straight_line as sl  # noqa: E402

PATH_BOX = {n: (lo, hi) for n, lo, hi in zip(ps.NAMES, ps.LOWER, ps.UPPER, strict=True)}
LINE_BOX = {n: v for n, v in sl.VARY.items() if v is not None}


def closes_over_a_turn(
    x0: float, y0: float, x1: float, y1: float, a: float, b: float, c: float, sweep: tuple[float, float] = (0, 7)
) -> bool:
    """Whether the dyad (b, c) closes at 720 crank angles over ``sweep`` (default a whole turn): the distance from
    the crank's end to B0 within [|b - c|, b + c] at each (checked point by point, not by Grashof's formula)."""
    t = np.linspace(*sweep, 720)
    dist = np.hypot(x1 - (x0 + a * np.cos(t)), y1 - (y0 + a * np.sin(t)))
    return bool(np.all(dist >= abs(b - c)) and np.all(dist <= b + c))


def test_the_examples_are_recognised_as_four_bars_and_a_slider_crank_is_not() -> None:
    fb = fourbar_starts.recognised(ps.four_bar())
    assert fb is not None
    assert fb.lengths == ("crank.length", "coupler.length", "rocker.length")
    assert (fb.a0, fb.a, fb.b, fb.b0, fb.p) == ("A0", "A", "B", "B0", "P")
    assert fourbar_starts.recognised(sl.four_bar()) is not None
    m = mechfem.Mechanism("slider_crank")
    a0 = m.fixed("A0", 0.0, 0.0)
    a = m.point("A", 1.0, 0.0)
    b = m.point("B", 4.0, 0.0, fixed="y")
    m.bar("crank", a0, a, length=1.0, angle=mechfem.Driven(0.0, name="theta"))
    m.bar("rod", a, b, length=3.0)
    assert fourbar_starts.recognised(m) is None


@pytest.mark.parametrize(("make", "box"), [(ps.four_bar, PATH_BOX), (sl.four_bar, LINE_BOX)])
def test_every_draw_lies_in_the_box_and_its_crank_turns_fully(
    make: object, box: dict[str, tuple[float, float]]
) -> None:
    mech = make()  # type: ignore[operator]
    fb = fourbar_starts.recognised(mech)
    assert fb is not None
    drawn = fourbar_starts.draws(fb, mech, box, 200, seed=3)
    usable = [d for d, why in drawn if not why]
    assert len(usable) == len(drawn)
    for d in usable:
        assert all(box[k][0] <= v <= box[k][1] for k, v in d.items())
        x0, y0 = d.get("A0.x", 0.0), d.get("A0.y", 0.0)
        assert closes_over_a_turn(x0, y0, d["B0.x"], d["B0.y"], *(d[k] for k in fb.lengths))


def test_the_draws_fill_the_box_and_do_not_depend_on_the_order_of_its_names() -> None:
    mech = ps.four_bar()
    fb = fourbar_starts.recognised(mech)
    assert fb is not None
    one = fourbar_starts.draws(fb, mech, PATH_BOX, 64, seed=7)
    other = fourbar_starts.draws(fb, mech, dict(reversed(list(PATH_BOX.items()))), 64, seed=7)
    assert one == other
    cranks = np.array([d["crank.length"] for d, _ in one])
    # The feasible cranks span most of the range 0.5..2, not a cluster.
    assert cranks.min() < 0.7 and cranks.max() > 1.6


def test_the_closed_form_position_one_is_the_solved_one_on_the_mechanisms_branch() -> None:
    mech = ps.four_bar()
    fb = fourbar_starts.recognised(mech)
    assert fb is not None
    own = multistart.assembled(mech, {})
    assert not isinstance(own, str)
    branch = fourbar_starts.side(fb, own)
    for d, _ in fourbar_starts.draws(fb, mech, PATH_BOX, 12, seed=1):
        trial = mech.variant(d)
        closed = fourbar_starts.position_one(fb, trial, branch)
        assert not isinstance(closed, str)
        at = fourbar_starts.assembled(fb, mech, branch, d)
        assert not isinstance(at, str)
        for name, x in closed.items():
            assert abs(float(at[name].value) - x) < 1e-9 * (1.0 + abs(x))


def test_at_least_four_draws_in_five_become_starts_when_the_crank_turns_fully() -> None:
    mech = sl.four_bar()
    timing = mechfem.FreeTiming("theta", sl.STARTS)
    kwargs = {"timing": timing, "full_rotation": True}
    base = {name: float(mech[name].value) for name in LINE_BOX}
    begins, reached, rejected, looked = multistart.screened(mech, base, LINE_BOX, 10, 2, kwargs)
    assert len(begins) == len(reached) == 10
    assert 10 / looked >= 0.8, rejected


def test_without_a_full_turn_every_other_start_is_a_plain_draw_of_the_box() -> None:
    """The starts alternate: plain draws of the box that can do the motion (the first of them first), and draws made
    to close over the sweep. The plain ones are the box's own draws, in order, lengths untouched."""
    mech = sl.four_bar()
    kwargs = {"timing": mechfem.FreeTiming("theta", sl.STARTS)}
    base = {name: float(mech[name].value) for name in LINE_BOX}
    begins, reached, _, looked = multistart.screened(mech, base, LINE_BOX, 6, 2, kwargs)
    assert len(begins) == len(reached) == 6
    plain = multistart.draws(LINE_BOX, multistart.SCREEN * 3, 2)
    kept = [d for d in plain if any(all(b[k] == d[k] for k in d) for b in begins)]
    assert [all(begins[k][n] == kept[k // 2][n] for n in kept[k // 2]) for k in (0, 2, 4)] == [True] * 3
    assert not any(any(all(begins[k][n] == d[n] for n in d) for d in plain) for k in (1, 3, 5))
    assert looked > 6  # plain draws are screened: some cannot do the motion


def test_an_optimum_reports_the_usable_fraction_of_its_draws() -> None:
    opt = mechfem.optimize(ps.four_bar(), PATH_BOX, targets=ps.targets(), starts=4, seed=1, steps=2)
    assert opt.drawn == 3 and opt.usable_draws == 1.0
    assert math.isnan(mechfem.optimize(ps.four_bar(), PATH_BOX, targets=ps.targets(), steps=2).usable_draws)


def test_the_sweep_is_the_crank_motion_of_the_problem() -> None:
    path, line = ps.four_bar(), sl.four_bar()
    fb = fourbar_starts.recognised(line)
    assert fb is not None
    timing = mechfem.FreeTiming("theta", sl.STARTS)
    assert fourbar_starts.sweep(fb, line, {"timing": timing}) == pytest.approx((0.0, 2.0))
    assert fourbar_starts.sweep(fb, line, {"timing": timing, "full_rotation": True}) is None
    assert fourbar_starts.sweep(fb, path, {}) == pytest.approx((0.0, math.radians(324.0)))
    assert fourbar_starts.sweep(fb, path, {"motion": mechfem.Motion.by(10, 7.0)}) is None


def test_draws_for_a_partial_sweep_close_over_it_and_need_not_turn_fully() -> None:
    mech = sl.four_bar()
    fb = fourbar_starts.recognised(mech)
    assert fb is not None
    theta = float(mech["theta"].value)
    drawn = fourbar_starts.draws(fb, mech, LINE_BOX, 100, seed=4, sweep=(0.0, 2.0))
    assert all(not why for _, why in drawn)
    full = 0
    for d, _ in drawn:
        pivots = (d["A0.x"], d["A0.y"], d["B0.x"], d["B0.y"])
        lengths = [d[k] for k in fb.lengths]
        assert closes_over_a_turn(*pivots, *lengths, sweep=(theta, theta + 2.0))
        full += closes_over_a_turn(*pivots, *lengths)
    # A two-radian swing admits linkages whose crank cannot turn fully: the draws use them.
    assert full < len(drawn)
