"""Every way of running gives one result type, addressed by names: a deck's run by the names the deck declares,
a named model's by its own, the buffers of both by number."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import mechfem
from bare_examples import bare
from mechfem import Mechanism

ROOT = Path(__file__).resolve().parents[2]
# The example without its NAMES block: a deck run named by the deck's numbers.
FOURBAR = bare(ROOT / "examples" / "fourbar" / "fourbar.mec")


def test_a_deck_run_and_a_model_run_are_one_type() -> None:
    deck = mechfem.run_deck(FOURBAR)
    named = Mechanism.from_deck(FOURBAR).run()
    assert type(deck) is type(named) is mechfem.RunResult
    assert mechfem.Analysis is mechfem.RunResult
    assert not deck.named and named.named
    assert deck.run_result() is deck and named.run_result() is named


def test_a_deck_run_is_addressed_by_deck_names_and_gives_its_buffers_values() -> None:
    r = mechfem.run_deck(FOURBAR)
    b = r.buffers
    # fourbar.mec: co-ordinates 9, 10 are the coupler point C; dependent -1 is ANGB of element 3, the rocker angle.
    assert np.array_equal(r.value("x9"), b[11]) and np.array_equal(r.value("x10"), b[12])
    assert np.array_equal(r.value("P9"), np.column_stack([b[11], b[12]]))
    assert np.array_equal(r.x("P9"), b[11]) and np.array_equal(r.y("P9"), b[12])
    assert np.array_equal(r.transfer("P9"), np.column_stack([b[13], b[14]]))
    assert np.array_equal(r.value("x9", 2, 1), b[15])
    assert np.array_equal(r.velocity("x10"), b[18]) and np.array_equal(r.acceleration("x9"), b[19])
    for name in ("ANGB(3)", "out1", "E3.angle"):
        assert np.array_equal(r.value(name), b[21]), name
        assert np.array_equal(r.output(name, 1), b[22]) and np.array_equal(r.output(name, 2), b[23])
        assert np.array_equal(r.velocity(name), b[24]) and np.array_equal(r.acceleration(name), b[25])
    assert np.array_equal(r.input(), b[1]) and np.array_equal(r.input(1), b[1])
    assert np.allclose(r.input(unit="deg"), np.degrees(b[1]), rtol=1e-15, atol=0.0)
    assert np.array_equal(r.value("ANGB(3)", unit="deg"), b[21] * (180.0 / np.pi))


def test_a_deck_run_and_the_model_read_from_it_agree_name_by_name() -> None:
    deck = mechfem.run_deck(FOURBAR)
    named = Mechanism.from_deck(FOURBAR).run(order=None)
    for name in ("P9", "x10", "out1", "ANGB(3)"):
        for q in (deck.value, deck.velocity, deck.acceleration):
            other = getattr(named, q.__name__)
            # The model read from the deck takes the deck's names: P9, out1 (and x10, ANGB(3) only for a deck).
            ref = name if name in ("P9", "out1") else {"x10": "P9.y", "ANGB(3)": "out1"}[name]
            assert np.array_equal(q(name), other(ref)), (name, q.__name__)


def test_what_a_deck_did_not_record_names_the_buffer_that_would() -> None:
    r = mechfem.run_deck(FOURBAR)
    with pytest.raises(KeyError, match=r"did not record BUFVX 5: .* add the buffer `BUFVX 5 <number>`"):
        r.velocity("P5")
    with pytest.raises(KeyError, match=r"BUFKE1 5 1"):
        r.value("row5", 1)
    with pytest.raises(ValueError, match="KIN ANA deck, so its run computed no drive torques"):
        r.drive_torque()
    with pytest.raises(KeyError, match=r"no point, co-ordinate, row or output named 'Cc'.*x<i> for co-ordinate i"):
        r.value("Cc")


def test_a_deck_table_lists_what_its_buffers_recorded() -> None:
    r = mechfem.run_deck(FOURBAR)
    table = r.table()
    assert {"time", "det", "E1.angle", "out1", "out1'", "out1''", "out1_dot", "out1_ddot", "P9.x", "P9.y'"} <= set(
        table
    )
    assert "P5.x_dot" not in table and np.array_equal(table["P9.y''"], r.buffers[16])


def test_a_named_run_gives_its_deck_buffers_and_the_outputs_read_it(tmp_path: Path) -> None:
    from mechfem.output.files import write_outputs

    m = Mechanism.from_deck(FOURBAR)
    r = m.run()
    deck = mechfem.run_deck(FOURBAR)
    assert sorted(r.buffers) == sorted(deck.buffers)
    assert r.names is not None and r.names.dependent == ["out1"] and deck.names is None
    written = write_outputs(r, tmp_path)
    assert {p.suffix for p in written} >= {".prt", ".csv"}
