"""Decks and the Python model give the same results both ways: every example deck read into the API, and
mechanisms built in Python written as decks and run by ``mechfem.run_deck``."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import numpy.typing as npt
import pytest

import mechfem
from conftest import ROOT
from mechfem import Mechanism, Motion
from mechfem.model.mechanism import Table
from model.test_model_api import supply


def mode(deck: Path) -> str:
    """The deck's mode line (the first line that is not a comment)."""
    lines = (line.split(";")[0].strip().upper() for line in deck.read_text().splitlines())
    return next((line for line in lines if line), "")


EXAMPLE_DECKS = sorted((ROOT / "examples").rglob("*.mec"))
# The valid decks of the deck reader with masses and loads (DYN ANA, DYN SIM), beside the examples.
DYNAMIC_DECKS = sorted(
    p
    for p in (ROOT / "crates" / "mechfem-deck" / "tests" / "decks" / "valid").glob("*.mec")
    if mode(p).startswith("DYN")
)
DECKS = EXAMPLE_DECKS + [p for p in DYNAMIC_DECKS if p not in EXAMPLE_DECKS]
RTOL = 1e-12


def deck_id(path: Path) -> str:
    return str(path.relative_to(ROOT / "examples" if path.is_relative_to(ROOT / "examples") else ROOT))


def same(a: npt.NDArray[np.float64], b: npt.NDArray[np.float64]) -> bool:
    """Equal within 1e-12 relative (of the larger magnitude in the column), NaN where the other has NaN."""
    if a.shape != b.shape or not np.array_equal(np.isnan(a), np.isnan(b)):
        return False
    scale = np.maximum(np.nanmax(np.abs(b), initial=0.0), 1e-300)
    return bool(np.all(np.abs(np.nan_to_num(a) - np.nan_to_num(b)) <= RTOL * scale))


def test_there_are_example_decks() -> None:
    assert len(EXAMPLE_DECKS) >= 2 and len(DYNAMIC_DECKS) >= 2
    assert any(mode(p) == "DYN SIM" for p in DYNAMIC_DECKS)


@pytest.mark.filterwarnings("ignore::mechfem.IncompleteRunWarning")  # the motion stops on purpose
@pytest.mark.parametrize("deck", DECKS, ids=deck_id)
def test_example_deck_read_into_the_api_gives_the_deck_results(deck: Path) -> None:
    try:
        ref = mechfem.run_deck(deck)
    except mechfem.MechfemError as e:
        with pytest.raises(type(e)):
            Mechanism.from_deck(deck).run()
        return
    m = Mechanism.from_deck(deck)
    # order=None: the transfer functions the deck's buffers need, as `mechfem run` computes them.
    r = m.run(order=None)
    assert r.positions == ref.positions and r.report.stop_reason() == ref.report.stop_reason()
    assert len(r.limits) == len(ref.report.limits)
    assert sorted(r.buffers) == sorted(ref.buffers)
    for number, values in ref.buffers.items():
        assert same(r.buffers[number], values), f"buffer {number}"
    assert same(r.coords, ref.coords) and same(r.time, ref.time) and same(r.det, ref.det)
    # The masses and loads came along: the same inverse dynamics, and a simulation simulated alike.
    assert (r.dynamic is not None) == (ref.model.mode in ("DYN ANA", "DYN SIM")) == (m.loads is not None)
    assert r.simulation == ref.simulation and (r.simulation is not None) == (ref.model.mode == "DYN SIM")
    if ref.dynamic is not None:
        assert same(r.drive_torque(1)[:, None], ref.dynamic.drive[:, :1]) and same(r.power(), ref.dynamic.power)
        assert same(r.energy().kinetic, ref.dynamic.kinetic) and same(r.energy().potential, ref.dynamic.potential)


@pytest.mark.parametrize("deck", DECKS, ids=deck_id)
def test_example_deck_written_back_reads_as_the_same_model(deck: Path, tmp_path: Path) -> None:
    m = Mechanism.from_deck(deck)
    again = Mechanism.from_deck(m.save_deck(tmp_path / deck.name))
    assert again.to_deck() == m.to_deck()
    assert [e.type for e in again.elements] == [e.type for e in m.elements]
    assert [(r.name, r.kind, r.value) for r in again.rows] == [(r.name, r.kind, r.value) for r in m.rows]
    assert [type(i) for i in again.loads or []] == [type(i) for i in m.loads or []]
    assert plain(again.motion) == plain(m.motion)


def plain(motion: Motion | None) -> tuple[object, ...] | None:
    """A motion as plain values (a table as its rows), to compare two of them."""
    if motion is None:
        return None
    inputs = [(k, im.rows(motion.dt).tolist() if isinstance(im, Table) else im) for k, im in motion.inputs.items()]
    return (motion.steps, motion.dt, motion.accuracy, motion.max_iter, motion.rtol, motion.atol, inputs)


@pytest.mark.filterwarnings("ignore::mechfem.IncompleteRunWarning")  # the motion stops on purpose
@pytest.mark.parametrize("deck", DECKS, ids=deck_id)
def test_every_transfer_function_agrees_with_the_deck_within_its_accuracy(deck: Path) -> None:
    # With every transfer function computed (the default), positions are predicted otherwise than in a
    # run that needs only the first order: the results agree within the Newton tolerance.
    try:
        ref = mechfem.run_deck(deck)
    except mechfem.MechfemError:
        return
    r = Mechanism.from_deck(deck).run()
    assert r.positions == ref.positions or not ref.report.complete
    k = min(r.positions, ref.positions)
    assert np.allclose(r.coords[:k], ref.coords[:k], rtol=1e-8, atol=1e-8, equal_nan=True)


def test_first_order_only_leaves_the_second_order_undefined() -> None:
    m = supply()
    r = m.run(Motion.by(36, 2 * math.pi), order=1)
    # Position 1 always has both orders; from position 2 on only the first is computed.
    assert np.isnan(r.output("delta", 2)[1:]).all() and np.isnan(r.acceleration("K")[1:]).all()
    assert np.isfinite(r.output("delta", 1)).all() and np.isfinite(r.det).all()
    full = m.run(Motion.by(36, 2 * math.pi))
    assert np.allclose(r.output("delta"), full.output("delta"), rtol=0, atol=1e-9)
    with pytest.raises(ValueError, match="order must be 1, 2 or None"):
        m.run(order=3)


def test_names_given_to_a_deck() -> None:
    # The example without its NAMES block: what the deck reader names after the deck's numbers.
    path = ROOT / "examples" / "gears" / "planetary_gr1.mec"
    lines = path.read_text().splitlines()
    start = lines.index("NAMES")
    end = lines.index("MOVEMENT", start)
    m = Mechanism.from_deck_text("\n".join(lines[:start] + lines[end:]), "planetary_gr1", path.parent)
    assert [p.name for p in m.points] == ["P1", "P3"]
    assert m["x6"].kind == "angle" and m["x9"].kind == "scalar" and m["x9"].fixed
    assert [e.name for e in m.elements] == [f"E{k}" for k in range(1, 7)]
    assert [r.name for r in m.inputs] == ["E2.angle", "E1.angle"]
    assert [r.name for r in m.outputs] == ["out1", "out2"]
    assert m.motion is not None and m.motion.steps == 36 and m.motion.dt == 0.01
    # A deck with a NAMES block: its names, and its elements' names for their own rows.
    supply_deck = Mechanism.from_deck(ROOT / "examples" / "supply" / "supply.mec")
    assert [p.name for p in supply_deck.points][:3] == ["A0", "A", "B"]
    assert supply_deck["kappa"].formula() == "coupler.angle - arm.angle"
    assert supply_deck.storage is not None and supply_deck.storage.buffers[2] == (101, "BUFKE1", ("delta", "alpha"))
    assert "crank.length" in supply_deck and "rod.length" in supply_deck


def test_a_deck_with_a_mistake_raises_the_deck_error(tmp_path: Path) -> None:
    deck = tmp_path / "bad.mec"
    deck.write_text("KIN ANA\nTOPOLOGY\nELEM 1 BNI 1 2 3 4\n")
    with pytest.raises(mechfem.DeckError, match="unknown element type"):
        Mechanism.from_deck(deck)
    with pytest.raises(mechfem.DeckError, match="cannot read"):
        Mechanism.from_deck(tmp_path / "missing.mec")


def api_models() -> list[tuple[Mechanism, Motion]]:
    rows = np.loadtxt(ROOT / "examples" / "slider_crank" / "crank.dat", comments="#")
    m = Mechanism("slider crank")
    A0, G = m.fixed("A0", 0.0, 0.0), m.fixed("G", -2.0, 0.3)
    A, B = m.point("A", 1.0, 0.2), m.point("B", 3.9, 0.3)
    m.bar("crank", A0, A, length=1.0, angle=mechfem.Driven())
    m.bar("rod", A, B, length=3.0, angle=mechfem.Output("rod_angle"))
    m.bar("guide", G, B, angle=0.0)
    table = Motion.table(rows[:, 1], rows[:, 2], rows[:, 3], time=rows[:, 0])
    return [(supply(), Motion.by(72, 2 * math.pi, dt=0.01)), (m, table)]


@pytest.mark.parametrize("k", [0, 1])
def test_model_written_as_a_deck_runs_the_same(k: int, tmp_path: Path) -> None:
    m, motion = api_models()[k]
    storage = mechfem.model.mechanism.Storage().buffer(1, "BUFDET").buffer(2, "BUFE0", m.outputs[0].name)
    storage.buffer(3, "BUFVX", m.coordinates[-1]).buffer(4, "BUFKX2", m.coordinates[-1].name, m.inputs[0])
    storage.savedata = [1, 2, 3, 4]
    path = m.save_deck(tmp_path / "model.mec", motion, storage)
    ref = mechfem.run_deck(path)
    r = m.run(motion, storage)  # BUFKX2 asks for the second order, as run() computes by default
    assert r.positions == ref.positions
    for number in (1, 2, 3, 4):
        assert same(r.buffers[number], ref.buffers[number])
    assert same(r.coords, ref.coords) and same(r.det, ref.det) and same(r.time, ref.time)
    assert same(r.output(m.outputs[0].name), ref.buffers[2]) and same(r.det, ref.buffers[1])
    # Read back, the deck is the same model with generated names.
    back = Mechanism.from_deck(path).run()
    assert same(back.coords, r.coords) and same(back.buffers[4], r.buffers[4])
