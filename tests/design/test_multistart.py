"""Multi-start of :func:`mechfem.optimize`: space-filling draws in a start box independent of the order of the
variables, a list of start designs, every start assembled afresh by continuation (or discarded with the reason),
and the usable fraction."""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pytest

import mechfem
from mechfem.design import multistart

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "examples" / "synthesis"))
import path_synthesis as ps  # noqa: E402

VARY = {name: (lo, hi) for name, lo, hi in zip(ps.NAMES, ps.LOWER, ps.UPPER, strict=True)}


def test_draws_fill_the_box_and_do_not_depend_on_the_order_of_the_names() -> None:
    box = {"b": (0.0, 1.0), "a": (-2.0, 2.0), "c": (5.0, 6.0)}
    one = multistart.draws(box, 64, seed=7)
    other = multistart.draws(dict(reversed(list(box.items()))), 64, seed=7)
    assert one == other
    x = np.array([[d[k] for k in ("a", "b", "c")] for d in one])
    assert np.all(x >= [-2.0, 0.0, 5.0]) and np.all(x <= [2.0, 1.0, 6.0])
    # Space-filling: every eighth of each range holds a draw (uniform random draws of 64 often leave one empty).
    for j, (lo, hi) in enumerate([(-2.0, 2.0), (0.0, 1.0), (5.0, 6.0)]):
        bins = np.floor((x[:, j] - lo) / (hi - lo) * 8).astype(int)
        assert set(bins) == set(range(8))
    assert multistart.draws(box, 64, seed=8) != one


def test_the_result_does_not_depend_on_the_order_of_the_variables() -> None:
    found = []
    for vary in (VARY, dict(reversed(list(VARY.items())))):
        opt = mechfem.optimize(ps.four_bar(), vary, targets=ps.targets(), starts=4, seed=5, steps=40)
        found.append(([s.start for s in opt.starts], opt.values, opt.objective))
    assert found[0][0] == found[1][0]
    assert found[0][2] == pytest.approx(found[1][2], rel=1e-6, abs=1e-18)
    for name in ps.NAMES:
        assert found[0][1][name] == pytest.approx(found[1][1][name], abs=1e-6)


def test_a_list_of_start_designs_and_a_discarded_one() -> None:
    near = {"B0.x": 3.1, "crank.length": 1.05}
    # A crank longer than coupler and rocker can reach: the dyad cannot close at the crank's start angle.
    impossible = {"crank.length": 2.0, "coupler.length": 1.5, "rocker.length": 1.0, "B0.x": 5.0}
    opt = mechfem.optimize(ps.four_bar(), VARY, targets=ps.targets(), starts=[near, impossible], steps=60)
    assert len(opt.starts) == 3
    assert opt.starts[1].start["B0.x"] == 3.1 and opt.starts[1].start["B0.y"] == ps.START[1]
    assert opt.starts[1].values is not None
    assert opt.starts[2].values is None and opt.starts[2].message.startswith("start design discarded: ")
    assert opt.usable == pytest.approx(2 / 3)
    assert opt.objective < 1e-12


def test_an_assembled_start_is_on_the_branch_of_the_mechanisms_estimates() -> None:
    m = ps.four_bar()
    r0 = m.run(mechfem.Motion.by(1, 1e-9))
    above = r0.value("B.y")[0] > 0.0
    moved = multistart.assembled(m, {"B0.x": 4.5, "B0.y": -1.5, "rocker.length": 3.5})
    assert not isinstance(moved, str)
    r1 = moved.run(mechfem.Motion.by(1, 1e-9))

    # The rocker pivot moved far; B stays on the same side of the line A -> B0 as in the mechanism.
    def side(r: mechfem.RunResult, b0: tuple[float, float]) -> float:
        ax, ay, bx, by = (r.value(n)[0] for n in ("A.x", "A.y", "B.x", "B.y"))
        return float(np.sign((b0[0] - ax) * (by - ay) - (b0[1] - ay) * (bx - ax)))

    assert side(r0, (ps.START[0], ps.START[1])) == side(r1, (4.5, -1.5))
    assert above


def test_a_start_box_outside_vary_is_refused() -> None:
    with pytest.raises(ValueError, match="start box"):
        mechfem.optimize(ps.four_bar(), VARY, targets=ps.targets(), starts=3, box={"coupler.w": (0.0, 1.0)})
    with pytest.raises(ValueError, match="empty list"):
        mechfem.optimize(ps.four_bar(), VARY, targets=ps.targets(), starts=[])


def test_draws_that_cannot_do_the_motion_are_passed_over_with_their_reason(monkeypatch: pytest.MonkeyPatch) -> None:
    mech = ps.four_bar()
    base = {name: float(mech[name].value) for name in VARY}
    # A four-bar's draws turn the crank by construction (tests/design/test_fourbar_starts.py): the first four are taken.
    assert multistart.screened(mech, base, VARY, 4, 1, {})[3] == 4
    # Any other mechanism draws in the box itself, as this four-bar does when not recognised.
    monkeypatch.setattr(multistart.fourbar_starts, "recognised", lambda _m: None)
    begins, reached, rejected, looked = multistart.screened(mech, base, VARY, 4, 1, {})
    assert len(begins) == len(reached) == 4
    assert looked == 4 + len(rejected)
    assert rejected, "half of this box cannot turn the crank through 324 degrees: some draw is passed over"
    for at in reached:
        assert multistart.runs_through(at, {}) == ""
    for begin, why in rejected:
        # A rejected draw really cannot do the motion: assembled afresh, it cannot be, or its motion stops.
        assert why
        at = multistart.assembled(mech, begin)
        assert isinstance(at, str) or multistart.runs_through(at, {}) != ""
    # The drawn starts are the first draws of the sequence that can: the same seed, the same starts.
    assert multistart.screened(mech, base, VARY, 4, 1, {})[0] == begins
    opt = mechfem.optimize(mech, VARY, targets=ps.targets(), starts=3, seed=1, steps=2)
    assert opt.usable == 1.0 and len(opt.starts) == 3
    assert opt.drawn == 2 + len(opt.rejected)
    assert all(r.values is None and r.message.startswith("draw passed over: ") for r in opt.rejected)
