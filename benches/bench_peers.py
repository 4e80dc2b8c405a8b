"""Times mechfem against peers on one four-bar, checks that they agree, and prints positions per second.

    make bench                                 # builds mechfem, then runs this script
    .venv/bin/python benches/bench_peers.py [--steps 360 100000] [--repeat 5] [--min-time 0.2] [--quick]

The mechanism is a crank-rocker four-bar with a coupler point (crank 1, coupler 3, rocker 2.5, frame 3.2;
the coupler point 1.8 from the crank pin A at 0.6 rad from A->B), its crank turned once at 2 rad/s in
360 and in 100 000 positions. Timed, each as the best of at least ``--repeat`` runs on one core, and of
more runs until they have taken ``--min-time`` seconds in all (the same rule for every tool: a short run of
a tool called from Python is otherwise timed above its floor):

* mechfem's core (Rust, ``examples/throughput.rs``): positions only, with first-order and with first- and
  second-order transfer functions at every position;
* mechfem from Python (``mechfem.run_deck``): a deck recording the coupler point, and one recording its
  velocity and acceleration too (exact second-order transfer functions at every position);
* mechfem's batch API (``mechfem.run_many``), when the installed mechfem has it: copies of the
  four-bar on one worker and on every core;
* pylinkage in its fastest mode, numba: ``Linkage.step_fast`` (positions) and
  ``Linkage.step_fast_with_kinematics`` (positions, velocities, accelerations);
* the PyPI package ``mechanism`` (vector loops solved by scipy's fsolve): positions, and positions with
  velocities and accelerations (``--quick`` times it at the smallest step count only: it takes about a
  minute for 100 000 positions).

Before anything is reported, every peer's coupler point (and its velocity and acceleration where the peer
computes them) is checked against mechfem's at every position. The peers are installed into ``.venv-bench``
(created on first use; the script re-runs itself there), never into mechfem's own environment; mechfem is
imported from this source tree (``python/``, with the compiled module that ``make install`` builds).

Nothing here asserts a time: it is a benchmark, not a test.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import platform
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable
from pathlib import Path

from benchenv import ROOT, ensure_venv

# The peers and the versions measured in docs/performance.md.
PEERS = ["pylinkage==1.3.0", "numba==0.68.1", "mechanism==1.1.10"]

# The four-bar.
A, B, C, D = 1.0, 3.0, 2.5, 3.2
P, ALPHA = 1.8, 0.6
OMEGA = 2.0

# Every timing is the best of at least --repeat calls, and of more while they have taken less than MIN_TIME
# seconds in all (--min-time), up to MAX_RUNS.
MIN_TIME = 0.2
MAX_RUNS = 100_000


def best_of(
    repeat: int, fn: Callable[..., object], setup: Callable[[], object] | None = None, min_time: float | None = None
) -> tuple[float, object]:
    """The shortest wall time of the calls, and the last result: at least ``repeat`` calls, and more until they
    have taken ``min_time`` seconds in all (default ``MIN_TIME``), so that a short run is timed at its floor
    whatever the tool. With ``setup``, each call is ``fn(setup())`` and only ``fn`` is timed (building a peer's
    model is not part of its run)."""
    min_time = MIN_TIME if min_time is None else min_time
    best, out, runs, total = math.inf, None, 0, 0.0
    while runs < max(repeat, 1) or (total < min_time and runs < MAX_RUNS):
        arg = setup() if setup else None
        # The last call's result goes before the next call, as timeit lets it go: a call is not timed while the
        # one before still holds its memory (tens of MB at 100 000 positions, for every tool).
        out = None
        t = time.perf_counter()
        out = fn(arg) if setup else fn()
        seconds = time.perf_counter() - t
        best, runs, total = min(best, seconds), runs + 1, total + seconds
    return best, out


# mechfem ---------------------------------------------------------------------------------------------


def fourbar_deck(steps: int, kinematics: bool) -> str:
    """The four-bar as a deck: one crank turn in ``steps`` steps at OMEGA rad/s."""
    dt = 2 * math.pi / (steps * OMEGA)
    storage = ["BUFX0   9  1", "BUFX0  10  2"]
    if kinematics:
        storage += ["BUFVX   9  3", "BUFVX  10  4", "BUFAX   9  5", "BUFAX  10  6"]
    return "\n".join(
        [
            "KIN ANA",
            "TOPOLOGY",
            "ELEM 1 BIN 1 2 5 6",
            "     2 TR2 5 6 7 8 9 10",
            "     3 BIN 3 4 7 8",
            "FORM 1 LENL 1 1",
            "     2 LENL 2 2",
            "     3 LENL 3 3",
            "     4 LENU 2 4",
            "     5 LENV 2 5",
            "     6 ANGB 1 6",
            "NRDOF 1",
            "GEOMETRY",
            f"XFIX 1 0.0\n 2 0.0\n 3 {D!r}\n 4 0.0",
            "XMOV 5 1.0\n 6 0.0\n 7 2.725\n 8 2.4545\n 9 1.02\n 10 1.8",
            f"PARA 1 {A!r}\n 2 {B!r}\n 3 {C!r}\n 4 {P * math.cos(ALPHA)!r}\n 5 {P * math.sin(ALPHA)!r}\n 6 0.0",
            "MOVEMENT",
            f"TSTEPE {steps} {dt!r}",
            "MOV_RELE 1 6.283185307179586",
            "STORAGE",
            *storage,
            "",
        ]
    )


def mechfem_core_rates(steps: list[int], repeat: int, min_time: float) -> list[dict[str, object]]:
    """The core's own rates from examples/throughput.rs (built in release mode)."""
    cmd = ["cargo", "run", "--quiet", "--release", "-p", "mechfem-core", "--example", "throughput", "--"]
    out = subprocess.run(
        cmd + [str(s) for s in steps] + ["--repeat", str(repeat), "--min-time", str(min_time)],
        cwd=ROOT,
        check=True,
        capture_output=True,
        text=True,
    ).stdout
    return [json.loads(line) for line in out.splitlines() if line.strip()]


# pylinkage -------------------------------------------------------------------------------------------


def pylinkage_fourbar(steps: int):  # type: ignore[no-untyped-def]
    from pylinkage.actuators import Crank
    from pylinkage.components import Ground
    from pylinkage.dyads import FixedDyad, RRRDyad
    from pylinkage.simulation import Linkage

    a0, b0 = Ground(0.0, 0.0, name="A0"), Ground(D, 0.0, name="B0")
    crank = Crank(anchor=a0, radius=A, angular_velocity=2 * math.pi / steps, initial_angle=0.0, name="A")
    rocker = RRRDyad(crank.output, b0, distance1=B, distance2=C, name="B")
    point = FixedDyad(crank.output, rocker, distance=P, angle=ALPHA, name="C")
    linkage = Linkage([a0, b0, crank, rocker, point], name="four-bar")
    linkage.set_input_velocity(crank, omega=OMEGA)
    return linkage


# mechanism -------------------------------------------------------------------------------------------


def mechanism_model(steps: int, kinematics: bool):  # type: ignore[no-untyped-def]
    """The four-bar as vector loops, and its coupler point's joint (filled in by ``iterate``)."""
    import numpy as np
    from mechanism import Mechanism, Vector, get_joints

    o, a, b, o4, e = get_joints("O A B O4 E")
    va = Vector((o, a), r=A)
    vb = Vector((a, b), r=B)
    vd = Vector((o, o4), r=D, theta=0, style="ground")
    vc = Vector((o4, b), r=C)
    ve = Vector((a, e), r=P)

    def loop(x, i):  # type: ignore[no-untyped-def]
        # The coupler point's vector turns with the coupler: its angle is the
        # coupler's plus ALPHA (its rates are the coupler's).
        ve(x[0] + (ALPHA if ve.get == ve.pos.get else 0.0))
        return va(i) + vb(x[0]) - vd() - vc(x[1])

    theta = np.linspace(0, 2 * math.pi, steps + 1)
    omega = np.full(theta.size, OMEGA) if kinematics else None
    alpha = np.zeros(theta.size) if kinematics else None
    guess = (np.array([0.96, 1.37]), np.array([1.0, 1.0]), np.array([1.0, 1.0]))
    m = Mechanism(vectors=(va, vb, vc, vd, ve), origin=o, loops=loop, pos=theta, vel=omega, acc=alpha, guess=guess)
    return m, e


def mechanism_iterate(model):  # type: ignore[no-untyped-def]
    m, e = model
    m.iterate()
    return e


# the run ---------------------------------------------------------------------------------------------


def machine() -> str:
    cpu = platform.processor() or platform.machine()
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    system = f"{platform.system()} {platform.release()}"
    return f"{cpu}, {os.cpu_count()} logical cores, {system}, Python {platform.python_version()}"


def main() -> None:
    global MIN_TIME
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--steps", type=int, nargs="+", default=[360, 100_000])
    parser.add_argument("--repeat", type=int, default=5)
    parser.add_argument("--min-time", type=float, default=MIN_TIME, help="seconds of calls per timing, at least")
    parser.add_argument("--quick", action="store_true", help="time the package mechanism at the smallest --steps only")
    args = parser.parse_args()
    MIN_TIME = args.min_time
    ensure_venv(PEERS, ".peers-stamp")
    sys.path.insert(0, str(ROOT / "python"))

    import numpy as np
    import pylinkage

    import mechfem

    print(f"machine: {machine()}")
    versions = {"pylinkage": pylinkage.__version__, "numpy": np.__version__}
    for name in ("numba", "mechanism"):
        from importlib.metadata import version

        versions[name] = version(name)
    print("versions: " + ", ".join(f"{k} {v}" for k, v in versions.items()))

    rows: list[dict[str, object]] = []

    def add(tool: str, mode: str, steps: int, seconds: float, size: int | None = None) -> None:
        # size: positions per mechanism (the row's positions, unless it runs several copies)
        rows.append(
            {
                "tool": tool,
                "mode": mode,
                "steps": steps,
                "size": size or steps,
                "seconds": seconds,
                "rate": steps / seconds,
            }
        )
        print(
            f"  {tool:34} {mode:24} {steps:>7} positions {seconds * 1e3:10.3f} ms {steps / seconds:14,.0f} /s",
            flush=True,
        )

    # Compile pylinkage's numba kernels before timing.
    pylinkage_fourbar(8).step_fast(iterations=8)
    pylinkage_fourbar(8).step_fast_with_kinematics(iterations=8)

    print("mechfem core (Rust, one core)")
    for r in mechfem_core_rates(args.steps, args.repeat, args.min_time):
        add("mechfem core", str(r["mode"]), int(r["steps"]), float(r["seconds"]))  # type: ignore[arg-type]

    with tempfile.TemporaryDirectory() as tmp:
        for steps in args.steps:
            measure(mechfem, steps, args, Path(tmp), add)

    report(rows)


def measure(mechfem, steps: int, args: argparse.Namespace, tmp: Path, add) -> None:  # type: ignore[no-untyped-def]
    """Times every tool at ``steps`` positions (a crank turn) and checks each against mechfem."""
    import numpy as np

    print(f"{steps} positions")
    decks = {}
    for kinematics in (False, True):
        path = tmp / f"fourbar_{steps}_{int(kinematics)}.mec"
        path.write_text(fourbar_deck(steps, kinematics))
        decks[kinematics] = path
    # mechfem from Python, and what it computed.
    t, pos = best_of(args.repeat, lambda: mechfem.run_deck(decks[False]))
    add("mechfem (Python, run_deck)", "positions", steps, t)
    t, kin = best_of(args.repeat, lambda: mechfem.run_deck(decks[True]))
    add("mechfem (Python, run_deck)", "velocity, acceleration", steps, t)
    ref_xy = np.column_stack([kin.buffers[1], kin.buffers[2]])
    ref_v = np.column_stack([kin.buffers[3], kin.buffers[4]])
    ref_a = np.column_stack([kin.buffers[5], kin.buffers[6]])
    assert kin.report.stop_reason() is None and ref_xy.shape == (steps + 1, 2)
    agree("mechfem positions-only deck", np.column_stack([pos.buffers[1], pos.buffers[2]]), ref_xy, 1e-9)

    # The batch API: copies of the four-bar, one worker and every core.
    batch_rows(mechfem, decks[True], steps, args.repeat, add)

    # pylinkage: position k is crank angle (k + 1) 2 pi / steps.
    t, traj = best_of(args.repeat, lambda lk: lk.step_fast(iterations=steps), lambda: pylinkage_fourbar(steps))
    add("pylinkage (numba step_fast)", "positions", steps, t)
    agree("pylinkage step_fast", traj[:, 4, :], ref_xy[1:], 1e-9)
    t, (p, v, a) = best_of(
        args.repeat, lambda lk: lk.step_fast_with_kinematics(iterations=steps), lambda: pylinkage_fourbar(steps)
    )
    add("pylinkage (numba, kinematics)", "velocity, acceleration", steps, t)
    agree("pylinkage positions", p[:, 4, :], ref_xy[1:], 1e-9)
    agree("pylinkage velocities", v[:, 4, :], ref_v[1:], 1e-8)
    agree("pylinkage accelerations", a[:, 4, :], ref_a[1:], 1e-8)

    # mechanism: scipy fsolve at every position.
    if args.quick and steps != min(args.steps):
        print("  mechanism: skipped (--quick)")
        return
    reps = 1 if steps > 1000 else max(1, args.repeat // 2)
    t, e = best_of(reps, mechanism_iterate, lambda: mechanism_model(steps, False), min_time=0.0)
    add("mechanism (scipy fsolve)", "positions", steps, t)
    agree("mechanism positions", np.column_stack([e.x_positions, e.y_positions]), ref_xy, 1e-6)
    t, e = best_of(reps, mechanism_iterate, lambda: mechanism_model(steps, True), min_time=0.0)
    add("mechanism (scipy fsolve)", "velocity, acceleration", steps, t)
    agree("mechanism velocities", np.column_stack([e.x_velocities, e.y_velocities]), ref_v, 1e-6)
    agree("mechanism accelerations", np.column_stack([e.x_accelerations, e.y_accelerations]), ref_a, 1e-5)


def agree(what: str, got, want, tol: float) -> None:  # type: ignore[no-untyped-def]
    """Stops the benchmark unless ``got`` matches mechfem's ``want`` at every position."""
    import numpy as np

    got, want = np.asarray(got, dtype=float), np.asarray(want, dtype=float)
    if got.shape != want.shape:
        raise SystemExit(f"{what}: shape {got.shape}, mechfem {want.shape}")
    err = float(np.max(np.abs(got - want) / (1.0 + np.abs(want))))
    if not err <= tol:
        raise SystemExit(f"{what} disagree with mechfem: largest relative difference {err:.2e} > {tol:.0e}")
    print(f"    agrees with mechfem: {what}, largest difference {err:.1e}")


def batch_rows(mechfem, deck: Path, steps: int, repeat: int, add) -> None:  # type: ignore[no-untyped-def]
    run_many = getattr(mechfem, "run_many", None)
    from_deck = getattr(getattr(mechfem, "Mechanism", None), "from_deck", None)
    if run_many is None or from_deck is None:
        print("  mechfem batch API: not in this mechfem (no mechfem.run_many): skipped")
        return
    copies = 8 if steps > 1000 else 64
    try:
        base = from_deck(str(deck))
        for workers in sorted({1, os.cpu_count() or 1}):
            t, out = best_of(repeat, lambda w=workers: run_many([base] * copies, workers=w, progress=False))
            if any(isinstance(o, Exception) for o in out):
                raise RuntimeError(next(o for o in out if isinstance(o, Exception)))
            add(
                f"mechfem (Python, run_many, {workers} worker{'s' if workers > 1 else ''})",
                f"{copies} x velocity, accel.",
                steps * copies,
                t,
                size=steps,
            )
    except (AttributeError, TypeError, RuntimeError) as e:
        print(f"  mechfem batch API: could not be timed ({type(e).__name__}: {e}): skipped")


def report(rows: list[dict[str, object]]) -> None:
    """Positions per second of every row, and its ratio to mechfem's at the same size: from Python
    (``run_deck``, the deck recording positions or the one recording velocities and accelerations too)
    and the core (positions only, or with second-order transfer functions)."""

    def ref(r: dict[str, object], tool: str, kinematic_mode: str, positions_mode: str) -> dict[str, object] | None:
        kinematic = str(r["mode"]) not in ("positions", "first")
        mode = kinematic_mode if kinematic else positions_mode
        return next((q for q in rows if q["tool"] == tool and q["size"] == r["size"] and q["mode"] == mode), None)

    def ratio(r: dict[str, object], q: dict[str, object] | None) -> str:
        return f"{float(r['rate']) / float(q['rate']):9.2f}" if q else "        -"  # type: ignore[arg-type]

    print()
    print("positions per second (best of the repeats; one core unless the row says otherwise) and the ratio")
    print("to mechfem's at the same number of positions: from Python (run_deck), and its core (Rust); rows")
    print("without velocities compare with mechfem's positions, rows with them with its second order")
    header = f"{'tool':44} {'computes':24} {'positions':>9} {'per second':>14} {'/ Python':>9} {'/ core':>9}"
    print(header)
    print("-" * len(header))
    for r in rows:
        py = ref(r, "mechfem (Python, run_deck)", "velocity, acceleration", "positions")
        core = ref(r, "mechfem core", "second", "positions")
        print(
            f"{r['tool']!s:44} {r['mode']!s:24} {r['steps']:>9} {float(r['rate']):14,.0f}"  # type: ignore[arg-type]
            f" {ratio(r, py)} {ratio(r, core)}"
        )


if __name__ == "__main__":
    main()
