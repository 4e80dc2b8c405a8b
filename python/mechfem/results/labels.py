"""The one naming scheme for every quantity a person reads: data-set headers, print-file tables, picture axes,
legends, the animation's title and the report.

The core decides every name and unit (``_core.Labels``, which a run's model echo carries: crates/mechfem-core's
``names.rs`` and ``units.rs``); this module asks it and puts the answers in the shapes the outputs use. Every
buffer gets a :class:`Label`: its name (the NAMES block's ``BUF`` label, else made from the names of what it
records, ``dpsi/dphi``, ``C.x``, else the deck's numbers, ``dANGB(8)/dinput1``, ``x13``), its unit, its kind and
a sentence in words. The run of a named model (:class:`mechfem.Mechanism`, whose names travel in
:attr:`RunResult.names`) is labelled by the model's own names, handed to the core (``Labels.renamed``).

Units. The core gives each quantity's kind as the exponents of length, angle, mass, force and time, the unit the
model states (``mm/deg``, ``-`` for a quantity over one of its own unit, ``N·mm`` for a torque, ``kg·mm²``; none
without UNITS) and the unit an axis shows (the stated one; without UNITS angles in ``rad`` and time in ``s``, and
nothing where a length, mass or force takes part, since those numbers are in no unit mechfem knows). The kind is
also said in the words of the unit algebra (``length``, ``rad``, ``s``, ``force``, ``torque``, ``energy``,
``power``, ``mass``: :func:`words`), which decide which quantities share an axis and which other modules turn into
a unit with :func:`shown`.
"""

from __future__ import annotations

import re
from collections.abc import Sequence
from dataclasses import dataclass

import mechfem._core as _core
from mechfem.model.echo import Buffer, EchoRow, Model
from mechfem.model.units import Units, joules, kind_of, watts
from mechfem.results.result import RunResult
from mechfem.results.result_tables import run_units

ANGLE = "rad"
LENGTH = "length"
RATIO = ""
TIME = "s"

#: Every kind a label can have.
KINDS = (
    "input",
    "position",
    "first order",
    "second order",
    "velocity",
    "acceleration",
    "time",
    "det",
    "force",
    "energy",
    "power",
    "mass",
)

Dims = Sequence[int]
"""The exponents of length, angle, mass, force and time of a quantity, as the core gives them."""

_BASE = ("length", "rad", "mass", "force", "s")


@dataclass(frozen=True)
class Label:
    """What buffer ``number`` holds, for a person."""

    number: int
    """The buffer number."""
    name: str
    """Its name: ``ANGB(8)``, ``dANGB(8)/dinput1``, ``d2ANGB(8)/dinput1^2``, ``x13``, ``vx13``, ``time``,
    ``det(D^c)``; the deck's names (``dpsi/dphi``, ``C.x``) or a named model's own (``dcoupler.angle/dcrank``)."""
    unit: str
    """The unit an axis shows: the stated one; without UNITS ``rad``, ``rad/s``, ``-`` (``""``: none)."""
    kind: str
    """One of :data:`KINDS`."""
    text: str
    """The words, e.g. ``first-order transfer function of ANGB(8) with respect to input 1``."""
    base: str = ""
    """The unit in the words of the unit algebra (``length/rad``), whatever the model's units: what decides
    whether two quantities share an axis."""
    stated: str = ""
    """The unit the core states for the buffer: the model's units (``mm/deg``, ``-`` for a pure number), "" for a
    model without units or where a kind the quantity needs has no unit."""

    def header(self) -> str:
        """The data-set header cell: the number, the name and, for a model with units, the unit in brackets
        (``101 dpsi/dphi [-]``, ``99 phi [deg]``; ``101 dANGB(8)/dinput1`` without UNITS)."""
        return with_unit(f"{self.number} {self.name}", self.stated)

    def axis(self) -> str:
        """An axis label with the unit: ``dANGB(8)/dinput1 [-]`` (no brackets without a unit)."""
        return with_unit(self.name, self.unit)

    def legend(self) -> str:
        """A legend or table entry: the number, the name and the unit (``101 dANGB(8)/dinput1 [-]``)."""
        return f"{self.number} {self.axis()}"

    @property
    def group(self) -> tuple[str, str]:
        """Which quantities may share one axis (:func:`axis_group`)."""
        return axis_group(self.kind, self.base or self.unit)


def axis_group(kind: str, unit: str) -> tuple[str, str]:
    """Which quantities may share one axis: the same kind (an input counts as a position) and unit."""
    return ("position" if kind == "input" else kind, unit)


# -- units --------------------------------------------------------------------------------------------------------


def over(num: str, den: str) -> str:
    """The unit ``num / den``: ``rad/rad``, ``1/s`` without a numerator, ``num`` without a denominator."""
    if not den:
        return num
    if "·" in den or "/" in den:
        den = f"({den})"
    return f"{num or '1'}/{den}"


def squared(a: str, b: str) -> str:
    """The product of two units: ``rad^2``, ``rad·length``, one of them when the other is none."""
    if not a or not b:
        return a or b
    return f"{a}^2" if a == b else f"{a}·{b}"


def words(dims: Dims, kind: str = "") -> str:
    """The unit of a quantity with exponents ``dims`` in the words of the unit algebra: ``length``, ``rad``,
    ``length/rad``, ``rad/s^2``, ``1/length``; a generalised force on an angle is a ``torque`` (``kind``
    ``force``) and force x length otherwise an ``energy`` (``power`` per second); a pure number is ``""``."""
    length, angle, mass, force, time = dims
    if (length, angle, mass, force) == (1, 0, 0, 1) and time in (0, -1):
        return "power" if time else "torque" if kind == "force" else "energy"

    def part(sign: int) -> str:
        # Force and mass first, as the core writes N·mm and kg·mm².
        out = []
        for k in (3, 2, 0, 1, 4):
            e = dims[k] * sign
            if e > 0:
                out.append(_BASE[k] + (f"^{e}" if e > 1 else ""))
        return "·".join(out)

    num, den = part(1), part(-1)
    return over(num, den) if den else num


def exponents(dims: Dims) -> dict[str, int]:
    """``dims`` as a mapping of the kinds that take part to their exponents (``{"length": 1, "angle": -1}``)."""
    return {k: e for k, e in zip(("length", "angle", "mass", "force", "time"), dims, strict=True) if e}


def _core_labels(model: Model) -> _core.Labels:
    if model.labels is None:
        raise ValueError("this model echo carries no names and units from the core")
    return model.labels


def coordinate_units(model: Model) -> dict[int, str]:
    """The unit of every co-ordinate, in the words of the unit algebra."""
    labels = _core_labels(model)
    return {c.number: words(labels.coordinate(c.number)[3]) for c in model.coordinates}


def row_unit(model: Model, row: EchoRow, coords: dict[int, str] | None = None) -> str:
    """The unit of a (possibly combined) row, in the words of the unit algebra (``coords`` is not needed: the core
    knows the co-ordinates' units)."""
    return words(_core_labels(model).row(row.dest)[3])


def stress_unit(unit: str) -> str:
    """The unit of a generalised force on a quantity of unit ``unit``: force, torque or energy."""
    return {LENGTH: "force", ANGLE: "torque"}.get(unit, "energy")


def _words(units: Units) -> dict[str, str | None]:
    """Each word of the unit algebra in ``units`` (None: the model does not give it)."""
    length, force = units.length, units.force
    moment = None if length is None or force is None else f"{force}·{length}"
    return {
        "length": length,
        "rad": units.angle,
        "s": units.time,
        "force": force,
        "torque": moment,
        "energy": None if moment is None else joules(units.as_dict()) or moment,
        "power": None if moment is None else watts(units.as_dict()) or f"{moment}/{units.time}",
        "mass": units.mass,
    }


_WORD = re.compile(r"[A-Za-z]+")
_RATIO = re.compile(r"^\(?([^()/]+)\)?/\(?([^()/]+)\)?$")


def shown(unit: str, units: Units) -> str:
    """``unit`` (in the words of the unit algebra) in ``units``: ``length/rad`` is ``mm/deg``, ``rad/s^2`` is
    ``deg/s²``; a quantity over one of its own unit is ``-``; "" when a word of it has no unit in ``units``."""
    words = _words(units)
    missing = False

    def word(m: re.Match[str]) -> str:
        nonlocal missing
        w = m.group(0)
        if w not in words:
            return w
        value = words[w]
        if value is None:
            missing = True
            return w
        return value

    out = _WORD.sub(word, unit)
    if missing:
        return ""
    ratio = _RATIO.match(out)
    if ratio is not None and ratio.group(1) == ratio.group(2):
        return "-"
    if ratio is not None and ratio.group(2) == f"{ratio.group(1)}^2":
        return f"1/{ratio.group(1)}"
    # Written as the core writes its units in the data set and the print file: mm/s², kg·mm².
    return out.replace("^2", "²").replace("^3", "³")


# -- names --------------------------------------------------------------------------------------------------------


def compact(formula: str) -> str:
    """A row's formula without spaces: ``ANGB(2)-ANGB(4)``."""
    return formula.replace(" ", "")


_RENAMED: dict[int, tuple[object, object, _core.Labels]] = {}
"""The core's labels of a named model's runs, renamed once per model echo and names (a few kept)."""


def _labels_of(result: RunResult) -> _core.Labels:
    """The core's labels of ``result``, with a named model's own names."""
    model, names = result.model, result.names
    labels = _core_labels(model)
    if names is None:
        return labels
    kept = _RENAMED.get(id(model))
    if kept is not None and kept[0] is model and kept[1] is names:
        return kept[2]
    # An input's name is its row's: the names of the inputs win over the rows' where both are given.
    prescribed = list(names.prescribed)
    for j, name in enumerate(names.inputs):
        r = model.dofs[j] if j < len(model.dofs) else 0
        if 0 < r <= len(prescribed):
            prescribed[r - 1] = name
    renamed = labels.renamed(names.coordinates, prescribed, names.dependent)
    if len(_RENAMED) > 16:
        _RENAMED.clear()
    _RENAMED[id(model)] = (model, names, renamed)
    return renamed


class _Namer:
    """Names and units of one run's co-ordinates, rows and inputs, as the core gives them, and the words of
    each buffer."""

    def __init__(self, result: RunResult) -> None:
        self.result = result
        self.named = result.names is not None
        self.core = _labels_of(result)

    def coordinate(self, i: int) -> str:
        return self.core.coordinate(i)[0]

    def coordinate_unit(self, i: int) -> str:
        return words(self.core.coordinate(i)[3])

    def row(self, r: int) -> str:
        try:
            return self.core.row(r)[0]
        except IndexError:
            return f"eps({r})"

    def row_words(self, r: int) -> str:
        """``row 5`` or ``dependent form parameter 1`` (``output`` for a named model's)."""
        if r < 0:
            return "output" if self.named else f"dependent form parameter {-r}"
        return f"row {r}"

    def row_unit(self, r: int) -> str:
        try:
            return words(self.core.row(r)[3])
        except IndexError:
            return RATIO

    def input(self, j: int) -> str:
        """The input in a derivative: ``input1``, or the name of its row."""
        try:
            return self.core.input(j)[0]
        except IndexError:
            return f"input{j}"

    def input_value(self, j: int) -> str:
        """The input as a quantity: its row by name, else its formula (``ANGB(1)``)."""
        try:
            return self.core.input(j)[1]
        except IndexError:
            return f"input{j}"

    def input_words(self, j: int) -> str:
        name = self.input(j)
        if self.named:
            return name
        return f"input {j} ({name})" if name != f"input{j}" else f"input {j}"

    def input_unit(self, j: int) -> str:
        try:
            return words(self.core.input(j)[5])
        except IndexError:
            return RATIO

    def label(self, b: Buffer) -> Label:
        """The label of ``b``: name and units from the core, kind and words from what it records."""
        kind, text = self._words(b)
        try:
            name, stated, unit, dims = self.core.buffer(b.number)
        except IndexError:
            return Label(b.number, b.name or compact(b.label()), b.unit, kind, text, stated=b.unit)
        return Label(b.number, name, unit, kind, text, base=words(dims, kind), stated=stated)

    def _words(self, b: Buffer) -> tuple[str, str]:
        """The kind of ``b`` and what it holds in words."""
        a = [*b.args, 0, 0, 0]
        kw = b.keyword
        if kw in ("BUFX0", "BUFKX1", "BUFKX2", "BUFVX", "BUFAX"):
            q = self.coordinate(a[0])
            words = f"co-ordinate {a[0]}" + (f" ({q})" if q != f"x{a[0]}" else "")
            return self._quantity(b, kw[3:], words, a)
        if kw in ("BUFE0", "BUFKE1", "BUFKE2", "BUFVE", "BUFAE"):
            q = self.row(a[0])
            return self._quantity(b, kw[3:].replace("E", "X", 1), f"{q} ({self.row_words(a[0])})", a)
        if kw == "BUFINP":
            value = self.input_value(a[0])
            return "input", f"value of input {a[0]}" + (f" ({value})" if value != f"input{a[0]}" else "")
        if kw in ("BUFSIG", "BUFDRV", "BUFREA"):
            if kw == "BUFSIG":
                what = stress_unit(self.row_unit(a[0]))
                text = f"generalised stress of {self.row_words(a[0])} ({self.row(a[0])}): the {what} its "
                return "force", text + "constraint applies, positive as it grows"
            if kw == "BUFDRV":
                what = stress_unit(self.input_unit(a[0]))
                return "force", f"drive {what} of input {a[0]} ({self.input_value(a[0])})"
            return "force", f"reaction of the frame on co-ordinate {a[0]} ({self.coordinate(a[0])})"
        if kw == "BUFTOL":
            rss = b.number != a[1]
            return "band", f"{'RSS' if rss else 'worst-case'} tolerance band of buffer {a[0]}"
        simple = {
            "BUFTIME": ("time", "time"),
            "BUFDET": ("det", "det(D^c), the measure of transfer quality"),
            "BUFEKIN": ("energy", "kinetic energy T"),
            "BUFEPOT": ("energy", "potential energy V (gravity and springs)"),
            "BUFPOW": ("power", "power the drives deliver"),
            "BUFMRED": ("mass", f"entry ({a[0]}, {a[1]}) of the mass matrix in the inputs"),
        }
        return simple.get(kw, ("position", b.label()))

    def _quantity(self, b: Buffer, what: str, words: str, a: list[int]) -> tuple[str, str]:
        """The kind and words of co-ordinate or row ``words`` (``what``: X0, KX1, KX2, VX or AX of it)."""
        if what == "X0":
            return "position", words
        if what == "VX":
            return "velocity", f"velocity of {words}"
        if what == "AX":
            return "acceleration", f"acceleration of {words}"
        j = a[1]
        if what == "KX1":
            return "first order", f"first-order transfer function of {words} with respect to {self.input_words(j)}"
        m = a[2] if len(b.args) > 2 else j
        wrt = f"{self.input_words(j)} (twice)" if m == j else f"{self.input_words(j)} and {self.input_words(m)}"
        return "second order", f"second-order transfer function of {words} with respect to {wrt}"


def buffer_labels(result: RunResult) -> dict[int, Label]:
    """The label of every buffer of ``result.storage``, by number."""
    namer = _Namer(result)
    return {b.number: namer.label(b) for b in result.storage.buffers}


def label(result: RunResult, number: int) -> Label:
    """The label of buffer ``number`` (``buffer N`` with no unit when the storage does not define it)."""
    try:
        b = result.storage.buffer(number)
    except KeyError:
        return Label(number, f"buffer{number}", "", "position", f"buffer {number}, not defined by the storage")
    return _Namer(result).label(b)


def coordinate_name(result: RunResult, i: int) -> str:
    """Co-ordinate i by name: ``x13``, or the model's name (``P.x``)."""
    return _Namer(result).coordinate(i)


def coordinate_axis(result: RunResult, i: int) -> str:
    """An axis label for co-ordinate i: ``x13 [mm]`` (``x13`` without a unit of length)."""
    name, _, unit, _ = _labels_of(result).coordinate(i)
    return with_unit(name, unit)


def point_name(result: RunResult, ix: int, iy: int) -> str:
    """The point of co-ordinates ix, iy: ``(x13, x14)``, or the model's point name (``P`` for ``P.x``, ``P.y``)."""
    x, y = coordinate_name(result, ix), coordinate_name(result, iy)
    if x.endswith(".x") and y.endswith(".y") and x[:-2] == y[:-2]:
        return x[:-2]
    return f"({x}, {y})"


def input_name(result: RunResult, j: int) -> str:
    """Input j in a derivative: ``input1``, or the model's name for it."""
    return _Namer(result).input(j)


def row_dest_unit(result: RunResult, dest: int) -> str:
    """The unit of prescribed row ``dest`` (> 0) or dependent form parameter ``-dest``, in the words of the unit
    algebra (:func:`display_unit` says it in the run's units)."""
    return _Namer(result).row_unit(dest)


def coordinate_unit(result: RunResult, i: int) -> str:
    """The unit of co-ordinate i, in the words of the unit algebra."""
    return _Namer(result).coordinate_unit(i)


def input_unit(result: RunResult, j: int) -> str:
    """The unit of input j (its row's), in the words of the unit algebra."""
    return _Namer(result).input_unit(j)


def display_unit(result: RunResult, unit: str) -> str:
    """``unit`` (in the words of the unit algebra) in the run's units (:func:`shown`)."""
    return shown(unit, run_units(result))


def value_unit(result: RunResult, name: object) -> str:
    """The unit of what ``result.value(name)`` gives, in the words of the unit algebra: an output's or row's, a
    co-ordinate's, a point's (a length)."""
    t = result._any(name)
    if t.kind == "row":
        return row_dest_unit(result, t.numbers[0])
    if t.kind == "coordinate":
        return coordinate_unit(result, t.numbers[0])
    return LENGTH


def det_unit(result: RunResult) -> str:
    """The unit of det(D^c), in the words of the unit algebra."""
    return words(_labels_of(result).det()[3])


def unit_in(result: RunResult, unit: str, given: str | None = None) -> str:
    """``unit`` (in the words of the unit algebra) in the run's units, its angles or lengths in ``given`` when given
    (the ``unit=`` of :meth:`~mechfem.RunResult.value`)."""
    if given is None:
        return display_unit(result, unit)
    kind = kind_of(given)
    units = run_units(result).as_dict()
    if kind is not None:
        units[kind] = given
    return shown(unit, Units.of(units))


def buffer_name(model: Model | None, number: int) -> str:
    """Buffer ``number`` of ``model`` by its label (``d2delta/dalpha^2``), ``buffer N`` where the model has none."""
    labels = None if model is None else model.labels
    try:
        return labels.buffer(number)[0] if labels is not None else f"buffer {number}"
    except IndexError:
        return f"buffer {number}"


def core_value(model: Model | None, number: int, value: float, digits: str = ".6g") -> str:
    """``value``, a number of the core's of buffer ``number`` (an optimiser's), in the units of ``model`` with the
    unit it shows: ``-296.5 deg`` (``rad`` without UNITS); as it is, without a unit, where the model has no such
    buffer."""
    labels = None if model is None else model.labels
    try:
        _, _, stated, dims = labels.buffer(number) if labels is not None else ("", "", "", (0, 0, 0, 0, 0))
    except IndexError:
        stated, dims = "", (0, 0, 0, 0, 0)
    v = value * labels.scale(dims) if labels is not None else value
    return f"{v:{digits}} {stated}" if stated and stated != "-" else f"{v:{digits}}"


def core_input(model: Model | None, j: int, value: float, digits: str = ".12g") -> str:
    """``name = value unit`` of input ``j`` at ``value``, a number of the core's: ``alpha = -58.2 deg``."""
    labels = None if model is None else model.labels
    if labels is None:
        return f"input {j} = {value:{digits}}"
    name, _, _, _, stated, dims = labels.input(j)
    v = value * labels.scale(dims)
    return f"{name} = {v:{digits}}" + (f" {stated}" if stated and stated != "-" else "")


def with_unit(name: str, unit: str) -> str:
    """``name [unit]``, or ``name`` without a unit: the form of every axis label."""
    return f"{name} [{unit}]" if unit else name
