"""Ctrl-C during a run: the positions computed before it are kept and written completely.

The interrupts here are real SIGINTs (the process signals itself from the progress callback at a chosen
position, or from a timer while a study runs), so they take the path a user's Ctrl-C takes: Python's signal
handler, noticed by the run's next progress report or check.
"""

from __future__ import annotations

import csv
import os
import signal
import subprocess
import sys
import textwrap
import threading
import time
from pathlib import Path

import numpy as np
import pytest

import mechfem
from conftest import ROOT

FOURBAR = ROOT / "examples" / "fourbar" / "fourbar.mec"
STEPS = 144


def sigint_at(position: int) -> mechfem.Progress:
    """A progress callback that sends SIGINT to this process once ``position`` positions are done."""
    sent = []

    def progress(done: int, total: int) -> None:
        if done >= position and not sent:
            sent.append(done)
            os.kill(os.getpid(), signal.SIGINT)

    return progress


def test_run_deck_raises_with_the_positions_so_far() -> None:
    full = mechfem.run_deck(FOURBAR)
    with pytest.raises(mechfem.RunInterrupted) as caught:
        mechfem.run_deck(FOURBAR, progress=sigint_at(40))
    part = caught.value.result
    assert isinstance(caught.value, KeyboardInterrupt)
    k = part.report.positions
    assert 40 <= k < STEPS + 1
    stop = part.report.stop
    assert stop is not None and stop.kind == "interrupted" and stop.last_good == k
    assert part.coords.shape == (k, full.coords.shape[1])
    # The positions kept are the ones an uninterrupted run computes.
    np.testing.assert_array_equal(part.coords, full.coords[:k])
    for number, values in part.buffers.items():
        np.testing.assert_array_equal(values, full.buffers[number][:k])


def test_an_error_of_the_progress_callback_is_raised_as_it_is() -> None:
    def progress(done: int, total: int) -> None:
        if done == 10:
            raise ValueError("the callback's own mistake")

    with pytest.raises(ValueError, match="own mistake"):
        mechfem.run_deck(FOURBAR, progress=progress)


def test_model_api_run_raises_with_the_analysis_so_far() -> None:
    m = mechfem.Mechanism.from_deck(FOURBAR)
    with pytest.raises(mechfem.RunInterrupted) as caught:
        m.run(progress=sigint_at(30))
    analysis = caught.value.result
    assert isinstance(analysis, mechfem.Analysis)
    assert 30 <= analysis.report.positions < STEPS + 1
    assert analysis.report.stop is not None and analysis.report.stop.kind == "interrupted"


@pytest.mark.large_run
@pytest.mark.parametrize("workers", [1, 2])
def test_ctrl_c_stops_the_variants_of_a_study_while_they_run(workers: int) -> None:
    # Simulations of 400 s, about 4 s each: the calling thread runs one of them itself (every one with one
    # worker) and notices Ctrl-C as it goes; the pool's thread stops when told to.
    supply = ROOT / "examples" / "supply"
    text = (supply / "supply_sim.mec").read_text()
    assert "TSTEPE 800 2.5E-3" in text
    text = text.replace("TSTEPE 800 2.5E-3", "TSTEPE 800 0.5")
    timer = threading.Timer(0.2, os.kill, (os.getpid(), signal.SIGINT))
    start = time.perf_counter()
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        mechfem._core.run_deck_variants([text] * 2, [(0, []), (1, [])], "sim.mec", str(supply), workers)
    timer.join()
    # Far sooner than the first simulation alone would take.
    assert time.perf_counter() - start < 2.0


# The command line, in a child process whose progress bar signals it half-way.
SCRIPT = textwrap.dedent(
    """
    import os, signal, sys
    from mechfem.cli import command as cli

    class Bar(cli.ProgressBar):
        def __call__(self, done, total):
            if done >= int(sys.argv[1]) and not getattr(self, "sent", False):
                self.sent = True
                os.kill(os.getpid(), signal.SIGINT)

    cli.ProgressBar = Bar
    sys.exit(cli.main(sys.argv[2:]))
    """
)


def run_cli_interrupted(at: int, *args: str | Path) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, "-c", SCRIPT, str(at), *map(str, args)],
        stdin=subprocess.DEVNULL,
        capture_output=True,
        text=True,
        timeout=300,
    )


def test_cli_writes_complete_files_up_to_the_last_good_position(tmp_path: Path) -> None:
    out = tmp_path / "out"
    proc = run_cli_interrupted(50, "run", FOURBAR, "-o", out)
    assert proc.returncode == 130, proc.stderr
    assert "Traceback" not in proc.stderr
    assert "interrupted" in proc.stderr
    rows = list(csv.reader((out / "fourbar.csv").read_text().splitlines()))
    header, body = rows[0], rows[1:]
    assert 50 <= len(body) < STEPS + 1
    assert f"Positions 1 to {len(body)} were computed and are all written" in proc.stderr
    # Every row is whole: as many fields as the header, each a number.
    assert all(len(r) == len(header) for r in body)
    assert all(np.isfinite(float(v)) for r in body for v in r)
    prt = (out / "fourbar.prt").read_text()
    assert f"interrupted after position {len(body)}" in prt
    assert (out / "fourbar.gif").is_file()
    assert not [p for p in out.iterdir() if p.name.startswith(".")], "a temporary file was left behind"


def run_cli_signalled_at_rows(out: Path, rows: list[int]) -> subprocess.CompletedProcess[str]:
    """``mechfem run`` of the four-bar into ``out``, sending itself a real SIGINT as it formats each row of the data
    set numbered in ``rows``."""
    script = textwrap.dedent(
        f"""
        import os, signal, sys
        from mechfem.cli import command as cli
        from mechfem.output import files as output

        write_row = output.format_row
        count = [0]

        def format_row(*a):
            count[0] += 1
            if count[0] in {rows!r}:
                os.kill(os.getpid(), signal.SIGINT)
            return write_row(*a)

        output.format_row = format_row
        sys.exit(cli.main(sys.argv[1:]))
        """
    )
    return subprocess.run(
        [sys.executable, "-c", script, "run", str(FOURBAR), "-o", str(out)], capture_output=True, text=True
    )


def test_cli_ctrl_c_while_writing_still_writes_the_data_set(tmp_path: Path) -> None:
    whole = tmp_path / "whole"
    first = subprocess.run(
        [sys.executable, "-m", "mechfem.cli.command", "run", FOURBAR, "-o", whole, "--no-media"],
        capture_output=True,
        text=True,
    )
    assert first.returncode == 0, first.stderr
    out = tmp_path / "out"
    proc = run_cli_signalled_at_rows(out, [20])
    assert proc.returncode == 130, proc.stderr
    assert "Traceback" not in proc.stderr
    assert "press Ctrl-C again to abandon them" in proc.stderr
    assert f"All {STEPS + 1} positions had been computed and are written" in proc.stderr
    # The data set and the print file are whole: the same as an uninterrupted run's.
    assert (out / "fourbar.csv").read_bytes() == (whole / "fourbar.csv").read_bytes()
    assert (out / "fourbar.prt").read_text().startswith("mechfem ")
    # Then the run stops: no pictures, no animation, and the print file lists none.
    assert "the pictures, animation and report are not written (Ctrl-C)" in proc.stderr
    assert sorted(p.name for p in out.iterdir()) == ["fourbar.csv", "fourbar.prt"]
    assert "PICTURES AND ANIMATION" not in (out / "fourbar.prt").read_text()
    assert f"wrote {out / 'fourbar.csv'}" in proc.stdout


def test_cli_second_ctrl_c_while_writing_abandons_the_data_set(tmp_path: Path) -> None:
    out = tmp_path / "out"
    first = subprocess.run(
        [sys.executable, "-m", "mechfem.cli.command", "run", FOURBAR, "-o", out], capture_output=True, text=True
    )
    assert first.returncode == 0, first.stderr
    before = (out / "fourbar.csv").read_bytes()
    (out / "fourbar.csv").write_bytes(b"an older data set\n")
    proc = run_cli_signalled_at_rows(out, [20, 40])
    assert proc.returncode == 130, proc.stderr
    assert "Traceback" not in proc.stderr
    assert "interrupted twice while the outputs were written: the file being written was abandoned" in proc.stderr
    # The data set being written is abandoned: the file there before stays as it was, whole.
    assert (out / "fourbar.csv").read_bytes() == b"an older data set\n" != before
    assert not [p for p in out.iterdir() if p.name.startswith(".")], "a temporary file was left behind"


# A simulation in a child process, signalled by a timer `after` seconds into it; it says on stderr how long after the
# signal the run returned (before the outputs are written).
SIM_SCRIPT = textwrap.dedent(
    """
    import os, signal, sys, threading, time
    from mechfem.cli import command as cli

    sent = []
    run = cli.run_with_progress

    def timed(*args, **kwargs):
        def send():
            sent.append(time.perf_counter())
            os.kill(os.getpid(), signal.SIGINT)

        threading.Timer(float(sys.argv[1]), send).start()
        result = run(*args, **kwargs)
        print(f"returned {time.perf_counter() - sent[0]:.3f} s after the signal", file=sys.stderr)
        return result

    cli.run_with_progress = timed
    sys.exit(cli.main(sys.argv[2:]))
    """
)


def simulation_deck(tmp_path: Path, tstepe: str) -> Path:
    """The supply mechanism's run-up (examples/supply/supply_sim.mec) with the output times ``tstepe``."""
    text = (ROOT / "examples" / "supply" / "supply_sim.mec").read_text()
    assert "TSTEPE 800 2.5E-3" in text
    deck = tmp_path / "sim.mec"
    deck.write_text(text.replace("TSTEPE 800 2.5E-3", f"TSTEPE {tstepe}"))
    return deck


def interrupt_simulation(deck: Path, out: Path, after: float) -> tuple[subprocess.CompletedProcess[str], float]:
    proc = subprocess.run(
        [sys.executable, "-c", SIM_SCRIPT, str(after), "run", str(deck), "-o", str(out), "--no-media"],
        stdin=subprocess.DEVNULL,
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert proc.returncode == 130, proc.stderr
    assert "Traceback" not in proc.stderr and "PanicException" not in proc.stderr, proc.stderr
    assert "interrupted" in proc.stderr
    returned = [line for line in proc.stderr.splitlines() if line.startswith("returned ")]
    assert returned, proc.stderr
    return proc, float(returned[0].split()[1])


def csv_rows(path: Path) -> list[list[str]]:
    """The data set's rows below its header, each checked to be whole: as many fields as the header, each a
    finite number."""
    rows = list(csv.reader(path.read_text().splitlines()))
    header, body = rows[0], rows[1:]
    assert all(len(r) == len(header) for r in body)
    assert all(np.isfinite(float(v)) for r in body for v in r)
    return body


@pytest.mark.large_run
def test_ctrl_c_stops_a_simulation_between_two_outputs(tmp_path: Path) -> None:
    # Outputs 2000 s apart: the first one past position 1 is many seconds of integration away. Ctrl-C half a
    # second in stops the integration within about a tenth of a second (the bound here is loose, for a busy
    # machine: what it catches is a simulation that does not stop until its next output, many seconds on), and
    # position 1, the only output reached, is written.
    deck = simulation_deck(tmp_path, "2 2000.0")
    out = tmp_path / "out"
    proc, after = interrupt_simulation(deck, out, 0.5)
    assert after < 5.0, proc.stderr
    assert len(csv_rows(out / "sim.csv")) == 1
    assert "interrupted after position 1 of 3" in (out / "sim.prt").read_text()


@pytest.mark.large_run
def test_ctrl_c_during_a_simulation_writes_every_output_reached(tmp_path: Path) -> None:
    # 2000 outputs over 200 s, a tenth of a second apart: every output reached is written, and they are the
    # outputs an uninterrupted simulation gives at the same times, to the last digit written.
    deck = simulation_deck(tmp_path, "2000 0.1")
    out = tmp_path / "out"
    proc, after = interrupt_simulation(deck, out, 1.0)
    assert after < 5.0, proc.stderr
    rows = csv_rows(out / "sim.csv")
    assert 1 < len(rows) < 2001
    assert f"Positions 1 to {len(rows)} were computed and are all written" in proc.stderr
    full = subprocess.run(
        [sys.executable, "-m", "mechfem.cli.command", "run", str(deck), "-o", str(tmp_path / "full"), "--no-media"],
        capture_output=True,
        text=True,
    )
    assert full.returncode == 0, full.stderr
    assert rows == csv_rows(tmp_path / "full" / "sim.csv")[: len(rows)]
