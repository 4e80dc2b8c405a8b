"""The usable fraction of a multi-start on the two four-bar benchmarks of docs/optimisation.md: path generation with
prescribed timing (examples/synthesis/path_synthesis.py, its box) and the straight line with free timing
(bench_free_timing.py). For each seed: the starts asked for, the draws of the box looked at to find them (those
that assemble and can do the problem's motion), the starts optimised, the best objective and the time.

    .venv/bin/python benches/bench_multistart.py [--starts 20] [--seeds 1 2 3]
"""

from __future__ import annotations

import argparse
import sys
import time
import warnings
from pathlib import Path

import numpy as np

import mechfem

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
sys.path.insert(0, str(HERE.parent / "examples" / "synthesis"))
import path_synthesis as ps  # noqa: E402
import straight_line as fl  # noqa: E402


def problems() -> dict[str, tuple[mechfem.Mechanism, dict[str, tuple[float, float] | None], dict[str, object]]]:
    path_vary: dict[str, tuple[float, float] | None] = {
        n: (lo, hi) for n, lo, hi in zip(ps.NAMES, ps.LOWER, ps.UPPER, strict=True)
    }
    line_targets = [mechfem.Target("P.x", fl.POINTS[:, 0]), mechfem.Target("P.y", fl.POINTS[:, 1])]
    timing = mechfem.FreeTiming("theta", list(0.5 + np.linspace(0.0, 2.0, 6)))
    return {
        "path generation, 10 points, prescribed timing": (ps.four_bar(), path_vary, {"targets": ps.targets()}),
        "straight line, 6 points, free timing": (
            fl.four_bar(),
            fl.VARY,
            {"targets": line_targets, "timing": timing, "rtol": 1e-12, "atol": 1e-20},
        ),
        "straight line, 6 points, free timing, full turn": (
            fl.four_bar(),
            fl.VARY,
            {"targets": line_targets, "timing": timing, "full_rotation": True, "rtol": 1e-12, "atol": 1e-20},
        ),
    }


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--starts", type=int, default=20)
    parser.add_argument("--seeds", type=int, nargs="+", default=[1, 2, 3])
    args = parser.parse_args()
    print("| problem | seed | starts | draws looked at | usable draws | starts optimised | best objective | seconds |")
    print("|---|---|---|---|---|---|---|---|")
    for name, (mech, vary, kwargs) in problems().items():
        for seed in args.seeds:
            t0 = time.perf_counter()
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                opt = mechfem.optimize(mech, vary, starts=args.starts, seed=seed, **kwargs)  # type: ignore[arg-type]
            used = sum(s.values is not None for s in opt.starts)
            print(
                f"| {name} | {seed} | {len(opt.starts)} | {opt.drawn} | {opt.usable_draws:.0%} | "
                f"{used} ({opt.usable:.0%}) | "
                f"{opt.objective:.2e} | {time.perf_counter() - t0:.0f} |",
                flush=True,
            )


if __name__ == "__main__":
    main()
