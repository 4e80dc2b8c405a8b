"""Every output speaks the model's names and units (docs/python-api.md, "Names and units"): the report of a run from
Python, the data set, the print file, the pictures and the animation's title, ``to_pandas`` and the drawings."""

from __future__ import annotations

import math
from pathlib import Path

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
    from mechfem.report import write_report

    result = mechfem.run_deck(ROOT / "examples" / "fourbar" / "fourbar.mec")
    written = write_report(result, tmp_path)
    assert result.to_html() == written.read_text(encoding="utf-8")
