"""The mechanism's drawing as DXF and SVG: read back, the entities sit where the run puts the mechanism."""

from __future__ import annotations

import math
import sys
import warnings
import xml.etree.ElementTree as ET
from collections import Counter
from pathlib import Path

import numpy as np
import pytest

import mechfem
from conftest import ROOT, SUPPLY, Cli
from mechfem import Driven, Mechanism, Motion, Output
from mechfem.viz import export

ezdxf = pytest.importorskip("ezdxf", reason="the DXF export needs ezdxf (pip install 'mechfem[dxf]')")

SVG = "{http://www.w3.org/2000/svg}"
BELT = ROOT / "examples" / "gears" / "belt_swing_arm.mec"

# The supply deck's TOPOLOGY and PARA lines: element -> (x, y co-ordinate numbers of P, of Q) and the length its
# LENL row prescribes (FORM lines 1-4, 7, 11, 12: rows 1-4, 6, 10, 11).
SUPPLY_BARS: dict[int, tuple[tuple[int, int], tuple[int, int], float]] = {
    1: ((1, 2), (9, 10), 0.4),
    2: ((11, 12), (9, 10), 0.8),
    3: ((3, 4), (11, 12), 0.8),
    4: ((11, 12), (13, 14), 0.8),
    5: ((13, 14), (15, 16), 6.78543),
    7: ((17, 18), (19, 20), 0.5),
    8: ((7, 8), (19, 20), 0.64952),
}
SUPPLY_PLATE = [(5, 6), (17, 18), (15, 16)]
SUPPLY_FIXED = [(1, 2), (3, 4), (5, 6), (7, 8)]
SUPPLY_MOVING = [(9, 10), (11, 12), (13, 14), (15, 16), (17, 18), (19, 20)]


@pytest.fixture(scope="module")
def supply() -> mechfem.RunResult:
    return mechfem.run_deck(SUPPLY)


def at(result: mechfem.RunResult, position: int, point: tuple[int, int]) -> tuple[float, float]:
    x = result.coords[position - 1]
    return float(x[point[0] - 1]), float(x[point[1] - 1])


def same_segment(a: tuple[tuple[float, float], tuple[float, float]], b: tuple[object, object]) -> bool:
    pa, qa = (np.asarray(p, dtype=float)[:2] for p in a)
    pb, qb = (np.asarray(p, dtype=float)[:2] for p in b)
    close = lambda u, v: bool(np.allclose(u, v, rtol=0, atol=1e-9))  # noqa: E731
    return (close(pa, pb) and close(qa, qb)) or (close(pa, qb) and close(qa, pb))


def xy(v: object) -> tuple[float, float]:
    """x and y of a DXF point (a Vec3)."""
    a = tuple(v)  # type: ignore[call-overload]
    return float(a[0]), float(a[1])


def entities(path: Path) -> list[object]:
    doc = ezdxf.readfile(path)
    assert not doc.audit().has_errors
    return list(doc.modelspace())


def on(ents: list[object], kind: str, layer: str) -> list[object]:
    return [e for e in ents if e.dxftype() == kind and e.dxf.layer == layer]  # type: ignore[attr-defined]


@pytest.mark.parametrize("position", [1, 10])
def test_dxf_bars_plate_pivots_and_paths_of_the_supply_mechanism(
    supply: mechfem.RunResult, tmp_path: Path, position: int
) -> None:
    path = export.export_drawing(supply, tmp_path / "supply.dxf", position)
    ents = entities(path)
    lines = on(ents, "LINE", "LINKS")
    assert len(lines) == len(SUPPLY_BARS)
    for element, (p, q, length) in SUPPLY_BARS.items():
        want = (at(supply, position, p), at(supply, position, q))
        found = [e for e in lines if same_segment(want, (e.dxf.start, e.dxf.end))]  # type: ignore[attr-defined]
        assert len(found) == 1, f"bar {element} at position {position}"
        # Its length is the PARA value of its LENL row, straight from the deck.
        start, end = found[0].dxf.start, found[0].dxf.end  # type: ignore[attr-defined]
        assert math.dist(xy(start), xy(end)) == pytest.approx(length, abs=1e-9)
    (plate,) = on(ents, "LWPOLYLINE", "LINKS")
    assert plate.closed  # type: ignore[attr-defined]
    corners = np.array([v[:2] for v in plate.get_points("xy")])  # type: ignore[attr-defined]
    assert np.allclose(corners, [at(supply, position, p) for p in SUPPLY_PLATE], atol=1e-9)
    circles = on(ents, "CIRCLE", "PIVOTS")
    centres = sorted(tuple(np.round(xy(c.dxf.center), 9)) for c in circles)  # type: ignore[attr-defined]
    points = sorted(tuple(np.round(at(supply, position, p), 9)) for p in SUPPLY_FIXED + SUPPLY_MOVING)
    assert centres == points
    # Each fixed pivot is a triangle with its apex at the pivot, on the ground layer.
    triangles = on(ents, "LWPOLYLINE", "GROUND")
    apexes = sorted(tuple(np.round(t.get_points("xy")[0][:2], 9)) for t in triangles)  # type: ignore[attr-defined]
    assert apexes == sorted(tuple(np.round(at(supply, 1, p), 9)) for p in SUPPLY_FIXED)
    # One path per moving point, through every position.
    paths = on(ents, "LWPOLYLINE", "PATHS")
    assert len(paths) == len(SUPPLY_MOVING)
    for p in SUPPLY_MOVING:
        want = supply.coords[:, [p[0] - 1, p[1] - 1]]
        assert any(
            np.allclose(np.array([v[:2] for v in e.get_points("xy")]), want, atol=1e-9)  # type: ignore[attr-defined]
            for e in paths
        ), f"path of ({p[0]}, {p[1]})"
    # Each point the deck's NAMES block names is labelled at its place, on the names layer.
    names = {e.dxf.text: xy(e.dxf.insert) for e in on(ents, "TEXT", "NAMES")}  # type: ignore[attr-defined]
    assert names.keys() == {p.name for p in supply.model.points}
    assert Counter(e.dxf.layer for e in ents).keys() <= {"LINKS", "GROUND", "PIVOTS", "PATHS", "NAMES"}  # type: ignore[attr-defined]


def test_dxf_of_a_belt_drive_has_tangent_spans_and_wheels(tmp_path: Path) -> None:
    result = mechfem.run_deck(BELT)
    ents = entities(export.export_drawing(result, tmp_path / "belt.dxf", 5, paths=False))
    x = result.coords[4]
    p, q = (x[0], x[1]), (x[3], x[4])
    wheels = on(ents, "CIRCLE", "GEARS")
    assert sorted((round(c.dxf.radius, 9), tuple(np.round(xy(c.dxf.center), 9))) for c in wheels) == sorted(  # type: ignore[attr-defined]
        [(40.0, tuple(np.round(p, 9))), (20.0, tuple(np.round(q, 9)))]
    )
    spans = on(ents, "LINE", "GEARS")
    assert len(spans) == 2
    for s in spans:
        a, b = np.asarray(xy(s.dxf.start)), np.asarray(xy(s.dxf.end))  # type: ignore[attr-defined]
        d = (b - a) / np.linalg.norm(b - a)

        def distance(c: tuple[float, float], a: np.ndarray = a, d: np.ndarray = d) -> float:
            v = np.asarray(c) - a
            return abs(float(d[0] * v[1] - d[1] * v[0]))

        assert distance(p) == pytest.approx(40.0, abs=1e-7)
        assert distance(q) == pytest.approx(20.0, abs=1e-7)
    assert len(on(ents, "ARC", "GEARS")) == 2
    assert not on(ents, "LWPOLYLINE", "PATHS")


def test_dxf_units_are_declared_not_scaled(supply: mechfem.RunResult, tmp_path: Path) -> None:
    path = export.export_drawing(supply, tmp_path / "mm.dxf", units="mm")
    doc = ezdxf.readfile(path)
    assert doc.header["$INSUNITS"] == 4
    lines = on(list(doc.modelspace()), "LINE", "LINKS")
    assert any(same_segment((at(supply, 1, (1, 2)), at(supply, 1, (9, 10))), (e.dxf.start, e.dxf.end)) for e in lines)  # type: ignore[attr-defined]
    with pytest.raises(ValueError, match="unknown length unit 'furlong'"):
        export.export_drawing(supply, tmp_path / "x.dxf", units="furlong")


def test_svg_parses_and_holds_one_element_per_shape(supply: mechfem.RunResult, tmp_path: Path) -> None:
    path = export.export_drawing(supply, tmp_path / "supply.svg", 1)
    root = ET.parse(path).getroot()
    assert root.tag == f"{SVG}svg"
    by_class = Counter(e.get("class", "").split()[0] for e in root.iter() if e.get("class"))
    assert by_class["bar"] == len(SUPPLY_BARS)
    assert by_class["plate"] == 1
    assert by_class["joint"] == len(SUPPLY_FIXED) + len(SUPPLY_MOVING)
    assert by_class["ground"] == len(SUPPLY_FIXED)
    assert by_class["path"] == len(SUPPLY_MOVING)
    # y points up: the SVG's y is the mechanism's -y, and every joint lies inside the viewBox.
    x0, y0, w, h = map(float, root.get("viewBox", "").split())
    centres = {(round(float(c.get("cx", "")), 6), round(-float(c.get("cy", "")), 6)) for c in root.iter(f"{SVG}circle")}
    for p in SUPPLY_FIXED + SUPPLY_MOVING:
        px, py = at(supply, 1, p)
        assert (round(px, 6), round(py, 6)) in centres
        assert x0 <= px <= x0 + w and y0 <= -py <= y0 + h


def test_analysis_exports_with_point_names_and_chosen_paths(tmp_path: Path) -> None:
    m = Mechanism("four <bar> & co")
    a0, b0 = m.fixed("A0", 0.0, 0.0), m.fixed("B0", 4.0, 0.0)
    a, b = m.point("A", 1.0, 0.0), m.point("B", 3.5, 2.5)
    m.bar("crank", a0, a, length=1.0, angle=Driven(start=0.0, name="phi"))
    m.bar("coupler", a, b, length=3.5)
    m.bar("rocker", b0, b, length=3.0, angle=Output("psi"))
    r = m.run(Motion.by(36, 2 * math.pi))
    ents = entities(r.to_dxf(tmp_path / "fourbar.dxf", position=10, paths=["B"]))
    names = {e.dxf.text for e in ents if e.dxftype() == "TEXT"}  # type: ignore[attr-defined]
    assert names == {"A0", "B0", "A", "B"}
    (path,) = on(ents, "LWPOLYLINE", "PATHS")
    assert np.allclose([v[:2] for v in path.get_points("xy")], r.value("B"), atol=1e-9)  # type: ignore[attr-defined]
    lines = on(ents, "LINE", "LINKS")
    crank = ((0.0, 0.0), tuple(r.value("A")[9]))
    assert any(same_segment(crank, (e.dxf.start, e.dxf.end)) for e in lines)  # type: ignore[attr-defined]
    svg = r.to_svg(tmp_path / "fourbar.svg", paths=False)
    root = ET.parse(svg).getroot()
    assert not [e for e in root.iter() if e.get("class") == "path"]
    texts = sorted(t.text or "" for t in root.iter(f"{SVG}text"))
    assert texts == ["A", "A0", "B", "B0"]
    assert root.find(f"{SVG}title").text == "four <bar> & co, position 1"  # type: ignore[union-attr]
    # The module-level function takes an Analysis too.
    assert mechfem.export_drawing(r, tmp_path / "again.svg", 2).is_file()


def test_bad_positions_formats_and_folders_are_clear_errors(supply: mechfem.RunResult, tmp_path: Path) -> None:
    for bad in (0, 74, -1):
        with pytest.raises(ValueError, match="from 1 to 73"):
            export.export_drawing(supply, tmp_path / "x.svg", bad)
    with pytest.raises(ValueError, match="whole number"):
        export.export_drawing(supply, tmp_path / "x.svg", "1")  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="name it .dxf or .svg"):
        export.export_drawing(supply, tmp_path / "x.pdf")
    with pytest.raises(ValueError, match="one of dxf, svg"):
        export.export_drawing(supply, tmp_path / "x.svg", format="png")
    with pytest.raises(FileNotFoundError):
        export.export_drawing(supply, tmp_path / "missing" / "x.svg")
    assert sorted(p.name for p in tmp_path.iterdir()) == []


def test_missing_ezdxf_says_how_to_install_it(
    supply: mechfem.RunResult, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setitem(sys.modules, "ezdxf", None)
    with pytest.raises(ImportError, match=r"pip install 'mechfem\[dxf\]'"):
        export.export_drawing(supply, tmp_path / "x.dxf")
    assert not export.dxf_available()
    assert export.export_drawing(supply, tmp_path / "x.svg").is_file()


def test_files_are_written_whole_and_replace_older_ones(supply: mechfem.RunResult, tmp_path: Path) -> None:
    target = tmp_path / "s.svg"
    target.write_text("old")
    export.export_drawing(supply, target, 3)
    export.export_drawing(supply, tmp_path / "s.dxf", 3)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["s.dxf", "s.svg"]
    assert ET.parse(target).getroot().find(f"{SVG}title").text == "supply, position 3"  # type: ignore[union-attr]


def test_draw_command_writes_both_files_into_the_output_folder(cli: Cli, tmp_path: Path) -> None:
    out = tmp_path / "out"
    proc = cli("draw", SUPPLY, "-o", out, "--position", "2", "--units", "m")
    assert proc.returncode == 0, proc.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == ["out"]
    assert sorted(p.name for p in out.iterdir()) == ["supply_pos2.dxf", "supply_pos2.svg"]
    assert f"wrote {out / 'supply_pos2.dxf'}" in proc.stdout
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        result = mechfem.run_deck(SUPPLY)
    ents = entities(out / "supply_pos2.dxf")
    assert any(
        same_segment((at(result, 2, (1, 2)), at(result, 2, (9, 10))), (e.dxf.start, e.dxf.end))  # type: ignore[attr-defined]
        for e in on(ents, "LINE", "LINKS")
    )
    proc = cli("draw", SUPPLY, "-o", out, "--format", "svg", "--no-paths")
    assert proc.returncode == 0, proc.stderr
    root = ET.parse(out / "supply_pos1.svg").getroot()
    assert not [e for e in root.iter() if e.get("class") == "path"]
    assert not (out / "supply_pos1.dxf").exists()


@pytest.mark.parametrize(
    ("args", "status", "words"),
    [
        (["--position", "74"], 1, "the run has 73 positions, so --position must be from 1 to 73"),
        (["--position", "0"], 2, "positions are numbered from 1"),
        (["--format", "pdf"], 2, "give dxf, svg or dxf,svg"),
        (["--units", "furlong"], 2, "invalid choice"),
    ],
)
def test_draw_command_refuses_bad_arguments_without_a_traceback(
    cli: Cli, tmp_path: Path, args: list[str], status: int, words: str
) -> None:
    proc = cli("draw", SUPPLY, "-o", tmp_path, *args)
    assert proc.returncode == status
    assert words in proc.stderr
    assert "Traceback" not in proc.stderr
    assert list(tmp_path.iterdir()) == []
