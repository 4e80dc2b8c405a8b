"""Path synthesis of a four-bar: pylinkage's particle swarm against mechfem's gradient method, on one problem.

    .venv/bin/python benches/bench_synthesis.py [--repeats 3] [--seed 1] [--particles 100] [--iterations 200]

The problem is the one of ``synthesis_problem.py`` beside this script: a crank-rocker with prescribed timing, ten
target points of its coupler point at crank angles 0, 36, ..., 324 degrees, seven design variables (the frame pivot
B0, the crank, coupler and rocker lengths, the coupler point (u, v)), A0 fixed at the origin, the known optimum
with error 0 (the four-bar of ``bench_peers.py``), a start box and a start design. Every method is scored by the
same closed-form error (``synthesis_problem.error``) of the design it returns.

pylinkage (``pip install pylinkage``; measured with 1.3.0) is run as its users run it:
``pylinkage.particle_swarm_optimization(eval_func, linkage, dimensions=7, bounds=box, order_relation=min, ...)``,
its own local-best PSO in NumPy, with the fitness computed on pylinkage's own model of the four-bar
(``pylinkage.simulation.Linkage`` of ``Ground`` A0 and B0, a ``Crank``, an ``RRRDyad`` for the rocker pin B and a
``FixedDyad`` for the coupler point P). pylinkage's driver passes the fitness only the link lengths as its
"constraints" and keeps the ground pivots where they started, so the fitness function (``PylinkageFitness``)
places B0 itself (``Ground.set_coord``) and sets the crank radius, the dyad's two lengths and the coupler point's
polar offset (``Linkage.set_constraints``). Prescribed timing is exact in pylinkage: a ``Crank`` turns by
``angular_velocity`` per step from where it is set, so the crank is set at theta_0 - delta and stepped by delta =
36 / ``--substeps`` degrees through one full turn (``Linkage.step``), and every ``--substeps``-th frame is a
prescribed crank angle (to rounding). The sub-steps keep the ``RRRDyad`` on its branch: it takes the intersection
nearest the previous one, so B is started far on the left of A->B0 (branch +1, as in the problem) and followed in
small steps; a design that cannot be assembled somewhere in the turn raises ``UnbuildableError`` and scores inf,
as the closed form does when the crank cannot make a full turn. Before timing, the script checks that this
fitness agrees with the closed form on the start, the optimum and random designs of the box. With ``--model
closed-form`` the PSO driver evaluates ``synthesis_problem.error`` instead (the same problem, without pylinkage's
simulation cost).

pylinkage's PSO draws its random numbers from ``numpy.random.default_rng()`` with no seed and takes none; the
script makes a run reproducible by handing it a generator seeded with ``--seed`` (``seeded_default_rng``), the
repeats using seed, seed + 1, ... Runs are mechanism runs: fitness evaluations, each one simulation of the four-bar
(particles x (iterations + 1) for the PSO). Seconds are the wall time of the whole optimisation on one core.

The mechfem row comes from ``run_mechfem`` below (``mechfem.optimize`` on the four-bar of
``examples/synthesis/path_synthesis.py``). Nothing here asserts a time or an error: it is a benchmark, not a test.
"""

from __future__ import annotations

import argparse
import contextlib
import math
import statistics
import sys
import time
from collections.abc import Iterator
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

import synthesis_problem as sp  # noqa: E402

try:
    import pylinkage as pl
    from pylinkage.exceptions import UnbuildableError
except ImportError:  # pragma: no cover - a message instead of a traceback
    sys.exit("pylinkage is not installed: .venv/bin/pip install pylinkage")


# mechfem ---------------------------------------------------------------------------------------------------------


def run_mechfem(problem: sp.Problem) -> dict[str, float]:
    """mechfem's gradient method on ``problem``: ``mechfem.optimize`` (trust-region least squares with the exact
    design sensitivities) on the four-bar of ``examples/synthesis/path_synthesis.py``, started from
    ``problem.start`` within ``problem.lower`` .. ``problem.upper``, its coupler point compared with
    ``problem.targets`` at ``problem.thetas`` (the motion has 9 positions between two of them, not compared, which
    keep every run on its branch). Runs are mechanism runs: one run of the motion with the sensitivities."""
    sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "examples" / "synthesis"))
    import path_synthesis as ps

    import mechfem

    if not np.allclose(problem.thetas, ps.THETAS):
        raise ValueError("the mechfem model turns the crank through the angles of path_synthesis.THETAS")
    n = ps.SUBSTEPS * (len(problem.thetas) - 1) + 1
    targets = []
    for k, name in enumerate(("P.x", "P.y")):
        values = np.full(n, np.nan)
        values[:: ps.SUBSTEPS] = problem.targets[:, k]
        targets.append(mechfem.Target(name, values))
    vary = {name: (float(lo), float(hi)) for name, lo, hi in zip(ps.NAMES, problem.lower, problem.upper, strict=True)}
    import scipy.optimize  # noqa: F401  (loaded once per session, as in a user's; not part of the timing)

    t0 = time.perf_counter()
    opt = mechfem.optimize(ps.four_bar(tuple(problem.start)), vary, targets=targets)
    seconds = time.perf_counter() - t0
    design = np.array([opt.values[name] for name in ps.NAMES])
    return {"runs": opt.runs, "seconds": seconds, "error": opt.objective, "design": design}


# pylinkage -------------------------------------------------------------------------------------------------------


class PylinkageFitness:
    """The problem's error computed on pylinkage's model of the four-bar, counting its calls (mechanism runs)."""

    def __init__(self, substeps: int) -> None:
        thetas = sp.THETAS
        spacing = np.diff(thetas)
        if not np.allclose(spacing, spacing[0]) or not math.isclose(spacing[0] * len(thetas), 2 * math.pi):
            raise ValueError("the crank angles must be equally spaced over one turn")
        self.substeps = substeps
        self.delta = float(spacing[0]) / substeps
        self.theta0 = float(thetas[0])
        self.frames = len(thetas) * substeps + 1  # the full turn, back to theta_0
        self.calls = 0
        x_b0, y_b0, a, b, c, u, v = sp.START
        self.a0 = pl.Ground(0.0, 0.0, name="A0")
        self.b0 = pl.Ground(x_b0, y_b0, name="B0")
        self.crank = pl.Crank(self.a0, a, angular_velocity=self.delta, initial_angle=self.theta0, name="A")
        self.rocker = pl.RRRDyad(self.crank.output, self.b0, b, c, name="B")
        self.point = pl.FixedDyad(self.crank.output, self.rocker, math.hypot(u, v), math.atan2(v, u), name="P")
        self.linkage = pl.Linkage([self.a0, self.b0, self.crank, self.rocker, self.point], name="four-bar")
        self.p_index = 4

    def set_design(self, design: np.ndarray) -> None:
        """B0, the lengths and the coupler point; the crank set one step before theta_0 and B far on the left of
        A->B0, so that the first step puts the crank at theta_0 and the dyad on branch +1."""
        x_b0, y_b0, a, b, c, u, v = (float(x) for x in design)
        self.b0.set_coord(x_b0, y_b0)
        self.linkage.set_constraints([a, b, c, math.hypot(u, v), math.atan2(v, u)])
        angle = self.theta0 - self.delta
        ax, ay = a * math.cos(angle), a * math.sin(angle)
        self.crank.set_coord(ax, ay)
        dx, dy = x_b0 - ax, y_b0 - ay
        d = math.hypot(dx, dy) or 1.0
        far = sp.BRANCH * (b + c)
        self.rocker.set_coord((ax + x_b0) / 2 - far * dy / d, (ay + y_b0) / 2 + far * dx / d)

    def coupler_points(self, design: np.ndarray) -> np.ndarray | None:
        """P at the prescribed crank angles from pylinkage's simulation of one turn; None if unbuildable."""
        self.set_design(design)
        try:
            frames = list(self.linkage.step(iterations=self.frames))
        except UnbuildableError:
            return None
        return np.array([frames[k * self.substeps][self.p_index] for k in range(len(sp.THETAS))], dtype=float)

    def error(self, design: np.ndarray) -> float:
        p = self.coupler_points(design)
        if p is None:
            return math.inf
        e = float(np.sum((p - sp.TARGETS) ** 2))
        return e if math.isfinite(e) else math.inf

    def __call__(self, linkage: object, params: list[float], init_pos: object = None) -> float:
        """pylinkage's ``eval_func(linkage, params, init_pos)``: params are the seven design variables."""
        self.calls += 1
        return self.error(np.asarray(params, dtype=float))


class ClosedFormFitness(PylinkageFitness):
    """The closed-form error of synthesis_problem, through the same driver (``--model closed-form``)."""

    def __call__(self, linkage: object, params: list[float], init_pos: object = None) -> float:
        self.calls += 1
        return sp.error(np.asarray(params, dtype=float))


def check_model(fitness: PylinkageFitness, samples: int, seed: int) -> tuple[int, int, float]:
    """pylinkage's fitness against the closed form on the start, the optimum and ``samples`` random designs of the
    box: (designs where both are finite, designs where only one is, largest relative difference of the finite)."""
    rng = np.random.default_rng(seed)
    designs = [sp.START, sp.OPTIMUM, *rng.uniform(sp.LOWER, sp.UPPER, size=(samples, len(sp.NAMES)))]
    both, one, worst = 0, 0, 0.0
    for design in designs:
        mine, ref = fitness.error(design), sp.error(design)
        if math.isfinite(mine) and math.isfinite(ref):
            both += 1
            worst = max(worst, abs(mine - ref) / max(ref, 1e-12) if ref > 1e-12 else abs(mine - ref))
        elif math.isfinite(mine) != math.isfinite(ref):
            one += 1
    return both, one, worst


@contextlib.contextmanager
def seeded_default_rng(seed: int) -> Iterator[None]:
    """``numpy.random.default_rng()`` without a seed returns a generator seeded with ``seed`` while in the block
    (pylinkage's PSO takes no seed of its own)."""
    real = np.random.default_rng

    def default_rng(s: object = None) -> np.random.Generator:
        return real(seed if s is None else s)

    np.random.default_rng = default_rng
    try:
        yield
    finally:
        np.random.default_rng = real


def run_pso(args: argparse.Namespace, seed: int) -> dict[str, object]:
    cls = ClosedFormFitness if args.model == "closed-form" else PylinkageFitness
    fitness = cls(args.substeps)
    center = sp.START if args.center == "start" else None
    with seeded_default_rng(seed):
        t = time.perf_counter()
        ensemble = pl.particle_swarm_optimization(
            fitness,
            fitness.linkage,
            center=center,
            dimensions=len(sp.NAMES),
            n_particles=args.particles,
            iterations=args.iterations,
            inertia=args.inertia,
            leader=args.leader,
            follower=args.follower,
            neighbors=args.neighbors,
            bounds=(sp.LOWER.tolist(), sp.UPPER.tolist()),
            order_relation=min,
            verbose=False,
        )
        seconds = time.perf_counter() - t
    design = np.asarray(ensemble.dimensions[0], dtype=float)
    return {
        "runs": fitness.calls,
        "seconds": seconds,
        "error": sp.error(design),
        "pso_score": float(ensemble.scores["score"][0]),
        "distance": float(np.linalg.norm(design - sp.OPTIMUM)),
        "design": design,
        "seed": seed,
    }


# the table -------------------------------------------------------------------------------------------------------


def row(name: str, runs: float, seconds: float, error: float, note: str = "") -> str:
    return f"{name:<28} {runs:>10.0f} {seconds:>10.3f} {error:>12.4e}  {note}"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=3, help="PSO runs, with seeds seed, seed + 1, ...")
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--particles", type=int, default=100)
    parser.add_argument("--iterations", type=int, default=200)
    parser.add_argument("--inertia", type=float, default=0.6, help="w (pylinkage's default)")
    parser.add_argument("--leader", type=float, default=3.0, help="c1, cognitive (pylinkage's default)")
    parser.add_argument("--follower", type=float, default=0.1, help="c2, social (pylinkage's default)")
    parser.add_argument("--neighbors", type=int, default=17, help="ring neighbourhood (pylinkage's default)")
    parser.add_argument(
        "--center",
        choices=["box", "start"],
        default="box",
        help="the swarm's start: uniform in the box, or around the start design",
    )
    parser.add_argument(
        "--model",
        choices=["pylinkage", "closed-form"],
        default="pylinkage",
        help="the fitness: pylinkage's simulation of the four-bar, or synthesis_problem.error",
    )
    parser.add_argument("--substeps", type=int, default=10, help="crank steps between two prescribed angles")
    args = parser.parse_args()

    np.set_printoptions(precision=5, suppress=True)
    print(f"pylinkage {pl.__version__}, numpy {np.__version__}, Python {sys.version.split()[0]}")
    print(
        f"problem: {len(sp.THETAS)} points, crank angles every {np.rad2deg(sp.THETAS[1] - sp.THETAS[0]):g} deg, "
        f"variables {', '.join(sp.NAMES)}; start error {sp.error(sp.START):.4f}, optimum error 0"
    )
    if args.model == "pylinkage":
        both, one, worst = check_model(PylinkageFitness(args.substeps), 500, args.seed)
        print(
            f"pylinkage's model against the closed form on 502 designs: {both} assemble in both, {one} in only "
            f"one, largest relative difference {worst:.1e}"
        )
    print(
        f"PSO: {args.particles} particles, {args.iterations} iterations, w {args.inertia}, c1 {args.leader}, "
        f"c2 {args.follower}, {args.neighbors} neighbours, start {args.center}, fitness {args.model}"
    )
    print()
    print(f"{'method':<28} {'runs':>10} {'seconds':>10} {'error':>12}")
    pso = []
    for k in range(args.repeats):
        r = run_pso(args, args.seed + k)
        pso.append(r)
        note = f"seed {r['seed']}, |x - x*| {r['distance']:.2e}"
        print(row("pylinkage PSO", r["runs"], r["seconds"], r["error"], note), flush=True)
    med = {key: statistics.median(r[key] for r in pso) for key in ("runs", "seconds", "error")}
    if args.repeats > 1:
        print(
            row(
                "pylinkage PSO (median)",
                med["runs"],
                med["seconds"],
                med["error"],
                f"best error {min(r['error'] for r in pso):.4e}",
            )
        )
    try:
        mf = run_mechfem(sp.PROBLEM)
    except NotImplementedError as exc:
        print(f"{'mechfem':<28} {'-':>10} {'-':>10} {'-':>12}  not run: {exc}")
        return
    error = mf["error"]
    note = ""
    if "design" in mf:
        error = sp.error(np.asarray(mf["design"], dtype=float))
        note = f"(reported {mf['error']:.4e})"
    print(row("mechfem", mf["runs"], mf["seconds"], error, note))
    print()
    print(
        f"PSO / mechfem: runs {med['runs'] / mf['runs']:.1f}x, time {med['seconds'] / mf['seconds']:.1f}x (PSO medians)"
    )


if __name__ == "__main__":
    main()
