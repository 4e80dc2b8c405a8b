"""A named mechanism runs on its compiled model, kept per topology (mechfem.run.compiled): a run after a change of its
numbers gives to the last bit what the deck text written for it gives, a change of its topology compiles it again
(the mechanism keeps its compiled models),
and the type Mechanism.run declares is the result it gives (mechfem.RunResult)."""

from __future__ import annotations

import math
import warnings
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np
import pytest

import mechfem
from mechfem import Driven, Keep, Mechanism, Motion, Output, _core
from mechfem.deck import deckio
from mechfem.model.storage import Picture, Storage
from mechfem.results.result import Analysis
from mechfem.run import compiled

ROOT = Path(__file__).resolve().parents[2]


def fourbar(b0x: float = 4.0, crank: float = 1.0, start: float | None = 0.3, coupler: Any = 3.5) -> Mechanism:
    m = Mechanism("fourbar")
    A0, B0 = m.fixed("A0", 0.0, 0.0), m.fixed("B0", b0x, 0.0)
    A, B = m.point("A", 1.0, 0.3), m.point("B", 3.5, 2.5)
    m.bar("crank", A0, A, length=crank, angle=Driven(start=start))
    m.bar("coupler", A, B, length=coupler)
    m.bar("rocker", B0, B, length=3.0, angle=Output("psi"))
    m.motion = Motion.by(72, 2 * math.pi)
    m.storage = Storage().buffer(1, "BUFX0", "B.x").buffer(2, "BUFKE1", "psi", "crank.angle")
    return m


def deck_text_run(m: Mechanism) -> _core.Run:
    """The run of the deck text written for ``m``: what a kept model must give."""
    deck = deckio.write(m, m.motion, m.storage)
    return _core.run_deck_text(deck.text, deck.path, ".")


def assert_same(a: mechfem.Analysis, d: _core.Run) -> None:
    assert np.array_equal(a.coords, d.coords)
    assert np.array_equal(np.asarray(a._raw.table), d.table, equal_nan=True)
    assert a._raw.model == d.model
    assert a._raw.storage == d.storage and a._raw.buffer_numbers == d.buffer_numbers
    assert np.array_equal(np.asarray(a._raw.buffers), d.buffers, equal_nan=True)


def kept_models(m: Mechanism) -> list[_core.Model]:
    """The compiled models ``m`` keeps, the most recently used last."""
    return compiled.kept(m).models()


def test_a_changed_value_runs_as_a_fresh_mechanism_with_it(monkeypatch: pytest.MonkeyPatch) -> None:
    m = fourbar()
    first = m.run()
    assert_same(first, deck_text_run(m))
    kept = kept_models(m)[-1]

    # No deck text is written for the same topology: the numbers go to the kept model.
    def no_text(*args: object, **kwargs: object) -> None:
        raise AssertionError("a deck was written for a kept topology")

    monkeypatch.setattr(deckio, "write", no_text)
    m.set("crank.length", 1.1)
    m.set("B0", (4.2, 0.0))
    m.set("B", (3.6, 2.4))
    m.set("crank.angle", 0.5)
    again = m.run()
    assert kept_models(m)[-1] is kept
    monkeypatch.undo()

    fresh = fourbar(b0x=4.2, crank=1.1, start=0.5)
    fresh.set("B", (3.6, 2.4))
    want = deck_text_run(fresh)
    assert_same(again, want)
    assert_same(fresh.run(), want)
    assert not np.array_equal(again.coords, first.coords)


def test_a_topology_change_compiles_again() -> None:
    m = fourbar()
    m.run()
    before = len(kept_models(m))
    kept = kept_models(m)[-1]
    storage = m.storage
    assert storage is not None
    changes = [
        lambda: setattr(m, "motion", Motion.by(36, math.pi)),
        lambda: storage.buffer(3, "BUFDET"),
        lambda: m.output("coupler angle", m["coupler"].angle),
        lambda: m.bar("stay", m.fixed("C0", 1.0, 1.0), m["B"]),
        lambda: setattr(m["crank.angle"], "value", None),  # the start taken from the co-ordinates: no PARA line
    ]
    for change in changes:
        change()
        r = m.run()
        assert kept_models(m)[-1] is not kept
        kept = kept_models(m)[-1]
        assert_same(r, deck_text_run(m))
    assert len(kept_models(m)) == min(before + len(changes), compiled._KEEP)


def test_a_row_without_value_takes_it_from_the_coordinates_it_has_now() -> None:
    # The coupler's length and the crank's start are those at the co-ordinates of the run, not of the compilation:
    # the same compiled model serves, and gives what the deck text with the new co-ordinates gives.
    m = fourbar(start=None, coupler=Keep())
    m.run()
    kept = kept_models(m)[-1]
    m.set("B", (3.4, 2.6))
    r = m.run()
    assert kept_models(m)[-1] is kept
    assert_same(r, deck_text_run(m))
    assert r.output("coupler.length")[0] == pytest.approx(math.hypot(2.4, 2.3))
    m.set("B0", (4.1, 0.0))
    assert_same(m.run(), deck_text_run(m))
    assert kept_models(m)[-1] is kept


def crossing(by: float) -> Mechanism:
    """A four-bar whose rocker B0->B points left, just above (``by`` > 0) or just below the x axis."""
    m = Mechanism("crossing")
    A0, B0 = m.fixed("A0", 0.0, 0.0), m.fixed("B0", 4.0, 0.0)
    A, B = m.point("A", 1.0, 0.0), m.point("B", 1.6, by)
    m.bar("crank", A0, A, length=1.0, angle=Driven(start=0.0))
    m.bar("coupler", A, B, length=3.2)
    m.bar("rocker", B0, B, length=2.5, angle=Output("psi"))
    m.motion = Motion.by(36, 2 * math.pi)
    return m


def test_an_element_turned_across_its_branch_tracks_its_angle_from_there() -> None:
    # The rocker B0->B points left, just above the x axis (about 177 degrees), then just below it (-177): the
    # angle it tracks starts from its direction at the co-ordinates of the run, with the same compiled model.
    m = crossing(0.1)
    assert_same(m.run(), deck_text_run(m))
    kept = kept_models(m)[-1]
    m.set("B", (1.6, -0.1))
    r = m.run()
    assert kept_models(m)[-1] is kept
    assert_same(r, deck_text_run(m))
    assert_same(crossing(-0.1).run(), deck_text_run(m))


def test_mistakes_in_the_numbers_are_named_by_the_deck_reader() -> None:
    m = fourbar()
    m.run()
    m.set("A", (0.0, 0.0))
    with pytest.raises(mechfem.DeckError, match="its points A0 and A coincide"):
        m.run()
    m.set("A", (1.0, 0.3))
    m.set("crank.length", 0.0)
    with pytest.raises(mechfem.DeckError, match="a length must be greater than zero"):
        m.run()
    m.set("crank.length", 1.0)
    assert_same(m.run(), deck_text_run(m))


@pytest.mark.parametrize("path", sorted(ROOT.glob("examples/*/*.mec")), ids=lambda p: p.name)
def test_every_example_runs_on_its_kept_model_as_its_deck_text(path: Path) -> None:
    if "KIN OPT" in path.read_text():
        pytest.skip("an optimisation deck")
    m = Mechanism.from_deck(path)
    for _ in range(2):
        with warnings.catch_warnings():
            # The decks of limit positions stop early, and say so.
            warnings.simplefilter("ignore", mechfem.IncompleteRunWarning)
            r = m.run(order=2, progress=False)
        deck = deckio.write(m, m.motion, m.storage)
        with deckio.tables_dir(deck.tables) as base:
            want = _core.run_deck_text(deck.text, deck.path, base)
        assert_same(r, want)
        # Then every prescribed value a little other, as the kept model takes them.
        for row in m.rows:
            if row.kind == "prescribed" and row.value is not None:
                row.value = row.value * (1 + 1e-9)


def test_mechanism_run_is_declared_to_return_the_result_it_gives() -> None:
    import typing

    a = fourbar().run()
    assert isinstance(a, Analysis)
    for method in (Mechanism.run, Mechanism.check, Mechanism.simulate):
        # The model imports RunResult for type checking only (it sits below the result): resolved here.
        hints = typing.get_type_hints(method, localns={"RunResult": mechfem.RunResult})
        assert hints["return"] is type(a), method.__name__


def same_as_deck_text(m: Mechanism) -> bool:
    """``m.run()`` gives what the deck text written for ``m`` now gives, or the same error; True when it ran."""
    try:
        want = deck_text_run(m)
    except mechfem.MechfemError as e:
        with pytest.raises(type(e)):
            m.run(progress=False)
        return False
    assert_same(m.run(progress=False), want)
    return True


def test_a_mechanism_unchanged_since_its_last_run_is_not_numbered_again(monkeypatch: pytest.MonkeyPatch) -> None:
    m = fourbar()
    first = m.run()

    def no_numbering(*args: object, **kwargs: object) -> None:
        raise AssertionError("numbered again")

    monkeypatch.setattr(deckio, "number_model", no_numbering)
    m.set("crank.length", 1.05)  # a number, not the topology
    m.set("B", (3.6, 2.4))
    again = m.run()
    monkeypatch.undo()
    assert again.numbering is first.numbering
    assert_same(again, deck_text_run(m))
    assert not np.array_equal(again.coords, first.coords)


def changes_in_place(m: Mechanism) -> list[Any]:
    """Changes of what a deck says besides its numbers, each made in place on the parts of ``m``."""
    from mechfem.model.loads import Gravity
    from mechfem.model.motion import By

    storage = m.storage
    assert storage is not None
    inputs = {None: By(math.pi)}
    psi = m["psi"]

    def motion_in_place() -> None:
        m.motion = Motion(36, inputs)
        m.run(progress=False)
        inputs[None] = By(0.5 * math.pi)

    def gravity_in_place() -> None:
        m.gravity(0.0, -9.81)
        m.mass("coupler", 2.0)
        m.run(progress=False)
        assert m.loads is not None
        m.loads.items[0] = Gravity(0.0, -1.0)

    def printbuf_in_place() -> None:
        storage.printbuf = [1]
        m.run(progress=False)
        storage.printbuf.append(2)

    def picture_in_place(change: Callable[[Picture], object]) -> Callable[[], None]:
        def made() -> None:
            storage.picture("first", ("PLOTFUNC", 1, 2))
            m.run(progress=False)
            change(storage.pictures[0])

        return made

    return [
        lambda: storage.buffers.__setitem__(0, (1, "BUFX0", ("A.y",))),
        lambda: storage.buffers.append((7, "BUFDET", ())),
        lambda: storage.savedata.append(1),
        lambda: setattr(storage, "printbuf", [1]),
        printbuf_in_place,
        lambda: storage.picture("first", ("PLOTFUNC", 1, 2)),
        picture_in_place(lambda pic: pic.plots.append(("PLOTHODO", "B", "B"))),
        picture_in_place(lambda pic: setattr(pic, "title", "renamed")),
        lambda: setattr(storage, "animate", "film"),
        motion_in_place,
        gravity_in_place,
        lambda: setattr(m["B0.y"], "fixed", False),
        lambda: setattr(m["A.x"], "number", 20),
        lambda: setattr(m["rocker"], "slots", (m["B"], m["B0"])),
        lambda: setattr(m["rocker"], "type", "HLF"),
        lambda: setattr(m["B"], "y", m["A.y"]),
        lambda: setattr(psi, "terms", ((1.0, m["coupler"].angle),)),
        lambda: setattr(psi.terms[0][1], "form", "LENL"),
        lambda: setattr(psi, "kind", "prescribed"),
        lambda: setattr(m["crank.angle"], "value", None),
        lambda: setattr(m, "name", "renamed"),
    ]


def test_every_change_in_place_since_the_last_run_is_run_as_its_deck_text() -> None:
    # The last run's shape stands for the topology: whatever a change in place touches, the next run is that of the
    # deck text the mechanism now writes, as a fresh mechanism's would be.
    ran = []
    for k in range(len(changes_in_place(fourbar()))):
        m = fourbar()
        assert same_as_deck_text(m)
        changes_in_place(m)[k]()
        try:
            ran.append(same_as_deck_text(m))
        except AssertionError as e:
            raise AssertionError(f"change {k}: {e}") from None
    # Most changes make a mechanism that runs, so that what it gives is compared, not only its error.
    assert sum(ran) >= 0.75 * len(ran), ran


def test_the_last_run_of_a_mechanism_does_not_keep_it_alive() -> None:
    import gc
    import weakref

    m = fourbar()
    m.run()
    gone = weakref.ref(m)
    del m
    gc.collect()
    assert gone() is None


def test_a_mechanism_keeps_its_compiled_models_and_a_pickle_takes_none_along() -> None:
    import pickle

    m = fourbar()
    first = m.run()
    (kept,) = kept_models(m)
    # Another mechanism of the same topology compiles its own.
    other = fourbar()
    other.run()
    assert kept_models(other)[-1] is not kept
    # A pickled mechanism leaves its compiled models behind, and compiles them again when it runs.
    back = pickle.loads(pickle.dumps(m))
    assert kept_models(back) == []
    again = back.run()
    assert_same(again, first._raw)
    assert kept_models(back)[-1] is not kept
