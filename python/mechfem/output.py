"""The output files of a run: the print file ``<stem>.prt`` and the data set ``<stem>.csv``.

Each file is written to a temporary file in the output folder and renamed when complete, so a reader
never sees half a file and an interrupted run leaves no stray temporary file behind.
"""

from __future__ import annotations

import os
import secrets
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import TextIO

from mechfem.result import Model, RunResult

#: Buffers per table in the print file, so that a table fits an ordinary terminal or page.
COLUMNS_PER_TABLE = 6


def count(n: int, singular: str, plural: str | None = None) -> str:
    """``1 stage``, ``2 stages``; ``plural`` when adding an s is not right."""
    return f"{n} {singular if n == 1 else plural or singular + 's'}"


@contextmanager
def atomic_text(path: Path) -> Iterator[TextIO]:
    """Opens a temporary file beside ``path`` for writing; renames it to ``path`` when the block succeeds.

    The temporary file is created like any other file (so the umask applies), under a name no other
    writer uses.
    """
    tmp = path.with_name(f".{path.name}.{os.getpid()}.{secrets.token_hex(4)}.tmp")
    try:
        with open(tmp, "x", encoding="utf-8", newline="\n") as f:
            yield f
        os.replace(tmp, path)
    except BaseException:
        tmp.unlink(missing_ok=True)
        raise


def write_outputs(result: RunResult, outdir: Path) -> list[Path]:
    """Writes the print file, and the data set when the deck has SAVEDATA; returns the files written."""
    outdir.mkdir(parents=True, exist_ok=True)
    stem = result.deck.stem
    written = [write_print_file(result, outdir / f"{stem}.prt")]
    if result.storage.savedata:
        written.append(write_data_set(result, outdir / f"{stem}.csv"))
    return written


def write_data_set(result: RunResult, path: Path) -> Path:
    """The data set: a header row of buffer numbers, then one row per position.

    Values are written with ``repr``, the shortest text that reads back as exactly the same double
    (up to 17 significant digits).
    """
    numbers = result.storage.savedata
    columns = [result.buffers[n] for n in numbers]
    with atomic_text(path) as f:
        f.write(",".join(str(n) for n in numbers) + "\n")
        for k in range(result.positions):
            f.write(",".join(repr(float(c[k])) for c in columns) + "\n")
    return path


def write_print_file(result: RunResult, path: Path) -> Path:
    """The print file: the model, the adjustment of position 1, the PRINTBUF tables, warnings and the stop."""
    with atomic_text(path) as f:
        f.write("\n".join(print_file_lines(result)) + "\n")
    return path


def print_file_lines(result: RunResult) -> list[str]:
    """The lines of the print file."""
    from mechfem import __version__

    out = [f"mechfem {__version__} - print file", f"deck: {result.deck}", ""]
    out += model_lines(result.model)
    out += adjustment_lines(result)
    out += motion_lines(result)
    out += table_lines(result)
    if result.report.warnings:
        out += ["WARNINGS", *(f"  {w}" for w in result.report.warnings), ""]
    reason = result.report.stop_reason()
    if reason is not None:
        out += ["MOTION STOPPED", f"  {reason}", ""]
    return out


def model_lines(model: Model) -> list[str]:
    """The echo of the model: sizes, elements, form parameters, DOFs and co-ordinates."""
    n_fixed = model.n_coords - model.n_moving
    out = [
        "MODEL",
        f"  {model.n_coords} co-ordinates ({n_fixed} fixed, {model.n_moving} moving), "
        f"{len(model.elements)} elements, {len(model.prescribed)} prescribed form parameters, "
        f"{len(model.dependent)} dependent, {count(len(model.dofs), 'degree of freedom', 'degrees of freedom')}",
        "",
        "  elements",
        "      no  type  co-ordinates",
    ]
    for e in model.elements:
        coords = "  ".join(f"{n}={c}" for n, c in zip(e.coord_names, e.coords, strict=True))
        out.append(f"    {e.number:4d}  {e.type:<4}  {coords}")
    out += ["", "  prescribed form parameters (rows of D^c)", "     row  value at position 1  form parameters"]
    for r in model.prescribed:
        out.append(f"    {r.dest:4d}  {r.value:17.10g}  {r.formula()}")
    if model.dependent:
        out += ["", "  dependent form parameters", "    dest  value at position 1  form parameters"]
        for r in model.dependent:
            out.append(f"    {r.dest:4d}  {r.value:17.10g}  {r.formula()}")
    out += ["", "  degrees of freedom (inputs)"]
    out += [f"    DOF {j}: row {row}" for j, row in enumerate(model.dofs, 1)]
    out += ["", "  co-ordinates", "      no  kind              given         position 1"]
    for c in model.coordinates:
        kind = "XMOV" if c.moving else "XFIX"
        out.append(f"    {c.number:4d}  {kind}  {c.given:17.10g}  {c.adjusted:17.10g}")
    out.append("")
    return out


def adjustment_lines(result: RunResult) -> list[str]:
    """How the initial co-ordinates were adjusted to make position 1."""
    a = result.report.adjust
    out = ["ADJUSTMENT OF POSITION 1"]
    largest = a.largest()
    if a.iterations == 0:
        out.append("  the given co-ordinates satisfy every prescribed value: no adjustment needed")
    else:
        out.append(f"  Newton iterations: {a.iterations} (in {count(a.stages, 'stage')})")
    if largest is not None:
        out.append(f"  largest initial deformation: {largest[1]:.6g} (row {largest[0]})")
    out.append(f"  largest remaining deformation: {a.residual:.3g}")
    out.append(f"  det(D^c) at position 1: {result.det[0]:.10g}")
    moved = [(r, e) for r, e in enumerate(a.initial_deformations, 1) if e != 0.0]
    if moved:
        out += ["  initial deformations (value at the given co-ordinates - prescribed value)"]
        out += [f"    row {r:4d}: {e:17.10g}" for r, e in moved]
    out.append("")
    return out


def motion_lines(result: RunResult) -> list[str]:
    """The size of the motion and how it went."""
    r = result.report
    if r.steps == 0:
        return ["MOTION", "  no MOVEMENT block: only position 1 was computed", ""]
    out = [
        "MOTION",
        f"  steps: {r.steps}, positions asked for: {r.steps + 1}, positions computed: {r.positions}",
    ]
    if r.subdivided_steps:
        out.append(f"  steps that had to be subdivided: {r.subdivided_steps}")
    out.append("")
    return out


def table_lines(result: RunResult) -> list[str]:
    """The PRINTBUF tables, COLUMNS_PER_TABLE buffers per table; nothing without PRINTBUF."""
    numbers = result.storage.printbuf
    if not numbers:
        return []
    out: list[str] = []
    for start in range(0, len(numbers), COLUMNS_PER_TABLE):
        group = numbers[start : start + COLUMNS_PER_TABLE]
        defs = [result.storage.buffer(n) for n in group]
        out.append("BUFFERS " + ", ".join(f"{d.number} = {d.label()}" for d in defs))
        out.append("  position" + "".join(f"{n:>18d}" for n in group))
        columns = [result.buffers[n] for n in group]
        for k in range(result.positions):
            out.append(f"  {k + 1:8d}" + "".join(f"{float(c[k]):18.10g}" for c in columns))
        out.append("")
    return out
