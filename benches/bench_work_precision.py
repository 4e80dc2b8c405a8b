"""Work-precision of mechfem's simulation (DYN SIM) against SciPy, SUNDIALS IDA and Exudyn on two mechanisms:
error against wall time and against evaluations of the equations of motion, over a range of tolerances.

    .venv/bin/python benches/bench_work_precision.py                      # everything (some minutes)
    .venv/bin/python benches/bench_work_precision.py --problem andrews --quick

The mechanisms (``benches/decks/``):

* ``andrews``: Andrews' squeezing mechanism (seven bodies, a spring, a drive torque), 0.03 s from rest, an output
  every millisecond; compared: the seven benchmark angles at the 31 outputs (``andrews.py``).
* ``stiff``: a four-bar with a spring and a strong damper on its rocker, a stiffness ratio of 1.2e5 to 2e6, 5 s from
  rest, an output every 10 ms; compared: the crank angle and its speed at the 501 outputs (``stiff_fourbar.py``).

The error of a run is the largest absolute error over every output and compared quantity against a reference of
this script's own, converged far below the errors measured: the problem's equations by SciPy's DOP853 (andrews) or
Radau (stiff) at rtol = atol = 1e-13, checked against a second method (Radau, LSODA) and against mechfem at its
tightest tolerance, whose differences are printed (the reference's own accuracy). For Andrews, the published
reference at t = 0.03 (PSIDE, itself about 2.7e-10 off) is printed beside it.

The solvers, each built once for a problem and then timed at each tolerance ``--tol`` (rtol = atol), the best of at
least ``--repeat`` calls and of more until they have taken ``--min-time`` seconds:

* mechfem: the deck run by ``mechfem.run_deck`` (compiled once: a deck file run again unchanged is not read again),
  and, where the deck reading shows, by ``run_deck_text`` (compiled in every call); each ``--mechfem`` method is the
  deck's ``INTEGRATOR`` statement (``default``: none): by default ``auto``, ``dopri5``, ``dop853`` and ``radau5``.
  INTTOL is the tolerance; no ACCURACY, so that the Newton tolerance follows from INTTOL as in a user's deck
  (``--accuracy tol``: ACCURACY 1e-10 or the tolerance below it).
* SciPy ``solve_ivp``: Radau, DOP853 and LSODA (``--scipy``) on the index-1 ODE form, right-hand sides vectorised
  NumPy (``vectorized=True``: Radau's finite-difference Jacobian is one call).
* SUNDIALS IDA (scikit-sundae): Andrews in the stabilised index-2 (GGL) form, the four-bar as an implicit ODE; with
  IDA's difference-quotient Jacobian and with an analytic one; built once (compiled per call beside it).
* Exudyn: generalized-alpha (index-3 DAE of rigid bodies and joints, fixed step: its accuracy is set by the step,
  ``--exudyn-steps``), built and assembled once.

Evaluations are counted in a separate, untimed run: every call of the right-hand side or residual, Jacobian
columns included (a vectorised call of k states counts k); mechfem's are the equations of motion its integrator
evaluated (one Newton position each). A run that takes longer than ``--budget`` seconds, or does not reach the
end, is timed once (to its stop), and the method is not run at tighter tolerances; an explicit SciPy method gives
up after a million evaluations. The peers are installed into ``.venv-bench`` (created on first use; the script
re-runs itself there), never into mechfem's ``.venv``; mechfem is imported from this source tree (``python/``, with
the compiled module ``make install`` builds). Nothing here asserts a time: it is a benchmark, not a test.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import sys
import time
from functools import partial
from typing import Any

from benchenv import ROOT, ensure_venv

# The peers and the versions measured in docs/simulation-benchmarks.md.
PEERS = ["scipy==1.17.1", "scikit-sundae==1.2.0", "exudyn==1.13.6"]
TARGETS = [1e-4, 1e-6, 1e-8, 1e-10]
# mechfem's INTEGRATOR methods that can afford the stiff problem at a tight tolerance.
STIFF_OK = ("implicit", "radau5", "auto", None)


def problems(names: list[str]) -> list[Any]:
    import andrews
    import numpy as np
    import sim_exudyn
    import stiff_fourbar
    from sim_solvers import Problem

    out = []
    if "andrews" in names:
        out.append(
            Problem(
                name="andrews",
                title="Andrews' squeezing mechanism, 0.03 s, 31 outputs, 7 angles",
                deck=andrews.DECK,
                times=np.linspace(0.0, andrews.T_END, andrews.OUTPUTS + 1),
                quantities=andrews.NAMES,
                read_mechfem=andrews.angles,
                ode_rhs=andrews.ode_rhs,
                y0=np.concatenate([andrews.Q0, np.zeros(7)]),
                ida=(andrews.ggl_residual, *andrews.consistent_start(), list(range(14, 26))),
                ida_jac=andrews.ggl_jacobian,
                exudyn=sim_exudyn.andrews,
            )
        )
    if "stiff" in names:
        f = stiff_fourbar
        out.append(
            Problem(
                name="stiff",
                title="stiff four-bar, 5 s, 501 outputs, crank angle and speed",
                deck=f.DECK,
                times=np.linspace(0.0, f.T_END, f.OUTPUTS + 1),
                quantities=["crank angle", "crank speed"],
                read_mechfem=lambda b: np.stack([np.asarray(b[2]), np.asarray(b[3])], axis=1),
                ode_rhs=f.ode_rhs,
                y0=np.array([f.Q0, 0.0]),
                ida=(f.residual, np.array([f.Q0, 0.0]), np.array([0.0, f.TORQUE / f.terms(f.Q0)[0]]), []),
                ida_jac=f.jacobian,
                exudyn=sim_exudyn.stiff_fourbar,
                stiff=True,
            )
        )
    return out


def reference(problem: Any, mechfem_tight: Any) -> tuple[Any, list[str]]:
    """The problem's reference solution and lines saying how far it is from the checks."""
    import numpy as np
    from scipy.integrate import solve_ivp

    p = problem
    n = len(p.quantities)

    def solve(method: str, tol: float) -> Any:
        sol = solve_ivp(
            p.ode_rhs, (p.times[0], p.times[-1]), p.y0, method=method, t_eval=p.times, rtol=tol, atol=tol,
            vectorized=True,
        )  # fmt: skip
        assert sol.success, sol.message
        return sol.y[:n].T

    main, checks = ("Radau", ["LSODA"]) if p.stiff else ("DOP853", ["Radau"])
    ref = solve(main, 1e-13)
    lines = [f"reference: SciPy {main} at rtol = atol = 1e-13 on the problem's equations"]
    for method in checks:
        lines.append(f"  against {method} at 1e-12: {np.abs(solve(method, 1e-12) - ref).max():.1e}")
    if mechfem_tight is not None:
        lines.append(f"  against mechfem at its tightest run: {np.abs(mechfem_tight - ref).max():.1e}")
    if p.name == "andrews":
        import andrews

        lines.append(
            f"  at t = 0.03 against the published reference: {np.abs(ref[-1] - andrews.Q_PUBLISHED).max():.1e}"
        )
    return ref, lines


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--problem", nargs="+", default=["andrews", "stiff"], choices=["andrews", "stiff"])
    parser.add_argument("--tol", type=float, nargs="+", default=[1e-4, 1e-6, 1e-8, 1e-10, 1e-12])
    parser.add_argument(
        "--mechfem",
        nargs="+",
        default=["auto", "dopri5", "dop853", "radau5"],
        help="the deck's INTEGRATOR methods ('default': no statement)",
    )
    parser.add_argument(
        "--accuracy",
        choices=["tol", "default"],
        default="default",
        help="mechfem's ACCURACY: none, the deck's default, which follows from INTTOL ('default'), or 1e-10 or the "
        "tolerance below it ('tol')",
    )
    parser.add_argument("--scipy", nargs="*", default=["Radau", "DOP853", "LSODA"])
    parser.add_argument("--no-ida", action="store_true")
    parser.add_argument("--no-exudyn", action="store_true")
    parser.add_argument(
        "--exudyn-steps", type=int, nargs="+", default=[10, 32, 100, 320, 1000], help="Exudyn's steps per output"
    )
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--min-time", type=float, default=0.3, help="seconds of calls per timing, at least")
    parser.add_argument("--budget", type=float, default=5.0, help="a run longer than this is timed once")
    parser.add_argument("--quick", action="store_true", help="--tol 1e-6 1e-9 --repeat 1 --min-time 0")
    parser.add_argument("--json", help="write every run to this file")
    args = parser.parse_args()
    if args.quick:
        args.tol, args.repeat, args.min_time = [1e-6, 1e-9], 1, 0.0
        args.exudyn_steps = [32, 320]
    ensure_venv(PEERS, ".work-precision-stamp")
    sys.path.insert(0, str(ROOT / "python"))

    import numpy as np
    import scipy
    from bench_simulation import machine
    from sim_exudyn import Exudyn, exudyn_version
    from sim_solvers import Ida, Mechfem, Scipy, sundae_version

    print(f"machine: {machine()}")
    print(f"versions: numpy {np.__version__}, scipy {scipy.__version__}, scikit-sundae {sundae_version()}, "
          f"exudyn {exudyn_version()}")  # fmt: skip
    rows: list[dict[str, Any]] = []
    for problem in problems(args.problem):
        print(f"\n== {problem.title}")
        if problem.name == "stiff":
            import stiff_fourbar as f

            ratio = f.stiffness_ratio(*f.reference_states())
            print(f"stiffness ratio along the motion: {ratio.min():.2g} to {ratio.max():.2g}")
        set_accuracy = args.accuracy == "tol"
        solvers: list[Any] = [Mechfem(None if m == "default" else m, set_accuracy) for m in args.mechfem]
        solvers += [Scipy(m) for m in args.scipy]
        if not args.no_ida and sundae_version() != "not installed":
            solvers += [Ida(jacobian=False), Ida(jacobian=True)]
        for s in solvers:
            s.build(problem)
        # mechfem's tightest run checks the reference; on the stiff problem only an implicit method's is affordable.
        checks = [s for s in solvers if isinstance(s, Mechfem) and (not problem.stiff or s.integrator in STIFF_OK)]
        tight = checks[-1].run(min(args.tol)).values if checks else None
        ref, lines = reference(problem, tight)
        print("\n".join(lines))
        for s in solvers:
            rows += measure(problem, s, args.tol, ref, args)
        if not args.no_exudyn and problem.exudyn is not None and exudyn_version() != "not installed":
            ex = Exudyn()
            ex.build(problem)
            steps = [k * (len(problem.times) - 1) for k in args.exudyn_steps]
            rows += measure(problem, ex, steps, ref, args, knob="steps")
        summary(problem, [r for r in rows if r["problem"] == problem.name])
        if args.json:
            with open(args.json, "w") as out:
                record = {"machine": machine(), "load": os.getloadavg(), "rows": rows}
                json.dump(record, out, indent=1, default=lambda o: o.item())  # NumPy's integers


def measure(
    problem: Any, solver: Any, knobs: list[Any], ref: Any, args: Any, knob: str = "tol"
) -> list[dict[str, Any]]:
    """Runs ``solver`` at each tolerance (or step count), times it and prints a row each."""
    from bench_simulation import best_of_alternating

    out = []
    for k in knobs:
        t = time.perf_counter()
        run = solver.counted(k) if hasattr(solver, "counted") else solver.run(k)
        first = time.perf_counter() - t
        row: dict[str, Any] = {
            "problem": problem.name, "solver": solver.name, knob: k, "evaluations": run.evaluations,
            "steps": run.steps, "jacobians": run.jacobians, "note": run.note,
            "error": None if run.values is None else problem.error(run.values, ref),
        }  # fmt: skip
        if run.gave_up:
            row["seconds"], row["timed"] = None, "no"
        elif first > args.budget or run.values is None:
            row["seconds"], row["timed"] = first, "once"
        else:
            calls = {"once": partial(solver.run, k)}
            if solver.per_call_differs:
                calls["fresh"] = partial(solver.run_fresh, k)
            best = best_of_alternating(calls, args.repeat, args.min_time)
            row["seconds"], row["timed"] = best["once"], "best"
            if "fresh" in best:
                row["seconds_fresh"] = best["fresh"]
        out.append(row)
        print_row(row, knob)
        if first > args.budget or run.gave_up:
            print(f"  ({solver.name}: {first:.1f} s for one run; tighter {knob} left out)", flush=True)
            break
        if run.values is None and knob == "tol":
            print(f"  ({solver.name} did not finish; tighter {knob} left out)", flush=True)
            break
    return out


def print_row(r: dict[str, Any], knob: str) -> None:
    at = f"{r[knob]:g}" if knob == "tol" else f"{r[knob]} steps"
    ev = "" if r["evaluations"] is None else f"{r['evaluations']:>9} ev"
    jac = "" if not r.get("jacobians") else f" {r['jacobians']:>5} J"
    err = "  did not finish" if r["error"] is None else f"  error {r['error']:.1e}"
    fresh = "" if "seconds_fresh" not in r else f" (compiled per call {r['seconds_fresh'] * 1e3:.2f} ms)"
    note = f"  [{r['note']}]" if r["note"] else ""
    sec = "not timed" if r["seconds"] is None else f"{r['seconds'] * 1e3:10.2f} ms"
    print(f"  {r['solver']:22} {at:>12} {ev}{jac:8} {sec}{fresh}{err}{note}", flush=True)


def summary(problem: Any, rows: list[dict[str, Any]]) -> None:
    """Each solver's time and evaluations at equal errors (log-log between the runs that bracket them)."""
    from sim_solvers import interpolate

    print(f"\n{problem.name}: at equal error, time (ms) / evaluations (log-log interpolated between runs)")
    print("  " + " " * 22 + "".join(f"{e:>22.0e}" for e in TARGETS))
    for name in dict.fromkeys(r["solver"] for r in rows):
        mine = [r for r in rows if r["solver"] == name and r["error"] is not None]
        cells = []
        for target in TARGETS:
            sec = interpolate([(r["error"], r["seconds"] or math.nan) for r in mine], target)
            ev = interpolate([(r["error"], r["evaluations"] or math.nan) for r in mine], target)
            cells.append("-" if sec is None else f"{sec * 1e3:.3g}" + ("" if ev is None else f" / {ev:.3g}"))
        print(f"  {name:22}" + "".join(f"{c:>22}" for c in cells))


if __name__ == "__main__":
    main()
