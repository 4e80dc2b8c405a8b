"""A named mechanism's run makes the storage's buffers as it goes (the binding's ``Full`` recorder): a buffer the full
layout has a column for from the record, a block of 256 positions at a time, a co-ordinate and a quantity the layout
has no column for (a transmission angle) at every position. Over runs of more positions than a block, not a multiple
of it, and one that stops early at a limit position, every buffer is to the last bit what the deck's own recording
(``run_deck`` of the deck written for the mechanism) gives, and what the full table's column of its quantity holds."""

from __future__ import annotations

import math
import warnings
from pathlib import Path

import numpy as np
import pytest

import mechfem
from mechfem import Driven, Mechanism, Motion, Output
from mechfem.model.storage import Storage


def fourbar(crank: float, steps: int) -> Mechanism:
    m = Mechanism("blocks")
    A0, B0 = m.fixed("A0", 0.0, 0.0), m.fixed("B0", 4.0, 0.0)
    A, B = m.point("A", 1.0, 0.3), m.point("B", 3.5, 2.5)
    m.bar("crank", A0, A, length=crank, angle=Driven(start=0.3))
    m.bar("coupler", A, B, length=3.5)
    m.bar("rocker", B0, B, length=3.0, angle=Output("psi"))
    m.motion = Motion.by(steps, 2 * math.pi)
    m.storage = (
        Storage()
        .buffer(1, "BUFX0", "B.x")
        .buffer(2, "BUFKE1", "psi", "crank.angle")
        .buffer(3, "BUFTRA", "coupler", "rocker")
        .buffer(4, "BUFAX", "B.y")
    )
    return m


@pytest.mark.parametrize(
    ("crank", "steps", "stops"),
    [
        (1.0, 600, False),  # a crank-rocker: 601 positions, two whole blocks and a part of one
        (1.0, 255, False),  # 256 positions: one block exactly
        (2.8, 1400, True),  # the crank cannot turn whole (2.8 + 4 > 3.5 + 3): the motion stops at a limit position
    ],
)
def test_every_buffer_is_what_the_decks_own_recording_gives(
    tmp_path: Path, crank: float, steps: int, stops: bool
) -> None:
    m = fourbar(crank, steps)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", mechfem.IncompleteRunWarning)
        named = m.run()
        m.save_deck(tmp_path / "blocks.mec")
        deck = mechfem.run_deck(tmp_path / "blocks.mec")
    positions = named.coords.shape[0]
    assert (positions < steps + 1) if stops else (positions == steps + 1)
    assert positions > 256 or steps == 255
    assert deck.coords.shape[0] == positions
    for number in (1, 2, 3, 4):
        assert np.array_equal(named.buffers[number], deck.buffers[number], equal_nan=True), f"buffer {number}"
    # The buffers read from the full layout's columns are those columns, to the last bit.
    assert np.array_equal(named.buffers[1], named.x("B"))
    assert np.array_equal(named.buffers[2], named.transfer("psi", 1, "crank.angle"), equal_nan=True)
    assert np.array_equal(named.buffers[4], named.acceleration("B")[:, 1], equal_nan=True)
    np.testing.assert_allclose(named.buffers[3], named.transmission_angle("coupler", "rocker"), rtol=0, atol=1e-12)
