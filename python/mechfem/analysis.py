"""The result of running a :class:`~mechfem.Mechanism`: every quantity of the deck's buffer table, by name.

Arrays have one entry per position (row k is position k + 1). Transfer functions are derivatives with
respect to the inputs (``order=1``: d/d q_j, ``order=2``: d2/d q_j d q_m); with one input ``wrt`` may be
left out. Points give two columns (x, y); co-ordinates, rows and outputs one. A mechanism with masses or
loads (:mod:`mechfem.loads`) also gives its inverse dynamics: drive forces and torques, stresses of the
prescribed rows, reactions of the frame, energies, power and the mass matrix. A simulation
(:meth:`~mechfem.Mechanism.simulate`) gives the same, along the motion the forces made, and
:attr:`Analysis.simulation` says what its integrator did.
"""

from __future__ import annotations

import dataclasses
import functools
import importlib
import math
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any, NamedTuple

import numpy as np
import numpy.typing as npt

import mechfem._core as _core
from mechfem.hooks import Hook
from mechfem.inverse_dynamics import Simulation
from mechfem.result import Limit, ModelNames, RunReport, RunResult
from mechfem.units import Unit, check_unit, factor

if TYPE_CHECKING:
    from mechfem.model import Coordinate, FormParameter, InputKey, Mechanism, Motion, Point, Row
    from mechfem.numbering import Numbering

FloatArray = npt.NDArray[np.float64]


class Energy(NamedTuple):
    """Energies at every position: ``kinetic`` T, ``potential`` V (gravity and springs) and ``total`` T + V."""

    kinetic: FloatArray
    potential: FloatArray
    total: FloatArray


class Analysis:
    """Everything a run of a mechanism computed, addressed by the mechanism's names.

    ``coords`` holds every co-ordinate (positions x co-ordinates, in deck numbering), ``time`` and
    ``det`` (det(D^c), the transfer quality) one value per position; ``buffers`` the deck's own
    buffers by number (from the storage of the run). ``parameters`` holds the values a design study
    gave this variant.
    """

    def __init__(
        self,
        mechanism: Mechanism,
        numbering: Numbering,
        d: _core.TextRunDict,
        parameters: dict[str, Any] | None = None,
        path: str = "",
    ) -> None:
        self.mechanism = mechanism
        self.numbering = numbering
        self.path = path or f"{mechanism.name}.mec"
        """The name of the deck written for the run."""
        self.parameters: dict[str, Any] = parameters or {}
        self.motion: Motion | None = None
        """The motion the run followed (None: position 1 only, or not known)."""
        self.coords: FloatArray = np.asarray(d["coords"], dtype=np.float64)
        self._raw = d
        # The full table, one column per quantity in the core's layout, sliced by block name (``_block``) when a
        # quantity is first asked for: a design study reads most variants through one or two of them.
        self._table: FloatArray = np.asarray(d["table"], dtype=np.float64)
        self.dynamic = bool(d["dynamic"])
        """True when the mechanism has masses or loads: the run computed its inverse dynamics."""
        sim = d.get("simulation")
        self.simulation: Simulation | None = None if sim is None else Simulation.from_core(sim)  # type: ignore[arg-type]
        """What the integrator of a simulation did (method, tolerances, steps, rejected steps, evaluations of the
        equations of motion, the time reached); None for a run of a prescribed motion."""

    def _block(self, name: str) -> FloatArray:
        """The layout's block ``name`` at every position: positions x its shape (a view of the table)."""
        start, shape = self._raw["layout"][name]
        width = math.prod(shape)
        return self._table[:, start : start + width].reshape(self._table.shape[0], *shape)

    @functools.cached_property
    def buffers(self) -> dict[int, FloatArray]:
        """The deck's own buffers by number (from the storage of the run)."""
        values = np.asarray(self._raw["buffer_values"], dtype=np.float64)
        return {n: values[:, k] for k, n in enumerate(self._raw["buffer_numbers"])}

    @functools.cached_property
    def time(self) -> FloatArray:
        """The time at every position."""
        return self._block("time")

    @functools.cached_property
    def det(self) -> FloatArray:
        """det(D^c) at every position."""
        return self._block("det")

    @functools.cached_property
    def inputs(self) -> FloatArray:
        """Input values, positions x inputs (DOF order)."""
        return self._block("inputs")

    @functools.cached_property
    def _row_index(self) -> dict[Row, int]:
        return {r: k for k, r in enumerate(self.numbering.rows)}

    # The run as a deck run reports it is built when first asked for: a design study reads most variants
    # through their outputs only, and building it (the model echo, the report) costs more than the rest.
    @functools.cached_property
    def _run_result(self) -> RunResult:
        return self._deck_result()

    @property
    def report(self) -> RunReport:
        """What the run did, as :func:`mechfem.run_deck` reports it for the deck written from the mechanism."""
        return self._run_result.report

    # -- the run

    @property
    def positions(self) -> int:
        """Positions computed."""
        return int(self.coords.shape[0])

    @property
    def complete(self) -> bool:
        """True when every position asked for was computed."""
        return self.report.complete

    @property
    def limits(self) -> list[Limit]:
        """Limit positions met on the way."""
        return self.report.limits

    def stop_reason(self) -> str | None:
        """Why the motion stopped early, where, and what to change (in the model's names and Python calls), or
        None."""
        from mechfem.explain import PythonWords

        return self.report.stop_reason(words=PythonWords(self.numbering))

    @property
    def warnings(self) -> list[str]:
        """The limit positions and singular positions, one sentence each (in the model's names)."""
        from mechfem.explain import PythonWords

        return self.report.describe_warnings(PythonWords(self.numbering))

    # -- names

    def _lookup(self, ref: object, what: str = "", kinds: tuple[type, ...] = ()) -> object:
        """The point, co-ordinate or row ``ref`` names (a form parameter gives its row); a name the model does not
        have is an error that suggests the closest ``what`` (of ``kinds``: any without)."""
        from mechfem.model import FormParameter, Row

        accept = (lambda o: isinstance(o, kinds)) if kinds else None
        obj = self.mechanism.find(ref, what, accept) if isinstance(ref, str) else ref
        if isinstance(obj, FormParameter):
            found = [r for r in self.numbering.rows if r.terms == ((1.0, obj),)]
            if not found:
                raise KeyError(
                    f"{obj.label} is neither prescribed nor an output; declare it with Mechanism.output() to get it"
                )
            obj = found[0]
        if isinstance(obj, Row) and obj not in self._row_index:
            raise KeyError(f"row {obj.name!r} is not part of this run")
        return obj

    def _column(self, c: Coordinate) -> int:
        try:
            return self.numbering.coord_number[c] - 1
        except KeyError:
            raise KeyError(f"co-ordinate {c.name!r} is not part of this run") from None

    def _dof(self, wrt: InputKey) -> int:
        return self.numbering.dof(wrt) - 1

    def _point(self, ref: str | Point) -> tuple[int, int]:
        obj = self._point_named(ref)
        return self._column(obj.x), self._column(obj.y)

    def _point_named(self, ref: str | Point) -> Point:
        from mechfem.model import Point

        obj = self._lookup(ref, "point", (Point,))
        if not isinstance(obj, Point):
            raise TypeError(f"{ref!r} is not a point")
        return obj

    def _traced_points(self, names: Sequence[str] | None = None) -> list[Point]:
        """The points whose paths a picture, animation or drawing traces: those called ``names``, or by default
        every moving point whose two co-ordinates the run computed."""
        if names is None:
            cols = self.numbering.coord_number
            return [p for p in self.mechanism.points if not p.fixed and p.x in cols and p.y in cols]
        return [self._point_named(name) for name in names]

    def _select(
        self,
        ref: object,
        coord: Callable[[list[int]], FloatArray],
        row: Callable[[int], FloatArray],
    ) -> FloatArray:
        from mechfem.model import Coordinate, Point, Row

        obj = self._lookup(ref, "point, co-ordinate, row or output", (Point, Coordinate, Row))
        if isinstance(obj, Point):
            return coord([self._column(obj.x), self._column(obj.y)])
        if isinstance(obj, Coordinate):
            return coord([self._column(obj)])[:, 0]
        if isinstance(obj, Row):
            return row(self._row_index[obj])
        raise TypeError(f"{ref!r} is not a point, co-ordinate, row or output")

    def _blocks(self, ref: object, coords: str, rows: str, *inputs: int) -> FloatArray:
        """``ref`` from the layout's block ``coords`` (a point or co-ordinate) or ``rows`` (a row), at the input
        indices ``inputs`` of the block's shape."""

        def at(where: Any) -> tuple[Any, ...]:
            return (slice(None), where, *inputs)

        return self._select(
            ref, lambda cols: self._block(coords)[at(cols)].copy(), lambda k: self._block(rows)[at(k)].copy()
        )

    # -- values

    def x(self, point: str | Point) -> FloatArray:
        """x of a point at every position."""
        return self.coords[:, self._point(point)[0]].copy()

    def y(self, point: str | Point) -> FloatArray:
        """y of a point at every position."""
        return self.coords[:, self._point(point)[1]].copy()

    def value(
        self,
        name: str | Point | Coordinate | Row | FormParameter,
        order: int = 0,
        wrt: InputKey = None,
        wrt2: InputKey = None,
        unit: Unit | None = None,
    ) -> FloatArray:
        """A point (positions x 2), co-ordinate, row or output at every position (``order`` 0), or its transfer
        function of first (d/d ``wrt``) or second order (d2/d ``wrt`` d ``wrt2``; ``wrt2`` defaults to ``wrt``).
        ``unit="deg"`` gives every angle in degrees: an angle's value, and a transfer function per degree of an
        angle input (d psi / d alpha of two angles is the same in either unit)."""
        if order == 0:
            out = self._select(name, lambda cols: self.coords[:, cols].copy(), lambda k: self._block("e0")[:, k].copy())
            return self._in_unit(out, name, (), unit)
        j = self._dof(wrt)
        if order == 1:
            out = self._blocks(name, "kx1", "ke1", j)
            return self._in_unit(out, name, (j,), unit)
        if order == 2:
            m = j if wrt2 is None else self._dof(wrt2)
            out = self._blocks(name, "kx2", "ke2", j, m)
            return self._in_unit(out, name, (j, m), unit)
        raise ValueError(f"order must be 0, 1 or 2, not {order!r}")

    def _in_unit(self, values: FloatArray, ref: object, dofs: Sequence[int], unit: Unit | None) -> FloatArray:
        """``values`` of ``ref`` differentiated by the inputs ``dofs`` (0-based) in ``unit``: with ``"deg"``, an
        angle's value times 180/pi, divided by 180/pi for each angle input it is differentiated by."""
        if check_unit(unit) != "deg":
            return values
        from mechfem.model import Coordinate, Row

        obj = self._lookup(ref)
        angle = (isinstance(obj, Coordinate) and obj.kind == "angle") or (isinstance(obj, Row) and obj.is_angle)
        power = int(angle) - sum(self.numbering.inputs[j].is_angle for j in dofs)
        if not angle and power == 0:
            name = getattr(obj, "name", ref)
            raise ValueError(
                f"{name!r} is not an angle, and neither is an input it is differentiated by: unit='deg' applies to "
                "angles only"
            )
        return values * factor("deg") ** power if power else values

    def position(self, name: str | Point | Coordinate | Row | FormParameter, unit: Unit | None = None) -> FloatArray:
        """The same as ``value(name)``: a point's (x, y), a co-ordinate, a row or an output (an angle in ``unit``,
        ``"rad"`` or ``"deg"``)."""
        return self.value(name, unit=unit)

    def output(
        self,
        name: str | Row | FormParameter,
        order: int = 0,
        wrt: InputKey = None,
        wrt2: InputKey = None,
        unit: Unit | None = None,
    ) -> FloatArray:
        """An output (or any row: a prescribed value, an input) and its transfer functions; see :meth:`value`."""
        from mechfem.model import Row

        if not isinstance(self._lookup(name, "output or row", (Row,)), Row):
            raise TypeError(f"{name!r} is not a row or output")
        return self.value(name, order, wrt, wrt2, unit)

    def transfer(
        self,
        name: str | Point | Coordinate | Row | FormParameter,
        order: int = 1,
        wrt: InputKey = None,
        wrt2: InputKey = None,
        unit: Unit | None = None,
    ) -> FloatArray:
        """Transfer function of first or second order; see :meth:`value`."""
        if order not in (1, 2):
            raise ValueError(f"a transfer function has order 1 or 2, not {order!r}")
        return self.value(name, order, wrt, wrt2, unit)

    def velocity(self, name: str | Point | Coordinate | Row | FormParameter, unit: Unit | None = None) -> FloatArray:
        """Velocity (time derivative) of a point (positions x 2), co-ordinate, row or output (an angle's in ``unit``
        per time)."""
        out = self._blocks(name, "vx", "ve")
        return self._in_unit(out, name, (), unit)

    def acceleration(
        self, name: str | Point | Coordinate | Row | FormParameter, unit: Unit | None = None
    ) -> FloatArray:
        """Acceleration of a point (positions x 2), co-ordinate, row or output (an angle's in ``unit`` per time
        squared)."""
        out = self._blocks(name, "ax", "ae")
        return self._in_unit(out, name, (), unit)

    def input(self, name: InputKey = None, unit: Unit | None = None) -> FloatArray:
        """The value of an input at every position (under free motion: where it went), an angle in ``unit``
        (``"rad"``, the default, or ``"deg"``)."""
        j = self._dof(name)
        return self._in_unit(self.inputs[:, j].copy(), self.numbering.inputs[j], (), unit)

    # -- inverse dynamics

    def _dynamics(self, what: str) -> None:
        if not self.dynamic:
            raise ValueError(
                f"the mechanism {self.mechanism.name!r} has no masses or loads, so its run computed no {what}: give "
                "them with Mechanism.mass, point_mass, inertia, gravity, force, load, load_table, spring or motor"
            )

    def sensitivity(self, quantity: Any, wrt: str | Sequence[str]) -> FloatArray:
        """The derivative of ``quantity`` at every position with respect to the design variables ``wrt`` (names of
        prescribed values or fixed co-ordinates, as for :func:`mechfem.optimize`): positions x variables, or one
        value per position for a single name. ``quantity`` is a name (its value) or ``Q(name, order, wrt)`` for a
        transfer function. Exact: from the factorisation of D^c at each position (one more run of the motion)."""
        names = [wrt] if isinstance(wrt, str) else list(wrt)
        out = SENSITIVITY.call(self, quantity, names)
        return out[:, 0].copy() if isinstance(wrt, str) else out

    def drive_torque(self, input: InputKey = None) -> FloatArray:
        """The force or torque the drive of an input delivers at every position (the stress of its row), positive when
        it does positive work as the input increases; ``input`` as ``wrt`` (it may be left out with one input)."""
        self._dynamics("drive torques")
        return self._block("drive")[:, self._dof(input)].copy()

    def stress(self, row: str | Row | FormParameter) -> FloatArray:
        """The generalised stress of a prescribed row (or input): the force or torque its constraint applies in the
        direction of increasing value, e.g. the axial force of a bar of prescribed length, positive when it pushes
        its ends apart."""
        from mechfem.model import Row

        self._dynamics("stresses")
        obj = self._lookup(row, "prescribed value or input", (Row,))
        if not isinstance(obj, Row):
            raise TypeError(f"{row!r} is not a row")
        dest = self.numbering.row_dest[obj]
        if dest < 0:
            raise KeyError(f"{obj.name!r} is an output, which carries no stress: only prescribed rows and inputs do")
        return self._block("sigma")[:, dest - 1].copy()

    def reaction(self, point_or_coordinate: str | Point | Coordinate) -> FloatArray:
        """The force the frame applies at a fixed point (positions x 2: x, y) or on one fixed co-ordinate."""
        from mechfem.model import Coordinate, Point

        self._dynamics("reactions")
        obj = self._lookup(point_or_coordinate, "point or co-ordinate", (Point, Coordinate))
        coords = [obj.x, obj.y] if isinstance(obj, Point) else [obj] if isinstance(obj, Coordinate) else None
        if coords is None:
            raise TypeError(f"{point_or_coordinate!r} is not a point or co-ordinate")
        moving = [c.name for c in coords if not c.fixed]
        if moving:
            fixed = [c.name for c in coords if c.fixed]
            hint = f"; ask for the fixed one, reaction({fixed[0]!r})" if fixed else ""
            raise KeyError(f"{', '.join(moving)} moves: only the frame (fixed co-ordinates) has reactions{hint}")
        out = self._block("reaction")[:, [self._column(c) for c in coords]].copy()
        return out if isinstance(obj, Point) else out[:, 0]

    def energy(self) -> Energy:
        """Kinetic, potential (gravity and springs) and total energy at every position."""
        self._dynamics("energies")
        t, v = self._block("ekin").copy(), self._block("epot").copy()
        return Energy(t, v, t + v)

    def power(self) -> FloatArray:
        """The power the drives deliver at every position (the sum of drive torque times input speed)."""
        self._dynamics("power")
        return self._block("power").copy()

    def mass_matrix(self) -> FloatArray:
        """The mass matrix M(q) in the inputs at every position (positions x D x D; kinetic energy
        ``T = 1/2 qdot^T M qdot``)."""
        self._dynamics("mass matrix")
        return self._block("mass").copy()

    # -- tables

    def table(self, coordinates: bool = True) -> dict[str, FloatArray]:
        """Every result as named columns: ``time``, ``det``, then each input, output and (with ``coordinates``)
        moving co-ordinate ``q`` as ``q``, ``q'``, ``q''`` (transfer functions; ``q'(a)``, ``q''(a,b)`` with
        several inputs), ``q_dot`` and ``q_ddot`` (velocity, acceleration)."""
        nb = self.numbering
        inputs = [r.name for r in nb.inputs]
        single = len(inputs) == 1
        out: dict[str, FloatArray] = {"time": self.time.copy(), "det": self.det.copy()}

        def add(name: str, ref: Coordinate | Row) -> None:
            out[name] = self.value(ref)
            for j, a in enumerate(inputs):
                out[f"{name}'" if single else f"{name}'({a})"] = self.value(ref, 1, j + 1)
                for m, b in enumerate(inputs[j:], j):
                    key = f"{name}''" if single else f"{name}''({a},{b})"
                    out[key] = self.value(ref, 2, j + 1, m + 1)
            out[f"{name}_dot"] = self.velocity(ref)
            out[f"{name}_ddot"] = self.acceleration(ref)

        for r in nb.inputs:
            out[r.name] = self.input(r)
            out[f"{r.name}_dot"] = self.velocity(r)
            out[f"{r.name}_ddot"] = self.acceleration(r)
        for r in nb.dependent:
            add(r.name, r)
        if coordinates:
            for c in nb.coords:
                if not c.fixed:
                    add(c.name, c)
        return out

    def to_pandas(self, coordinates: bool = True) -> Any:
        """:meth:`table` as a ``pandas.DataFrame`` indexed by position (1, 2, ...). Needs pandas
        (``pip install 'mechfem[pandas]'``)."""
        pd = _pandas()
        frame = pd.DataFrame(self.table(coordinates))
        frame.index = pd.RangeIndex(1, self.positions + 1, name="position")
        return frame

    # -- pictures

    def run_result(self) -> RunResult:
        """The run as :func:`mechfem.run_deck` returns it for the deck written from the mechanism (deck numbers),
        as the deck's pictures and animation use it."""
        return self._run_result

    def _deck_result(self) -> RunResult:
        from mechfem.result import run_result

        d: dict[str, Any] = dict(self._raw)
        nd = self.inputs.shape[1]
        # A deck's own blocks (``run_deck``'s layout), in its order: the buffers, the hodographs of every
        # co-ordinate, the dynamics, time and det.
        blocks = {"buffers": np.asarray(d["buffer_values"], dtype=np.float64)}
        blocks["hodograph"] = self._block("kx1")[:, :, 0] if nd else np.zeros((self.positions, 0))
        if self.dynamic:
            blocks["inputs"], blocks["drive"] = self.inputs, self._block("drive")
            blocks.update((name, self._block(name)) for name in ("ekin", "epot", "power"))
        blocks["time"], blocks["det"] = self.time, self.det
        starts = np.cumsum([0] + [math.prod(b.shape[1:]) for b in blocks.values()])
        d["layout"] = {name: (int(at), b.shape[1:]) for (name, b), at in zip(blocks.items(), starts, strict=False)}
        d["table"] = np.column_stack([b.reshape(self.positions, -1) for b in blocks.values()])
        d["hodograph_coords"] = list(range(1, self.coords.shape[1] + 1)) if nd else []
        result = run_result(Path(self.path), d)  # type: ignore[arg-type]
        nb = self.numbering
        # The model's own names, so that the pictures and tables label every quantity as the model calls it.
        names = ModelNames(
            coordinates=[c.name for c in nb.coords],
            prescribed=[r.name for r in nb.prescribed],
            dependent=[r.name for r in nb.dependent],
            inputs=[r.name for r in nb.inputs],
        )
        return dataclasses.replace(result, names=names)

    def plot(self, *outputs: str, **options: Any) -> Any:
        """A figure (``matplotlib.figure.Figure``): the mechanism at position 1 with the paths of its moving points,
        beside the ``outputs`` (default: every output) against the first input. Options: ``picture=k`` draws
        picture k of the storage as the deck does; ``points=[...]`` chooses the paths; ``against="time"``."""
        return PLOT.call(self, outputs, **options)

    def animate(self, path: str | Path, points: Sequence[str] | None = None) -> list[Path]:
        """Writes an animation of the motion to ``path`` (GIF; also MP4 when ffmpeg is installed) with the paths
        of ``points`` (default: every moving point); returns the files written."""
        return ANIMATE.call(self, path, points)

    def to_dxf(
        self, path: str | Path, position: int = 1, paths: bool | Sequence[str] = True, units: str | None = None
    ) -> Path:
        """Writes the mechanism at ``position`` (1-based) as a DXF file with the paths of its moving points
        (``paths``: True, False or point names) and the points' names, one layer per kind of shape; ``units``
        ("mm", "m", ...) declares the length unit. Needs ezdxf (``pip install 'mechfem[dxf]'``)."""
        return TO_DXF.call(self, path, position, paths, units)

    def to_svg(self, path: str | Path, position: int = 1, paths: bool | Sequence[str] = True) -> Path:
        """Writes the mechanism at ``position`` (1-based) as an SVG file, as :meth:`to_dxf` does a DXF file."""
        return TO_SVG.call(self, path, position, paths)

    def _repr_png_(self) -> bytes | None:
        return PNG.call(self)

    def _repr_html_(self) -> str:
        return HTML.call(self)

    def __repr__(self) -> str:
        state = "complete" if self.complete else f"stopped after position {self.positions}"
        return f"Analysis({self.mechanism.name!r}: {self.positions} positions, {state}, {len(self.limits)} limit(s))"


# The methods above whose work an upper layer does (docs/architecture.md), filled by mechfem.optimise,
# mechfem.figures, mechfem.export and mechfem.notebook when they are imported.
SENSITIVITY: Hook[Callable[[Analysis, Any, list[str]], FloatArray]] = Hook("Analysis.sensitivity", "mechfem.optimise")
PLOT: Hook[Callable[..., Any]] = Hook("Analysis.plot", "mechfem.figures")
ANIMATE: Hook[Callable[[Analysis, str | Path, Sequence[str] | None], list[Path]]] = Hook(
    "Analysis.animate", "mechfem.figures"
)
TO_DXF: Hook[Callable[[Analysis, str | Path, int, bool | Sequence[str], str | None], Path]] = Hook(
    "Analysis.to_dxf", "mechfem.export"
)
TO_SVG: Hook[Callable[[Analysis, str | Path, int, bool | Sequence[str]], Path]] = Hook(
    "Analysis.to_svg", "mechfem.export"
)
PNG: Hook[Callable[[Analysis], bytes | None]] = Hook("Analysis._repr_png_", "mechfem.notebook")
HTML: Hook[Callable[[Analysis], str]] = Hook("Analysis._repr_html_", "mechfem.notebook")


def _pandas() -> Any:
    try:
        return importlib.import_module("pandas")
    except ImportError:
        raise ImportError(
            "to_pandas() needs pandas, which mechfem does not install by itself: pip install 'mechfem[pandas]' "
            "(or pip install pandas)"
        ) from None
