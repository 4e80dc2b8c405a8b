"""The table of a run in the core's full layout (``layout`` in the run dict): its blocks tile the table, every run of
one deck in a study shares the same layout, and an ``Analysis`` sliced by it gives, to the last bit, what the deck
reader's run records for each quantity on its own (``run_deck``, one buffer per quantity)."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import numpy.typing as npt
import pytest

import mechfem
import mechfem._core as _core
from mechfem.deck import deckio
from mechfem.results.result import Analysis

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
# One and two inputs, masses and loads, a motion that stops early at a limit position, free motion started at a dead
# centre (no transfer functions there: NaN).
DECKS = [
    "fourbar/fourbar.mec",
    "supply/supply_dyn.mec",
    "manipulator/manipulator.mec",
    "limits/stephenson_limits.mec",
    "dead centre",
]


def mechanism(deck: str, tmp_path: Path) -> mechfem.Mechanism:
    if deck != "dead centre":
        return mechfem.Mechanism.from_deck(EXAMPLES / deck)
    text = (EXAMPLES / "limits" / "slider_dead_centre_free.mec").read_text()
    for old, new in (
        ("XMOV 3 0.5", "XMOV 3 1.0"),
        ("     4 0.866", "     4 0.0"),
        ("     5 3.372", "     5 4.0"),
        ("     3 3.3722813232690143", "     3 4.0"),
    ):
        assert old in text
        text = text.replace(old, new)
    path = tmp_path / "dead_centre.mec"
    path.write_text(text)
    return mechfem.Mechanism.from_deck(path)


@pytest.mark.filterwarnings("ignore::mechfem.IncompleteRunWarning")
def test_the_blocks_tile_the_table_once(tmp_path: Path) -> None:
    for deck in DECKS:
        m = mechanism(deck, tmp_path)
        text = deckio.write(m, m.motion, m.storage)
        d = _core.run_deck_text(text.text, text.path, str(EXAMPLES))
        table = np.asarray(d.table)
        n, nd, nr = d.n_coords, d.n_dof, d.n_prescribed + d.n_dependent
        at = 0
        for name, (start, shape) in sorted(d.layout.items(), key=lambda item: item[1][0]):
            assert start == at, f"{deck}: block {name} starts where the one before it ends"
            at += math.prod(shape)
        assert at == table.shape[1], deck
        assert list(d.layout)[-2:] == ["time", "det"]
        assert d.layout["kx2"][1] == (n, nd, nd) and d.layout["ke1"][1] == (nr, nd)
        assert ("sigma" in d.layout) == d.dynamic
        # Column by column: each quantity's values over the positions are contiguous.
        assert table.flags.f_contiguous and np.asarray(d.buffers).flags.f_contiguous


def test_every_run_of_one_deck_in_a_study_shares_what_does_not_change() -> None:
    m = mechfem.Mechanism.from_deck(EXAMPLES / "fourbar" / "fourbar.mec")
    text = deckio.write(m, m.motion, m.storage)
    variants = [(0, [(1, 1, length)]) for length in (0.99, 1.0, 1.01)]
    out = _core.run_deck_variants([text.text], variants, text.path, str(EXAMPLES), 2, None, None)
    first = out[0]
    assert not isinstance(first, mechfem.MechfemError)
    for d in out[1:]:
        assert not isinstance(d, mechfem.MechfemError)
        assert d.layout is first.layout and d.storage is first.storage
        assert d.model.elements is first.model.elements
        assert d.model.prescribed is not first.model.prescribed
    # ... and what does: each variant's own PARA and row values at position 1.
    assert [d.model.prescribed[0].para for d in out] == [0.99, 1.0, 1.01]
    assert len({d.model.prescribed[0].value for d in out}) == 3


def storage_of_every_quantity(a: Analysis) -> tuple[str, dict[int, npt.NDArray[np.float64]]]:
    """A STORAGE section with a buffer for every quantity of the run's deck, and what ``a`` says each buffer holds."""
    nb = a.numbering
    n, nd = len(nb.coords), len(nb.inputs)
    rows = [(k + 1, r) for k, r in enumerate(nb.prescribed)] + [(-(k + 1), r) for k, r in enumerate(nb.dependent)]
    lines: list[str] = []
    want: dict[int, npt.NDArray[np.float64]] = {}

    def buf(line: str, values: npt.NDArray[np.float64]) -> None:
        b = len(lines) + 1
        lines.append(f"{line} {b}")
        want[b] = np.asarray(values, dtype=np.float64)

    buf("BUFTIME", a.time)
    buf("BUFDET", a.det)
    for j in range(1, nd + 1):
        buf(f"BUFINP {j}", a.input(j))
    for i, c in enumerate(nb.coords, 1):
        buf(f"BUFX0 {i}", a.coords[:, i - 1])
        buf(f"BUFVX {i}", a.velocity(c))
        buf(f"BUFAX {i}", a.acceleration(c))
        for j in range(1, nd + 1):
            buf(f"BUFKX1 {i} {j}", a.value(c, 1, j))
            for k in range(1, nd + 1):
                buf(f"BUFKX2 {i} {j} {k}", a.value(c, 2, j, k))
    for dest, r in rows:
        buf(f"BUFE0 {dest}", a.value(r))
        buf(f"BUFVE {dest}", a.velocity(r))
        buf(f"BUFAE {dest}", a.acceleration(r))
        for j in range(1, nd + 1):
            buf(f"BUFKE1 {dest} {j}", a.value(r, 1, j))
            for k in range(1, nd + 1):
                buf(f"BUFKE2 {dest} {j} {k}", a.value(r, 2, j, k))
    if a.dynamic:
        energy = a.energy()
        buf("BUFEKIN", energy.kinetic)
        buf("BUFEPOT", energy.potential)
        buf("BUFPOW", a.power())
        for j in range(1, nd + 1):
            buf(f"BUFDRV {j}", a.drive_torque(j))
            for k in range(1, nd + 1):
                buf(f"BUFMRED {j} {k}", a.mass_matrix()[:, j - 1, k - 1])
        for dest, r in rows[: len(nb.prescribed)]:
            buf(f"BUFSIG {dest}", a.stress(r))
        for i, c in enumerate(nb.coords, 1):
            if c.fixed:
                buf(f"BUFREA {i}", a.reaction(c))
    assert n and len(want) > 3 * n
    return "STORAGE\n" + "\n".join(lines) + "\nEND\n", want


@pytest.mark.filterwarnings("ignore::mechfem.IncompleteRunWarning")
@pytest.mark.parametrize("deck", DECKS)
def test_analysis_gives_what_each_quantity_records_on_its_own(deck: str, tmp_path: Path) -> None:
    m = mechanism(deck, tmp_path)
    a = m.run(order=2, progress=False)
    storage, want = storage_of_every_quantity(a)
    # The same deck with a buffer for every quantity, read and run from its file: each buffer recorded by itself.
    text = deckio.write(m, m.motion, m.storage).text
    path = tmp_path / "every.mec"
    path.write_text(text[: text.index("\nSTORAGE\n") + 1] + storage)
    ref = mechfem.run_deck(path)
    assert ref.report.positions == a.positions and sorted(ref.buffers) == sorted(want)
    if deck == "dead centre":
        assert ref.report.singular_positions == [1]
        assert np.isnan(a.velocity("A")[0]).all() and not np.isnan(a.velocity("A")[1:]).any()
    for b, got in want.items():
        line = storage.splitlines()[b]
        assert got.tobytes() == np.ascontiguousarray(ref.buffers[b]).tobytes(), f"{deck}: {line}"
