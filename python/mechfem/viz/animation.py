"""The deck's animation (``ANIMATE name``): the mechanism moving through its positions.

``name.gif`` is always written; ``name.mp4`` too when ``ffmpeg`` is on the PATH. Each frame shows the
mechanism, the paths of the PLOTHODO points (faint for the whole motion, strong up to the frame) and their
first-order velocity arrows, with fixed axis limits that hold every position. A run with more positions than
:data:`MAX_FRAMES` is subsampled evenly (the first and last positions are always shown).

Frames are rendered one at a time and written to the files as they are made, so memory does not grow with
the number of frames. Both files are written under temporary names and renamed when complete.
"""

from __future__ import annotations

import math
import os
import secrets
import shutil
import subprocess
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import BinaryIO

import numpy as np
import numpy.typing as npt

from mechfem._util.atomic import atomic_path
from mechfem.results.labels import buffer_labels, display_unit
from mechfem.results.result import RunResult
from mechfem.viz.drawing import MechanismDrawing
from mechfem.viz.mpl_drawing import MplMechanism
from mechfem.viz.plots import ARROW_COLOUR, PATH_COLOUR, fit_equal, hodograph

IntArray = npt.NDArray[np.int64]

#: Most frames an animation has; longer runs are subsampled.
MAX_FRAMES = 120
#: Frames per second.
FPS = 20
#: The longer side of a frame, in pixels.
FRAME_SIZE = 720


@dataclass(frozen=True)
class FramePlan:
    """Which positions become frames."""

    positions: int
    """Positions computed."""
    frames: IntArray
    """The 0-based positions shown, in order."""

    @property
    def subsampled(self) -> bool:
        return len(self.frames) < self.positions

    def describe(self) -> str:
        """``73 frames, one per position`` or how the positions were subsampled."""
        n = len(self.frames)
        if not self.subsampled:
            return f"{n} frames, one per position" if n != 1 else "1 frame"
        every = (self.positions - 1) / max(n - 1, 1)
        return f"{n} frames for {self.positions} positions: subsampled, about one position in {every:.3g} is shown"


def frame_plan(positions: int, max_frames: int = MAX_FRAMES) -> FramePlan:
    """Evenly spread frames over ``positions`` positions, at most ``max_frames`` (>= 2), first and last included."""
    if positions <= max_frames:
        return FramePlan(positions, np.arange(positions, dtype=np.int64))
    frames = np.unique(np.linspace(0, positions - 1, max(max_frames, 2)).round().astype(np.int64))
    return FramePlan(positions, frames)


def ffmpeg() -> str | None:
    """The ffmpeg program, or None when it is not on the PATH."""
    return shutil.which("ffmpeg")


def animation_files(result: RunResult, outdir: Path, mp4: bool | None = None) -> list[Path]:
    """The files ``ANIMATE name`` makes: ``name.gif``, and ``name.mp4`` with ffmpeg (``mp4=None``: if on the PATH)."""
    name = result.storage.animate
    if not name:
        return []
    with_mp4 = ffmpeg() is not None if mp4 is None else mp4
    return [outdir / f"{name}.gif"] + ([outdir / f"{name}.mp4"] if with_mp4 else [])


@dataclass
class AnimationInfo:
    """What :func:`write_animation` wrote."""

    plan: FramePlan
    files: list[Path] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)
    """Anything that did not go as asked (e.g. ffmpeg failing), one sentence each."""


PALETTE_FRAMES = 5
"""Frames, spread over the animation, whose colours make the GIF's palette."""


def spread(frames: npt.NDArray[np.intp], count: int) -> list[int]:
    """Up to ``count`` of ``frames``, evenly spread from the first to the last."""
    picks = np.unique(np.linspace(0, len(frames) - 1, min(count, len(frames))).round().astype(int))
    return [int(frames[i]) for i in picks]


def palette_of(frames: list[npt.NDArray[np.uint8]]) -> object:
    """A 255-colour palette (a PIL image in mode P) for every frame: an adaptive palette of the given frames
    side by side. Mapping a frame onto a fixed palette is some thirty times faster than finding one for
    each frame, and the frames of one animation share their colours (the same styles, antialiased on the
    same background)."""
    from PIL import Image

    montage = Image.fromarray(np.concatenate(frames, axis=1))
    return montage.quantize(colors=255, method=Image.Quantize.MEDIANCUT, dither=Image.Dither.NONE)


class GifStream:
    """Writes an animated GIF frame by frame: only the current frame is ever held in memory.

    Frames are mapped onto ``palette`` when one is set (see :func:`palette_of`), otherwise each gets an
    adaptive palette of its own.
    """

    def __init__(self, f: BinaryIO, fps: int = FPS) -> None:
        self.f = f
        self.duration = max(20, round(1000 / fps))
        self.frames = 0
        self.palette: object | None = None
        self.previous: npt.NDArray[np.uint8] | None = None

    def add(self, rgb: object) -> None:
        from PIL import GifImagePlugin, Image

        assert isinstance(rgb, Image.Image)
        rgb = rgb.convert("RGB")
        # Only the rectangle that differs from the frame before is stored (the rest stays on screen): the
        # frame, its fixed parts and the faint whole paths are written once.
        pixels = np.asarray(rgb)
        box = (0, 0, rgb.width, rgb.height)
        if self.previous is not None and self.previous.shape == pixels.shape:
            changed = np.any(pixels != self.previous, axis=2)
            rows, cols = np.flatnonzero(changed.any(axis=1)), np.flatnonzero(changed.any(axis=0))
            box = (int(cols[0]), int(rows[0]), int(cols[-1]) + 1, int(rows[-1]) + 1) if rows.size else (0, 0, 1, 1)
            rgb = rgb.crop(box)
        self.previous = pixels.copy()
        if self.palette is not None:
            assert isinstance(self.palette, Image.Image)
            frame = rgb.convert("RGB").quantize(palette=self.palette, dither=Image.Dither.NONE)
        else:
            frame = rgb.convert("RGB").quantize(colors=255, method=Image.Quantize.MEDIANCUT, dither=Image.Dither.NONE)
        if self.frames == 0:
            header, _ = GifImagePlugin.getheader(frame, info={"loop": 0, "duration": self.duration})
            self.f.write(b"".join(header))
        chunks = GifImagePlugin.getdata(frame, offset=box[:2], duration=self.duration, include_color_table=True)
        for chunk in chunks:
            self.f.write(chunk)
        self.frames += 1

    def close(self) -> None:
        self.f.write(b";")


class _Mp4Pipe:
    """Raw RGB frames piped into ffmpeg, which encodes them to MP4 (H.264 when it has it)."""

    def __init__(self, program: str, path: Path, width: int, height: int, fps: int) -> None:
        encoders = subprocess.run(
            [program, "-hide_banner", "-encoders"], capture_output=True, text=True, check=False
        ).stdout
        codec = ["-c:v", "libx264", "-pix_fmt", "yuv420p"] if "libx264" in encoders else ["-c:v", "mpeg4", "-q:v", "3"]
        args = [program, "-y", "-loglevel", "error", "-f", "rawvideo", "-pix_fmt", "rgb24"]
        args += ["-s", f"{width}x{height}", "-r", str(fps), "-i", "-", "-an", *codec, str(path)]
        self.proc = subprocess.Popen(args, stdin=subprocess.PIPE, stderr=subprocess.PIPE)

    def add(self, rgb: npt.NDArray[np.uint8]) -> None:
        assert self.proc.stdin is not None
        self.proc.stdin.write(np.ascontiguousarray(rgb).tobytes())

    def close(self) -> str | None:
        """Waits for ffmpeg; returns its complaint when it failed."""
        assert self.proc.stdin is not None
        self.proc.stdin.close()
        err = self.proc.stderr.read().decode(errors="replace") if self.proc.stderr else ""
        if self.proc.wait() != 0:
            return err.strip().splitlines()[-1] if err.strip() else f"exit status {self.proc.returncode}"
        return None


def title_width(text: str) -> int:
    """The width in pixels of ``text`` as the animation's title draws it (10 points at 100 dpi)."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    fig = Figure(figsize=(2.0, 1.0), dpi=100)
    canvas = FigureCanvasAgg(fig)
    t = fig.suptitle(text, fontsize=10)
    return math.ceil(t.get_window_extent(canvas.get_renderer()).width)


def _title(result: RunResult, name: str, k: int) -> str:
    text = f"{name}: position {k + 1} of {result.positions}"
    inputs = [b for b in result.storage.buffers if b.keyword == "BUFINP"]
    labels = buffer_labels(result) if inputs else {}
    shown = []
    for b in inputs[:2]:
        value = float(result.buffers[b.number][k])
        lab = labels[b.number]
        shown.append(f"{lab.name} = {value:.6g} {lab.unit}".rstrip())
    if not shown and result.time.size:
        shown.append(f"time = {float(result.time[k]):.6g} {display_unit(result, 's')}")
    return text + ("  (" + ", ".join(shown) + ")" if shown else "")


MAX_PATH_POINTS = 20_000
"""Most points of a path drawn in a frame: far more than a frame has pixels along the path, and few enough
that a run of a million positions draws its 200 frames in seconds, not minutes."""


def path_sample(positions: int) -> npt.NDArray[np.intp]:
    """The positions whose points draw the paths: all of them, or every s-th and the last."""
    stride = max(1, -(-positions // MAX_PATH_POINTS))
    sample = np.arange(0, positions, stride)
    if positions and sample[-1] != positions - 1:
        sample = np.append(sample, positions - 1)
    return sample


def write_animation(
    result: RunResult,
    outdir: Path,
    max_frames: int = MAX_FRAMES,
    mp4: bool | None = None,
    on_frame: Callable[[int, int], object] | None = None,
) -> AnimationInfo:
    """Writes the deck's animation into ``outdir``; ``mp4=None`` writes MP4 when ffmpeg is on the PATH.

    ``on_frame(done, total)`` is called after every frame.
    """
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure
    from PIL import Image

    plan = frame_plan(result.positions, max_frames)
    info = AnimationInfo(plan)
    name = result.storage.animate
    if not name:
        return info
    outdir.mkdir(parents=True, exist_ok=True)
    drawing = MechanismDrawing(result.model, result.coords)
    hodos = [p for pic in result.storage.pictures for p in pic.plots if p.keyword == "PLOTHODO"]
    hodos = list({(p.a, p.b): p for p in hodos}.values())
    paths = [hodograph(result, p.a, p.b) for p in hodos]

    # Fixed limits: every frame's shapes and the whole paths, with a margin.
    x0, x1, y0, y1 = drawing.bounds(plan.frames)
    for h in paths:
        ok = np.isfinite(h.x) & np.isfinite(h.y)
        if ok.any():
            x0, x1 = min(x0, float(h.x[ok].min())), max(x1, float(h.x[ok].max()))
            y0, y1 = min(y0, float(h.y[ok].min())), max(y1, float(h.y[ok].max()))
    pad = 0.05 * max(x1 - x0, y1 - y0, 1e-12)
    x0, x1, y0, y1 = x0 - pad, x1 + pad, y0 - pad, y1 + pad
    # Frame size in pixels: the longer side FRAME_SIZE, both even (video encoders need that), room for the title.
    aspect = (y1 - y0) / (x1 - x0)
    title_px = 36
    titles = [_title(result, name, int(k)) for k in plan.frames]
    if aspect >= 1:
        height = FRAME_SIZE
        # A tall mechanism gets a narrow frame, but never narrower than its longest title.
        width = max(320, round((height - title_px) / aspect), title_width(max(titles, key=len)) + 16)
    else:
        width = FRAME_SIZE
        height = max(240, round(width * aspect) + title_px)
    width, height = width + width % 2, height + height % 2
    dpi = 100
    fig = Figure(figsize=(width / dpi, height / dpi), dpi=dpi)
    canvas = FigureCanvasAgg(fig)
    ax = fig.add_axes((0.0, 0.0, 1.0, 1.0 - title_px / height))
    ax.set_axis_off()
    fit_equal(ax, (x0, x1, y0, y1))
    first = int(plan.frames[0])
    mech = MplMechanism(ax, drawing, result.coords[first])
    traces = []
    sample = path_sample(result.positions)
    for h in paths:
        ax.plot(h.x[sample], h.y[sample], color=PATH_COLOUR, lw=0.8, alpha=0.25, zorder=4)
        (trace,) = ax.plot([], [], color=PATH_COLOUR, lw=1.6, zorder=4.5)
        (arrow,) = ax.plot([], [], color=ARROW_COLOUR, lw=2.0, zorder=4.6)
        (head,) = ax.plot([], [], "o", color=PATH_COLOUR, ms=4, zorder=4.7)
        traces.append((h, trace, arrow, head))
    title = fig.suptitle("", fontsize=10, y=1.0 - 6 / height, va="top")
    # What moves is drawn anew in each frame over a copy of what does not (the axes and the faint whole
    # paths, which may have many points): rendering those once is most of the time of a frame.
    moving = sorted(
        [*mech.artists, *(a for _, trace, arrow, head in traces for a in (trace, arrow, head))],
        key=lambda a: a.get_zorder(),
    )
    for a in [*moving, title]:
        a.set_animated(True)
    canvas.draw()
    background = canvas.copy_from_bbox(fig.bbox)

    def draw(k: int) -> npt.NDArray[np.uint8]:
        """Frame ``k`` as RGB pixels (a view of the canvas, valid until the next frame is drawn)."""
        mech.update(result.coords[k])
        for h, trace, arrow, head in traces:
            upto = np.append(sample[: np.searchsorted(sample, k)], k)
            trace.set_data(h.x[upto], h.y[upto])
            px, py = float(h.x[k]), float(h.y[k])
            head.set_data([px], [py])
            vx = float(result.kx1[h.ix][k]) if h.ix in result.kx1 else math.nan
            vy = float(result.kx1[h.iy][k]) if h.iy in result.kx1 else math.nan
            if math.isfinite(vx) and math.isfinite(vy) and h.scale > 0:
                arrow.set_data([px, px + vx * h.scale], [py, py + vy * h.scale])
            else:
                arrow.set_data([], [])
        title.set_text(titles[int(np.searchsorted(plan.frames, k))])
        canvas.restore_region(background)
        for a in moving:
            ax.draw_artist(a)
        fig.draw_artist(title)
        return np.asarray(canvas.buffer_rgba())[:, :, :3]

    files = animation_files(result, outdir, mp4)
    gif_path = files[0]
    mp4_path = files[1] if len(files) > 1 else None
    mp4_tmp = None
    pipe: _Mp4Pipe | None = None
    program = ffmpeg()
    if mp4_path is not None and program is not None:
        mp4_tmp = mp4_path.with_name(f".{mp4_path.stem}.{os.getpid()}.{secrets.token_hex(4)}.tmp.mp4")
        pipe = _Mp4Pipe(program, mp4_tmp, width, height, FPS)
    elif mp4_path is not None:
        info.notes.append("MP4 not written: ffmpeg is not on the PATH.")
    try:
        with atomic_path(gif_path) as gif_tmp, open(gif_tmp, "xb") as f:
            gif = GifStream(f)
            gif.palette = palette_of([draw(k).copy() for k in spread(plan.frames, PALETTE_FRAMES)])
            for done, k in enumerate(plan.frames, 1):
                rgb = draw(k)
                gif.add(Image.fromarray(rgb))
                if pipe is not None:
                    pipe.add(rgb)
                if on_frame is not None:
                    on_frame(done, len(plan.frames))
            gif.close()
        info.files.append(gif_path)
    finally:
        if pipe is not None:
            complaint = pipe.close()
            assert mp4_tmp is not None and mp4_path is not None
            if complaint is None and gif_path in info.files:
                os.replace(mp4_tmp, mp4_path)
                info.files.append(mp4_path)
            else:
                mp4_tmp.unlink(missing_ok=True)
                if complaint is not None:
                    info.notes.append(f"MP4 not written: ffmpeg failed: {complaint}")
    return info
