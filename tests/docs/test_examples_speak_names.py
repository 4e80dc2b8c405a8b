"""Every shipped example speaks its names and units in every output a first-time user reads: the data set's header,
the print file (outside the model echo, which shows each row's form parameters beside its name), the limit and stop
sentences, the pictures' titles, axes and legends, the animation's title, ``to_pandas()``, the paths and point labels
of a DXF/SVG drawing, the report's charts. Nothing says a deck number (``ANGB(8)``, ``x13``, ``input1``) or a
dimension instead of a unit (``[length]``, ``[torque]``); a deck in degrees says no radians.

The pictures and the report are drawn for a few examples only (the slow part), every other output for all.
"""

from __future__ import annotations

import re
import warnings
from pathlib import Path

import pytest
from matplotlib.text import Text

import mechfem
from conftest import ROOT
from deck.test_names_units import fourbar_mm_deg
from mechfem.output.files import print_file_lines
from mechfem.report.html import report_data
from mechfem.results.labels import buffer_labels
from mechfem.results.result import RunResult
from mechfem.viz import animation, export
from mechfem.viz.plots import picture_figure, picture_title

EXAMPLES = sorted((ROOT / "examples").rglob("*.mec"))
RAW = re.compile(
    r"(ANG[BV]|LEN[LUV]|COOR|GEAR|BELT)\(\d+\)|\b(d2?|v|a)?x\d+\b|\bd?input\d+\b"
    r"|\[(length|torque|force|energy|power|mass)\]"
)
"""A deck number where a name belongs (``ANGB(8)``, ``x13``, ``dx13/dinput1``, ``vx13``), or a dimension where a unit
belongs."""
DRAWN = ("fourbar.mec", "chain_swing_arm.mec", "supply_dyn.mec")


def run(deck: Path) -> RunResult:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return mechfem.run_deck(deck)


def texts(result: RunResult) -> list[str]:
    """Every text of the outputs that are quick to make."""
    labels = buffer_labels(result)
    out = [x.header() for x in labels.values()] + [x.axis() for x in labels.values()]
    out += [str(c) for c in result.to_pandas().columns]
    lines = print_file_lines(result)
    # The model echo lists each row's form parameters beside its name (``ANGB(1)  = phi``): that is its job.
    # The buffer table's last column says what each buffer holds in the deck's words (``generalised stress of row 6
    # (LENL(5))``): its name and unit columns are what must speak names.
    echo_end = next(k for k, line in enumerate(lines) if line.startswith("ADJUSTMENT"))
    table = next((k for k, line in enumerate(lines) if line.startswith("BUFFERS")), echo_end)
    table_end = lines.index("", table) if table > echo_end else table
    out += lines[echo_end:table] + [line.split(" BUF")[0] for line in lines[table:table_end]] + lines[table_end:]
    out += [picture_title(result, k) for k in range(len(result.storage.pictures))]
    if result.storage.animate:
        out.append(animation._title(result, result.storage.animate, result.positions - 1))
    drawing = export.result_drawing(result)
    out += [p.label for p in drawing.paths] + [x.text for x in drawing.labels]
    return out


def drawn(result: RunResult) -> list[str]:
    """Every text of the pictures and of the report's charts."""
    out = []
    for k in range(len(result.storage.pictures)):
        fig = picture_figure(result, k)
        out += [t.get_text() for t in fig.findobj(Text)]  # type: ignore[attr-defined]
    return out + _strings(report_data(result))


def _strings(obj: object) -> list[str]:
    if isinstance(obj, str):
        return [obj]
    if isinstance(obj, dict):
        # A column's ``text`` says what it holds in the deck's words, as the print file's buffer table does.
        return [s for k, v in obj.items() if k != "text" for s in _strings(v)]
    if isinstance(obj, (list, tuple)):
        return [s for v in obj for s in _strings(v)]
    return []


def raw(found: list[str]) -> list[str]:
    return [t for t in found if RAW.search(t)]


@pytest.mark.parametrize("deck", EXAMPLES, ids=lambda p: p.name)
def test_an_example_names_what_it_shows(deck: Path) -> None:
    result = run(deck)
    assert raw(texts(result)) == []
    if deck.name in DRAWN:
        assert raw(drawn(result)) == []


def test_a_deck_in_degrees_says_no_radians(tmp_path: Path) -> None:
    deck = tmp_path / "fourbar_mm.mec"
    deck.write_text(fourbar_mm_deg())
    result = run(deck)
    found = texts(result) + drawn(result)
    assert raw(found) == []
    assert [t for t in found if re.search(r"\brad\b", t)] == []
    assert any("deg" in t for t in found) and any("mm" in t for t in found)


def test_the_audit_finds_a_raw_name(tmp_path: Path) -> None:
    # The four-bar without its NAMES block says its deck numbers, and the audit sees them.
    text = (ROOT / "examples" / "fourbar" / "fourbar.mec").read_text()
    deck = tmp_path / "fourbar.mec"
    deck.write_text(text[: text.index("NAMES")] + text[text.index("MOVEMENT") :])
    found = raw(texts(run(deck)))
    assert (
        "11 x9" in found
        and "13 dx9/dinput1" in found
        and "fourbar: position 145 of 145  (ANGB(1) = 12.5664 rad)" in found
    )
