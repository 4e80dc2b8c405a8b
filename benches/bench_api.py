"""Times mechfem's Python API end to end against pylinkage (numba) on the four-bar of bench_peers.py.

    .venv/bin/python benches/bench_api.py [--steps 360 100000] [--repeat 7] [--variants 400]

Timed, each the best of repeated calls (``bench_peers.best_of``), the tools alternated position count by
position count in one run, every tool twice: **compiled once** (its model made and compiled before the timing and
reused by every timed call, as a user who runs one model many times does) and **compiled per call** (its model
read or built and compiled inside each timed call):

* ``mechfem.run_deck`` on a deck on disk: one recording the coupler point with ``det=False`` (positions only),
  and one recording its velocity and acceleration too (first- and second-order transfer functions); compiled
  once is the deck run again unchanged (kept compiled), compiled per call a deck text never run before;
* the same velocity/acceleration deck as a named model, ``Mechanism.run(order=2)`` (compiled per call: its kept
  compiled model forgotten before each call, so the call builds it through the typed builder), and through a
  compiled handle, ``_core.Model.from_path(deck).run(order=2)`` (compiled per call: ``_core.Model(text)``);
* pylinkage's ``step_fast`` and ``step_fast_with_kinematics`` (numba): compiled once is one linkage, compiled with
  ``Linkage.compile`` and run once before the timing, set back to its start (``set_coords``, untimed) before each
  call; compiled per call is a linkage built before each call (untimed) whose numba state is made in the call;
* the core's own run of the same four-bar (``examples/throughput.rs``), positions only and second order with nothing
  recorded, and second order with every position recorded as ``Mechanism.run`` records it: a round of it (its best
  of repeated runs) in every round of the tools, so that it meets the machine's load as they do;
* ``mechfem.sweep`` of 360-position variants of the four-bar (its crank length), on 1 and on 2 workers alternated,
  the best of the rounds run between the tools' rounds.

Every tool's coupler point is first checked against the closed form of the four-bar (the crank pin on its
circle, the rocker pin at its distances from the crank pin and the rocker pivot), and pylinkage's against
mechfem's at every position, velocities and accelerations included. Nothing here asserts a time.

The run ends with the side-by-side tables of docs/performance.md (markdown): every tool's time per call, compiled
once and per call, at every position count, and the ratios the speed targets are stated in.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable
from pathlib import Path

from bench_peers import (
    ALPHA,
    PEERS,
    A,
    B,
    C,
    D,
    P,
    agree,
    best_of,
    fourbar_deck,
    pylinkage_fourbar,
)
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


def throughput_example() -> Path:
    """Builds ``examples/throughput.rs`` in release mode (the workspace's profile) and returns its path."""
    subprocess.run(
        ["cargo", "build", "--quiet", "--release", "-p", "mechfem-core", "--example", "throughput"],
        cwd=ROOT,
        check=True,
    )
    return ROOT / "target" / "release" / "examples" / "throughput"


def core_round(example: Path, steps: int, mode: str, min_time: float) -> float:
    """One round of the core's own run: the best of its repeated runs (at least ``min_time`` seconds of them), in
    seconds."""
    out = subprocess.run(
        [str(example), str(steps), "--mode", mode, "--repeat", "3", "--min-time", str(min_time)],
        check=True,
        capture_output=True,
        text=True,
    ).stdout
    return float(json.loads(out.splitlines()[-1])["seconds"])


def measure(steps: int, args: argparse.Namespace, tmp: Path, add, rates, times, study_round, example: Path) -> None:  # type: ignore[no-untyped-def]
    """Checks, then times every tool at ``steps`` steps, alternating them, and a round of the study after each
    round of the tools."""
    import numpy as np

    import mechfem
    from mechfem import _core

    print(f"{steps} steps")
    pos_deck, kin_deck = tmp / f"pos_{steps}.mec", tmp / f"kin_{steps}.mec"
    pos_deck.write_text(fourbar_deck(steps, False))
    kin_deck.write_text(fourbar_deck(steps, True))
    # Decks as a user keeps them, last changed before the session: a file changed in the last seconds is read
    # again at every call until it has settled (docs/performance.md, What a call costs).
    hour_ago = time.time() - 3600
    for deck in (pos_deck, kin_deck):
        os.utime(deck, (hour_ago, hour_ago))
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
    agree("compiled handle", np.asarray(handle.run(order=2).coords), kin.coords, 0.0)
    _, (p, v, a) = best_of(
        1, lambda lk: lk.step_fast_with_kinematics(iterations=steps), lambda: pylinkage_fourbar(steps)
    )
    agree("pylinkage positions", p[:, 4, :], ref_xy[1:], 1e-9)
    agree("pylinkage velocities", v[:, 4, :], np.column_stack([kin.buffers[3], kin.buffers[4]])[1:], 1e-8)
    agree("pylinkage accelerations", a[:, 4, :], np.column_stack([kin.buffers[5], kin.buffers[6]])[1:], 1e-8)

    # Every tool twice: its model compiled once and reused by every timed call (mechfem's kept deck, pylinkage's
    # linkage compiled by ``Linkage.compile`` and set back to its start before each call, untimed), and compiled
    # anew inside each timed call (a deck text never run before, a linkage built and compiled by its first call).
    fresh = iter(range(10**9))

    def new_deck(kinematics: bool) -> Path:
        # A text never run before (its first line says which call it is for): read, parsed and compiled in the call.
        path = tmp / f"new_{steps}_{kinematics}.mec"
        path.write_text(f"; call {next(fresh)}\n" + fourbar_deck(steps, kinematics))
        return path

    def kept_linkage():  # type: ignore[no-untyped-def]
        linkage = pylinkage_fourbar(steps)
        linkage.compile()
        linkage.step_fast_with_kinematics(iterations=steps)  # numba's own compilation, once
        start = linkage.get_coords()

        def reset():  # type: ignore[no-untyped-def]
            linkage.set_coords(start)
            return linkage

        return reset

    kept_lk = kept_linkage()

    def forget_compiled() -> object:
        # The mechanism keeps its compiled models: forgotten, untimed.
        vars(mech).pop("_kept", None)
        return mech

    kin_text = fourbar_deck(steps, True)
    tools: dict[str, tuple[Callable[..., object], Callable[[], object] | None]] = {
        "run_deck, positions only (det=False), compiled once": (lambda: mechfem.run_deck(pos_deck, det=False), None),
        "run_deck, positions only (det=False), compiled per call": (
            lambda p: mechfem.run_deck(p, det=False),
            lambda: new_deck(False),
        ),
        "pylinkage step_fast, compiled once": (lambda lk: lk.step_fast(iterations=steps), kept_lk),
        "pylinkage step_fast, compiled per call": (
            lambda lk: lk.step_fast(iterations=steps),
            lambda: pylinkage_fourbar(steps),
        ),
        "run_deck, second order, compiled once": (lambda: mechfem.run_deck(kin_deck), None),
        "run_deck, second order, compiled per call": (lambda p: mechfem.run_deck(p), lambda: new_deck(True)),
        "pylinkage step_fast_with_kinematics, compiled once": (
            lambda lk: lk.step_fast_with_kinematics(iterations=steps),
            kept_lk,
        ),
        "pylinkage step_fast_with_kinematics, compiled per call": (
            lambda lk: lk.step_fast_with_kinematics(iterations=steps),
            lambda: pylinkage_fourbar(steps),
        ),
        "Mechanism.run(order=2), compiled once": (lambda: mech.run(order=2, progress=False), None),
        "Mechanism.run(order=2), compiled per call": (lambda m: m.run(order=2, progress=False), forget_compiled),
        "compiled handle run(order=2), compiled once": (lambda: handle.run(order=2), None),
        "compiled handle run(order=2), compiled per call": (
            lambda: _core.Model(kin_text, "kin.mec", ".").run(order=2),
            None,
        ),
    }
    rounds = args.repeat
    # A call at 100 000 positions writes tens of MB, and its time moves by a third from call to call with the
    # memory's state: more calls a round there, so that the best of them is the call's own cost.
    min_time = 0.05 if steps < 10_000 else 0.25
    best: dict[str, float] = {}
    core_positions = "the core's own run, positions only (throughput example)"
    core_second = "the core's own run, second order (throughput example)"
    core_recorded = "the core's own run, second order, recorded as Mechanism.run records (throughput example)"
    for _ in range(rounds):
        for name, (fn, setup) in tools.items():
            t, _ = best_of(1, fn, setup, min_time)
            best[name] = min(best.get(name, math.inf), t)
        # The core's own runs in the same round: nothing recorded, and everything Mechanism.run records.
        for name, mode in ((core_positions, "positions"), (core_second, "second"), (core_recorded, "recorded")):
            best[name] = min(best.get(name, math.inf), core_round(example, steps, mode, min_time))
        study_round()
    for name, t in best.items():
        add(name, steps, t)
        times[name, steps] = t
    core = best[core_second]
    once, per = "compiled once", "compiled per call"
    second, with_kin = "run_deck, second order", "pylinkage step_fast_with_kinematics"
    positions, fast = "run_deck, positions only (det=False)", "pylinkage step_fast"
    named, handled = "Mechanism.run(order=2)", "compiled handle run(order=2)"
    pairs = [
        (f"second order / pylinkage with kinematics, {once}", second, with_kin, once),
        (f"second order / pylinkage with kinematics, {per}", second, with_kin, per),
        (f"positions only / pylinkage step_fast, {once}", positions, fast, once),
        (f"positions only / pylinkage step_fast, {per}", positions, fast, per),
        (f"Mechanism.run time / compiled handle time, {once}", handled, named, once),
    ]
    for what, num, den, how in pairs:
        print(f"  ratio {what}: {rates[f'{num}, {how}', steps] / rates[f'{den}, {how}', steps]:.2f}")
    print(f"  ratio Mechanism.run(order=2) time / the core's own run time: {best[f'{named}, {once}'] / core:.2f}")
    recorded = best[f"{named}, {once}"] / best[core_recorded]
    print(f"  ratio Mechanism.run(order=2) time / the core's own run recording the same: {recorded:.2f}")
    # What a call adds to the core's own run of the same mode (reading the kept deck, recording, the result).
    for what, name, own in (
        ("run_deck, positions only", f"{positions}, {once}", core_positions),
        ("run_deck, second order", f"{second}, {once}", core_second),
    ):
        print(f"  ratio {what} time / the core's own run time: {best[name] / best[own]:.2f}")


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
    times: dict[tuple[str, int], float] = {}

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

    # The core's own run (examples/throughput.rs), timed round by round with the tools.
    example = throughput_example()
    for steps in args.steps:
        measure(steps, args, tmp, add, rates, times, study_round, example)
    for w, rate in study_rates.items():
        print(f"  sweep, {args.variants} variants x 360 positions, {w} worker(s): {rate:,.0f} variants/s")
    print(f"  sweep speed-up 1 -> 2 workers: {study_rates[2] / study_rates[1]:.2f}")
    print()
    print(side_by_side(times, args.steps))


# The rows of the side-by-side table: (tool as the bench names it, what it computes).
TABLE_ROWS = [
    ("run_deck, positions only (det=False)", "`mechfem.run_deck(det=False)`", "positions"),
    ("pylinkage step_fast", "pylinkage `step_fast`", "positions"),
    ("run_deck, second order", "`mechfem.run_deck`", "+ velocity, acceleration (second order)"),
    ("pylinkage step_fast_with_kinematics", "pylinkage `step_fast_with_kinematics`", "+ velocity, acceleration"),
    ("Mechanism.run(order=2)", "`Mechanism.run(order=2)`", "every quantity of the buffer table"),
    ("compiled handle run(order=2)", "compiled handle, `_core.Model.run(order=2)`", "the same"),
    (
        "the core's own run, positions only (throughput example)",
        "the core's own run (`throughput`)",
        "positions only, nothing recorded",
    ),
    (
        "the core's own run, second order (throughput example)",
        "the core's own run (`throughput`)",
        "second order, nothing recorded",
    ),
    (
        "the core's own run, second order, recorded as Mechanism.run records (throughput example)",
        "the core's own run (`throughput`)",
        "second order, every position recorded as `Mechanism.run` records it",
    ),
]

# The ratios of the side-by-side table: (what, numerator, denominator, whether a ratio of speeds).
TABLE_RATIOS = [
    (
        "`run_deck` second order against `step_fast_with_kinematics`, both compiled once (speed)",
        "run_deck, second order, compiled once",
        "pylinkage step_fast_with_kinematics, compiled once",
        True,
    ),
    (
        "the same, both compiled per call",
        "run_deck, second order, compiled per call",
        "pylinkage step_fast_with_kinematics, compiled per call",
        True,
    ),
    (
        "`run_deck(det=False)` against `step_fast`, both compiled once (speed)",
        "run_deck, positions only (det=False), compiled once",
        "pylinkage step_fast, compiled once",
        True,
    ),
    (
        "the same, both compiled per call",
        "run_deck, positions only (det=False), compiled per call",
        "pylinkage step_fast, compiled per call",
        True,
    ),
    (
        "`Mechanism.run(order=2)` time over the core's own run (second order)",
        "Mechanism.run(order=2), compiled once",
        "the core's own run, second order (throughput example)",
        False,
    ),
    (
        "`Mechanism.run(order=2)` time over the core's own run recording the same",
        "Mechanism.run(order=2), compiled once",
        "the core's own run, second order, recorded as Mechanism.run records (throughput example)",
        False,
    ),
    (
        "`Mechanism.run(order=2)` time over the compiled handle's",
        "Mechanism.run(order=2), compiled once",
        "compiled handle run(order=2), compiled once",
        False,
    ),
]


def side_by_side(times: dict[tuple[str, int], float], steps: list[int]) -> str:
    """The times of every tool, compiled once and per call, at every position count, and the ratios of the
    targets, as two markdown tables (docs/performance.md shows them)."""

    def shown(seconds: float | None) -> str:
        if seconds is None:
            return ""
        text = f"{seconds * 1e6:,.0f} µs" if seconds < 1e-2 else f"{seconds * 1e3:,.1f} ms"
        return text.replace(",", " ")

    head = ["tool", "computes"] + [
        f"{n:,}".replace(",", " ") + f", {how}" for n in steps for how in ("compiled once", "per call")
    ]
    lines = ["| " + " | ".join(head) + " |", "|---|---|" + "---:|" * (2 * len(steps))]
    for tool, label, computes in TABLE_ROWS:
        cells = []
        for n in steps:
            if tool.startswith("the core"):
                cells += [shown(times.get((tool, n))), ""]
            else:
                cells += [
                    shown(times.get((f"{tool}, compiled once", n))),
                    shown(times.get((f"{tool}, compiled per call", n))),
                ]
        lines.append("| " + " | ".join([label, computes, *cells]) + " |")
    lines += ["", "| ratio | " + " | ".join(f"{n:,} positions".replace(",", " ") for n in steps) + " |"]
    lines.append("|---|" + "---:|" * len(steps))
    for what, num, den, speed in TABLE_RATIOS:
        cells = []
        for n in steps:
            a, b = times.get((num, n)), times.get((den, n))
            cells.append("" if a is None or b is None else f"{(b / a if speed else a / b):.2f}")
        lines.append("| " + " | ".join([what, *cells]) + " |")
    return "\n".join(lines)


if __name__ == "__main__":
    main()
