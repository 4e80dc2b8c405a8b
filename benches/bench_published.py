"""The classic four-bar path-synthesis benchmarks (examples/synthesis/benchmarks.py: five points with prescribed
timing, six points on a straight line with free timing, eighteen points on a closed curve, the ten-point ellipse),
solved by mechfem's multi-start, SciPy's differential evolution and pylinkage's particle swarm, three seeds each.

* mechfem: ``optimize(..., starts=N, seed=s)`` as ``benchmarks.solve`` states the problem; the error reported is
  the source's objective evaluated on the optimum by ``benchmarks.published_error`` (independent of mechfem), with
  whether the optimum lies within the published ranges and meets the published constraints.
* SciPy's ``differential_evolution`` (best1bin, seeded, ``polish=False``) on the source's own formulation: its
  variables and ranges, its objective plus its penalty (``alpha`` times the constraint violations, as in the
  source), a design whose dyad does not close at a point scoring 1e10; the source's budget: population and
  generations of its ``src/config.py``.
* pylinkage's ``particle_swarm_optimization`` (``--pso``; ``pip install pylinkage``) on the same penalised
  objective and ranges, seeded as in bench_synthesis.py, the same number of evaluations as the source's budget.

    .venv/bin/python benches/bench_published.py [--problems five_points straight_line closed_curve ellipse]
        [--seeds 1 2 3] [--starts N] [--methods mechfem de pso]
"""

from __future__ import annotations

import argparse
import math
import sys
import time
import warnings
from pathlib import Path
from typing import Any

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
sys.path.insert(0, str(HERE.parent / "examples" / "synthesis"))
import benchmarks as bm  # noqa: E402

BUDGET = {"five_points": (50, 100, 1e3), "straight_line": (100, 1000, 1e6), "closed_curve": (50, 100, 1e3)}
BUDGET["ellipse"] = (100, 1000, 1e6)
"""The source's population, generations and penalty factor alpha of each case (its src/config.py)."""
STARTS = {"five_points": 20, "straight_line": 40, "closed_curve": 100, "ellipse": 100}
"""mechfem's starts per problem (``--starts`` sets one number for all)."""


def source_bounds(key: str) -> list[tuple[float, float]]:
    """The source's variables' ranges, in its order: r1..r4, rcx, rcy[, x0, y0, theta0][, crank angles]."""
    b = bm.BENCHMARKS[key]
    out = [(0.0, b.length)] * 4 + [(-b.place, b.place)] * 2
    if not b.frame_fixed:
        out += [(-b.place, b.place)] * 2 + [(0.0, 2.0 * math.pi)]
    if key == "closed_curve":
        out += [(0.0, 2.0 * math.pi)]
    elif b.free:
        out += [(0.0, 2.0 * math.pi)] * len(b.points)
    return out


def source_design(key: str, x: np.ndarray) -> dict[str, Any]:
    b = bm.BENCHMARKS[key]
    d: dict[str, Any] = dict(zip(("r1", "r2", "r3", "r4", "rcx", "rcy"), map(float, x[:6]), strict=True))
    if b.frame_fixed:
        d |= {"x0": 0.0, "y0": 0.0, "theta0": 0.0, "theta2": b.thetas}
    else:
        d |= {"x0": float(x[6]), "y0": float(x[7]), "theta0": float(x[8])}
        d["theta2"] = x[9] + b.thetas if key == "closed_curve" else np.asarray(x[9:])
    return d


def penalised(key: str, x: np.ndarray) -> float:
    """The source's objective plus alpha times its constraint violations; 1e10 where the dyad does not close."""
    b = bm.BENCHMARKS[key]
    d = source_design(key, x)
    if min(d["r1"], d["r2"], d["r3"]) <= 0.0:
        return 1e10
    f = bm.published_error(b, d)
    if not math.isfinite(f):
        return 1e10
    grashof, crank_shortest = bm.grashof(d)
    violations = float(not (grashof and crank_shortest)) if b.crank_shortest else float(not grashof)
    if b.free:
        t = np.asarray(d["theta2"], dtype=float)
        k = int(np.argmin(t))
        shifted = np.concatenate([t[k:], t[:k]])
        violations += float(np.sum(np.diff(shifted) <= 0.0))
    return f + BUDGET[key][2] * violations


def run_mechfem(key: str, seed: int, starts: int) -> dict[str, Any]:
    b = bm.BENCHMARKS[key]
    t0 = time.perf_counter()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        opt = bm.solve(b, starts, seed)
    seconds = time.perf_counter() - t0
    d = bm.published_design(b, opt)
    grashof, crank_shortest = bm.grashof(d)
    return {
        "error": bm.published_error(b, d),
        "objective": opt.objective,
        "usable": opt.usable,
        "usable_draws": opt.usable_draws,
        "runs": sum(s.runs for s in opt.starts),
        "seconds": seconds,
        "in ranges": bm.within_published_ranges(b, d),
        "grashof": grashof,
        "crank shortest": crank_shortest,
        "ordered": bm.ordered(d) if b.free else True,
    }


def run_de(key: str, seed: int) -> dict[str, Any]:
    from scipy.optimize import differential_evolution

    bounds = source_bounds(key)
    population, generations, _ = BUDGET[key]
    calls = 0

    def f(x: np.ndarray) -> float:
        nonlocal calls
        calls += 1
        return penalised(key, x)

    t0 = time.perf_counter()
    res = differential_evolution(
        f, bounds, popsize=max(1, math.ceil(population / len(bounds))), maxiter=generations, seed=seed, polish=False
    )
    return {"error": float(res.fun), "runs": calls, "seconds": time.perf_counter() - t0}


def run_pso(key: str, seed: int) -> dict[str, Any]:
    import bench_synthesis as bs
    import pylinkage as pl

    bounds = source_bounds(key)
    population, generations, _ = BUDGET[key]
    calls = 0

    def fitness(_linkage: object, params: Any, _init: object = None) -> float:
        nonlocal calls
        calls += 1
        return penalised(key, np.asarray(params, dtype=float))

    linkage = bs.ClosedFormFitness(1).linkage
    t0 = time.perf_counter()
    with bs.seeded_default_rng(seed):
        ensemble = pl.particle_swarm_optimization(
            fitness,
            linkage,
            dimensions=len(bounds),
            n_particles=population,
            iterations=generations,
            bounds=([lo for lo, _ in bounds], [hi for _, hi in bounds]),
            order_relation=min,
            verbose=False,
        )
    design = np.asarray(ensemble.dimensions[0], dtype=float)
    return {"error": penalised(key, design), "runs": calls, "seconds": time.perf_counter() - t0}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--problems", nargs="+", default=list(bm.BENCHMARKS))
    parser.add_argument("--seeds", type=int, nargs="+", default=[1, 2, 3])
    parser.add_argument("--starts", type=int, default=None)
    parser.add_argument("--methods", nargs="+", default=["mechfem", "de"])
    args = parser.parse_args()
    print("| problem | method | seed | starts | best error | usable starts | usable draws | runs | seconds | checks |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for key in args.problems:
        for method in args.methods:
            for seed in args.seeds:
                if method == "mechfem":
                    starts = args.starts or STARTS[key]
                    r = run_mechfem(key, seed, starts)
                    checks = ", ".join(k for k in ("in ranges", "grashof", "crank shortest", "ordered") if r[k])
                    print(
                        f"| {key} | mechfem | {seed} | {starts} | {r['error']:.3e} | {r['usable']:.0%} | "
                        f"{r['usable_draws']:.0%} | {r['runs']} | {r['seconds']:.1f} | {checks} |",
                        flush=True,
                    )
                else:
                    r = run_de(key, seed) if method == "de" else run_pso(key, seed)
                    print(
                        f"| {key} | {method} | {seed} | | {r['error']:.3e} | | | {r['runs']} | {r['seconds']:.1f} | |",
                        flush=True,
                    )


if __name__ == "__main__":
    main()
