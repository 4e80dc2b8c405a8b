"""Times a design study of the four-bar locally and on a Dask cluster, and the overhead of a chunk.

    .venv/bin/python benches/bench_cluster.py [--variants 100000] [--steps 360] [--workers 2] [--chunk-size N]
    .venv/bin/python benches/bench_cluster.py --quick              # 10 000 variants
    .venv/bin/python benches/bench_cluster.py --scheduler tcp://scheduler:8786   # a running cluster instead

The study: ``--variants`` lengths of the rocker of a four-bar (crank 1, coupler 3.5, ground 4, rocker 2.6 to 3.4),
each run through one turn of the crank in ``--steps`` steps (360: 361 positions) with the first-order transfer
functions, and the stroke of the rocker measured in Python from each variant's Analysis.

Timed, wall clock:

* locally: ``mechfem.sweep`` on ``--workers`` threads of this process (``executor=None``);
* on the cluster: the same sweep with ``executor=client`` (a ``LocalCluster`` of ``--workers`` worker processes of
  one thread each, started before the clock, or the scheduler given), in chunks of ``--chunk-size`` (default: the
  sweep's own choice, about a second of one core each).

The overhead of a chunk is measured apart: a study of ``--small`` variants sent as one-variant chunks, less the
same study's time in one chunk, divided by the chunks each worker thread handled. The two tables are checked to
be equal. Nothing here asserts a time: it is a benchmark, not a test.
"""

from __future__ import annotations

import argparse
import math
import os
import platform
import time
from typing import Any

import numpy as np

import mechfem
from mechfem import Driven, Mechanism, Motion, Output


def fourbar() -> Mechanism:
    m = Mechanism("fourbar")
    A0, B0 = m.fixed("A0", 0.0, 0.0), m.fixed("B0", 4.0, 0.0)
    A, B = m.point("A", 1.0, 0.0), m.point("B", 3.5, 2.5)
    m.bar("crank", A0, A, length=1.0, angle=Driven(start=0.0, name="phi"))
    m.bar("coupler", A, B, length=3.5)
    m.bar("rocker", B0, B, length=3.0, angle=Output("psi"))
    return m


def stroke(r: mechfem.Analysis) -> float:
    return float(np.ptp(r.output("psi")))


def study(n: int, steps: int, **kw: Any) -> tuple[mechfem.Study, float]:
    lengths = {"rocker.length": np.linspace(2.6, 3.4, n)}
    t0 = time.perf_counter()
    s = mechfem.sweep(fourbar(), lengths, {"stroke": stroke}, motion=Motion.by(steps, 2 * math.pi), order=1, **kw)
    return s, time.perf_counter() - t0


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--variants", type=int, default=100_000)
    ap.add_argument("--quick", action="store_true", help="10 000 variants")
    ap.add_argument("--steps", type=int, default=360)
    ap.add_argument("--workers", type=int, default=2, help="threads locally, worker processes on the LocalCluster")
    ap.add_argument("--chunk-size", type=int, default=None)
    ap.add_argument("--small", type=int, default=200, help="variants of the chunk-overhead study")
    ap.add_argument("--scheduler", default=None, help="address of a running Dask scheduler (default: a LocalCluster)")
    args = ap.parse_args()
    n = 10_000 if args.quick else args.variants

    from distributed import Client, LocalCluster

    print(f"{platform.processor() or platform.machine()}, {os.cpu_count()} cores, mechfem {mechfem.__version__}")
    print(f"{n} variants of the four-bar, {args.steps + 1} positions each")
    local, t_local = study(n, args.steps, workers=args.workers, progress=False)
    print(f"locally, {args.workers} threads:       {t_local:8.2f} s  {n / t_local:9.0f} variants/s")

    cluster = None
    if args.scheduler:
        client = Client(args.scheduler)
    else:
        cluster = LocalCluster(
            n_workers=args.workers, processes=True, threads_per_worker=1, dashboard_address=":0", silence_logs=40
        )
        client = Client(cluster)
    try:
        client.wait_for_workers(1)
        slots = sum(client.nthreads().values())
        # Warm up: every worker imports mechfem once.
        study(2 * slots, 8, executor=client, chunk_size=1, progress=False)
        remote, t_remote = study(n, args.steps, executor=client, chunk_size=args.chunk_size, progress=False)
        size = mechfem.studies.cluster.chunk_size(n, args.steps + 1, client, args.chunk_size)
        chunks = math.ceil(n / size)
        where = args.scheduler or f"LocalCluster of {args.workers} processes x 1 thread"
        print(f"on the cluster ({where}), {chunks} chunks of {size}:")
        print(f"                                {t_remote:8.2f} s  {n / t_remote:9.0f} variants/s")
        for name, col in local.columns.items():
            same = list(col) == list(remote[name]) if col.dtype == object else np.array_equal(col, remote[name])
            assert same, f"the tables differ in {name}"
        print("tables equal: yes")

        m = args.small
        _, t_one = study(m, args.steps, executor=client, chunk_size=math.ceil(m / slots), progress=False)
        _, t_many = study(m, args.steps, executor=client, chunk_size=1, progress=False)
        overhead = (t_many - t_one) / (m / slots - 1)
        print(f"overhead of a chunk:            {1e3 * overhead:8.2f} ms  ({m} one-variant chunks vs {slots} chunks)")
        print(f"overhead of the study's chunks: {100 * overhead * chunks / slots / t_remote:8.2f} % of its time")
    finally:
        client.close()
        if cluster is not None:
            cluster.close()


if __name__ == "__main__":
    main()
