"""The progress bar through a run's phases, and the binary data sets written directly."""

from __future__ import annotations

import io
import sys
from pathlib import Path

import numpy as np
import pytest

import mechfem
from conftest import SUPPLY
from mechfem._util.progress import Console, ProgressBar
from mechfem.output.datasets import MissingDependency, write_npz, write_parquet


class Terminal(io.StringIO):
    """A text stream that says it is a terminal."""

    def isatty(self) -> bool:
        return True


def test_the_bar_names_each_phase_and_counts_it_from_zero() -> None:
    out = Terminal()
    bar = ProgressBar(file=out, mininterval=0)
    assert bar.active
    bar.phase("computing", unit="positions")
    bar(50, 73)
    bar(73, 73)
    bar.phase("pictures", 2, "pictures")
    bar.advance()
    bar.advance()
    bar.close()
    lines = out.getvalue().split("\r")
    assert any(line.startswith("computing: 100%") and "73/73" in line for line in lines)
    assert any(line.startswith("pictures:   0%") and "0/2 " in line for line in lines)
    assert any(line.startswith("pictures: 100%") and "2/2 " in line for line in lines)
    assert not any("computing" in line for line in lines[lines.index(next(x for x in lines if "pictures" in x)) :])
    # One line, redrawn in place, and cleared when the bar closes.
    assert "\n" not in out.getvalue() and lines[-1] == "" and lines[-2].strip() == ""


def test_the_bar_is_silent_when_its_stream_is_not_a_terminal() -> None:
    out = io.StringIO()
    bar = ProgressBar(file=out)
    assert not bar.active
    bar.phase("computing", unit="positions")
    bar(10, 10)
    bar.close()
    assert out.getvalue() == ""


def test_a_forced_bar_draws_on_any_stream_and_show_false_never() -> None:
    out = io.StringIO()
    bar = ProgressBar(show=True, file=out, mininterval=0)
    bar.phase("data set", 1_000_000, "rows")
    bar(1_000_000, 1_000_000)
    bar.close()
    # A large count is shown scaled.
    assert "data set" in out.getvalue() and "1.00M/1.00M" in out.getvalue()
    never = Terminal()
    bar = ProgressBar(show=False, file=never)
    bar.phase("computing")
    bar(1, 1)
    bar.close()
    assert never.getvalue() == ""


def test_lines_written_above_the_bar_reach_their_stream(capsys: pytest.CaptureFixture[str]) -> None:
    out = Terminal()
    bar = ProgressBar(file=out)
    console = Console(bar)
    bar.phase("pictures", 2)
    console.say("wrote a.png")
    console.note("note: something")
    console.close()
    captured = capsys.readouterr()
    assert captured.out == "wrote a.png\n"
    assert captured.err == "note: something\n"


def test_a_quiet_console_says_only_errors(capsys: pytest.CaptureFixture[str]) -> None:
    console = Console(ProgressBar(show=False), quiet=True)
    console.say("wrote a.png")
    console.note("warning: w")
    console.error("error: e")
    console.close()
    captured = capsys.readouterr()
    assert captured.out == "" and captured.err == "error: e\n"


def test_binary_data_sets_hold_the_computed_doubles(tmp_path: Path) -> None:
    from mechfem.results.labels import buffer_labels

    result = mechfem.run_deck(SUPPLY)
    labels = buffer_labels(result)
    names = [labels[n].header() for n in result.storage.savedata]
    with np.load(write_npz(result, tmp_path / "s.npz")) as z:
        assert z.files == ["position", *names]
        assert z["position"].tolist() == list(range(1, result.positions + 1))
        for n, name in zip(result.storage.savedata, names, strict=True):
            assert z[name].view(np.uint64).tolist() == result.buffers[n].view(np.uint64).tolist()
    pq = pytest.importorskip("pyarrow.parquet")
    table = pq.read_table(write_parquet(result, tmp_path / "s.parquet"))
    assert table.column_names == ["position", *names]
    for n, name in zip(result.storage.savedata, names, strict=True):
        values = table.column(name).to_numpy()
        assert values.view(np.uint64).tolist() == result.buffers[n].view(np.uint64).tolist()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["s.npz", "s.parquet"]


def test_parquet_without_pyarrow_names_the_extra(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    result = mechfem.run_deck(SUPPLY)
    monkeypatch.setitem(sys.modules, "pyarrow", None)
    with pytest.raises(MissingDependency, match=r"pip install 'mechfem\[parquet\]'"):
        write_parquet(result, tmp_path / "s.parquet")
    assert list(tmp_path.iterdir()) == []


def test_a_binary_data_set_with_nan_gets_its_notes(tmp_path: Path) -> None:
    from mechfem.output.files import write_outputs

    result = mechfem.run_deck(SUPPLY)
    result.buffers[101][5] = np.nan
    written = write_outputs(result, tmp_path, fmt="npz")
    assert [p.name for p in written] == ["supply.npz", "supply.notes.txt", "supply.prt"]
    notes = (tmp_path / "supply.notes.txt").read_text()
    assert notes.startswith("Notes on supply.npz, the data set of ")
    assert "column 101 (BUFKE1 -1 1) holds nan at position 6 and nowhere else" in notes
    with np.load(tmp_path / "supply.npz") as z:
        column = z["101 ddelta/dalpha"]
        assert np.isnan(column[5]) and not np.isnan(np.delete(column, 5)).any()
