"""The names a deck declares in its NAMES block reach the model echo of its run (docs/deck.md, "NAMES"); comments
name nothing. A deck written from a :class:`~mechfem.Mechanism` is to name every co-ordinate, element and row as
the model does: the tests of that are marked until the deck writer writes a NAMES block (it still writes the
model's names as comments)."""

from __future__ import annotations

import math
import re
from collections.abc import Callable
from pathlib import Path

import numpy as np
import pytest

import mechfem
from conftest import ROOT
from mechfem import Driven, Mechanism, Motion, Output
from mechfem.deckio import number_model
from test_model_api import supply


def fourbar() -> Mechanism:
    """The four-bar of docs/python-api.md: a crank input, a coupler point, the rocker angle as an output."""
    m = Mechanism("fourbar")
    A0, B0 = m.fixed("A0", 0.0, 0.0), m.fixed("B0", 4.0, 0.0)
    A, B, C = m.point("A", 1.0, 0.0), m.point("B", 3.5, 2.5), m.point("C", 1.5, 2.0)
    m.bar("crank", A0, A, length=1.0, angle=Driven(start=0.0, name="phi"))
    m.ternary2("coupler", A, B, C, length=3.5, u=1.5, v=1.2)
    m.bar("rocker", B0, B, length=3.0, angle=Output("psi"))
    return m


WRITER = pytest.mark.xfail(
    strict=True, reason="the deck writer (mechfem.deckio) writes names as comments, which name nothing; a NAMES block"
)


@WRITER
@pytest.mark.parametrize("build", [fourbar, supply])
def test_a_saved_deck_names_what_the_model_names(build: Callable[[], Mechanism], tmp_path: Path) -> None:
    m = build()
    deck = tmp_path / f"{m.name}.mec"
    m.save_deck(deck, Motion.by(12, 2 * math.pi))
    model = mechfem.run_deck(deck).model
    nb = number_model(m)
    assert [c.name for c in model.coordinates] == [c.name for c in nb.coords]
    assert [e.name for e in model.elements] == [e.name for e in nb.elements]
    assert [r.name for r in model.prescribed] == [r.name for r in nb.prescribed]
    assert [r.name for r in model.dependent] == [r.name for r in nb.dependent]


def test_a_combined_row_is_named_before_its_formula(tmp_path: Path) -> None:
    text = (ROOT / "examples" / "supply" / "supply.mec").read_text()
    deck = tmp_path / "supply.mec"
    deck.write_text(re.sub(r"^MOVEMENT", "NAMES\nROW 5 kappa\nDEP 1 psi\nMOVEMENT", text, count=1, flags=re.M))
    r = mechfem.run_deck(deck)
    assert [x.name for x in r.model.prescribed][4] == "kappa"
    assert r.model.dependent[0].name == "psi"
    labels = {b.number: b.name for b in r.storage.buffers}
    assert labels[100] == "psi" and labels[101] == "dpsi/dinput1"


def test_a_hand_written_decks_comments_name_nothing() -> None:
    model = mechfem.run_deck(ROOT / "examples" / "fourbar" / "fourbar.mec").model
    # `; A0`, `; crank A0-A` and `; row 1: crank length` are notes, single words included.
    assert [c.name for c in model.coordinates] == [None] * 10
    assert [e.name for e in model.elements] == [None, None, None]
    assert [r.name for r in model.prescribed + model.dependent] == [None] * 7


def test_names_change_no_number(tmp_path: Path) -> None:
    text = (ROOT / "examples" / "fourbar" / "fourbar.mec").read_text()
    named, bare = tmp_path / "named.mec", tmp_path / "bare.mec"
    names = "NAMES\nPOINT 1 2 A0\nPOINT 9 10 C\nELEM 1 crank\nDEP 1 psi\nMOVEMENT"
    named.write_text(re.sub(r"^MOVEMENT", names, text, count=1, flags=re.M))
    bare.write_text("\n".join(line.split(";")[0].rstrip() for line in text.splitlines()) + "\n")
    a, b = mechfem.run_deck(named), mechfem.run_deck(bare)
    assert np.array_equal(a.coords, b.coords) and np.array_equal(a.det, b.det)
    for number, column in b.buffers.items():
        assert np.array_equal(a.buffers[number], column)
    assert all(c.name is None for c in b.model.coordinates) and a.model.coordinates[0].name == "A0.x"
    assert a.model.coordinates[9].name == "C.y" and a.model.elements[0].name == "crank"


@WRITER
def test_a_saved_deck_run_is_addressed_by_the_model_names(tmp_path: Path) -> None:
    from mechfem.model import Storage

    m = fourbar()
    motion = Motion.by(12, 2 * math.pi, dt=0.01)
    storage = Storage().buffer(1, "BUFINP", "phi").buffer(2, "BUFX0", "C.x").buffer(3, "BUFX0", "C.y")
    storage.buffer(4, "BUFKE1", "psi", "phi").buffer(5, "BUFVX", "C.x").buffer(6, "BUFE0", "coupler.length")
    deck = tmp_path / "fourbar.mec"
    m.save_deck(deck, motion, storage)
    r, named = mechfem.run_deck(deck), m.run(motion, storage, order=None)  # the same orders: the same bits
    assert not r.named and r.names is None  # the print file and pictures keep the deck's numbers
    assert np.array_equal(r.value("C"), named.value("C")) and np.array_equal(r.x("C"), named.x("C"))
    assert np.array_equal(r.output("psi", 1, "phi"), named.output("psi", 1, "phi"))
    assert np.array_equal(r.input("phi"), named.input("phi")) and np.array_equal(
        r.velocity("C.x"), named.velocity("C.x")
    )
    assert np.array_equal(r.value("coupler.length"), named.value("coupler.length"))
    # The deck's own names still work beside the declared ones.
    assert np.array_equal(r.value("out1", 1), r.value("psi", 1)) and np.array_equal(r.value("P9"), r.value("C"))
