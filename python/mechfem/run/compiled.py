"""The compiled models of a named :class:`~mechfem.Mechanism`, kept by the mechanism per topology.

A mechanism is built into the core's model (:func:`mechfem.run.building.build`, no deck text) once per *topology*:
everything its deck would say apart from the numbers a compiled model takes anew at every run, the values of the
co-ordinates (XFIX, XMOV) and the prescribed values and input starts (PARA). A run of a mechanism whose topology is
unchanged builds nothing: :func:`kept_model` gives the compiled model, the numbering of the mechanism and
its numbers as changes, taken from its parts.

The topology (:func:`topology`) is what the deck writer puts on the deck's lines besides those numbers, in deck
numbers: the mechanism's name, its elements (types and co-ordinates), which co-ordinates are fixed, its rows (kind,
terms, whether a value is given), its masses and loads, motion and storage. What a deck reader derives from the
co-ordinates when it compiles (the directions its elements track their angles from, the value of a row the deck
gives none) the compiled model derives again from the co-ordinates of every run (``Mechanism::start_state`` in the
core), so a kept model gives to the last bit what the deck text gives whatever its points' positions.

A model that needs files beside it (a table motion, a load table) has no kept model: it is built for each run.

The compiled models belong to the mechanism (:class:`Kept`, held in its ``_kept`` attribute): they go with it, a
variant (a deep copy) starts with its original's, and a pickled mechanism takes none along (the other process
compiles its own).

Working out the topology walks the whole model, which costs about as much as a short run. So each mechanism also
remembers what its last run read (:func:`_shape`): the same objects, with the attributes the numbering and the
topology read from them. While that is unchanged, so are the numbering and the topology, and the run takes the model
its last run had without working either out again.
"""

from __future__ import annotations

import math
import threading
from collections.abc import Hashable, Mapping
from dataclasses import dataclass, fields
from typing import Any

import mechfem._core as _core
from mechfem.deck import deckio
from mechfem.deck.naming import Numbering, number
from mechfem.model.loads import Loads, LoadTable
from mechfem.model.mechanism import Mechanism
from mechfem.model.motion import Free, Motion, Table, To, check_units, input_dof
from mechfem.model.parts import Coordinate, Element, Row
from mechfem.model.storage import Storage
from mechfem.run import building

Change = tuple[int, int, float]
"""A number of a compiled deck, as ``_core.Model.run`` takes it: (0, co-ordinate, value) for XFIX and XMOV, (1, row,
value) for PARA."""


_KEEP = 4
"""How many topologies a mechanism keeps compiled models for."""
# Runs on several threads share a mechanism's kept models.
_LOCK = threading.Lock()


@dataclass
class _Last:
    """What the last run of one mechanism read, and what it ran on."""

    shape: tuple[object, ...]
    model: _core.Model
    numbering: Numbering
    quiet_units: str | None = None
    """The angle unit in which the motion's units were last checked and had nothing to say: the shape holds the
    motion and its inputs (immutable) and the inputs' start values, so the same check would say nothing again."""


class Kept:
    """The compiled models of one mechanism by topology (the least recently used first), and what its last run
    read. A compiled model is immutable: copies of the mechanism share it."""

    __slots__ = ("by_topology", "last")

    def __init__(self, by_topology: dict[Hashable, _core.Model] | None = None) -> None:
        self.by_topology: dict[Hashable, _core.Model] = {} if by_topology is None else by_topology
        self.last: _Last | None = None

    def __deepcopy__(self, memo: dict[int, Any]) -> Kept:
        # A variant has other objects, so what the last run read is not its own.
        with _LOCK:
            return Kept(dict(self.by_topology))

    def __reduce__(self) -> tuple[type[Kept], tuple[()]]:
        return (Kept, ())

    def models(self) -> list[_core.Model]:
        """The kept models, the least recently used first."""
        with _LOCK:
            return list(self.by_topology.values())


def kept(mech: Mechanism) -> Kept:
    """The compiled models ``mech`` keeps (none yet for a mechanism never run)."""
    attributes = vars(mech)
    # Reading one attribute needs no lock (nor does a run of a mechanism that has its models); making them does.
    out = attributes.get("_kept")
    if type(out) is Kept:
        return out
    with _LOCK:
        out = attributes.get("_kept")
        if not isinstance(out, Kept):
            out = attributes["_kept"] = Kept()
    return out


def kept_model(
    mech: Mechanism, motion: Motion | None, storage: Storage | None
) -> tuple[_core.Model, Numbering, list[Change]] | None:
    """The compiled model of ``mech`` with ``motion`` and ``storage`` (compiled only when its topology is new), its
    numbering and its numbers as changes; None for a mechanism that is not kept: one whose model needs files (it is
    built for each run), and one that the deck writer or reader would refuse (its deck text names the mistake).

    Building raises the deck reader's :class:`~mechfem.DeckError` (deck numbers, as ``_core.ModelBuilder`` gives
    it)."""
    shape = _shape(mech, motion, storage)
    models = kept(mech)
    last = models.last
    if last is not None and last.shape == shape:
        changes = _changes(last.numbering)
        if changes is None:
            return None
        angle = mech.units.angle
        if motion is not None and last.quiet_units != angle:
            last.quiet_units = angle if check_units(motion, last.numbering.inputs, angle) else None
        return last.model, last.numbering, changes
    numbering = deckio.number_model(mech)
    key = topology(mech, motion, storage, numbering)
    if key is None:
        return None
    changes = _changes(numbering)
    if changes is None:
        return None
    by_topology = models.by_topology
    with _LOCK:
        model = by_topology.pop(key, None)
        if model is not None:
            # The most recently used last.
            by_topology[key] = model
    quiet = None
    if model is not None:
        # The deck writer checks the motion's units at every run: so does a kept model.
        if motion is not None and check_units(motion, numbering.inputs, mech.units.angle):
            quiet = mech.units.angle
    else:
        try:
            model, _ = building.build(mech, motion, storage)
        except (KeyError, ValueError, TypeError):
            return None
        with _LOCK:
            by_topology.pop(key, None)
            while len(by_topology) >= _KEEP:
                by_topology.pop(next(iter(by_topology)))
            by_topology[key] = model
    with _LOCK:
        models.last = _Last(shape, model, numbering, quiet)
    return model, numbering, changes


def _shape(mech: Mechanism, motion: Motion | None, storage: Storage | None) -> tuple[object, ...]:
    """Everything :func:`deckio.number_model` and :func:`topology` read, apart from the numbers a kept model takes
    anew at every run: each object by identity, with the attributes read from it. Equal shapes number the model alike
    and make equal topologies.

    The values of the inputs stand in it, since a :class:`~mechfem.model.motion.To` motion is checked against its
    input's start; so does the count of names, which resolve a buffer's arguments (a mechanism only ever adds names)."""
    rows = mech.rows
    loads = mech.loads
    return (
        mech.name,
        len(mech._names) + sum(map(len, mech._shared.values())),
        [(c, c.fixed, c.number) for c in mech.coordinates],
        [(p, p.x, p.y) for p in mech.points],
        [(e, e.type, e.slots) for e in mech.elements],
        [(r, r.kind, r.name, r.value is None, r.terms) for r in rows],
        # One comprehension over every term (a comprehension a row would cost a call each).
        [(p, p.element, p.form) for r in rows for _, p in r.terms],
        [r.value for r in rows if r.kind == "input"],
        None if loads is None else (loads, list(loads.items)),
        None if motion is None else (motion, list(motion.inputs.items())),
        None if storage is None else _storage_shape(storage),
    )


def _storage_shape(storage: Storage) -> tuple[object, ...]:
    """The storage block's lists as they are now (a storage is changed in place by :meth:`Storage.buffer`)."""
    printbuf = None if storage.printbuf is None else list(storage.printbuf)
    pictures = [(p, p.title, list(p.plots)) for p in storage.pictures]
    return (storage, list(storage.buffers), printbuf, list(storage.savedata), storage.animate, pictures)


def topology(
    mech: Mechanism, motion: Motion | None, storage: Storage | None, numbering: Numbering
) -> tuple[object, ...] | None:
    """What the deck of ``mech`` (numbered ``numbering``) with ``motion`` and ``storage`` says besides the numbers
    of XFIX, XMOV and PARA; None when the deck
    needs files beside it, or when the deck writer would refuse the model (it then says why)."""
    try:
        return _topology(mech, motion, storage, numbering)
    except (KeyError, ValueError, TypeError):
        return None


def _topology(
    mech: Mechanism, motion: Motion | None, storage: Storage | None, nb: Numbering
) -> tuple[object, ...] | None:
    element = {e: k for k, e in enumerate(nb.elements, 1)}
    coord = nb.coord_number
    elements = tuple([(e.type, *[coord[c] for c in e.coordinates]) for e in nb.elements])
    rows = tuple(
        [(r.kind, r.value is None, *[(number(f), p.form, element[p.element]) for f, p in r.terms]) for r in nb.rows]
    )
    fixed = tuple([bool(c.fixed) for c in nb.coords])
    loads = None if mech.loads is None else _loads(mech.loads, nb, element)
    moves = None if motion is None else _motion(motion, nb)
    stored = None if storage is None else _storage(mech, storage, nb)
    if (mech.loads is not None and loads is None) or (motion is not None and moves is None):
        return None
    return (mech.name, elements, rows, fixed, loads, moves, stored)


def _loads(loads: Loads, nb: Numbering, element: dict[Element, int]) -> tuple[object, ...] | None:
    """The DYNAMICS block in deck numbers; None with a load table, whose file the deck needs beside it."""
    if any(isinstance(it, LoadTable) for it in loads):
        return None

    def ref(v: object) -> object:
        if isinstance(v, Element):
            return element[v]
        if isinstance(v, Coordinate):
            return nb.coord_number[v]
        if isinstance(v, Row):
            return nb.row_dest[v]
        return number(v) if isinstance(v, float | int) else v

    return tuple([(type(it).__name__, *[ref(getattr(it, f.name)) for f in fields(it)]) for it in loads.in_deck_order()])


def _motion(motion: Motion, nb: Numbering) -> tuple[object, ...] | None:
    """The MOVEMENT block per DOF; None for one the deck writer or reader refuses, and with a table motion, whose
    file the deck needs beside it."""
    inputs = nb.inputs
    time = motion.steps * motion.dt
    per_dof: dict[int, tuple[str, str]] = {}
    for key, im in motion.inputs.items():
        j = input_dof(key, inputs)
        if isinstance(im, Table) or j in per_dof or (isinstance(im, Free) and len(inputs) != 1):
            return None
        value = im.ds if isinstance(im, Free) else im.value
        # The deck reader refuses an end the input cannot reach at a rate a number can hold.
        start = inputs[j - 1].value
        if isinstance(im, To) and start is not None and not math.isfinite((value - start) / time):
            return None
        per_dof[j] = (type(im).__name__, number(value))
    if len(per_dof) != len(inputs):
        return None
    tolerances = (motion.accuracy, motion.max_iter, motion.rtol, motion.atol)
    return (
        motion.steps,
        number(motion.dt),
        *[per_dof[j] for j in range(1, len(inputs) + 1)],
        tuple([None if v is None else number(v) for v in tolerances]),
        motion.integrator,
        motion.stop_when,
    )


def _storage(mech: Mechanism, storage: Storage, nb: Numbering) -> tuple[object, ...]:
    """The STORAGE block in deck numbers."""
    buffers = tuple([(b, kw, *deckio.buffer_numbers(mech, nb, b, kw, args)) for b, kw, args in storage.buffers])
    pictures = tuple(
        [
            (
                pic.title.replace(";", ",").rstrip(),
                *[(kw, *deckio.plot_numbers(mech, nb, kw, a, b)) for kw, a, b in pic.plots],
            )
            for pic in storage.pictures
        ]
    )
    printbuf = None if storage.printbuf is None else tuple(map(str, storage.printbuf))
    return (buffers, printbuf, tuple(map(str, storage.savedata)), storage.animate, pictures)


def changes_of(values: Mapping[Row | Coordinate, float], nb: Numbering) -> list[Change]:
    """``values`` of co-ordinates (XFIX, XMOV) and prescribed rows (PARA) as changes of the deck numbered ``nb``."""
    return [
        (0, nb.coord_number[obj], float(v)) if isinstance(obj, Coordinate) else (1, nb.row_dest[obj], float(v))
        for obj, v in values.items()
    ]


def _changes(nb: Numbering) -> list[Change] | None:
    """The numbers of XFIX, XMOV and PARA; None when one is not finite or when a constant length is not above
    zero, which the deck reader refuses (with a message the kept model could not give)."""
    changes = [(0, i, float(c.value)) for i, c in enumerate(nb.coords, 1)]
    for k, r in enumerate(nb.prescribed, 1):
        if r.value is None:
            continue
        if r.kind == "prescribed" and len(r.terms) == 1 and r.terms[0][1].form == "LENL":
            if not r.value / r.terms[0][0] > 0:
                return None
        changes.append((1, k, float(r.value)))
    # A NaN or an infinity makes the sum not finite (and so do values large enough to overflow it: the deck text
    # runs those too).
    return changes if math.isfinite(sum([v for _, _, v in changes])) else None


__all__ = ["Change", "Kept", "changes_of", "kept", "kept_model", "topology"]
