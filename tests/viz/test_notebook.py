"""Results in Jupyter: the HTML of an Analysis, a deck's RunResult and a Study, with every name escaped."""

from __future__ import annotations

import base64
import math
import warnings
import xml.etree.ElementTree as ET
from html.parser import HTMLParser

import numpy as np
import pytest

import mechfem
from bare_examples import bare
from conftest import ROOT, SUPPLY
from mechfem import Driven, Mechanism, Motion, Output
from mechfem.viz import figures, notebook

SVG = "{http://www.w3.org/2000/svg}"
TURN = 2 * math.pi


class Page(HTMLParser):
    """The tags, the text of every table cell, and the images of an HTML fragment."""

    def __init__(self, text: str) -> None:
        super().__init__()
        self.tags: list[str] = []
        self.cells: list[str] = []
        self.images: list[dict[str, str]] = []
        self.titles: list[str] = []
        self._cell: list[str] | None = None
        self._strong = False
        self.feed(text)
        self.close()

    def handle_starttag(self, tag: str, attrs: list[tuple[str, str | None]]) -> None:
        self.tags.append(tag)
        if tag in ("td", "th"):
            self._cell = []
        elif tag == "img":
            self.images.append({k: v or "" for k, v in attrs})
        elif tag == "strong":
            self._strong = True

    def handle_endtag(self, tag: str) -> None:
        if tag in ("td", "th") and self._cell is not None:
            self.cells.append("".join(self._cell))
            self._cell = None
        elif tag == "strong":
            self._strong = False

    def handle_data(self, data: str) -> None:
        if self._cell is not None:
            self._cell.append(data)
        if self._strong:
            self.titles.append(data)

    def after(self, label: str, n: int = 1) -> list[str]:
        """The ``n`` cells after the cell ``label``."""
        k = self.cells.index(label)
        return self.cells[k + 1 : k + 1 + n]


def fourbar(rocker: float = 3.0, name: str = "fourbar") -> Mechanism:
    m = Mechanism(name)
    a0, b0 = m.fixed("A0", 0.0, 0.0), m.fixed("B0", 4.0, 0.0)
    a, b = m.point("A", 1.0, 0.0), m.point("B", 3.5, 2.5)
    m.bar("crank", a0, a, length=1.0, angle=Driven(start=0.0, name="phi"))
    m.bar("coupler", a, b, length=3.5)
    m.bar("rocker", b0, b, length=rocker, angle=Output("psi"))
    m.bar("probe", a0, b, angle=Output("reach <AB> & 'more'"))
    return m


def data(uri: str, kind: str) -> bytes:
    prefix = f"data:{kind};base64,"
    assert uri.startswith(prefix)
    return base64.b64decode(uri[len(prefix) :])


def test_analysis_shows_its_summary_outputs_and_picture() -> None:
    r = fourbar(name="four <bar> & 'co'").run(Motion.by(36, TURN))
    page = Page(r._repr_html_())
    assert "bar" not in page.tags  # the mechanism's name is text, not markup
    assert page.titles == ["Analysis of four <bar> & 'co'"]
    assert page.after("mechanism") == ["four <bar> & 'co'"]
    assert page.after("positions") == ["37"]
    assert page.after("state") == ["complete"]
    assert page.after("limit positions") == ["none"]
    # psi is an angle; the probe's angle too, under a name that needs escaping.
    psi = r.output("psi")
    assert page.after("psi", 3) == [f"{psi.min():.6g}", f"{psi.max():.6g}", "rad"]
    assert page.after("reach <AB> & 'more'", 3)[2] == "rad"
    # The picture is the one _repr_png_ gives, as a PNG.
    (img,) = page.images
    png = data(img["src"], "image/png")
    assert png.startswith(b"\x89PNG\r\n\x1a\n")
    assert png == r._repr_png_()
    assert "four <bar>" in img["alt"]


def test_the_picture_is_rendered_once_for_html_and_png(monkeypatch: pytest.MonkeyPatch) -> None:
    r = fourbar().run(Motion.by(12, TURN))
    calls: list[object] = []
    real = figures.result_png

    def counting(a: mechfem.Analysis) -> bytes | None:
        calls.append(a)
        return real(a)

    monkeypatch.setattr(figures, "result_png", counting)
    r._repr_html_()
    r._repr_png_()
    r._repr_html_()
    assert len(calls) == 1


def test_a_stopped_analysis_says_why_and_lists_its_limits() -> None:
    m = fourbar(rocker=1.0)  # non-Grashof: the crank cannot turn once, the motion stops at a limit position
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", mechfem.IncompleteRunWarning)
        r = m.run(Motion.by(36, TURN))
    assert not r.complete
    page = Page(r._repr_html_())
    (why,) = page.after("state")
    assert why.startswith(f"The motion stopped after position {r.positions} of 37")
    (limits,) = page.after("limit positions")
    assert limits == ("none" if not r.limits else "".join(x.describe(r.report.input_names) for x in r.limits))


def test_a_deck_run_shows_its_buffers_with_labels_and_the_mechanism() -> None:
    result = mechfem.run_deck(bare(SUPPLY))
    page = Page(result._repr_html_())
    assert page.titles == ["Run of supply.mec"]
    assert page.after("mode") == ["KIN ANA"]
    assert page.after("positions") == ["73"]
    # Buffer 99 is BUFINP 1, the crank angle ANGB(1), turned once from its start: its range is one turn.
    name, lo, hi, unit = page.after("99", 4)
    assert (name, unit) == ("ANGB(1)", "rad")
    assert float(hi) - float(lo) == pytest.approx(TURN, abs=1e-5)
    # Buffer 101 is BUFKE1 -1 1: d(output angle)/d(input 1), in rad per rad.
    assert page.after("101", 4)[0] == "dANGB(8)/dinput1"
    assert page.after("101", 4)[3] == "-"
    (img,) = page.images
    svg = ET.fromstring(data(img["src"], "image/svg+xml"))
    joints = [c for c in svg.iter(f"{SVG}circle") if (c.get("class") or "").startswith("joint")]
    assert len(joints) == 10  # the supply mechanism's ten points
    x = result.coords[0]
    assert {(round(float(c.get("cx", "")), 6), round(-float(c.get("cy", "")), 6)) for c in joints} >= {
        (round(x[8], 6), round(x[9], 6))
    }


def test_a_stopped_deck_run_says_why() -> None:
    deck = ROOT / "examples" / "limits" / "slider_dead_centre.mec"
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", mechfem.IncompleteRunWarning)
        result = mechfem.run_deck(deck)
    page = Page(result._repr_html_())
    (why,) = page.after("state")
    assert why == result.report.stop_reason()
    assert why.startswith("The motion stopped")


def test_a_study_shows_a_summary_and_its_first_rows() -> None:
    rockers = [*np.linspace(2.8, 3.2, 14), 0.3, 0.4]  # the last two cannot be assembled: 3.5 - rocker > 3
    study = mechfem.sweep(fourbar, {"rocker": rockers}, motion=Motion.by(12, TURN), progress=False)
    page = Page(study._repr_html_())
    assert page.titles == ["Study of 16 variants"]
    assert page.after("variants") == ["16"]
    ok = int(np.sum(study["ok"]))
    assert ok == 14
    assert page.after("position 1 computed") == ["14 of 16"]
    assert page.after("parameters") == ["rocker"]
    header = list(study.columns)[: notebook.STUDY_COLUMNS]
    starts = [k for k in range(len(page.cells)) if page.cells[k : k + len(header)] == header]
    assert len(starts) == 1, "the table's header row"
    k = starts[0]
    rows = page.cells[k + len(header) :]
    assert len(rows) == notebook.STUDY_ROWS * len(header)
    assert rows[0] == f"{rockers[0]:.6g}"
    assert rows[header.index("ok")] == "yes"
    assert "the first 10 of 16 rows" in study._repr_html_()


def test_errors_in_a_study_are_escaped() -> None:
    study = mechfem.sweep(fourbar, {"rocker": [0.3]}, motion=Motion.by(4, TURN), progress=False)
    html = study._repr_html_()
    page = Page(html)
    (error,) = [c for c in page.cells if c == study["error"][0]]
    assert error  # the cell holds the error's text exactly, whatever characters it has
    assert "script" not in page.tags


def test_jupyter_picks_the_html() -> None:
    formatters = pytest.importorskip("IPython.core.formatters", reason="IPython is not installed")
    r = fourbar().run(Motion.by(12, TURN))
    shown, _ = formatters.DisplayFormatter().format(r)
    assert "text/html" in shown and "image/png" in shown
    assert shown["text/html"].startswith('<div class="mechfem">')
