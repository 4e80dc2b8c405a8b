"""A run writes into its output folder and nowhere else, every file whole; exit codes tell a failure from a
stopped motion; the Python API gives the same numbers from several threads as serially."""

from __future__ import annotations

import subprocess
import warnings
import xml.etree.ElementTree as ET
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

import mechfem
import mechfem.model.storage
from conftest import ROOT, Cli, mechfem_command
from mechfem import Mechanism, Motion
from mechfem.model.motion import Table

FOURBAR = ROOT / "examples" / "fourbar" / "fourbar.mec"
ROCKER = ROOT / "tests" / "decks" / "rocker.mec"
ANIMATE_LINE = 91  # the ANIMATE line of fourbar.mec


def fourbar_copy(folder: Path, animate: str | None = None, steps: int | None = None) -> Path:
    """fourbar.mec in ``folder``, with another ANIMATE name and fewer steps if asked."""
    lines = FOURBAR.read_text().splitlines()
    assert lines[ANIMATE_LINE - 1].startswith("ANIMATE")
    if animate is not None:
        lines[ANIMATE_LINE - 1] = f"ANIMATE {animate}"
    if steps is not None:
        lines = [f"TSTEPE {steps} {6.283185307179586 / steps!r}" if t.startswith("TSTEPE") else t for t in lines]
    folder.mkdir(parents=True, exist_ok=True)
    deck = folder / "fourbar.mec"
    deck.write_text("\n".join(lines) + "\n")
    return deck


# --- confinement ----------------------------------------------------------------------------------------------------


@pytest.mark.parametrize("name", ["../film", "{outside}/film", "films/film", "films\\film", "..", "f" * 201])
def test_an_animate_name_that_leaves_the_output_folder_is_a_deck_error(cli: Cli, tmp_path: Path, name: str) -> None:
    outside = tmp_path / "outside"
    outside.mkdir()
    deck = fourbar_copy(tmp_path / "deck", name.format(outside=outside))
    out = tmp_path / "deck" / "out"
    proc = cli("run", deck, "-o", out)
    assert proc.returncode == 1, proc.stderr
    assert f"fourbar.mec:{ANIMATE_LINE}:9" in proc.stderr and "hint: give a plain file name" in proc.stderr
    assert "Traceback" not in proc.stderr
    assert not out.exists()
    assert list(outside.iterdir()) == []
    assert sorted(p.name for p in tmp_path.iterdir()) == ["deck", "outside"]


@pytest.mark.parametrize(
    ("name", "problem"),
    [
        ("../film", "leads out of the output folder"),
        ("/tmp/film", "is an absolute path"),
        ("C:film", "is an absolute path"),
        ("films/film", "has a folder part"),
        ("films\\film", "has a folder part"),
        ("film\0", "holds a NUL character"),
        ("  ", "is empty"),
        ("f" * 201, "is 201 bytes long"),
        ("my film", "holds a blank"),
        ("film\u202egif.exe", "holds the character U\\+202E, which does not show as itself"),
        ("film\u2028x", "holds a blank"),  # a line separator is white space to Python
        ("film\u200bx", "holds the character U\\+200B"),
    ],
)
def test_the_api_refuses_an_animate_name_that_is_not_a_plain_file_name(tmp_path: Path, name: str, problem: str) -> None:
    m = Mechanism.from_deck(FOURBAR)
    assert m.storage is not None
    m.storage.animate = name
    for call in (m.run, m.to_deck, lambda: m.save_deck(tmp_path / "saved.mec")):
        with pytest.raises(ValueError, match=f"the storage of mechanism 'fourbar'.*{problem}"):
            call()
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("file", ["../escape.dat", "tables/input.dat", "/tmp/input.dat"])
def test_save_deck_writes_table_files_beside_the_deck_only(tmp_path: Path, file: str) -> None:
    m = Mechanism.from_deck(FOURBAR)
    motion = Motion(10, {None: Table(np.linspace(0.0, 1.0, 11), file=file)})
    deck = tmp_path / "deck" / "saved.mec"
    with pytest.raises(ValueError, match="mechanism 'fourbar': the table file name"):
        m.save_deck(deck, motion)
    assert list(tmp_path.iterdir()) == []
    written = m.save_deck(deck, Motion(10, {None: Table(np.linspace(0.0, 1.0, 11), file="input.dat")}))
    assert sorted(p.name for p in written.parent.iterdir()) == ["input.dat", "saved.mec"]


def test_symlinks_in_the_output_folder_are_replaced_not_followed(cli: Cli, tmp_path: Path) -> None:
    deck = fourbar_copy(tmp_path / "deck", steps=12)
    out, outside = tmp_path / "out", tmp_path / "outside"
    out.mkdir()
    outside.mkdir()
    names = ["fourbar.prt", "fourbar.csv", "fourbar.gif", "fourbar.html", "fourbar_pic1.png", "fourbar_pic1.svg"]
    for name in names:
        (outside / name).write_text("precious")
        (out / name).symlink_to(outside / name)
    # A dangling link, and a link to a folder outside.
    (out / "fourbar_pic2.png").symlink_to(outside / "nothing.png")
    (out / "fourbar_pic2.svg").symlink_to(outside)
    proc = cli("run", deck, "-o", out, "--report", "--max-frames", "4")
    assert proc.returncode == 0, proc.stderr
    for name in names:
        assert (outside / name).read_text() == "precious"
        assert not (out / name).is_symlink() and (out / name).is_file(), name
    for name in ("fourbar_pic2.png", "fourbar_pic2.svg"):
        assert not (out / name).is_symlink() and (out / name).is_file(), name
    assert sorted(p.name for p in outside.iterdir()) == sorted(names)


# --- exit codes -----------------------------------------------------------------------------------------------------


def test_exit_codes_tell_a_failure_from_a_stopped_motion(cli: Cli, tmp_path: Path) -> None:
    assert cli("run", FOURBAR, "-o", tmp_path / "ok", "--max-frames", "2").returncode == 0
    stopped = cli("run", ROCKER, "-o", tmp_path / "stopped")
    assert stopped.returncode == 3 and "The motion stopped after position" in stopped.stderr
    assert (tmp_path / "stopped" / "rocker.prt").is_file()
    failed = cli("run", ROOT / "tests" / "decks" / "no_closure.mec", "-o", tmp_path / "failed")
    assert failed.returncode == 1 and not (tmp_path / "failed").exists()
    assert cli("run", "--max-frames", "1", FOURBAR).returncode == 2


def test_an_internal_error_exits_4(monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]) -> None:
    from mechfem.cli import command as cli

    def broken(args: object) -> int:
        raise ZeroDivisionError("a bug")

    monkeypatch.setattr(cli, "cmd_check", broken)
    assert cli.main(["check", str(FOURBAR)]) == cli.EXIT_INTERNAL == 4
    assert "This is a bug in mechfem" in capsys.readouterr().err


def test_a_stopped_motion_warns_in_the_python_api() -> None:
    with pytest.warns(mechfem.IncompleteRunWarning, match="The motion stopped after position"):
        result = mechfem.run_deck(ROCKER)
    assert result.report.stop_reason() is not None
    with pytest.warns(mechfem.IncompleteRunWarning, match="The motion stopped after position"):
        analysis = Mechanism.from_deck(ROCKER).run()
    assert analysis.stop_reason() is not None
    assert issubclass(mechfem.IncompleteRunWarning, UserWarning)
    # A complete run does not warn.
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert mechfem.run_deck(FOURBAR).report.stop_reason() is None


# --- the empty picture ----------------------------------------------------------------------------------------------


def test_media_draw_a_picture_without_plots(tmp_path: Path) -> None:
    from mechfem.model.echo import EchoPicture
    from mechfem.output.media import Media

    r = mechfem.run_deck(fourbar_copy(tmp_path / "deck", steps=6))
    pictures = [EchoPicture("empty", 0, []), *r.storage.pictures]
    r = r.replace(storage=r.storage.replace(pictures=pictures))
    media = Media(r, tmp_path / "out", max_frames=3, report=True)
    assert "picture 1 'empty' (line 0: no plots)" in "\n".join(media.print_lines())
    written = [p.name for p, _ in media.write()]
    assert {"fourbar_pic1.png", "fourbar_pic1.svg", "fourbar.gif", "fourbar.html"} <= set(written)
    with pytest.raises(ValueError, match="has no plots"):
        mechfem.model.storage.Storage().picture("nothing")


# --- concurrency ----------------------------------------------------------------------------------------------------


def check_whole(path: Path) -> None:
    """Every output file reads completely."""
    suffix = path.suffix
    if suffix == ".csv":
        rows = path.read_text().splitlines()
        assert len(rows) > 2 and all(len(r.split(",")) == len(rows[0].split(",")) for r in rows), path
        np.array([[float(v) for v in r.split(",")] for r in rows[1:]])
    elif suffix in (".png", ".gif"):
        with Image.open(path) as im:
            for k in range(getattr(im, "n_frames", 1)):
                im.seek(k)
                im.load()
    elif suffix == ".svg":
        ET.parse(path)
    elif suffix == ".html":
        assert path.read_text().rstrip().endswith("</html>"), path
    elif suffix == ".prt":
        text = path.read_text()
        assert text.startswith("mechfem ") and "PICTURES AND ANIMATION" in text, path
    else:
        raise AssertionError(f"unexpected file {path}")


def test_two_runs_into_one_folder_leave_only_whole_files(tmp_path: Path) -> None:
    deck = fourbar_copy(tmp_path / "deck", steps=48)
    out = tmp_path / "out"
    args = [*mechfem_command(), "run", str(deck), "-o", str(out), "--report", "--max-frames", "24"]
    runs = [
        subprocess.Popen(args, stdin=subprocess.DEVNULL, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
        for _ in range(2)
    ]
    # Each run either writes everything, or is refused at once because the other holds the folder's lock on the
    # outputs of fourbar; at least one writes.
    statuses = []
    for p in runs:
        _, err = p.communicate(timeout=300)
        assert p.returncode == 0 or (p.returncode == 1 and b"another mechfem run is writing" in err), err.decode()
        statuses.append(p.returncode)
    assert 0 in statuses
    files = sorted(out.iterdir())
    assert not [p for p in files if ".tmp" in p.name], files
    names = {p.name for p in files}
    assert {
        "fourbar.prt",
        "fourbar.csv",
        "fourbar.gif",
        "fourbar.html",
        "fourbar_pic1.png",
        "fourbar_pic3.svg",
    } <= names
    for path in files:
        if path.suffix != ".mp4":
            check_whole(path)


def test_the_api_from_several_threads_gives_the_serial_numbers() -> None:
    base = Mechanism.from_deck(FOURBAR)
    rows = [r for r in base.rows if r.value is not None and r.kind != "input"]
    variants = []
    for k in range(4):
        m = Mechanism.from_deck(FOURBAR)
        row = next(r for r in m.rows if r.name == rows[0].name)
        row.value = float(rows[0].value) * (1.0 + 0.02 * k)  # type: ignore[arg-type]
        variants.append(m)

    def numbers(job: Mechanism | Path) -> np.ndarray:
        if isinstance(job, Path):
            buffers = mechfem.run_deck(job).buffers
            return np.concatenate([np.asarray(buffers[n]) for n in sorted(buffers)])
        return np.asarray(job.run().coords)

    jobs: list[Mechanism | Path] = [*variants, FOURBAR, ROOT / "examples" / "supply" / "supply.mec"]
    serial = [numbers(j) for j in jobs]
    with ThreadPoolExecutor(max_workers=len(jobs)) as pool:
        threaded = list(pool.map(numbers, jobs * 2))
    for a, b in zip(serial * 2, threaded, strict=True):
        np.testing.assert_allclose(b, a, rtol=0, atol=0)
    assert not np.allclose(serial[0], serial[1])
