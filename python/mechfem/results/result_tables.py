"""The values of a :class:`~mechfem.RunResult`: its table of columns, read by block name, and the quantities a
user asks for by name (values, transfer functions, velocities, accelerations, inverse dynamics, named tables).

A run's table has one column per quantity and a layout naming its blocks (``mechfem_core::run::Layout``): a named
model's run records every block (``kx1``: d x_i / d input_j of every co-ordinate i and input j, ``e0`` every
row's value, ...), a deck's run only the block ``buffers`` (its STORAGE block's buffers, in deck order) and those
its outputs need. A quantity is found in its block when the run recorded the block, else in the buffer that
records it; a deck's run that recorded neither says which BUF line would.
"""

from __future__ import annotations

import functools
import math
import os
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any, NamedTuple, Protocol, cast

import numpy as np
import numpy.typing as npt

import mechfem._core as _core
from mechfem._util import optional
from mechfem.model.catalogue import coordinate_dimensions, form_dimension
from mechfem.model.echo import BUFFER_ARGS, EchoStorage, Model, ModelNames
from mechfem.model.units import Units, check_output_unit, kind_of, scale
from mechfem.results import designer
from mechfem.results.run_report import RunReport
from mechfem.results.words import Words

FloatArray = npt.NDArray[np.float64]


class NameTarget(NamedTuple):
    """What a name stands for, in deck numbers."""

    kind: str
    """``point``, ``coordinate`` or ``row``."""
    numbers: tuple[int, ...]
    """A point's co-ordinates (x, y), a co-ordinate's number, or a row's signed destination (``-k``: output k)."""
    name: str
    """Its name, for messages."""
    angle: bool
    """True for an angle (a co-ordinate or row whose unit is the radian)."""


class NotRecordedError(KeyError):
    """A quantity a deck's run did not record. A ``KeyError`` whose ``str()`` is the message itself."""

    def __str__(self) -> str:
        return str(self.args[0]) if self.args else ""


class NotOfKindError(ValueError):
    """``unit=`` of a kind (an angle, a length) that neither a quantity nor an input it is differentiated by is."""


class Energy(NamedTuple):
    """Energies at every position: ``kinetic`` T, ``potential`` V (gravity and springs) and ``total`` T + V."""

    kinetic: FloatArray
    potential: FloatArray
    total: FloatArray


#: The block of the full layout that holds each buffer keyword's quantity (``x0``: the co-ordinates, kept beside
#: the table).
BLOCK_OF: dict[str, str] = {
    "BUFINP": "inputs",
    "BUFTIME": "time",
    "BUFX0": "x0",
    "BUFKX1": "kx1",
    "BUFKX2": "kx2",
    "BUFVX": "vx",
    "BUFAX": "ax",
    "BUFE0": "e0",
    "BUFKE1": "ke1",
    "BUFKE2": "ke2",
    "BUFVE": "ve",
    "BUFAE": "ae",
    "BUFDET": "det",
    "BUFSIG": "sigma",
    "BUFDRV": "drive",
    "BUFREA": "reaction",
    "BUFEKIN": "ekin",
    "BUFEPOT": "epot",
    "BUFPOW": "power",
    "BUFMRED": "mass",
    "BUFTRA": "transmission",
    "BUFPIN": "pin",
    "BUFSHAKE": "shaking",
}
KEYWORD_OF = {b: k for k, b in BLOCK_OF.items()}
#: The argument kinds of each block's index, as its buffer keyword takes them: ``i`` a co-ordinate, ``r`` a row, ``j``
#: an input (a buffer's second input, ``m``, is one too).
INDEX_KINDS = {BLOCK_OF[kw]: kinds.replace("m", "j") for kw, kinds in BUFFER_ARGS.items()}


class Names(Protocol):
    """How a result resolves what a user names (:mod:`mechfem.run.namespace` builds one)."""

    @property
    def mechanism(self) -> Any:
        """The :class:`~mechfem.Mechanism` the names belong to (for a deck, the one its topology makes)."""

    @property
    def numbering(self) -> Any:
        """Its :class:`~mechfem.deck.naming.Numbering`: the deck numbers of its parts."""

    @property
    def named(self) -> bool:
        """True for a named model's own names, False for those of a deck."""

    def target(self, ref: object, what: str, kinds: tuple[str, ...]) -> NameTarget:
        """The point, co-ordinate or row ``ref`` names (of ``kinds``), in deck numbers."""

    def dof(self, key: object) -> int:
        """The DOF number (1-based) of an input."""

    def input(self, j: int) -> NameTarget:
        """The row of input ``j`` (0-based DOF)."""

    def coordinate(self, i: int) -> NameTarget:
        """Co-ordinate ``i`` (its deck number)."""

    def words(self, report: RunReport) -> Words:
        """The words to say ``report``'s stop reason and warnings with."""

    def model_names(self) -> ModelNames | None:
        """The names the labels of pictures and tables use (None: the deck's numbers)."""

    def traced(self, names: Sequence[str] | None) -> list[Any]:
        """The points whose paths pictures trace: those called ``names``, or every moving point."""

    def columns(self, coordinates: bool) -> tuple[list[Any], list[Any], list[Any]]:
        """The inputs, outputs and (with ``coordinates``) moving co-ordinates :meth:`RunResult.table` lists."""


class ResultTables:
    """The value part of :class:`~mechfem.RunResult` (see there); ``_raw`` is the compiled module's run, whose
    arrays are made when first asked for."""

    coords: FloatArray
    _raw: _core.Run

    def __init__(self, raw: _core.Run) -> None:
        self._layout: Mapping[str, tuple[int, Sequence[int]]] = raw.layout

    @functools.cached_property
    def _table(self) -> FloatArray:
        """The run's table: positions x the columns of ``_layout``."""
        return self._raw.table

    def _column(self, c: int) -> FloatArray:
        """Column ``c`` of the table at every position: a view of the table once it is made (``table()``,
        ``to_pandas()``), else that column alone, made from the run's record and kept. A value or a plot of a few
        quantities of a long run does not make the table's every column."""
        if "_table" in self.__dict__:
            return self._table[:, c]
        made: dict[int, FloatArray] = self.__dict__.setdefault("_columns_made", {})
        column = made.get(c)
        if column is None:
            column = made[c] = self._raw.column(c)
        return column

    # -- what the result class gives

    @property
    def _names(self) -> Names:
        raise NotImplementedError

    @property
    def model(self) -> Model:
        raise NotImplementedError

    @property
    def storage(self) -> EchoStorage:
        raise NotImplementedError

    @property
    def named(self) -> bool:
        raise NotImplementedError

    @property
    def path(self) -> str:
        raise NotImplementedError

    # -- names

    def _target(self, ref: object, what: str, kinds: tuple[str, ...]) -> NameTarget:
        return self._names.target(ref, what, kinds)

    def _dof(self, wrt: object) -> int:
        """The 0-based index of the input ``wrt`` names."""
        return self._names.dof(wrt) - 1

    def _dynamic_needed(self, what: str) -> None:
        if "drive" in self._layout:
            return
        if self.named:
            raise ValueError(
                f"the mechanism {self._names.mechanism.name!r} has no masses or loads, so its run computed no {what}: "
                "give them with Mechanism.mass, point_mass, inertia, gravity, force, load, load_table, spring or motor"
            )
        raise ValueError(
            f"the deck {self.path} is a {self.model.mode} deck, so its run computed no {what}: give it a DYNAMICS "
            "block and the mode DYN ANA"
        )

    # -- the table

    def _block(self, name: str) -> FloatArray:
        """The layout's block ``name`` at every position: positions x its shape (a view of the table once it is
        made, else of its columns made alone)."""
        start, shape = self._layout[name]
        width = math.prod(shape)
        if "_table" in self.__dict__:
            return self._table[:, start : start + width].reshape(self._table.shape[0], *shape)
        columns = [self._column(start + k) for k in range(width)]
        positions = len(columns[0]) if columns else self._raw.positions
        return np.column_stack(columns).reshape(positions, *shape) if columns else np.empty((positions, *shape))

    @functools.cached_property
    def _recorded(self) -> dict[tuple[object, ...], int]:
        """The table column of each quantity a deck's buffer (or hodograph) records, by (block, 0-based index)."""
        out: dict[tuple[object, ...], int] = {}
        if "buffers" in self._layout:
            column = self._columns("buffers", "buffer_numbers")
            for b in self.storage.buffers:
                if b.keyword == "BUFTOL":
                    continue  # a tolerance band, no quantity of a block
                block = BLOCK_OF[b.keyword]
                kinds = INDEX_KINDS.get(block, "")
                args = list(b.args) + ([b.args[-1]] if len(b.args) < len(kinds) else [])
                index = tuple(self._index(k, a) for k, a in zip(kinds, args, strict=False))
                out.setdefault((block, *index), column[b.number])
        if "hodograph" in self._layout:
            for i, c in self._columns("hodograph", "hodograph_coords").items():
                out.setdefault(("kx1", i - 1, 0), c)
        return out

    def _columns(self, block: str, numbers: str) -> dict[int, int]:
        """The table column of each entry of a deck's ``block`` (``buffers``, ``hodograph``), by the number the
        list ``numbers`` of the run gives it (a buffer's, a co-ordinate's)."""
        start = self._layout[block][0]
        listed: list[int] = getattr(self._raw, numbers)
        return {n: start + k for k, n in enumerate(listed)}

    def _index(self, kind: str, number: int) -> int:
        """The 0-based index in a block of a deck number of ``kind`` (a row's: prescribed rows, then outputs)."""
        if kind == "r" and number < 0:
            return len(self.model.prescribed) - number - 1
        return number - 1

    def _series(self, block: str, *index: int) -> FloatArray:
        """Quantity ``index`` (0-based) of ``block`` at every position: a view of the table."""
        if block == "x0":
            return self.coords[:, index[0]]
        where = self._layout.get(block)
        if where is not None and block != "buffers":
            start, shape = where
            column = 0
            for i, n in zip(index, shape, strict=True):  # row-major in the block's shape
                if not 0 <= i < n:
                    raise IndexError(f"index {i} out of range 0..{n - 1} in the block {block!r} of the run's table")
                column = column * n + i
            return self._column(start + column)
        recorded = self._recorded.get((block, *index))
        if recorded is None:
            raise NotRecordedError(self._unrecorded(block, index))
        return self._column(recorded)

    def _unrecorded(self, block: str, index: Sequence[int]) -> str:
        """Why a deck's run has no ``block`` ``index``, and the buffer that would record it."""
        np_ = len(self.model.prescribed)
        numbers = []
        for kind, k in zip(INDEX_KINDS.get(block, ""), index, strict=False):
            numbers.append(str((k + 1 if k < np_ else np_ - k - 1) if kind == "r" else k + 1))
        line = " ".join([KEYWORD_OF[block], *numbers, "<number>"])
        return (
            f"the run of {self.path} did not record {line.replace(' <number>', '')}: a deck's run records what its "
            f"STORAGE block asks for; add the buffer `{line}` there"
        )

    @functools.cached_property
    def buffers(self) -> dict[int, FloatArray]:
        """The deck's own buffers by number (from the storage of the run)."""
        values = self._raw.buffers
        return {n: values[:, k] for k, n in enumerate(self._raw.buffer_numbers)}

    @functools.cached_property
    def kx1(self) -> dict[int, FloatArray]:
        """d x_i / d input 1 at every position by co-ordinate i, for the hodographs (a deck's run: the co-ordinates
        its PLOTHODO lines name; NaN where D^c is singular)."""
        if "hodograph" in self._layout:
            return {i: self._column(c) for i, c in self._columns("hodograph", "hodograph_coords").items()}
        nd = self._layout["kx1"][1][1]
        return {i: self._series("kx1", i - 1, 0) for i in range(1, self.coords.shape[1] + 1)} if nd else {}

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
        if "inputs" in self._layout:
            return self._block("inputs")
        nd = len(self.model.dofs)
        return np.column_stack([self._input(j) for j in range(nd)]) if nd else np.zeros((self.coords.shape[0], 0))

    def _input(self, j: int) -> FloatArray:
        """Input ``j`` (0-based): its block or buffer, else the value of its row."""
        try:
            return self._series("inputs", j)
        except KeyError:
            return self._series("e0", self.model.dofs[j] - 1)

    # -- values by name

    def _of(self, t: NameTarget, coords: str, rows: str, *inputs: int) -> FloatArray:
        """The quantity ``t`` names from block ``coords`` (a point or co-ordinate) or ``rows`` (a row), at the
        input indices ``inputs``: a new array."""
        if t.kind == "row":
            return self._series(rows, self._index("r", t.numbers[0]), *inputs).copy()
        columns = [self._series(coords, i - 1, *inputs) for i in t.numbers]
        return np.column_stack(columns) if t.kind == "point" else columns[0].copy()

    def _any(self, ref: object) -> NameTarget:
        return self._target(ref, "point, co-ordinate, row or output", ("point", "coordinate", "row"))

    def x(self, point: object, unit: str | None = None) -> FloatArray:
        """x of a point at every position (in the length unit ``unit`` when given: ``"mm"``, ``"m"``, ...)."""
        t = self._target(point, "point", ("point",))
        return self._in_unit(self.coords[:, t.numbers[0] - 1].copy(), t, (), unit)

    def y(self, point: object, unit: str | None = None) -> FloatArray:
        """y of a point at every position (in the length unit ``unit`` when given)."""
        t = self._target(point, "point", ("point",))
        return self._in_unit(self.coords[:, t.numbers[1] - 1].copy(), t, (), unit)

    def value(
        self, name: object, order: int = 0, wrt: object = None, wrt2: object = None, unit: str | None = None
    ) -> FloatArray:
        """A point (positions x 2), co-ordinate, row or output at every position (``order`` 0), or its transfer
        function of first (d/d ``wrt``) or second order (d2/d ``wrt`` d ``wrt2``; ``wrt2`` defaults to ``wrt``).
        Numbers are in the model's units (its deck's UNITS, or the :class:`~mechfem.Mechanism`'s); ``unit`` gives
        every angle (``"deg"``, ``"rad"``) or every length (``"mm"``, ``"m"``, ``"cm"``, ``"in"``) in that unit
        instead: an angle's value, and a transfer function per degree of an angle input (d psi / d alpha of two
        angles is the same in either unit)."""
        return self._value(self._any(name), order, wrt, wrt2, unit)

    def _value(self, t: NameTarget, order: int, wrt: object, wrt2: object, unit: str | None) -> FloatArray:
        if order == 0:
            return self._in_unit(self._of(t, "x0", "e0"), t, (), unit)
        j = self._dof(wrt)
        if order == 1:
            return self._in_unit(self._of(t, "kx1", "ke1", j), t, (j,), unit)
        if order == 2:
            m = j if wrt2 is None else self._dof(wrt2)
            return self._in_unit(self._of(t, "kx2", "ke2", j, m), t, (j, m), unit)
        raise ValueError(f"order must be 0, 1 or 2, not {order!r}")

    def _in_unit(self, values: FloatArray, t: NameTarget, dofs: Sequence[int], unit: str | None) -> FloatArray:
        """``values`` of ``t`` differentiated by the inputs ``dofs`` (0-based) with every angle (or length) in
        ``unit``: with ``"deg"`` for a model in radians, an angle's value times 180/pi, divided by 180/pi for each
        angle input it is differentiated by."""
        kind = kind_of(check_output_unit(unit) or "")
        if unit is None or kind is None:
            return values
        if kind not in ("angle", "length"):
            raise ValueError(f"unit={unit!r}: a result is given in another unit of angle or length only")
        source = run_units(self).get(kind)
        if source == unit:
            return values
        of_kind = self._dimension(t) == kind
        power = int(of_kind) - sum(self._dimension(self._names.input(j)) == kind for j in dofs)
        if not of_kind and power == 0:
            raise NotOfKindError(
                f"{t.name!r} is not {'an angle' if kind == 'angle' else 'a length'}, and neither is an input it is "
                f"differentiated by: unit={unit!r} applies to {'angles' if kind == 'angle' else 'lengths'} only"
            )
        if source is None:
            raise ValueError(
                f"unit={unit!r}: the model has no unit of length to convert from; give it one (UNITS LENGTH in its "
                "deck, Mechanism(length=...))"
            )
        return values * scale(source, unit) ** power if power else values

    def _dimension(self, t: NameTarget) -> str:
        """What ``t`` measures: ``angle``, ``length`` or ``ratio`` (a point is a length)."""
        if t.angle:
            return "angle"
        if t.kind == "point":
            return "length"
        model = self.model
        if t.kind == "coordinate":
            return _coordinate_dimensions(model).get(t.numbers[0], "length")
        rows = {r.dest: r for r in [*model.prescribed, *model.dependent]}
        row = rows.get(t.numbers[0])
        if row is None:
            return "ratio"
        dims = set()
        elements = {e.number: e for e in model.elements}
        for term in row.terms:
            e = elements[term.element]
            dim = form_dimension(e.type, term.form)
            dims.add(_coordinate_dimensions(model).get(e.coords[0], "length") if dim == "any" and e.coords else dim)
        return dims.pop() if len(dims) == 1 else "ratio"

    def position(self, name: object, unit: str | None = None) -> FloatArray:
        """The same as ``value(name)``: a point's (x, y), a co-ordinate, a row or an output (an angle in ``unit``,
        ``"rad"`` or ``"deg"``)."""
        return self.value(name, unit=unit)

    def output(
        self, name: object, order: int = 0, wrt: object = None, wrt2: object = None, unit: str | None = None
    ) -> FloatArray:
        """An output (or any row: a prescribed value, an input) and its transfer functions; see :meth:`value`."""
        return self._value(self._target(name, "output or row", ("row",)), order, wrt, wrt2, unit)

    def transfer(
        self, name: object, order: int = 1, wrt: object = None, wrt2: object = None, unit: str | None = None
    ) -> FloatArray:
        """Transfer function of first or second order; see :meth:`value`."""
        if order not in (1, 2):
            raise ValueError(f"a transfer function has order 1 or 2, not {order!r}")
        return self.value(name, order, wrt, wrt2, unit)

    def velocity(self, name: object, unit: str | None = None) -> FloatArray:
        """Velocity (time derivative) of a point (positions x 2), co-ordinate, row or output (an angle's in ``unit``
        per time)."""
        t = self._any(name)
        return self._in_unit(self._of(t, "vx", "ve"), t, (), unit)

    def acceleration(self, name: object, unit: str | None = None) -> FloatArray:
        """Acceleration of a point (positions x 2), co-ordinate, row or output (an angle's in ``unit`` per time
        squared)."""
        t = self._any(name)
        return self._in_unit(self._of(t, "ax", "ae"), t, (), unit)

    def input(self, name: object = None, unit: str | None = None) -> FloatArray:
        """The value of an input at every position (under free motion: where it went), an angle in ``unit``
        (``"rad"``, the default, or ``"deg"``)."""
        j = self._dof(name)
        return self._in_unit(self._input(j).copy(), self._names.input(j), (), unit)

    # -- inverse dynamics

    def drive_torque(self, input: object = None) -> FloatArray:
        """The force or torque the drive of an input delivers at every position (the stress of its row), positive when
        it does positive work as the input increases; ``input`` as ``wrt`` (it may be left out with one input)."""
        self._dynamic_needed("drive torques")
        return self._series("drive", self._dof(input)).copy()

    def stress(self, row: object) -> FloatArray:
        """The generalised stress of a prescribed row (or input): the force or torque its constraint applies in the
        direction of increasing value, e.g. the axial force of a bar of prescribed length, positive when it pushes
        its ends apart."""
        self._dynamic_needed("stresses")
        t = self._target(row, "prescribed value or input", ("row",))
        dest = t.numbers[0]
        if dest < 0:
            raise KeyError(f"{t.name!r} is an output, which carries no stress: only prescribed rows and inputs do")
        return self._series("sigma", dest - 1).copy()

    def reaction(self, point_or_coordinate: object) -> FloatArray:
        """The force the frame applies at a fixed point (positions x 2: x, y) or on one fixed co-ordinate."""
        self._dynamic_needed("reactions")
        t = self._target(point_or_coordinate, "point or co-ordinate", ("point", "coordinate"))
        coords = [(self._names.coordinate(i).name, self.model.coordinates[i - 1].moving) for i in t.numbers]
        moving = [name for name, m in coords if m]
        if moving:
            fixed = [name for name, m in coords if not m]
            hint = f"; ask for the fixed one, reaction({fixed[0]!r})" if fixed else ""
            hint += f"; the force each element exerts on it is pin_forces({t.name!r})" if t.kind == "point" else ""
            raise KeyError(f"{', '.join(moving)} moves: only the frame (fixed co-ordinates) has reactions{hint}")
        out = np.column_stack([self._series("reaction", i - 1) for i in t.numbers])
        return out if t.kind == "point" else out[:, 0].copy()

    def pin_force(self, element: object, point: object) -> FloatArray:
        """The force ``element`` exerts on the pin at ``point`` (positions x 2), see :mod:`mechfem.results.designer`."""
        return designer.pin_force(self, element, point)

    def pin_forces(self, point: object) -> dict[str, FloatArray]:
        """The force each element meeting at ``point`` exerts on it, by element name."""
        return designer.pin_forces(self, point)

    def shaking(self) -> FloatArray:
        """Shaking force x, y and moment about the origin on the frame (positions x 3), inertia only."""
        return designer.shaking(self)

    def transmission_angle(self, first: object, second: object, unit: str | None = None) -> FloatArray:
        """The angle between the first sides of two elements at every position, in [0, pi] (or degrees)."""
        return designer.transmission_angle(self, first, second, unit)

    def energy(self) -> Energy:
        """Kinetic, potential (gravity and springs) and total energy at every position."""
        self._dynamic_needed("energies")
        t, v = self._series("ekin").copy(), self._series("epot").copy()
        return Energy(t, v, t + v)

    def power(self) -> FloatArray:
        """The power the drives deliver at every position (the sum of drive torque times input speed)."""
        self._dynamic_needed("power")
        return self._series("power").copy()

    def mass_matrix(self) -> FloatArray:
        """The mass matrix M(q) in the inputs at every position (positions x D x D; kinetic energy
        ``T = 1/2 qdot^T M qdot``)."""
        self._dynamic_needed("mass matrix")
        if "mass" in self._layout:
            return self._block("mass").copy()
        nd = len(self.model.dofs)
        out = [[self._series("mass", j, m) for m in range(nd)] for j in range(nd)]
        return np.stack([np.stack(row, axis=-1) for row in out], axis=1)

    # -- tables

    def table(self, coordinates: bool = True, unit: str | None = None) -> dict[str, FloatArray]:
        """Every result as named columns: ``time``, ``det``, then each input, output and (with ``coordinates``)
        moving co-ordinate ``q`` as ``q``, ``q'``, ``q''`` (transfer functions; ``q'(a)``, ``q''(a,b)`` with
        several inputs), ``q_dot`` and ``q_ddot`` (velocity, acceleration). A deck's run gives those its buffers
        recorded. Numbers are in the model's units; ``unit`` gives every angle or every length in that unit, as
        for :meth:`value`."""
        return self._table_columns(coordinates, unit)[0]

    def table_units(self, coordinates: bool = True, unit: str | None = None) -> dict[str, str]:
        """The unit of every column of :meth:`table` (``mm``, ``deg``, ``mm/deg``, ``deg/s``, ``N·mm``, ``J``;
        ``-`` for a ratio of one unit; ``""`` where the model gives no unit, e.g. a length without UNITS)."""
        return self._table_columns(coordinates, unit)[1]

    def _table_columns(self, coordinates: bool, unit: str | None) -> tuple[dict[str, FloatArray], dict[str, str]]:
        """:meth:`table` and :meth:`table_units`."""
        from mechfem.results import table_columns

        return table_columns.columns(cast(Any, self), coordinates, unit)

    # -- the report

    def to_html(self) -> str:
        """The interactive report of the run as one self-contained HTML page (the text of the file ``mechfem run
        --report`` writes): the mechanism animated, det(D^c) and the limit positions, every picture and a table of
        the buffers, named and in the model's units."""
        from mechfem.report import html as report
        from mechfem.results.result import RunResult

        return report.render_report(cast(RunResult, self))

    def save_report(self, path: str | os.PathLike[str]) -> Path:
        """Writes :meth:`to_html` to ``path`` (a file; its folder is made if needed), whole or not at all; returns
        the path."""
        from mechfem.report import html as report
        from mechfem.results.result import RunResult

        return report.save_report(cast(RunResult, self), Path(path))

    def to_pandas(self, coordinates: bool = True, unit: str | None = None) -> Any:
        """:meth:`table` as a ``pandas.DataFrame`` indexed by position (1, 2, ...), its columns named as the model
        names its parts (``unit``: as for :meth:`table`), with ``attrs["units"]`` mapping each column to its unit
        (:meth:`table_units`). Needs pandas (``pip install 'mechfem[pandas]'``)."""
        pd = optional.pandas()
        columns, units = self._table_columns(coordinates, unit)
        frame = pd.DataFrame(columns)
        frame.index = pd.RangeIndex(1, self.coords.shape[0] + 1, name="position")
        frame.attrs["units"] = units
        return frame


def _coordinate_dimensions(model: Model) -> dict[int, str]:
    """What each co-ordinate measures, from the first element that uses it (``any``: left to the others)."""
    out: dict[int, str] = {}
    for e in model.elements:
        for i, dim in zip(e.coords, coordinate_dimensions(e.type), strict=False):
            if dim != "any":
                out.setdefault(i, dim)
    return out


def run_units(result: Any) -> Units:
    """The units of a run's numbers: its deck's UNITS (the model echo's), or its named model's."""
    given = getattr(result.model, "units", None)
    if given is not None:
        return Units.of(given)
    if getattr(result, "named", False):
        units = getattr(result.mechanism, "units", None)
        if isinstance(units, Units):
            return units
    return Units()
