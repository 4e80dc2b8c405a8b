"""Design variables and buffers in the model's own units (its UNITS: lengths in mm, angles in degrees, ...).

The core's design models take every variable in the core's units (metres, radians) and give a buffer's value, its
gradient and the co-ordinates at position 1 in them too. :func:`mechfem.optimize` and
:meth:`mechfem.RunResult.sensitivity` work in the model's units throughout, as the designer states the problem
(ranges, start values, free timing and its order, a whole turn of 360, a TargetAt or Bound of a length or an
angle): the models here hand the core a variable times its unit's factor (pi/180 for degrees, 1/1000 for mm) and
scale its gradient column by the same factor (d/d degree = pi/180 d/d radian), and give a length's or an angle's
value, its gradient and the co-ordinates at position 1 divided by it; a transfer function is divided by its
quantity's factor over its inputs' (mm/deg). A dynamic optimisation's mass variables (a mass in g, a centre of mass
in mm, a moment of inertia in kg·mm²) and its drive torques and shaking forces and moments (N·mm) are scaled the
same way. A model in metres, radians, kilograms and newtons is not wrapped, so its results stay bit for bit the
core's."""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING, Any

import numpy as np

import mechfem._core as _core
from mechfem.design import evaluated
from mechfem.model.catalogue import coordinate_dimensions, form_dimension
from mechfem.model.units import scale

if TYPE_CHECKING:
    from mechfem.design.frame_angle import Turn
    from mechfem.design.timing import Plan
    from mechfem.model.mechanism import Mechanism
    from mechfem.model.parts import Coordinate

DEGREE = math.pi / 180.0


class Factors:
    """What a value in the model's units is multiplied by to give it in the core's, by dimension: ``length`` (1 for
    metres), ``angle`` (1 for radians, :data:`DEGREE` for degrees), ``mass`` (1 for kilograms) and ``force`` (1 for
    newtons)."""

    def __init__(self, mech: Mechanism) -> None:
        self.mech = mech
        self.length = scale(mech.units.length or "m", "m")
        self.angle = DEGREE if mech.units.angle == "deg" else 1.0
        self.mass = scale(mech.units.mass or "kg", "kg")
        self.force = scale(mech.units.force or "N", "N")

    @property
    def wrapped(self) -> bool:
        """Whether the core's models need wrapping: the model is not in metres, radians, kilograms and newtons."""
        return any(f != 1.0 for f in (self.length, self.angle, self.mass, self.force))

    def mass_variable(self, kind: int, on: Coordinate | None) -> float:
        """The factor of a mass model's variable of ``kind`` (:data:`mechfem.design.dynamic_optimise.BODY_FIELDS`:
        10 a body's mass, 11 and 12 its centre's u and v, 13 its moment of inertia, 14 a point mass, 15 an inertia
        on the co-ordinate ``on``: a mass on a length, a moment of inertia on an angle)."""
        if kind in (11, 12):
            return self.length
        if kind == 13 or (kind == 15 and on is not None and on.kind == "angle"):
            return self.mass * self.length**2
        return self.mass

    def of(self, dimension: str | None) -> float:
        return self.length if dimension == "length" else self.angle if dimension == "angle" else 1.0

    def coordinate(self, c: Coordinate) -> float:
        """The factor of co-ordinate ``c``: a point's x or y is a length; an angle an angle; a scalar measures what
        its element's catalogue entry says (a radius is a length, a ratio has no unit)."""
        if c.kind in ("x", "y"):
            return self.length
        if c.kind == "angle":
            return self.angle
        for e in self.mech.elements:
            for slot, dimension in zip(e.coordinates, coordinate_dimensions(e.type), strict=False):
                if slot is c:
                    return self.of(dimension)
        return 1.0

    def form(self, obj: Any) -> float:
        """The factor of a form parameter or a row of them (every term of one dimension; 1 for a mixed row)."""
        terms = obj.terms() if callable(obj.terms) else obj.terms
        dimensions = set()
        for _, p in terms:
            dimension = form_dimension(p.element.type, p.form)
            if dimension == "any":
                dimension = "angle" if p.is_angle else "length"
            dimensions.add(dimension)
        return self.of(dimensions.pop()) if len(dimensions) == 1 else 1.0


class ScaledModel:
    """A core design model whose variables are given in the model's units: ``factors`` (one per variable) turn
    them into the core's; ``buffers`` (one per buffer, 1 for none) and ``coordinates`` (one per co-ordinate, deck
    order) turn a buffer's value and a co-ordinate at position 1 from the core's units into the model's by
    division."""

    def __init__(
        self,
        inner: Any,
        factors: Sequence[float],
        buffers: Sequence[float] = (),
        coordinates: Sequence[float] = (),
        extrema: Sequence[float] = (),
    ) -> None:
        self.inner, self.factors = inner, np.asarray(factors, dtype=np.float64)
        self.buffers = np.asarray(buffers, dtype=np.float64)
        self.coordinates = list(coordinates)
        self.extrema = list(extrema)
        """The factor of each extremum spec's buffer."""

    @property
    def runs(self) -> int:
        return int(self.inner.runs)

    def start(self) -> list[float]:
        return [float(y) / f for y, f in zip(self.inner.start(), self.factors, strict=True)]

    def start_at(self, values: list[float]) -> _core.Evaluation:
        got: _core.Evaluation = self.inner.start_at(self._in_core(values))
        return self._scaled(got)

    def evaluate(self, values: list[float]) -> _core.Evaluation:
        got: _core.Evaluation = self.inner.evaluate(self._in_core(values))
        return self._scaled(got)

    def _in_core(self, values: Sequence[float]) -> list[float]:
        return [float(v) * f for v, f in zip(values, self.factors, strict=True)]

    def _scaled(self, got: _core.Evaluation) -> _core.Evaluation:
        if not got.feasible:
            return got
        gradient = np.asarray(got.gradient, dtype=np.float64) * self.factors
        values = got.values
        scaled = [k for k, f in enumerate(self.buffers) if f != 1.0]
        if scaled:
            values = np.array(values, dtype=np.float64)
            for k in scaled:
                values[:, k] /= self.buffers[k]
                gradient[:, k, :] /= self.buffers[k]
        position_one = got.position_one
        if position_one and self.coordinates:
            position_one = [float(v) / f for v, f in zip(position_one, self.coordinates, strict=False)] + list(
                position_one[len(self.coordinates) :]
            )
        extrema = got.extrema
        if extrema and any(f != 1.0 for f in self.extrema):
            extrema = [self._extremum(x) for x in extrema]
        return evaluated.replaced(got, values=values, gradient=gradient, position_one=position_one, extrema=extrema)

    def _extremum(self, x: _core.Extremum) -> _core.Extremum:
        f = self.extrema[x.spec] if x.spec < len(self.extrema) else 1.0
        gradient = np.asarray(x.gradient, dtype=np.float64) * self.factors / f
        return evaluated.replaced(x, value=x.value / f, gradient=list(gradient))


class ScaledBuilder:
    """A model builder whose design models take the variables in ``factors`` (core numbering -> factor) in the
    model's units and give the buffers in ``buffers`` (number -> factor) and the co-ordinates at position 1
    (``coordinates``, deck order) in them."""

    def __init__(
        self,
        builder: Any,
        factors: Mapping[tuple[int, int], float],
        buffers: Mapping[int, float],
        coordinates: Sequence[float] = (),
    ) -> None:
        self.builder, self.factors, self.buffers, self.coordinates = builder, factors, buffers, coordinates

    def design(self, base: str, variables: list[tuple[int, int]], buffers: list[int], extrema: Any) -> Any:
        return self._wrapped(self.builder.design(base, variables, buffers, extrema), variables, buffers, extrema)

    def dynamic_design(self, base: str, variables: list[tuple[int, int]], buffers: list[int], extrema: Any) -> Any:
        """The dynamic design model (inverse dynamics' buffers, mass variables) in the model's units."""
        model = self.builder.dynamic_design(base, variables, buffers, extrema)
        return self._wrapped(model, variables, buffers, extrema)

    def _wrapped(self, model: Any, variables: list[tuple[int, int]], buffers: list[int], extrema: Any) -> ScaledModel:
        return ScaledModel(
            model,
            [self.factors.get(v, 1.0) for v in variables],
            [self.buffers.get(b, 1.0) for b in buffers],
            self.coordinates,
            [self.buffers.get(int(spec[0]), 1.0) for spec in extrema],
        )


def whole_turn(mech: Mechanism) -> float:
    """One turn in the mechanism's unit of angle: 2 pi, or 360 when its angles are in degrees."""
    return 360.0 if mech.units.angle == "deg" else 2.0 * math.pi


def variable_factors(
    mech: Mechanism,
    vary: Mapping[str, tuple[float, float] | None] | Sequence[str],
    variables: Sequence[tuple[int, int, float]],
    timed: Plan | None,
    turn: Turn | None = None,
) -> dict[tuple[int, int], float]:
    """The factor of each variable (core numbering) of ``optimize`` that has a unit other than the core's, the
    free timing's input and what a frame angle's ``turn`` moves among them."""
    from mechfem.design.dynamic_optimise import inertia_coordinate, is_mass
    from mechfem.design.optimise import _lookup
    from mechfem.model.mechanism import Coordinate

    units = Factors(mech)
    out: dict[tuple[int, int], float] = {}
    for name, (kind, number, _) in zip(vary, variables, strict=True):
        if is_mass(kind):
            f = units.mass_variable(kind, inertia_coordinate(mech, name))
            if f != 1.0:
                out[(kind, number)] = f
            continue
        obj = _lookup(mech, name)
        f = units.coordinate(obj) if isinstance(obj, Coordinate) else units.form(obj)
        if f != 1.0:
            out[(kind, number)] = f
    if timed is not None:
        f = units.angle if timed.angle else units.length
        if f != 1.0:
            out[timed.input_var] = f
    if turn is not None:
        moved = [v for v in turn.names if v not in out]
        out |= variable_factors(mech, [turn.names[v] for v in moved], [(k, n, 0.0) for k, n in moved], None)
    return out


def buffer_factors(mech: Mechanism, keys: Mapping[tuple[str, tuple[object, ...]], int]) -> dict[int, float]:
    """Of the buffers ``keys`` (``optimize``'s (keyword, arguments) -> number), those whose unit in the model is not
    the core's, with their factor: a length's or an angle's value (a co-ordinate or a row; a transmission angle),
    a transfer function of one (its unit over its inputs' units), a drive torque or force, and the shaking force
    and moment."""
    from mechfem.model.mechanism import Coordinate, FormParameter, Row

    units = Factors(mech)
    out = {}
    for (keyword, args), number in keys.items():
        obj = args[0] if args else None
        f = 1.0
        if keyword == "BUFDRV" and isinstance(obj, str):
            # A torque drives an angle, a force a length.
            f = units.force * (units.length if mech[obj].is_angle else 1.0)
        elif keyword in ("BUFSHAKE", "BUFSHAKE+1"):
            f = units.force
        elif keyword == "BUFSHAKE+2":
            f = units.force * units.length
        elif keyword == "BUFTRA":
            f = units.angle
        elif keyword == "BUFX0" and isinstance(obj, Coordinate):
            f = units.coordinate(obj)
        elif keyword == "BUFE0" and isinstance(obj, Row | FormParameter):
            f = units.form(obj)
        elif keyword in ("BUFKX1", "BUFKX2", "BUFKE1", "BUFKE2") and isinstance(obj, Coordinate | Row | FormParameter):
            # A transfer function in the model's derived unit (mm/deg, deg/deg): the quantity's factor over the
            # factor of each input it is taken with respect to.
            f = units.coordinate(obj) if isinstance(obj, Coordinate) else units.form(obj)
            inputs = [r for r in mech.rows if r.kind == "input"]
            for j in args[1:]:
                f /= units.form(inputs[int(j) - 1])  # type: ignore[call-overload]
        if f != 1.0:
            out[number] = f
    return out


def coordinate_factors(mech: Mechanism, coords: Sequence[Coordinate]) -> list[float]:
    """The factor of each co-ordinate ``coords`` (a deck's numbering, in order)."""
    units = Factors(mech)
    return [units.coordinate(c) for c in coords]


def builder(
    mech: Mechanism,
    core: Any,
    factors: Mapping[tuple[int, int], float],
    keys: Mapping[tuple[str, tuple[object, ...]], int],
    numbering: Any = None,
) -> Any:
    """``core`` wrapped so that its design models work in ``mech``'s units: the variables ``factors``
    (:func:`variable_factors`), the buffers ``keys`` (:func:`buffer_factors`) and, with the deck's ``numbering``,
    the co-ordinates at position 1; ``core`` itself for a model in metres and radians."""
    if not Factors(mech).wrapped:
        return core
    coords = coordinate_factors(mech, numbering.coords) if numbering is not None else []
    return ScaledBuilder(core, factors, buffer_factors(mech, keys), coords)


__all__ = [
    "DEGREE",
    "Factors",
    "ScaledBuilder",
    "ScaledModel",
    "buffer_factors",
    "builder",
    "coordinate_factors",
    "variable_factors",
    "whole_turn",
]
