"""Resource limits: a run whose results would not fit in the memory limit is refused before it starts."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import mechfem
from conftest import ROOT, Cli
from mechfem._util.limits import DEFAULT_MEMORY_LIMIT, memory_limit, parse_size

FOURBAR = ROOT / "examples" / "fourbar" / "fourbar.mec"
TOO_MANY = ROOT / "tests" / "decks" / "too_many_positions.mec"


@pytest.mark.parametrize(
    ("text", "size"),
    [("1048576", 1048576), ("512M", 512 * 1024**2), ("4G", 4 * 1024**3), ("1.5GiB", 3 * 1024**3 // 2), ("2k", 2048)],
)
def test_sizes_are_read_with_binary_units(text: str, size: int) -> None:
    assert parse_size(text) == size


@pytest.mark.parametrize("text", ["", "lots", "-1G", "0", "1e9", "4 GB of memory", "nan"])
def test_a_wrong_size_is_a_clear_error(text: str) -> None:
    with pytest.raises(ValueError, match="size"):
        parse_size(text)


def test_the_limit_comes_from_the_argument_then_the_environment(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.delenv("MECHFEM_MEMORY_LIMIT", raising=False)
    assert memory_limit() == DEFAULT_MEMORY_LIMIT
    monkeypatch.setenv("MECHFEM_MEMORY_LIMIT", "3G")
    assert memory_limit() == 3 * 1024**3
    assert memory_limit("1M") == 1024**2
    monkeypatch.setenv("MECHFEM_MEMORY_LIMIT", "plenty")
    with pytest.raises(ValueError, match="MECHFEM_MEMORY_LIMIT"):
        memory_limit()


def test_ten_million_positions_are_refused_before_the_run(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.delenv("MECHFEM_MEMORY_LIMIT", raising=False)
    calls = []
    with pytest.raises(mechfem.ResourceError, match=r"10000001 positions x 13 values.*limit of 2 GiB"):
        mechfem.run_deck(TOO_MANY, progress=lambda done, total: calls.append(done))
    assert calls == [], "the run started"


def test_the_estimate_counts_every_recorded_value() -> None:
    # The four-bar example records 18 buffers, time, det(D^c), 2 hodograph derivatives and 10 co-ordinates:
    # 32 numbers per position, 145 positions, 3 x 8 bytes each at the peak.
    need = 145 * 32 * 24
    mechfem.run_deck(FOURBAR, memory_limit=need)
    with pytest.raises(mechfem.ResourceError):
        mechfem.run_deck(FOURBAR, memory_limit=need - 1)


def test_model_api_and_batch_obey_the_limit(monkeypatch: pytest.MonkeyPatch) -> None:
    m = mechfem.Mechanism.from_deck(FOURBAR)
    monkeypatch.setenv("MECHFEM_MEMORY_LIMIT", "10k")
    with pytest.raises(mechfem.ResourceError):
        m.run()
    # A batch reports each variant's error in its place.
    assert all(isinstance(r, mechfem.ResourceError) for r in mechfem.run_many([m, m], workers=2))
    monkeypatch.delenv("MECHFEM_MEMORY_LIMIT")
    assert m.run().report.complete


def test_cli_refuses_and_writes_nothing(cli: Cli, tmp_path: Path) -> None:
    out = tmp_path / "out"
    proc = cli("run", TOO_MANY, "-o", out)
    assert proc.returncode == 1
    assert "more than the memory limit" in proc.stderr and "--memory-limit" in proc.stderr
    assert not out.exists() or not any(out.iterdir())


def test_cli_memory_limit_option(cli: Cli, tmp_path: Path) -> None:
    proc = cli("run", FOURBAR, "-o", tmp_path, "--memory-limit", "1k")
    assert proc.returncode == 1 and "limit of 1 KiB" in proc.stderr
    proc = cli("run", FOURBAR, "-o", tmp_path, "--memory-limit", "64M")
    assert proc.returncode == 0, proc.stderr
    proc = cli("run", FOURBAR, "-o", tmp_path, "--memory-limit", "much")
    assert proc.returncode == 2 and "not a size" in proc.stderr


@pytest.mark.parametrize("text", ["18446744073709551616", "16777216T", "1e30", "99999999999999999999999G"])
def test_a_limit_beyond_64_bits_is_a_usage_error(cli: Cli, tmp_path: Path, text: str) -> None:
    proc = cli("run", FOURBAR, "-o", tmp_path, "--memory-limit", text)
    assert proc.returncode == 2, proc.stderr
    assert "--memory-limit" in proc.stderr and "Traceback" not in proc.stderr


def test_the_largest_limit_is_taken_exactly() -> None:
    assert parse_size("18446744073709551615") == 2**64 - 1
    with pytest.raises(ValueError, match="at most 18446744073709551615 bytes"):
        parse_size("18446744073709551616")


def test_a_limit_beyond_64_bits_from_the_environment_is_a_usage_error(
    cli: Cli, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setenv("MECHFEM_MEMORY_LIMIT", "18446744073709551616")
    proc = cli("run", FOURBAR, "-o", tmp_path)
    assert proc.returncode == 2 and "MECHFEM_MEMORY_LIMIT" in proc.stderr, proc.stderr


@pytest.mark.parametrize("limit", [10**30, 2**64, 0, -1, 1.5e9, "1e30"])
def test_a_wrong_memory_limit_of_the_api_is_a_value_error(limit: object) -> None:
    with pytest.raises(ValueError, match="memory limit|size"):
        mechfem.run_deck(FOURBAR, memory_limit=limit)  # type: ignore[arg-type]


@pytest.mark.parametrize("workers", [-1, 0, 10**30, 2.5, True])
def test_a_wrong_number_of_workers_is_a_value_error(workers: object) -> None:
    m = mechfem.Mechanism.from_deck(FOURBAR)
    with pytest.raises(ValueError, match="workers is the number of threads"):
        mechfem.sweep(m, {"r2": [1.0, 2.0]}, workers=workers, progress=False)  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="workers is the number of threads"):
        mechfem.run_many([m], workers=workers, progress=False)  # type: ignore[arg-type]


def test_workers_may_be_any_whole_number_type() -> None:
    m = mechfem.Mechanism.from_deck(FOURBAR)
    runs = mechfem.run_many([m, m], workers=np.int64(2), progress=False)
    assert len(runs) == 2 and all(isinstance(r, mechfem.RunResult) for r in runs)
