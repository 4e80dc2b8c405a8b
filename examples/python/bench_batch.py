"""Times a design study of the supply mechanism on one worker thread and on every core.

    .venv/bin/python examples/python/bench_batch.py [--variants 400] [--steps 720] [--repeat 5]

Each variant gives the coupler angle kappa another value and turns the crank once; ``mechfem.sweep``
runs all of them in the compiled core on worker threads with the GIL released. The script prints the
best wall time of ``--repeat`` runs per number of workers with the CPU time it took per second (about the
number of cores that were busy; other programs running at the same time slow the wall time down), and for
comparison one ``Mechanism.run`` per variant in a Python loop. It is a benchmark, not a test: nothing is
asserted about times.
"""

from __future__ import annotations

import argparse
import functools
import math
import os
import resource
import time
from collections.abc import Callable

import numpy as np

import mechfem
from mechfem import Mechanism, Motion

SUPPLY = os.path.join(os.path.dirname(__file__), "..", "supply", "supply.mec")


def stroke(r: mechfem.Analysis) -> float:
    return float(np.ptp(r.output("delta")))


def best_of(repeat: int, fn: Callable[[], object]) -> tuple[float, float]:
    """The best wall time of ``repeat`` calls, and the CPU time (user + system) of that call divided by it:
    about the number of cores that were busy."""
    best = (math.inf, 0.0)
    for _ in range(repeat):
        r0, t = resource.getrusage(resource.RUSAGE_SELF), time.perf_counter()
        fn()
        wall, r1 = time.perf_counter() - t, resource.getrusage(resource.RUSAGE_SELF)
        cpu = (r1.ru_utime - r0.ru_utime) + (r1.ru_stime - r0.ru_stime)
        best = min(best, (wall, cpu / wall))
    return best


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--variants", type=int, default=400)
    parser.add_argument("--steps", type=int, default=720)
    parser.add_argument("--repeat", type=int, default=5)
    args = parser.parse_args()

    base = Mechanism.from_deck(SUPPLY)
    motion = Motion.by(args.steps, 2 * math.pi)
    kappas = np.linspace(-5.30, -5.05, args.variants)
    cores = os.cpu_count() or 1
    print(f"{args.variants} variants of the supply mechanism, {args.steps} steps each, {cores} cores")

    def study(workers: int) -> mechfem.Study:
        return mechfem.sweep(
            base, {"kappa": kappas}, {"stroke": stroke}, motion=motion, workers=workers, progress=False
        )

    reference = study(1)
    assert reference["complete"].all()
    rows = []
    for workers in sorted({1, 2, cores}):
        if workers > cores:
            continue
        assert np.array_equal(study(workers)["stroke"], reference["stroke"])
        rows.append((workers, best_of(args.repeat, functools.partial(study, workers))))

    loop_n = max(1, args.variants // 10)
    loop = best_of(1, lambda: [base.variant(kappa=float(k)).run(motion) for k in kappas[:loop_n]])
    loop = (loop[0] * args.variants / loop_n, loop[1])

    one = rows[0][1][0]
    print(f"{'workers':>8} {'wall [s]':>9} {'variants/s':>11} {'speed-up':>9} {'cpu/wall':>9}")
    for workers, (t, busy) in rows:
        print(f"{workers:>8} {t:>9.3f} {args.variants / t:>11.1f} {one / t:>9.2f} {busy:>9.2f}")
    t, busy = loop
    print(f"{'run()':>8} {t:>9.3f} {args.variants / t:>11.1f} {one / t:>9.2f} {busy:>9.2f}   (one Mechanism.run each)")


if __name__ == "__main__":
    main()
