"""A frame angle (VARYFRAME) in a deck in mm and degrees: the path-generation example with B0 on the line of the
known four-bar and the points turned by 0.4 rad about A0, written once in metres and radians and once with
``UNITS LENGTH mm ANGLE deg`` (every length times 1000, every angle in degrees). Both find the known four-bar
turned by 0.4 rad; the mm deck's print file and written design state it in mm and degrees. What the turn moves is
held in the core's units, so the deck in mm starts from the metre deck's design."""

from __future__ import annotations

import math
import sys
from pathlib import Path

import numpy as np
import pytest

import mechfem
from conftest import ROOT, mechfem_command
from mechfem.design import optimise_deck

SYNTHESIS = ROOT / "examples" / "synthesis"
sys.path.insert(0, str(SYNTHESIS))
import path_synthesis as ps  # noqa: E402

PHI = 0.4
"""The turn of the points about A0: the frame angle to find, in radians."""

#: path.mec's lines with B0 fixed at the known four-bar's place and the frame angle varied, in metres and in mm.
LINES = [
    ("     3 2.8 ", "     3 3.2 ", "     3 3200.0 "),
    ("     4 0.4\n", "     4 0.0\n", "     4 0.0\n"),
    ("XMOV 5 1.2 ", "XMOV 5 1.2 ", "XMOV 5 1200.0 "),
    ("     7 2.0\n", "     7 2.0\n", "     7 2000.0\n"),
    ("     8 2.1\n", "     8 2.1\n", "     8 2100.0\n"),
    ("     9 2.2\n", "     9 2.2\n", "     9 2200.0\n"),
    ("    10 1.4\n", "    10 1.4\n", "    10 1400.0\n"),
    ("PARA 1 1.2\n", "PARA 1 1.2\n", "PARA 1 1200.0\n"),
    ("     2 2.6\n", "     2 2.6\n", "     2 2600.0\n"),
    ("     3 1.0\n", "     3 1.0\n", "     3 1000.0\n"),
    ("     4 1.4\n", "     4 1.4\n", "     4 1400.0\n"),
    ("     5 2.8\n", "     5 2.8\n", "     5 2800.0\n"),
    ("MOV_RELE 1 5.654866776461628", "MOV_RELE 1 5.654866776461628", "MOV_RELE 1 324.0"),
    ("VARYX 3 1.0 5.0\n", "", ""),
    ("VARYX 4 -2.0 2.0\n", "", ""),
    ("VARY 1 0.5 2.0", "VARY 1 0.5 2.0", "VARY 1 500.0 2000.0"),
    ("VARY 2 1.5 5.0", "VARY 2 1.5 5.0", "VARY 2 1500.0 5000.0"),
    ("VARY 5 1.0 4.0", "VARY 5 1.0 4.0", "VARY 5 1000.0 4000.0"),
    ("VARY 3 -1.0 3.0", "VARY 3 -1.0 3.0", "VARY 3 -1000.0 3000.0"),
    ("VARY 4 -1.0 3.0", "VARY 4 -1.0 3.0", "VARY 4 -1000.0 3000.0"),
    ("TARGET 1 path_x.dat\n", "TARGET 1 path_x.dat\n", "TARGET 1 path_x_mm.dat\n"),
    (
        "TARGET 2 path_y.dat\n",
        "TARGET 2 path_y.dat\nVARYFRAME 1 -3.141592653589793 3.141592653589793\n",
        "TARGET 2 path_y_mm.dat\nVARYFRAME 1 -180.0 180.0\n",
    ),
    ("KIN OPT\n", "KIN OPT\n", "KIN OPT\nUNITS LENGTH mm ANGLE deg\n"),
]


def _decks(tmp_path: Path) -> tuple[Path, Path]:
    c, s = math.cos(PHI), math.sin(PHI)
    points = ps.known_points() @ np.array([[c, s], [-s, c]])
    for k, axis in enumerate("xy"):
        for suffix, f in (("", 1.0), ("_mm", 1000.0)):
            rows = ["*"] * (ps.SUBSTEPS * (len(ps.THETAS) - 1) + 1)
            rows[:: ps.SUBSTEPS] = [repr(float(v) * f) for v in points[:, k]]
            (tmp_path / f"path_{axis}{suffix}.dat").write_text("\n".join(rows) + "\n")
    si = mm = (SYNTHESIS / "path.mec").read_text()
    for old, in_m, in_mm in LINES:
        assert old in si, old
        si, mm = si.replace(old, in_m, 1), mm.replace(old, in_mm, 1)
    (tmp_path / "turned.mec").write_text(si)
    (tmp_path / "turned_mm.mec").write_text(mm)
    return tmp_path / "turned.mec", tmp_path / "turned_mm.mec"


def test_a_frame_angle_in_degrees_finds_the_metre_decks_turn(tmp_path: Path) -> None:
    found = []
    for deck in _decks(tmp_path):
        opt = optimise_deck.describe(deck).optimise
        assert opt is not None
        found.append(optimise_deck.optimise(deck, opt))
    si, mm = found
    # The same start (what the turn moves in the core's units) and the same optimum, the frame angle last.
    assert mm.start_objective == pytest.approx(si.start_objective, rel=1e-12)
    assert si.objective < 1e-18 and mm.objective < 1e-18
    assert np.allclose(mm.x, si.x, rtol=1e-8, atol=1e-10)
    assert si.x[-1] == pytest.approx(PHI, abs=1e-8)
    assert mm.deck is not None
    scales = optimise_deck.deck_scales(mm.deck.block, mm.deck.problem)
    assert scales == pytest.approx([1000.0] * 5 + [math.degrees(1.0)])
    # The written design in the deck's units: B0 turned by 0.4 rad about A0, in mm; the crank starts at 0.4 rad.
    m = mechfem.Mechanism.from_deck(optimise_deck.write_design_deck(mm, tmp_path / "out"))
    assert (m["B0.x"].value, m["B0.y"].value) == pytest.approx((3200.0 * math.cos(PHI), 3200.0 * math.sin(PHI)))
    assert m["theta"].value == pytest.approx(math.degrees(PHI), abs=1e-6)
    assert m["crank_length"].value == pytest.approx(1000.0, abs=1e-6)


def test_the_print_file_states_the_frame_angle_in_degrees(tmp_path: Path) -> None:
    import subprocess

    _, deck = _decks(tmp_path)
    p = subprocess.run(
        [*mechfem_command(), "run", str(deck), "-o", str(tmp_path / "out"), "--no-media"],
        capture_output=True,
        text=True,
    )
    assert p.returncode == 0, p.stderr
    assert f"frame = {math.degrees(PHI):.10g} deg" in p.stdout + p.stderr
    printed = (tmp_path / "out" / "turned_mm.prt").read_text()
    rows = {line.split()[0]: line.split()[1:] for line in printed.split("design variables:")[1].splitlines()[2:8]}
    assert rows["frame"][0] == "deg" and float(rows["frame"][2]) == pytest.approx(math.degrees(PHI), abs=1e-6)
    assert [float(v) for v in rows["frame"][3:5]] == [-180.0, 180.0]
    assert rows["crank_length"][0] == "mm" and float(rows["crank_length"][2]) == pytest.approx(1000.0, abs=1e-6)
