"""The optimisation engine of ``KIN OPT`` and :func:`mechfem.optimize`: a problem in a deck's numbering, evaluated
by the compiled model handle ``_core.DesignModel`` (values and exact design sensitivities at every position, and at
the extrema of a reference), and solved with SciPy.

* Targets alone are least squares: ``scipy.optimize.least_squares`` (trust-region reflective, within the variables'
  ranges), with the Jacobian from the sensitivities.
* With bounds on buffers, a MINIMISE/MAXIMISE term or a Python objective: ``scipy.optimize.minimize`` with SLSQP,
  the bounds as inequality constraints at every position. A bound on a function of the design variables alone
  (:class:`DesignBound`: the frame length) is one more such inequality, with its exact gradient.

Every design is evaluated on the assembly branch of the start design, whatever was evaluated before: its position 1
is assembled from a prediction that depends on the design alone, and is accepted only with the start design's
orientation (the sign of the determinant of every group of co-ordinates found together, see docs/optimisation.md).
So a design's objective never depends on the order the optimiser evaluates designs in. A design that cannot be
assembled on that branch, whose motion leaves it (a limit position jumped over) or whose motion stops is infeasible:
the optimiser gets a value far worse than any it has seen, so its trust region or line search falls back towards the
last good design, and the solution counts the infeasible designs by reason.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Literal

import numpy as np
import numpy.typing as npt

import mechfem._core as _core
from mechfem.design.dynamic_design import magnitude, reduced
from mechfem.design.optimum import Optimum
from mechfem.design.rules import _EPS, _FEASIBLE, TURN, FTol, _Converged, _optimiser_bounds, _reported, _stop_message
from mechfem.errors import MechfemError

FloatArray = npt.NDArray[np.float64]
Reduce = Literal["max", "maxabs", "rms", "end"]


@dataclass
class ValuesTerm:
    """``weight * (buffer - values)^2`` at every position whose value is not NaN."""

    buffer: int
    values: FloatArray
    weight: float = 1.0


@dataclass
class AtTerm:
    """``weight * (buffer at position - value)^2``; ``position`` 0-based."""

    buffer: int
    position: int
    value: float
    weight: float = 1.0


@dataclass
class ExtremumTerm:
    """``weight * (buffer - value)^2`` at every extremum of ``reference``."""

    buffer: int
    reference: int
    value: float
    weight: float = 1.0


DesignModelOf = Callable[
    [list[tuple[int, int]], list[int], list[tuple[int, int]]], _core.DesignModel | _core.DynamicDesignModel
]
"""Compiles the model of a problem for its variables, the buffers evaluated and the extrema taken:
``(variables, buffers, extrema)`` as ``_core.DesignModel`` takes them."""


def deck_model(text: str, path: str, base_dir: str) -> DesignModelOf:
    """The design model of the deck ``text`` (named ``path``, its files read from ``base_dir``)."""

    def of(variables: list[tuple[int, int]], buffers: list[int], extrema: list[tuple[int, int]]) -> _core.DesignModel:
        return _core.DesignModel(text, path, base_dir, variables, buffers, extrema)

    return of


def built_model(builder: _core.ModelBuilder, base_dir: str) -> DesignModelOf:
    """The design model built by ``builder`` (a Python model's items, no deck text; table files in ``base_dir``)."""

    def of(variables: list[tuple[int, int]], buffers: list[int], extrema: list[tuple[int, int]]) -> _core.DesignModel:
        return builder.design(base_dir, variables, buffers, extrema)

    return of


@dataclass(frozen=True)
class DesignBound:
    """Constraint: ``lo <= f(x) <= hi`` for a function of the design variables alone (no run of the mechanism),
    ``f(x)`` returning its value and exact gradient; ``name`` says what it bounds."""

    name: str
    f: Callable[[FloatArray], tuple[float, FloatArray]]
    lo: float
    hi: float


@dataclass
class Problem:
    """An optimisation in a deck's numbering: buffers are buffer numbers of the model ``model`` compiles."""

    model: DesignModelOf
    variables: list[tuple[int, int]]
    """``(kind, number)``: kind 0 a fixed co-ordinate, 1 a prescribed row."""
    names: list[str]
    lo: FloatArray
    hi: FloatArray
    terms: list[ValuesTerm | AtTerm | ExtremumTerm] = field(default_factory=list)
    bounds: list[tuple[int, float, float]] = field(default_factory=list)
    design_bounds: list[DesignBound] = field(default_factory=list)
    """Bounds on functions of the variables alone (the frame length)."""
    objective: tuple[Literal[1, -1], Reduce, int] | None = None
    """``(sense, reduce, buffer)``: +1 minimise, -1 maximise."""
    objective_with: int | None = None
    """A second buffer of the MINIMISE/MAXIMISE term: the term is then of the magnitude ``sqrt(b^2 + b2^2)`` at
    every position (a force's x and y)."""
    custom: Callable[[Evaluation], tuple[float, FloatArray]] | None = None
    extra_buffers: list[int] = field(default_factory=list)
    """Buffers evaluated for ``custom`` beyond those of the terms."""
    steps: int = 200
    tol: float | None = None
    """The classic stopping tolerance (OPTTOL): least squares stop when an accepted step changes the sum of squares
    by less than ``tol`` times it, SLSQP when an iteration changes the objective by less than ``tol`` times the
    start objective (at least ``tol``)."""
    stop: FTol | None = None
    """Stopping tolerances independent of the start objective (OPTFTOL); when given, ``tol`` is not used."""
    periodic: list[bool] = field(default_factory=list)
    """Per variable (empty: none): an angle that wraps. The optimiser sees it without bounds; it is evaluated at
    the value a whole number of turns away that lies within half a turn of its start value, and reported within
    ``[lo, lo + 2 pi)``."""
    whole_turn: float = TURN
    """One turn in the angles' unit: 2 pi, or 360 in a model whose angles are in degrees."""


@dataclass
class Iteration:
    """One iteration of the optimiser: its objective, the largest violation of a bound, the step's size (the
    largest change of a variable), the mechanism runs so far and the design ``x`` it reached."""

    number: int
    objective: float
    violation: float
    step: float
    runs: int
    x: FloatArray = field(default_factory=lambda: np.zeros(0), repr=False)


class NonFiniteObjective(MechfemError, ValueError):
    """The objective or its gradient is not finite at a design: a target's buffer is so far from its value, or so
    heavily weighted, that its squared difference overflows. ``term`` is the target's index in the problem's
    terms, None for the MINIMISE/MAXIMISE term or a Python objective."""

    def __init__(self, message: str, term: int | None) -> None:
        super().__init__(message)
        self.term = term


_KEYWORDS = {"ValuesTerm": "TARGET", "AtTerm": "TARGETAT", "ExtremumTerm": "TARGETEXT"}


def _finite_terms(problem: Problem, res: list[FloatArray], jac: list[FloatArray]) -> None:
    """Raises :class:`NonFiniteObjective` for the first target whose residuals, Jacobian or share of the sum of
    squares is not finite (the sum itself included), before anything squares them where numpy would warn."""
    total = 0.0
    with np.errstate(all="ignore"):
        for k, (t, r, j) in enumerate(zip(problem.terms, res, jac, strict=True)):
            total += float(r @ r)
            if not (np.all(np.isfinite(r)) and np.all(np.isfinite(j)) and math.isfinite(total)):
                raise NonFiniteObjective(
                    f"the objective is not finite: the weighted squared difference of the "
                    f"{_KEYWORDS[type(t).__name__]} on buffer {t.buffer} overflows (the buffer lies too far from "
                    "the value asked for, or the weight is too large)",
                    k,
                )


class Infeasible(MechfemError):
    """The start design of an optimisation cannot be assembled or moved through the whole motion."""


class Evaluation:
    """One design evaluated: every buffer at every position and its derivatives with respect to the variables."""

    def __init__(self, column: dict[int, int], x: FloatArray, d: _core.Evaluation) -> None:
        self.x = x
        self._column = column
        self._values: FloatArray = d.values
        self._gradient: FloatArray = d.gradient
        self.extrema: list[_core.Extremum] = d.extrema
        self.position_one: list[float] = list(d.position_one or [])
        """The design's co-ordinates at position 1, in deck order."""

    def value(self, buffer: int) -> FloatArray:
        """The buffer at every position."""
        return np.asarray(self._values[:, self._column[buffer]], dtype=np.float64)

    def gradient(self, buffer: int) -> FloatArray:
        """Its derivative with respect to every variable: positions x variables."""
        return np.asarray(self._gradient[:, self._column[buffer], :], dtype=np.float64)


def _buffers(problem: Problem) -> list[int]:
    out: list[int] = []
    for b in [t.buffer for t in problem.terms] + [b for b, _, _ in problem.bounds]:
        if b not in out:
            out.append(b)
    if problem.objective is not None and problem.objective[2] not in out:
        out.append(problem.objective[2])
    if problem.objective_with is not None and problem.objective_with not in out:
        out.append(problem.objective_with)
    return out + [b for b in problem.extra_buffers if b not in out]


def _extrema(problem: Problem) -> list[tuple[int, int]]:
    return [(t.buffer, t.reference) for t in problem.terms if isinstance(t, ExtremumTerm)]


class Evaluator:
    """Evaluates designs through one compiled model, counting runs and remembering the best design seen."""

    def __init__(self, problem: Problem) -> None:
        self.problem = problem
        buffers = _buffers(problem)
        self._column = {b: k for k, b in enumerate(buffers)}
        self.model = problem.model(problem.variables, buffers, _extrema(problem))
        self._cache: tuple[bytes, Evaluation | str] | None = None
        self.extrema_count: list[int] | None = None
        self.infeasible = 0
        """How many designs evaluated were infeasible."""
        self.reasons: dict[str, tuple[int, str]] = {}
        """Infeasible designs by kind of reason (see ``DesignModel.evaluate``): how many, and the first one's reason."""
        self._turns = np.array(problem.periodic, dtype=bool) if any(problem.periodic) else None
        self._centre: FloatArray | None = None

    def wrapped(self, x: FloatArray) -> FloatArray:
        """``x`` with every periodic variable moved by whole turns to within half a turn of its start value: the
        same mechanism, assembled by a continuation from the start design that never goes round the long way."""
        x = np.asarray(x, dtype=np.float64)
        if self._turns is None or self._centre is None:
            return x
        d = x - self._centre
        turn = self.problem.whole_turn
        return np.where(self._turns, self._centre + (d - turn * np.round(d / turn)), x)

    @property
    def runs(self) -> int:
        return int(self.model.runs)

    def start(self) -> FloatArray:
        return np.asarray(self.model.start(), dtype=np.float64)

    def start_at(self, x: FloatArray) -> Evaluation:
        """Evaluates ``x`` as the start design: its assembly branch is that of every later evaluation, its number of
        extrema that of every TARGETEXT. Raises :class:`Infeasible` with the reason."""
        self._cache = None
        self._centre = np.array(x, dtype=np.float64)
        d = self.model.start_at([float(v) for v in x])
        if not d.feasible:
            raise Infeasible(str(d.reason))
        e = Evaluation(self._column, np.array(x), d)
        self.extrema_count = _extremum_counts(self.problem, e)
        return e

    def __call__(self, x: FloatArray) -> Evaluation:
        """The evaluation at ``x``; raises :class:`Infeasible` with the reason."""
        x = self.wrapped(x)
        key = x.tobytes()
        if self._cache is None or self._cache[0] != key:
            d = self.model.evaluate([float(v) for v in x])
            result: Evaluation | str = str(d.reason)
            kind = str(d.reason_kind)
            if d.feasible:
                result, kind = Evaluation(self._column, np.array(x), d), "extrema"
                counts = _extremum_counts(self.problem, result)
                if self.extrema_count is None:
                    self.extrema_count = counts
                elif counts != self.extrema_count:
                    result = (
                        f"the reference of a TARGETEXT has {counts} extrema here, {self.extrema_count} at the start"
                    )
            if isinstance(result, str):
                self.infeasible += 1
                n, first = self.reasons.get(kind, (0, result))
                self.reasons[kind] = (n + 1, first)
            self._cache = (key, result)
        found = self._cache[1]
        if isinstance(found, str):
            raise Infeasible(found)
        return found


def _extremum_counts(problem: Problem, e: Evaluation) -> list[int]:
    specs = [t for t in problem.terms if isinstance(t, ExtremumTerm)]
    return [sum(1 for x in e.extrema if x.spec == k) for k in range(len(specs))]


# --- the objective -------------------------------------------------------------------------------------------------


def residuals(problem: Problem, e: Evaluation) -> tuple[FloatArray, FloatArray]:
    """The least-squares residuals ``sqrt(w) (b - value)`` of every target and their Jacobian."""
    res: list[FloatArray] = []
    jac: list[FloatArray] = []
    n = len(problem.variables)
    # An overflow is found and named by _finite_terms below, not warned of by numpy on the way.
    with np.errstate(over="ignore", invalid="ignore"):
        _residual_terms(problem, e, res, jac)
    if not res:
        return np.zeros(0), np.zeros((0, n))
    _finite_terms(problem, res, jac)
    return np.concatenate(res), np.vstack(jac)


def _residual_terms(problem: Problem, e: Evaluation, res: list[FloatArray], jac: list[FloatArray]) -> None:
    """The residuals and Jacobian rows of every term of ``problem`` at ``e``, appended to ``res`` and ``jac``."""
    n = len(problem.variables)
    k_ext = 0
    for t in problem.terms:
        w = math.sqrt(t.weight)
        if isinstance(t, ValuesTerm):
            v, g = e.value(t.buffer), e.gradient(t.buffer)
            keep = ~np.isnan(t.values)
            res.append(w * (v[keep] - t.values[keep]))
            jac.append(w * g[keep])
        elif isinstance(t, AtTerm):
            res.append(w * (e.value(t.buffer)[t.position : t.position + 1] - t.value))
            jac.append(w * e.gradient(t.buffer)[t.position : t.position + 1])
        else:
            found = [x for x in e.extrema if x.spec == k_ext]
            k_ext += 1
            res.append(np.array([w * (x.value - t.value) for x in found], dtype=np.float64))
            jac.append(np.array([w * np.asarray(x.gradient) for x in found], dtype=np.float64).reshape(-1, n))


def misses(problem: Problem, e: Evaluation) -> list[tuple[float, int | None]]:
    """How far each target is from its value at ``e``: the largest difference (unweighted) and the position
    (0-based) where it is, None for a TARGETEXT; NaN where a target compares nothing."""
    out: list[tuple[float, int | None]] = []
    k_ext = 0
    for t in problem.terms:
        if isinstance(t, ValuesTerm):
            d = np.abs(e.value(t.buffer) - t.values)
            k = int(np.nanargmax(d)) if np.any(~np.isnan(d)) else None
            out.append((float(d[k]) if k is not None else math.nan, k))
        elif isinstance(t, AtTerm):
            out.append((abs(float(e.value(t.buffer)[t.position]) - t.value), t.position))
        else:
            found = [abs(x.value - t.value) for x in e.extrema if x.spec == k_ext]
            k_ext += 1
            out.append((max(found) if found else math.nan, None))
    return out


def objective(problem: Problem, e: Evaluation) -> tuple[float, FloatArray]:
    """Sum of squares of the targets, plus the MINIMISE/MAXIMISE term, plus a Python objective; with gradient."""
    r, j = residuals(problem, e)
    with np.errstate(all="ignore"):
        f, g = float(r @ r), 2.0 * (r @ j)
        if problem.objective is not None:
            sense, reduce, b = problem.objective
            v, gv = e.value(b), e.gradient(b)
            if problem.objective_with is not None:
                v, gv = magnitude(v, gv, e.value(problem.objective_with), e.gradient(problem.objective_with))
            fo, go = reduced(reduce, v, gv)
            f, g = f + sense * fo, g + sense * go
            _finite_objective(f, g, "the MINIMISE or MAXIMISE term")
        if problem.custom is not None:
            fc, gc = problem.custom(e)
            f, g = f + float(fc), g + np.asarray(gc, dtype=np.float64)
            _finite_objective(f, g, "the objective function given")
    _finite_objective(f, g, "the sum of the targets' squared differences")
    return f, np.asarray(g, dtype=np.float64)


def _finite_objective(f: float, g: FloatArray, what: str) -> None:
    if not (math.isfinite(f) and np.all(np.isfinite(g))):
        raise NonFiniteObjective(f"the objective is not finite: {what} overflows (or its gradient does)", None)


def constraints(problem: Problem, e: Evaluation) -> tuple[FloatArray, FloatArray]:
    """Every bound as ``c >= 0`` at every position, and the Jacobian."""
    cs: list[FloatArray] = [np.zeros(0)]
    js: list[FloatArray] = [np.zeros((0, len(problem.variables)))]
    for b, lo, hi in problem.bounds:
        v, g = e.value(b), e.gradient(b)
        cs += [v - lo, hi - v]
        js += [g, -g]
    for d in problem.design_bounds:
        f, df = d.f(e.x)
        cs += [np.array([f - d.lo, d.hi - f])]
        js += [np.vstack([df, -df])]
    return np.concatenate(cs), np.vstack(js)


def violation(problem: Problem, e: Evaluation) -> float:
    c, _ = constraints(problem, e)
    return float(max(0.0, -c.min())) if c.size else 0.0


# --- solving -------------------------------------------------------------------------------------------------------


@dataclass
class _Best:
    """The last design the optimiser moved to: where an infeasible one falls back to, without another run."""

    x: FloatArray
    f: float
    e: Evaluation


def solve(problem: Problem, report: Callable[[Iteration], object] | None = None) -> Optimum:
    """Optimises from the problem's start design; ``report`` is called with every iteration. The optimum holds the
    variables by the problem's names in its order, the final evaluation and the targets' misses there; whoever
    stated the problem adds what it knows (the mechanism, the deck)."""
    if len(set(problem.names)) != len(problem.names):
        raise ValueError(f"the design variables' names are not unique: {problem.names}")
    from scipy import optimize

    t0 = time.perf_counter()
    ev = Evaluator(problem)
    x0 = np.clip(ev.start(), problem.lo, problem.hi)
    try:
        e0 = ev.start_at(x0)
    except Infeasible as err:
        raise Infeasible(f"the start design is infeasible: {err}") from None
    f0, _ = objective(problem, e0)
    history: list[Iteration] = [Iteration(0, f0, violation(problem, e0), 0.0, ev.runs, np.array(x0))]
    best = _Best(x0, f0, e0)
    if report is not None:
        report(history[0])

    def note(x: FloatArray, e: Evaluation) -> None:
        f, _ = objective(problem, e)
        step = float(np.max(np.abs(x - best.x)))
        it = Iteration(len(history), f, violation(problem, e), step, ev.runs, np.array(x))
        history.append(it)
        best.x, best.f, best.e = np.array(x), f, e
        if report is not None:
            report(it)

    def feasible(x: FloatArray) -> Evaluation:
        """The evaluation at ``x``, or the best design's when ``x`` is infeasible."""
        try:
            return ev(x)
        except Infeasible:
            return best.e

    constrained = bool(problem.bounds or problem.design_bounds)
    least_squares = not constrained and problem.objective is None and problem.custom is None
    if least_squares:

        def fun(x: FloatArray) -> FloatArray:
            try:
                e = ev(x)
            except Infeasible:
                return 1e3 * (1.0 + np.abs(residuals(problem, best.e)[0]))
            r, _ = residuals(problem, e)
            f = float(r @ r)
            if f < best.f:
                before = best.f
                note(x, e)
                if problem.stop is not None and problem.stop.met(before, f):
                    raise _Converged
            return r

        def jac(x: FloatArray) -> FloatArray:
            return residuals(problem, feasible(x))[1]

        tol = problem.tol if problem.tol is not None else 1e-12
        if problem.stop is not None:
            # SciPy's relative test is the same as FTol's when rtol is above the rounding (below it SciPy warns);
            # the absolute part is tested in fun.
            tol = problem.stop.rtol if problem.stop.rtol > _EPS else None  # type: ignore[assignment]
        method = "least_squares (trf)"
        try:
            out = optimize.least_squares(
                fun,
                x0,
                jac=jac,
                bounds=_optimiser_bounds(problem),
                method="trf",
                x_scale="jac",
                ftol=tol,
                xtol=1e-12,
                gtol=1e-12,
                max_nfev=max(problem.steps, 1),
            )
            x, success, message = out.x, bool(out.success), str(out.message)
        except _Converged:
            x, success, message = best.x, True, _stop_message(problem.stop)
    else:
        scale = np.maximum(problem.hi - problem.lo, 1e-12)  # a turn for a periodic variable

        def fg(x: FloatArray) -> tuple[float, FloatArray]:
            try:
                e = ev(x)
            except Infeasible:
                # A bowl around the last good design, steep against the objective's size: the value and its
                # gradient agree, so the line search steps back along the way it came, and by interpolation
                # rather than by a fixed fraction, towards where the designs stop being feasible.
                d = (np.asarray(x, dtype=np.float64) - best.x) / scale
                w = 1e3 * (1.0 + min(abs(best.f), 1e300))
                return best.f + w * (1e-6 + float(d @ d)), 2.0 * w * d / scale
            f, g = objective(problem, e)
            # The best feasible design met, not only the optimiser's iterates: the last of them may be infeasible.
            if f < best.f and violation(problem, e) == 0.0:
                note(np.asarray(x, dtype=np.float64), e)
            return f, g

        def cons(x: FloatArray) -> FloatArray:
            try:
                return constraints(problem, ev(x))[0]
            except Infeasible:
                return -np.ones_like(constraints(problem, best.e)[0])

        last = [f0]

        def callback(xk: FloatArray) -> None:
            if np.array_equal(xk, best.x):
                e = best.e  # noted when it was evaluated
            else:
                try:
                    e = ev(xk)
                except Infeasible:
                    return
                note(np.asarray(xk), e)
            if problem.stop is None:
                return
            f, _ = objective(problem, e)
            before, last[0] = last[0], f
            if problem.stop.met(before, f) and violation(problem, e) <= _FEASIBLE:
                raise _Converged

        def cons_jac(x: FloatArray) -> FloatArray:
            return constraints(problem, feasible(x))[1]

        tol = problem.tol if problem.tol is not None else 1e-10
        # SLSQP's own test is absolute (|f_k - f_k-1| < ftol, the bounds met within ftol); OPTTOL scales it by the
        # start objective. FTol's relative part is tested in the callback, its absolute part is SLSQP's.
        ftol = tol * max(1.0, abs(f0)) if problem.stop is None else max(problem.stop.atol, 1e-300)
        method = "SLSQP"
        try:
            # scipy-stubs types a constraint's "fun" as scalar-valued; SLSQP takes a vector of constraints from one
            # function (and its Jacobian as a matrix), as used here.
            out = optimize.minimize(  # type: ignore[call-overload]
                fg,
                x0,
                jac=True,
                method="SLSQP",
                bounds=[
                    (None, None) if math.isinf(a) else (a, b) for a, b in zip(*_optimiser_bounds(problem), strict=True)
                ],
                constraints=[{"type": "ineq", "fun": cons, "jac": cons_jac}] if constrained else [],
                callback=callback,
                options={"maxiter": max(problem.steps, 1), "ftol": ftol},
            )
            x, success, message = out.x, bool(out.success), str(out.message)
        except _Converged:
            x, success, message = best.x, True, _stop_message(problem.stop)
    try:
        e = ev(x)
    except Infeasible:
        x, e = best.x, best.e
    f, _ = objective(problem, e)
    if not np.array_equal(x, best.x):
        note(x, e)
    final_x = _reported(problem, np.asarray(x, dtype=np.float64))
    specs = [t for t in problem.terms if isinstance(t, ExtremumTerm)]
    return Optimum(
        mechanism=None,
        start=dict(zip(problem.names, map(float, x0), strict=True)),
        values=dict(zip(problem.names, map(float, final_x), strict=True)),
        objective=float(f),
        start_objective=float(f0),
        history=history,
        runs=ev.runs,
        infeasible=ev.infeasible,
        reasons=dict(ev.reasons),
        success=success,
        message=message,
        seconds=time.perf_counter() - t0,
        method=method,
        misses=misses(problem, e),
        extrema=[(specs[ex.spec], ex.input, ex.value) for ex in e.extrema],
        final=e,
    )
