"""Path synthesis of a four-bar: SciPy's differential evolution against mechfem's multi-start of exact-gradient
optimisations, on the path-generation problem of docs/optimisation.md (ten points, prescribed timing, seven
variables, the same box; the known optimum has error 0).

SciPy's ``differential_evolution`` (best1bin, popsize 15, its defaults otherwise, ``polish=False`` so that it is
measured alone, seeded) minimises ``synthesis_problem.error``, the closed form in NumPy (inf where the crank cannot
turn fully); its evaluations are counted as mechanism runs. mechfem's ``optimize(..., starts=n, seed=s)`` runs the
same problem from n starts (mechanism runs as it counts them). For each seed: runs, seconds, best error.

    .venv/bin/python benches/bench_differential_evolution.py [--seeds 1 2 3] [--starts 20] [--maxiter 3000]
"""

from __future__ import annotations

import argparse
import sys
import time
import warnings
from pathlib import Path

import numpy as np
from scipy.optimize import differential_evolution

import mechfem

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
sys.path.insert(0, str(HERE.parent / "examples" / "synthesis"))
import path_synthesis as ps  # noqa: E402
import synthesis_problem as sp  # noqa: E402


def run_de(seed: int, maxiter: int) -> tuple[int, float, float]:
    calls = 0

    def f(x: np.ndarray) -> float:
        nonlocal calls
        calls += 1
        e = sp.error(x)
        return e if np.isfinite(e) else 1e6

    t0 = time.perf_counter()
    res = differential_evolution(
        f, list(zip(sp.LOWER, sp.UPPER, strict=True)), seed=seed, maxiter=maxiter, tol=0.0, atol=1e-20, polish=False
    )
    return calls, time.perf_counter() - t0, float(res.fun)


def run_mechfem(seed: int, starts: int) -> tuple[int, float, float]:
    vary: dict[str, tuple[float, float] | None] = {
        n: (lo, hi) for n, lo, hi in zip(ps.NAMES, ps.LOWER, ps.UPPER, strict=True)
    }
    t0 = time.perf_counter()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        opt = mechfem.optimize(ps.four_bar(), vary, targets=ps.targets(), starts=starts, seed=seed)
    runs = sum(s.runs for s in opt.starts)
    return runs, time.perf_counter() - t0, opt.objective


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seeds", type=int, nargs="+", default=[1, 2, 3])
    parser.add_argument("--starts", type=int, default=20)
    parser.add_argument("--maxiter", type=int, default=3000)
    args = parser.parse_args()
    print("| method | seed | mechanism runs | seconds | best error |\n|---|---|---|---|---|")
    for seed in args.seeds:
        runs, seconds, err = run_de(seed, args.maxiter)
        print(f"| SciPy differential_evolution | {seed} | {runs} | {seconds:.1f} | {err:.2e} |", flush=True)
        runs, seconds, err = run_mechfem(seed, args.starts)
        print(f"| mechfem, {args.starts} starts | {seed} | {runs} | {seconds:.1f} | {err:.2e} |", flush=True)


if __name__ == "__main__":
    main()
