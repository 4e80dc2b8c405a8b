"""A variable frame angle (``optimize(..., frame=FrameAngle(pivot))``): the frame's fixed points turned about the
pivot and the angle input's start turned with it, as one design variable with an exact gradient."""

from __future__ import annotations

import math
import sys
from pathlib import Path

import numpy as np
import pytest

import mechfem
from mechfem.deck import deckio
from mechfem.design import engine as design
from mechfem.design import frame_angle
from mechfem.design.frame_angle import FrameAngle
from mechfem.design.optimise import _Deck, _variable
from mechfem.run import building

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "examples" / "synthesis"))
import path_synthesis as ps  # noqa: E402

KNOWN = (3.2, 0.0, 1.0, 3.0, 2.5, 1.8 * math.cos(0.6), 1.8 * math.sin(0.6))
TURN = 0.4


def turned_targets(phi: float) -> list[mechfem.Target]:
    """The known four-bar's coupler points with its whole frame turned by ``phi`` about A0 (the origin): the crank
    angles are measured from the frame, so every point turns by ``phi``."""
    c, s = math.cos(phi), math.sin(phi)
    pts = ps.known_points() @ np.array([[c, s], [-s, c]])
    n = ps.SUBSTEPS * (len(ps.THETAS) - 1) + 1
    out = []
    for k, name in enumerate(("P.x", "P.y")):
        values = np.full(n, np.nan)
        values[:: ps.SUBSTEPS] = pts[:, k]
        out.append(mechfem.Target(name, values))
    return out


def test_the_frame_angle_of_a_turned_four_bar_is_found() -> None:
    # The dimensions a little off the known ones, the frame not turned: only a frame turned by TURN (crank angles
    # with it) passes the turned points.
    start = (3.2, 0.0, 1.05, 2.95, 2.5, 1.5, 1.0)
    vary = {name: (lo, hi) for name, lo, hi in zip(ps.NAMES, ps.LOWER, ps.UPPER, strict=True) if name[:2] != "B0"}
    opt = mechfem.optimize(
        ps.four_bar(start), vary, targets=turned_targets(TURN), frame=FrameAngle("A0"), rtol=1e-14, atol=1e-24
    )
    assert opt.objective < 1e-18
    assert opt.values["frame"] == pytest.approx(TURN, abs=1e-9)
    assert opt.start["frame"] == 0.0
    for name, value in zip(ps.NAMES, KNOWN, strict=True):
        if name in vary:
            assert opt.values[name] == pytest.approx(value, abs=1e-8)
    # The optimised mechanism is the turned one: B0 on the turned frame line, the crank starting at TURN.
    m = opt.mechanism
    assert (m["B0.x"].value, m["B0.y"].value) == pytest.approx((3.2 * math.cos(TURN), 3.2 * math.sin(TURN)))
    assert m["theta"].value == pytest.approx(TURN, abs=1e-9)
    run = opt.run()
    for target in turned_targets(TURN):
        got, want = run.value(target.quantity), np.asarray(target.values)
        ok = ~np.isnan(want)
        assert np.max(np.abs(got[ok] - want[ok])) < 1e-8


def test_without_the_frame_angle_the_turned_points_are_not_reached() -> None:
    start = (3.2, 0.0, 1.05, 2.95, 2.5, 1.5, 1.0)
    vary = {name: (lo, hi) for name, lo, hi in zip(ps.NAMES, ps.LOWER, ps.UPPER, strict=True) if name[:2] != "B0"}
    opt = mechfem.optimize(ps.four_bar(start), vary, targets=turned_targets(TURN), rtol=1e-14, atol=1e-24)
    assert opt.objective > 1e-3


def test_the_frame_angles_gradient_agrees_with_central_differences() -> None:
    # The pivot A0 and B0 vary too: the turn's Jacobian then has the pivot's and the points' terms.
    m = ps.four_bar((3.0, 0.3, 1.1, 2.8, 2.6, 1.2, 1.1))
    names = ["A0.x", "A0.y", "B0.x", "B0.y", "crank.length", "coupler.u"]
    deck = _Deck(m)
    buffers = [deck.buffer("P.x"), deck.buffer("P.y"), deck.buffer(mechfem.Q("P.x", 1))]
    built = building.builder(m, m.motion, deck.storage)
    variables = [(k, n) for k, n, _ in (_variable(m, built.numbering, name) for name in names)]
    turn = frame_angle.plan(m, FrameAngle("A0"), built.numbering, None)
    exposed = [*variables, frame_angle.SENTINEL]
    with deckio.tables_dir(built.tables) as base:
        model = frame_angle.turned(design.built_model(built.builder, base), turn)(exposed, buffers, [])
        z0 = [*model.start()]
        assert z0[-1] == 0.0
        z0[-1] = 0.3
        got = model.evaluate(z0)
        assert got.feasible
        grad = np.asarray(got.gradient)
        h = 1e-6
        for j in range(len(z0)):
            up, down = list(z0), list(z0)
            up[j] += h
            down[j] -= h
            fd = (np.asarray(model.evaluate(up).values) - np.asarray(model.evaluate(down).values)) / (2 * h)
            scale = max(1.0, float(np.max(np.abs(fd))))
            assert np.max(np.abs(grad[:, :, j] - fd)) < 1e-6 * scale, j


def test_a_pivot_that_is_not_a_fixed_point_is_refused() -> None:
    vary = {"crank.length": (0.5, 2.0)}
    with pytest.raises(ValueError, match="not a fixed point"):
        mechfem.optimize(ps.four_bar(), vary, targets=ps.targets(), frame=FrameAngle("A"))
