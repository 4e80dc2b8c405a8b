"""The input motion of a :class:`~mechfem.Mechanism`: steps, and per input how it moves.

:class:`Motion` is the MOVEMENT block of a deck: ``steps`` steps of ``dt`` each, and per input
:class:`By` (MOV_RELE), :class:`To` (MOV_ABSE), :class:`Free` (MOV_FREE), :class:`Table` (MOV_FUNC) or
:class:`Dynamic` (MOV_DYN: the input moves under the forces, and the deck simulates, mode ``DYN SIM``).

The value of an angle input may be given in degrees (``unit="deg"``); the deck gets it in radians
(:mod:`mechfem.model.units`). A change of an angle input larger than 100 rad given without a unit warns with
:class:`~mechfem.errors.UnitWarning`: it was probably meant in degrees.
"""

from __future__ import annotations

import warnings
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Protocol, TypeAlias, Union

import numpy as np
import numpy.typing as npt

from mechfem._util.checks import finite
from mechfem._util.names import unknown_name
from mechfem.errors import UnitWarning, user_stacklevel
from mechfem.model.catalogue import MAX_ITER, MAX_STEPS
from mechfem.model.units import LARGE_ANGLE, Unit, array_to_radians, check_unit, to_radians, wrong_angle_unit

if TYPE_CHECKING:
    from mechfem.model.parts import FormParameter, Row

FloatArray = npt.NDArray[np.float64]


class MechanismInputs(Protocol):
    """What a simulation's motion needs of a :class:`~mechfem.Mechanism` (which sits above the motion)."""

    name: str

    @property
    def inputs(self) -> list[Row]: ...


@dataclass(frozen=True)
class By:
    """Equidistant steps that change the input by ``delta`` in total (MOV_RELE); an angle in ``unit`` (``"rad"``,
    the default, or ``"deg"``)."""

    delta: float
    unit: Unit | None = None

    def __post_init__(self) -> None:
        check_unit(self.unit)

    @property
    def value(self) -> float:
        """``delta`` in the model's unit (radians for an angle)."""
        return to_radians(self.delta, self.unit)


@dataclass(frozen=True)
class To:
    """Equidistant steps from the input's value at position 1 to ``end`` (MOV_ABSE); an angle in ``unit``
    (``"rad"``, the default, or ``"deg"``)."""

    end: float
    unit: Unit | None = None

    def __post_init__(self) -> None:
        check_unit(self.unit)

    @property
    def value(self) -> float:
        """``end`` in the model's unit (radians for an angle)."""
        return to_radians(self.end, self.unit)


@dataclass(frozen=True)
class Free:
    """Free motion through limit positions with step ``ds`` in co-ordinate space (MOV_FREE; one input only).

    ``ds`` is the Euclidean length of a step over every moving co-ordinate at once (lengths and angles together),
    not an angle, so it has no unit; its sign sets the direction the input starts in."""

    ds: float

    def __post_init__(self) -> None:
        if finite(self.ds, "the step ds of free motion") == 0.0:
            raise ValueError(
                "the step ds of free motion must not be 0: give the distance the moving co-ordinates travel per "
                "step, e.g. Motion.free(steps, ds=0.01) (negative to start the other way)"
            )


@dataclass(frozen=True, eq=False)
class Table:
    """The input's value (and velocity, acceleration) at every position (MOV_FUNC).

    ``time`` defaults to ``k * dt``, velocities and accelerations to 0. ``file`` is the file name a
    deck written by :meth:`Mechanism.save_deck` uses for it. ``unit`` (``"rad"``, the default, or ``"deg"``) is
    the unit of an angle's values, velocities (per time) and accelerations.
    """

    values: FloatArray
    velocities: FloatArray | None = None
    accelerations: FloatArray | None = None
    time: FloatArray | None = None
    file: str | None = None
    unit: Unit | None = None

    def __post_init__(self) -> None:
        check_unit(self.unit)

    def rows(self, dt: float) -> FloatArray:
        """The four columns ``t value velocity acceleration``, one row per position, in the model's units."""
        v = array_to_radians(self.values, self.unit)
        n = v.shape[0]

        def column(a: npt.ArrayLike | None, default: FloatArray) -> FloatArray:
            if a is None:
                return default
            out = array_to_radians(a, self.unit)
            if out.shape != (n,):
                raise ValueError(f"a motion table needs {n} values per column, one per position, got {out.shape}")
            return out

        zero = np.zeros(n)
        t = np.asarray(self.time, dtype=np.float64) if self.time is not None else dt * np.arange(n, dtype=np.float64)
        if t.shape != (n,):
            raise ValueError(f"a motion table needs {n} times, one per position, got {t.shape}")
        return np.column_stack([t, v, column(self.velocities, zero), column(self.accelerations, zero)])


@dataclass(frozen=True)
class Dynamic:
    """The input moves under the forces, starting with the speed ``v0`` (MOV_DYN): the run is a simulation (mode
    ``DYN SIM``), which needs masses (:meth:`Mechanism.mass`, ...). ``unit`` ``"deg"`` gives an angle's speed in
    degrees per time."""

    v0: float = 0.0
    unit: Unit | None = None

    def __post_init__(self) -> None:
        check_unit(self.unit)

    @property
    def value(self) -> float:
        """``v0`` in the model's unit (radians per time for an angle)."""
        return to_radians(self.v0, self.unit)


InputMotion: TypeAlias = By | To | Free | Table | Dynamic
InputKey: TypeAlias = Union[str, int, "Row", "FormParameter", None]
"""An input named by its name, its DOF number (1-based), its row or form parameter; None: the only input."""


@dataclass(frozen=True)
class Motion:
    """The input motion: ``steps`` steps (``steps + 1`` positions) of ``dt`` each, and one motion per input.

    Build it with :meth:`by`, :meth:`to`, :meth:`free`, :meth:`table` or :meth:`dynamic`, or give
    ``inputs`` (input name, DOF number or None for the only input -> :class:`By`, :class:`To`,
    :class:`Free`, :class:`Table` or :class:`Dynamic`). ``accuracy`` and ``max_iter`` set the Newton
    tolerance and iteration limit (deck keywords ACCURACY, MAXITER; default 1e-10 and 25). ``rtol``
    and ``atol`` are the tolerances of a simulation's integrator (INTTOL; each defaults to ACCURACY),
    ``integrator`` its method (INTEGRATOR, one of :data:`INTEGRATORS`) and ``stop_when`` a ``(buffer, value)``
    whose crossing ends the simulation (STOPWHEN; the buffer by number or by name, see
    :func:`mechfem.model.stopping.stop_buffer`).
    """

    steps: int
    inputs: Mapping[InputKey, InputMotion]
    dt: float = 1.0
    accuracy: float | None = None
    max_iter: int | None = None
    rtol: float | None = None
    atol: float | None = None
    integrator: str = "auto"
    stop_when: tuple[int | str, float] | None = None

    def __post_init__(self) -> None:
        if int(self.steps) != self.steps or self.steps < 1:
            raise ValueError(f"a motion needs at least one step, got {self.steps!r}")
        if self.steps > MAX_STEPS:
            raise ValueError(f"a motion has at most {MAX_STEPS} steps, got {self.steps!r}: use fewer, longer steps")
        if not self.dt > 0:
            raise ValueError(f"the time per step must be positive, got {self.dt!r}")
        if not np.isfinite(self.steps * float(self.dt)):
            raise ValueError(
                f"{self.steps} steps of dt = {self.dt!r} last longer than the largest time a number can hold: give a "
                "shorter dt (steps * dt must stay below about 1.8e308)"
            )
        if self.max_iter is not None and not 1 <= self.max_iter <= MAX_ITER:
            raise ValueError(f"max_iter must be from 1 to {MAX_ITER}, got {self.max_iter!r}")
        for key, im in self.inputs.items():
            if isinstance(im, Table) and len(np.asarray(im.values)) != self.steps + 1:
                raise ValueError(
                    f"the table of {'the input' if key is None else f'input {key!r}'} has "
                    f"{len(np.asarray(im.values))} values; {self.steps} steps "
                    f"make {self.steps + 1} positions"
                )
        if self.simulated:
            free = [key for key, im in self.inputs.items() if isinstance(im, Free)]
            if free:
                raise ValueError(
                    f"input {free[0]!r} has free motion (Free), which has no timing and cannot be simulated: drive it "
                    "with By, To or Table, or let it move under the forces with Dynamic"
                )
        elif self.rtol is not None or self.atol is not None:
            raise ValueError(
                "rtol and atol are the tolerances of a simulation's integrator: give them to a motion in which an "
                "input moves under the forces (Dynamic, Motion.dynamic or Mechanism.simulate)"
            )
        elif self.integrator != "auto" or self.stop_when is not None:
            raise ValueError(
                "integrator and stop_when set how a simulation is integrated and where it ends: give them to a motion "
                "in which an input moves under the forces (Dynamic, Motion.dynamic or Mechanism.simulate)"
            )
        check_integrator(self.integrator)
        if self.stop_when is not None:
            check_stop_when(self.stop_when)
        for what, tol in (("rtol", self.rtol), ("atol", self.atol)):
            if tol is not None and not finite(tol, what) > 0:
                raise ValueError(f"{what} must be positive, got {tol!r}")

    @property
    def simulated(self) -> bool:
        """True when an input moves under the forces (:class:`Dynamic`): the run simulates (``DYN SIM``)."""
        return any(isinstance(im, Dynamic) for im in self.inputs.values())

    @staticmethod
    def _per_input(
        value: float | Mapping[InputKey, float], make: Callable[[float, Unit | None], InputMotion], unit: Unit | None
    ) -> dict[InputKey, InputMotion]:
        check_unit(unit)
        if isinstance(value, Mapping):
            return {k: make(finite(v, "a motion value"), unit) for k, v in value.items()}
        return {None: make(finite(value, "a motion value"), unit)}

    @classmethod
    def by(
        cls,
        steps: int,
        delta: float | Mapping[InputKey, float],
        dt: float = 1.0,
        *,
        unit: Unit | None = None,
        accuracy: float | None = None,
        max_iter: int | None = None,
    ) -> Motion:
        """Equidistant steps changing the input by ``delta`` (a mapping for several inputs); an angle in ``unit``
        (``"rad"``, the default, or ``"deg"``: ``Motion.by(72, 360, unit="deg")`` is one turn)."""
        return cls(steps, cls._per_input(delta, By, unit), dt, accuracy, max_iter)

    @classmethod
    def to(
        cls,
        steps: int,
        end: float | Mapping[InputKey, float],
        dt: float = 1.0,
        *,
        unit: Unit | None = None,
        accuracy: float | None = None,
        max_iter: int | None = None,
    ) -> Motion:
        """Equidistant steps from position 1 to ``end`` (a mapping for several inputs); an angle in ``unit``
        (``"rad"``, the default, or ``"deg"``)."""
        return cls(steps, cls._per_input(end, To, unit), dt, accuracy, max_iter)

    @classmethod
    def free(
        cls,
        steps: int,
        ds: float,
        dt: float = 1.0,
        *,
        accuracy: float | None = None,
        max_iter: int | None = None,
    ) -> Motion:
        """Free motion of a one-input mechanism: ``steps`` steps of length ``ds`` in co-ordinate space (lengths and
        angles together, so ``ds`` has no unit; its sign sets the direction the input starts in)."""
        return cls(steps, {None: Free(finite(ds, "ds"))}, dt, accuracy, max_iter)

    @classmethod
    def table(
        cls,
        values: npt.ArrayLike | Mapping[InputKey, npt.ArrayLike],
        velocities: npt.ArrayLike | Mapping[InputKey, npt.ArrayLike] | None = None,
        accelerations: npt.ArrayLike | Mapping[InputKey, npt.ArrayLike] | None = None,
        time: npt.ArrayLike | None = None,
        dt: float = 1.0,
        *,
        unit: Unit | None = None,
        accuracy: float | None = None,
        max_iter: int | None = None,
    ) -> Motion:
        """The inputs' values at every position (one array per input; a mapping for several inputs),
        optionally with velocities and accelerations (for velocity and acceleration results) and times; an
        angle's values in ``unit`` (``"rad"``, the default, or ``"deg"``)."""

        def per(a: object) -> dict[InputKey, FloatArray | None]:
            if a is None:
                return {}
            if isinstance(a, Mapping):
                return {k: np.asarray(v, dtype=np.float64) for k, v in a.items()}
            return {None: np.asarray(a, dtype=np.float64)}

        vals, vels, accs = per(values), per(velocities), per(accelerations)
        t = None if time is None else np.asarray(time, dtype=np.float64)
        if not vals:
            raise ValueError("a motion table needs values")
        lengths = {len(v) for v in vals.values() if v is not None}
        if len(lengths) != 1:
            raise ValueError(f"every input needs the same number of values, got {sorted(lengths)}")
        n = lengths.pop()
        inputs: dict[InputKey, InputMotion] = {}
        for key, v in vals.items():
            assert v is not None
            inputs[key] = Table(v, vels.get(key), accs.get(key), t, unit=check_unit(unit))
        return cls(n - 1, inputs, dt, accuracy, max_iter)

    @classmethod
    def dynamic(
        cls,
        t_end: float,
        steps: int,
        v0: float | Mapping[InputKey, float] = 0.0,
        *,
        drive: Mapping[InputKey, By | To | Table] | None = None,
        rtol: float | None = None,
        atol: float | None = None,
        accuracy: float | None = None,
        max_iter: int | None = None,
        unit: Unit | None = None,
        integrator: str = "auto",
        stop_when: tuple[int | str, float] | None = None,
    ) -> Motion:
        """A simulation from time 0 to ``t_end`` in ``steps`` output steps (``dt = t_end / steps``): the inputs
        of ``v0`` (a number: the only input; a mapping for several) move under the forces from those speeds (an
        angle's in ``unit`` per time, ``"rad"`` or ``"deg"``), the inputs of ``drive`` follow their motion.
        :meth:`Mechanism.simulate` fills in the inputs left out. ``integrator`` and ``stop_when`` are
        :class:`Motion`'s."""
        dt = _step(t_end, steps)
        inputs: dict[InputKey, InputMotion] = cls._per_input(v0, Dynamic, unit)
        for key, im in (drive or {}).items():
            if key in inputs:
                raise ValueError(f"input {key!r} is given a speed in v0 and a motion in drive: it can have only one")
            inputs[key] = _driven(key, im)
        return cls(steps, inputs, dt, accuracy, max_iter, rtol, atol, integrator, stop_when)


INTEGRATORS = ("auto", "explicit", "implicit", "dop853", "dopri5", "radau5")
"""The integration methods of a simulation (deck INTEGRATOR): ``auto`` (the default) integrates with
Dormand-Prince 5(4) and goes over to the implicit Radau IIA 5 where the motion is stiff, ``explicit`` (=
``dopri5``) and ``dop853`` (Dormand-Prince of order 8) never do, ``implicit`` (= ``radau5``) always does."""


def check_integrator(integrator: object) -> str:
    """``integrator`` if it is one of :data:`INTEGRATORS`; a ValueError naming them otherwise."""
    if not isinstance(integrator, str) or integrator not in INTEGRATORS:
        raise ValueError(
            f"integrator {integrator!r} is not an integration method: give one of {', '.join(INTEGRATORS)} "
            "('auto', the default, switches between the explicit dopri5 and the implicit radau5 as the motion needs)"
        )
    return integrator


def check_stop_when(stop_when: object) -> tuple[int | str, float]:
    """``stop_when`` as ``(buffer, value)``: a buffer number or name and a finite value; a ValueError otherwise."""
    if not (isinstance(stop_when, tuple) and len(stop_when) == 2):
        raise ValueError(
            f"stop_when is a (buffer, value) pair, e.g. ('omega', 0.0), got {stop_when!r}: the buffer by its number or "
            "by the name of the one quantity it holds, the value in the mechanism's own units"
        )
    buffer, value = stop_when
    if isinstance(buffer, bool) or not isinstance(buffer, (int, str)) or (isinstance(buffer, int) and buffer < 1):
        raise ValueError(f"the buffer of stop_when is a buffer number (1 up) or a name, got {buffer!r}")
    return buffer, finite(value, "the value of stop_when")


def _step(t_end: float, steps: int) -> float:
    """``t_end / steps``, the time of an output step, for a positive ``t_end`` and at least one step."""
    end = finite(t_end, "t_end")
    if not end > 0:
        raise ValueError(f"a simulation runs from time 0 to t_end > 0, got t_end = {t_end!r}")
    if int(steps) != steps or steps < 1:
        raise ValueError(f"a simulation needs at least one output step, got steps = {steps!r}")
    return end / steps


def _driven(key: InputKey, im: object) -> InputMotion:
    """A prescribed motion of ``drive``; a number, free motion or :class:`Dynamic` there is refused."""
    if isinstance(im, By | To | Table):
        return im
    name = getattr(key, "name", key)
    if isinstance(im, Dynamic):
        raise TypeError(
            f"drive gives input {name!r} the motion {im!r}: drive holds prescribed motions (By, To, Table); leave an "
            "input that moves under the forces out of drive and give its speed in v0"
        )
    if isinstance(im, Free):
        raise TypeError(f"drive gives input {name!r} free motion, which has no timing: give it By, To or Table")
    raise TypeError(f"drive gives input {name!r} {im!r}; expected By(delta), To(end) or Table(...)")


def input_dof(key: InputKey, inputs: Sequence[Row]) -> int:
    """The DOF number (1-based) of the input ``key`` among the input rows ``inputs`` (DOF order): by name, DOF
    number, row or the form parameter it holds; None for the only input."""
    if key is None:
        if not inputs:
            raise ValueError(
                "the mechanism has no inputs: make a form parameter an input with Driven() (e.g. angle=Driven()) or "
                "Mechanism.drive"
            )
        if len(inputs) != 1:
            names = ", ".join(repr(r.name) for r in inputs)
            raise ValueError(f"the mechanism has {len(inputs)} inputs ({names}): name the one meant")
        return 1
    if isinstance(key, bool):
        raise TypeError(f"not an input: {key!r}")
    if isinstance(key, int):
        if not 1 <= key <= len(inputs):
            names = ", ".join(f"{j} ({r.name})" for j, r in enumerate(inputs, 1)) or "none"
            raise ValueError(f"the mechanism has no input number {key}; its inputs are {names}")
        return key
    for j, r in enumerate(inputs, 1):
        if key is r or r.name == key or r.terms == ((1.0, key),):
            return j
    name = getattr(key, "label", getattr(key, "name", key))
    raise unknown_name("input", name, [r.name for r in inputs])


def check_units(motion: Motion, inputs: Sequence[Row], angle: str = "rad") -> bool:
    """Refuses degrees for an input that is not an angle, and warns with :class:`~mechfem.errors.UnitWarning` when
    a motion given without a unit changes an angle input of a model in radians (``angle``: the model's angle unit)
    by more than :data:`~mechfem.model.units.LARGE_ANGLE` radians (``inputs``: the input rows in DOF order), when a step
    or an end of a model in degrees looks like radians, and when an angle input's start value looks like the other
    unit (:func:`~mechfem.model.units.wrong_angle_unit`, the deck reader's test). True when it had nothing to say."""
    quiet = True
    for row in inputs:
        why = None if row.value is None or not row.is_angle else wrong_angle_unit(row.value, angle)
        if why is not None:
            words = "degrees" if angle == "deg" else "radians"
            quiet = False
            warnings.warn(
                f"the start value {row.value:g} of the angle input {row.name!r} is in {words}, the model's angle "
                f"unit, but {why}: give it in {words}, or give the model the other angle unit "
                "(Mechanism(..., angle=...))",
                UnitWarning,
                stacklevel=user_stacklevel(),
            )
    for key, im in motion.inputs.items():
        row = inputs[input_dof(key, inputs) - 1]
        unit = getattr(im, "unit", None)
        if unit == "deg" and not row.is_angle:
            raise ValueError(
                f"the motion gives the input {row.name!r} in degrees (unit='deg'), but it is not an angle "
                f"({row.formula()}): give its motion in its own unit, without unit='deg'"
            )
        if unit is None and row.is_angle and angle == "deg" and isinstance(im, By | To):
            value = im.delta if isinstance(im, By) else im.end
            why = wrong_angle_unit(value, angle)
            if why is not None:
                what = "step" if isinstance(im, By) else "end"
                quiet = False
                warnings.warn(
                    f"the motion's {what} {value:g} of the angle input {row.name!r} is in degrees, the model's angle "
                    f"unit, but {why}: give it in degrees, or say unit='rad'",
                    UnitWarning,
                    stacklevel=user_stacklevel(),
                )
        change = 0.0 if unit is not None or not row.is_angle or angle != "rad" else _change(im, row.value)
        if change > LARGE_ANGLE:
            quiet = False
            warnings.warn(
                f"the motion changes the angle input {row.name!r} by {change:.6g} rad ({change / (2 * np.pi):.3g} "
                "turns): if degrees were meant, say so with unit='deg' (as in Motion.by(steps, 360, unit='deg')); "
                "unit='rad' says that radians are meant and silences this warning",
                UnitWarning,
                stacklevel=user_stacklevel(),
            )
    return quiet


def _change(im: InputMotion, start: float | None) -> float:
    """How far a motion given without a unit moves its input (from ``start``, or 0 when it is not given)."""
    if isinstance(im, By):
        return abs(im.delta)
    if isinstance(im, To):
        return abs(im.end - (start or 0.0))
    if isinstance(im, Table):
        v = np.asarray(im.values, dtype=np.float64)
        return float(np.nanmax(np.abs(v - v[0]))) if v.size else 0.0
    return 0.0


def simulation(
    mech: MechanismInputs,
    t_end: float,
    steps: int,
    v0: float | Mapping[InputKey, float] | None,
    drive: Mapping[InputKey, By | To | Table] | None,
    *,
    rtol: float | None = None,
    atol: float | None = None,
    accuracy: float | None = None,
    max_iter: int | None = None,
    unit: Unit | None = None,
    integrator: str = "auto",
    stop_when: tuple[int | str, float] | None = None,
) -> Motion:
    """The motion of :meth:`Mechanism.simulate` for ``mech``: the inputs of ``drive`` follow their motion, every
    other one moves under the forces from its speed in ``v0`` (a number for the only such input, a mapping by
    input, None: from rest; an angle's in ``unit`` per time); the other arguments are :class:`Motion`'s."""
    dt = _step(t_end, steps)
    mechanism, inputs = mech.name, mech.inputs
    if not inputs:
        raise ValueError(f"the mechanism {mechanism!r} has no inputs: nothing can move under the forces")
    driven: dict[str, InputMotion] = {}
    for key, im in (drive or {}).items():
        row = inputs[input_dof(key, inputs) - 1]
        if row.name in driven:
            raise ValueError(f"drive gives input {row.name!r} two motions (as {key!r} and before)")
        driven[row.name] = _driven(row.name, im)
    free = [r for r in inputs if r.name not in driven]
    if not free:
        names = ", ".join(repr(r.name) for r in inputs)
        raise ValueError(
            f"drive prescribes every input of {mechanism!r} ({names}), so nothing moves under the forces: leave out "
            "of drive the inputs to simulate, or use Mechanism.run for inverse dynamics"
        )
    speeds: dict[str, float] = {}
    if isinstance(v0, Mapping):
        for key, v in v0.items():
            row = inputs[input_dof(key, inputs) - 1]
            if row.name in driven:
                raise ValueError(
                    f"v0 gives a speed to input {row.name!r}, which drive prescribes: its speed follows from its "
                    "motion; give v0 for the inputs that move under the forces only "
                    f"({', '.join(repr(r.name) for r in free)})"
                )
            speeds[row.name] = finite(v, f"the initial speed v0 of input {row.name!r}")
    elif v0 is not None:
        if len(free) != 1:
            raise ValueError(
                f"v0 = {v0!r} is one speed, but {len(free)} inputs of {mechanism!r} move under the forces "
                f"({', '.join(repr(r.name) for r in free)}): give v0 as a mapping from input name to speed"
            )
        speeds[free[0].name] = finite(v0, f"the initial speed v0 of input {free[0].name!r}")
    inputs_motion: dict[InputKey, InputMotion] = {
        r.name: driven[r.name] if r.name in driven else Dynamic(speeds.get(r.name, 0.0), check_unit(unit))
        for r in inputs
    }
    return Motion(steps, inputs_motion, dt, accuracy, max_iter, rtol, atol, integrator, stop_when)
