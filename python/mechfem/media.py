"""Pictures, animation and report of a run, together: what will be written (for the print file) and writing it."""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

from mechfem.animation import MAX_FRAMES, animation_files, frame_plan, write_animation
from mechfem.plots import picture_files, write_pictures
from mechfem.report import report_file, write_report
from mechfem.result import RunResult


@dataclass
class Media:
    """The pictures and the animation the deck asks for, and the report when ``report`` is set."""

    result: RunResult
    outdir: Path
    max_frames: int = MAX_FRAMES
    report: bool = False
    notes: list[str] = field(default_factory=list)
    """What :meth:`write` has to say beyond the files it wrote (a missing MP4)."""

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

    def write(self) -> list[tuple[Path, str]]:
        """Writes everything; returns each file with a short note on it (may be empty)."""
        r = self.result
        written: list[tuple[Path, str]] = [(p, "") for p in write_pictures(r, self.outdir)]
        if r.storage.animate:
            info = write_animation(r, self.outdir, self.max_frames)
            what = info.plan.describe()
            written += [(p, what) for p in info.files]
            self.notes += info.notes
        if self.report:
            written.append((write_report(r, self.outdir), "open it in a web browser"))
        return written
