"""Tolerance bands from the exact design sensitivities: each dimension's sensitivity against central differences of
whole runs (the dimension perturbed, the mechanism run again), the bands against their formulas, the print file's
section, and the linear bands against the Monte-Carlo tolerance study."""

from __future__ import annotations

import math
import re
import shutil
from pathlib import Path

import numpy as np
import pytest

import mechfem
from conftest import ROOT, fourbar_mm_deg
from mechfem import Driven, Mechanism, Motion, Output
from mechfem.output.files import print_file_lines
from mechfem.studies.bands import deck_bands, tolerance_bands

DECK = ROOT / "crates/mechfem-deck/tests/decks/valid/tolerance_fourbar.mec"
MOTION = Motion.by(24, 2 * math.pi)


def fourbar() -> Mechanism:
    m = Mechanism("fourbar")
    A0, B0 = m.fixed("A0", 0.0, 0.0), m.fixed("B0", 4.0, 0.0)
    A, B = m.point("A", 1.0, 0.0), m.point("B", 3.5, 2.5)
    m.bar("crank", A0, A, length=1.0, angle=Driven(start=0.0, name="phi"))
    m.bar("coupler", A, B, length=3.5)
    m.bar("rocker", B0, B, length=3.0, angle=Output("psi"))
    return m


def _run_with(tmp_path: Path, text: str, line: str, number: str, value: float) -> mechfem.RunResult:
    """The deck with the number ``number`` of the first line starting with ``line`` replaced by ``value``, run."""
    pattern = re.compile(rf"^({re.escape(line)}\s+){re.escape(number)}$", re.M)
    changed, n = pattern.subn(lambda m: f"{m.group(1)}{value!r}", text, count=1)
    assert n == 1, line
    path = tmp_path / "perturbed.mec"
    path.write_text(changed.replace("TOLERANCE\n", "TOLERANCE_OFF\n").split("TOLERANCE_OFF\n")[0] + "END\n")
    return mechfem.run_deck(path)


def test_deck_bands_are_the_central_differences_of_whole_runs(tmp_path: Path) -> None:
    # The deck is in mm and degrees: the sensitivities, tolerances and bands are in them too.
    result = mechfem.run_deck(DECK)
    bands = deck_bands(result)
    assert bands is not None and bands.positions == 37
    text = DECK.read_text()
    # (the line and the number written there, the PARA/XFIX line that sets it, its perturbation in mm)
    dims = {
        "crank_length": ("PARA 1", "10.0"),
        "rocker_length": ("     5", "30.0"),
        "row 4 (LENV(2))": ("     4", "12.0"),
        "B0.x": ("     3", "40.0"),
    }
    assert list(bands.tolerances) == list(dims) and bands.tolerances["B0.x"] == 0.1
    sources = {"psi": 100, "C.y": 101, "dpsi/dphi": 102}
    assert list(bands.bands) == list(sources)
    h = 1e-3
    for k, (name, (line, number)) in enumerate(dims.items()):
        # PARA 5 and PARA 4 are repetition lines of PARA; XFIX 3 one of XFIX: the first match after its keyword.
        start = text.index("PARA") if name != "B0.x" else text.index("XFIX")
        head, tail = text[:start], text[start:]
        plus = _run_with(tmp_path, head + tail, line, number, float(number) + h)
        minus = _run_with(tmp_path, head + tail, line, number, float(number) - h)
        for band, b in sources.items():
            fd = (plus.buffers[b] - minus.buffers[b]) / (2 * h)
            exact = bands[band].sensitivity[:, k]
            scale = max(1.0, float(np.abs(exact).max()))
            assert np.allclose(exact, fd, rtol=1e-5, atol=1e-6 * scale), (name, band, np.abs(exact - fd).max())
    for band, b in sources.items():
        # The nominal values are the run's own buffers (each run converged to the deck's ACCURACY).
        assert np.allclose(bands[band].value, result.buffers[b], rtol=1e-8, atol=1e-8)
        s, t = bands[band].sensitivity, np.array(list(bands.tolerances.values()))
        assert np.allclose(bands[band].worst, np.abs(s) @ t) and np.allclose(bands[band].rss, np.sqrt((s * s) @ t**2))


def test_print_file_gives_the_widest_band_where_it_is_and_the_shares_largest_first() -> None:
    result = mechfem.run_deck(DECK)
    bands = deck_bands(result)
    assert bands is not None
    lines = print_file_lines(result)
    start = lines.index("TOLERANCE BANDS")
    section = lines[start : lines.index("LIMIT POSITIONS")]
    psi = bands["psi"]
    k = psi.at
    assert psi.worst[k] == psi.worst.max()
    assert any(
        f"+-{psi.worst[k]:.6g} deg worst case" in line
        and f"position {k + 1} (phi = {bands.inputs[k, 0]:.6g} deg)" in line
        for line in section
    )
    # The shares' rows, in order of their deviation |s| t; they add up to the worst case.
    at = section.index("  psi (BUFTOL 100 200: worst case 200, RSS 201)")
    rows = [section[at + 4 + j].split() for j in range(4)]
    deviations = [float(r[2]) for r in rows if len(r) == 5]
    assert deviations == sorted(deviations, reverse=True)
    assert math.isclose(sum(s.deviation for s in psi.shares()), psi.worst[k], rel_tol=1e-12)
    assert math.isclose(sum(s.of_variance for s in psi.shares()), 1.0, rel_tol=1e-12)
    assert rows[0][0] == "B0.x"


def test_a_deck_without_tolerance_has_no_section_and_the_same_print_file(tmp_path: Path) -> None:
    text = DECK.read_text()
    plain = tmp_path / "plain.mec"
    plain.write_text(text[: text.index("TOLERANCE")] + "END\n")
    shutil.copy(DECK, tmp_path / "banded.mec")
    a, b = mechfem.run_deck(plain), mechfem.run_deck(tmp_path / "banded.mec")
    assert deck_bands(a) is None
    assert "TOLERANCE BANDS" not in print_file_lines(a)
    for n in a.buffers:
        assert np.array_equal(a.buffers[n], b.buffers[n])


def test_python_bands_by_name_are_the_central_differences_of_whole_runs() -> None:
    mech = fourbar()
    tol = {"crank.length": 0.01, "rocker.length": 0.02, "B0": 0.02}
    bands = tolerance_bands(mech, tol, ["psi", "B.y"], motion=MOTION)
    assert list(bands.tolerances) == ["crank.length", "rocker.length", "B0.x", "B0.y"]
    assert bands.input_names == ["phi"] and bands.positions == 25
    h = 1e-6
    # Two of the four dimensions, one of each kind, keep the test short; the deck's test checks every kind.
    for k, name in [(0, "crank.length"), (3, "B0.y")]:
        value = mech[name].value
        plus = mech.variant({name: value + h}).run(MOTION)
        minus = mech.variant({name: value - h}).run(MOTION)
        for q in ("psi", "B.y"):
            fd = (plus.value(q) - minus.value(q)) / (2 * h)
            assert np.allclose(bands[q].sensitivity[:, k], fd, rtol=1e-5, atol=1e-7), (name, q)
    frame = bands.to_pandas()
    assert list(frame.columns) == ["phi", "psi", "psi worst", "psi rss", "B.y", "B.y worst", "B.y rss"]
    assert np.array_equal(frame["psi worst"].to_numpy(), bands["psi"].worst)


def test_linear_bands_against_the_monte_carlo_study() -> None:
    # Uniform draws within +-t of small tolerances: at the position of the widest band, every sampled deviation
    # lies within the worst case (to first order; the second-order rest is far below 1% of it here), and the sampled
    # standard deviation times sqrt(3) is the RSS band (a uniform draw within +-t has the standard deviation t/sqrt 3).
    mech = fourbar()
    tol = {"crank.length": 0.002, "rocker.length": 0.004, "B0.x": 0.004}
    bands = tolerance_bands(mech, tol, ["psi"], motion=MOTION)
    psi = bands["psi"]
    k = psi.at
    study = mechfem.tolerance_study(
        mech,
        tol,
        {"psi_k": lambda a: float(a.value("psi")[k])},
        n=400,
        seed=3,
        distribution="uniform",
        motion=MOTION,
    )
    spread = study.spread["psi_k"]
    assert spread.n == 400 and math.isclose(spread.nominal, psi.value[k], rel_tol=1e-12)
    deviation = max(spread.max - spread.nominal, spread.nominal - spread.min)
    assert deviation <= psi.worst[k] * 1.01
    # 400 draws estimate a standard deviation to about 3%.
    assert spread.std * math.sqrt(3) == pytest.approx(psi.rss[k], rel=0.1)


def test_dyn_ana_bands_are_those_of_its_kinematics(tmp_path: Path) -> None:
    text = DECK.read_text()
    dyn = tmp_path / "dyn.mec"
    dyn.write_text(text.replace("KIN ANA", "DYN ANA", 1).replace("MOVEMENT", "DYNAMICS\nMASS 1 1.0 5 0\nMOVEMENT", 1))
    kin, dyn_bands = deck_bands(mechfem.run_deck(DECK)), deck_bands(mechfem.run_deck(dyn))
    assert kin is not None and dyn_bands is not None
    for name, band in kin.bands.items():
        assert np.array_equal(band.sensitivity, dyn_bands[name].sensitivity)
        assert np.array_equal(band.worst, dyn_bands[name].worst)


def test_a_failed_band_run_leaves_the_print_file_standing(monkeypatch: pytest.MonkeyPatch) -> None:
    from mechfem.errors import MechfemError
    from mechfem.studies import bands as module

    def fail(*_: object) -> None:
        raise MechfemError("no sensitivities here")

    monkeypatch.setattr(module._core, "deck_tolerance", fail)
    lines = print_file_lines(mechfem.run_deck(DECK))
    at = lines.index("TOLERANCE BANDS")
    assert lines[at + 2] == "  no sensitivities here" and "LIMIT POSITIONS" in lines


def test_a_mechanism_that_cannot_assemble_is_told_in_its_own_words() -> None:
    from deck.test_python_words import speaks_python

    broken = fourbar()
    broken.set("rocker.length", 10.0)  # longer than the other three links together
    with pytest.raises(mechfem.MechfemError) as err:
        tolerance_bands(broken, {"crank.length": 0.01}, ["psi"], motion=MOTION)
    speaks_python(str(err.value))
    with pytest.raises(ValueError, match="moves: its place follows"):
        tolerance_bands(fourbar(), {"A.x": 0.01}, ["psi"], motion=MOTION)


def test_bands_of_a_motion_that_stops_are_those_up_to_there() -> None:
    short = fourbar()
    short.set("rocker.length", 0.5)  # not a crank-rocker: the crank meets a limit position
    with pytest.warns(mechfem.IncompleteRunWarning, match="stopped after position 6 of 25"):
        bands = tolerance_bands(short, {"crank.length": 0.01}, ["psi"], motion=MOTION)
    assert bands.positions == 6 and bands["psi"].worst.shape == (6,)


def test_python_bands_are_in_the_models_units() -> None:
    # The four-bar in mm and degrees: tolerances in mm, psi and its band in degrees, sensitivities in deg/mm.
    m = fourbar_mm_deg()
    motion = Motion.by(12, 360)
    bands = tolerance_bands(m, {"crank.length": 0.05}, ["psi"], motion=motion)
    assert bands.units == {"crank.length": "mm"} and bands["psi"].unit == "deg" and bands.input_units == ["deg"]
    assert np.allclose(bands.inputs[:, 0], np.linspace(0.0, 360.0, 13))
    h = 1e-4
    plus, minus = (m.variant({"crank.length": 10.0 + d}).run(motion).value("psi") for d in (h, -h))
    assert np.allclose(bands["psi"].sensitivity[:, 0], (plus - minus) / (2 * h), rtol=1e-6, atol=1e-8)
    assert np.allclose(bands["psi"].worst, np.abs(bands["psi"].sensitivity[:, 0]) * 0.05)


def test_a_named_models_run_has_no_deck_bands(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    # Even with a deck of the same name and a TOLERANCE block in the working folder.
    shutil.copy(DECK, tmp_path / "fourbar.mec")
    monkeypatch.chdir(tmp_path)
    result = fourbar().run(MOTION)
    assert deck_bands(result) is None and "TOLERANCE BANDS" not in print_file_lines(result)


def test_a_transfer_function_is_named_by_its_label() -> None:
    from mechfem import Q

    bands = tolerance_bands(fourbar(), {"crank.length": 0.01}, ["psi", Q("psi", 1)], motion=MOTION)
    assert list(bands.bands) == ["psi", "dpsi/dphi"]
    # d/dp of dpsi/dphi against the central difference of the first-order transfer functions of two runs.
    h = 1e-6
    runs = [fourbar().variant({"crank.length": 1.0 + d}).run(MOTION) for d in (h, -h)]
    fd = (runs[0].transfer("psi", 1) - runs[1].transfer("psi", 1)) / (2 * h)
    assert np.allclose(bands["dpsi/dphi"].sensitivity[:, 0], fd, rtol=1e-5, atol=1e-6)


def test_python_bands_write_and_read_no_deck_text(monkeypatch: pytest.MonkeyPatch) -> None:
    # The mechanism reaches the core through the typed builder: no deck writer, no deck reader of text.
    from mechfem import _core
    from mechfem.deck import deckio

    expected = tolerance_bands(fourbar(), {"crank.length": 0.01, "B0": 0.02}, ["psi"], motion=MOTION)

    def refuse(*_: object, **__: object) -> None:
        raise AssertionError("deck text written or read")

    monkeypatch.setattr(deckio, "write", refuse)
    monkeypatch.setattr(deckio, "write_text", refuse)
    for name in ("deck_tolerance", "run_deck_text", "describe_deck_text", "DesignModel", "Model"):
        monkeypatch.setattr(_core, name, refuse)
    bands = tolerance_bands(fourbar(), {"crank.length": 0.01, "B0": 0.02}, ["psi"], motion=MOTION)
    assert np.array_equal(bands["psi"].worst, expected["psi"].worst)


def test_deck_and_python_give_identical_bands() -> None:
    # The deck's model read into a Mechanism and toleranced by name gives the deck's bands, number for number.
    deck = deck_bands(mechfem.run_deck(DECK))
    assert deck is not None
    with pytest.warns(UserWarning, match="TOLERANCE block is left out"):
        mech = Mechanism.from_deck(DECK)
    rows = {r.name: r for r in mech.rows}
    assert "crank_length" in rows and "rocker_length" in rows
    v_of_c = next(r for r in mech.rows if r.kind == "prescribed" and r.value == 12.0)
    tol = {"crank_length": 0.05, "rocker_length": 0.05, v_of_c.name: 0.1, "B0.x": 0.1}
    python = tolerance_bands(mech, tol, ["psi", "C.y"])
    for name in ("psi", "C.y"):
        a, b = deck[name], python[name]
        assert np.array_equal(a.worst, b.worst) and np.array_equal(a.rss, b.rss), name
        assert np.array_equal(a.sensitivity, b.sensitivity) and a.at == b.at


def test_worst_case_band_is_the_sum_of_central_differences_times_tolerances() -> None:
    # sum_k |dq/dp_k| t_k with each dq/dp_k a central difference of two whole runs.
    mech = fourbar()
    tol = {"crank.length": 0.01, "rocker.length": 0.02, "B0.x": 0.02}
    bands = tolerance_bands(mech, tol, ["psi"], motion=MOTION)
    h = 1e-6
    worst = np.zeros(bands.positions)
    squares = np.zeros(bands.positions)
    for name, t in tol.items():
        value = mech[name].value
        plus, minus = (mech.variant({name: value + d}).run(MOTION).value("psi") for d in (h, -h))
        fd = (plus - minus) / (2 * h)
        worst += np.abs(fd) * t
        squares += (fd * t) ** 2
    assert np.allclose(bands["psi"].worst, worst, rtol=1e-6, atol=1e-10)
    assert np.allclose(bands["psi"].rss, np.sqrt(squares), rtol=1e-6, atol=1e-10)
