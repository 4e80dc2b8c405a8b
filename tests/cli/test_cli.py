"""The ``mechfem`` command: runs, checks, messages and exit status."""

from __future__ import annotations

import csv
import re
from pathlib import Path

import pytest

import mechfem
from conftest import SUPPLY, Cli

SUPPLY_STEPS = 72


def test_run_supply_writes_print_file_and_data_set(cli: Cli, supply_with_savedata: Path, tmp_path: Path) -> None:
    out = tmp_path / "out"
    # Pictures and animation of this deck: test_run_writes_pictures_and_animation.
    proc = cli("run", supply_with_savedata, "-o", out, "--no-media")
    assert proc.returncode == 0, proc.stderr
    prt, data = out / "supply.prt", out / "supply.csv"
    assert prt.is_file() and data.is_file()
    assert f"wrote {prt}" in proc.stdout
    rows = list(csv.reader(data.read_text().splitlines()))
    # The header names the buffers as the deck's NAMES block names alpha and delta.
    assert rows[0] == ["99 alpha", "100 delta", "101 ddelta/dalpha", "102 d2delta/dalpha^2"]
    assert len(rows) - 1 == SUPPLY_STEPS + 1
    text = prt.read_text()
    assert "ADJUSTMENT OF POSITION 1" in text
    # The legend of the tables: number, name, unit, deck line, what the buffer holds.
    assert re.search(r"^ +99 +alpha +rad +BUFINP 1 +value of input 1 \(alpha\)$", text, re.M)


def test_run_without_savedata_writes_no_data_set(cli: Cli, tmp_path: Path) -> None:
    text = "\n".join(line for line in SUPPLY.read_text().splitlines() if "SAVEDATA" not in line)
    deck = tmp_path / "deck" / "supply.mec"
    deck.parent.mkdir()
    deck.write_text(text + "\n")
    out = tmp_path / "out"
    proc = cli("run", deck, "-o", out, "--no-media")
    assert proc.returncode == 0, proc.stderr
    assert not (out / "supply.csv").exists()
    assert (out / "supply.prt").is_file()


def test_run_writes_pictures_and_animation(cli: Cli, tmp_path: Path) -> None:
    proc = cli("run", SUPPLY, "-o", tmp_path)
    assert proc.returncode == 0, proc.stderr
    for name in ("supply_pic1.png", "supply_pic1.svg", "supply_pic2.png", "supply_pic2.svg", "film.gif"):
        assert f"wrote {tmp_path / name}" in proc.stdout
    assert "film.gif (73 frames, one per position)" in proc.stdout
    text = (tmp_path / "supply.prt").read_text()
    assert "PICTURES AND ANIMATION" in text
    assert "PLOTHODO 13 14): supply_pic1.png, supply_pic1.svg" in text


def test_default_output_folder_is_the_decks_folder(cli: Cli, supply_with_savedata: Path, tmp_path: Path) -> None:
    proc = cli("run", supply_with_savedata, "--no-media", cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    assert (supply_with_savedata.parent / "supply.prt").is_file()
    assert (supply_with_savedata.parent / "supply.csv").is_file()


def test_data_set_has_full_precision(cli: Cli, supply_with_savedata: Path, tmp_path: Path) -> None:
    import mechfem

    proc = cli("run", supply_with_savedata, "-o", tmp_path, "--no-media")
    assert proc.returncode == 0, proc.stderr
    rows = list(csv.reader((tmp_path / "supply.csv").read_text().splitlines()))
    result = mechfem.run_deck(supply_with_savedata)
    for col, cell in enumerate(rows[0]):
        column = result.buffers[int(cell.split()[0])]
        # Every value reads back as exactly the double that was computed.
        assert [float(r[col]) for r in rows[1:]] == column.tolist()
    # An irrational-looking value, such as the output angle, shows at least 15 significant digits.
    digits = rows[5][1].lstrip("-").replace(".", "").split("e")[0].lstrip("0")
    assert len(digits) >= 15


def test_outputs_are_written_atomically(cli: Cli, supply_with_savedata: Path, tmp_path: Path) -> None:
    out = tmp_path / "out"
    (out).mkdir()
    (out / "supply.prt").write_text("old")
    proc = cli("run", supply_with_savedata, "-o", out)
    assert proc.returncode == 0, proc.stderr
    # No temporary file is left behind: only the finished outputs.
    pictures = ["supply_pic1.png", "supply_pic1.svg", "supply_pic2.png", "supply_pic2.svg"]
    assert sorted(p.name for p in out.iterdir()) == sorted(["supply.csv", "supply.prt", "film.gif", *pictures])
    assert (out / "supply.prt").read_text() != "old"


def test_check_lists_the_adjusted_coordinates(cli: Cli) -> None:
    proc = cli("check", SUPPLY)
    assert proc.returncode == 0, proc.stderr
    checked = mechfem.check_deck(SUPPLY)
    lines = proc.stdout.splitlines()
    at = lines.index("  moving co-ordinates at position 1:")
    rows = [line.split() for line in lines[at + 2 : at + 2 + checked.n_moving]]
    assert [int(r[0]) for r in rows] == list(range(9, 21))
    for r in rows:
        assert float(r[2]) == pytest.approx(checked.coords[int(r[0]) - 1], rel=1e-9)


def test_check_supply(cli: Cli) -> None:
    proc = cli("check", SUPPLY)
    assert proc.returncode == 0, proc.stderr
    assert "20 co-ordinates (8 fixed, 12 moving)" in proc.stdout
    assert "det(D^c) at position 1" in proc.stdout


def test_invalid_deck_names_file_and_line_without_traceback(cli: Cli, tmp_path: Path) -> None:
    deck = tmp_path / "broken.mec"
    text = SUPPLY.read_text().replace("ELEM\t1\tBIN", "ELEM\t1\tBIX")
    deck.write_text(text)
    line = next(k for k, t in enumerate(text.splitlines(), 1) if "BIX" in t)
    for command in ("run", "check"):
        proc = cli(command, deck, "-o", tmp_path) if command == "run" else cli(command, deck)
        assert proc.returncode != 0
        assert "broken.mec" in proc.stderr
        assert f":{line}:" in proc.stderr
        assert "Traceback" not in proc.stderr + proc.stdout
    assert not (tmp_path / "broken.prt").exists()


def test_missing_deck_is_a_message_not_a_traceback(cli: Cli, tmp_path: Path) -> None:
    proc = cli("run", tmp_path / "nothing.mec")
    assert proc.returncode != 0
    assert "nothing.mec" in proc.stderr
    assert "Traceback" not in proc.stderr


def test_unwritable_output_is_a_message_not_a_traceback(cli: Cli, tmp_path: Path) -> None:
    blocker = tmp_path / "file"
    blocker.write_text("")
    proc = cli("run", SUPPLY, "-o", blocker / "sub")
    assert proc.returncode == 1
    assert "Traceback" not in proc.stderr
    assert "cannot write" in proc.stderr


def test_usage_error_exits_2(cli: Cli) -> None:
    proc = cli("frobnicate")
    assert proc.returncode == 2
    assert "Traceback" not in proc.stderr


def test_stopped_motion_writes_partial_results_and_exits_3(cli: Cli, tmp_path: Path) -> None:
    from run.test_run_deck import ROCKER

    proc = cli("run", ROCKER, "-o", tmp_path)
    assert proc.returncode == 3
    assert "The motion stopped after position" in proc.stderr
    assert "Traceback" not in proc.stderr
    rows = (tmp_path / "rocker.csv").read_text().splitlines()
    assert 2 < len(rows) < 38
    assert "MOTION STOPPED" in (tmp_path / "rocker.prt").read_text()


def test_failure_at_position_1_is_one_paragraph(cli: Cli, tmp_path: Path) -> None:
    from run.test_run_deck import ROOT

    proc = cli("run", ROOT / "tests" / "decks" / "superfluous.mec", "-o", tmp_path)
    assert proc.returncode == 1
    assert proc.stderr.startswith("error: ") and "superfluous.mec: position 1 cannot be computed" in proc.stderr
    assert proc.stderr.strip().count("\n") == 0
    assert list(tmp_path.iterdir()) == []
