"""A deck with a TOLERANCE block read into a mechanism: the mechanism does not carry the block
(``mechfem.tolerance_bands`` computes the bands of a mechanism), so its bands are left out with a warning that says
so, together with every place the deck shows them (PRINTBUF, SAVEDATA, a picture's plot), and the mechanism runs as
the deck does otherwise."""

from __future__ import annotations

import numpy as np
import pytest

import mechfem
from conftest import ROOT

DECK = ROOT / "tests" / "decks" / "fourbar_tolerances.mec"
BANDS = [10, 11, 12, 13, 14, 15]


def test_the_bands_are_left_out_with_a_warning_and_the_rest_runs_as_the_deck() -> None:
    with pytest.warns(UserWarning, match=r"TOLERANCE block is left out .* \(10, 11, 12, 13, 14, 15\)") as caught:
        m = mechfem.Mechanism.from_deck(DECK)
    assert str(DECK) in str(caught[0].message) and "mechfem.tolerance_bands" in str(caught[0].message)
    storage = m.storage
    assert storage is not None
    assert [b for b, _, _ in storage.buffers] == [1, 2, 3, 4]
    assert storage.printbuf == [] and storage.savedata == [1, 2, 3, 4]
    assert [(p.title, p.plots) for p in storage.pictures] == [
        ("the rocker angle's tolerance band", [("PLOTFUNC", 1, 2)])
    ]
    deck, mech = mechfem.run_deck(DECK), m.run(order=None)
    assert sorted(deck.buffers) == [1, 2, 3, 4, *BANDS] and sorted(mech.buffers) == [1, 2, 3, 4]
    for b in (1, 2, 3, 4):
        np.testing.assert_array_equal(mech.buffers[b], deck.buffers[b])
    # The bands the deck computes are those of the same mechanism from Python.
    bands = mechfem.tolerance_bands(
        m, {"crank_length": 0.002, "rocker_length": 0.002, "v_C": 0.005, "B0.x": 0.005}, ["psi"]
    )
    np.testing.assert_allclose(bands["psi"].worst, deck.buffers[10], rtol=1e-12, atol=1e-15)
    np.testing.assert_allclose(bands["psi"].rss, deck.buffers[11], rtol=1e-12, atol=1e-15)


def test_a_deck_without_a_tolerance_block_reads_without_a_warning(recwarn: pytest.WarningsRecorder) -> None:
    mechfem.Mechanism.from_deck(ROOT / "examples" / "fourbar" / "fourbar.mec")
    assert not [w for w in recwarn if "TOLERANCE" in str(w.message)]
