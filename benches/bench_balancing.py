"""Balancing a slider-crank: mechfem's OPTIMISE block of a DYN ANA deck (SLSQP with the exact design sensitivities
of inverse dynamics) against SciPy's differential evolution and pylinkage's particle swarm on the same objective,
the RMS shaking force over one turn of examples/balancing/slider_crank_balance.mec as a function of the crank's
centre of mass (u, v) in the deck's box [-0.2, 0.2]^2.

SciPy's ``differential_evolution`` (best1bin, popsize 15, its defaults otherwise, ``polish=False`` so that it is
measured alone, seeded) and, with ``--pso``, pylinkage's ``particle_swarm_optimization`` (30 particles, the
population differential evolution has for two variables, and ``--pso-iterations`` iterations, seeded as in
bench_synthesis.py; it needs pylinkage, which ``make bench`` installs into .venv-bench) evaluate the same mechanism
runs (``_core.DynamicDesignModel``, its values only); every evaluation is counted as a mechanism run. For each: runs,
seconds, the (u, v) found, its distance from the closed form's ``u = -r (m_A + m_rec / 2) / m_1``, ``v = 0``, and the
RMS shaking force.

    .venv/bin/python benches/bench_balancing.py [--seeds 1 2 3] [--maxiter 1000] [--pso] [--pso-iterations 40]
"""

from __future__ import annotations

import argparse
import os
import time
from pathlib import Path

import numpy as np
from scipy.optimize import differential_evolution

from mechfem import _core
from mechfem.design import optimise_deck

DECK = Path(__file__).resolve().parent.parent / "examples" / "balancing" / "slider_crank_balance.mec"
R, L, A, M_CRANK, M_ROD, M_PISTON = 0.1, 0.35, 0.1, 2.0, 1.2, 1.5
U_CLOSED = -R * (M_ROD * (L - A) / L + (M_PISTON + M_ROD * A / L) / 2) / M_CRANK


def rms_model() -> _core.DynamicDesignModel:
    """The deck's designs by the crank's centre (u, v), the shaking force's x and y recorded."""
    text = DECK.read_text()
    return _core.DynamicDesignModel(text, os.fspath(DECK), os.fspath(DECK.parent), [(11, 1), (12, 1)], [3, 4], [])


def run_de(seed: int, maxiter: int) -> tuple[int, float, np.ndarray, float]:
    model = rms_model()

    t0 = time.perf_counter()
    res = differential_evolution(
        lambda x: rms(model, x), [(-0.2, 0.2)] * 2, seed=seed, maxiter=maxiter, tol=1e-12, polish=False
    )
    return int(model.runs), time.perf_counter() - t0, np.asarray(res.x), float(res.fun)


def rms(model: _core.DynamicDesignModel, x: np.ndarray) -> float:
    """The RMS shaking force of the design ``x`` = (u, v); 1e12 for one that cannot be evaluated."""
    d = model.evaluate([float(v) for v in x])
    v = d.values
    return float(np.sqrt(np.mean(v[:, 0] ** 2 + v[:, 1] ** 2))) if d.feasible else 1e12


def run_pso(seed: int, iterations: int) -> tuple[int, float, np.ndarray, float]:
    import bench_synthesis as bs
    import pylinkage as pl

    model = rms_model()

    def fitness(_linkage: object, params: list[float], _init: object = None) -> float:
        return rms(model, np.clip(np.asarray(params, dtype=float), -0.2, 0.2))

    t0 = time.perf_counter()
    with bs.seeded_default_rng(seed):
        ensemble = pl.particle_swarm_optimization(
            fitness,
            bs.ClosedFormFitness(1).linkage,
            dimensions=2,
            n_particles=30,
            iterations=iterations,
            bounds=([-0.2, -0.2], [0.2, 0.2]),
            order_relation=min,
            verbose=False,
        )
    x = np.clip(np.asarray(ensemble.dimensions[0], dtype=float), -0.2, 0.2)
    seconds = time.perf_counter() - t0
    return int(model.runs), seconds, x, rms(model, x)


def run_mechfem() -> tuple[int, float, np.ndarray, float, int]:
    t0 = time.perf_counter()
    outcome = optimise_deck.optimise(DECK, optimise_deck.describe(DECK).optimise)
    s = outcome
    return s.runs, time.perf_counter() - t0, np.asarray(s.x), s.objective, len(s.history) - 1


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--seeds", type=int, nargs="+", default=[1, 2, 3])
    parser.add_argument("--maxiter", type=int, default=1000)
    parser.add_argument("--pso", action="store_true", help="pylinkage's particle swarm too (in .venv-bench)")
    parser.add_argument("--pso-iterations", type=int, default=40)
    args = parser.parse_args()
    if args.pso:
        from bench_peers import PEERS
        from benchenv import ensure_venv

        ensure_venv(PEERS, ".peers-stamp")
    print(f"closed form: u = {U_CLOSED:.10f} m, v = 0")
    print(f"{'method':<28} {'runs':>7} {'seconds':>8} {'u (m)':>14} {'v (m)':>12} {'|x - x*|':>10} {'RMS (N)':>12}")
    runs, secs, x, f, iterations = run_mechfem()
    err = float(np.hypot(x[0] - U_CLOSED, x[1]))
    label = f"mechfem SLSQP ({iterations} it.)"
    print(f"{label:<28} {runs:>7} {secs:>8.3f} {x[0]:>14.10f} {x[1]:>12.2e} {err:>10.2e} {f:>12.6f}")
    for seed in args.seeds:
        runs, secs, x, f = run_de(seed, args.maxiter)
        err = float(np.hypot(x[0] - U_CLOSED, x[1]))
        label = f"SciPy DE (seed {seed})"
        print(f"{label:<28} {runs:>7} {secs:>8.3f} {x[0]:>14.10f} {x[1]:>12.2e} {err:>10.2e} {f:>12.6f}")
    for seed in args.seeds if args.pso else []:
        runs, secs, x, f = run_pso(seed, args.pso_iterations)
        err = float(np.hypot(x[0] - U_CLOSED, x[1]))
        label = f"pylinkage swarm (seed {seed})"
        print(f"{label:<28} {runs:>7} {secs:>8.3f} {x[0]:>14.10f} {x[1]:>12.2e} {err:>10.2e} {f:>12.6f}")


if __name__ == "__main__":
    main()
