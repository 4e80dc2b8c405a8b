"""A bound on the frame length (``Bound(FrameLength("A0", "B0"), lo, hi)``): the distance between two fixed points,
a function of the design variables alone, as an inequality of SLSQP with its exact gradient."""

from __future__ import annotations

import math
import sys
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest

import mechfem
from mechfem.design import engine as design
from mechfem.design.frame_length import FrameLength, design_bound

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "examples" / "synthesis"))
import path_synthesis as ps  # noqa: E402

VARY = {name: (lo, hi) for name, lo, hi in zip(ps.NAMES, ps.LOWER, ps.UPPER, strict=True)}


def test_the_frame_lengths_gradient_is_that_of_central_differences() -> None:
    mech = ps.four_bar()
    mech.set("A0.y", 0.3)  # not varied: a constant of the length
    names = ["coupler.u", "B0.y", "A0.x", "crank.length", "B0.x"]
    bound = design_bound(mech, FrameLength("A0", "B0"), 0.5, 3.0, names)
    x = np.array([1.0, -0.7, 0.4, 1.2, 2.9])
    d, g = bound.f(x)
    assert d == pytest.approx(math.hypot(2.9 - 0.4, -0.7 - 0.3), rel=1e-15)
    h = 1e-6
    central = np.array([(bound.f(x + h * e)[0] - bound.f(x - h * e)[0]) / (2 * h) for e in np.eye(len(x))])
    assert np.max(np.abs(g - central)) < 1e-9
    assert g[0] == 0.0 and g[3] == 0.0
    # The engine's constraints: lo <= d <= hi as two rows c >= 0, their Jacobian that of central differences too.
    problem = design.Problem(None, [(0, k) for k in range(5)], names, np.zeros(5), np.ones(5), design_bounds=[bound])  # type: ignore[arg-type]

    def rows(v: np.ndarray) -> np.ndarray:
        return design.constraints(problem, SimpleNamespace(x=v))[0]  # type: ignore[arg-type]

    c, jac = design.constraints(problem, SimpleNamespace(x=x))  # type: ignore[arg-type]
    assert c == pytest.approx([d - 0.5, 3.0 - d])
    numeric = np.column_stack([(rows(x + h * e) - rows(x - h * e)) / (2 * h) for e in np.eye(len(x))])
    assert np.max(np.abs(jac - numeric)) < 1e-9


def test_the_bound_holds_the_optimum_to_a_frame_shorter_than_the_exact_ones() -> None:
    """The known four-bar's frame is 3.2 long: bounded to at most 3.0 the optimum lies on the bound, with an error
    above 0; without the bound the same start reaches the exact frame."""
    targets = ps.targets()
    bounded = mechfem.optimize(
        ps.four_bar(),
        VARY,
        targets=targets,
        bounds=[mechfem.Bound(FrameLength("A0", "B0"), 1.0, 3.0)],
        rtol=1e-12,
        atol=1e-24,
    )
    frame = math.hypot(bounded.values["B0.x"], bounded.values["B0.y"])
    assert bounded.method == "SLSQP"
    assert frame == pytest.approx(3.0, abs=1e-8)
    assert bounded.objective > 1e-6
    free = mechfem.optimize(ps.four_bar(), VARY, targets=targets, rtol=1e-12, atol=1e-24)
    assert free.objective < 1e-18
    assert math.hypot(free.values["B0.x"], free.values["B0.y"]) == pytest.approx(3.2, abs=1e-8)


def test_a_frame_length_names_fixed_points_that_vary() -> None:
    mech = ps.four_bar()
    with pytest.raises(ValueError, match="not a fixed point"):
        design_bound(mech, FrameLength("A0", "B"), 0.0, 3.0, list(VARY))
    with pytest.raises(ValueError, match="does not vary"):
        design_bound(mech, FrameLength("A0", "B0"), 0.0, 3.0, ["crank.length"])
