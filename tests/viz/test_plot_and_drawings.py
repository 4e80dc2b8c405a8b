"""What a designer sees of a run as a picture: ``RunResult.plot`` as a figure for scripts and notebooks, the
paths drawn over the mechanism, point names in the drawings, and ``mechfem draw`` without ezdxf."""

from __future__ import annotations

import math
import subprocess
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt
import numpy as np
import pytest
from matplotlib.figure import Figure

from conftest import SUPPLY
from mechfem import Driven, Mechanism, Motion, Output
from mechfem.viz import export

SVG = "{http://www.w3.org/2000/svg}"


def fourbar() -> Mechanism:
    m = Mechanism("crank-rocker")
    A0 = m.fixed("A0", 0.0, 0.0)
    B0 = m.fixed("B0", 3.2, 0.0)
    A = m.point("A", 0.0, 1.0)
    B = m.point("B", 3.0, 2.2)
    C = m.point("C", 1.5, 2.8)
    m.bar("crank", A0, A, length=1.0, angle=Driven(name="phi"))
    m.ternary2("coupler", A, B, C, length=3.0, u=1.8 * math.cos(0.6), v=1.8 * math.sin(0.6))
    m.bar("rocker", B0, B, length=2.5, angle=Output("psi"))
    return m


@pytest.fixture(scope="module")
def run() -> object:
    return fourbar().run(Motion.by(36, 2 * math.pi))


def test_plot_returns_a_figure_pyplot_shows(run: object) -> None:
    plt.close("all")
    fig = run.plot("psi")  # type: ignore[attr-defined]
    assert isinstance(fig, Figure)
    # Registered with pyplot, so that plt.show() in a script shows it.
    assert [plt.figure(n) for n in plt.get_fignums()] == [fig]
    plt.close("all")


def test_plot_position_draws_the_mechanism_there_and_marks_it(run: object) -> None:
    fig = run.plot("psi", position=10)  # type: ignore[attr-defined]
    mech, chart = fig.axes[0], fig.axes[1]
    assert mech.get_title() == "crank-rocker: position 10 and paths"
    phi = run.input("phi")  # type: ignore[attr-defined]
    marks = [ln for ln in chart.get_lines() if ln.get_linestyle() == ":"]
    assert len(marks) == 1 and float(np.asarray(marks[0].get_xdata())[0]) == pytest.approx(phi[9])
    # The crank pin A is labelled where it is at position 10.
    a = run.value("A")[9]  # type: ignore[attr-defined]
    (label,) = [t for t in mech.texts if t.get_text() == "A"]
    assert label.xy == pytest.approx((a[0], a[1]))
    with pytest.raises(ValueError, match="from 1 to 37"):
        run.plot(position=38)  # type: ignore[attr-defined]
    plt.close("all")


def test_plot_into_given_axes(run: object) -> None:
    fig, (left, right) = plt.subplots(1, 2)
    assert run.plot(ax=left) is fig  # type: ignore[attr-defined]
    assert run.plot("psi", ax=right) is fig  # type: ignore[attr-defined]
    assert len(fig.axes) == 2
    (psi,) = [ln for ln in right.get_lines() if ln.get_linestyle() != ":"]
    assert np.allclose(psi.get_ydata(), run.value("psi"))  # type: ignore[attr-defined]
    paths = [ln for ln in left.get_lines() if ln.get_label() == "path of C"]
    assert len(paths) == 1
    plt.close("all")


def test_paths_are_drawn_over_the_mechanism(run: object, tmp_path: Path) -> None:
    fig = run.plot()  # type: ignore[attr-defined]
    mech = fig.axes[0]
    shapes = [a.get_zorder() for a in (*mech.patches, *mech.collections)]
    paths = [ln.get_zorder() for ln in mech.get_lines() if str(ln.get_label()).startswith("path of")]
    assert paths and shapes and min(paths) > max(shapes)
    plt.close("all")
    svg = ET.parse(run.to_svg(tmp_path / "m.svg")).getroot()  # type: ignore[attr-defined]
    groups = [g.get("id") for g in svg.findall(f"{SVG}g")]
    assert groups.index("paths") > groups.index("mechanism")


def test_deck_drawing_labels_the_points_the_deck_names(tmp_path: Path) -> None:
    import mechfem

    named = tmp_path / "named.mec"
    fourbar().save_deck(named)
    result = mechfem.run_deck(named)
    d = export.result_drawing(result, 1)
    assert {lab.text for lab in d.labels} >= {"A0", "B0", "A", "B", "C"}
    unnamed = export.result_drawing(mechfem.run_deck(SUPPLY), 1)
    assert all(not lab.text.startswith("(") for lab in unnamed.labels)


def test_draw_without_ezdxf_writes_the_svg_and_says_how_to_get_dxf(tmp_path: Path) -> None:
    out = tmp_path / "out"
    code = (
        "import sys; sys.modules['ezdxf'] = None; from mechfem.cli.command import main; "
        f"sys.exit(main(['draw', {str(SUPPLY)!r}, '-o', {str(out)!r}]))"
    )
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert proc.returncode == 0, proc.stderr
    assert sorted(p.name for p in out.iterdir()) == ["supply_pos1.svg"]
    assert "pip install 'mechfem[dxf]'" in proc.stdout + proc.stderr
    asked = subprocess.run(
        [sys.executable, "-c", code.replace("'-o'", "'--format', 'dxf', '-o'")],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert asked.returncode != 0 and "ezdxf" in asked.stderr


def test_gif_stores_only_what_changed_and_shows_every_frame_whole() -> None:
    import io

    from PIL import Image

    from mechfem.viz.animation import GifStream

    rng = np.random.default_rng(1)
    first = (rng.integers(0, 4, (120, 160, 3)) * 60).astype(np.uint8)
    second = first.copy()
    second[50:55, 70:75] = 255
    out = io.BytesIO()
    gif = GifStream(out)
    gif.add(Image.fromarray(first))
    one = out.tell()
    gif.add(Image.fromarray(second))
    gif.add(Image.fromarray(second))
    gif.close()
    assert out.tell() - one < one / 10
    im = Image.open(io.BytesIO(out.getvalue()))
    assert im.n_frames == 3
    for k, want in enumerate([first, second, second]):
        im.seek(k)
        assert np.array_equal(np.asarray(im.convert("RGB")), want)


def test_animation_of_a_tall_mechanism_is_wide_enough_for_its_title(tmp_path: Path) -> None:
    import warnings

    from PIL import Image

    import mechfem
    from mechfem.viz.animation import _title, title_width, write_animation

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        result = mechfem.run_deck(SUPPLY)
    storage = result.storage.replace(animate="tall")
    info = write_animation(result.replace(storage=storage), tmp_path, max_frames=4, mp4=False)
    im = Image.open(info.files[0])
    longest = max((_title(result, "tall", int(k)) for k in info.plan.frames), key=len)
    assert im.height > 2 * im.width and im.width >= title_width(longest) + 16


def test_report_table_lists_buffers_by_number_whatever_the_storage_order(tmp_path: Path) -> None:
    import warnings

    import mechfem
    from conftest import ROOT
    from mechfem.report.html import report_data

    text = (ROOT / "examples" / "fourbar" / "fourbar.mec").read_text()
    lines = text.splitlines()
    first = next(i for i, ln in enumerate(lines) if ln.startswith("BUFINP"))
    last = next(i for i, ln in enumerate(lines) if ln.startswith("BUFDET"))
    lines[first : last + 1] = reversed(lines[first : last + 1])
    deck = tmp_path / "reversed.mec"
    deck.write_text("\n".join(lines) + "\n")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        data = report_data(mechfem.run_deck(deck))
    numbers = [int(key[1:]) for key in data["table"]]
    assert len(numbers) > 5 and numbers == sorted(numbers)


def test_dynamic_reports_chart_the_drive_once_and_a_simulation_against_time() -> None:
    import warnings

    import mechfem
    from conftest import ROOT
    from mechfem.report.html import report_data

    supply = ROOT / "examples" / "supply"
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        dyn = report_data(mechfem.run_deck(supply / "supply_dyn.mec"))
        sim = report_data(mechfem.run_deck(supply / "supply_sim.mec"))
    titles = [c["title"] for c in dyn["cards"]]
    # The deck's first picture charts the drive torque (BUFDRV 110); the report does not add a second chart of it.
    assert not any(t.startswith("drive force or torque") for t in titles)
    assert any(t.startswith("energies against") for t in titles)
    generated = [c for c in sim["cards"] if c["picture"] is None and c["title"].startswith(("drive", "energies"))]
    assert generated and all(c["title"].endswith("against time") for c in generated)
