"""Pictures, the mechanism drawing and the animation: python/mechfem/viz/plots.py, drawing.py, animation.py."""

from __future__ import annotations

import io
import math
import shutil
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest
from matplotlib.axes import Axes
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure
from PIL import Image

import mechfem
from bare_examples import bare
from conftest import ROOT, SUPPLY, Cli
from mechfem.output.media import Media
from mechfem.results.result import RunResult
from mechfem.viz.animation import MAX_FRAMES, GifStream, frame_plan, write_animation
from mechfem.viz.drawing import MechanismDrawing
from mechfem.viz.plots import HODOGRAPH_ARROW_SIZE, HODOGRAPH_ARROWS, hodograph, picture_figure, write_pictures

EVERY_ELEMENT = ROOT / "tests" / "decks" / "every_element.mec"
ALL_TYPES = {"BIN", "HLF", "TR1", "TR2", "GR1", "GR2", "RK1", "RK2", "BLT", "CRD"}
SUPPLY_PICTURES = ["supply_pic1.png", "supply_pic1.svg", "supply_pic2.png", "supply_pic2.svg"]


@pytest.fixture(scope="module")
def supply() -> RunResult:
    return mechfem.run_deck(bare(SUPPLY))


@pytest.fixture(scope="module")
def every_element() -> RunResult:
    return mechfem.run_deck(EVERY_ELEMENT)


def supply_variant(tmp_path: Path, name: str, replace: dict[str, str]) -> Path:
    """A copy of the supply deck with some text replaced."""
    text = bare(SUPPLY).read_text()
    for old, new in replace.items():
        assert old in text
        text = text.replace(old, new)
    deck = tmp_path / f"{name}.mec"
    deck.write_text(text)
    return deck


def test_supply_pictures_are_written_as_png_and_svg(supply: RunResult, tmp_path: Path) -> None:
    written = write_pictures(supply, tmp_path)
    assert [p.name for p in written] == SUPPLY_PICTURES
    # Written under temporary names and renamed: nothing else is left in the folder.
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted(SUPPLY_PICTURES)
    for name in SUPPLY_PICTURES:
        path = tmp_path / name
        assert path.stat().st_size > 20_000, name
        if name.endswith(".png"):
            with Image.open(path) as im:
                assert im.format == "PNG"
                width, height = im.size
                assert width >= 900 and height >= 550, (name, im.size)
        else:
            root = ET.parse(path).getroot()
            assert root.tag.endswith("svg")


def test_function_picture_has_one_panel_per_kind_each_with_its_unit(supply: RunResult) -> None:
    # Picture 2 plots the output angle and its first- and second-order transfer functions against the input:
    # three kinds of quantity, three panels stacked over one shared x axis.
    fig = picture_figure(supply, 1)
    assert isinstance(fig, Figure)
    assert [ax.get_ylabel() for ax in fig.axes] == [
        "ANGB(8) [rad]",
        "dANGB(8)/dinput1 [-]",
        "d2ANGB(8)/dinput1^2 [1/rad]",
    ]
    # Only the bottom panel names the shared x axis: the input, row 12 = ANGB(1), an angle.
    assert [ax.get_xlabel() for ax in fig.axes] == ["", "", "ANGB(1) [rad]"]
    top, middle, bottom = fig.axes
    assert top.get_shared_x_axes().joined(top, bottom) and middle.get_shared_x_axes().joined(middle, bottom)
    for ax, number in zip(fig.axes, (100, 101, 102), strict=True):
        assert np.array_equal(ax.lines[0].get_ydata(), supply.buffers[number], equal_nan=True)
    suptitle = fig.get_suptitle()
    assert suptitle == "supply, picture 2: ANGB(8), dANGB(8)/dinput1, d2ANGB(8)/dinput1^2 against ANGB(1)"


def test_functions_of_one_kind_and_unit_share_a_panel_with_a_legend(tmp_path: Path) -> None:
    # Two angles (the output and the input) against time: one panel, a legend, the unit once on the axis.
    deck = supply_variant(
        tmp_path,
        "angles",
        {
            "  PRINTBUF\n": "  BUFTIME 98\n  PRINTBUF\n",
            "    PLOTFUNC 99 100\n    PLOTFUNC 99 101\n    PLOTFUNC 99 102\n": (
                "    PLOTFUNC 98 100\n    PLOTFUNC 98 99\n"
            ),
        },
    )
    fig = picture_figure(mechfem.run_deck(deck), 1)
    assert isinstance(fig, Figure)
    (ax,) = fig.axes
    assert ax.get_xlabel() == "time [s]"
    assert ax.get_ylabel() == "ANGB(8), ANGB(1) [rad]"
    legend = ax.get_legend()
    assert legend is not None
    assert [t.get_text() for t in legend.get_texts()] == ["ANGB(8) [rad]", "ANGB(1) [rad]"]


def test_a_beginpic_title_is_the_picture_title(every_element: RunResult) -> None:
    fig = picture_figure(every_element, 0)
    assert isinstance(fig, Figure)
    assert fig.get_suptitle() == "Plate point on W4"


def test_hodograph_arrows_are_the_first_order_vectors_tangent_to_the_path(supply: RunResult) -> None:
    h = hodograph(supply, 13, 14)
    assert 12 <= len(h.at) <= HODOGRAPH_ARROWS
    alpha = supply.buffers[99]
    for n, k in enumerate(h.at):
        if k == 0 or k == supply.positions - 1:
            continue
        # Central differences of the path along the input: the same vector, to O(step^2).
        da = alpha[k + 1] - alpha[k - 1]
        fd = np.array([h.x[k + 1] - h.x[k - 1], h.y[k + 1] - h.y[k - 1]]) / da
        v = np.array([h.vx[n], h.vy[n]])
        cos = float(fd @ v / (np.linalg.norm(fd) * np.linalg.norm(v)))
        assert cos > 0.999, (k, cos)
        assert np.linalg.norm(v) == pytest.approx(np.linalg.norm(fd), rel=0.02)
    # The longest arrow is a fixed fraction of the size of the path.
    size = math.hypot(np.ptp(h.x), np.ptp(h.y))
    longest = float(np.max(np.hypot(h.vx, h.vy))) * h.scale
    assert longest == pytest.approx(HODOGRAPH_ARROW_SIZE * size)


def test_hodograph_picture_draws_path_arrows_and_mechanism(supply: RunResult) -> None:
    fig = picture_figure(supply, 0)
    assert isinstance(fig, Figure)
    # The path is small against the whole (tall) mechanism: a second panel shows it enlarged.
    assert len(fig.axes) == 2
    whole, zoom = fig.axes
    for ax in (whole, zoom):
        assert len(ax.collections) >= 1  # arrows (quiver) and ground hatching
        assert any(line.get_label() == "path of (x13, x14)" for line in ax.lines)
        assert (ax.get_xlabel(), ax.get_ylabel()) == ("x13", "x14")
        assert len(ax.patches) >= 9  # joints, fixed pivots
    assert whole.get_ylim()[0] < -6.5  # the whole mechanism, down to its lowest pivot
    assert zoom.get_ylim()[1] < 1.5


def test_plotcurv_has_equal_axis_scales(tmp_path: Path) -> None:
    # The coupler curve is about four times as wide as it is high: unequal scales would show.
    deck = supply_variant(
        tmp_path,
        "curve",
        {
            "  PRINTBUF\n": "  BUFX0 13 113\n  BUFX0 14 114\n  PRINTBUF\n",
            "    PLOTHODO 13 14\n": "    PLOTCURV 113 114\n",
        },
    )
    result = mechfem.run_deck(deck)
    fig = picture_figure(result, 0)
    assert isinstance(fig, Figure)
    FigureCanvasAgg(fig).draw()
    (ax,) = fig.axes
    assert isinstance(ax, Axes)
    origin = ax.transData.transform((0.0, 0.0))
    per_x = ax.transData.transform((1.0, 0.0)) - origin
    per_y = ax.transData.transform((0.0, 1.0)) - origin
    assert abs(per_x[0]) == pytest.approx(abs(per_y[1]), rel=1e-6)
    assert ax.get_xlabel() == "x13" and ax.get_ylabel() == "x14"


def test_every_element_type_is_drawn(every_element: RunResult, tmp_path: Path) -> None:
    r = every_element
    assert {e.type for e in r.model.elements} == ALL_TYPES
    drawing = MechanismDrawing(r.model, r.coords)
    assert drawing.notes == []
    first = drawing.shapes(r.coords[0])
    roles = [s.role for s in first]
    # Shapes keep their kinds and roles at every position, so renderers only move them.
    for k in range(r.positions):
        assert [(s.kind, s.role) for s in drawing.shapes(r.coords[k])] == [(s.kind, s.role) for s in first]
    for s in first:
        assert all(math.isfinite(v) for v in s.data), s
    # Four fixed pivots with ground hatching; four wheels (the belt's, the gears' and the racks' wheels shared).
    assert roles.count("ground") == 4
    assert roles.count("wheel") == 4
    assert roles.count("plate") == 2  # TR1, TR2
    assert roles.count("belt") == 4  # two spans, two wraps
    assert roles.count("rack") == 4  # RK1, RK2: teeth and back
    assert roles.count("bar") == 1
    written = write_pictures(r, tmp_path)
    assert len(written) == 6
    info = write_animation(r, tmp_path, max_frames=8, mp4=False)
    assert [p.name for p in info.files] == ["every_element.gif"]
    with Image.open(tmp_path / "every_element.gif") as im:
        assert im.n_frames == 8


def test_gear_wheel_radii_come_from_the_ratio_and_the_centre_distance(every_element: RunResult) -> None:
    r = every_element
    drawing = MechanismDrawing(r.model, r.coords)
    radii = sorted(round(s.data[2], 9) for s in drawing.shapes(r.coords[0]) if s.role == "wheel")
    # Pinion 0.5 (RK2, belt), W2 0.3 (belt, GR2, RK1), W3 0.5 (GR2, GR1), W4 0.3 from GR1's i = -5/3 and |GH| = 0.8.
    assert radii == [0.3, 0.3, 0.5, 0.5]


def test_belt_spans_are_tangent_to_both_wheels(every_element: RunResult) -> None:
    r = every_element
    drawing = MechanismDrawing(r.model, r.coords)
    x = r.coords[r.positions // 2]
    p, f = (x[0], x[1]), (x[8], x[9])
    spans = [s for s in drawing.shapes(x) if s.role == "belt" and s.kind == "line"]
    assert len(spans) == 2
    for s in spans:
        a, b = np.array(s.data[:2]), np.array(s.data[2:])
        d = (b - a) / np.linalg.norm(b - a)

        def distance(c: tuple[float, float], a: np.ndarray = a, d: np.ndarray = d) -> float:
            w = np.array(c) - a
            return abs(w[0] * d[1] - w[1] * d[0])

        assert distance(p) == pytest.approx(0.5)
        assert distance(f) == pytest.approx(0.3)


@pytest.mark.parametrize(
    "deck",
    sorted((ROOT / "examples").glob("*/*.mec")) + sorted((ROOT / "tests" / "decks").glob("*.mec")),
    ids=lambda p: f"{p.parent.name}/{p.name}",
)
@pytest.mark.filterwarnings("ignore::mechfem.IncompleteRunWarning")  # the motion stops on purpose
def test_every_deck_can_be_drawn(deck: Path) -> None:
    try:
        r = mechfem.run_deck(deck)
    except mechfem.MechfemError as e:
        pytest.skip(f"the deck does not run, nothing to draw: {type(e).__name__}")
    drawing = MechanismDrawing(r.model, r.coords)
    kinds = None
    for k in np.unique(np.linspace(0, r.positions - 1, 12).round().astype(int)):
        shapes = drawing.shapes(r.coords[k])
        assert kinds is None or [(s.kind, s.role) for s in shapes] == kinds
        kinds = [(s.kind, s.role) for s in shapes]
    x0, x1, y0, y1 = drawing.bounds()
    assert x0 < x1 and y0 < y1


def test_slider_is_drawn_as_a_block_on_a_rail() -> None:
    deck = ROOT / "examples" / "slider_crank" / "slider_crank.mec"
    if not deck.exists():
        pytest.skip("examples/slider_crank is not there")
    r = mechfem.run_deck(deck)
    roles = [s.role for s in MechanismDrawing(r.model, r.coords).shapes(r.coords[0])]
    assert roles.count("slider") == 1
    assert roles.count("rail") == 1  # the guide keeps its direction and starts at a fixed point


def test_animation_has_one_frame_per_position(supply: RunResult, tmp_path: Path) -> None:
    info = write_animation(supply, tmp_path, mp4=False)
    assert info.files == [tmp_path / "film.gif"]
    assert not info.plan.subsampled
    assert sorted(p.name for p in tmp_path.iterdir()) == ["film.gif"]
    with Image.open(tmp_path / "film.gif") as im:
        assert im.n_frames == supply.positions == 73
        assert im.info["duration"] == 50
        assert im.info["loop"] == 0
        width, height = im.size
        assert width % 2 == 0 and height % 2 == 0
        assert max(width, height) == 720


def test_a_long_run_is_subsampled_to_at_most_120_frames(tmp_path: Path) -> None:
    deck = supply_variant(tmp_path, "long", {"TSTEPE 72": "TSTEPE 19999"})
    result = mechfem.run_deck(deck)
    assert result.positions == 20000
    info = write_animation(result, tmp_path, mp4=False)
    assert info.plan.subsampled
    assert len(info.plan.frames) == MAX_FRAMES
    with Image.open(tmp_path / "film.gif") as im:
        assert im.n_frames == MAX_FRAMES
    lines = Media(result, tmp_path).print_lines()
    assert any("120 frames for 20000 positions: subsampled" in line for line in lines)


def test_frame_plan_spreads_frames_evenly_and_keeps_the_ends() -> None:
    assert list(frame_plan(5).frames) == [0, 1, 2, 3, 4]
    plan = frame_plan(20000)
    assert len(plan.frames) == 120 and plan.frames[0] == 0 and plan.frames[-1] == 19999
    assert np.all(np.diff(plan.frames) > 0)
    steps = np.diff(plan.frames)
    assert steps.max() - steps.min() <= 1
    assert len(frame_plan(1000, max_frames=50).frames) == 50


def test_gif_frames_are_written_as_they_are_made() -> None:
    out = io.BytesIO()
    gif = GifStream(out)
    sizes = []
    for k in range(5):
        gif.add(Image.new("RGB", (40, 30), (40 * k, 100, 255 - 40 * k)))
        sizes.append(len(out.getvalue()))
    gif.close()
    assert all(b > a for a, b in zip(sizes, sizes[1:], strict=False))
    out.seek(0)
    with Image.open(out) as im:
        assert im.n_frames == 5
        im.seek(4)
        assert im.convert("RGB").getpixel((5, 5)) == (160, 100, 95)


@pytest.mark.skipif(shutil.which("ffmpeg") is None, reason="ffmpeg is not on the PATH: no MP4 is written")
def test_mp4_is_written_when_ffmpeg_is_there(supply: RunResult, tmp_path: Path) -> None:
    info = write_animation(supply, tmp_path, max_frames=20)
    assert [p.name for p in info.files] == ["film.gif", "film.mp4"]
    assert (tmp_path / "film.mp4").stat().st_size > 1000


def test_max_frames_option_limits_the_animation(cli: Cli, tmp_path: Path) -> None:
    proc = cli("run", SUPPLY, "-o", tmp_path, "--max-frames", "10")
    assert proc.returncode == 0, proc.stderr
    assert "film.gif (10 frames for 73 positions: subsampled" in proc.stdout
    with Image.open(tmp_path / "film.gif") as im:
        assert im.n_frames == 10
    assert "10 frames for 73 positions" in (tmp_path / "supply.prt").read_text()
    for wrong in ("1", "201", "ten"):
        proc = cli("run", SUPPLY, "-o", tmp_path, "--max-frames", wrong)
        assert proc.returncode == 2 and "--max-frames" in proc.stderr
