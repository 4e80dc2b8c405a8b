"""A :class:`~mechfem.Mechanism` built into the core's model through the typed builder (``_core.ModelBuilder``),
without deck text.

The builder takes the model's items one call each, with deck numbers (:func:`mechfem.deck.deckio.number_model`) and the
model's names, in the order a deck states them, and compiles them with the deck reader's own compiler: the model
it gives is the one the deck text of the mechanism (:func:`mechfem.deck.deckio.write`) compiles to, to the last bit
(``tests/run/test_builder.py`` compares the two for every example). The builder takes a model's names and units as a
deck's NAMES block and UNITS line give them (``ModelBuilder.name``, ``ModelBuilder.units``); a mechanism gives them
the ones its deck says. Table motions and load tables are handed over as the files the deck would name, in a
temporary folder; no deck text is written or read.

Each item is noted with what it is and its name in the Python model (as :attr:`mechfem.deck.naming.DeckText.notes`
notes the lines of a written deck): a mistake the builder or the compiler finds (coincident points, a point on no
element, a zero length) names the item it is about by its number (the diagnostic's ``line``), and :func:`explain`
words it by the model's names from the notes, without deck text. A value no deck can state raises the deck writer's
``ValueError``, ``KeyError`` or ``TypeError`` here.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import mechfem._core as _core
from mechfem.deck import deckio
from mechfem.deck.explain import _DECK_FIELDS, _RULES, _Context, translate, with_attributes
from mechfem.deck.naming import DeckText, Numbering, names_block
from mechfem.errors import DeckError, MechfemError
from mechfem.model import loads
from mechfem.model.loads import Body, Force, Gravity, Inertia, Load, LoadTable, PointMass, Spring
from mechfem.model.mechanism import By, Dynamic, Element, Free, Mechanism, Motion, Storage, Table, To
from mechfem.model.stopping import stop_buffer
from mechfem.model.storage import check_animate_name, check_table_names
from mechfem.model.units import Units


def build(mech: Mechanism, motion: Motion | None, storage: Storage | None) -> tuple[_core.Model, Numbering]:
    """The compiled model of ``mech`` with ``motion`` and ``storage``, and its numbering."""
    b = builder(mech, motion, storage)
    with deckio.tables_dir(b.tables) as base:
        return b.builder.build(base), b.numbering


Note = tuple[str, str, str]
"""What an item is, its name in the Python model and the deck keyword that states it: ``("element", "crank",
"ELEM")``."""


class Built(NamedTuple):
    """A mechanism's items handed to the builder, not yet compiled: what compiles them (``build``, ``design``, a
    study's workers), the deck numbering they are given in, the table files (name: text) they read, the inputs
    that move under the forces, the name messages give the model, each item's note by its number and the model's
    mode (``KIN ANA``, ``DYN SIM``, ...)."""

    builder: _core.ModelBuilder
    numbering: Numbering
    tables: dict[str, str]
    simulated: list[str]
    path: str
    notes: dict[int, Note]
    mode: str


def builder(mech: Mechanism, motion: Motion | None, storage: Storage | None) -> Built:
    """``mech`` with ``motion`` and ``storage`` handed to the typed builder (see :class:`Built`)."""
    nb = deckio.number_model(mech)
    tables: dict[str, str] = {}
    simulated = _simulated(motion, nb)
    b = _core.ModelBuilder(f"{mech.name}.mec", loads.mode(mech, simulated))
    notes = _Notes(b)
    mode = loads.mode(mech, simulated)
    # The output name before the items, the table names after them (the items make the tables): the same refusals
    # as the deck writer's (check_file_names), from run, to_deck and save_deck.
    check_animate_name(mech.name, storage)
    try:
        _builder(b, notes, mech, motion, storage, nb, tables)
    except DeckError as e:
        # The builder names the item it refuses by the name it was given.
        raise refused(e, Built(b, nb, tables, simulated, f"{mech.name}.mec", notes.lines(), mode), mech.name) from None
    check_table_names(mech.name, tables)
    return Built(b, nb, tables, simulated, f"{mech.name}.mec", notes.lines(), mode)


def explain(
    err: MechfemError, built: Built, mech: Mechanism, motion: Motion | None, storage: Storage | None
) -> MechfemError:
    """The error of a run of the built model in the model's words (:func:`mechfem.deck.explain.translate`): an error of
    a run from the numbering; a model the builder or the compiler refused from the note of the item it is about."""
    if isinstance(err, DeckError):
        return refused(err, built, mech.name)
    words = DeckText("", built.path, {}, built.numbering, built.tables, built.simulated)
    return translate(err, words, mech.name)


def refused(err: DeckError, built: Built, model: str) -> DeckError:
    """A mistake the builder or the compiler found in the items of ``model``, in the model's words: ``name`` and
    ``what`` say which item it is about (``"C.x"``, ``"co-ordinate"``), and the diagnostic's fields that are not of a
    deck (``kind``, ``message``, ``hint``, ``element``, ``coordinate``, ``detail``, ...) stay; ``deck``, ``line``,
    ``column`` and ``text``, which place a mistake in deck text, are None: no deck was written."""
    what, name, keyword = built.notes.get(int(getattr(err, "line", 0) or 0), ("", "", ""))
    context = _Item(model, built.numbering, what, name, err, built.mode, keyword)
    rule = _RULES.get(str(getattr(err, "kind", "")))
    message = rule(context) if rule is not None else None
    if message is None:
        headline = str(getattr(err, "message", "") or str(err))
        where = f", {what} {name!r}" if what else ""
        message = f"in the mechanism {model!r}{where}: {headline}"
    new = DeckError(message)
    fields = {k: getattr(err, k) for k in _DECK_FIELDS if hasattr(err, k) and k not in ("column", "text")}
    with_attributes(new, **fields)
    with_attributes(
        new, path=built.path, line=None, column=None, text=None, deck=None, name=name or None, what=what or None
    )
    return new


class _Item(_Context):
    """What a rule of :mod:`mechfem.deck.explain` knows of an item: its keyword from its note, not from deck text."""

    def __init__(self, model: str, nb: Numbering, what: str, name: str, err: DeckError, mode: str, kw: str) -> None:
        super().__init__(model, nb, what, name, err, mode)
        self.kw = kw

    def keyword(self) -> str:
        return self.kw


class _Notes:
    """The note of each item handed to a builder, by item number: a call is noted before it is made, and the note
    goes to every item the call added (the one it refused included)."""

    def __init__(self, b: _core.ModelBuilder) -> None:
        self.b = b
        self.last = b.item
        self.pending: Note | None = None
        self._lines: dict[int, Note] = {}

    def __call__(self, what: str, name: str, keyword: str) -> None:
        self._flush()
        self.pending = (what, name, keyword)

    def _flush(self) -> None:
        if self.pending is not None:
            for k in range(self.last + 1, self.b.item + 1):
                self._lines[k] = self.pending
        self.last = self.b.item

    def lines(self) -> dict[int, Note]:
        """Every item's note; the last call's item, refused or not, is the number after those of the calls before."""
        self._flush()
        if self.pending is not None:
            self._lines.setdefault(self.last + 1, self.pending)
        return self._lines


def _simulated(motion: Motion | None, nb: Numbering) -> list[str]:
    """The names of the inputs that move under the forces (MOV_DYN)."""
    dynamic = [] if motion is None else [k for k, im in motion.inputs.items() if isinstance(im, Dynamic)]
    return [nb.inputs[nb.dof(k) - 1].name for k in dynamic]


def _builder(
    b: _core.ModelBuilder,
    note: _Notes,
    mech: Mechanism,
    motion: Motion | None,
    storage: Storage | None,
    nb: Numbering,
    tables: dict[str, str],
) -> None:
    if mech.units.deck_line() is not None:
        # The fields the deck writer's UNITS line gives: those that differ from a deck without one.
        default = Units()
        given = {k: (v if v != default.get(k) else None) for k, v in mech.units.as_dict().items()}
        note("units", str(mech.units), "UNITS")
        b.units(given["length"], given["angle"], given["mass"], given["force"], given["time"])
    coord = nb.coord_number
    element = {e: k for k, e in enumerate(nb.elements, 1)}
    for e in nb.elements:
        note("element", e.name, "ELEM")
        b.element(e.type, [coord[c] for c in e.coordinates], f"{e.name}: {' '.join(s.name for s in e.slots)}")
    for r in nb.rows:
        dest = nb.row_dest[r]
        formula = r.formula()
        comment = r.name if formula == r.name else f"{r.name}: {formula}"
        for f, p in r.terms:
            if p.element not in element:
                raise ValueError(f"row {r.name!r}: {p!r} belongs to another mechanism")
            note(r.kind, r.name, "FORM")
            b.form(p.form, element[p.element], dest, float(f), comment)
    n_dof = len(nb.inputs)
    note("inputs", ", ".join(r.name for r in nb.inputs), "NRDOF")
    b.nrdof(n_dof)
    for i, c in enumerate(nb.coords, 1):
        note("co-ordinate", c.name, "XFIX" if c.fixed else "XMOV")
        b.coordinate(i, float(c.value), not c.fixed, c.name)
    for r in nb.prescribed:
        if r.value is not None:
            note(r.kind, r.name, "PARA")
            b.para(nb.row_dest[r], float(r.value), r.name)
    for text, (what, name) in names_block(mech, nb):
        # The NAMES block the deck writer writes, line by line: a keyword, its numbers and the name.
        if text != "NAMES":
            kind, *numbers, label = text.split()
            note(what, name, "NAMES")
            b.name(kind, [int(n) for n in numbers], label)
    if mech.loads is not None:
        note("", "", "DYNAMICS")
        b.dynamics()
        _loads(b, note, mech, nb, element, tables)
    if motion is not None:
        _motion(b, note, mech, motion, nb, tables)
        integrator = None if motion.integrator == "auto" else motion.integrator
        note("motion", "", "INTEGRATOR")
        b.simulation(integrator, stop_buffer(motion, storage, mech.name))
    if storage is not None:
        _storage(b, note, mech, storage, nb)


def _loads(
    b: _core.ModelBuilder,
    note: _Notes,
    mech: Mechanism,
    nb: Numbering,
    element: dict[Element, int],
    tables: dict[str, str],
) -> None:
    """The masses and loads, as :func:`mechfem.model.loads.deck_lines` writes them."""
    assert mech.loads is not None
    i = nb.coord_number
    stem = deckio._file_stem(mech.name)
    n_tables = 0
    for it in mech.loads.in_deck_order():
        if isinstance(it, Body):
            e = it.element
            note("mass", e.name, "MASS")
            b.mass(element[e], float(it.mass), float(it.u), float(it.v), float(it.inertia), e.name)
        elif isinstance(it, PointMass):
            note("point mass", loads._label(it.x, it.y), "PMASS")
            b.point_mass(i[it.x], i[it.y], float(it.mass), loads._label(it.x, it.y))
        elif isinstance(it, Inertia):
            note("inertia", it.coordinate.name, "INERTIA")
            b.inertia(i[it.coordinate], float(it.inertia), it.coordinate.name)
        elif isinstance(it, Gravity):
            note("gravity", "", "GRAVITY")
            b.gravity(float(it.gx), float(it.gy))
        elif isinstance(it, Force):
            note("force", loads._label(it.x, it.y), "FORCE")
            b.force(i[it.x], i[it.y], float(it.fx), float(it.fy), loads._label(it.x, it.y))
        else:
            r, name = nb.row_dest[it.row], it.row.name
            if isinstance(it, Load):
                note("load", name, "LOAD")
                b.load(r, float(it.value), name)
            elif isinstance(it, LoadTable):
                n_tables += 1
                file = it.file or f"{stem}_load{n_tables}.dat"
                loads.add_table(tables, file, loads.table_text(it))
                note("load", name, "LOADFUNC")
                b.load_table(r, file, name)
            elif isinstance(it, Spring):
                note("load", name, "SPRING")
                b.spring(r, float(it.stiffness), float(it.free_value), float(it.damping), name)
            else:
                note("load", name, "MOTOR")
                b.motor(r, float(it.stall_torque), float(it.no_load_speed), name)


def _motion(
    b: _core.ModelBuilder, note: _Notes, mech: Mechanism, motion: Motion, nb: Numbering, tables: dict[str, str]
) -> None:
    """The motion, with the deck writer's checks (:func:`mechfem.deck.deckio.write`)."""
    per_dof = deckio.input_motions(mech, motion, nb)
    note("motion", "steps", "TSTEPE")
    b.movement(_whole(motion.steps, "the motion's steps"), float(motion.dt))
    for j, im in enumerate(per_dof, 1):
        name = nb.inputs[j - 1].name
        if isinstance(im, By):
            note("motion of input", name, "MOV_RELE")
            b.motion(j, "by", float(im.value), name)
        elif isinstance(im, To):
            note("motion of input", name, "MOV_ABSE")
            b.motion(j, "to", float(im.value), name)
        elif isinstance(im, Free):
            note("motion of input", name, "MOV_FREE")
            b.motion(j, "free", float(im.ds), name)
        elif isinstance(im, Dynamic):
            note("motion of input", name, "MOV_DYN")
            b.motion(j, "dynamic", float(im.value), name)
        elif isinstance(im, Table):
            file = im.file or f"{deckio._file_stem(mech.name)}_input{j}.dat"
            if any(ch.isspace() or ch == ";" for ch in file):
                raise ValueError(f"a table motion's file name (Table.file) cannot hold blanks or ';': {file!r}")
            loads.add_table(tables, file, deckio._table_text(im.rows(motion.dt), name))
            note("motion of input", name, "MOV_FUNC")
            b.motion_table(j, file, name)
        else:
            raise TypeError(f"not an input motion: {im!r}")
    accuracy = None if motion.accuracy is None else float(motion.accuracy)
    max_iter = None if motion.max_iter is None else int(motion.max_iter)
    note("motion", "accuracy, max_iter, rtol and atol", "ACCURACY")
    b.tolerances(accuracy, max_iter, deckio.inttol(motion))


def _storage(b: _core.ModelBuilder, note: _Notes, mech: Mechanism, storage: Storage, nb: Numbering) -> None:
    """The buffers, lists and pictures, their arguments in deck numbers."""
    note("", "", "STORAGE")
    b.storage()
    for n, kw, args in storage.buffers:
        note("buffer", str(n), kw)
        what = f"the buffer {n!r} of mechanism {mech.name!r}"
        b.buffer(kw, [_whole(a, what) for a in deckio.buffer_numbers(mech, nb, n, kw, args)], _whole(n, what))
    if storage.printbuf is not None:
        note("storage", "PRINTBUF", "PRINTBUF")
        b.printbuf([_whole(x, "Storage.printbuf") for x in storage.printbuf])
    if storage.savedata:
        note("storage", "SAVEDATA", "SAVEDATA")
        b.savedata([_whole(x, "Storage.savedata") for x in storage.savedata])
    if storage.animate:
        note("storage", "ANIMATE", "ANIMATE")
        b.animate(storage.animate)
    for pic in storage.pictures:
        if not pic.plots:
            raise ValueError(
                f"the storage of mechanism {mech.name!r}: picture {pic.title!r} has no plots; give at least one"
            )
        plots: list[tuple[str, int, int]] = []
        for kw, a, c in pic.plots:
            first, second = deckio.plot_numbers(mech, nb, kw, a, c)
            plots.append((kw, _whole(first, f"picture {pic.title!r}"), _whole(second, f"picture {pic.title!r}")))
        note("picture", pic.title, "BEGINPIC")
        b.picture(pic.title.replace(";", ",").rstrip(), plots)


def _whole(v: object, what: str) -> int:
    """A whole number as the deck reads one; a ValueError naming ``what`` gives it for anything else."""
    if isinstance(v, bool) or not isinstance(v, int | float) or not math.isfinite(v) or v != int(v):
        raise ValueError(f"{what}: {v!r} is not a whole number; give a whole number")
    return int(v)


__all__ = ["Built", "build", "builder", "explain"]
