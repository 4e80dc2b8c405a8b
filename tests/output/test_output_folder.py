"""The output folder of a command, checked before the run: no output replaces an input of the run, no output name
is too long for the folder, and two runs that would write the outputs of one stem into one folder do not mix them.
"""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

from conftest import ROOT, Cli, mechfem_command
from mechfem.output import output_folder

FOURBAR = ROOT / "examples" / "fourbar" / "fourbar.mec"
SLIDER = ROOT / "crates" / "mechfem-deck" / "tests" / "decks" / "valid" / "motion_file.mec"


def fourbar_in(folder: Path, name: str = "fourbar.mec", steps: int = 12) -> Path:
    """fourbar.mec as ``folder/name`` with ``steps`` steps."""
    lines = [
        f"TSTEPE {steps} {6.283185307179586 / steps!r}" if t.startswith("TSTEPE") else t
        for t in FOURBAR.read_text().splitlines()
    ]
    folder.mkdir(parents=True, exist_ok=True)
    deck = folder / name
    deck.write_text("\n".join(lines) + "\n")
    return deck


def table_deck(folder: Path, table: str) -> Path:
    """The MOV_FUNC deck of the deck reader's tests in ``folder``, its table file named ``table``."""
    folder.mkdir(parents=True, exist_ok=True)
    deck = folder / "slider.mec"
    deck.write_text(
        SLIDER.read_text().replace("crank.dat", table).replace("BUFINP 1 2\n", "BUFINP 1 2\nSAVEDATA 1 2\n")
    )
    (folder / table).write_text((SLIDER.parent / "crank.dat").read_text())
    return deck


# --- an output never replaces an input --------------------------------------------------------------------------------


def test_a_deck_named_like_its_print_file_is_not_overwritten(cli: Cli, tmp_path: Path) -> None:
    deck = fourbar_in(tmp_path, "deck.prt")
    before = deck.read_bytes()
    proc = cli("run", deck, "--no-media")
    assert proc.returncode == 1, proc.stderr
    assert f"the print file {deck} would replace {deck}, the deck itself" in proc.stderr
    assert "-o OUTDIR" in proc.stderr and "Traceback" not in proc.stderr
    assert deck.read_bytes() == before
    assert sorted(p.name for p in tmp_path.iterdir()) == ["deck.prt"]
    # Into another folder it runs.
    assert cli("run", deck, "--no-media", "-o", tmp_path / "out").returncode == 0


@pytest.mark.parametrize("how", ["same name", "symbolic link", "hard link"])
def test_a_table_file_is_not_overwritten_by_the_data_set(cli: Cli, tmp_path: Path, how: str) -> None:
    deck = table_deck(tmp_path / "deck", "slider.csv" if how == "same name" else "table.dat")
    table = deck.parent / ("slider.csv" if how == "same name" else "table.dat")
    out = deck.parent
    if how != "same name":
        out = tmp_path / "out"
        out.mkdir()
        if how == "symbolic link":
            (out / "slider.csv").symlink_to(table)
        else:
            os.link(table, out / "slider.csv")
    before = table.read_bytes()
    proc = cli("run", deck, "-o", out, "--no-media")
    assert proc.returncode == 1, proc.stderr
    assert f"the data set {out / 'slider.csv'} would replace {table}, the table file" in proc.stderr
    assert table.read_bytes() == before
    assert not (out / "slider.prt").exists()
    # The next run still reads its table.
    assert cli("run", deck, "-o", tmp_path / "elsewhere", "--no-media").returncode == 0


def test_report_and_draw_do_not_overwrite_their_inputs(cli: Cli, tmp_path: Path) -> None:
    deck = fourbar_in(tmp_path, "deck.html")
    before = deck.read_bytes()
    proc = cli("report", deck)
    assert proc.returncode == 1, proc.stderr
    assert f"the report {deck} would replace {deck}, the deck itself" in proc.stderr
    assert deck.read_bytes() == before
    deck = table_deck(tmp_path / "draw", "slider_pos1.svg")
    table = deck.parent / "slider_pos1.svg"
    before = table.read_bytes()
    proc = cli("draw", deck, "--format", "svg")
    assert proc.returncode == 1, proc.stderr
    assert f"the drawing {table} would replace {table}, the table file `slider_pos1.svg`" in proc.stderr
    assert table.read_bytes() == before


# --- output names -----------------------------------------------------------------------------------------------------


def test_a_deck_name_too_long_for_its_outputs_is_refused_before_the_run(cli: Cli, tmp_path: Path) -> None:
    # 236 bytes, a valid name, and so is <stem>_pic1.png; its temporary name (with a process id of at least one
    # digit) is not.
    deck = fourbar_in(tmp_path / "deck", "f" * 232 + ".mec")
    out = tmp_path / "out"
    proc = cli("run", deck, "-o", out)
    assert proc.returncode == 1, proc.stderr
    assert "would need a file name of" in proc.stderr and "more than the 255 bytes" in proc.stderr
    assert "Give the deck a shorter name" in proc.stderr and "Traceback" not in proc.stderr
    # Nothing written, not even the folder.
    assert not out.exists()
    shorter = fourbar_in(tmp_path / "deck", "f" * 200 + ".mec")
    assert cli("run", shorter, "-o", out).returncode == 0


# --- two runs into one folder -----------------------------------------------------------------------------------------


def hold_lock(out: Path, stem: str) -> subprocess.Popen[str]:
    """Another process that holds the lock of ``stem`` in ``out``, as a run does while it computes and writes, until
    its stdin is closed; returned once it holds it."""
    script = textwrap.dedent(
        f"""
        import sys
        from pathlib import Path
        from mechfem.output.output_folder import locked
        with locked(Path({str(out)!r}), {stem!r}):
            print("locked", flush=True)
            sys.stdin.read()
        """
    )
    proc = subprocess.Popen([sys.executable, "-c", script], stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True)
    assert proc.stdout is not None and proc.stdout.readline() == "locked\n"
    return proc


def test_a_second_run_of_the_same_stem_into_one_folder_is_refused_at_once(tmp_path: Path) -> None:
    second = fourbar_in(tmp_path / "b", steps=6)
    out = tmp_path / "out"
    out.mkdir()
    (out / "fourbar.prt").write_text("the first run's print file\n")
    # Another process holds the lock until it is told to let go: no race with how long a real run takes.
    holder = hold_lock(out, "fourbar")
    try:
        refused = subprocess.run(
            [*mechfem_command(), "run", str(second), "-o", str(out)],
            stdin=subprocess.DEVNULL,
            capture_output=True,
            text=True,
            timeout=120,
        )
        assert refused.returncode == 1, refused.stderr
        assert "another mechfem run is writing the outputs of `fourbar`" in refused.stderr
        assert "-o OUTDIR" in refused.stderr and "Traceback" not in refused.stderr
        # The refused run wrote nothing: the holder's files are as they were.
        assert (out / "fourbar.prt").read_text() == "the first run's print file\n"
        assert sorted(p.name for p in out.iterdir()) == [".fourbar.lock", "fourbar.prt"]
    finally:
        holder.communicate("", timeout=60)
    assert holder.returncode == 0
    assert not (out / ".fourbar.lock").exists()
    # Once the holder has let go, the second runs.
    again = subprocess.run(
        [*mechfem_command(), "run", str(second), "-o", str(out)], stdin=subprocess.DEVNULL, capture_output=True
    )
    assert again.returncode == 0, again.stderr
    assert f"deck: {second}" in (out / "fourbar.prt").read_text()


def test_the_lock_is_released_and_removed_whatever_ends_the_run(tmp_path: Path) -> None:
    out = tmp_path / "out"
    out.mkdir()
    with output_folder.locked(out, "deck"):
        assert (out / ".deck.lock").exists()
        with pytest.raises(output_folder.OutputConflict, match="another mechfem run"):
            with output_folder.locked(out, "deck"):
                pass
        with output_folder.locked(out, "other"):
            pass
    assert list(out.iterdir()) == []
    with pytest.raises(KeyError), output_folder.locked(out, "deck"):
        raise KeyError
    assert list(out.iterdir()) == []
    # A lock file left by a run killed outright is taken over.
    (out / ".deck.lock").write_text("")
    with output_folder.locked(out, "deck"):
        pass
    assert list(out.iterdir()) == []


def test_a_folder_made_for_the_lock_is_removed_when_nothing_is_written(tmp_path: Path) -> None:
    out = tmp_path / "new" / "out"
    with output_folder.locked(out, "deck"):
        assert out.is_dir()
    assert list(tmp_path.iterdir()) == []


def test_a_run_killed_while_it_holds_the_lock_does_not_block_the_next(tmp_path: Path) -> None:
    out = tmp_path / "out"
    proc = hold_lock(out, "fourbar")
    proc.send_signal(signal.SIGKILL)
    proc.wait(timeout=60)
    assert (out / ".fourbar.lock").exists()
    deck = fourbar_in(tmp_path / "deck")
    done = subprocess.run(
        [*mechfem_command(), "run", str(deck), "-o", str(out), "--no-media"], stdin=subprocess.DEVNULL
    )
    assert done.returncode == 0
    assert not (out / ".fourbar.lock").exists()


def test_a_table_name_with_a_nul_byte_is_left_to_the_deck_reader(tmp_path: Path, cli: Cli) -> None:
    # An earlier run's print file is in the folder, so the check that no output replaces an input compares the
    # deck's table names with it: a NUL byte in one must reach the reader's error (exit 1), not end as exit 4.
    deck = tmp_path / "slider.mec"
    text = (ROOT / "tests" / "decks" / "rocker.mec").read_text()
    deck.write_text(text.replace("MOVEMENT", "MOVEMENT\nMOV_FUNC 1 cr\0ank.dat", 1))
    (tmp_path / "slider.prt").write_text("an earlier print file\n")
    proc = cli("run", str(deck), "--no-media")
    assert proc.returncode == 1, proc.stderr
    assert "This is a bug" not in proc.stderr and "slider.mec" in proc.stderr
