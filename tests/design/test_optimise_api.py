"""mechfem.optimize and Analysis.sensitivity: the supply mechanism's coupler angle, path and function generation."""

from __future__ import annotations

import importlib.util
import math
import sys
from pathlib import Path

import numpy as np
import pytest

import mechfem
from mechfem import Q

ROOT = Path(__file__).resolve().parents[2]


def _example(name: str):  # type: ignore[no-untyped-def]
    path = ROOT / "examples" / "synthesis" / f"{name}.py"
    spec = importlib.util.spec_from_file_location(name, path)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.modules[name] = module
    spec.loader.exec_module(module)
    return module


def supply(kappa: float = -5.25) -> mechfem.Mechanism:
    return mechfem.Mechanism.from_deck(ROOT / "examples" / "supply" / "supply.mec").variant(kappa=kappa)


def test_supply_coupler_angle_at_the_dead_positions() -> None:
    seen: list[float] = []
    opt = mechfem.optimize(
        supply(),
        {"kappa": (-5.5, -5.0)},
        targets=[mechfem.TargetExtremum(Q("delta", 2), "delta", 0.0)],
        progress=lambda it: seen.append(it.objective),
    )
    # The theory prints kappa = -5.17514 for this design.
    assert abs(opt.values["kappa"] - (-5.17514)) < 2e-4
    assert opt.start == {"kappa": -5.25}
    assert opt.objective < 1e-6 * opt.start_objective
    assert seen[0] == opt.start_objective and len(seen) == len(opt.history)
    tf2 = opt.run().output("delta", 2)
    # Both dead-position values are tiny next to the largest second-order transfer function.
    assert math.sqrt(opt.objective) < 0.01 * np.abs(tf2).max()
    assert opt.runs < 60


def test_sensitivity_against_central_differences() -> None:
    m = supply(-5.2)
    r = m.run()
    names = ["kappa", "B0.x", "rod.length"]
    s = r.sensitivity(Q("delta", 2), names)
    assert s.shape == (r.positions, 3)
    for k, name in enumerate(names):
        start = m[name].value
        h = 1e-5 * max(1.0, abs(start))
        plus = m.variant({name: start + h}).run().output("delta", 2)
        minus = m.variant({name: start - h}).run().output("delta", 2)
        fd = (plus - minus) / (2 * h)
        assert np.allclose(fd, s[:, k], rtol=1e-5, atol=1e-5 * np.abs(s[:, k]).max()), name
    one = r.sensitivity("A.x", "crank.length")
    assert one.shape == (r.positions,)


def test_path_generation_reaches_the_known_four_bar() -> None:
    ps = _example("path_synthesis")
    opt = ps.synthesise()
    assert opt.objective < 1e-16
    assert opt.values["B0.x"] == pytest.approx(3.2, abs=1e-7)
    assert opt.values["coupler.u"] == pytest.approx(1.8 * math.cos(0.6), abs=1e-7)
    assert opt.runs < 40
    # The optimised mechanism passes the points at the crank angles.
    r = opt.run()
    pts = np.column_stack([r.x("P"), r.y("P")])[:: ps.SUBSTEPS]
    assert np.abs(pts - ps.known_points()).max() < 1e-7


def test_function_generation_follows_the_logarithm() -> None:
    fg = _example("function_generation")
    opt = fg.synthesise()
    rms = math.degrees(math.sqrt(opt.objective / (fg.STEPS + 1)))
    assert rms < 0.5
    assert opt.objective < 1e-3 * opt.start_objective
    r = opt.run()
    assert np.abs(r.output("phi") - fg.wanted()).max() < math.radians(1.0)
    # The optimum says how far its one target is left, and where: as the optimised mechanism's run shows.
    left = np.abs(r.output("phi") - fg.wanted())
    ((largest, where),) = opt.misses
    assert largest == pytest.approx(left.max(), rel=1e-9) and where == int(np.argmax(left))


def test_bounds_and_minimise_with_slsqp() -> None:
    # Keep the output's first-order transfer function within a band while making its rms second order small.
    opt = mechfem.optimize(
        supply(-5.2),
        {"kappa": (-5.5, -5.0)},
        minimize=("rms", Q("delta", 2)),
        bounds=[mechfem.Bound(Q("delta", 1), -2.0, 2.0)],
        steps=50,
    )
    assert opt.method == "SLSQP"
    r = opt.run()
    assert np.all(np.abs(r.output("delta", 1)) <= 2.0 + 1e-6)
    assert opt.objective <= opt.start_objective


def test_python_objective_with_its_gradient() -> None:
    q = Q("delta", 2)

    def f(e: mechfem.Evaluated) -> tuple[float, np.ndarray]:
        v, g = e.value(q), e.gradient(q)
        return float(v @ v), 2 * v @ g

    opt = mechfem.optimize(supply(-5.2), {"kappa": (-5.5, -5.0)}, objective=f, quantities=[q], steps=50)
    assert opt.objective <= opt.start_objective


def test_mistakes_are_named() -> None:
    m = supply()
    with pytest.raises(ValueError, match="moves"):
        mechfem.optimize(m, {"A.x": (0, 1)}, targets=[mechfem.TargetAt("delta", 0, 1.0)])
    with pytest.raises(ValueError, match="outside its range"):
        mechfem.optimize(m, {"kappa": (-5.1, -5.0)}, targets=[mechfem.TargetAt("delta", 0, 1.0)])
    with pytest.raises(ValueError, match="nothing to optimise"):
        mechfem.optimize(m, {"kappa": (-5.5, -5.0)})
    with pytest.raises(TypeError, match="is a point"):
        mechfem.optimize(m, {"A0": (0, 1)}, targets=[mechfem.TargetAt("delta", 0, 1.0)])
    # SciPy counts iterations in 32 bits: 2**31 would wrap round and stop at once.
    with pytest.raises(ValueError, match="steps must be from 1 to 2147483647"):
        mechfem.optimize(m, {"kappa": (-5.5, -5.0)}, targets=[mechfem.TargetAt("delta", 0, 1.0)], steps=2**31)


def test_an_infeasible_start_is_an_error_and_an_infeasible_step_is_not() -> None:
    m = supply()
    with pytest.raises(mechfem.Infeasible, match="start design"):
        mechfem.optimize(
            m.variant({"crank.length": 3.0}), {"crank.length": (0.1, 5.0)}, targets=[mechfem.TargetAt("delta", 0, 1.0)]
        )
    # The output's swing grows with the crank until, past a crank of about 0.541, the motion cannot be completed in the
    # branch it starts in: the optimiser meets such designs and steps back from them.

    def swing(e: mechfem.Evaluated) -> tuple[float, np.ndarray]:
        v, g = e.value("delta"), e.gradient("delta")
        i, k = int(np.argmax(v)), int(np.argmin(v))
        return -(v[i] - v[k]), -(g[i] - g[k])

    opt = mechfem.optimize(m, {"crank.length": (0.1, 5.0)}, objective=swing, quantities=["delta"], steps=40)
    assert 0.53 < opt.values["crank.length"] < 0.55
    assert opt.infeasible > 0 and opt.runs > opt.infeasible
    # The design returned is one that runs through the whole motion.
    assert opt.run().complete
