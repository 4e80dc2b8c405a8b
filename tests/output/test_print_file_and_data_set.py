"""The print file and the data set."""

from __future__ import annotations

from pathlib import Path

import pytest

import mechfem
from conftest import SUPPLY
from mechfem._util.atomic import atomic_text
from mechfem.output.files import print_file_lines, write_outputs


def test_atomic_text_leaves_nothing_behind_on_failure(tmp_path: Path) -> None:
    target = tmp_path / "x.prt"
    with pytest.raises(RuntimeError), atomic_text(target) as f:
        f.write("half")
        raise RuntimeError("interrupted")
    assert list(tmp_path.iterdir()) == []


def test_atomic_text_gives_files_the_usual_permissions(tmp_path: Path) -> None:
    with atomic_text(tmp_path / "a.prt") as f:
        f.write("x")
    (tmp_path / "b.prt").write_text("x")
    assert (tmp_path / "a.prt").stat().st_mode == (tmp_path / "b.prt").stat().st_mode


def test_print_file_without_printbuf_has_no_table(tmp_path: Path) -> None:
    deck = tmp_path / "quiet.mec"
    deck.write_text(SUPPLY.read_text().replace("PRINTBUF", "; no PRINTBUF"))
    lines = print_file_lines(mechfem.run_deck(deck))
    assert not any(line.startswith("BUFFERS") for line in lines)
    assert "ADJUSTMENT OF POSITION 1" in lines


def test_print_file_tabulates_every_buffer_for_bare_printbuf() -> None:
    result = mechfem.run_deck(SUPPLY)
    lines = print_file_lines(result)
    header = next(k for k, line in enumerate(lines) if line.startswith("  position"))
    assert lines[header].split() == ["position", "99", "100", "101", "102"]
    assert lines[header + 1].split() == ["alpha", "delta", "ddelta/dalpha", "d2delta/dalpha^2"]
    table = lines[header + 2 : header + 2 + result.positions]
    assert [int(row.split()[0]) for row in table] == list(range(1, 74))


def test_print_file_echoes_the_model() -> None:
    text = "\n".join(print_file_lines(mechfem.run_deck(SUPPLY)))
    assert "20 co-ordinates (8 fixed, 12 moving), 8 elements, 12 prescribed form parameters" in text
    assert "ANGB(2) - ANGB(4)" in text
    assert "DOF 1: row 12" in text


def test_outputs_go_to_a_new_folder(tmp_path: Path) -> None:
    written = write_outputs(mechfem.run_deck(SUPPLY), tmp_path / "a" / "b")
    assert sorted(p.name for p in written) == ["supply.csv", "supply.prt"]
