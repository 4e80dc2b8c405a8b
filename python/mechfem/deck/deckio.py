"""Decks to and from the Python model: :class:`~mechfem.Mechanism` as deck text, a deck as a mechanism.

A mechanism runs without deck text: :mod:`mechfem.run.building` hands its items to the deck reader's typed builder in
the numbering of this module, and the model compiled from them is the one its deck text compiles to, to the last bit
(:mod:`mechfem.run.compiled` keeps it per topology). This module

* writes a mechanism with its motion and storage as deck text (:func:`write`), one keyword per line, its units on
  the ``UNITS`` line and its names in the ``NAMES`` block (:mod:`mechfem.deck.naming`), keeping a note of what each
  line declares;
* numbers a mechanism as its deck does (:func:`number_model`), and the arguments of its buffers and plots
  (:func:`buffer_numbers`, :func:`plot_numbers`);
* reads a deck into a mechanism with the names and units it declares, and generated names for the rest
  (:func:`read`).
"""

from __future__ import annotations

import dataclasses
import math
import os
import re
import sys
import tempfile
from collections.abc import Callable, Iterator, Mapping
from contextlib import contextmanager
from pathlib import Path
from typing import Literal, NamedTuple

import numpy as np

import mechfem._core as _core
from mechfem._util.atomic import atomic_text
from mechfem.deck.explain import translate
from mechfem.deck.naming import DeckNames, DeckText, Numbering, model_unit, names_block, number
from mechfem.model import loads
from mechfem.model.catalogue import DEFAULT_ACCURACY, DEFAULT_MAX_ITER, MIN_INTEGRATION_TOLERANCE
from mechfem.model.mechanism import (
    BUFFER_ARGS,
    FORMS,
    SLOTS,
    By,
    Coordinate,
    Dynamic,
    Element,
    FormParameter,
    Free,
    InputKey,
    InputMotion,
    Mechanism,
    Motion,
    Point,
    Ref,
    Row,
    Slot,
    Storage,
    Table,
    To,
)
from mechfem.model.motion import check_units
from mechfem.model.stopping import stop_buffer, stop_name
from mechfem.model.storage import check_file_names, from_described, warn_bands_left_out
from mechfem.model.units import Units, scale

Progress = bool | Callable[[int, int], object] | None


def number_model(mech: Mechanism) -> Numbering:
    """Numbers the co-ordinates (a deck's own numbers are kept; others follow, fixed ones first), elements and rows
    (inputs last)."""
    explicit = {c.number: c for c in mech.coordinates if c.number is not None}
    start = max(explicit, default=0)
    rest = [c for c in mech.coordinates if c.number is None]
    ordered = [c for c in rest if c.fixed] + [c for c in rest if not c.fixed]
    by_number = dict(explicit)
    for k, c in enumerate(ordered, start + 1):
        by_number[k] = c
    coords = [by_number[k] for k in sorted(by_number)]
    prescribed = [r for r in mech.rows if r.kind == "prescribed"] + [r for r in mech.rows if r.kind == "input"]
    dependent = [r for r in mech.rows if r.kind == "output"]
    return Numbering(coords, list(mech.elements), prescribed, dependent)


class _Lines:
    def __init__(self) -> None:
        self.lines: list[str] = []
        self.notes: dict[int, tuple[str, str]] = {}

    def add(self, text: str, note: tuple[str, str] | None = None, comment: str | None = None) -> None:
        if comment:
            text = f"{text} ; {comment}"
        self.lines.append(text)
        if note is not None:
            self.notes[len(self.lines)] = note


def _resolve(mech: Mechanism, numbering: Numbering, ref: Ref, kind: str, where: str) -> list[int]:
    """A buffer's or plot's argument as deck numbers: ``i`` co-ordinate, ``r`` row, ``j`` input, ``P`` point."""
    if isinstance(ref, bool):
        raise TypeError(f"{where}: not a reference: {ref!r}")
    if isinstance(ref, int):
        return [ref]
    obj: object = mech[ref] if isinstance(ref, str) else ref
    if kind == "P":
        if isinstance(obj, Point):
            return [numbering.coord_number[obj.x], numbering.coord_number[obj.y]]
        kind = "i"
    if kind == "i" and isinstance(obj, Coordinate) and obj in numbering.coord_number:
        return [numbering.coord_number[obj]]
    if kind == "r":
        if isinstance(obj, FormParameter):
            found = [r for r in numbering.rows if r.terms == ((1.0, obj),)]
            if found:
                obj = found[0]
        if isinstance(obj, Row) and obj in numbering.row_dest:
            return [numbering.row_dest[obj]]
    if kind in "jm" and isinstance(obj, Row | FormParameter | str):
        return [numbering.dof(obj)]
    if kind == "e" and obj in numbering.elements:
        return [numbering.elements.index(obj) + 1]
    what = {"i": "a co-ordinate", "r": "a row or output", "j": "an input", "m": "an input", "e": "an element"}[kind]
    raise ValueError(f"{where}: {ref!r} is not {what} of the mechanism {mech.name!r}")


def buffer_numbers(mech: Mechanism, numbering: Numbering, b: int, kw: str, args: tuple[Ref, ...]) -> list[int]:
    """The deck numbers of the arguments of buffer ``b`` (``kw args``)."""
    resolved: list[int] = []
    for kind, a in zip(BUFFER_ARGS[kw], args, strict=False):
        resolved += _resolve(mech, numbering, a, kind, f"buffer {b}")
    return resolved


def plot_numbers(mech: Mechanism, numbering: Numbering, kw: str, first: Ref, second: Ref) -> tuple[int, int]:
    """The two deck numbers of a plot: buffers, or for PLOTHODO a point's co-ordinates."""
    if kw == "PLOTHODO" and first == second:
        ab = _resolve(mech, numbering, first, "P", "PLOTHODO")
    elif kw == "PLOTHODO":
        ab = _resolve(mech, numbering, first, "i", kw) + _resolve(mech, numbering, second, "i", kw)
    elif isinstance(first, int) and isinstance(second, int):
        ab = [first, second]
    else:
        raise ValueError(f"{kw} takes two buffer numbers, got {first!r} and {second!r}")
    if len(ab) != 2:
        raise ValueError(f"{kw} needs a point or two co-ordinates, got {first!r}")
    return ab[0], ab[1]


def _table_text(rows: np.ndarray, name: str) -> str:
    head = f"# input motion of {name}: t value velocity acceleration, one row per position\n"
    return head + "".join(" ".join(number(v) for v in row) + "\n" for row in rows)


def _file_stem(name: str) -> str:
    return re.sub(r"[^A-Za-z0-9_.-]", "_", name) or "mechanism"


def input_motions(mech: Mechanism, motion: Motion, nb: Numbering) -> list[InputMotion]:
    """The motion of each input of ``mech`` (numbered by ``nb``) in DOF order, in the model's units; a ValueError
    for a motion a deck cannot state (free motion of several inputs, an input given two motions or none)."""
    n_dof = len(nb.inputs)
    if n_dof != 1 and any(isinstance(im, Free) for im in motion.inputs.values()):
        raise ValueError(
            f"free motion (Motion.free, Free) needs a mechanism with one input, and {mech.name!r} has {n_dof} "
            f"({', '.join(r.name for r in nb.inputs) or 'none'}): drive them with Motion.by, Motion.to or "
            "Motion.table"
        )
    check_units(motion, nb.inputs, mech.units.angle)
    per_dof: dict[int, tuple[InputKey, InputMotion]] = {}
    for key, im in motion.inputs.items():
        j = nb.dof(key)
        if j in per_dof:
            raise ValueError(f"input {nb.inputs[j - 1].name!r} is given two motions ({per_dof[j][0]!r}, {key!r})")
        per_dof[j] = (key, im)
    missing = [nb.inputs[j - 1].name for j in range(1, n_dof + 1) if j not in per_dof]
    if missing:
        raise ValueError(f"the motion gives no motion for the input(s) {', '.join(map(repr, missing))}")
    return [model_unit(per_dof[j][1], nb.inputs[j - 1], mech.units.angle) for j in range(1, n_dof + 1)]


def inttol(motion: Motion) -> tuple[float, float] | None:
    """The integrator's tolerances (rtol, atol) the motion sets, or None: INTTOL takes both, and the one not given
    is ACCURACY, as the deck reader's default (with the core's floor)."""
    if motion.rtol is None and motion.atol is None:
        return None
    tol = max(motion.accuracy or DEFAULT_ACCURACY, MIN_INTEGRATION_TOLERANCE)
    rtol, atol = (tol if v is None else v for v in (motion.rtol, motion.atol))
    return float(rtol), float(atol)


def write(
    mech: Mechanism,
    motion: Motion | None = None,
    storage: Storage | None = None,
    overrides: Mapping[Row | Coordinate, float] | None = None,
) -> DeckText:
    """Writes ``mech`` as deck text; ``overrides`` replace prescribed values and initial co-ordinates."""
    over = overrides or {}
    nb = number_model(mech)
    out = _Lines()
    out.add(f"; written by mechfem from the Python model '{mech.name}'")
    dynamic = [] if motion is None else [k for k, im in motion.inputs.items() if isinstance(im, Dynamic)]
    simulated = [nb.inputs[nb.dof(k) - 1].name for k in dynamic]
    out.add(loads.mode(mech, simulated))
    units = mech.units.deck_line()
    if units is not None:
        out.add(units, ("units", str(mech.units)))
    out.add("TOPOLOGY")
    for k, e in enumerate(nb.elements, 1):
        nums = " ".join(str(nb.coord_number[c]) for c in e.coordinates)
        out.add(f"ELEM {k} {e.type} {nums}", ("element", e.name))
    element_number = {e: k for k, e in enumerate(nb.elements, 1)}
    seq = 0
    for r in nb.rows:
        dest = nb.row_dest[r]
        for f, p in r.terms:
            seq += 1
            if p.element not in element_number:
                raise ValueError(f"row {r.name!r}: {p!r} belongs to another mechanism")
            k = element_number[p.element]
            out.add(f"FORM {seq} {p.form} {k} {dest} {number(f)}", (r.kind, r.name))
    n_dof = len(nb.inputs)
    out.add(f"NRDOF {n_dof}", ("inputs", ", ".join(r.name for r in nb.inputs)))
    out.add("GEOMETRY")
    for i, c in enumerate(nb.coords, 1):
        kw = "XFIX" if c.fixed else "XMOV"
        out.add(f"{kw} {i} {number(over.get(c, c.value))}", ("co-ordinate", c.name))
    for r in nb.prescribed:
        value = over.get(r, r.value)
        if value is not None:
            out.add(f"PARA {nb.row_dest[r]} {number(value)}", (r.kind, r.name))
    for text, note in names_block(mech, nb):
        out.add(text, note)

    tables: dict[str, str] = {}
    if mech.loads is not None:
        out.add("DYNAMICS")
        for text, note, _ in loads.deck_lines(mech.loads, nb, _file_stem(mech.name), tables):
            out.add(text, note)
    if motion is not None:
        per_dof = input_motions(mech, motion, nb)
        out.add("MOVEMENT")
        out.add(f"TSTEPE {motion.steps} {number(motion.dt)}", ("motion", "steps"))
        for j in range(1, n_dof + 1):
            im = per_dof[j - 1]
            name = nb.inputs[j - 1].name
            note = ("motion of input", name)
            if isinstance(im, By):
                out.add(f"MOV_RELE {j} {number(im.value)}", note)
            elif isinstance(im, To):
                out.add(f"MOV_ABSE {j} {number(im.value)}", note)
            elif isinstance(im, Free):
                out.add(f"MOV_FREE {j} {number(im.ds)}", note)
            elif isinstance(im, Dynamic):
                out.add(f"MOV_DYN {j} {number(im.value)}", note)
            elif isinstance(im, Table):
                file = im.file or f"{_file_stem(mech.name)}_input{j}.dat"
                if any(ch.isspace() or ch == ";" for ch in file):
                    raise ValueError(f"a table motion's file name (Table.file) cannot hold blanks or ';': {file!r}")
                loads.add_table(tables, file, _table_text(im.rows(motion.dt), name))
                out.add(f"MOV_FUNC {j} {file}", note)
            else:
                raise TypeError(f"not an input motion: {im!r}")
        if motion.accuracy is not None:
            out.add(f"ACCURACY {number(motion.accuracy)}", ("motion", "accuracy"))
        if motion.max_iter is not None:
            out.add(f"MAXITER {int(motion.max_iter)}", ("motion", "max_iter"))
        tolerances = inttol(motion)
        if tolerances is not None:
            out.add(f"INTTOL {number(tolerances[0])} {number(tolerances[1])}", ("motion", "rtol and atol"))
        if motion.integrator != "auto":
            out.add(f"INTEGRATOR {motion.integrator}", ("motion", "integrator"))
        stop = stop_buffer(motion, storage, mech.name)
        if stop is not None:
            out.add(f"STOPWHEN {stop[0]} {number(stop[1])}", ("motion", "stop_when"))

    if storage is not None:
        out.add("STORAGE")
        for b, kw, args in storage.buffers:
            resolved = buffer_numbers(mech, nb, b, kw, args)
            out.add(" ".join([kw, *map(str, resolved), str(b)]), ("buffer", str(b)))
        if storage.printbuf is not None:
            out.add(" ".join(["PRINTBUF", *map(str, storage.printbuf)]), ("storage", "PRINTBUF"))
        if storage.savedata:
            out.add(" ".join(["SAVEDATA", *map(str, storage.savedata)]), ("storage", "SAVEDATA"))
        if storage.animate:
            out.add(f"ANIMATE {storage.animate}", ("storage", "ANIMATE"))
        for pic in storage.pictures:
            if not pic.plots:
                raise ValueError(
                    f"the storage of mechanism {mech.name!r}: picture {pic.title!r} has no plots; give at least one"
                )
            out.add(f"BEGINPIC {pic.title.replace(';', ',')}".rstrip(), ("picture", pic.title))
            for kw, first, second in pic.plots:
                a, b = plot_numbers(mech, nb, kw, first, second)
                out.add(f"{kw} {a} {b}", ("picture", pic.title))
            out.add("ENDPIC")
    out.add("END")
    check_file_names(mech.name, storage, tables)
    return DeckText("\n".join(out.lines) + "\n", f"{mech.name}.mec", out.notes, nb, tables, simulated)


def save(mech: Mechanism, path: Path, motion: Motion | None, storage: Storage | None) -> Path:
    """Writes the deck to ``path`` and its MOV_FUNC files beside it."""
    deck = write(mech, motion, storage)
    path.parent.mkdir(parents=True, exist_ok=True)
    # Each file whole or not at all, as the run's outputs.
    for name, text in [*deck.tables.items(), (path.name, deck.text)]:
        with atomic_text(path.parent / name) as f:
            f.write(text)
    return path


@contextmanager
def tables_dir(tables: Mapping[str, str]) -> Iterator[str]:
    """A folder holding the MOV_FUNC files (a temporary one, removed afterwards), or ``.`` without any."""
    if not tables:
        yield "."
        return
    with tempfile.TemporaryDirectory(prefix="mechfem-") as d:
        for name, text in tables.items():
            Path(d, name).write_text(text)
        yield d


# --- running ---------------------------------------------------------------------------------------------------------


def progress_callback(progress: Progress, what: str) -> Callable[[int, int], object] | None:
    """A callable for ``_core``: None, the user's own, or for ``True`` a progress bar counting ``what`` on stderr,
    drawn when stderr is a terminal or the code runs in a Jupyter kernel (whose stderr is no terminal but shows
    the bar under the cell), and left out when output is redirected."""
    if progress is None or progress is False:
        return None
    if progress is True:
        from mechfem._util.progress import ProgressBar

        # A Jupyter kernel has imported ipykernel: its stderr is a pipe, yet the bar belongs under the cell.
        bar = ProgressBar(show=True if "ipykernel" in sys.modules else None)
        bar.phase("running", unit=what)
        return bar
    return progress


# --- reading decks -------------------------------------------------------------------------------------------------


def read(path: Path) -> Mechanism:
    """Reads the deck at ``path`` into a mechanism (see :meth:`Mechanism.from_deck` for the names): its text up to
    END, read as every deck is (a regular file of at most 16 MiB before END)."""
    text = _core.read_deck_text(path)
    return read_text(text, path.stem, path.parent if str(path.parent) else Path("."), os.fspath(path))


class Declared(NamedTuple):
    """A co-ordinate as a deck declares it: its number, value and whether it moves."""

    number: int
    value: float
    moving: bool


class DeclaredRow(NamedTuple):
    """A row as a deck declares it: destination, terms ``(element number, form, factor)``, PARA and its DOF."""

    dest: int
    terms: list[tuple[int, str, float]]
    para: float | None
    input: int | None


def topology(
    name: str,
    coords: list[Declared],
    elements: list[tuple[int, str, list[int]]],
    prescribed: list[DeclaredRow],
    dependent: list[DeclaredRow],
    names: DeckNames | None = None,
    units: Units | None = None,
) -> Mechanism:
    """The mechanism a deck's topology and geometry make (elements ``(number, type, co-ordinate numbers)`` in
    element order, rows in destination order), in ``units``: its parts named as ``names`` (the deck's NAMES block)
    says, the others after their numbers: points after their x co-ordinate (``P5``), other co-ordinates ``x13``,
    elements ``E1``..., a row of one form parameter its element's own (``E8.angle``), others ``row6`` and ``out1``.
    The deck's numbers are kept."""
    m = Mechanism(name, units=units)
    declared = names or DeckNames()
    by_number = {c.number: c for c in coords}
    objects: dict[int, Coordinate] = {}
    taken = {*declared.points.values(), *declared.coordinates.values(), *declared.elements.values()}
    taken.update(declared.rows.values())

    def generated(base: str) -> str:
        """``base``, or with a suffix when the deck declares it for another part."""
        out, k = base, 1
        while out in taken or out in m:
            k += 1
            out = f"{base}_{k}"
        return out

    def new_coordinate(i: int, cname: str, kind: Literal["x", "y", "angle", "scalar"]) -> Coordinate:
        spec = by_number[i]
        c = Coordinate(cname, spec.value, not spec.moving, kind, number=i)
        m._claim(cname, c)
        m.coordinates.append(c)
        objects[i] = c
        return c

    # Points: every (x, y) pair an element uses, named after the x co-ordinate's number.
    pairs: dict[tuple[int, int], Point] = {}
    angle_use: set[int] = set()
    for _, etype, numbers in elements:
        nums = list(numbers)
        for kind in SLOTS[etype]:
            if kind == "P":
                ix, iy = nums[0], nums[1]
                nums = nums[2:]
                if (ix, iy) in pairs:
                    continue
                pname = declared.points.get((ix, iy)) or generated(f"P{ix}" if f"P{ix}" not in m else f"P{ix}_{iy}")
                cx = objects.get(ix) or new_coordinate(ix, f"{pname}.x", "x")
                cy = objects.get(iy) or new_coordinate(iy, f"{pname}.y", "y")
                p = Point(pname, cx, cy)
                cx.point = cx.point or p
                cy.point = cy.point or p
                m._claim(pname, p)
                m.points.append(p)
                pairs[(ix, iy)] = p
            else:
                if kind == "a":
                    angle_use.add(nums[0])
                nums = nums[1:]
    for i in sorted(by_number):
        if i not in objects:
            cname = declared.coordinates.get(i) or generated(f"x{i}")
            new_coordinate(i, cname, "angle" if i in angle_use else "scalar")

    made: list[Element] = []
    for k, etype, numbers in elements:
        nums = list(numbers)
        slots: list[Slot] = []
        for kind in SLOTS[etype]:
            if kind == "P":
                slots.append(pairs[(nums[0], nums[1])])
                nums = nums[2:]
            else:
                slots.append(objects[nums[0]])
                nums = nums[1:]
        el = Element(declared.elements.get(k) or generated(f"E{k}"), etype, slots)
        m._claim(el.name, el)
        m.elements.append(el)
        made.append(el)

    # Rows in destination order; a single form parameter with factor 1 becomes its element's own row.
    own: set[FormParameter] = set()

    def add_row(spec: DeclaredRow, kind: Literal["prescribed", "input", "output"], fallback: str) -> Row:
        terms = tuple((f, FormParameter(made[e - 1], form)) for e, form, f in spec.terms)
        fp = terms[0][1]
        single = len(terms) == 1 and terms[0][0] == 1.0 and fp not in own and kind != "output"
        given = declared.rows.get(spec.dest)
        if single and (given is not None or fp.label not in m):
            own.add(fp)
            row = Row(given or fp.label, kind, terms, spec.para, element=True)
        else:
            row = Row(given or generated(fallback), kind, terms, spec.para)
        m._claim(row.name, row)
        m.rows.append(row)
        return row

    for spec in prescribed:
        add_row(spec, "input" if spec.input is not None else "prescribed", f"row{spec.dest}")
    for spec in dependent:
        add_row(spec, "output", f"out{-spec.dest}")
    return m


def read_text(text: str, name: str, base_dir: Path, path: str | None = None) -> Mechanism:
    """Reads deck text into a mechanism; MOV_FUNC files are read from ``base_dir``."""
    d = _core.describe_deck_text(text, path or f"{name}.mec", os.fspath(base_dir))
    coords = [Declared(c.number, c.given, c.moving) for c in d.coordinates]
    elements = [(e.number, e.type, list(e.coords)) for e in d.elements]

    def declared_rows(specs: list[_core.EchoRow]) -> list[DeclaredRow]:
        return [DeclaredRow(r.dest, [(t.element, t.form, t.factor) for t in r.terms], r.para, r.input) for r in specs]

    m = topology(
        name,
        coords,
        elements,
        declared_rows(d.prescribed),
        declared_rows(d.dependent),
        DeckNames.of(d.names),
        Units.of(d.units),
    )
    nb = number_model(m)
    if d.motion is not None:
        mv = d.motion
        inputs: dict[InputKey, InputMotion] = {}
        for j, im in enumerate(mv.inputs, 1):
            key = nb.inputs[j - 1].name
            value = im.value
            if im.kind == "table":
                rows = np.asarray(im.rows, dtype=np.float64).reshape(-1, 4)
                inputs[key] = Table(rows[:, 1], rows[:, 2], rows[:, 3], rows[:, 0], im.file)
            elif value is None:
                raise ValueError(f"input {j}: a {im.kind} motion without a value")
            elif im.kind == "by":
                inputs[key] = By(value)
            elif im.kind == "to":
                inputs[key] = To(value)
            elif im.kind == "dynamic":
                inputs[key] = Dynamic(value)
            else:
                inputs[key] = Free(value)
        tol, max_iter = d.tol, d.max_iter
        rtol, atol = d.inttol or (None, None)
        m.motion = Motion(
            mv.steps,
            inputs,
            mv.dt,
            # The core's default (in metres) comes back in the model's length unit: equal to it within rounding.
            None if math.isclose(tol, DEFAULT_ACCURACY * scale("m", m.units.length), rel_tol=1e-12) else tol,
            None if max_iter == DEFAULT_MAX_ITER else max_iter,
            rtol,
            atol,
            d.integrator or "auto",
        )

    def ref_name(kind: str, v: int) -> Ref:
        if kind == "i":
            return nb.coords[v - 1].name
        if kind == "r":
            return nb.prescribed[v - 1].name if v > 0 else nb.dependent[-v - 1].name
        if kind == "e":
            return nb.elements[v - 1].name or v
        return nb.inputs[v - 1].name

    m.storage, bands = from_described(d.storage, ref_name)
    warn_bands_left_out(path or name, bands)
    stop = d.stop_when
    if stop is not None and m.motion is not None:
        m.motion = dataclasses.replace(m.motion, stop_when=(stop_name(m.storage, int(stop[0])), float(stop[1])))
    read_loads(m, nb, d.dynamics)
    return m


def read_loads(mech: Mechanism, nb: Numbering, d: _core.EchoDynamics | None) -> None:
    """Gives ``mech`` (read from a deck with the numbering ``nb``) the masses and loads of the deck's DYNAMICS
    block as the deck reader compiled them (``d``, None for a deck without one)."""
    if d is None:
        return
    mech.loads = loads.Loads()

    def row(dest: int) -> Row:
        return nb.prescribed[dest - 1] if dest > 0 else nb.dependent[-dest - 1]

    def point(x: int, y: int) -> tuple[Coordinate, Coordinate]:
        return nb.coords[x - 1], nb.coords[y - 1]

    for b in d.bodies:
        mech.mass(nb.elements[b.element - 1], b.mass, b.u, b.v, b.inertia)
    for p in d.point_masses:
        mech.point_mass(point(p.x, p.y), p.mass)
    for i in d.inertias:
        mech.inertia(nb.coords[i.coord - 1], i.inertia)
    if d.gravity != (0.0, 0.0):
        mech.gravity(*d.gravity)
    for f in d.forces:
        mech.force(point(f.x, f.y), f.fx, f.fy)
    for ld in d.loads:
        r = row(ld.dest)
        match ld.kind:
            case "LOAD":
                mech.load(r, _number(ld.value))
            case "LOADFUNC":
                t, values = zip(*ld.rows, strict=True)
                mech.load_table(r, list(t), list(values), file=ld.file)
            case "SPRING":
                mech.spring(r, _number(ld.k), _number(ld.e0), _number(ld.c))
            case _:
                mech.motor(r, _number(ld.t0), _number(ld.w0))


def _number(v: float | None) -> float:
    """A number a load of its kind always has (the compiled module gives None only to the other kinds')."""
    if v is None:
        raise ValueError("a load without the number its kind needs")
    return v


def write_text(mech: Mechanism, motion: Motion | None, storage: Storage | None) -> str:
    """The deck text of ``mech`` (:meth:`Mechanism.to_deck`)."""
    return write(mech, motion, storage).text


__all__ = ["DeckText", "Numbering", "read", "read_text", "save", "translate", "write", "FORMS"]
