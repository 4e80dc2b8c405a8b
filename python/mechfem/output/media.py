"""Pictures, animation and report of a run, together: what will be written (for the print file) and writing it."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

from mechfem.report.html import report_file, write_report
from mechfem.results.result import RunResult
from mechfem.viz.animation import MAX_FRAMES, animation_files, frame_plan, write_animation
from mechfem.viz.plots import picture_files, write_pictures

if TYPE_CHECKING:
    from mechfem._util.progress import ProgressBar


@dataclass
class Media:
    """The pictures and the animation the deck asks for, and the report when ``report`` is set."""

    result: RunResult
    outdir: Path
    max_frames: int = MAX_FRAMES
    report: bool = False
    notes: list[str] = field(default_factory=list)
    """What :meth:`write` has to say beyond the files it wrote (a missing MP4)."""
    optimisation: dict[str, Any] | None = None
    """A KIN OPT deck's optimisation, for the report (:mod:`mechfem.report.optimum_report`)."""

    def print_lines(self) -> list[str]:
        """The print file's section on pictures, animation and report; empty when there are none."""
        r, out = self.result, []
        for k, (pic, (png, svg)) in enumerate(zip(r.storage.pictures, picture_files(r, self.outdir), strict=True), 1):
            plots = ", ".join(f"{p.keyword} {p.a} {p.b}" for p in pic.plots) or "no plots"
            title = f" '{pic.title}'" if pic.title else ""
            out.append(f"  picture {k}{title} (line {pic.line}: {plots}): {png.name}, {svg.name}")
        if r.storage.animate:
            files = ", ".join(p.name for p in animation_files(r, self.outdir))
            plan = frame_plan(r.positions, self.max_frames)
            out.append(f"  ANIMATE {r.storage.animate}: {files} ({plan.describe()})")
        if self.report:
            out.append(f"  interactive report: {report_file(r, self.outdir).name}")
        return ["PICTURES AND ANIMATION", *out, ""] if out else []

    def write(
        self, progress: ProgressBar | None = None, on_file: Callable[[Path, str], object] | None = None
    ) -> list[tuple[Path, str]]:
        """Writes everything; returns each file with a short note on it (may be empty).

        ``progress`` counts the pictures and the animation's frames; ``on_file(path, note)`` is called as soon as
        each file is complete.
        """
        r = self.result
        written: list[tuple[Path, str]] = []

        def done(path: Path, note: str = "") -> None:
            written.append((path, note))
            if on_file is not None:
                on_file(path, note)

        pictures = picture_files(r, self.outdir)
        if pictures and progress is not None:
            progress.phase("pictures", len(pictures), "pictures")

        def picture_file(path: Path, k: int) -> None:
            done(path)
            # A picture is done when the last of its files is.
            if progress is not None and path == pictures[k - 1][-1]:
                progress(k, len(pictures))

        write_pictures(r, self.outdir, picture_file)
        if r.storage.animate:
            plan = frame_plan(r.positions, self.max_frames)
            if progress is not None:
                progress.phase("animation", len(plan.frames), "frames")
            info = write_animation(r, self.outdir, self.max_frames, on_frame=progress)
            for p in info.files:
                done(p, info.plan.describe())
            self.notes += info.notes
        if self.report:
            if progress is not None:
                progress.phase("report")
            done(write_report(r, self.outdir, self.optimisation), "open it in a web browser")
        return written
