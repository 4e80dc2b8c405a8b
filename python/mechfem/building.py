"""A :class:`~mechfem.Mechanism` built into the core's model through the typed builder (``_core.ModelBuilder``),
without deck text.

The builder takes the model's items one call each, with deck numbers (:func:`mechfem.deckio.number_model`) and the
model's names, in the order a deck states them, and compiles them with the deck reader's own compiler: the model
it gives is the one the deck text of the mechanism (:func:`mechfem.deckio.write`) compiles to, to the last bit
(``tests/test_builder.py`` compares the two for every example). The builder takes a model's names and units as a
deck's NAMES block and UNITS line give them (``ModelBuilder.name``, ``ModelBuilder.units``); a mechanism gives them
the ones its deck says. Table motions and load tables are handed over as the files the deck would name, in a
temporary folder; no deck text is written or read.

A mistake the builder or the compiler finds raises :class:`~mechfem.DeckError`; so does the Python side of the
model (a ``ValueError``, ``KeyError`` or ``TypeError``) for what the deck writer refuses.
"""

from __future__ import annotations

import mechfem._core as _core
from mechfem import deckio, loads
from mechfem.deck_names import names_block
from mechfem.loads import Body, Force, Gravity, Inertia, Load, LoadTable, PointMass, Spring
from mechfem.model import By, Dynamic, Element, Free, Mechanism, Motion, Storage, Table, To
from mechfem.numbering import Numbering
from mechfem.stopping import stop_buffer
from mechfem.storage import check_file_names
from mechfem.units import Units


def build(mech: Mechanism, motion: Motion | None, storage: Storage | None) -> tuple[_core.Model, Numbering]:
    """The compiled model of ``mech`` with ``motion`` and ``storage``, and its numbering."""
    nb = deckio.number_model(mech)
    tables: dict[str, str] = {}
    builder = _builder(mech, motion, storage, nb, tables)
    check_file_names(mech.name, storage, tables)
    with deckio.tables_dir(tables) as base:
        return builder.build(base), nb


def _builder(
    mech: Mechanism, motion: Motion | None, storage: Storage | None, nb: Numbering, tables: dict[str, str]
) -> _core.ModelBuilder:
    dynamic = [] if motion is None else [k for k, im in motion.inputs.items() if isinstance(im, Dynamic)]
    simulated = [nb.inputs[nb.dof(k) - 1].name for k in dynamic]
    b = _core.ModelBuilder(f"{mech.name}.mec", loads.mode(mech, simulated))
    if mech.units.deck_line() is not None:
        # The fields the deck writer's UNITS line gives: those that differ from a deck without one.
        default = Units()
        given = {k: (v if v != default.get(k) else None) for k, v in mech.units.as_dict().items()}
        b.units(given["length"], given["angle"], given["mass"], given["force"], given["time"])
    coord = nb.coord_number
    element = {e: k for k, e in enumerate(nb.elements, 1)}
    for e in nb.elements:
        b.element(e.type, [coord[c] for c in e.coordinates], f"{e.name}: {' '.join(s.name for s in e.slots)}")
    for r in nb.rows:
        dest = nb.row_dest[r]
        formula = r.formula()
        comment = r.name if formula == r.name else f"{r.name}: {formula}"
        for f, p in r.terms:
            if p.element not in element:
                raise ValueError(f"row {r.name!r}: {p!r} belongs to another mechanism")
            b.form(p.form, element[p.element], dest, float(f), comment)
    n_dof = len(nb.inputs)
    b.nrdof(n_dof)
    for i, c in enumerate(nb.coords, 1):
        b.coordinate(i, float(c.value), not c.fixed, c.name)
    for r in nb.prescribed:
        if r.value is not None:
            b.para(nb.row_dest[r], float(r.value), r.name)
    for text, _ in names_block(mech, nb):
        # The NAMES block the deck writer writes, line by line: a keyword, its numbers and the name.
        if text != "NAMES":
            kind, *numbers, name = text.split()
            b.name(kind, [int(n) for n in numbers], name)
    if mech.loads is not None:
        b.dynamics()
        _loads(b, mech, nb, element, tables)
    if motion is not None:
        _motion(b, mech, motion, nb, tables)
        integrator = None if motion.integrator == "auto" else motion.integrator
        b.simulation(integrator, stop_buffer(motion, storage, mech.name))
    if storage is not None:
        _storage(b, mech, storage, nb)
    return b


def _loads(
    b: _core.ModelBuilder, mech: Mechanism, nb: Numbering, element: dict[Element, int], tables: dict[str, str]
) -> None:
    """The masses and loads, as :func:`mechfem.loads.deck_lines` writes them."""
    assert mech.loads is not None
    i = nb.coord_number
    stem = deckio._file_stem(mech.name)
    n_tables = 0
    for it in mech.loads.in_deck_order():
        if isinstance(it, Body):
            e = it.element
            b.mass(element[e], float(it.mass), float(it.u), float(it.v), float(it.inertia), e.name)
        elif isinstance(it, PointMass):
            b.point_mass(i[it.x], i[it.y], float(it.mass), loads._label(it.x, it.y))
        elif isinstance(it, Inertia):
            b.inertia(i[it.coordinate], float(it.inertia), it.coordinate.name)
        elif isinstance(it, Gravity):
            b.gravity(float(it.gx), float(it.gy))
        elif isinstance(it, Force):
            b.force(i[it.x], i[it.y], float(it.fx), float(it.fy), loads._label(it.x, it.y))
        else:
            r, name = nb.row_dest[it.row], it.row.name
            if isinstance(it, Load):
                b.load(r, float(it.value), name)
            elif isinstance(it, LoadTable):
                n_tables += 1
                file = it.file or f"{stem}_load{n_tables}.dat"
                loads.add_table(tables, file, loads.table_text(it))
                b.load_table(r, file, name)
            elif isinstance(it, Spring):
                b.spring(r, float(it.stiffness), float(it.free_value), float(it.damping), name)
            else:
                b.motor(r, float(it.stall_torque), float(it.no_load_speed), name)


def _motion(b: _core.ModelBuilder, mech: Mechanism, motion: Motion, nb: Numbering, tables: dict[str, str]) -> None:
    """The motion, with the deck writer's checks (:func:`mechfem.deckio.write`)."""
    per_dof = deckio.input_motions(mech, motion, nb)
    b.movement(_whole(motion.steps), float(motion.dt))
    for j, im in enumerate(per_dof, 1):
        name = nb.inputs[j - 1].name
        if isinstance(im, By):
            b.motion(j, "by", float(im.value), name)
        elif isinstance(im, To):
            b.motion(j, "to", float(im.value), name)
        elif isinstance(im, Free):
            b.motion(j, "free", float(im.ds), name)
        elif isinstance(im, Dynamic):
            b.motion(j, "dynamic", float(im.value), name)
        elif isinstance(im, Table):
            file = im.file or f"{deckio._file_stem(mech.name)}_input{j}.dat"
            loads.add_table(tables, file, deckio._table_text(im.rows(motion.dt), name))
            b.motion_table(j, file, name)
        else:
            raise TypeError(f"not an input motion: {im!r}")
    accuracy = None if motion.accuracy is None else float(motion.accuracy)
    max_iter = None if motion.max_iter is None else int(motion.max_iter)
    b.tolerances(accuracy, max_iter, deckio.inttol(motion))


def _storage(b: _core.ModelBuilder, mech: Mechanism, storage: Storage, nb: Numbering) -> None:
    """The buffers, lists and pictures, their arguments in deck numbers."""
    b.storage()
    for n, kw, args in storage.buffers:
        b.buffer(kw, [_whole(a) for a in deckio.buffer_numbers(mech, nb, n, kw, args)], _whole(n))
    if storage.printbuf is not None:
        b.printbuf([_whole(x) for x in storage.printbuf])
    if storage.savedata:
        b.savedata([_whole(x) for x in storage.savedata])
    if storage.animate:
        b.animate(storage.animate)
    for pic in storage.pictures:
        if not pic.plots:
            raise ValueError(f"picture {pic.title!r} has no plots")
        plots: list[tuple[str, int, int]] = []
        for kw, a, c in pic.plots:
            first, second = deckio.plot_numbers(mech, nb, kw, a, c)
            plots.append((kw, _whole(first), _whole(second)))
        b.picture(pic.title.replace(";", ",").rstrip(), plots)


def _whole(v: object) -> int:
    """A whole number as the deck reads one; a ValueError for anything else (the deck writer then names it)."""
    if isinstance(v, bool) or not isinstance(v, int | float) or v != int(v):
        raise ValueError(f"not a whole number: {v!r}")
    return int(v)


__all__ = ["build"]
