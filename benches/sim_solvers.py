"""The problems and solvers of the simulation work-precision benchmark (``bench_work_precision.py``).

A :class:`Problem` holds a mechfem deck, the output times, the peers' form of its equations and the quantities
compared (the benchmark's angles). A solver is built once for a problem (:meth:`Solver.build`: mechfem's decks
compiled, a peer's model or solver object made) and then run at a tolerance (:meth:`Solver.run`, the call that is
timed); :meth:`Solver.run_fresh`, where it differs, builds everything again inside the call (compiled per call).
mechfem's integrator is a parameter (:class:`Mechfem`'s ``integrator``: the deck's ``INTEGRATOR`` statement, or
none for the default), so every method a deck can ask for is measured by the same code.
"""

from __future__ import annotations

import math
import tempfile
import warnings
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np


@dataclass
class Run:
    """One run of a solver at one tolerance."""

    values: Any  # outputs x quantities, or None when the run did not reach the end
    evaluations: int | None = None  # evaluations of the equations of motion (right-hand side or residual)
    steps: int | None = None
    jacobians: int | None = None
    note: str = ""  # why the run did not reach the end, or what else to know
    gave_up: bool = False  # stopped by the evaluation budget: not timed


@dataclass
class Problem:
    name: str
    title: str
    deck: Path
    times: Any  # the output times
    quantities: list[str]
    read_mechfem: Callable[[dict[int, Any]], Any]  # a mechfem run's buffers -> outputs x quantities
    ode_rhs: Callable[[float, Any], Any]  # the peers' ODE form, vectorised
    y0: Any
    ida: tuple[Callable[..., None], Any, Any, list[int]]  # residual, y0, yp0, algebraic indices
    ida_jac: Callable[..., None] | None = None  # the residual's analytic Jacobian for IDA
    exudyn: Callable[[Any], Any] | None = None  # builds the Exudyn model (see sim_exudyn.py)
    stiff: bool = False
    extra: dict[str, Any] = field(default_factory=dict)

    def error(self, values: Any, reference: Any) -> float:
        """The largest absolute error over every output and quantity (radians)."""
        return float(np.abs(np.asarray(values) - reference).max())


class Solver:
    name = ""
    per_call_differs = False

    def build(self, problem: Problem) -> None:
        self.problem = problem

    def run(self, tol: float) -> Run:
        raise NotImplementedError

    def run_fresh(self, tol: float) -> Run:
        return self.run(tol)


# --- mechfem --------------------------------------------------------------------------------------------------------


def accuracy(tol: float) -> float:
    """The Newton tolerance (ACCURACY) with an integration tolerance: the default 1e-10, or ``tol`` below it."""
    return min(1e-10, tol)


def deck_at(text: str, tol: float, integrator: str | None, set_accuracy: bool = True) -> str:
    """The deck ``text`` with INTTOL ``tol``, ACCURACY :func:`accuracy` (with ``set_accuracy``; otherwise none, the
    default) and, if given, ``INTEGRATOR integrator``."""
    out = []
    for line in text.splitlines():
        word = line.split(";")[0].split()
        if word and word[0] in ("INTTOL", "ACCURACY", "INTEGRATOR"):
            continue
        out.append(line)
        if word and word[0] == "MOV_DYN":
            out.append(f"INTTOL\t{tol:.3e}\t{tol:.3e}")
            if set_accuracy:
                out.append(f"ACCURACY\t{accuracy(tol):.3e}")
            if integrator is not None:
                out.append(f"INTEGRATOR\t{integrator}")
    return "\n".join(out) + "\n"


class Mechfem(Solver):
    """mechfem running the problem's deck (``mechfem.run_deck``): compiled once per tolerance (a deck file run again
    unchanged is not read again), or per call (``run_deck_text``)."""

    per_call_differs = True

    def __init__(self, integrator: str | None = None, set_accuracy: bool = True) -> None:
        self.integrator, self.set_accuracy = integrator, set_accuracy
        self.name = "mechfem" + ("" if integrator is None else f" {integrator}")
        self._tmp = tempfile.TemporaryDirectory()
        self._decks: dict[float, Path] = {}

    def deck(self, tol: float) -> Path:
        if tol not in self._decks:
            path = Path(self._tmp.name) / f"{self.problem.name}_{len(self._decks)}.mec"
            path.write_text(deck_at(self.problem.deck.read_text(), tol, self.integrator, self.set_accuracy))
            self._decks[tol] = path
        return self._decks[tol]

    def run(self, tol: float) -> Run:
        import mechfem

        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            try:
                result = mechfem.run_deck(self.deck(tol), det=False)
            except mechfem.DeckError as e:  # a method this mechfem does not have
                return Run(None, note=str(e).splitlines()[0])
        return self._read(result)

    def run_fresh(self, tol: float) -> Run:
        from mechfem import _core
        from mechfem._util import limits
        from mechfem.results.result import run_result

        path = self.deck(tol)
        raw = _core.run_deck_text(path.read_text(), path, path.parent, memory_limit=limits.memory_limit(None))
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            return self._read(run_result(path, raw))

    def _read(self, result: Any) -> Run:
        sim, stop = result.simulation, result.report.stop
        # The Jacobians an implicit method formed.
        jacobians = None if sim is None else sim.jacobians
        if stop is None:
            values = self.problem.read_mechfem(result.buffers)
            return Run(values, sim.evaluations, sim.steps, jacobians)
        # The solver's own words, up to the hint that follows them.
        why = stop.message.split(" (")[0].split(": ")[-1]
        return Run(None, sim.evaluations, sim.steps, None, f"stopped at t = {sim.reached:.3g}: {why}")


# --- SciPy ----------------------------------------------------------------------------------------------------------


class GaveUp(Exception):
    """A run stopped by its evaluation budget, at time ``t``."""

    def __init__(self, t: float) -> None:
        self.t = t


class Counted:
    """A right-hand side that counts its evaluations (a vectorised call of k states counts k), and gives up
    (:class:`GaveUp`) beyond ``limit`` of them."""

    def __init__(self, fun: Callable[[float, Any], Any], limit: int) -> None:
        self.fun, self.count, self.limit = fun, 0, limit

    def __call__(self, t: float, y: Any) -> Any:
        self.count += 1 if y.ndim == 1 else y.shape[1]
        if self.count > self.limit:
            raise GaveUp(t)
        return self.fun(t, y)


# An explicit method on the stiff problem needs millions of evaluations of a Python right-hand side (minutes each):
# a counted run gives up beyond this many, and is not timed.
EVALUATION_BUDGET = 1_000_000


class Scipy(Solver):
    """``scipy.integrate.solve_ivp`` on the problem's ODE form, output at the problem's times (``t_eval``, its dense
    output); ``vectorized=True`` so that Radau's finite-difference Jacobian is one call of the right-hand side. There
    is nothing to build: the right-hand side is a Python function."""

    def __init__(self, method: str) -> None:
        self.method = method
        self.name = f"SciPy {method}"

    def solve(self, fun: Callable[[float, Any], Any], tol: float) -> Any:
        from scipy.integrate import solve_ivp

        p = self.problem
        return solve_ivp(
            fun, (p.times[0], p.times[-1]), p.y0, method=self.method, t_eval=p.times, rtol=tol, atol=tol,
            vectorized=True,
        )  # fmt: skip

    def run(self, tol: float) -> Run:
        sol = self.solve(self.problem.ode_rhs, tol)
        return self._read(sol)

    def counted(self, tol: float) -> Run:
        """A run whose evaluations are counted (not timed: the count costs a Python call per evaluation)."""
        fun = Counted(self.problem.ode_rhs, EVALUATION_BUDGET)
        try:
            run = self._read(self.solve(fun, tol))
        except GaveUp as stop:
            end = self.problem.times[-1]
            return Run(None, fun.count, None, None, f"gave up at t = {stop.t:.3g} of {end:g}", gave_up=True)
        run.evaluations = fun.count
        return run

    def _read(self, sol: Any) -> Run:
        n = len(self.problem.quantities)
        if not sol.success:
            return Run(None, sol.nfev, None, sol.njev, sol.message)
        return Run(sol.y[:n].T, sol.nfev, len(sol.t), sol.njev)


# --- SUNDIALS IDA (scikit-sundae) -----------------------------------------------------------------------------------


class Ida(Solver):
    """SUNDIALS IDA (variable-order BDF, scikit-sundae) on the problem's residual form, dense linear solver, output
    at the problem's times. The solver object is made once (:meth:`build`) and re-initialised by each ``solve``;
    ``run_fresh`` makes it in the call. With ``jacobian``, the problem's analytic Jacobian; otherwise IDA's own
    difference quotients (one residual per unknown and Jacobian)."""

    per_call_differs = True

    def __init__(self, jacobian: bool) -> None:
        self.jacobian = jacobian
        self.name = "IDA" + (" analytic J" if jacobian else "")
        self._solvers: dict[float, Any] = {}

    def make(self, tol: float, residual: Callable[..., None]) -> Any:
        from sksundae.ida import IDA

        p = self.problem
        res, y0, _, algebraic = p.ida
        atol = np.full(len(y0), tol)
        # IDA has no switch to leave the algebraic unknowns (multipliers) out of the error test; a large atol on
        # them does that (their error is the index-2 system's own and not what is compared).
        atol[algebraic] = 1e6
        options: dict[str, Any] = {
            "rtol": tol, "atol": atol, "linsolver": "dense", "max_num_steps": 1_000_000,
            "algebraic_idx": algebraic or None,
        }  # fmt: skip
        if self.jacobian and p.ida_jac is not None:
            options["jacfn"] = p.ida_jac
        return IDA(residual, **options)

    def build(self, problem: Problem) -> None:
        super().build(problem)
        self._solvers = {}

    def solver(self, tol: float) -> Any:
        if tol not in self._solvers:
            self._solvers[tol] = self.make(tol, self.problem.ida[0])
        return self._solvers[tol]

    def run(self, tol: float) -> Run:
        return self._read(self.solver(tol), tol)

    def run_fresh(self, tol: float) -> Run:
        return self._read(self.make(tol, self.problem.ida[0]), tol)

    def counted(self, tol: float) -> Run:
        calls = [0]
        res = self.problem.ida[0]

        def counting(t: float, y: Any, yp: Any, out: Any) -> None:
            calls[0] += 1
            res(t, y, yp, out)

        run = self._read(self.make(tol, counting), tol)
        run.evaluations = calls[0]
        return run

    def _read(self, solver: Any, tol: float) -> Run:
        p = self.problem
        _, y0, yp0, _ = p.ida
        sol = solver.solve(p.times, y0, yp0)
        n = len(p.quantities)
        if not sol.success:
            return Run(None, sol.nfev, None, sol.njev, sol.message)
        return Run(sol.y[:, :n], sol.nfev, None, sol.njev)


def sundae_version() -> str:
    try:
        from importlib.metadata import version

        return version("scikit-sundae")
    except Exception:  # noqa: BLE001
        return "not installed"


def interpolate(runs: list[tuple[float, float]], at: float) -> float | None:
    """The cost (second of each pair) at error ``at`` (first): log-log between the two runs whose errors bracket it
    on the method's work-precision front (a run that costs more than another without being more accurate is left
    out); None outside the front's range."""
    front: list[tuple[float, float]] = []
    for e, c in sorted((e, c) for e, c in runs if e > 0 and c > 0 and math.isfinite(e) and math.isfinite(c)):
        if not front or c < front[-1][1]:
            front.append((e, c))
    for (e1, c1), (e2, c2) in zip(front, front[1:], strict=False):
        if e1 <= at <= e2:
            w = (math.log(at) - math.log(e1)) / (math.log(e2) - math.log(e1))
            return math.exp(math.log(c1) + w * (math.log(c2) - math.log(c1)))
    return None
