"""The one naming scheme for every quantity a person reads: data-set headers, print-file tables, picture axes,
legends, the animation's title and the report.

Every buffer gets a :class:`Label`: a compact name (``ANGB(8)``, ``dANGB(8)/dinput1``, ``x13``, ``vx13``), its
unit, its kind and a sentence in words. A deck's run is named by deck numbers and form parameters; the run of a
named model (:class:`mechfem.Mechanism`, whose names travel in :attr:`RunResult.names`) by the model's own names
(``P.x``, ``dcoupler_angle/dcrank``).

Units. A unit is worked out in the words of its kind: ``length``, ``rad`` for an angle, ``s`` for time, and
ratios (a gear ratio) have none (``""``). A derivative's unit is the quantity's over the input's (``rad/rad``,
``length/rad``), a velocity adds ``/s`` and an acceleration ``/s^2``. A stress or reaction is a ``force`` on a
length, a ``torque`` on an angle and an ``energy`` on a ratio; energies are ``energy``, power ``power``, and the
mass matrix ``mass`` times one ``length`` for every input that is an angle or a ratio. A label then says it in the
model's units (:func:`shown`: the deck's ``UNITS``, or a :class:`~mechfem.Mechanism`'s): ``mm/deg``, ``N·mm`` for a
torque (FORCE x LENGTH), ``kg·mm^2``, a quantity over one of its own unit as ``-``; a unit whose kind the model does
not give (a length without ``UNITS LENGTH``) is not shown at all.
"""

from __future__ import annotations

import dataclasses
import re
from collections.abc import Callable
from dataclasses import dataclass

from mechfem.catalogue import CATALOGUE, FORMS, Dimension, coordinate_dimensions, form_dimension
from mechfem.echo import Buffer, Model, Row
from mechfem.result import RunResult
from mechfem.result_tables import run_units
from mechfem.units import Units

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

UNITS: dict[Dimension, str | None] = {"length": LENGTH, "angle": ANGLE, "ratio": RATIO, "any": None}
"""The unit of each of the catalogue's dimensions (``any``: the unit comes from the other elements that share the
co-ordinate)."""

#: The unit of each co-ordinate of an element type, in deck order, from the core's catalogue. The ``i`` of a rack
#: element is the pinion's radius, a length; the ``i`` of a ``GR1`` is a ratio.
SLOT_UNITS: dict[str, tuple[str | None, ...]] = {
    t: tuple(UNITS[k] for k in coordinate_dimensions(t)) for t in CATALOGUE
}


@dataclass(frozen=True)
class Label:
    """What buffer ``number`` holds, for a person."""

    number: int
    """The buffer number."""
    name: str
    """Compact readable name: ``ANGB(8)``, ``dANGB(8)/dinput1``, ``d2ANGB(8)/dinput1^2``, ``x13``, ``vx13``,
    ``time``, ``det(D^c)``; a named model's own names instead (``dcoupler_angle/dcrank``, ``P.x``)."""
    unit: str
    """``rad``, ``length``, ``rad/rad``, ``length/s^2``, ``s``, ``torque``, ... (``""``: none)."""
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
        """An axis label with the unit: ``dANGB(8)/dinput1 [rad/rad]`` (no brackets without a unit)."""
        return with_unit(self.name, self.unit)

    def legend(self) -> str:
        """A legend or table entry: the number, the name and the unit (``101 dANGB(8)/dinput1 [rad/rad]``)."""
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


def coordinate_units(model: Model) -> dict[int, str]:
    """The unit of every co-ordinate, from the elements that use it (a length when none says)."""
    out: dict[int, str] = {}
    for e in model.elements:
        for i, unit in zip(e.coords, SLOT_UNITS.get(e.type, ()), strict=False):
            if unit is not None:
                out.setdefault(i, unit)
    for c in model.coordinates:
        out.setdefault(c.number, LENGTH)
    return out


def form_unit(model: Model, form: str, element: int, coords: dict[int, str] | None = None) -> str:
    """The unit of form parameter ``form`` of element ``element``, from the catalogue's dimension (a gear pair's
    ``GEAR`` is an assembly angle, a rack's an assembly length; a ``COOR`` has its co-ordinate's unit)."""
    e = next((x for x in model.elements if x.number == element), None)
    if e is None or form not in FORMS.get(e.type, ()):
        return RATIO
    unit = UNITS[form_dimension(e.type, form)]
    if unit is not None:
        return unit
    if e.coords:
        return (coords if coords is not None else coordinate_units(model)).get(e.coords[0], LENGTH)
    return RATIO


def row_unit(model: Model, row: Row, coords: dict[int, str] | None = None) -> str:
    """The unit of a (possibly combined) row: its terms' unit. Terms of different units have a factor that
    carries the difference, so the terms with factor +-1 decide; failing them, the first term."""
    units = [form_unit(model, t.form, t.element, coords) for t in row.terms]
    plain = {u for u, t in zip(units, row.terms, strict=True) if abs(t.factor) == 1.0}
    if len(plain) == 1:
        return plain.pop()
    return units[0] if units else RATIO


def stress_unit(unit: str) -> str:
    """The unit of a generalised force on a quantity of unit ``unit``: force, torque or energy."""
    return {LENGTH: "force", ANGLE: "torque"}.get(unit, "energy")


def inertia_unit(a: str, b: str) -> str:
    """The unit of the mass-matrix entry for inputs of units ``a`` and ``b``: mass times a length for each input
    that is an angle or a ratio (a point's move per unit of it is a length)."""
    lengths = sum(u != LENGTH for u in (a, b))
    return "mass" + ("·length" if lengths == 1 else "·length^2" if lengths == 2 else "")


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
        "energy": moment,
        "power": None if moment is None else f"{moment}/{units.time}",
        "mass": units.mass,
    }


_WORD = re.compile(r"[A-Za-z]+")
_RATIO = re.compile(r"^\(?([^()/]+)\)?/\(?([^()/]+)\)?$")


def shown(unit: str, units: Units) -> str:
    """``unit`` (in the words of the unit algebra) in ``units``: ``length/rad`` is ``mm/deg``; a quantity over
    one of its own unit is ``-``; "" when a word of it has no unit in ``units``."""
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
    return out


# -- names --------------------------------------------------------------------------------------------------------


def compact(formula: str) -> str:
    """A row's formula without spaces: ``ANGB(2)-ANGB(4)``."""
    return formula.replace(" ", "")


def _wrapped(name: str) -> str:
    """``name`` bracketed when an operator in it would make a derivative's name ambiguous."""
    return f"({name})" if any(c in name[1:] for c in "+-*/ ") or name.startswith("-") else name


class _Namer:
    """Names and units of one run's co-ordinates, rows and inputs, computed once for all its buffers."""

    def __init__(self, result: RunResult) -> None:
        self.result = result
        self.units = run_units(result)
        self.model = result.model
        self.names = result.names
        self.coords = coordinate_units(self.model)
        self.rows = {r.dest: r for r in [*self.model.prescribed, *self.model.dependent]}

    def coordinate(self, i: int) -> str:
        n = self.names
        if n is not None and 0 < i <= len(n.coordinates):
            return n.coordinates[i - 1]
        declared = self.model.coordinates[i - 1].name if 0 < i <= len(self.model.coordinates) else None
        return declared or f"x{i}"

    def coordinate_unit(self, i: int) -> str:
        return self.coords.get(i, LENGTH)

    def row(self, r: int) -> str:
        n = self.names
        if n is not None:
            names = n.prescribed if r > 0 else n.dependent
            if 0 < abs(r) <= len(names):
                return names[abs(r) - 1]
        row = self.rows.get(r)
        if row is not None and row.name:
            return row.name
        return compact(row.formula()) if row is not None else f"eps({r})"

    def row_words(self, r: int) -> str:
        """``row 5`` or ``dependent form parameter 1`` (``output`` for a named model's)."""
        if r < 0:
            return "output" if self.names is not None else f"dependent form parameter {-r}"
        return f"row {r}"

    def row_unit(self, r: int) -> str:
        row = self.rows.get(r)
        return row_unit(self.model, row, self.coords) if row is not None else RATIO

    def input_row(self, j: int) -> int | None:
        dofs = self.model.dofs
        return dofs[j - 1] if 0 < j <= len(dofs) else None

    def input(self, j: int) -> str:
        """The input in a derivative: ``input1``, or the model's name for it."""
        n = self.names
        if n is not None and 0 < j <= len(n.inputs):
            return n.inputs[j - 1]
        r = self.input_row(j)
        declared = self.rows[r].name if r is not None and r in self.rows else None
        return declared or f"input{j}"

    def input_value(self, j: int) -> str:
        """The input as a quantity: its row's form parameter (``ANGB(1)``), or the model's name for it."""
        n = self.names
        if n is not None and 0 < j <= len(n.inputs):
            return n.inputs[j - 1]
        r = self.input_row(j)
        return self.row(r) if r is not None else f"input{j}"

    def input_words(self, j: int) -> str:
        n = self.names
        if n is not None and 0 < j <= len(n.inputs):
            return n.inputs[j - 1]
        declared = self.input(j)
        return f"input {j} ({declared})" if declared != f"input{j}" else f"input {j}"

    def input_unit(self, j: int) -> str:
        r = self.input_row(j)
        return self.row_unit(r) if r is not None else RATIO

    def label(self, b: Buffer) -> Label:
        """The label of ``b``: the name and unit the core gives it (the deck's ``BUF`` label or NAMES, its
        UNITS); a named model's own names (which may hold dots no deck name can); a unit in the words of the
        algebra said in the run's units where the core gives none (an angle in ``rad`` without UNITS)."""
        lab = self._label(b)
        name = lab.name if self.names is not None or not b.name else b.name
        unit = b.unit or shown(lab.unit, self.units)
        return dataclasses.replace(lab, name=name, unit=unit, base=lab.unit, stated=b.unit)

    def _label(self, b: Buffer) -> Label:
        a = [*b.args, 0, 0, 0]
        kw = b.keyword
        if kw in ("BUFX0", "BUFKX1", "BUFKX2", "BUFVX", "BUFAX"):
            q, unit, words = self.coordinate(a[0]), self.coordinate_unit(a[0]), f"co-ordinate {a[0]}"
            if q != f"x{a[0]}":
                words = f"{words} ({q})"
            return self._quantity(b, kw[3:], q, unit, words, a)
        if kw in ("BUFE0", "BUFKE1", "BUFKE2", "BUFVE", "BUFAE"):
            q, unit = self.row(a[0]), self.row_unit(a[0])
            return self._quantity(b, kw[3:].replace("E", "X", 1), q, unit, f"{q} ({self.row_words(a[0])})", a)
        n = b.number
        simple: dict[str, Callable[[], Label]] = {
            "BUFINP": lambda: Label(
                n,
                self.input_value(a[0]),
                self.input_unit(a[0]),
                "input",
                f"value of input {a[0]}" + (f" ({self.input_value(a[0])})" if self.input_row(a[0]) else ""),
            ),
            "BUFTIME": lambda: Label(n, "time", TIME, "time", "time"),
            "BUFDET": lambda: Label(n, "det(D^c)", "", "det", "det(D^c), the measure of transfer quality"),
            "BUFSIG": lambda: Label(
                n,
                f"sigma({self.row(a[0])})",
                stress_unit(self.row_unit(a[0])),
                "force",
                f"generalised stress of {self.row_words(a[0])} ({self.row(a[0])}): the "
                f"{stress_unit(self.row_unit(a[0]))} its constraint applies, positive as it grows",
            ),
            "BUFDRV": lambda: Label(
                n,
                f"drive({self.input_value(a[0])})",
                stress_unit(self.input_unit(a[0])),
                "force",
                f"drive {stress_unit(self.input_unit(a[0]))} of input {a[0]} ({self.input_value(a[0])})",
            ),
            "BUFREA": lambda: Label(
                n,
                f"reaction({self.coordinate(a[0])})",
                stress_unit(self.coordinate_unit(a[0])),
                "force",
                f"reaction of the frame on co-ordinate {a[0]} ({self.coordinate(a[0])})",
            ),
            "BUFEKIN": lambda: Label(n, "Ekin", "energy", "energy", "kinetic energy T"),
            "BUFEPOT": lambda: Label(n, "Epot", "energy", "energy", "potential energy V (gravity and springs)"),
            "BUFPOW": lambda: Label(n, "power", "power", "power", "power the drives deliver"),
            "BUFMRED": lambda: self._mass(b, a[0], a[1]),
        }
        make = simple.get(kw)
        if make is not None:
            return make()
        return Label(n, compact(b.label()), "", "position", b.label())

    def _mass(self, b: Buffer, j: int, m: int) -> Label:
        names = (str(j), str(m)) if self.names is None else (self.input(j), self.input(m))
        return Label(
            b.number,
            f"M({names[0]},{names[1]})",
            inertia_unit(self.input_unit(j), self.input_unit(m)),
            "mass",
            f"entry ({j}, {m}) of the mass matrix in the inputs",
        )

    def _quantity(self, b: Buffer, what: str, q: str, unit: str, words: str, a: list[int]) -> Label:
        """The label of a co-ordinate or row ``q`` (``what``: X0, KX1, KX2, VX or AX of it)."""
        n = b.number
        if what == "X0":
            return Label(n, q, unit, "position", words)
        if what == "VX":
            return Label(n, f"v{_wrapped(q)}", over(unit, TIME), "velocity", f"velocity of {words}")
        if what == "AX":
            return Label(n, f"a{_wrapped(q)}", over(unit, f"{TIME}^2"), "acceleration", f"acceleration of {words}")
        j = a[1]
        if what == "KX1":
            return Label(
                n,
                f"d{_wrapped(q)}/d{self.input(j)}",
                over(unit, self.input_unit(j)),
                "first order",
                f"first-order transfer function of {words} with respect to {self.input_words(j)}",
            )
        m = a[2] if len(b.args) > 2 else j
        if m == j:
            name = f"d2{_wrapped(q)}/d{self.input(j)}^2"
            wrt = f"{self.input_words(j)} (twice)"
        else:
            name = f"d2{_wrapped(q)}/d{self.input(j)}d{self.input(m)}"
            wrt = f"{self.input_words(j)} and {self.input_words(m)}"
        unit2 = over(unit, squared(self.input_unit(j), self.input_unit(m)))
        return Label(n, name, unit2, "second order", f"second-order transfer function of {words} with respect to {wrt}")


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
    namer = _Namer(result)
    return with_unit(namer.coordinate(i), shown(namer.coordinate_unit(i), namer.units))


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


def with_unit(name: str, unit: str) -> str:
    """``name [unit]``, or ``name`` without a unit: the form of every axis label."""
    return f"{name} [{unit}]" if unit else name
