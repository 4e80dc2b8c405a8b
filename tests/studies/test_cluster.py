"""Studies on an executor: a Dask LocalCluster of two worker processes gives the local run's numbers bit for bit,
loses nothing when a worker is killed mid-study, and keeps every variant's row when variants or chunks fail."""

from __future__ import annotations

import concurrent.futures
import math
import multiprocessing
import os
import signal
import sys
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import numpy as np
import pytest

import mechfem
from conftest import ROOT
from mechfem import Mechanism, Motion, Q
from mechfem.studies.cluster import TaskFailed, chunk_size, run_tasks
from model.test_model_api import python_code, supply
from studies.test_batch import fourbar

pytestmark = pytest.mark.cluster

MOTION = Motion.by(72, 2 * math.pi)
NO_DASK = "dask[distributed] is not installed: pip install mechfem[dask]"
MEASURES = {
    "stroke": lambda r: float(np.ptp(r.output("psi"))),
    "d2": lambda r: float(np.max(np.abs(r.output("psi", 2)))),
}


@pytest.fixture(scope="module")
def client() -> Iterator[Any]:
    distributed = pytest.importorskip("distributed", reason=NO_DASK)
    try:
        cluster = distributed.LocalCluster(
            n_workers=2, processes=True, threads_per_worker=1, dashboard_address=":0", silence_logs=50
        )
    except Exception as err:  # pragma: no cover - a machine that cannot start worker processes
        pytest.skip(f"dask cannot start worker processes here: {type(err).__name__}: {err}")
    c = distributed.Client(cluster)
    yield c
    c.close()
    cluster.close()


def same_table(a: mechfem.Study, b: mechfem.Study) -> None:
    assert list(a.columns) == list(b.columns) and len(a) == len(b)
    for name, col in a.columns.items():
        if col.dtype == object:
            assert list(col) == list(b[name]), name
        else:
            assert np.array_equal(col, b[name], equal_nan=col.dtype.kind == "f"), name


def test_a_sweep_on_the_cluster_is_the_local_sweep_bit_for_bit(client: Any) -> None:
    # Rockers from 1 to 8: long ones cannot be assembled, a short one stops at a limit position.
    grid = {"rocker.length": np.linspace(1.0, 8.0, 15), "B0.x": [3.9, 4.1]}
    local = mechfem.sweep(fourbar(), grid, MEASURES, motion=MOTION, progress=False)
    remote = mechfem.sweep(fourbar(), grid, MEASURES, motion=MOTION, progress=False, executor=client, chunk_size=5)
    same_table(local, remote)
    assert not local["ok"].all() and local["ok"].any() and not local["complete"][local["ok"]].all()
    # A model function: one deck per variant, shipped with its chunk; full results on request.
    sets = [{"rocker": r, "ground": g} for r in (2.8, 3.0, 10.0) for g in (3.9, 4.1)]
    local = mechfem.sweep(fourbar, sets, MEASURES, motion=MOTION, progress=False, keep_results=True)
    remote = mechfem.sweep(fourbar, sets, MEASURES, motion=MOTION, progress=False, keep_results=True, executor=client)
    same_table(local, remote)
    assert local.results is not None and remote.results is not None
    for a, b in zip(local.results, remote.results, strict=True):
        assert type(a) is type(b)
        if isinstance(a, mechfem.Analysis):
            assert isinstance(b, mechfem.Analysis) and np.array_equal(a.coords, b.coords)
            assert b.parameters == a.parameters
        else:
            assert str(a) == str(b)


def test_run_many_on_the_cluster(client: Any) -> None:
    mechs = [fourbar(r) for r in (3.2, 10.0, 2.8)]
    out = mechfem.run_many(mechs, MOTION, progress=False, executor=client, chunk_size=2)
    assert isinstance(out[1], mechfem.ConvergenceError)
    for k in (0, 2):
        got = out[k]
        assert isinstance(got, mechfem.Analysis)
        assert np.array_equal(got.output("psi"), mechs[k].run(MOTION).output("psi"))


def test_a_worker_killed_mid_study_loses_nothing(client: Any) -> None:
    lengths = {"rocker.length": np.linspace(2.6, 3.4, 1200)}
    motion = Motion.by(360, 2 * math.pi)
    local = mechfem.sweep(fourbar(), lengths, MEASURES, motion=motion, progress=False)
    pids = list(client.run(os.getpid).values())
    killed: list[int] = []

    def kill_one(done: int, total: int) -> None:
        # When the first chunk is back, the other worker is busy with its own: kill it.
        if not killed:
            os.kill(pids[0], signal.SIGKILL)
            killed.append(pids[0])

    remote = mechfem.sweep(
        fourbar(), lengths, MEASURES, motion=motion, progress=kill_one, executor=client, chunk_size=100
    )
    assert killed
    same_table(local, remote)
    assert remote["ok"].all()
    client.wait_for_workers(2, timeout=60)
    assert pids[0] not in client.run(os.getpid).values()


def test_failing_variants_and_chunks_are_rows_with_their_reason(client: Any, tmp_path: Path) -> None:
    def picky(r: mechfem.Analysis) -> float:
        if r.parameters["rocker"] == 2.8:
            raise ZeroDivisionError("no stroke for this one")
        return float(np.ptp(r.output("psi")))

    sets = [{"rocker": 3.0}, {"rocker": 10.0}, {"rocker": 2.8}, {"rocker": 3.2}]
    study = mechfem.sweep(fourbar, sets, {"stroke": picky}, motion=MOTION, progress=False, executor=client)
    assert list(study["ok"]) == [True, False, True, True]
    assert study["error"][1].startswith("position 1 of the mechanism 'fourbar' cannot be computed: Newton iteration")
    assert study["error"][2] == "measure 'stroke': ZeroDivisionError: no stroke for this one"
    assert math.isnan(study["stroke"][2]) and study["stroke"][3] > 0 and study["error"][3] == ""
    same_table(study, mechfem.sweep(fourbar, sets, {"stroke": picky}, motion=MOTION, progress=False))
    # A measure from a module the workers cannot import: every chunk fails, every row says why.
    (tmp_path / "only_here.py").write_text("def swing(r):\n    return 1.0\n")
    sys.path.insert(0, str(tmp_path))
    try:
        import only_here  # type: ignore[import-not-found]

        study = mechfem.sweep(
            fourbar, sets, {"swing": only_here.swing}, motion=MOTION, progress=False, executor=client, retries=0
        )
    finally:
        sys.path.remove(str(tmp_path))
        sys.modules.pop("only_here", None)
    assert len(study) == 4 and not study["ok"].any() and list(study["rocker"]) == [3.0, 10.0, 2.8, 3.2]
    assert all("the task of this chunk failed" in e and "only_here" in e for e in study["error"])


def test_a_failed_task_is_kept_in_its_place(client: Any) -> None:
    out = run_tasks(client, lambda x: 1.0 / x, [1.0, 0.0, 4.0], retries=1)
    assert out[0] == 1.0 and out[2] == 0.25
    assert isinstance(out[1], TaskFailed) and out[1].reason.startswith("ZeroDivisionError")


def test_executors_of_the_standard_library() -> None:
    grid = {"rocker.length": np.linspace(2.6, 3.4, 9)}
    local = mechfem.sweep(fourbar(), grid, MEASURES, motion=MOTION, progress=False)
    with concurrent.futures.ThreadPoolExecutor(2) as pool:
        same_table(local, mechfem.sweep(fourbar(), grid, MEASURES, motion=MOTION, progress=False, executor=pool))
    # Processes get the task by cloudpickle: the lambdas of MEASURES travel with it.
    spawn = multiprocessing.get_context("spawn")
    with concurrent.futures.ProcessPoolExecutor(2, mp_context=spawn) as pool:
        same_table(local, mechfem.sweep(fourbar(), grid, MEASURES, motion=MOTION, progress=False, executor=pool))


def test_chunks_are_about_a_second_and_every_slot_gets_two() -> None:
    with concurrent.futures.ThreadPoolExecutor(4) as pool:
        assert chunk_size(100_000, 361, pool) == 416
        assert chunk_size(100, 361, pool) == 13
        assert chunk_size(100, 361, pool, requested=7) == 7
        with pytest.raises(ValueError, match="at least 1"):
            chunk_size(100, 361, pool, requested=0)


def test_multi_start_returns_the_best_and_every_start(client: Any) -> None:
    supply_deck = Mechanism.from_deck(ROOT / "examples" / "supply" / "supply.mec").variant(kappa=-5.25)
    vary = {"kappa": (-5.5, -5.0), "crank.length": (0.3, 1.2)}
    target = [mechfem.TargetExtremum(Q("delta", 2), "delta", 0.0)]
    local = mechfem.optimize(supply_deck, vary, targets=target, steps=30, starts=4, seed=3)
    remote = mechfem.optimize(supply_deck, vary, targets=target, steps=30, starts=4, seed=3, executor=client)
    assert len(local.starts) == len(remote.starts) == 4
    assert local.starts[0].start == {"kappa": -5.25, "crank.length": 0.4}
    for a, b in zip(local.starts, remote.starts, strict=True):
        assert a.start == b.start and a.values == b.values and a.message == b.message
        assert a.objective == b.objective or (math.isnan(a.objective) and math.isnan(b.objective))
    # Draws with a long crank cannot be assembled or moved: they are passed over with the reason, on the
    # cluster as here, and the starts optimised are the draws that can.
    assert [s.start for s in remote.rejected] == [s.start for s in local.rejected]
    assert remote.rejected and all(
        s.start["crank.length"] > 0.55 and s.message.startswith("draw passed over") for s in remote.rejected
    )
    assert remote.drawn == local.drawn == 3 + len(remote.rejected)
    failed = [s for s in remote.starts if s.values is None]
    assert remote.usable == local.usable == (4 - len(failed)) / 4
    found = [s.objective for s in remote.starts if s.values is not None]
    assert remote.objective == min(found) and remote.values == local.values
    assert remote.run().complete


def test_a_tolerance_study_on_the_cluster_is_the_local_one(client: Any) -> None:
    tolerances = {"crank.length": 0.002, "B0": 0.005, "link.length": 0.01}
    outputs = {"swing": lambda a: float(np.ptp(a.output("delta")))}
    local = mechfem.tolerance_study(supply(), tolerances, outputs, n=300, seed=7, motion=MOTION)
    remote = mechfem.tolerance_study(supply(), tolerances, outputs, n=300, seed=7, motion=MOTION, executor=client)
    assert local.spread == remote.spread and local.failed == remote.failed == 0
    same_table(local.study, remote.study)
    s = local.spread["swing"]
    nominal = float(np.ptp(supply().run(MOTION).output("delta")))
    assert s.nominal == nominal and s.n == 300 and s.min < nominal < s.max
    assert s.percentiles[5.0] < s.percentiles[50.0] < s.percentiles[95.0]
    # The draws: normal with the tolerance at three standard deviations, B0's two co-ordinates apart.
    crank = local.study["crank.length"]
    assert abs(np.mean(crank) - 0.4) < 0.0005 and 0.0005 < np.std(crank) < 0.0008
    assert local.study["B0"][0] != remote.study["B0"][1] and "swing: nominal" in repr(local)
    uniform = mechfem.tolerance_study(supply(), {"crank.length": 0.002}, outputs, n=50, distribution="uniform")
    assert np.all(np.abs(uniform.study["crank.length"] - 0.4) <= 0.002)


def test_tolerance_study_mistakes() -> None:
    outputs = {"swing": lambda a: 0.0}
    with pytest.raises(ValueError, match="no value to draw"):
        mechfem.tolerance_study(supply(), {"delta": 0.1}, outputs)
    with pytest.raises(ValueError, match="normal"):
        mechfem.tolerance_study(supply(), {"crank.length": 0.1}, outputs, distribution="triangle")  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="not negative"):
        mechfem.tolerance_study(supply(), {"crank.length": -0.1}, outputs)


def test_the_cluster_page_runs(monkeypatch: pytest.MonkeyPatch) -> None:
    pytest.importorskip("distributed", reason=NO_DASK)
    code = python_code(ROOT / "docs" / "cluster.md")
    assert "LocalCluster" in code
    monkeypatch.chdir(ROOT)
    namespace: dict[str, object] = {"__name__": "docs_cluster_md"}
    exec(compile(code, "docs/cluster.md", "exec"), namespace)
