"""A run's storage requests are the compiled module's own objects (``mechfem.model.echo.EchoStorage``): read through
attributes, equal when they hold the same, picklable, changed by ``replace``."""

from __future__ import annotations

import pickle
from pathlib import Path

import pytest

import mechfem
from mechfem import _core
from mechfem.model.echo import EchoPicture, EchoStorage

ROOT = Path(__file__).resolve().parents[2]
FOURBAR = ROOT / "examples" / "fourbar" / "fourbar.mec"


@pytest.fixture(scope="module")
def storage() -> EchoStorage:
    return mechfem.run_deck(FOURBAR).storage


def test_the_storage_is_the_compiled_modules_object(storage: EchoStorage) -> None:
    assert type(storage) is _core.EchoStorage is EchoStorage
    assert isinstance(storage.buffers[0], mechfem.Buffer)
    assert isinstance(storage.pictures[0], EchoPicture)
    assert isinstance(storage.pictures[0].plots[0], mechfem.Plot)


def test_the_storage_says_what_the_deck_asks_for(storage: EchoStorage) -> None:
    # fourbar.mec: BUFKE1 -1 1 22 at line 83, PRINTBUF 1 2 11 12 21 30, two SAVEDATA lines, ANIMATE fourbar.
    b = storage.buffer(22)
    assert (b.number, b.keyword, b.args, b.line, b.part) == (22, "BUFKE1", [-1, 1], 83, 0)
    assert b.label() == "BUFKE1 -1 1"
    assert storage.printbuf == [1, 2, 11, 12, 21, 30]
    assert storage.savedata == [1, 2, 11, 12, 13, 14, 15, 16, 17, 18, 19, 20, 21, 22, 23, 24, 25, 30]
    assert storage.animate == "fourbar"
    assert [p.title for p in storage.pictures][0] == "coupler curve and velocity hodograph"
    assert storage.pictures[0].plots == [mechfem.Plot("PLOTHODO", 9, 10)]
    assert [(q.keyword, q.a, q.b) for q in storage.pictures[1].plots] == [("PLOTFUNC", 1, 21)] + [
        ("PLOTFUNC", 1, k) for k in (22, 23)
    ]
    with pytest.raises(KeyError):
        storage.buffer(99)


def test_the_storage_pickles_and_compares_by_value(storage: EchoStorage) -> None:
    again = pickle.loads(pickle.dumps(storage))
    assert again == storage and again is not storage
    assert pickle.loads(pickle.dumps(storage.buffers[3])) == storage.buffers[3]
    assert storage.buffers[0] != storage.buffers[1]


def test_replace_changes_only_what_it_names(storage: EchoStorage) -> None:
    changed = storage.replace(animate="film", pictures=[EchoPicture("empty", 0, [])])
    assert (changed.animate, [p.title for p in changed.pictures]) == ("film", ["empty"])
    assert (changed.buffers, changed.printbuf, changed.savedata) == (
        storage.buffers,
        storage.printbuf,
        storage.savedata,
    )
    assert storage.animate == "fourbar"
    assert storage.replace(printbuf=None).printbuf is None
    with pytest.raises(TypeError):
        storage.replace(colour="red")


def test_a_printbuf_without_numbers_tabulates_every_buffer(tmp_path: Path) -> None:
    deck = tmp_path / "all.mec"
    deck.write_text(FOURBAR.read_text().replace("PRINTBUF 1 2 11 12 21 30", "PRINTBUF"))
    storage = mechfem.run_deck(deck).storage
    assert storage.printbuf == [b.number for b in storage.buffers]
