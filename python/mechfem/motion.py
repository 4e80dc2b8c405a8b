"""The input motion of a :class:`~mechfem.Mechanism`: steps, and per input how it moves.

:class:`Motion` is the MOVEMENT block of a deck: ``steps`` steps of ``dt`` each, and per input
:class:`By` (MOV_RELE), :class:`To` (MOV_ABSE), :class:`Free` (MOV_FREE) or :class:`Table` (MOV_FUNC).
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import TYPE_CHECKING, TypeAlias, Union

import numpy as np
import numpy.typing as npt

from mechfem.checks import finite

if TYPE_CHECKING:
    from mechfem.model import FormParameter, Row

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


InputMotion: TypeAlias = By | To | Free | Table
InputKey: TypeAlias = Union[str, int, "Row", "FormParameter", None]
"""An input named by its name, its DOF number (1-based), its row or form parameter; None: the only input."""


@dataclass(frozen=True)
class Motion:
    """The input motion: ``steps`` steps (``steps + 1`` positions) of ``dt`` each, and one motion per input.

    Build it with :meth:`by`, :meth:`to`, :meth:`free` or :meth:`table`, or give ``inputs`` (input
    name, DOF number or None for the only input -> :class:`By`, :class:`To`, :class:`Free` or
    :class:`Table`). ``accuracy`` and ``max_iter`` set the Newton tolerance and iteration limit
    (deck keywords ACCURACY, MAXITER; default 1e-10 and 25).
    """

    steps: int
    inputs: Mapping[InputKey, InputMotion]
    dt: float = 1.0
    accuracy: float | None = None
    max_iter: int | None = None

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
