"""A run's table is made column by column as its quantities are read: a value, a transfer function or a plot of a
few quantities makes those columns alone, the same to the last bit as the whole table's (in the model's units:
mm and degrees here), and ``table()`` or ``to_pandas()`` makes the rest."""

from __future__ import annotations

import pickle

import numpy as np

from conftest import fourbar_mm_deg
from mechfem import Motion


def test_a_value_makes_its_columns_alone_and_the_same_as_the_tables() -> None:
    m, motion = fourbar_mm_deg(), Motion.by(36, 360)
    alone, whole = m.run(motion), m.run(motion)
    psi, psi2, bx = alone.value("psi"), alone.value("psi", 2), alone.value("B.x", 1)
    # Only the columns read were made.
    assert "_table" not in alone.__dict__
    assert 0 < len(alone.__dict__["_columns_made"]) < whole._table.shape[1]
    np.testing.assert_array_equal(psi, whole.value("psi"))
    np.testing.assert_array_equal(psi2, whole.value("psi", 2))
    np.testing.assert_array_equal(bx, whole.value("B.x", 1))
    # Every column made alone is the whole table's column, bit for bit, in the model's units (degrees, mm).
    fresh = m.run(motion)
    for c in range(whole._table.shape[1]):
        np.testing.assert_array_equal(fresh._column(c), whole._table[:, c])
    assert "_table" not in fresh.__dict__
    assert np.nanmax(np.abs(whole.value("psi"))) > 6.3  # degrees, not radians


def test_the_whole_table_after_some_columns_and_a_pickle_agree() -> None:
    m, motion = fourbar_mm_deg(), Motion.by(12, 360)
    r = m.run(motion)
    before = r.value("psi").copy()
    table = r.table()
    np.testing.assert_array_equal(table["psi"], before)
    again = pickle.loads(pickle.dumps(m.run(motion)))
    np.testing.assert_array_equal(again.value("psi"), before)
    np.testing.assert_array_equal(again.value("B.x", 1), r.value("B.x", 1))
