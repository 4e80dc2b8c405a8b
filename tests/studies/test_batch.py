"""Design studies: many variants on worker threads give what one run each gives, failures stay in the table."""

from __future__ import annotations

import io
import math
import subprocess
import sys
import types

import numpy as np
import pytest

import mechfem
from conftest import ROOT
from mechfem import Driven, Mechanism, Motion, Output
from mechfem.studies.batch import default_measures
from model.test_model_api import supply

TURN = 2 * math.pi
MOTION = Motion.by(36, TURN)


def fourbar(rocker: float = 3.0, ground: float = 4.0) -> Mechanism:
    m = Mechanism("fourbar")
    A0, B0 = m.fixed("A0", 0.0, 0.0), m.fixed("B0", ground, 0.0)
    A, B = m.point("A", 1.0, 0.0), m.point("B", 3.5, 2.5)
    m.bar("crank", A0, A, length=1.0, angle=Driven(start=0.0, name="phi"))
    m.bar("coupler", A, B, length=3.5)
    m.bar("rocker", B0, B, length=rocker, angle=Output("psi"))
    return m


def stroke(r: mechfem.Analysis) -> float:
    return float(np.ptp(r.output("psi")))


def test_sweep_of_a_named_value_gives_the_single_runs() -> None:
    base = fourbar()
    lengths = np.linspace(2.6, 3.4, 5)
    study = mechfem.sweep(base, {"rocker.length": lengths}, {"stroke": stroke}, motion=MOTION, progress=False)
    assert len(study) == 5 and study.parameters == ["rocker.length"] and study.measures == ["stroke"]
    assert np.array_equal(study["rocker.length"], lengths) and study["ok"].all() and study["complete"].all()
    for k, length in enumerate(lengths):
        single = base.variant({"rocker.length": float(length)}).run(MOTION)
        assert study["stroke"][k] == stroke(single)
    # The base mechanism is not changed by the study.
    assert base["rocker.length"].value == 3.0


def test_sweep_of_a_builder_function_over_a_grid() -> None:
    study = mechfem.sweep(fourbar, {"rocker": [2.8, 3.0], "ground": [3.9, 4.0, 4.1]}, motion=MOTION, progress=False)
    assert len(study) == 6
    assert list(study["rocker"]) == [2.8, 2.8, 2.8, 3.0, 3.0, 3.0]
    assert list(study["ground"]) == [3.9, 4.0, 4.1] * 2
    assert set(study.measures) == {"psi.min", "psi.max", "min_abs_det"}
    r = fourbar(3.0, 4.1).run(MOTION)
    assert study.records()[5]["psi.max"] == float(np.max(r.output("psi")))


def test_one_worker_and_several_give_the_same_table() -> None:
    ks = np.linspace(-5.25, -5.1, 8)
    measures = {"stroke": lambda r: float(np.ptp(r.output("delta"))), "d2": lambda r: float(r.output("delta", 2)[3])}
    one = mechfem.sweep(supply(), {"kappa": ks}, measures, motion=MOTION, workers=1, progress=False)
    two = mechfem.sweep(supply(), {"kappa": ks}, measures, motion=MOTION, workers=2, progress=False)
    for name in ("kappa", "stroke", "d2", "positions"):
        assert np.array_equal(one[name], two[name])


def test_failing_variants_are_rows_of_the_table_not_exceptions() -> None:
    sets = [{"rocker": 3.0}, {"rocker": 10.0}, {"rocker": 2.0}]
    study = mechfem.sweep(fourbar, sets, {"stroke": stroke}, motion=MOTION, progress=False, keep_results=True)
    assert list(study["ok"]) == [True, False, True]
    assert study["error"][1].startswith("position 1 of the mechanism 'fourbar' cannot be computed: Newton iteration")
    assert study["error"][0] == ""
    assert math.isnan(study["stroke"][1]) and study["positions"][1] == 0
    assert study.results is not None and isinstance(study.results[1], mechfem.ConvergenceError)
    assert isinstance(study.results[0], mechfem.Analysis) and study.results[0].parameters == {"rocker": 3.0}
    best = study.best("stroke", largest=True)
    assert best["rocker"] == 2.0


def test_variants_with_a_deck_mistake_carry_the_model_names() -> None:
    def broken(extra: bool) -> Mechanism:
        m = fourbar()
        if extra:
            m.point("Z", 0.0, 1.0)
        return m

    out = mechfem.run_many([broken(False), broken(True)], MOTION, progress=False)
    assert isinstance(out[0], mechfem.Analysis) and out[0].complete
    assert isinstance(out[1], mechfem.DeckError) and out[1].name == "Z.x"  # type: ignore[attr-defined]


def test_a_study_of_points_and_rows_gives_the_single_runs_bit_for_bit() -> None:
    # The study changes the numbers of one compiled deck; a single run writes and reads a deck of its own.
    base = fourbar()
    sets = [{"B0": (4.2, 0.1), "crank.length": 0.9}, {"B0": (3.8, -0.1), "rocker.length": 3.2}]
    study = mechfem.sweep(base, sets, {"stroke": stroke}, motion=MOTION, progress=False, keep_results=True)
    assert study.results is not None
    for p, got in zip(sets, study.results, strict=True):
        assert isinstance(got, mechfem.Analysis)
        want = base.variant(p).run(MOTION)
        assert np.array_equal(got.coords, want.coords) and np.array_equal(got.det, want.det)
        assert np.array_equal(got.output("psi", 2), want.output("psi", 2))
        assert got.report.adjust == want.report.adjust


def test_run_many_of_one_mechanism_many_times() -> None:
    m = fourbar()
    out = mechfem.run_many([m, m, m], MOTION, progress=False)
    want = m.run(MOTION)
    for got in out:
        assert isinstance(got, mechfem.Analysis)
        assert np.array_equal(got.coords, want.coords)


def test_points_as_parameters_and_records() -> None:
    study = mechfem.sweep(fourbar(), [{"B0": (4.2, 0.1)}, {"B0": (4.0, 0.0)}], motion=MOTION, progress=False)
    assert study["B0"][0] == (4.2, 0.1)
    recs = study.records()
    assert recs[1]["B0"] == (4.0, 0.0) and recs[1]["ok"] is True
    assert "2 variants, 2 ok" in repr(study)


def test_progress_is_reported_per_variant() -> None:
    calls: list[tuple[int, int]] = []
    mechfem.sweep(fourbar, {"rocker": [2.8, 3.0, 3.2]}, motion=MOTION, progress=lambda d, t: calls.append((d, t)))
    assert [d for d, _ in calls] == [1, 2, 3] and {t for _, t in calls} == {3}


def test_an_error_in_the_progress_callback_stops_the_study() -> None:
    def stop(done: int, total: int) -> None:
        raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        mechfem.sweep(fourbar, {"rocker": [2.8, 3.0, 3.2]}, motion=MOTION, progress=stop)


class Terminal(io.StringIO):
    def isatty(self) -> bool:
        return True


def test_the_progress_bar_counts_variants_on_a_terminal_only(
    capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch
) -> None:
    mechfem.sweep(fourbar, {"rocker": [2.8, 3.0, 3.2]}, motion=MOTION, progress=True)
    assert capsys.readouterr().err == ""
    terminal = Terminal()
    monkeypatch.setattr(sys, "stderr", terminal)
    mechfem.sweep(fourbar, {"rocker": [2.8, 3.0, 3.2]}, motion=MOTION, progress=True)
    lines = terminal.getvalue().split("\r")
    assert any(line.startswith("running:") and "/3 " in line and "variants" in line for line in lines)
    # The bar is one line, cleared when the study ends.
    assert "\n" not in terminal.getvalue() and lines[-2].strip() == ""


def test_table_as_pandas(monkeypatch: pytest.MonkeyPatch) -> None:
    study = mechfem.sweep(fourbar, {"rocker": [2.8, 3.0]}, {"stroke": stroke}, motion=MOTION, progress=False)
    monkeypatch.setitem(sys.modules, "pandas", None)
    with pytest.raises(ImportError, match="pandas"):
        study.to_pandas()
    monkeypatch.undo()
    pd = pytest.importorskip("pandas")
    frame = study.to_pandas()
    assert isinstance(frame, pd.DataFrame) and list(frame.columns[:2]) == ["rocker", "ok"]


def test_default_measures_and_mistakes() -> None:
    assert set(default_measures(fourbar())) == {"psi.min", "psi.max", "min_abs_det"}
    with pytest.raises(ValueError, match="at least one variant"):
        mechfem.sweep(fourbar, [], progress=False)
    with pytest.raises(TypeError, match="not a Mechanism"):
        mechfem.sweep(lambda rocker: None, {"rocker": [1.0]}, progress=False)  # type: ignore[arg-type,return-value]
    with pytest.raises(ValueError, match="used twice"):
        mechfem.sweep(fourbar, {"rocker": [3.0]}, {"ok": stroke}, motion=MOTION, progress=False)


def test_run_many_keeps_the_order() -> None:
    mechs = [fourbar(r) for r in (3.2, 2.8, 3.0)]
    out = mechfem.run_many(mechs, MOTION, workers=2, progress=False)
    for m, r in zip(mechs, out, strict=True):
        assert isinstance(r, mechfem.Analysis) and r.mechanism is m
        assert np.array_equal(r.output("psi"), m.run(MOTION).output("psi"))


def test_the_bench_script_runs() -> None:
    # A smoke test of examples/python/bench_batch.py on a tiny study; it asserts nothing about times.
    script = ROOT / "examples" / "python" / "bench_batch.py"
    args = ["--variants", "4", "--steps", "8", "--repeat", "1"]
    proc = subprocess.run([sys.executable, str(script), *args], capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0, proc.stderr
    assert "4 variants of the supply mechanism" in proc.stdout and "speed-up" in proc.stdout


def test_the_progress_bar_shows_in_a_jupyter_kernel(
    capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch
) -> None:
    # A kernel's stderr is a pipe, not a terminal, yet Jupyter shows it under the cell.
    monkeypatch.setitem(sys.modules, "ipykernel", types.ModuleType("ipykernel"))
    mechfem.sweep(fourbar, {"rocker": [2.8, 3.0, 3.2]}, motion=MOTION, progress=True)
    assert "/3 " in capsys.readouterr().err
