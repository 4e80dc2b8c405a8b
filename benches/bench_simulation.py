"""Times mechfem's simulation (DYN SIM) against the same mechanism's equations of motion written by hand and integrated
with SciPy, checks that they agree, and prints steps, evaluations, wall time and error of each.

    .venv/bin/python benches/bench_simulation.py [--tol 1e-6 1e-8 1e-10] [--repeat 5] [--min-time 0.5]

The mechanism is the run-up of a slider-crank: a crank of 0.05 m with a flywheel (J = 4e-3 kg m^2 about the shaft),
a rod of 0.2 m (0.6 kg, centre of mass 0.08 m from the crank pin, J = 2.5e-3 kg m^2 about it) and a slider of 0.5 kg
on the line through the shaft, driven by a constant torque of 1 N m against a constant gas force of 10 N on the
slider (towards the shaft), from 0.3 rad and 30 rad/s for 1 s (about 19 turns), results every millisecond (1000
output steps). No gravity.

Timed, each as the best of at least ``--repeat`` calls, and of more calls until they have taken ``--min-time``
seconds, the tools alternating:

* mechfem from Python as a user calls it: ``Mechanism.simulate`` (writing the deck, reading it, simulating, building
  the ``Analysis`` with every co-ordinate's transfer functions, velocity and acceleration and the inverse dynamics
  at every output), and ``mechfem.run_deck`` of the deck saved for the same simulation (recording the crank angle
  and its speed);
* the equations of motion written by hand (Lagrange, one degree of freedom: ``M(q) q'' + M'(q) q'^2 / 2 = Q(q)``,
  derived below) as a Python function integrated by ``scipy.integrate.solve_ivp`` with ``method="Radau"`` (implicit,
  order 5, its Jacobian by finite differences, as ``solve_ivp`` does without ``jac``) and with ``method="RK45"``
  (explicit, Dormand-Prince 5(4)), at the same ``rtol`` and ``atol``, output at the same times
  (``t_eval``).

Before anything is timed, the hand-written equations are checked against mechfem: the mass matrix and the
generalised force at every output of mechfem's simulation, and the motion itself against a reference (the hand
equations by ``DOP853`` at 1e-13). The error of each tool is its largest error in the crank angle over the outputs
(and the error at the last one) against that reference. Radau is much more accurate than its tolerance says, and
Dormand-Prince less, so "equal accuracy" compares mechfem's time with Radau's at the same error: Radau is timed over
the tolerances of ``--radau-tol``, and its time at mechfem's error is interpolated (log-log) between the two runs
whose errors bracket it (with the time of the loosest run at least as accurate beside it).

SciPy is installed into ``.venv-bench`` (created on first use; the script re-runs itself there), never into
mechfem's own environment; mechfem is imported from this source tree (``python/``, with the compiled module that
``make install`` builds). Nothing here asserts a time: it is a benchmark, not a test.

The work-precision comparison with SciPy, SUNDIALS IDA and Exudyn on Andrews' squeezing mechanism and a stiff
four-bar is ``bench_work_precision.py`` (docs/simulation-benchmarks.md).
"""

from __future__ import annotations

import argparse
import math
import os
import platform
import sys
import tempfile
import time
from collections.abc import Callable
from functools import partial
from pathlib import Path
from typing import Any

from benchenv import ROOT, ensure_venv

# SciPy as measured in docs/performance.md.
PEERS = ["scipy==1.17.1"]

# The slider-crank (SI units).
R, L = 0.05, 0.2  # crank, rod
A, M_ROD, J_ROD = 0.08, 0.6, 2.5e-3  # rod: centre of mass from the crank pin, mass, J about the centre
M_CRANK, J_CRANK = 2.0, 4e-3  # crank with its flywheel: centre of mass on the shaft, J about it
M_SLIDER = 0.5
TORQUE, GAS = 1.0, 10.0  # drive torque on the crank; gas force on the slider, towards the shaft
Q0, W0 = 0.3, 30.0  # crank angle and speed at the start
T_END, OUTPUTS = 1.0, 1000


# --- the equations of motion, by hand ---------------------------------------------------------------------------------
#
# Crank angle q, s = sin q, c = cos q, lam = R / L, w = sqrt(1 - lam^2 s^2). The slider is at x = R c + L w, the rod's
# angle phi has sin(phi) = -lam s, its centre of mass is G = (R c + A w, (R - A lam) s). Derivatives with respect to q:
#
#   g    = s c / w                                 g'    = (c^2 - s^2) / w + lam^2 s^2 c^2 / w^3
#   x'   = -R s - R lam g                          x''   = -R c - R lam g'
#   phi' = -lam c / w                              phi'' = lam s / w - lam^3 s c^2 / w^3
#   G'   = (-R s - A lam^2 g, (R - A lam) c)       G''   = (-R c - A lam^2 g', -(R - A lam) s)
#
# Kinetic energy T = M(q) q'^2 / 2 with M = J_crank + m_rod |G'|^2 + J_rod phi'^2 + m_slider x'^2, so Lagrange gives
# M q'' + M' q'^2 / 2 = Q with M' = 2 (m_rod G'.G'' + J_rod phi' phi'' + m_slider x' x'') and the generalised force
# Q = torque - gas x' (the gas force pushes the slider towards the shaft, -x).


def terms(q: float) -> tuple[float, float, float]:
    """M(q), M'(q) and Q(q)."""
    s, c = math.sin(q), math.cos(q)
    lam = R / L
    w = math.sqrt(1.0 - lam * lam * s * s)
    g1 = (c * c - s * s) / w + lam * lam * s * s * c * c / w**3
    x1 = -R * s - R * lam * s * c / w
    x2 = -R * c - R * lam * g1
    p1 = -lam * c / w
    p2 = lam * s / w - lam**3 * s * c * c / w**3
    gx1, gy1 = -R * s - A * lam * lam * s * c / w, (R - A * lam) * c
    gx2, gy2 = -R * c - A * lam * lam * g1, -(R - A * lam) * s
    m = J_CRANK + M_ROD * (gx1 * gx1 + gy1 * gy1) + J_ROD * p1 * p1 + M_SLIDER * x1 * x1
    dm = 2.0 * (M_ROD * (gx1 * gx2 + gy1 * gy2) + J_ROD * p1 * p2 + M_SLIDER * x1 * x2)
    return m, dm, TORQUE - GAS * x1


def rhs(t: float, y: list[float]) -> list[float]:
    """The state (q, q') and its rate."""
    m, dm, force = terms(y[0])
    return [y[1], (force - 0.5 * dm * y[1] * y[1]) / m]


# --- mechfem ----------------------------------------------------------------------------------------------------------


def slider_crank(mechfem: Any) -> Any:
    """The slider-crank as a mechfem model: its crank angle ``q`` moves under the forces."""
    from mechfem import Driven, Mechanism

    m = Mechanism("slider crank")
    shaft = m.fixed("O", 0.0, 0.0)
    pin = m.point("A", R * math.cos(Q0), R * math.sin(Q0))
    slider = m.point("B", R * math.cos(Q0) + math.sqrt(L * L - (R * math.sin(Q0)) ** 2), 0.0, fixed="y")
    m.bar("crank", shaft, pin, length=R, angle=Driven(start=Q0, name="q"))
    m.bar("rod", pin, slider, length=L)
    m.mass("crank", M_CRANK, J=J_CRANK)
    m.mass("rod", M_ROD, u=A, J=J_ROD)
    m.point_mass(slider, M_SLIDER)
    m.load("q", TORQUE)
    m.force(slider, -GAS, 0.0)
    return m


def accuracy(tol: float) -> float:
    """The Newton tolerance (ACCURACY) to go with an integrator's tolerance: the default 1e-10, or ``tol`` below it."""
    return min(1e-10, tol)


# --- timing -----------------------------------------------------------------------------------------------------------


def best_of_alternating(
    calls: dict[str, Callable[[], object]], repeat: int, min_time: float, max_rounds: int = 10_000
) -> dict[str, float]:
    """The shortest wall time of each call, the calls taking turns: at least ``repeat`` rounds, and more while some
    call has taken less than ``min_time`` seconds in all."""
    best = dict.fromkeys(calls, math.inf)
    total = dict.fromkeys(calls, 0.0)
    rounds = 0
    while rounds < repeat or (min(total.values()) < min_time and rounds < max_rounds):
        for name, call in calls.items():
            t = time.perf_counter()
            call()
            seconds = time.perf_counter() - t
            best[name], total[name] = min(best[name], seconds), total[name] + seconds
        rounds += 1
    return best


def machine() -> str:
    cpu = platform.processor() or platform.machine()
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    return f"{cpu}, {os.cpu_count()} logical cores, Python {platform.python_version()}, {platform.system()}"


# --- the run ----------------------------------------------------------------------------------------------------------


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--tol", type=float, nargs="+", default=[1e-6, 1e-8, 1e-10], help="rtol = atol of each run")
    parser.add_argument(
        "--radau-tol",
        type=float,
        nargs="+",
        default=[1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10],
        help="the tolerances Radau is timed at for the comparison at equal accuracy",
    )
    parser.add_argument("--repeat", type=int, default=5)
    parser.add_argument("--min-time", type=float, default=0.5, help="seconds of calls per timing, at least")
    args = parser.parse_args()
    ensure_venv(PEERS, ".simulation-stamp")
    sys.path.insert(0, str(ROOT / "python"))

    import numpy as np
    import scipy
    from scipy.integrate import solve_ivp

    import mechfem
    from mechfem import Motion
    from mechfem.model.mechanism import Storage

    print(f"machine: {machine()}")
    print(f"versions: numpy {np.__version__}, scipy {scipy.__version__}")
    times = np.linspace(0.0, T_END, OUTPUTS + 1)
    model = slider_crank(mechfem)

    def scipy_run(method: str, tol: float, t_eval: Any = times) -> Any:
        return solve_ivp(rhs, (0.0, T_END), [Q0, W0], method=method, rtol=tol, atol=tol, t_eval=t_eval)

    # The reference, and the hand equations checked against mechfem.
    ref = scipy_run("DOP853", 1e-13)
    q_ref, w_ref = ref.y
    tight = model.simulate(T_END, OUTPUTS, W0, rtol=1e-12, atol=1e-12, accuracy=1e-12)
    q = tight.input("q")
    mass = np.array([terms(v)[0] for v in q])
    force = np.array([terms(v)[2] for v in q])
    print(f"the motion: {(q_ref[-1] - Q0) / (2 * math.pi):.1f} turns, speed {W0:g} to {w_ref[-1]:.1f} rad/s")
    print(f"mechfem's integrator: {tight.simulation.method}")
    print("checks of the hand-written equations against mechfem (largest relative difference over the outputs):")
    print(f"  mass matrix M(q): {np.abs(tight.mass_matrix()[:, 0, 0] / mass - 1).max():.1e}")
    # mechfem's drive torque with q'' = 0 would be -Q - h; here the drive is zero, so M q'' + M' q'^2 / 2 = Q.
    dm = np.array([terms(v)[1] for v in q])
    w, acc = tight.velocity("q"), tight.acceleration("q")
    print(f"  M q'' + M' q'^2 / 2 - Q: {np.abs(mass * acc + 0.5 * dm * w * w - force).max() / np.abs(force).max():.1e}")
    print(f"  crank angle, mechfem at 1e-12 against the reference: {np.abs(q - q_ref).max():.1e} rad")
    x = R * np.cos(q) + L * np.sqrt(1 - (R / L * np.sin(q)) ** 2)
    print(f"  slider, mechfem against x(q): {np.abs(tight.x('B') - x).max():.1e} m")

    def errors(angle: Any) -> tuple[float, float]:
        """The largest error of the crank angle over the outputs, and the error at the last one."""
        e = np.abs(np.asarray(angle) - q_ref)
        return float(e.max()), float(e[-1])

    rows: list[dict[str, Any]] = []
    with tempfile.TemporaryDirectory() as tmp:
        for tol in args.tol:
            motion_kw = {"rtol": tol, "atol": tol, "accuracy": accuracy(tol)}
            storage = Storage().buffer(1, "BUFINP", "q").buffer(2, "BUFVE", "q")
            motion = Motion.dynamic(T_END, OUTPUTS, W0, **motion_kw)
            deck = model.save_deck(Path(tmp) / f"slider_crank_{tol:g}.mec", motion, storage)
            sim = model.simulate(T_END, OUTPUTS, W0, **motion_kw)
            ran = mechfem.run_deck(deck)
            assert sim.complete and ran.report.complete and sim.simulation is not None
            assert np.allclose(ran.buffers[1], sim.input("q"), rtol=0, atol=1e-9)
            radau, rk45 = scipy_run("Radau", tol), scipy_run("RK45", tol)
            steps = {m: len(scipy_run(m, tol, None).t) - 1 for m in ("Radau", "RK45")}
            best = best_of_alternating(
                {
                    "simulate": partial(model.simulate, T_END, OUTPUTS, W0, **motion_kw),
                    "run_deck": partial(mechfem.run_deck, deck),
                    "Radau": partial(scipy_run, "Radau", tol),
                    "RK45": partial(scipy_run, "RK45", tol),
                },
                args.repeat,
                args.min_time,
            )
            s = sim.simulation
            rows += [
                {
                    "tol": tol,
                    "tool": "mechfem Mechanism.simulate",
                    "steps": s.steps,
                    "rejected": s.rejected,
                    "evaluations": s.evaluations,
                    "seconds": best["simulate"],
                    "errors": errors(sim.input("q")),
                },
                {
                    "tol": tol,
                    "tool": "mechfem run_deck",
                    "steps": s.steps,
                    "rejected": s.rejected,
                    "evaluations": s.evaluations,
                    "seconds": best["run_deck"],
                    "errors": errors(ran.buffers[1]),
                },
                {
                    "tol": tol,
                    "tool": "SciPy Radau, hand equations",
                    "steps": steps["Radau"],
                    "rejected": None,
                    "evaluations": radau.nfev,
                    "seconds": best["Radau"],
                    "errors": errors(radau.y[0]),
                    "extra": f"{radau.njev} Jacobians, {radau.nlu} LU",
                },
                {
                    "tol": tol,
                    "tool": "SciPy RK45, hand equations",
                    "steps": steps["RK45"],
                    "rejected": None,
                    "evaluations": rk45.nfev,
                    "seconds": best["RK45"],
                    "errors": errors(rk45.y[0]),
                },
            ]
            report(rows[-4:])

        # Radau over a range of tolerances, for the comparison at equal accuracy.
        print("\nSciPy Radau over its tolerances (hand equations)")
        radau_rows = []
        for tol in args.radau_tol:
            sol = scipy_run("Radau", tol)
            best = best_of_alternating({"Radau": partial(scipy_run, "Radau", tol)}, args.repeat, args.min_time)
            radau_rows.append(
                {
                    "tol": tol,
                    "tool": "SciPy Radau",
                    "steps": len(scipy_run("Radau", tol, None).t) - 1,
                    "rejected": None,
                    "evaluations": sol.nfev,
                    "seconds": best["Radau"],
                    "errors": errors(sol.y[0]),
                }
            )
        report(radau_rows)

    print("\nat equal accuracy (the largest error over the outputs):")
    for row in rows:
        if row["tool"].startswith("mechfem"):
            print(f"  {row['tool']:28} at {row['tol']:g}: {equal_accuracy(row, radau_rows)}")


def equal_accuracy(row: dict[str, Any], radau: list[dict[str, Any]]) -> str:
    """Radau's time at the error of mechfem's ``row``: the loosest Radau run at least as accurate, and the time
    interpolated (log-log) between the two Radau runs whose errors bracket mechfem's."""
    error, seconds = row["errors"][0], row["seconds"]
    good = [r for r in radau if r["errors"][0] <= error]
    if not good:
        return f"error {error:.1e}: no Radau run of --radau-tol is as accurate"
    match = max(good, key=lambda r: r["errors"][0])
    text = (
        f"error {error:.1e}, {seconds * 1e3:.2f} ms; Radau at {match['tol']:g} (error {match['errors'][0]:.1e}) "
        f"takes {match['seconds'] / seconds:.0f} times as long"
    )
    worse = [r for r in radau if r["errors"][0] > error]
    if worse:
        above = min(worse, key=lambda r: r["errors"][0])
        (e1, t1), (e2, t2) = ((r["errors"][0], r["seconds"]) for r in (above, match))
        at = math.exp(math.log(t1) + (math.log(error) - math.log(e1)) * (math.log(t2 / t1) / math.log(e2 / e1)))
        text += f", at mechfem's error (interpolated from {above['tol']:g}) {at / seconds:.0f} times"
    return text


def report(rows: list[dict[str, Any]]) -> None:
    for r in rows:
        largest, last = r["errors"]
        rejected = "" if r["rejected"] is None else f" ({r['rejected']} rejected)"
        extra = f", {r['extra']}" if r.get("extra") else ""
        print(
            f"  tol {r['tol']:<6g} {r['tool']:30} {r['steps']:>6} steps{rejected:15} {r['evaluations']:>7} evaluations"
            f"{extra}  {r['seconds'] * 1e3:9.2f} ms  error {largest:.1e} (last {last:.1e})",
            flush=True,
        )


if __name__ == "__main__":
    main()
