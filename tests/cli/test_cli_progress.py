"""The command line around a run: the progress bar, the "wrote" lines, --quiet, --no-media, the data set's
formats and ``python -m mechfem``."""

from __future__ import annotations

import csv
import fcntl
import os
import pty
import struct
import subprocess
import sys
import termios
import threading
from pathlib import Path

import numpy as np
import pytest

from conftest import SUPPLY, Cli, mechfem_command
from mechfem._util.progress import Console
from mechfem.cli import command as cli

# What `mechfem run` writes for the supply deck, in the order the files are complete.
SUPPLY_FILES = [
    "supply.csv",
    "supply.prt",
    "supply_pic1.png",
    "supply_pic1.svg",
    "supply_pic2.png",
    "supply_pic2.svg",
    "film.gif",
]


def test_python_m_mechfem_runs_the_command(tmp_path: Path) -> None:
    proc = subprocess.run(
        [sys.executable, "-m", "mechfem", "--help"], capture_output=True, text=True, timeout=120, check=False
    )
    assert proc.returncode == 0, proc.stderr
    assert proc.stdout.startswith("usage: mechfem ")
    for command in ("run", "report", "check"):
        assert command in proc.stdout
    proc = subprocess.run(
        [sys.executable, "-m", "mechfem", "run", str(SUPPLY), "-o", str(tmp_path), "--no-media"],
        capture_output=True,
        text=True,
        timeout=300,
        check=False,
    )
    assert proc.returncode == 0, proc.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == ["supply.csv", "supply.prt"]


def test_run_help_names_the_flags(cli: Cli) -> None:
    proc = cli("run", "--help")
    assert proc.returncode == 0
    for flag in ("--no-media", "--quiet", "--format {csv,npz,parquet}"):
        assert flag in proc.stdout


def test_quiet_says_nothing_and_keeps_the_exit_status(cli: Cli, tmp_path: Path) -> None:
    proc = cli("run", SUPPLY, "-o", tmp_path / "run", "--quiet", "--max-frames", "2")
    assert (proc.returncode, proc.stdout, proc.stderr) == (0, "", "")
    assert sorted(p.name for p in (tmp_path / "run").iterdir()) == sorted(SUPPLY_FILES)
    proc = cli("report", SUPPLY, "-o", tmp_path / "report", "-q")
    assert (proc.returncode, proc.stdout, proc.stderr) == (0, "", "")
    assert [p.name for p in (tmp_path / "report").iterdir()] == ["supply.html"]
    proc = cli("check", SUPPLY, "--quiet")
    assert (proc.returncode, proc.stdout, proc.stderr) == (0, "", "")
    proc = cli("draw", SUPPLY, "-o", tmp_path / "draw", "--format", "svg", "--quiet")
    assert (proc.returncode, proc.stdout, proc.stderr) == (0, "", "")
    assert [p.name for p in (tmp_path / "draw").iterdir()] == ["supply_pos1.svg"]


def test_quiet_still_says_errors(cli: Cli, tmp_path: Path) -> None:
    from run.test_run_deck import ROCKER

    # A motion that stops early: exit status 3, and the reason is an error.
    proc = cli("run", ROCKER, "-o", tmp_path, "--quiet")
    assert proc.returncode == 3 and proc.stdout == ""
    assert proc.stderr.startswith("error: ") and "The motion stopped after position" in proc.stderr
    broken = tmp_path / "broken.mec"
    broken.write_text(SUPPLY.read_text().replace("ELEM\t1\tBIN", "ELEM\t1\tBIX"))
    proc = cli("check", broken, "--quiet")
    assert proc.returncode == 1 and proc.stdout == "" and "broken.mec" in proc.stderr


def test_no_media_writes_print_file_and_data_set_only(cli: Cli, tmp_path: Path) -> None:
    proc = cli("run", SUPPLY, "-o", tmp_path, "--no-media")
    assert proc.returncode == 0, proc.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == ["supply.csv", "supply.prt"]
    assert [line for line in proc.stdout.splitlines() if line.startswith("wrote")] == [
        f"wrote {tmp_path / 'supply.csv'}",
        f"wrote {tmp_path / 'supply.prt'}",
    ]
    # The print file lists no pictures that were not written.
    assert "PICTURES AND ANIMATION" not in (tmp_path / "supply.prt").read_text()


def test_report_and_no_media_together_are_a_command_line_mistake(cli: Cli, tmp_path: Path) -> None:
    proc = cli("run", SUPPLY, "-o", tmp_path, "--report", "--no-media")
    assert proc.returncode == 2
    assert "--no-media" in proc.stderr and "Traceback" not in proc.stderr
    assert list(tmp_path.iterdir()) == []


def test_each_wrote_line_comes_as_its_file_is_complete(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    # At each line, the folder as it is then: the file the line names is there, the files named later are not
    # (beside the run's lock file, removed as it ends).
    seen: list[tuple[str, list[str]]] = []
    say = Console.say

    def record(self: Console, line: str) -> None:
        names = sorted(p.name for p in tmp_path.iterdir() if p.name != ".supply.lock") if tmp_path.exists() else []
        seen.append((line, names))
        say(self, line)

    monkeypatch.setattr(Console, "say", record)
    assert cli.main(["run", str(SUPPLY), "-o", str(tmp_path), "--max-frames", "2"]) == 0
    wrote = [(line.split()[1], folder) for line, folder in seen if line.startswith("wrote ")]
    assert [Path(name).name for name, _ in wrote] == SUPPLY_FILES
    for k, (_, folder) in enumerate(wrote):
        assert folder == sorted(SUPPLY_FILES[: k + 1]), f"line {k + 1}: the folder holds {folder}"
    out = capsys.readouterr().out.splitlines()
    assert out[0] == f"{SUPPLY}: 73 positions computed"
    assert [line.split()[1] for line in out if line.startswith("wrote ")] == [name for name, _ in wrote]


def run_on_a_terminal(*args: str | Path) -> tuple[int, str, str]:
    """Runs ``mechfem ARGS`` with stderr on a pseudo-terminal; returns the exit status, stdout and what the
    terminal showed."""
    master, slave = pty.openpty()
    # A new pseudo-terminal is 0 columns wide, and a bar as wide as the terminal would be empty: 30 x 100.
    fcntl.ioctl(slave, termios.TIOCSWINSZ, struct.pack("HHHH", 30, 100, 0, 0))
    proc = subprocess.Popen(
        [*mechfem_command(), *map(str, args)], stdin=subprocess.DEVNULL, stdout=subprocess.PIPE, stderr=slave
    )
    os.close(slave)
    shown: list[bytes] = []

    def read() -> None:
        # The terminal must be drained while the command runs, or it blocks once the buffer is full.
        while True:
            try:
                data = os.read(master, 4096)
            except OSError:  # EIO: every writer has closed the terminal
                return
            if not data:
                return
            shown.append(data)

    reader = threading.Thread(target=read)
    reader.start()
    out, _ = proc.communicate(timeout=300)
    reader.join(timeout=60)
    os.close(master)
    return proc.returncode, out.decode(), b"".join(shown).decode(errors="replace")


def test_the_bar_shows_every_phase_on_a_terminal(tmp_path: Path) -> None:
    status, out, shown = run_on_a_terminal("run", SUPPLY, "-o", tmp_path, "--report", "--max-frames", "4")
    assert status == 0
    for phase in ("computing", "data set", "print file", "pictures", "animation", "report"):
        assert f"\r{phase}" in shown, f"no {phase!r} phase in {shown!r}"
    assert "73/73" in shown and "4/4" in shown and "frames" in shown
    # The bar stays on stderr: stdout has the lines alone.
    assert "\r" not in out and out.count("wrote ") == len(SUPPLY_FILES) + 1


def test_no_bar_when_stderr_is_not_a_terminal(cli: Cli, tmp_path: Path) -> None:
    proc = cli("run", SUPPLY, "-o", tmp_path, "--no-media")
    assert proc.returncode == 0 and proc.stderr == ""


def test_quiet_draws_no_bar_even_on_a_terminal(tmp_path: Path) -> None:
    status, out, shown = run_on_a_terminal("run", SUPPLY, "-o", tmp_path, "--quiet", "--no-media")
    assert (status, out, shown) == (0, "", "")


def csv_columns(path: Path) -> dict[str, list[float]]:
    with path.open() as f:
        header, *rows = list(csv.reader(f))
    return {name: [float(r[c]) for r in rows] for c, name in enumerate(header)}


def bits(values: object) -> list[int]:
    return np.asarray(values, dtype=np.float64).view(np.uint64).tolist()


def test_npz_and_parquet_columns_equal_the_csv_to_the_last_bit(cli: Cli, tmp_path: Path) -> None:
    for fmt in ("csv", "npz", "parquet"):
        proc = cli("run", SUPPLY, "-o", tmp_path / fmt, "--format", fmt, "--no-media")
        assert proc.returncode == 0, proc.stderr
        assert sorted(p.name for p in (tmp_path / fmt).iterdir()) == sorted([f"supply.{fmt}", "supply.prt"])
        assert f"wrote {tmp_path / fmt / f'supply.{fmt}'}" in proc.stdout
    expected = csv_columns(tmp_path / "csv" / "supply.csv")
    assert len(expected) == 4 and all(len(v) == 73 for v in expected.values())
    with np.load(tmp_path / "npz" / "supply.npz") as z:
        assert z.files == ["position", *expected]
        assert z["position"].tolist() == list(range(1, 74))
        for name, values in expected.items():
            assert z[name].dtype == np.float64 and bits(z[name]) == bits(values), name
    pq = pytest.importorskip("pyarrow.parquet")
    table = pq.read_table(tmp_path / "parquet" / "supply.parquet")
    assert table.column_names == ["position", *expected]
    assert table.column("position").to_pylist() == list(range(1, 74))
    for name, values in expected.items():
        assert bits(table.column(name).to_numpy()) == bits(values), name
    # The print files do not depend on the format.
    prt = [(tmp_path / fmt / "supply.prt").read_text() for fmt in ("csv", "npz", "parquet")]
    assert prt[0] == prt[1] == prt[2]


def test_parquet_without_pyarrow_is_refused_before_the_run(tmp_path: Path) -> None:
    script = (
        "import sys; sys.modules['pyarrow'] = None; from mechfem.cli.command import main; sys.exit(main(sys.argv[1:]))"
    )
    out = tmp_path / "out"
    proc = subprocess.run(
        [sys.executable, "-c", script, "run", str(SUPPLY), "-o", str(out), "--format", "parquet"],
        stdin=subprocess.DEVNULL,
        capture_output=True,
        text=True,
        timeout=300,
        check=False,
    )
    assert proc.returncode == 1
    assert "pip install 'mechfem[parquet]'" in proc.stderr and "pyarrow" in proc.stderr
    assert "Traceback" not in proc.stderr and proc.stderr.count("\n") == 1
    # Nothing was computed, so nothing is written.
    assert proc.stdout == "" and not out.exists()


def test_an_unknown_format_is_a_command_line_mistake(cli: Cli, tmp_path: Path) -> None:
    proc = cli("run", SUPPLY, "-o", tmp_path, "--format", "xlsx")
    assert proc.returncode == 2 and "invalid choice: 'xlsx'" in proc.stderr
