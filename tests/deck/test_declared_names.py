"""The names a deck's NAMES block declares reach the model echo of its run (docs/deck.md, NAMES): a deck written
from a :class:`~mechfem.Mechanism` names its points, elements, rows and outputs as the model does, and comments
name nothing."""

from __future__ import annotations

import math
from collections.abc import Callable
from pathlib import Path

import numpy as np
import pytest

import mechfem
from mechfem import Driven, Mechanism, Motion, Output
from mechfem.deck.deckio import number_model
from model.test_model_api import supply


def fourbar() -> Mechanism:
    """The four-bar of docs/python-api.md: a crank input, a coupler point, the rocker angle as an output."""
    m = Mechanism("fourbar")
    A0, B0 = m.fixed("A0", 0.0, 0.0), m.fixed("B0", 4.0, 0.0)
    A, B, C = m.point("A", 1.0, 0.0), m.point("B", 3.5, 2.5), m.point("C", 1.5, 2.0)
    m.bar("crank", A0, A, length=1.0, angle=Driven(start=0.0, name="phi"))
    m.ternary2("coupler", A, B, C, length=3.5, u=1.5, v=1.2)
    m.bar("rocker", B0, B, length=3.0, angle=Output("psi"))
    return m


@pytest.mark.parametrize("build", [fourbar, supply])
def test_a_saved_deck_names_what_the_model_names(build: Callable[[], Mechanism], tmp_path: Path) -> None:
    m = build()
    deck = tmp_path / f"{m.name}.mec"
    m.save_deck(deck, Motion.by(12, 2 * math.pi))
    model = mechfem.run_deck(deck).model
    nb = number_model(m)
    # A point's co-ordinates are named after it; an element's own row (crank.length) is named by its element.
    assert [c.name for c in model.coordinates] == [c.name for c in nb.coords]
    assert [e.name for e in model.elements] == [e.name for e in nb.elements]
    own = [len(r.terms) == 1 and r.name == r.terms[0][1].label for r in nb.prescribed + nb.dependent]
    expected = [None if o else r.name for o, r in zip(own, nb.prescribed + nb.dependent, strict=True)]
    assert [r.name for r in model.prescribed + model.dependent] == expected


def test_a_combined_row_is_named_by_its_row_line(tmp_path: Path) -> None:
    deck = tmp_path / "supply.mec"
    deck.write_text(supply().to_deck(Motion.by(12, 2 * math.pi)))
    assert "ROW 5 kappa" in deck.read_text().splitlines()
    names = [r.name for r in mechfem.run_deck(deck).model.prescribed]
    assert "kappa" in names and "alpha" == names[-1]


def test_comments_name_nothing(tmp_path: Path) -> None:
    lines = fourbar().to_deck().splitlines()
    lines = lines[: lines.index("NAMES")] + ["END"]
    # A comment after a co-ordinate, an element and a row, as decks had them to name things: notes only.
    noted = [f"{line} ; A0.x" if line.startswith(("XFIX 1 ", "ELEM 1 ", "FORM 1 ")) else line for line in lines]
    deck = tmp_path / "noted.mec"
    deck.write_text("\n".join(noted) + "\n")
    model = mechfem.check_deck(deck).model
    assert model.coordinates[0].name is None and model.elements[0].name is None
    assert all(r.name is None for r in model.prescribed)


def test_names_change_no_number(tmp_path: Path) -> None:
    text = fourbar().to_deck(Motion.by(12, 2 * math.pi))
    named, bare = tmp_path / "named.mec", tmp_path / "bare.mec"
    named.write_text(text)
    lines = text.splitlines()
    bare.write_text("\n".join(lines[: lines.index("NAMES")] + lines[lines.index("MOVEMENT") :]) + "\n")
    a, b = mechfem.run_deck(named), mechfem.run_deck(bare)
    assert np.array_equal(a.coords, b.coords) and np.array_equal(a.det, b.det)
    assert all(c.name is None for c in b.model.coordinates) and a.model.coordinates[0].name == "A0.x"


def test_a_saved_deck_run_is_addressed_by_the_model_names(tmp_path: Path) -> None:
    from mechfem.model.mechanism import Storage

    m = fourbar()
    motion = Motion.by(12, 2 * math.pi, dt=0.01)
    storage = Storage().buffer(1, "BUFINP", "phi").buffer(2, "BUFX0", "C.x").buffer(3, "BUFX0", "C.y")
    storage.buffer(4, "BUFKE1", "psi", "phi").buffer(5, "BUFVX", "C.x").buffer(6, "BUFE0", "coupler.length")
    deck = tmp_path / "fourbar.mec"
    m.save_deck(deck, motion, storage)
    r, named = mechfem.run_deck(deck), m.run(motion, storage, order=None)  # the same orders: the same bits
    assert not r.named and r.names is None
    assert np.array_equal(r.value("C"), named.value("C")) and np.array_equal(r.x("C"), named.x("C"))
    assert np.array_equal(r.output("psi", 1, "phi"), named.output("psi", 1, "phi"))
    assert np.array_equal(r.input("phi"), named.input("phi")) and np.array_equal(
        r.velocity("C.x"), named.velocity("C.x")
    )
    assert np.array_equal(r.value("coupler.length"), named.value("coupler.length"))
    # The deck's own names still work beside the declared ones.
    assert np.array_equal(r.value("out1", 1), r.value("psi", 1)) and np.array_equal(r.value("x9"), r.x("C"))
    # Its buffers are labelled by the names.
    from mechfem.results.labels import buffer_labels

    assert [lab.name for lab in buffer_labels(r).values()] == ["phi", "C.x", "C.y", "dpsi/dphi", "vC.x", "LENL(2)"]
