"""What a command reads: the deck (a regular file, read only up to its END line and within a size limit) and the
tables it names (a byte-order mark is no part of a row; an error quotes no more of the file than the word at
fault); the MOV_FUNC table of a simulation checked like a load table. And what the report embeds of them: text that
holds no markup."""

from __future__ import annotations

import json
import os
import re
import time
from pathlib import Path

import numpy as np
import pytest

import mechfem
from conftest import ROOT, Cli
from mechfem.report.html import render_report, report_data

FOURBAR = ROOT / "examples" / "fourbar" / "fourbar.mec"
INVALID = ROOT / "crates" / "mechfem-deck" / "tests" / "decks" / "invalid"
VALID = ROOT / "crates" / "mechfem-deck" / "tests" / "decks" / "valid"


# --- the deck ---------------------------------------------------------------------------------------------------------


@pytest.mark.parametrize("command", ["run", "check", "report", "draw"])
def test_a_deck_that_is_a_pipe_or_a_device_is_refused_at_once(cli: Cli, tmp_path: Path, command: str) -> None:
    fifo = tmp_path / "deck.mec"
    os.mkfifo(fifo)
    for deck in (fifo, Path("/dev/zero")):
        args = [command, str(deck)] + ([] if command == "check" else ["-o", str(tmp_path / "out")])
        started = time.monotonic()
        proc = cli(*args)
        assert proc.returncode == 1, proc.stderr
        assert "cannot read the deck: it is not a regular file" in proc.stderr and "Traceback" not in proc.stderr
        assert time.monotonic() - started < 60
    assert sorted(p.name for p in tmp_path.iterdir()) == ["deck.mec"]


def test_the_model_api_reads_a_deck_as_the_command_does(tmp_path: Path) -> None:
    fifo = tmp_path / "deck.mec"
    os.mkfifo(fifo)
    for deck in (fifo, Path("/dev/zero")):
        with pytest.raises(mechfem.DeckError, match="cannot read the deck: it is not a regular file"):
            mechfem.Mechanism.from_deck(deck)
    after = tmp_path / "after.mec"
    after.write_bytes(FOURBAR.read_bytes() + b"\xff\x00 not a deck\n")
    plain = tmp_path / "plain" / "after.mec"
    plain.parent.mkdir()
    plain.write_bytes(FOURBAR.read_bytes())
    assert mechfem.Mechanism.from_deck(after).to_deck() == mechfem.Mechanism.from_deck(plain).to_deck()


def test_text_after_end_is_not_read(cli: Cli, tmp_path: Path) -> None:
    text = FOURBAR.read_text()
    assert text.endswith("\nEND\n")
    deck = tmp_path / "deck.mec"
    # Bytes that are no text, and a line of 40 MiB, after END.
    deck.write_bytes(text.encode() + b"\xff\x00 not a deck\n" + b"x" * (40 << 20))
    proc = cli("run", deck, "-o", tmp_path / "out", "--no-media")
    assert proc.returncode == 0, proc.stderr
    plain = tmp_path / "plain" / "deck.mec"
    plain.parent.mkdir()
    plain.write_text(text)
    assert cli("run", plain, "-o", tmp_path / "plain_out", "--no-media").returncode == 0
    assert (tmp_path / "out" / "deck.csv").read_bytes() == (tmp_path / "plain_out" / "deck.csv").read_bytes()
    assert mechfem._core.read_deck_text(deck) == text


def test_a_deck_larger_than_the_limit_is_refused(cli: Cli, tmp_path: Path) -> None:
    deck = tmp_path / "deck.mec"
    # A sparse file of 17 MiB of NUL bytes: no END line before the limit.
    with deck.open("wb") as f:
        f.write(FOURBAR.read_bytes().replace(b"\nEND\n", b"\n"))
        f.truncate(17 << 20)
    proc = cli("check", deck)
    assert proc.returncode == 1, proc.stderr
    assert "the deck is larger than 16 MiB before its END line" in proc.stderr


# --- the tables it names ----------------------------------------------------------------------------------------------


def slider_with_table(folder: Path, table: str) -> Path:
    """The MOV_FUNC deck of the deck reader's tests in ``folder``, its table ``table`` (text)."""
    folder.mkdir(parents=True, exist_ok=True)
    (folder / "crank.dat").write_text(table)
    deck = folder / "slider.mec"
    deck.write_text((VALID / "motion_file.mec").read_text())
    return deck


def test_a_table_with_a_byte_order_mark_reads_as_without(cli: Cli, tmp_path: Path) -> None:
    table = (VALID / "crank.dat").read_text()
    plain = slider_with_table(tmp_path / "plain", table)
    marked = slider_with_table(tmp_path / "marked", "\ufeff" + table)
    proc = cli("run", marked, "-o", tmp_path / "out", "--no-media")
    assert proc.returncode == 0, proc.stderr
    np.testing.assert_array_equal(mechfem.run_deck(marked).coords, mechfem.run_deck(plain).coords)


@pytest.mark.parametrize(
    "secret",
    [
        "machine example.com login me password hunter2",  # six words: a wrong count
        "hunter2 0",  # two words: not a number
        "0 hunter2 correct horse",  # four words, the second not a number
    ],
)
def test_a_table_file_error_quotes_no_more_of_the_file_than_the_word_at_fault(
    cli: Cli, tmp_path: Path, secret: str
) -> None:
    deck = slider_with_table(tmp_path, f"{secret}\nsecond line\n")
    proc = cli("run", deck, "-o", tmp_path / "out")
    assert proc.returncode == 1, proc.stderr
    words = secret.split()
    # The only word of the file shown is the one at fault (a wrong count shows none), and never the next line. The
    # table's path is taken out first: pytest's temporary folders have numbers of their own ("pytest-0").
    said = proc.stderr.replace(str(tmp_path), "<tmp>")
    shown = [w for w in words if re.search(rf"(?<![\w.]){re.escape(w)}(?![\w.])", said)]
    assert len(shown) <= 1, proc.stderr
    if len(words) in (2, 4):
        assert shown == ["hunter2"], proc.stderr
    assert "second line" not in proc.stderr
    assert "crank.dat:1:" in proc.stderr


# --- MOV_FUNC tables of a simulation ----------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("name", "message"),
    [
        ("mov_func_sim_time_back", "the time 1 comes before the time 1.5 of the row above (line 4)"),
        ("mov_func_sim_time_twice", "the time 0.5 is the time of the row above (line 3) too"),
        ("mov_func_sim_late_start", "the MOV_FUNC table starts at t = 0.1, after the simulation's start at t = 0"),
        ("mov_func_sim_early_end", "the MOV_FUNC table ends at t = 1, before the simulation's end at t = 2"),
    ],
)
def test_the_mov_func_table_of_a_simulation_is_checked(cli: Cli, tmp_path: Path, name: str, message: str) -> None:
    proc = cli("run", INVALID / f"{name}.mec", "-o", tmp_path)
    assert proc.returncode == 1, proc.stderr
    assert f"error: {message}" in proc.stderr and "hint: " in proc.stderr
    assert list(tmp_path.iterdir()) == []


def test_a_mov_func_table_that_covers_the_simulation_runs(cli: Cli, tmp_path: Path) -> None:
    deck = tmp_path / "deck.mec"
    deck.write_text((INVALID / "mov_func_sim_early_end.mec").read_text().replace("sim_early_end.dat", "ok.dat"))
    # Times written in decimal: 0.1 * 3 is not 0.3, and the end is still covered.
    (tmp_path / "ok.dat").write_text("0.0 0.0 1.0\n0.5 0.5 1.0\n1.0 1.0 1.0\n1.5 1.5 1.0\n1.9999999999999998 2.0 1.0\n")
    proc = cli("run", deck, "-o", tmp_path / "out", "--no-media")
    assert proc.returncode == 0, proc.stderr


# --- the report's embedded data ---------------------------------------------------------------------------------------


def test_a_picture_title_with_markup_cannot_break_the_report(tmp_path: Path) -> None:
    title = "<!--<script> </script> & </style> \u2028 >"
    text = FOURBAR.read_text().replace("BEGINPIC coupler curve and velocity hodograph", f"BEGINPIC {title}")
    deck = tmp_path / "deck.mec"
    deck.write_text(text)
    result = mechfem.run_deck(deck)
    page = render_report(result)
    found = re.search(r'<script type="application/json" id="data">(.*?)</script>', page, re.S)
    assert found is not None
    block = found.group(1)
    assert "<" not in block and ">" not in block and "&" not in block
    data = json.loads(block)
    assert data == json.loads(json.dumps(report_data(result), allow_nan=False))
    assert title in json.dumps(data, ensure_ascii=False)
    # The page has exactly the markup of the page of a plain title: none opened or closed by this one.
    plain = render_report(mechfem.run_deck(FOURBAR))
    for tag in ("<script", "</script>", "<!--", "<style", "</style>"):
        assert page.count(tag) == plain.count(tag), tag
