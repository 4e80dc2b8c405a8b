"""The typed builder (``_core.ModelBuilder``, :mod:`mechfem.run.building`) and the deck reader make the same core model.

Every example deck the Python API runs (kinematic, inverse dynamics, simulation) is read into a
:class:`~mechfem.Mechanism`; the model the builder makes of it and the one its deck text compiles to are compared in
full (the compiled model's ``Debug`` text), and so are their runs, number by number to the last bit. A run of the
mechanism (``Mechanism.run``) writes no deck text at all.
"""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np
import pytest
from tests.conftest import ROOT

import mechfem
import mechfem._core as _core
from mechfem.deck import deckio
from mechfem.errors import DeckError
from mechfem.run import building

EXAMPLES = sorted(p for p in (ROOT / "examples").glob("*/*.mec") if _core.deck_files(p).mode != "KIN OPT")


def _same_bits(a: object, b: object) -> bool:
    x, y = np.asarray(a, dtype=np.float64), np.asarray(b, dtype=np.float64)
    return x.shape == y.shape and x.tobytes() == y.tobytes()


def _text_model(mech: mechfem.Mechanism) -> tuple[_core.Model, deckio.DeckText]:
    """The model the mechanism's deck text compiles to."""
    deck = deckio.write(mech, mech.motion, mech.storage)
    with deckio.tables_dir(deck.tables) as base:
        return _core.Model(deck.text, deck.path, base), deck


@pytest.mark.parametrize("path", EXAMPLES, ids=lambda p: p.stem)
def test_builder_and_deck_reader_make_the_same_model(path: Path) -> None:
    mech = mechfem.Mechanism.from_deck(path)
    built, nb = building.build(mech, mech.motion, mech.storage)
    text, deck = _text_model(mech)
    assert built.fingerprint() == text.fingerprint()
    assert nb.coords == deck.numbering.coords
    ran, read = built.run(), text.run()
    for key in ("table", "buffers", "coords"):
        assert _same_bits(getattr(ran, key), getattr(read, key)), key
    assert ran.layout == read.layout
    assert ran.report == read.report


@pytest.mark.filterwarnings("ignore::mechfem.IncompleteRunWarning")
@pytest.mark.parametrize("path", EXAMPLES, ids=lambda p: p.stem)
def test_mechanism_run_gives_the_deck_texts_numbers_without_writing_deck_text(
    path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    mech = mechfem.Mechanism.from_deck(path)
    deck = deckio.write(mech, mech.motion, mech.storage)
    with deckio.tables_dir(deck.tables) as base:
        read = _core.run_deck_text(deck.text, deck.path, base)

    def no_text(*args: object, **kwargs: object) -> None:
        raise AssertionError("Mechanism.run wrote or read deck text")

    monkeypatch.setattr(deckio, "write", no_text)
    monkeypatch.setattr(_core, "run_deck_text", no_text)
    result = mech.run(mech.motion, mech.storage)
    assert _same_bits(result._raw.table, read.table)
    assert _same_bits(result.coords, read.coords)


def test_a_refused_value_is_a_deck_error_naming_the_item() -> None:
    b = _core.ModelBuilder("m.mec", "KIN ANA")
    b.element("BIN", [1, 2, 3, 4], "crank: A0 A")
    with pytest.raises(DeckError, match='the row "crank.angle" has destination 0'):
        b.form("ANGB", 1, 0, 1.0, "crank.angle")
    with pytest.raises(DeckError, match='the element "coupler" has the unknown element type `BNI`'):
        b.element("BNI", [1, 2, 3, 4], "coupler")
    b.form("LENL", 1, 1, 1.0, "crank.length")
    b.form("ANGB", 1, 2, 1.0, "crank.angle")
    b.nrdof(1)
    with pytest.raises(DeckError, match='the value of the co-ordinate "A.x" is NaN, not a finite number'):
        b.coordinate(3, float("nan"), True, "A.x")


def test_a_model_the_compiler_refuses_is_worded_in_the_models_words() -> None:
    m = mechfem.Mechanism("coincident")
    m.bar("crank", m.fixed("A0", 0.0, 0.0), m.point("A", 0.0, 0.0), length=1.0, angle=mechfem.Driven())
    with pytest.raises(mechfem.MechfemError) as err:
        m.run()
    assert "crank" in str(err.value) and "coincide" in str(err.value)


def test_the_built_model_reads_table_files_from_a_folder_of_its_own() -> None:
    mech = mechfem.Mechanism.from_deck(ROOT / "examples" / "slider_crank" / "slider_crank.mec")
    assert mech.motion is not None
    before = set(os.listdir("."))
    built, _ = building.build(mech, mech.motion, mech.storage)
    assert set(os.listdir(".")) == before
    assert len(built.run().coords) == mech.motion.steps + 1


def test_the_builder_carries_names_and_units_as_a_decks_names_block_and_units_line() -> None:
    text = "\n".join(
        [
            "; crank",
            "KIN ANA",
            "UNITS LENGTH mm ANGLE deg",
            "TOPOLOGY",
            "ELEM 1 BIN 1 2 3 4",
            "FORM 1 LENL 1 1 1.0",
            "FORM 2 ANGB 1 2 1.0",
            "NRDOF 1",
            "GEOMETRY",
            "XFIX 1 0.0",
            "XFIX 2 0.0",
            "XMOV 3 30.0",
            "XMOV 4 0.0",
            "NAMES",
            "POINT 3 4 A",
            "ELEM 1 crank",
            "ROW 2 phi",
            "MOVEMENT",
            "TSTEPE 4 0.5",
            "MOV_RELE 1 90.0",
            "END",
        ]
    )
    b = _core.ModelBuilder("crank.mec", "KIN ANA")
    b.units(length="mm", angle="deg")
    b.element("BIN", [1, 2, 3, 4], "crank")
    b.form("LENL", 1, 1, 1.0, "crank.length")
    b.form("ANGB", 1, 2, 1.0, "phi")
    b.nrdof(1)
    for i, value, moving in [(1, 0.0, False), (2, 0.0, False), (3, 30.0, True), (4, 0.0, True)]:
        b.coordinate(i, value, moving)
    b.name("POINT", [3, 4], "A")
    b.name("ELEM", [1], "crank")
    b.name("ROW", [2], "phi")
    b.movement(4, 0.5)
    b.motion(1, "by", 90.0, "phi")
    b.tolerances()
    built, read = b.build("."), _core.Model(text, "crank.mec", ".")
    assert built.fingerprint() == read.fingerprint()
    assert "crank" in built.fingerprint() and "Deg" in built.fingerprint()
    assert _same_bits(built.run().coords, read.run().coords)
    bad = _core.ModelBuilder("crank.mec", "KIN ANA")
    bad.element("BIN", [1, 2, 3, 4], "crank")
    bad.nrdof(1)
    with pytest.raises(DeckError, match="`coupler.length` is not a name"):
        bad.name("ROW", [1], "coupler.length")
    with pytest.raises(DeckError, match="`furlong` is not a unit of length"):
        _core.ModelBuilder("m.mec", "KIN ANA").units(length="furlong")
