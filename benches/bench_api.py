"""Times mechfem's Python API end to end against pylinkage (numba) on the four-bar of bench_peers.py.

    .venv/bin/python benches/bench_api.py [--steps 360 100000] [--repeat 7] [--variants 400]

Timed, each the best of repeated calls (``bench_peers.best_of``), the tools alternated position count by
position count in one run:

* ``mechfem.run_deck`` on a deck on disk: one recording the coupler point with ``det=False`` (positions only),
  and one recording its velocity and acceleration too (first- and second-order transfer functions);
* the same velocity/acceleration deck as a named model, ``Mechanism.run(order=2)``, and through a compiled
  handle, ``_core.Model.from_path(deck).run(order=2)``, for the same work;
* ``mechfem.sweep`` of 360-position variants of the four-bar (its crank length), on 1 and on 2 workers alternated,
  the best of the rounds run between the tools' rounds;
* pylinkage's ``step_fast`` and ``step_fast_with_kinematics``.

Every tool's coupler point is first checked against the closed form of the four-bar (the crank pin on its
circle, the rocker pin at its distances from the crank pin and the rocker pivot), and pylinkage's against
mechfem's at every position, velocities and accelerations included. Nothing here asserts a time.
"""

from __future__ import annotations

import argparse
import math
import sys
import tempfile
import time
from pathlib import Path

from bench_peers import ALPHA, PEERS, A, B, C, D, P, agree, best_of, fourbar_deck, pylinkage_fourbar
from benchenv import ROOT, ensure_venv


def closed_form_check(coords, steps: int) -> None:  # type: ignore[no-untyped-def]
    """The four-bar's own equations at every position: crank pin on its circle at the prescribed angle, the
    coupler and rocker lengths, and the coupler point at P, ALPHA from the crank pin."""
    import numpy as np

    phi = np.linspace(0.0, 2.0 * math.pi, steps + 1)
    ax, ay, bx, by, cx, cy = (coords[:, i] for i in (4, 5, 6, 7, 8, 9))
    assert np.allclose(ax, A * np.cos(phi), atol=1e-9) and np.allclose(ay, A * np.sin(phi), atol=1e-9)
    assert np.allclose(np.hypot(bx - ax, by - ay), B, atol=1e-9)
    assert np.allclose(np.hypot(bx - D, by), C, atol=1e-9)
    theta = np.arctan2(by - ay, bx - ax) + ALPHA
    assert np.allclose(cx, ax + P * np.cos(theta), atol=1e-9) and np.allclose(cy, ay + P * np.sin(theta), atol=1e-9)


def measure(steps: int, args: argparse.Namespace, tmp: Path, add, rates, study_round) -> None:  # type: ignore[no-untyped-def]
    """Checks, then times every tool at ``steps`` steps, alternating them, and a round of the study after each
    round of the tools."""
    import numpy as np

    import mechfem
    from mechfem import _core

    print(f"{steps} steps")
    pos_deck, kin_deck = tmp / f"pos_{steps}.mec", tmp / f"kin_{steps}.mec"
    pos_deck.write_text(fourbar_deck(steps, False))
    kin_deck.write_text(fourbar_deck(steps, True))
    mech = mechfem.Mechanism.from_deck(str(kin_deck))
    handle = _core.Model.from_path(kin_deck)
    # Checks first: the closed form, then pylinkage against mechfem.
    pos, kin = mechfem.run_deck(pos_deck, det=False), mechfem.run_deck(kin_deck)
    closed_form_check(pos.coords, steps)
    closed_form_check(kin.coords, steps)
    ref_xy = np.column_stack([kin.buffers[1], kin.buffers[2]])
    agree("positions-only run", np.column_stack([pos.buffers[1], pos.buffers[2]]), ref_xy, 1e-9)
    an = mech.run(order=2, progress=False)
    agree("Mechanism.run", an.coords, kin.coords, 0.0)
    agree("compiled handle", np.asarray(handle.run(order=2)["coords"]), kin.coords, 0.0)
    _, (p, v, a) = best_of(
        1, lambda lk: lk.step_fast_with_kinematics(iterations=steps), lambda: pylinkage_fourbar(steps)
    )
    agree("pylinkage positions", p[:, 4, :], ref_xy[1:], 1e-9)
    agree("pylinkage velocities", v[:, 4, :], np.column_stack([kin.buffers[3], kin.buffers[4]])[1:], 1e-8)
    agree("pylinkage accelerations", a[:, 4, :], np.column_stack([kin.buffers[5], kin.buffers[6]])[1:], 1e-8)

    # Alternated: each round times every tool once more; the best of each is kept.
    best: dict[str, float] = {}
    tools = {
        "run_deck, positions only (det=False)": lambda: mechfem.run_deck(pos_deck, det=False),
        "pylinkage step_fast": None,
        "run_deck, second order": lambda: mechfem.run_deck(kin_deck),
        "pylinkage step_fast_with_kinematics": None,
        "Mechanism.run(order=2)": lambda: mech.run(order=2, progress=False),
        "compiled handle run(order=2)": lambda: handle.run(order=2),
    }
    rounds = args.repeat
    # A call at 100 000 positions writes tens of MB, and its time moves by a third from call to call with the
    # memory's state: more calls a round there, so that the best of them is the call's own cost.
    min_time = 0.05 if steps < 10_000 else 0.25
    for _ in range(rounds):
        for name, fn in tools.items():
            if name == "pylinkage step_fast":
                t, _ = best_of(1, lambda lk: lk.step_fast(iterations=steps), lambda: pylinkage_fourbar(steps), min_time)
            elif name == "pylinkage step_fast_with_kinematics":
                t, _ = best_of(
                    1,
                    lambda lk: lk.step_fast_with_kinematics(iterations=steps),
                    lambda: pylinkage_fourbar(steps),
                    min_time,
                )
            else:
                t, _ = best_of(1, fn, min_time=min_time)
            best[name] = min(best.get(name, math.inf), t)
        study_round()
    for name, t in best.items():
        add(name, steps, t)
    pairs = [
        ("second order / pylinkage with kinematics", "run_deck, second order", "pylinkage step_fast_with_kinematics"),
        ("positions only / pylinkage step_fast", "run_deck, positions only (det=False)", "pylinkage step_fast"),
        ("Mechanism.run time / compiled handle time", "compiled handle run(order=2)", "Mechanism.run(order=2)"),
    ]
    for what, num, den in pairs:
        print(f"  ratio {what}: {rates[num, steps] / rates[den, steps]:.2f}")


def main() -> None:
    ensure_venv([p for p in PEERS if not p.startswith("mechanism")], ".api-stamp")
    sys.path.insert(0, str(ROOT / "python"))
    import numpy as np

    import mechfem

    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--steps", type=int, nargs="+", default=[360, 100_000])
    ap.add_argument("--repeat", type=int, default=7)
    ap.add_argument("--variants", type=int, default=400)
    args = ap.parse_args()
    tmp = Path(tempfile.mkdtemp(prefix="mechfem-bench-"))
    rates: dict[tuple[str, int], float] = {}

    def add(tool: str, steps: int, seconds: float, per: str = "positions") -> None:
        rate = (steps + 1) / seconds if per == "positions" else steps / seconds
        rates[tool, steps] = rate
        print(f"  {tool:<48} {seconds * 1e3:10.3f} ms  {rate:14,.0f} {per}/s", flush=True)

    # A study: variants of the crank length, 360 positions each.
    (tmp / "study.mec").write_text(fourbar_deck(360, True))
    base = mechfem.Mechanism.from_deck(str(tmp / "study.mec"))
    name = "E1.length"
    values = np.linspace(0.9, 1.1, args.variants)
    study_rates: dict[int, float] = {}

    def study_round() -> None:
        # One and two workers, alternated like the tools; its rounds are spread over the whole run, between the
        # tools' rounds, so that a few seconds of the machine's noise cannot spoil every one of them.
        for workers in (1, 2):
            t0 = time.perf_counter()
            mechfem.sweep(base, {name: values}, workers=workers, progress=False)
            rate = args.variants / (time.perf_counter() - t0)
            study_rates[workers] = max(study_rates.get(workers, 0.0), rate)

    for steps in args.steps:
        measure(steps, args, tmp, add, rates, study_round)
    for w, rate in study_rates.items():
        print(f"  sweep, {args.variants} variants x 360 positions, {w} worker(s): {rate:,.0f} variants/s")
    print(f"  sweep speed-up 1 -> 2 workers: {study_rates[2] / study_rates[1]:.2f}")


if __name__ == "__main__":
    main()
