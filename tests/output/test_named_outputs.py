"""Every output speaks the model's names and units (docs/python-api.md, "Names and units"): the report of a run from
Python, the data set, the print file, the pictures and the animation's title, ``to_pandas`` and the drawings."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

import mechfem
from conftest import ROOT
from mechfem import Driven, Mechanism, Motion, Output


def fourbar(**units: str) -> Mechanism:
    """The four-bar of docs/python-api.md with a named crank input ``phi`` and output ``psi``."""
    m = Mechanism("fourbar", **units)
    A0, B0 = m.fixed("A0", 0.0, 0.0), m.fixed("B0", 4.0, 0.0)
    A, B, C = m.point("A", 1.0, 0.0), m.point("B", 3.5, 2.5), m.point("C", 1.5, 2.0)
    m.bar("crank", A0, A, length=1.0, angle=Driven(start=0.0, name="phi"))
    m.ternary2("coupler", A, B, C, length=3.5, u=1.5, v=1.2)
    m.bar("rocker", B0, B, length=3.0, angle=Output("psi"))
    return m


def test_the_report_of_a_run_from_python_is_public_and_named(tmp_path: Path) -> None:
    result = fourbar().run(Motion.by(12, 2 * math.pi))
    page = result.to_html()
    assert page.startswith("<!doctype html>")
    assert '"psi' in page and "dpsi/dphi" in page
    path = result.save_report(tmp_path / "sub" / "fourbar report.html")
    assert path == tmp_path / "sub" / "fourbar report.html"
    assert path.read_text(encoding="utf-8") == page


def test_the_report_of_a_deck_is_the_page_the_command_writes(tmp_path: Path) -> None:
    from mechfem.report.html import write_report

    result = mechfem.run_deck(ROOT / "examples" / "fourbar" / "fourbar.mec")
    written = write_report(result, tmp_path)
    assert result.to_html() == written.read_text(encoding="utf-8")


# --- a deck in millimetres and degrees against its SI twin ---------------------------------------------------------

FOURBAR = ROOT / "examples" / "fourbar" / "fourbar.mec"


def _twin(tmp_path: Path) -> tuple[Path, Path]:
    """The four-bar example as an SI deck (its numbers in metres and radians) and as the same deck in millimetres
    and degrees: every length times 1000, the crank angle (row 6) and the motion in degrees."""
    text = FOURBAR.read_text()
    si = tmp_path / "si" / "fourbar.mec"
    si.parent.mkdir()
    si.write_text(text.replace("KIN ANA", "KIN ANA\nUNITS LENGTH m ANGLE rad", 1))
    block, keyword, out = "", "", []
    for line in text.splitlines():
        words = line.split(";")[0].split()
        if words and words[0] in ("GEOMETRY", "NAMES", "MOVEMENT"):
            block = words[0]
        elif block == "GEOMETRY" and words:
            if not words[0].isdigit():
                keyword, words = words[0], words[1:]
            row, value = int(words[0]), float(words[1])
            # Row 6 (PARA) is the crank angle; every other number of the block is a length.
            converted = math.degrees(value) if (keyword, row) == ("PARA", 6) else value * 1000.0
            line = f"{keyword} {row} {converted!r}"
        out.append(line)
    mm = "\n".join(out).replace("KIN ANA", "KIN ANA\nUNITS LENGTH mm ANGLE deg", 1)
    mm = mm.replace("MOV_RELE 1 12.566370614359172", "MOV_RELE 1 720.0")
    deck = tmp_path / "mm" / "fourbar.mec"
    deck.parent.mkdir()
    deck.write_text(mm)
    return si, deck


def test_a_deck_in_mm_and_degrees_gives_its_si_twins_numbers_converted(tmp_path: Path) -> None:
    import numpy as np

    si_deck, mm_deck = _twin(tmp_path)
    si, mm = mechfem.run_deck(si_deck), mechfem.run_deck(mm_deck)
    deg = 180.0 / math.pi
    assert np.allclose(mm.coords, si.coords * 1000.0, rtol=1e-9, atol=1e-9)
    # Buffer by buffer, each in its own derived unit: phi in deg, C in mm, dC/dphi in mm/deg, d2psi/dphi^2 in 1/deg.
    scale = {1: deg, 2: 1.0, 11: 1e3, 13: 1e3 / deg, 15: 1e3 / deg**2, 17: 1e3, 19: 1e3, 21: deg, 22: 1.0}
    scale |= {23: 1.0 / deg, 24: deg, 25: deg}
    for b, f in scale.items():
        assert np.allclose(mm.buffers[b], si.buffers[b] * f, rtol=1e-9, atol=1e-9 * max(1.0, abs(f))), b


def test_a_deck_in_mm_and_degrees_names_its_units_in_every_output(tmp_path: Path) -> None:
    from mechfem.output.files import print_file_lines, write_data_set
    from mechfem.results.labels import buffer_labels

    _, mm_deck = _twin(tmp_path)
    r = mechfem.run_deck(mm_deck)
    labels = buffer_labels(r)
    legends = {b: labels[b].legend() for b in (1, 2, 11, 13, 15, 17, 21, 22, 23, 24)}
    assert legends == {
        1: "1 phi [deg]",
        2: "2 time [s]",
        11: "11 C.x [mm]",
        13: "13 dC.x/dphi [mm/deg]",
        15: "15 d2C.x/dphi^2 [mm/deg²]",
        17: "17 vC.x [mm/s]",
        21: "21 psi [deg]",
        22: "22 dpsi/dphi [-]",
        23: "23 d2psi/dphi^2 [1/deg]",
        24: "24 vpsi [deg/s]",
    }
    # The data set's header and the print file say the names (and the print file the units).
    data = write_data_set(r, tmp_path / "out")
    header = data.read_text().splitlines()[0] if data is not None else ""
    assert "phi" in header and "C.x" in header and "ANGB" not in header and "x9" not in header
    printed = "\n".join(print_file_lines(r))
    assert "C.x       mm" in printed and "psi       deg" in printed and "value of input 1 (phi)" in printed
    # The report page and the animation's title.
    page = r.to_html()
    assert "dC.x/dphi" in page and "mm/deg" in page
    from mechfem.viz.animation import _title

    assert _title(r, "fourbar", 0).endswith(f"(phi = {r.buffers[1][0]:.6g} deg)")


def test_the_optimisation_summary_names_its_variables_in_the_decks_units(tmp_path: Path) -> None:
    from mechfem.design import optimise_deck

    opt_deck = ROOT / "examples" / "supply" / "supply_opt.mec"
    problem = optimise_deck.problem(opt_deck, opt_deck.read_text(), optimise_deck.describe(opt_deck).optimise)
    model = mechfem.run_deck(ROOT / "examples" / "supply" / "supply.mec").model
    assert optimise_deck.variable_labels(problem, model) == [("kappa", "rad")]
    # The same deck with its angles in degrees: kappa is said in degrees.
    deg = tmp_path / "supply.mec"
    text = (ROOT / "examples" / "supply" / "supply.mec").read_text()
    text = text.replace("KIN ANA", "KIN ANA\nUNITS ANGLE deg", 1).replace("6.283185307179586", "360")
    deg.write_text(text.replace(" -5.17514 ;", f" {math.degrees(-5.17514)!r} ;"))
    in_degrees = mechfem.run_deck(deg).model
    assert optimise_deck.values_line(problem, [-296.5], in_degrees) == "kappa = -296.5 deg"
    # Without the echo, the deck's numbers.
    assert optimise_deck.values_line(problem, [-5.175], None) == "PARA 5 = -5.175"


def test_drawings_and_tables_use_the_names(tmp_path: Path) -> None:
    r = mechfem.run_deck(FOURBAR)
    svg = r.to_svg(tmp_path / "fourbar.svg").read_text()
    assert ">C<" in svg and ">A0<" in svg and ">P9<" not in svg
    columns = list(r.table())
    assert {"phi", "psi", "psi'", "psi''", "C.x", "C.x'"} <= set(columns)
    assert not any(c.startswith(("x9", "ANGB")) for c in columns)


def test_a_dxf_drawing_names_its_points_and_declares_the_decks_length_unit(tmp_path: Path) -> None:
    ezdxf = pytest.importorskip("ezdxf")
    _, mm_deck = _twin(tmp_path)
    path = mechfem.run_deck(mm_deck).to_dxf(tmp_path / "fourbar.dxf")
    doc = ezdxf.readfile(path)
    assert doc.header["$INSUNITS"] == 4  # millimetres, from the deck's UNITS LENGTH mm
    names = {e.dxf.text for e in doc.modelspace().query("TEXT MTEXT") if e.dxf.layer == "NAMES"}
    assert {"A0", "B0", "A", "B", "C"} <= names
