"""Design sensitivities and optimisation of a named mechanism: :func:`optimize` and the targets it takes.

A quantity is named as for :meth:`RunResult.value` (a co-ordinate such as ``"C.x"``, a row or an output; :class:`Q`
for its transfer function of order 1 or 2 with respect to an input). Each quantity becomes a buffer of a model
evaluated by the same engine as a ``KIN OPT`` deck (:mod:`mechfem.design.engine`).
"""

from __future__ import annotations

import copy
import dataclasses
import sys
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Literal, TypeAlias

import numpy as np

from mechfem.deck import deckio
from mechfem.design import dynamic_optimise, frame_angle, model_units
from mechfem.design import engine as design
from mechfem.design import rules as design_rules
from mechfem.design.engine import FloatArray, Iteration
from mechfem.design.frame_angle import FrameAngle
from mechfem.design.frame_length import FrameLength, design_bound
from mechfem.design.optimum import Optimum, Start
from mechfem.design.timing import POINT_MOTION_STEP, FreeTiming, Plan, TimedModel, plan, timed_inputs, within_bound
from mechfem.model.mechanism import Coordinate, FormParameter, InputKey, Point, Row
from mechfem.model.motion import Motion
from mechfem.model.storage import Storage
from mechfem.run import building

if TYPE_CHECKING:
    from mechfem.model.mechanism import Mechanism
    from mechfem.results.result import RunResult

Name: TypeAlias = "str | Coordinate | Row | FormParameter"


@dataclass(frozen=True)
class Q:
    """A quantity at every position: ``name``'s value (``order`` 0) or its transfer function of first or second
    order with respect to the input ``wrt`` (and ``wrt2``; default: the only input)."""

    name: Name
    order: int = 0
    wrt: InputKey = None
    wrt2: InputKey = None


@dataclass(frozen=True)
class Transmission:
    """The transmission angle between the elements ``first`` and ``second`` at every position (the deck's BUFTRA:
    the angle between their first sides, in [0, pi]), e.g. for a ``Bound``."""

    first: str
    second: str


Quantity: TypeAlias = "str | Coordinate | Row | FormParameter | Q | Transmission | dynamic_optimise.DynamicQuantity"


@dataclass
class Target:
    """Least squares: ``quantity`` should take ``values`` (one per position; NaN: not compared), times ``weight``."""

    quantity: Quantity
    values: Sequence[float] | FloatArray
    weight: float = 1.0


@dataclass
class TargetAt:
    """Least squares: ``quantity`` at ``position`` (0-based index of the run's positions) should equal ``value``."""

    quantity: Quantity
    position: int
    value: float
    weight: float = 1.0


@dataclass
class TargetExtremum:
    """Least squares: ``quantity`` at every extremum of ``reference`` (a co-ordinate or an output, found between
    the positions where its first-order transfer function changes sign and located to full precision) should equal
    ``value``; e.g. an output's second-order transfer function at its dead positions."""

    quantity: Quantity
    reference: Name
    value: float = 0.0
    weight: float = 1.0


@dataclass
class Bound:
    """Constraint: ``quantity`` stays within ``[lo, hi]`` at every position; a :class:`FrameLength` (a function of
    the design alone) within ``[lo, hi]``."""

    quantity: Quantity | FrameLength
    lo: float
    hi: float


class _Deck:
    """The mechanism written with one buffer per quantity, numbered in order of first use."""

    def __init__(self, mech: Mechanism) -> None:
        self.mech = mech
        self.storage = Storage()
        self.keys: dict[tuple[str, tuple[object, ...]], int] = {}

    def buffer(self, q: Quantity) -> int:
        if isinstance(q, dynamic_optimise.Drive | dynamic_optimise.Shaking | dynamic_optimise.ShakingForce):
            return dynamic_optimise.buffer(self._numbered, q)
        if isinstance(q, Transmission):
            return self._numbered(("BUFTRA", (q.first, q.second)), "BUFTRA", self.mech[q.first], self.mech[q.second])
        spec = q if isinstance(q, Q) else Q(q)
        obj = _lookup(self.mech, spec.name)
        coord = isinstance(obj, Coordinate)
        if spec.order not in (0, 1, 2):
            raise ValueError(f"{spec!r}: order must be 0, 1 or 2")
        keyword = ("BUFX0", "BUFKX1", "BUFKX2")[spec.order] if coord else ("BUFE0", "BUFKE1", "BUFKE2")[spec.order]
        dofs: tuple[int, ...] = ()
        if spec.order >= 1:
            from mechfem.model.motion import input_dof

            inputs = [r for r in self.mech.rows if r.kind == "input"]
            j = input_dof(spec.wrt, inputs)
            dofs = (j,) if spec.order == 1 else (j, input_dof(spec.wrt2 if spec.wrt2 is not None else j, inputs))
        return self._numbered((keyword, (obj, *dofs)), keyword, obj, *dofs)

    def _numbered(self, key: tuple[str, tuple[object, ...]], keyword: str | None, *args: Any) -> int:
        if key not in self.keys:
            number = len(self.keys) + 1
            if keyword is not None:  # None: a number a buffer line before fills (BUFSHAKE's y and moment)
                self.storage.buffer(number, keyword, *args)
            self.keys[key] = number
        return self.keys[key]


def _lookup(mech: Mechanism, name: Name) -> Coordinate | Row | FormParameter:
    obj = mech[name] if isinstance(name, str) else name
    if isinstance(obj, Point):
        raise TypeError(f"{obj.name!r} is a point: name one co-ordinate, {obj.name + '.x'!r} or {obj.name + '.y'!r}")
    if not isinstance(obj, Coordinate | Row | FormParameter):
        raise TypeError(f"{name!r} is not a co-ordinate, row or output of {mech.name!r}")
    return obj


def _variable(mech: Mechanism, numbering: deckio.Numbering, name: str) -> tuple[int, int, float]:
    """``(kind, deck number, start value)`` of a design variable."""
    obj = _lookup(mech, name)
    if isinstance(obj, FormParameter):
        rows = [r for r in numbering.prescribed if r.terms == ((1.0, obj),)]
        if not rows:
            raise ValueError(f"{name!r} is not prescribed: only a prescribed value or a fixed co-ordinate can vary")
        obj = rows[0]
    if isinstance(obj, Coordinate):
        if not obj.fixed:
            raise ValueError(
                f"{name!r} moves: its value is found, not chosen; vary the prescribed row that fixes it, or a fixed "
                "co-ordinate"
            )
        return 0, numbering.coord_number[obj], obj.value
    if obj.kind == "output":
        raise ValueError(f"{name!r} is an output: it has no prescribed value to vary")
    if obj.value is None:
        raise ValueError(f"{name!r} has no prescribed value (it takes its value at the given co-ordinates): give one")
    return 1, numbering.row_dest[obj], float(obj.value)


def _model(
    builder: Any, base: str, timed: Plan | None, full: bool, mechanism: Mechanism, storage: Storage
) -> design.DesignModelOf:
    """The problem's model: the mechanism's, or the free timing's points; checked for a full turn if ``full`` (in
    the model's units when ``builder`` makes its design models in them)."""
    of = design.built_model(builder, base) if timed is None else _timed_model(timed, base)
    if not full:
        return of
    from mechfem.design import full_rotation as _full

    return _full.checked(of, mechanism, storage, base, bool(builder.design_in_model_units))


def _timed_model(timed: Plan, base: str) -> design.DesignModelOf:
    """The points' models put together as one model of as many positions
    (:class:`~mechfem.design.timing.TimedModel`)."""

    def of(variables: list[tuple[int, int]], buffers: list[int], extrema: list[tuple[int, int]]) -> Any:
        shared = [v for v in variables if v[0] != 2]
        points = [b.design(base, [*shared, timed.input_var], buffers, extrema) for b in timed.builders]
        return TimedModel(points, len(shared), timed.thetas, timed.ordered, timed.angle, timed.turn)

    return of


def _extremum_terms(terms: Sequence[object]) -> bool:
    return any(isinstance(t, design.ExtremumTerm) for t in terms)


def _periodic(mech: Mechanism, name: str, span: tuple[float, float] | None) -> bool:
    """Whether the variable ``name`` with range ``span`` wraps: an angle without a range or with a range of one
    whole turn."""
    obj = _lookup(mech, name)
    angle = obj.kind == "angle" if isinstance(obj, Coordinate) else obj.is_angle
    if span is None:
        if not angle:
            raise ValueError(f"{name!r} is not an angle: give its range (lo, hi); only an angle may go without one")
        return True
    return angle and design_rules.full_turn(float(span[0]), float(span[1]), model_units.whole_turn(mech))


def _span(mech: Mechanism, name: str, span: tuple[float, float] | None) -> tuple[float, float]:
    """A variable's range; for an angle without one, the turn centred on its value."""
    if span is not None:
        return float(span[0]), float(span[1])
    value = float(getattr(mech[name], "value", None) or 0.0)
    return value - model_units.whole_turn(mech) / 2.0, value + model_units.whole_turn(mech) / 2.0


def _progress(progress: bool | Callable[[Iteration], object] | None) -> Callable[[Iteration], object] | None:
    if callable(progress):
        return progress
    if progress:

        def show(it: Iteration) -> None:
            print(
                f"  iteration {it.number}: objective {it.objective:.6e}, largest violation {it.violation:.2e}, "
                f"step {it.step:.2e}, {it.runs} runs",
                file=sys.stderr,
            )

        return show
    return None


def optimize(
    mechanism: Mechanism,
    vary: Mapping[str, tuple[float, float] | None],
    *,
    targets: Sequence[Target | TargetAt | TargetExtremum] = (),
    bounds: Sequence[Bound] = (),
    minimize: tuple[Literal["max", "maxabs", "rms", "end"], Quantity] | None = None,
    maximize: tuple[Literal["max", "maxabs", "rms", "end"], Quantity] | None = None,
    objective: Callable[[Evaluated], tuple[float, Any]] | None = None,
    quantities: Sequence[Quantity] = (),
    motion: Motion | None = None,
    steps: int = 200,
    tol: float | None = None,
    progress: bool | Callable[[Iteration], object] | None = None,
    starts: int | Sequence[Mapping[str, float]] = 1,
    rtol: float | None = None,
    atol: float | None = None,
    seed: int | None = None,
    executor: object | None = None,
    timing: FreeTiming | None = None,
    box: Mapping[str, tuple[float, float]] | None = None,
    full_rotation: bool = False,
    frame: FrameAngle | None = None,
) -> Optimum:
    """Changes the values ``vary`` names (prescribed values: lengths, u, v, fixed angles, gear ratios, an input's
    start; fixed co-ordinates: frame pivots ``"A0.x"``) within their ``(lo, hi)`` until the targets are met as
    well as they can be, with exact gradients from the design sensitivities.

    The objective is the weighted sum of squares of the ``targets``, plus the ``minimize`` / ``maximize`` term
    (``"max"``, ``"maxabs"``, ``"rms"`` or ``"end"`` of a quantity over the positions), plus ``objective(e)``: a
    Python function of an :class:`Evaluated` design ``e`` that returns the value and its gradient over the
    variables, reading ``e.value(q)`` and ``e.gradient(q)`` (positions x variables) of the quantities listed in
    ``quantities``. Targets alone are solved by SciPy's trust-region least
    squares (``least_squares``); with ``bounds`` or another term by SLSQP (``minimize``). ``steps`` limits the
    iterations (least squares: the evaluations). ``rtol`` and ``atol`` end it when an iteration changes the
    objective f by less than ``atol + rtol * |f|``, for either method and whatever the start objective (the one not
    given is 0). Without them, ``tol`` is the classic tolerance: the relative change of the sum of squares for least
    squares, and for SLSQP a change below ``tol`` times the start objective.
    ``motion`` (default the mechanism's) gives the positions; ``progress`` True prints every iteration on
    stderr, a callable gets every :class:`~mechfem.design.engine.Iteration`.

    Raises ValueError for a name that cannot vary and :class:`~mechfem.design.engine.Infeasible` when the start design
    cannot be assembled or moved through the motion. A design met on the way that cannot is reported to the
    optimiser as a very poor one, never raised.

    ``starts`` > 1 is a multi-start: the given design and ``starts - 1`` designs drawn within ``box`` (name ->
    (lo, hi); default the ranges of ``vary``) by a scrambled Halton sequence seeded with ``seed``, or ``starts``
    a list of start designs (name -> value; the names not given keep the mechanism's values). Every start is
    assembled afresh by continuation from the mechanism's position 1 (:mod:`mechfem.design.multistart`); one that cannot
    be is discarded with the reason. The others are optimised one after the other or as tasks of an
    ``executor`` (a Dask ``distributed.Client`` or a ``concurrent.futures.Executor``; there ``progress`` is not
    shown). The best optimum is returned; its ``starts`` holds every start's :class:`Start` (a failed one with
    its reason) and ``usable`` the fraction of starts optimised. :class:`~mechfem.design.engine.Infeasible` is raised
    only when every start failed.

    ``full_rotation`` True: a design is feasible only if its input (one angle) also turns fully, without a limit
    position, on the start design's branch (:mod:`mechfem.design.full_rotation`). ``timing`` (a
    :class:`~mechfem.design.timing.FreeTiming`) makes the input's value at each target point a design
    variable: the positions are then the target points (``Optimum.timing`` the values found).
    """
    if not isinstance(starts, int) or starts != 1 or executor is not None:
        kwargs = {
            "targets": targets,
            "bounds": bounds,
            "minimize": minimize,
            "maximize": maximize,
            "objective": objective,
            "quantities": quantities,
            "motion": motion,
            "steps": steps,
            "tol": tol,
            "progress": progress,
            "rtol": rtol,
            "atol": atol,
            "timing": timing,
            "full_rotation": full_rotation,
            "frame": frame,
        }
        if not isinstance(starts, int) and not starts:
            raise ValueError("starts is an empty list: give at least one start design, or a number of starts")
        if any(dynamic_optimise.variable_named(mechanism, name) for name in vary):
            raise ValueError("a multi-start varies dimensions: balance a mechanism's masses from one start (starts=1)")
        from mechfem.design import multistart

        return multistart.multi_start(mechanism, vary, kwargs, starts, seed, executor, box)
    motion = motion or mechanism.motion
    if timing is not None:
        motion = Motion.by(1, POINT_MOTION_STEP)
    if motion is None:
        raise ValueError("an optimisation needs a motion (its positions are where targets are compared)")
    if not vary:
        raise ValueError("nothing to vary: name at least one prescribed value or fixed co-ordinate")
    if minimize is not None and maximize is not None:
        raise ValueError("give minimize or maximize, not both")
    if not 1 <= steps <= 2**31 - 1:
        # SciPy's SLSQP counts iterations in 32 bits: a larger limit wraps round to a negative one.
        raise ValueError(f"steps must be from 1 to 2147483647, not {steps}")
    stop = None
    if rtol is not None or atol is not None:
        if tol is not None:
            raise ValueError("give tol, or rtol and atol, not both")
        stop = design_rules.FTol(float(rtol or 0.0), float(atol or 0.0))
    deck = _Deck(mechanism)
    terms: list[design.ValuesTerm | design.AtTerm | design.ExtremumTerm] = []
    for t in targets:
        b = deck.buffer(t.quantity)
        if isinstance(t, Target):
            terms.append(design.ValuesTerm(b, np.asarray(t.values, dtype=np.float64), t.weight))
        elif isinstance(t, TargetAt):
            terms.append(design.AtTerm(b, int(t.position), float(t.value), t.weight))
        else:
            terms.append(design.ExtremumTerm(b, deck.buffer(t.reference), float(t.value), t.weight))
    bound_terms = [
        (deck.buffer(bd.quantity), float(bd.lo), float(bd.hi))
        for bd in bounds
        if not isinstance(bd.quantity, FrameLength)
    ]
    goal: tuple[Literal[1, -1], design.Reduce, int] | None = None
    goal_q = minimize[1] if minimize is not None else maximize[1] if maximize is not None else None
    if minimize is not None:
        goal = (1, minimize[0], deck.buffer(minimize[1]))
    elif maximize is not None:
        goal = (-1, maximize[0], deck.buffer(maximize[1]))
    extra = [deck.buffer(q) for q in quantities]
    if not (terms or goal or objective):
        raise ValueError("nothing to optimise: give targets, minimize, maximize or objective")
    built = building.builder(mechanism, motion, deck.storage)
    variables = [
        dynamic_optimise.variable(mechanism, built.numbering, name) or _variable(mechanism, built.numbering, name)
        for name in vary
    ]
    positions = motion.steps + 1
    timed = None
    if timing is not None:
        if any(isinstance(t, design.ExtremumTerm) for t in terms):
            raise ValueError("a TargetExtremum needs a motion: with free timing the positions are the target points")
        timed = plan(mechanism, timing, deck.storage, built.numbering)
        positions = len(timed.thetas)
    free_input = None if timing is None else timing.input
    turn = None if frame is None else frame_angle.plan(mechanism, frame, built.numbering, free_input)
    # Variables, buffers and position 1 in the model's units (mm, degrees): the core's design models convert at
    # their edges.
    builder = built.builder
    for b in [builder, *([] if timed is None else timed.builders)]:
        b.design_in_model_units = True
    for term in terms:
        if isinstance(term, design.ValuesTerm) and len(term.values) != positions:
            raise ValueError(f"a Target has {len(term.values)} values for the motion's {positions} positions")
        if isinstance(term, design.AtTerm) and not 0 <= term.position < positions:
            raise ValueError(f"TargetAt position {term.position} is outside 0..{positions - 1}")
    dynamic = any(dynamic_optimise.is_mass(v[0]) for v in variables) or dynamic_optimise.recorded(deck.keys)
    if dynamic and (timing is not None or full_rotation or frame is not None or _extremum_terms(terms)):
        raise ValueError(
            "a dynamic optimisation (masses varied, or a drive or shaking judged) is judged at the instants of the "
            "motion: free timing, full_rotation, frame and TargetExtremum belong to kinematic synthesis"
        )
    periodic = [
        False if dynamic_optimise.is_mass(v[0]) else _periodic(mechanism, name, span)
        for (name, span), v in zip(vary.items(), variables, strict=True)
    ]
    half = model_units.whole_turn(mechanism) / 2.0
    ranges = [(s - half, s + half) if v is None else v for (_, _, s), v in zip(variables, vary.values(), strict=True)]
    lo = np.array([float(v[0]) for v in ranges])
    hi = np.array([float(v[1]) for v in ranges])
    for name, (_, _, start), a, b in zip(vary, variables, lo, hi, strict=True):
        if not a < b:
            raise ValueError(f"{name!r}: the range ({a}, {b}) is empty")
        if not a <= start <= b:
            raise ValueError(f"{name!r} starts at {start}, outside its range ({a}, {b})")
    framed = None
    if frame is not None:
        span = frame.span or (-half, half)
        framed = (frame.name, float(span[0]), float(span[1]), frame.span is None)
    with deckio.tables_dir(built.tables) as base:
        model = (
            dynamic_optimise.model(builder, base)
            if dynamic
            else _model(builder, base, timed, full_rotation, mechanism, deck.storage)
        )
        problem = synthesis_problem(
            model,
            [(k, n) for k, n, _ in variables],
            list(vary),
            lo,
            hi,
            periodic,
            frame=framed,
            turn=turn,
            timed=timed,
            whole_turn=model_units.whole_turn(mechanism),
            terms=terms,
            bounds=bound_terms,
            design_bounds=[
                design_bound(mechanism, bd.quantity, bd.lo, bd.hi, list(vary))
                for bd in bounds
                if isinstance(bd.quantity, FrameLength)
            ],
            objective=goal,
            objective_with=goal[2] + 1 if isinstance(goal_q, dynamic_optimise.ShakingForce) and goal else None,
            custom=None if objective is None else _named(objective, deck),
            extra_buffers=extra,
            steps=steps,
            tol=tol,
            stop=stop,
        )
        sol = design.solve(problem, _progress(progress))
    optimised = copy.deepcopy(mechanism)
    x0, x = sol.x_start, sol.x
    thetas = None
    turned_by = None
    if frame is not None:
        n = len(vary)
        turned_by = (float(x0[n]), float(x[n]))
        x, x0 = np.delete(x, n), np.delete(x0, n)
    if timed is not None and timing is not None:
        n = len(vary)
        thetas = [float(t) for t in timed_inputs(timed, x[n:])]
        optimised.set(timing.input, thetas[0])
        x, x0 = x[:n], x0[:n]
        motion = None
    for name, value in zip(vary, x, strict=True):
        if not dynamic_optimise.apply(optimised, name, float(value)):
            optimised.set(name, float(value))
    if turn is not None and turned_by is not None and frame is not None:
        frame_angle.apply(optimised, turn, turned_by[1])
    _carry_position_one(optimised, built.numbering, sol.position_one)
    start_values = dict(zip(vary, map(float, x0), strict=True))
    final_values = dict(zip(vary, map(float, x), strict=True))
    if turned_by is not None and frame is not None:
        start_values[frame.name], final_values[frame.name] = turned_by
    began = None if timing is None else [float(t) for t in timing.starts]
    begun = Start(
        start_values, final_values, sol.objective, sol.runs, sol.success, sol.message, sol.seconds, began, thetas
    )
    return dataclasses.replace(
        sol, mechanism=optimised, start=start_values, values=final_values, motion=motion, timing=thetas, starts=[begun]
    )


def synthesis_problem(
    model: design.DesignModelOf,
    variables: Sequence[tuple[int, int]],
    names: Sequence[str],
    lo: FloatArray,
    hi: FloatArray,
    periodic: Sequence[bool],
    *,
    frame: tuple[str, float, float, bool] | None,
    turn: frame_angle.Turn | None,
    timed: Plan | None,
    **fields: Any,
) -> design.Problem:
    """The design problem of ``variables`` (core numbering, ranges ``lo``..``hi``) on ``model``, with the frame
    angle ``frame`` = (name, lo, hi, wraps) turning the model by ``turn``, and with the free timing ``timed``'s
    input at every point appended as variables; ``fields`` are the rest of :class:`design.Problem` (terms, bounds,
    objective, tolerances). Both ``optimize`` and a deck's FREETIME/FULLROT/VARYFRAME set their problem up here."""
    variables, names = list(variables), list(names)
    wraps = list(periodic) or [False] * len(variables)
    if frame is not None:
        name, a, b, periodic_frame = frame
        variables, names = [*variables, frame_angle.SENTINEL], [*names, name]
        lo, hi = np.append(lo, a), np.append(hi, b)
        wraps.append(periodic_frame)
    if timed is not None:
        sweep = within_bound(timed, len(variables))
        if sweep is not None:
            fields["design_bounds"] = [*fields.get("design_bounds", []), sweep]
        variables += [(2, k) for k in range(len(timed.thetas))]
        names += timed.names
        lo, hi = np.concatenate([lo, timed.lo]), np.concatenate([hi, timed.hi])
        wraps += timed.periodic
    return design.Problem(
        model=model if turn is None else frame_angle.turned(model, turn),
        variables=variables,
        names=names,
        lo=lo,
        hi=hi,
        periodic=wraps if any(wraps) else [],
        **fields,
    )


# --- multi-start ---------------------------------------------------------------------------------------------------


def _carry_position_one(mech: Mechanism, numbering: deckio.Numbering, x: Sequence[float]) -> None:
    """Starts the moving co-ordinates at the optimised design's position 1, so that it assembles in the branch the
    optimisation followed."""
    for c, value in zip(numbering.coords, x, strict=False):
        if not c.fixed and np.isfinite(value):
            mech[c.name].value = float(value)


def sensitivity(analysis: RunResult, quantity: Quantity, wrt: Sequence[str]) -> FloatArray:
    """The derivative of ``quantity`` at every position with respect to each design variable in ``wrt``
    (positions x variables); see :meth:`RunResult.sensitivity`."""
    mech, motion = analysis.mechanism, analysis.motion
    if motion is None:
        raise ValueError("sensitivities need a motion: the analysis computed position 1 only")
    deck = _Deck(mech)
    b = deck.buffer(quantity)
    built = building.builder(mech, motion, deck.storage)
    variables = [_variable(mech, built.numbering, name) for name in wrt]
    core = built.builder
    core.design_in_model_units = True
    with deckio.tables_dir(built.tables) as base:
        model = core.design(base, [(k, n) for k, n, _ in variables], [b], [])
        d = model.evaluate([v for _, _, v in variables])
    if not d.feasible:
        raise design.Infeasible(str(d.reason))
    return np.asarray(d.gradient[:, 0, :], dtype=np.float64)


class Evaluated:
    """One design as a Python objective sees it: a quantity's values at every position and their gradient."""

    def __init__(self, e: design.Evaluation, deck: _Deck) -> None:
        self._e, self._deck = e, deck
        self.x = e.x
        """The design variables' values, in the order of ``vary``."""

    def _buffer(self, q: Quantity) -> int:
        known = dict(self._deck.keys)
        b = self._deck.buffer(q)
        if len(self._deck.keys) != len(known):
            raise KeyError(f"{q!r} is not among the quantities given to optimize (quantities=[...])")
        return b

    def value(self, q: Quantity) -> FloatArray:
        """``q`` at every position."""
        return self._e.value(self._buffer(q))

    def gradient(self, q: Quantity) -> FloatArray:
        """The derivatives of ``q`` with respect to the design variables: positions x variables."""
        return self._e.gradient(self._buffer(q))


def _named(
    fn: Callable[[Evaluated], tuple[float, Any]], deck: _Deck
) -> Callable[[design.Evaluation], tuple[float, FloatArray]]:
    def call(e: design.Evaluation) -> tuple[float, FloatArray]:
        f, g = fn(Evaluated(e, deck))
        return float(f), np.asarray(g, dtype=np.float64)

    return call


__all__ = [
    "Bound",
    "Evaluated",
    "FrameLength",
    "Optimum",
    "Q",
    "Start",
    "Target",
    "TargetAt",
    "TargetExtremum",
    "optimize",
    "sensitivity",
]
