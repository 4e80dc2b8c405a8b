"""The straight-line problem with free timing (docs/optimisation.md, Free timing): six points on a vertical line,
the crank angles free, A0 and B0 free; a multi-start of ``mechfem.optimize`` for the seeds given.

    .venv/bin/python benches/bench_free_timing.py [--starts 20] [--seeds 1 2 3]

The points, ranges and four-bar are those of ``examples/synthesis/straight_line.py``; here the crank need not turn
fully and the six crank angles start 0.4 rad apart from 0.5 rad.
"""

from __future__ import annotations

import argparse
import sys
import time
import warnings
from pathlib import Path

import numpy as np

import mechfem

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "examples" / "synthesis"))
from straight_line import POINTS, VARY, four_bar  # noqa: E402


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--starts", type=int, default=20)
    parser.add_argument("--seeds", type=int, nargs="+", default=[1, 2, 3])
    args = parser.parse_args()
    targets = [mechfem.Target("P.x", POINTS[:, 0]), mechfem.Target("P.y", POINTS[:, 1])]
    timing = mechfem.FreeTiming("theta", list(0.5 + np.linspace(0.0, 2.0, 6)))
    print("| seed | starts usable | best sum of squared distances | seconds |\n|---|---|---|---|")
    for seed in args.seeds:
        t0 = time.perf_counter()
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            opt = mechfem.optimize(
                four_bar(), VARY, targets=targets, timing=timing, starts=args.starts, seed=seed, rtol=1e-12, atol=1e-20
            )
        usable = sum(s.values is not None for s in opt.starts)
        print(f"| {seed} | {usable} of {len(opt.starts)} | {opt.objective:.2e} | {time.perf_counter() - t0:.0f} |")


if __name__ == "__main__":
    main()
