"""Path synthesis of a four-bar: SciPy's differential evolution against mechfem's multi-start of exact-gradient
optimisations, on the two four-bar problems of docs/optimisation.md: path generation (ten points, prescribed timing,
seven variables, the known optimum has error 0) and the straight line (six points, free timing and a crank that
turns fully, fifteen variables: A0, B0, the three lengths, u, v and the six crank angles), each in the box mechfem
draws its starts from.

SciPy's ``differential_evolution`` (best1bin, popsize 15, its defaults otherwise, ``polish=False`` so that it is
measured alone, seeded) minimises the closed form in NumPy (``synthesis_problem``: a design whose crank cannot turn
fully scores 1e6); its evaluations are counted as mechanism runs. mechfem's ``optimize(..., starts=n, seed=s)`` runs the
same problem from n starts (mechanism runs as it counts them). For each seed: runs, seconds, best error.

    .venv/bin/python benches/bench_differential_evolution.py [--seeds 1 2 3] [--starts 20] [--maxiter 3000]
        [--problems path line] [--methods de mechfem]
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
import straight_line as sl  # noqa: E402
import synthesis_problem as sp  # noqa: E402


def line_error(z: np.ndarray) -> float:
    """The straight line in closed form: z = A0 (2), B0 (2), crank, coupler, rocker, u, v, six crank angles."""
    a0 = z[:2]
    design = np.array([z[2] - a0[0], z[3] - a0[1], *z[4:9]])
    if not sp.full_turn(design):
        return np.inf
    p = sp.coupler_points(design, z[9:]) + a0
    return float(np.sum((p - sl.POINTS) ** 2))


PROBLEMS = {
    "path": (sp.error, list(zip(sp.LOWER, sp.UPPER, strict=True))),
    "line": (line_error, [v for v in sl.VARY.values() if v is not None] + [(0.0, 2.0 * np.pi)] * 6),
}


def run_de(problem: str, seed: int, maxiter: int) -> tuple[int, float, float]:
    error, box = PROBLEMS[problem]
    calls = 0

    def f(x: np.ndarray) -> float:
        nonlocal calls
        calls += 1
        e = error(x)
        return e if np.isfinite(e) else 1e6

    t0 = time.perf_counter()
    res = differential_evolution(f, box, seed=seed, maxiter=maxiter, tol=0.0, atol=1e-20, polish=False)
    return calls, time.perf_counter() - t0, float(res.fun)


def run_mechfem(problem: str, seed: int, starts: int) -> tuple[int, float, float]:
    t0 = time.perf_counter()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        if problem == "path":
            vary: dict[str, tuple[float, float] | None] = {
                n: (lo, hi) for n, lo, hi in zip(ps.NAMES, ps.LOWER, ps.UPPER, strict=True)
            }
            opt = mechfem.optimize(ps.four_bar(), vary, targets=ps.targets(), starts=starts, seed=seed)
        else:
            opt = sl.synthesise(starts=starts, seed=seed, steps=200)
    runs = sum(s.runs for s in opt.starts)
    return runs, time.perf_counter() - t0, opt.objective


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seeds", type=int, nargs="+", default=[1, 2, 3])
    parser.add_argument("--starts", type=int, default=20)
    parser.add_argument("--maxiter", type=int, default=3000)
    parser.add_argument("--problems", nargs="+", default=["path", "line"], choices=sorted(PROBLEMS))
    parser.add_argument("--methods", nargs="+", default=["de", "mechfem"], choices=["de", "mechfem"])
    args = parser.parse_args()
    print("| problem | method | seed | mechanism runs | seconds | best error |\n|---|---|---|---|---|---|")
    for problem in args.problems:
        for seed in args.seeds:
            if "de" in args.methods:
                runs, seconds, err = run_de(problem, seed, args.maxiter)
                row = f"| {problem} | SciPy differential_evolution | {seed} | {runs} | {seconds:.1f} | {err:.2e} |"
                print(row, flush=True)
            if "mechfem" not in args.methods:
                continue
            runs, seconds, err = run_mechfem(problem, seed, args.starts)
            print(
                f"| {problem} | mechfem, {args.starts} starts | {seed} | {runs} | {seconds:.1f} | {err:.2e} |",
                flush=True,
            )


if __name__ == "__main__":
    main()
