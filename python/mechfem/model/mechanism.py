"""Mechanisms built in Python: named points, elements and form parameters instead of co-ordinate numbers.

A :class:`Mechanism` is written as a deck and run through the same reader and solver as
``mechfem run``, so a model built here and the same model written as a deck give the same
numbers. Every element type of the catalogue has a method; each of its form parameters is

* left free (``None``, the default),
* prescribed to a value (a number) or kept at its value at the given co-ordinates (:class:`Keep`),
* an input that the motion drives (:class:`Driven`),
* or an output only (:class:`Output`).

Combinations of form parameters (a fixed angle between two bars, a gear relation, any
factor-weighted sum) are written with ``+``, ``-`` and ``*`` and passed to
:meth:`Mechanism.prescribe`, :meth:`Mechanism.drive` or :meth:`Mechanism.output`::

    m = Mechanism("fourbar")
    A0, B0 = m.fixed("A0", 0, 0), m.fixed("B0", 4, 0)
    A, B = m.point("A", 1, 0), m.point("B", 3.5, 2.5)
    crank = m.bar("crank", A0, A, length=1.0, angle=Driven())
    coupler = m.bar("coupler", A, B, length=3.5)
    rocker = m.bar("rocker", B0, B, length=3.0, angle=Output("psi"))
    result = m.run(Motion.by(72, 2 * math.pi))
    result.output("psi", order=1)          # d psi / d crank angle at every position
"""

from __future__ import annotations

import copy
import os
from collections.abc import Callable, Iterator, Mapping
from pathlib import Path
from typing import TYPE_CHECKING, Any, Literal

import numpy.typing as npt

from mechfem._util.checks import check_name, finite
from mechfem._util.names import article, plural, suggestion, unknown_name
from mechfem.model.builders import ElementMethods
from mechfem.model.catalogue import FORMS, MAX_ITER, SLOTS
from mechfem.model.echo import BUFFER_ARGS
from mechfem.model.motion import By, Dynamic, Free, InputKey, InputMotion, Motion, Table, To, input_dof, simulation
from mechfem.model.parts import (
    ATTRIBUTES,
    Combination,
    Coordinate,
    Driven,
    Element,
    Expression,
    FormParameter,
    Keep,
    Output,
    Point,
    Role,
    Row,
    Slot,
    kind_of,
)
from mechfem.model.storage import Picture, Ref, Storage
from mechfem.model.units import Unit, Units, angle_in, check_unit

if TYPE_CHECKING:
    from mechfem.model.loads import (
        Body,
        Force,
        Gravity,
        Inertia,
        Load,
        Loads,
        LoadTable,
        Motor,
        PointMass,
        PointRef,
        RowRef,
        Spring,
    )
    from mechfem.results.result import RunResult


class Mechanism(ElementMethods):
    """A planar mechanism: named points and co-ordinates, elements on them, prescribed form parameters,
    inputs and outputs.

    ``motion`` and ``storage`` are the defaults :meth:`run` and :meth:`to_deck` use (set by
    :meth:`from_deck` to the deck's own). ``loads`` holds the masses and loads (None without any: a
    kinematic model, mode ``KIN ANA``; with them its deck is a ``DYN ANA`` one, or ``DYN SIM`` for
    :meth:`simulate`).

    ``units`` are the units of every number given to it and of every number its runs give back (a
    :class:`~mechfem.model.units.Units`, or a mapping by kind); ``length``, ``angle``, ``mass``, ``force`` and ``time``
    set one kind each: ``Mechanism("fourbar", angle="deg")`` reads and gives every angle in degrees,
    ``length="mm"`` every length in millimetres. Its deck says them on its ``UNITS`` line.
    """

    def __init__(
        self,
        name: str = "mechanism",
        *,
        units: Units | Mapping[str, str | None] | None = None,
        length: str | None = None,
        angle: str | None = None,
        mass: str | None = None,
        force: str | None = None,
        time: str | None = None,
    ) -> None:
        self.name = check_name(name)
        given = {k: v for k, v in Units.of(units).as_dict().items() if v is not None}
        one = {"length": length, "angle": angle, "mass": mass, "force": force, "time": time}
        self.units: Units = Units(**{**given, **{k: v for k, v in one.items() if v is not None}})
        """The units of the model's numbers (:class:`~mechfem.model.units.Units`)."""
        self.coordinates: list[Coordinate] = []
        self.points: list[Point] = []
        self.elements: list[Element] = []
        self.rows: list[Row] = []
        self.motion: Motion | None = None
        self.storage: Storage | None = None
        self.loads: Loads | None = None
        self._names: dict[str, object] = {}
        # Parts that share a name with a part of another kind (names are unique within a kind, names-units.md):
        # ``_names`` holds the first, ``_shared`` the others, which ``find`` reaches by the kind it accepts.
        self._shared: dict[str, list[object]] = {}

    # -- names

    def _named(self, name: str) -> list[object]:
        """Every part called ``name``: one, or one of each kind that shares it."""
        first = self._names.get(name)
        return [] if first is None else [first, *self._shared.get(name, [])]

    def _check_free(self, name: str, kind: type | None = None) -> None:
        """Refuse ``name`` when a part of the same ``kind`` (any part when None) already has it."""
        check_name(name)
        taken = [o for o in self._named(name) if kind is None or isinstance(o, kind)]
        if taken:
            raise ValueError(f"the name {name!r} is already used by {taken[0]!r}")

    def _claim(self, name: str, obj: object) -> None:
        kind = next((k for k in (Point, Coordinate, Element, Row) if isinstance(obj, k)), type(obj))
        self._check_free(name, kind)
        if name in self._names:
            self._shared.setdefault(name, []).append(obj)
        else:
            self._names[name] = obj

    def _has(self, obj: object) -> bool:
        """Whether ``obj`` is this mechanism's part of its name."""
        return any(o is obj for o in self._named(getattr(obj, "name", "")))

    def __getitem__(self, name: str) -> Any:
        """The point, co-ordinate, element or row called ``name`` (typed ``Any`` for convenience: check with
        ``isinstance`` where it matters); a KeyError suggesting the closest names for a name it does not have."""
        return self.find(name)

    def find(
        self, name: object, what: str = "", accept: Callable[[object], bool] | None = None, kinds: str | None = None
    ) -> Any:
        """The part called ``name`` that ``accept`` accepts (default: any); for a name the model does not have, an
        :class:`~mechfem._util.names.UnknownNameError` (a KeyError) naming the closest ``what`` it has (``kinds``: the
        plural in the list of those names), and a TypeError for a part that ``accept`` refuses."""
        named = self._named(name) if isinstance(name, str) else []
        obj = named[0] if named else None
        for part in named:
            if accept is None or accept(part):
                return part
        if obj is not None:
            raise TypeError(f"{name!r} is {article(kind_of(obj))} of the mechanism {self.name!r}, not {article(what)}")
        # The names of the closest one's kind only, or every name with the points first: a model has many names.
        known = sorted((n for n, o in self._names.items() if accept is None or accept(o)), key=self._order)
        close = suggestion(name, known)
        same = [] if close is None else [n for n in known if self._order(n) == self._order(close)]
        if close is not None and len(same) < len(known):
            kinds, known = plural(kind_of(self._names[close])), same
        where = f" in the mechanism {self.name!r}"
        raise unknown_name(what or "part", name, known, where, kinds or (plural(what) if what else "names"))

    def _order(self, name: str) -> int:
        return _KINDS.index(kind_of(self._names[name]))

    def __contains__(self, name: object) -> bool:
        return name in self._names

    def names(self) -> Iterator[str]:
        """Every name, in the order they were given."""
        return iter(self._names)

    @property
    def inputs(self) -> list[Row]:
        """The input rows, in DOF order."""
        return [r for r in self.rows if r.kind == "input"]

    @property
    def outputs(self) -> list[Row]:
        """The output rows, in order."""
        return [r for r in self.rows if r.kind == "output"]

    @property
    def prescribed(self) -> list[Row]:
        """The prescribed rows that are not inputs."""
        return [r for r in self.rows if r.kind == "prescribed"]

    def _own(self, obj: Slot) -> Slot:
        if isinstance(obj, Point | Coordinate) and self._has(obj):
            return obj
        if isinstance(obj, Point | Coordinate):
            raise ValueError(f"{obj!r} belongs to another mechanism")
        raise TypeError(f"expected a point or a co-ordinate of this mechanism, got {obj!r}")

    # -- co-ordinates and points

    def _coordinate(
        self, name: str, value: float, fixed: bool, kind: Literal["x", "y", "angle", "scalar"]
    ) -> Coordinate:
        c = Coordinate(name, finite(value, f"the value of {name!r}"), bool(fixed), kind)
        self._claim(name, c)
        self.coordinates.append(c)
        return c

    def fixed(self, name: str, x: float, y: float) -> Point:
        """A point of the frame (both co-ordinates fixed)."""
        return self.point(name, x, y, fixed="xy")

    def point(self, name: str, x: float, y: float, *, fixed: Literal["", "x", "y", "xy"] = "") -> Point:
        """A moving point at ``(x, y)`` (an estimate of position 1); ``fixed`` names co-ordinates that do not move
        (``"y"``: a slider on a horizontal guide)."""
        if fixed not in ("", "x", "y", "xy"):
            raise ValueError(f"fixed must be '', 'x', 'y' or 'xy', not {fixed!r}")
        self._check_free(name, Point)
        cx = self._coordinate(f"{name}.x", x, "x" in fixed, "x")
        cy = self._coordinate(f"{name}.y", y, "y" in fixed, "y")
        p = Point(name, cx, cy)
        cx.point = cy.point = p
        self._claim(name, p)
        self.points.append(p)
        return p

    def angle(self, name: str, value: float = 0.0, *, fixed: bool = False) -> Coordinate:
        """An angle co-ordinate (of a half beam, ternary-1, gear or belt wheel); moving unless ``fixed``."""
        return self._coordinate(name, value, fixed, "angle")

    def scalar(self, name: str, value: float, *, fixed: bool = True) -> Coordinate:
        """A scalar co-ordinate (a transmission ratio, a radius); fixed unless ``fixed=False``."""
        return self._coordinate(name, value, fixed, "scalar")

    # -- rows

    def _terms(self, expr: Expression) -> tuple[tuple[float, FormParameter], ...]:
        if not isinstance(expr, FormParameter | Combination):
            raise TypeError(f"expected a form parameter or a combination of them, got {expr!r}")
        terms = expr.terms()
        for _, p in terms:
            if not self._has(p.element):
                raise ValueError(f"{p!r} belongs to another mechanism")
        return terms

    def _row(
        self, name: str, kind: Literal["prescribed", "input", "output"], expr: Expression, value: float | None
    ) -> Row:
        v = None if value is None else finite(value, f"the value of {name!r}")
        r = Row(name, kind, self._terms(expr), v)
        self._claim(name, r)
        self.rows.append(r)
        return r

    def prescribe(self, name: str, expr: Expression, value: float | None = None) -> Row:
        """Prescribes a form parameter or a combination (a row of D^c) to ``value``; None keeps its value at the
        given co-ordinates."""
        return self._row(name, "prescribed", expr, value)

    def fixed_angle(self, name: str, a: Element, b: Element, value: float | None = None) -> Row:
        """Prescribes the angle ``a.angle - b.angle`` between two elements (e.g. two bars of one rigid link)."""
        return self.prescribe(name, a.angle - b.angle, value)

    def drive(self, name: str, expr: Expression, start: float | None = None, unit: Unit | None = None) -> Row:
        """Makes a form parameter or a combination an input; ``start`` is its value at position 1 (in the model's
        units; an angle's in ``unit``, ``"rad"`` or ``"deg"``, when given)."""
        if start is not None and check_unit(unit) not in (None, self.units.angle):
            if not all(p.is_angle for _, p in self._terms(expr)):
                raise ValueError(f"the input {name!r} is not an angle: give its start without unit={unit!r}")
            start = angle_in(finite(start, f"the start of {name!r}"), unit, self.units.angle)
        return self._row(name, "input", expr, start)

    def output(self, name: str, expr: Expression) -> Row:
        """Computes a form parameter or a combination at every position, as the output ``name``."""
        return self._row(name, "output", expr, None)

    # -- masses and loads (mechfem.model.loads): inverse dynamics (DYN ANA) in a run, a simulation (DYN SIM) in simulate

    def mass(self, element: Element | str, m: float, u: float = 0.0, v: float = 0.0, J: float = 0.0) -> Body:
        """Makes ``element`` (BIN, HLF, TR1, TR2) a rigid body of mass ``m``, centre of mass at ``(u, v)`` in its frame
        (origin at its first point; u along P->Q of BIN and TR2, along the angle co-ordinate of HLF and TR1) and
        moment of inertia ``J`` about that centre."""
        from mechfem.model import loads

        return loads.add_mass(self, element, m, u, v, J)

    def point_mass(self, point: PointRef, m: float) -> PointMass:
        """A point mass ``m`` at ``point`` (or at two co-ordinates ``(x, y)``)."""
        from mechfem.model import loads

        return loads.add_point_mass(self, point, m)

    def inertia(self, angle: Coordinate | str, J: float) -> Inertia:
        """A rotational inertia ``J`` on an angle co-ordinate (a wheel of a gear pair or belt without an element)."""
        from mechfem.model import loads

        return loads.add_inertia(self, angle, J)

    def gravity(self, gx: float, gy: float) -> Gravity:
        """The acceleration of gravity, e.g. ``m.gravity(0, -9.81)`` (given again, it replaces the one before)."""
        from mechfem.model import loads

        return loads.add_gravity(self, gx, gy)

    def force(self, point: PointRef, fx: float, fy: float) -> Force:
        """A constant force ``(fx, fy)`` at ``point`` (or at two co-ordinates ``(x, y)``)."""
        from mechfem.model import loads

        return loads.add_force(self, point, fx, fy)

    def load(self, row: RowRef, value: float) -> Load:
        """A constant generalised force on a prescribed row, input or output (by name, row or form parameter): a
        torque on an angle, a force along a length; it does the work ``value * d row``."""
        from mechfem.model import loads

        return loads.add_load(self, row, value)

    def load_table(self, row: RowRef, t: npt.ArrayLike, values: npt.ArrayLike, *, file: str | None = None) -> LoadTable:
        """A generalised force on ``row`` given at the times ``t``, linear between them, constant outside (a LOADFUNC
        file written beside the deck, named ``file`` or ``<mechanism>_load<k>.dat``)."""
        from mechfem.model import loads

        return loads.add_load_table(self, row, t, values, file)

    def spring(self, row: RowRef, k: float, free_value: float, damping: float = 0.0) -> Spring:
        """A spring of stiffness ``k`` and free value ``free_value`` on ``row`` with a viscous damper ``damping``:
        the generalised force ``-k (row - free_value) - damping * d(row)/dt``."""
        from mechfem.model import loads

        return loads.add_spring(self, row, k, free_value, damping)

    def motor(self, row: RowRef, stall_torque: float, no_load_speed: float) -> Motor:
        """A motor on ``row`` whose torque falls linearly with its speed:
        ``stall_torque (1 - d(row)/dt / no_load_speed)``."""
        from mechfem.model import loads

        return loads.add_motor(self, row, stall_torque, no_load_speed)

    # -- values

    def set(self, name: str, value: float | tuple[float, float]) -> None:
        """Changes a value in place, in the model's units (:attr:`units`): a row's prescribed value (an input's
        start), a co-ordinate's initial value, or a point's ``(x, y)``."""
        for target, v in self._targets({name: value}).items():
            if isinstance(target, Row):
                target.value = v
            else:
                target.value = v

    def _targets(self, changes: Mapping[str, float | tuple[float, float]]) -> dict[Row | Coordinate, float]:
        out: dict[Row | Coordinate, float] = {}
        for name, value in changes.items():
            obj = self._names.get(name)
            if isinstance(obj, Row) and obj.kind == "output":
                raise ValueError(f"{name!r} is an output: it has no prescribed value")
            obj = self.find(name, "point, co-ordinate, prescribed value or input", _has_value, "names with a value")
            if isinstance(obj, Point):
                if not isinstance(value, tuple | list) or len(value) != 2:
                    raise TypeError(f"point {name!r} takes (x, y), got {value!r}")
                out[obj.x] = finite(value[0], f"{name}.x")
                out[obj.y] = finite(value[1], f"{name}.y")
            elif isinstance(obj, Coordinate):
                out[obj] = finite(value, name)  # type: ignore[arg-type]
            else:
                out[obj] = finite(value, name)  # type: ignore[arg-type]
        return out

    def variant(self, changes: Mapping[str, float | tuple[float, float]] | None = None, /, **more: float) -> Mechanism:
        """A copy with some values changed (see :meth:`set`), e.g. ``m.variant(kappa=-5.2)``
        or ``m.variant({"B0.x": 0.6})``."""
        m = copy.deepcopy(self)
        for name, v in {**(changes or {}), **more}.items():
            m.set(name, v)
        return m

    # -- decks

    def to_deck(self, motion: Motion | None = None, storage: Storage | None = None) -> str:
        """The mechanism as deck text (with ``motion`` and ``storage``; defaults: :attr:`motion`, :attr:`storage`).

        A :class:`Table` motion refers to a MOV_FUNC file: :meth:`save_deck` writes it beside the deck.
        """
        from mechfem.deck import deckio

        return deckio.write_text(self, motion or self.motion, storage or self.storage)

    def save_deck(
        self, path: str | os.PathLike[str], motion: Motion | None = None, storage: Storage | None = None
    ) -> Path:
        """Writes the deck (and the files of its table motions, beside it); returns the deck's path."""
        from mechfem.deck import deckio

        return deckio.save(self, Path(path), motion or self.motion, storage or self.storage)

    @classmethod
    def from_deck(cls, path: str | os.PathLike[str]) -> Mechanism:
        """Reads a deck: points are named ``P<i>`` after their x co-ordinate's number, other co-ordinates
        ``x<i>``, elements ``E<k>``, combined rows ``row<r>`` and outputs ``out<k>``; an element's own row
        is named by its label (``E1.angle``). The deck's motion and storage become :attr:`motion` and
        :attr:`storage`."""
        from mechfem.deck import deckio

        return deckio.read(Path(path))

    @classmethod
    def from_deck_text(cls, text: str, name: str = "deck", base_dir: str | os.PathLike[str] = ".") -> Mechanism:
        """As :meth:`from_deck`, for deck text; MOV_FUNC files are read from ``base_dir``."""
        from mechfem.deck import deckio

        return deckio.read_text(text, name, Path(base_dir))

    # -- analysis

    def run(
        self,
        motion: Motion | None = None,
        storage: Storage | None = None,
        progress: bool | Callable[[int, int], object] | None = None,
        order: int | None = 2,
        *,
        raise_on_stop: bool = False,
    ) -> RunResult:
        """Runs the motion (default :attr:`motion`; without one, position 1 only) and returns every result.

        ``progress`` True shows a progress bar, a callable is called as ``progress(done, total)``.
        ``order`` is the transfer functions computed at every position: 2 (default) first and second
        order; 1 first order only (faster; second-order results and accelerations are NaN); None what the
        storage's buffers need, as ``mechfem run`` computes them. The solver predicts positions differently
        without the second order, so only runs with the same orders agree to the last bit (otherwise
        within the Newton tolerance, ACCURACY).
        Raises :class:`~mechfem.DeckError` for a model the deck reader refuses and
        :class:`~mechfem.AssemblyError`, :class:`~mechfem.ConvergenceError` or
        :class:`~mechfem.LimitPositionError` when position 1 cannot be computed, in this model's words, and
        :class:`~mechfem.ResourceError` before the run when its results would exceed the memory limit
        (:mod:`mechfem._util.limits`). Ctrl-C raises :class:`~mechfem.RunInterrupted` with the :class:`RunResult` of
        the positions computed so far. A motion that stops early returns the positions up to there
        (:meth:`RunResult.stop_reason` says why) and warns with :class:`~mechfem.IncompleteRunWarning`; with
        ``raise_on_stop`` it raises :class:`~mechfem.RunStoppedError` carrying that :class:`RunResult` instead.
        """
        from mechfem.run import running

        return running.run(
            self,
            motion or self.motion,
            storage or self.storage,
            progress=progress,
            order=order,
            raise_on_stop=raise_on_stop,
        )

    def simulate(
        self,
        t_end: float,
        steps: int,
        v0: float | Mapping[InputKey, float] | None = None,
        *,
        drive: Mapping[InputKey, By | To | Table] | None = None,
        rtol: float | None = None,
        atol: float | None = None,
        accuracy: float | None = None,
        max_iter: int | None = None,
        storage: Storage | None = None,
        progress: bool | Callable[[int, int], object] | None = None,
        order: int | None = 2,
        raise_on_stop: bool = False,
        unit: Unit | None = None,
        integrator: str = "auto",
        stop_when: tuple[int | str, float] | None = None,
    ) -> RunResult:
        """Simulates the motion under the masses and loads from time 0 to ``t_end`` (mode ``DYN SIM``), with results
        at ``steps + 1`` positions ``t_end / steps`` apart: the inputs of ``drive`` (input -> :class:`By`,
        :class:`To` or :class:`Table`) follow that motion, every other input moves under the forces from the speed
        ``v0`` (a number for the only one, a mapping by input for several; None: from rest; an angle's speed in
        ``unit`` per time, ``"rad"`` or ``"deg"``). ``rtol`` and ``atol``
        are the integrator's tolerances (default ``accuracy``, 1e-10); the rest is as for :meth:`run`, whose
        :class:`RunResult` it returns, with :attr:`RunResult.simulation` the integrator's work. A simulation that
        stops early (a limit position, a step size that collapsed) returns the positions it reached and says why,
        as a run does. ``integrator`` is the method (one of :data:`~mechfem.model.motion.INTEGRATORS`: ``"auto"``,
        ``"explicit"`` = ``"dopri5"``, ``"dop853"``, ``"implicit"`` = ``"radau5"``); ``stop_when`` = ``(buffer,
        value)`` ends the simulation where that buffer of the storage (by number, or by the name of the one
        quantity it holds) crosses ``value``, in the mechanism's own units (:attr:`RunResult.simulation` says
        ``event``). The same as ``run(Motion.dynamic(...))`` with every input named."""
        motion = simulation(
            self,
            t_end,
            steps,
            v0,
            drive,
            rtol=rtol,
            atol=atol,
            accuracy=accuracy,
            max_iter=max_iter,
            unit=unit,
            integrator=integrator,
            stop_when=stop_when,
        )
        return self.run(motion, storage, progress, order, raise_on_stop=raise_on_stop)

    def check(self, motion: Motion | None = None) -> RunResult:
        """Computes position 1 only (with the first values of a table motion, as a run would)."""
        from mechfem.run import running

        return running.run(self, motion or self.motion, self.storage, with_motion=False)

    def __repr__(self) -> str:
        return (
            f"Mechanism({self.name!r}: {len(self.points)} points, {len(self.elements)} elements, "
            f"{len(self.rows)} rows, {len(self.inputs)} input(s))"
        )

    def figure(self, names: bool = True) -> Any:
        """A figure (``matplotlib.figure.Figure``) of the mechanism at position 1, its points named."""
        from mechfem.viz import figures

        return figures.mechanism_figure(self, names)

    def _repr_png_(self) -> bytes | None:
        """The mechanism at position 1 as a PNG image (for Jupyter), or None when it cannot be drawn."""
        from mechfem.viz import figures

        return figures.mechanism_png(self)


_KINDS = ("point", "element", "input", "output", "prescribed value", "co-ordinate")
"""The kinds of names in the order a list of names shows them."""


def _has_value(obj: object) -> bool:
    """Whether ``obj`` has a value :meth:`Mechanism.set` can change: a point, a co-ordinate, a prescribed row or an
    input (an output has none)."""
    return isinstance(obj, Point | Coordinate) or (isinstance(obj, Row) and obj.kind != "output")


# The input motion and the storage live in their own modules; they are named here too.
__all__ = [
    "ATTRIBUTES",
    "BUFFER_ARGS",
    "FORMS",
    "MAX_ITER",
    "SLOTS",
    "By",
    "Combination",
    "Coordinate",
    "Driven",
    "Dynamic",
    "Element",
    "Expression",
    "FormParameter",
    "Free",
    "InputKey",
    "InputMotion",
    "Keep",
    "Mechanism",
    "Motion",
    "Output",
    "Picture",
    "Point",
    "Ref",
    "Role",
    "Row",
    "Slot",
    "Storage",
    "Table",
    "To",
    "input_dof",
]
