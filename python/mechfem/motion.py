"""The input motion of a :class:`~mechfem.Mechanism`: steps, and per input how it moves.

:class:`Motion` is the MOVEMENT block of a deck: ``steps`` steps of ``dt`` each, and per input
:class:`By` (MOV_RELE), :class:`To` (MOV_ABSE), :class:`Free` (MOV_FREE), :class:`Table` (MOV_FUNC) or
:class:`Dynamic` (MOV_DYN: the input moves under the forces, and the deck simulates, mode ``DYN SIM``).
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, TypeAlias, Union

import numpy as np
import numpy.typing as npt

from mechfem.checks import finite

if TYPE_CHECKING:
    from mechfem.model import FormParameter, Mechanism, Row

FloatArray = npt.NDArray[np.float64]

MAX_ITER = 1000
"""The most Newton iterations per position a motion may allow (MAXITER of the deck reader)."""


@dataclass(frozen=True)
class By:
    """Equidistant steps that change the input by ``delta`` in total (MOV_RELE)."""

    delta: float


@dataclass(frozen=True)
class To:
    """Equidistant steps from the input's value at position 1 to ``end`` (MOV_ABSE)."""

    end: float


@dataclass(frozen=True)
class Free:
    """Free motion through limit positions with step ``ds`` in co-ordinate space (MOV_FREE; one input only)."""

    ds: float


@dataclass(frozen=True, eq=False)
class Table:
    """The input's value (and velocity, acceleration) at every position (MOV_FUNC).

    ``time`` defaults to ``k * dt``, velocities and accelerations to 0. ``file`` is the file name a
    deck written by :meth:`Mechanism.save_deck` uses for it.
    """

    values: FloatArray
    velocities: FloatArray | None = None
    accelerations: FloatArray | None = None
    time: FloatArray | None = None
    file: str | None = None

    def rows(self, dt: float) -> FloatArray:
        """The four columns ``t value velocity acceleration``, one row per position."""
        v = np.asarray(self.values, dtype=np.float64)
        n = v.shape[0]

        def column(a: npt.ArrayLike | None, default: FloatArray) -> FloatArray:
            if a is None:
                return default
            out = np.asarray(a, dtype=np.float64)
            if out.shape != (n,):
                raise ValueError(f"a motion table needs {n} values per column, one per position, got {out.shape}")
            return out

        zero = np.zeros(n)
        t = column(self.time, dt * np.arange(n, dtype=np.float64))
        return np.column_stack([t, v, column(self.velocities, zero), column(self.accelerations, zero)])


@dataclass(frozen=True)
class Dynamic:
    """The input moves under the forces, starting with the speed ``v0`` (MOV_DYN): the run is a simulation (mode
    ``DYN SIM``), which needs masses (:meth:`Mechanism.mass`, ...)."""

    v0: float = 0.0


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
    and ``atol`` are the tolerances of a simulation's integrator (INTTOL; each defaults to ACCURACY).
    """

    steps: int
    inputs: Mapping[InputKey, InputMotion]
    dt: float = 1.0
    accuracy: float | None = None
    max_iter: int | None = None
    rtol: float | None = None
    atol: float | None = None

    def __post_init__(self) -> None:
        if int(self.steps) != self.steps or self.steps < 1:
            raise ValueError(f"a motion needs at least one step, got {self.steps!r}")
        if not self.dt > 0:
            raise ValueError(f"the time per step must be positive, got {self.dt!r}")
        if self.max_iter is not None and not 1 <= self.max_iter <= MAX_ITER:
            raise ValueError(f"max_iter must be from 1 to {MAX_ITER} (as MAXITER in a deck), got {self.max_iter!r}")
        for key, im in self.inputs.items():
            if isinstance(im, Table) and len(np.asarray(im.values)) != self.steps + 1:
                raise ValueError(
                    f"the table of input {key!r} has {len(np.asarray(im.values))} values; {self.steps} steps "
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
        for what, tol in (("rtol", self.rtol), ("atol", self.atol)):
            if tol is not None and not finite(tol, what) > 0:
                raise ValueError(f"{what} must be positive (as in INTTOL), got {tol!r}")

    @property
    def simulated(self) -> bool:
        """True when an input moves under the forces (:class:`Dynamic`): the run simulates (``DYN SIM``)."""
        return any(isinstance(im, Dynamic) for im in self.inputs.values())

    @staticmethod
    def _per_input(
        value: float | Mapping[InputKey, float], make: Callable[[float], InputMotion]
    ) -> dict[InputKey, InputMotion]:
        if isinstance(value, Mapping):
            return {k: make(finite(v, "a motion value")) for k, v in value.items()}
        return {None: make(finite(value, "a motion value"))}

    @classmethod
    def by(
        cls,
        steps: int,
        delta: float | Mapping[InputKey, float],
        dt: float = 1.0,
        *,
        accuracy: float | None = None,
        max_iter: int | None = None,
    ) -> Motion:
        """Equidistant steps changing the input by ``delta`` (a mapping for several inputs)."""
        return cls(steps, cls._per_input(delta, By), dt, accuracy, max_iter)

    @classmethod
    def to(
        cls,
        steps: int,
        end: float | Mapping[InputKey, float],
        dt: float = 1.0,
        *,
        accuracy: float | None = None,
        max_iter: int | None = None,
    ) -> Motion:
        """Equidistant steps from position 1 to ``end`` (a mapping for several inputs)."""
        return cls(steps, cls._per_input(end, To), dt, accuracy, max_iter)

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
        """Free motion of a one-input mechanism: ``steps`` steps of length ``ds`` in co-ordinate space."""
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
        accuracy: float | None = None,
        max_iter: int | None = None,
    ) -> Motion:
        """The inputs' values at every position (one array per input; a mapping for several inputs),
        optionally with velocities and accelerations (for velocity and acceleration results) and times."""

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
            inputs[key] = Table(v, vels.get(key), accs.get(key), t)
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
    ) -> Motion:
        """A simulation from time 0 to ``t_end`` in ``steps`` output steps (``dt = t_end / steps``): the inputs
        of ``v0`` (a number: the only input; a mapping for several) move under the forces from those speeds, the
        inputs of ``drive`` follow their motion. :meth:`Mechanism.simulate` fills in the inputs left out."""
        dt = _step(t_end, steps)
        inputs: dict[InputKey, InputMotion] = cls._per_input(v0, Dynamic)
        for key, im in (drive or {}).items():
            if key in inputs:
                raise ValueError(f"input {key!r} is given a speed in v0 and a motion in drive: it can have only one")
            inputs[key] = _driven(key, im)
        return cls(steps, inputs, dt, accuracy, max_iter, rtol, atol)


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
        if len(inputs) != 1:
            names = ", ".join(repr(r.name) for r in inputs) or "none"
            raise ValueError(f"the mechanism has {len(inputs)} inputs ({names}): say which one")
        return 1
    if isinstance(key, bool):
        raise TypeError(f"not an input: {key!r}")
    if isinstance(key, int):
        if not 1 <= key <= len(inputs):
            raise ValueError(f"input number {key} is out of range 1..{len(inputs)}")
        return key
    for j, r in enumerate(inputs, 1):
        if key is r or r.name == key or r.terms == ((1.0, key),):
            return j
    names = ", ".join(repr(r.name) for r in inputs) or "none"
    raise KeyError(f"{key!r} is not an input; the inputs are {names}")


def simulation(
    mech: Mechanism,
    t_end: float,
    steps: int,
    v0: float | Mapping[InputKey, float] | None,
    drive: Mapping[InputKey, By | To | Table] | None,
    *,
    rtol: float | None = None,
    atol: float | None = None,
    accuracy: float | None = None,
    max_iter: int | None = None,
) -> Motion:
    """The motion of :meth:`Mechanism.simulate` for ``mech``: the inputs of ``drive`` follow their motion, every
    other one moves under the forces from its speed in ``v0`` (a number for the only such input, a mapping by
    input, None: from rest); the other arguments are :class:`Motion`'s."""
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
        r.name: driven[r.name] if r.name in driven else Dynamic(speeds.get(r.name, 0.0)) for r in inputs
    }
    return Motion(steps, inputs_motion, dt, accuracy, max_iter, rtol, atol)
