"""The output files of a run: the print file ``<stem>.prt`` and the data set ``<stem>.csv`` (or ``.npz``,
``.parquet``: :mod:`mechfem.output.datasets`).

Each file is written to a temporary file in the output folder and renamed when complete, so a reader
never sees half a file and an interrupted run leaves no stray temporary file behind.
"""

from __future__ import annotations

import csv
import os
import signal
import textwrap
import threading
from collections.abc import Callable, Sequence
from pathlib import Path
from types import FrameType
from typing import TYPE_CHECKING, Any

import numpy as np

from mechfem._util.atomic import atomic_text
from mechfem.model.echo import EchoStorage, Model
from mechfem.model.masses import Exponents, Said, dynamics_lines
from mechfem.output.datasets import write_binary
from mechfem.results.designer import print_lines as designer_lines
from mechfem.results.inverse_dynamics import summary_lines
from mechfem.results.labels import Label, buffer_labels, coordinate_unit, input_unit, row_dest_unit
from mechfem.results.result import RunResult
from mechfem.results.words import count, with_unit

if TYPE_CHECKING:
    from mechfem._util.progress import ProgressBar

#: Buffers per table in the print file, so that a table fits an ordinary terminal or page.
COLUMNS_PER_TABLE = 6


def write_outputs(
    result: RunResult,
    outdir: Path,
    media: Sequence[str] | Callable[[], Sequence[str]] = (),
    fmt: str = "csv",
    progress: ProgressBar | None = None,
    on_file: Callable[[Path], object] | None = None,
) -> list[Path]:
    """Writes the data set in format ``fmt`` (csv, npz or parquet) when the deck has SAVEDATA, with its notes when
    it holds NaN, then the print file; returns the files written.

    ``media`` are the print file's lines on pictures, animation and report
    (:meth:`mechfem.output.media.Media.print_lines`), or a function that gives them when the print file is written
    (after the data set). ``progress`` is told each phase and how far it is; ``on_file(path)`` is called as soon as each
    file is complete.
    """
    outdir.mkdir(parents=True, exist_ok=True)
    stem = result.deck.stem
    written: list[Path] = []

    def done(path: Path) -> None:
        written.append(path)
        if on_file is not None:
            on_file(path)

    if result.storage.savedata:
        data = outdir / f"{stem}.{fmt}"
        if fmt == "csv":
            if progress is not None:
                progress.phase("data set", result.positions, "rows")
            done(write_data_set(result, data, progress))
        else:
            if progress is not None:
                progress.phase("data set")
            done(write_binary(result, data, fmt))
        if nan_positions(result, result.storage.savedata):
            done(write_data_set_notes(result, outdir / f"{stem}.notes.txt", data))
    if progress is not None:
        progress.phase("print file")
    done(write_print_file(result, outdir / f"{stem}.prt", media() if callable(media) else media))
    return written


class FinishOnInterrupt:
    """A block (in the main thread) during which the first Ctrl-C does not stop the file being written: it is noted
    in :attr:`pressed` and said on standard error at once, and the block goes on; a second Ctrl-C raises
    KeyboardInterrupt as usual. Outside the main thread, where no signal handler can be set, Ctrl-C is not
    deferred."""

    def __init__(self) -> None:
        self.pressed = False
        self._previous: Callable[[int, FrameType | None], Any] | int | None = None
        self._installed = False

    def _handler(self, signum: int, frame: FrameType | None) -> None:
        if self.pressed:
            # A third Ctrl-C must not interrupt the clean-up of the file the second one abandons.
            signal.signal(signal.SIGINT, signal.SIG_IGN)
            raise KeyboardInterrupt
        self.pressed = True
        # os.write, not print: a handler may run in the middle of a write to sys.stderr (the progress bar), and
        # a buffered stream written again from within itself raises. A closed stderr must not cost the files.
        lead = "\r\x1b[K" if os.isatty(2) else ""
        try:
            os.write(
                2,
                f"{lead}mechfem: Ctrl-C: the data set and the print file of what was computed are being finished; "
                "press Ctrl-C again to abandon them\n".encode(),
            )
        except OSError:
            pass

    def __enter__(self) -> FinishOnInterrupt:
        if threading.current_thread() is threading.main_thread():
            self._previous = signal.signal(signal.SIGINT, self._handler)
            self._installed = True
        return self

    def __exit__(self, *exc: object) -> None:
        if self._installed:
            signal.signal(signal.SIGINT, self._previous)


def write_data_set(result: RunResult, path: Path, on_rows: Callable[[int, int], object] | None = None) -> Path:
    """The data set: a header row, then one row per position.

    Each header cell is the buffer's number, a space and its name (``101 dANGB(8)/dinput1``), then for a deck with
    UNITS its unit in brackets (``101 dpsi/dphi [-]``, ``99 phi [deg]``; :meth:`Label.header`), so that a program
    takes the number as the cell's first word; the csv module quotes a
    cell whose name holds a comma. Values are written with ``repr``, the shortest text that reads back as exactly
    the same double (up to 17 significant digits).
    """
    numbers = result.storage.savedata
    labels = buffer_labels(result)
    table = np.column_stack([np.asarray(result.buffers[n], dtype=np.float64) for n in numbers])
    with atomic_text(path) as f:
        csv.writer(f, lineterminator="\n").writerow([labels[n].header() for n in numbers])
        # A block of rows at a time: tolist() gives Python floats in bulk, which is several times faster
        # than indexing numpy per value, and the block keeps the memory for text small.
        for start in range(0, result.positions, CSV_BLOCK):
            f.writelines(format_row(row) for row in table[start : start + CSV_BLOCK].tolist())
            if on_rows is not None:
                on_rows(min(start + CSV_BLOCK, result.positions), result.positions)
    return path


CSV_BLOCK = 10_000


def format_row(row: list[float]) -> str:
    """One line of the data set."""
    return ",".join(map(repr, row)) + "\n"


def write_print_file(result: RunResult, path: Path, media: Sequence[str] = ()) -> Path:
    """The print file: the model, the adjustment of position 1, the PRINTBUF tables, warnings, the stop and
    ``media`` (lines on pictures, animation and report)."""
    with atomic_text(path) as f:
        f.write("\n".join([*print_file_lines(result), *media]) + "\n")
    return path


def print_file_lines(result: RunResult) -> list[str]:
    """The lines of the print file."""
    from mechfem._version import __version__

    said = said_of(result)
    out = [f"mechfem {__version__} - print file", f"deck: {result.deck}", units_line(result.model), ""]
    out += model_lines(result.model, said)
    out += adjustment_lines(result, said)
    out += motion_lines(result)
    if result.simulation is not None:
        out += result.simulation.lines(result.dynamic, result.time, said)
    if result.dynamic is not None:
        out += summary_lines(result.dynamic, result.time, said)
    out += table_lines(result)
    out += designer_lines(result)
    from mechfem.studies.tolerance_print import tolerance_lines

    out += tolerance_lines(result)
    out += limit_lines(result, said)
    if result.report.warnings:
        out += ["WARNINGS", *(line for w in result.report.warnings for line in paragraph(w)), ""]
    reason = result.report.stop_reason(written=True)
    if reason is not None:
        out += ["MOTION STOPPED", *paragraph(reason), ""]
    return out


#: The kind of each word of :mod:`mechfem.results.labels`' unit algebra a row or co-ordinate has.
KIND_OF_WORD: dict[str, Exponents] = {"length": {"length": 1}, "rad": {"angle": 1}, "": {}}


def said_of(result: RunResult) -> Said:
    """How the print file says ``result``'s numbers: the deck's units, the kinds of its rows, co-ordinates and
    inputs, its named points and rows."""
    model = result.model
    rows = [*model.prescribed, *model.dependent]
    return Said(
        units=model.units,
        rows={r.dest: KIND_OF_WORD.get(row_dest_unit(result, r.dest), {}) for r in rows},
        inputs=[KIND_OF_WORD.get(input_unit(result, j), {}) for j in range(1, len(model.dofs) + 1)],
        coords={c.number: KIND_OF_WORD.get(coordinate_unit(result, c.number), {}) for c in model.coordinates},
        points={(p.x, p.y): p.name for p in model.points},
        row_names={r.dest: r.name for r in rows if r.name},
    )


def det_unit(model: Model) -> str:
    """The unit of det(D^c) of ``model``, as the core gives it: the product of the rows' units over the moving
    co-ordinates' (``deg/mm`` for a four-bar in mm and degrees); "" where a kind of it has no unit."""
    return model.labels.det()[1] if model.labels is not None else ""


def det_words(model: Model, value: float, digits: int) -> str:
    """``det(D^c) = value unit``."""
    return f"det(D^c) = {with_unit(f'{value:.{digits}g}', det_unit(model))}"


def units_line(model: Model) -> str:
    """The print file's statement of the units its numbers are in."""
    given = [f"{kind.upper()} {unit}" for kind, unit in model.units.items() if unit]
    if not given:
        return "units: none declared (no UNITS line): every number is the deck's own, angles in radians"
    return f"units: {' '.join(given)} (the UNITS line); every number below is in them"


def model_lines(model: Model, said: Said | None = None) -> list[str]:
    """The echo of the model: sizes, elements, form parameters, DOFs and co-ordinates, each value with its unit
    (``said``) when the deck has UNITS."""
    said = said or Said()

    def unit(kind: Exponents) -> str:
        u = said.unit(kind)
        return f"{u:<8}" if said.units and any(said.units.values()) else ""

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
        out.append(f"    {e.number:4d}  {e.type:<4}  {coords}{_named(e.name)}")
    out += ["", "  prescribed form parameters (rows of D^c)", "     row  value at position 1  form parameters"]
    for r in model.prescribed:
        out.append(f"    {r.dest:4d}  {r.value:17.10g}{unit(said.rows.get(r.dest, {}))}  {r.formula()}{_named(r.name)}")
    if model.dependent:
        out += ["", "  dependent form parameters", "    dest  value at position 1  form parameters"]
        for r in model.dependent:
            out.append(
                f"    {r.dest:4d}  {r.value:17.10g}{unit(said.rows.get(r.dest, {}))}  {r.formula()}{_named(r.name)}"
            )
    out += ["", "  degrees of freedom (inputs)"]
    out += [f"    DOF {j}: row {row}{_named(model.prescribed[row - 1].name)}" for j, row in enumerate(model.dofs, 1)]
    out += ["", "  co-ordinates", "      no  kind              given         position 1"]
    for c in model.coordinates:
        kind = "XMOV" if c.moving else "XFIX"
        u = unit(said.coords.get(c.number, {"length": 1}))
        out.append(f"    {c.number:4d}  {kind}  {c.given:17.10g}  {c.adjusted:17.10g}{u}{_named(c.name)}".rstrip())
    if model.dynamics is not None:
        out += dynamics_lines(model.dynamics, said)
    out.append("")
    return out


def _named(name: str | None) -> str:
    """What the print file's echo of the model adds to a line for a thing the deck's NAMES block names."""
    return f"  = {name}" if name else ""


def adjustment_lines(result: RunResult, said: Said | None = None) -> list[str]:
    """How the initial co-ordinates were adjusted to make position 1; a row's deformation with its unit
    (``said``)."""
    said = said or Said()

    def deformation(row: int, e: float, fmt: str) -> str:
        return f"{e:{fmt}}{said.unit(said.rows.get(row, {}))}"

    a = result.report.adjust
    out = ["ADJUSTMENT OF POSITION 1"]
    largest = a.largest()
    if a.iterations == 0:
        out.append("  the given co-ordinates satisfy every prescribed value: no adjustment needed")
    else:
        out.append(f"  Newton iterations: {a.iterations} (in {count(a.stages, 'stage')})")
    if largest is not None:
        out.append(f"  largest initial deformation: {deformation(largest[0], largest[1], '.6g')} (row {largest[0]})")
    out.append(f"  largest remaining deformation: {a.residual:.3g}")
    out.append(f"  {det_words(result.model, float(result.det[0]), 10).replace(' =', ' at position 1:', 1)}")
    moved = [(r, e) for r, e in enumerate(a.initial_deformations, 1) if e != 0.0]
    if moved:
        out += ["  initial deformations (value at the given co-ordinates - prescribed value)"]
        out += [f"    row {r:4d}: {deformation(r, e, '17.10g')}" for r, e in moved]
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
    """The PRINTBUF section: a legend of every tabulated buffer (number, name, unit, deck line, what it holds),
    then the tables, COLUMNS_PER_TABLE buffers per table, each column headed by its number and name. Nothing
    without PRINTBUF."""
    numbers = result.storage.printbuf
    if not numbers:
        return []
    labels = buffer_labels(result)
    out = ["BUFFERS", *legend_lines(result, numbers, labels), ""]
    for start in range(0, len(numbers), COLUMNS_PER_TABLE):
        group = numbers[start : start + COLUMNS_PER_TABLE]
        # A column is as wide as the numbers need (10 significant digits) or its name, whichever is wider.
        widths = [max(COLUMN_WIDTH, len(labels[n].name) + 2) for n in group]
        out.append("  position" + "".join(f"{n:>{w}d}" for n, w in zip(group, widths, strict=True)))
        out.append("          " + "".join(f"{labels[n].name:>{w}}" for n, w in zip(group, widths, strict=True)))
        columns = [result.buffers[n] for n in group]
        for k in range(result.positions):
            out.append(
                f"  {k + 1:8d}" + "".join(f"{float(c[k]):{w}.10g}" for c, w in zip(columns, widths, strict=True))
            )
        out.append("")
    return out


#: The width of a table column in the print file (a name longer than it widens its column).
COLUMN_WIDTH = 18


def legend_lines(result: RunResult, numbers: list[int], labels: dict[int, Label]) -> list[str]:
    """One line per buffer: number, name, unit (``-`` for a pure number, such as deg/deg; blank where the model
    gives no unit of a kind the quantity needs), the deck line that defines it and what it holds."""
    rows = [(str(n), labels[n].name, labels[n].unit, result.storage.buffer(n).label(), labels[n].text) for n in numbers]
    head = ("no", "name", "unit", "deck line", "what it holds")
    widths = [max(len(r[c]) for r in [head, *rows]) for c in range(4)]
    out = []
    for r in [head, *rows]:
        cells = [r[0].rjust(widths[0]), *(r[c].ljust(widths[c]) for c in range(1, 4)), r[4]]
        out.append(("    " + "  ".join(cells)).rstrip())
    return out


#: A model with at most this many moving co-ordinates has all of them listed at every limit position; a larger one
#: has only the co-ordinates its BUFX0 buffers record.
SHORT_MODEL = 10

#: Width of the paragraphs of the limit-position and stop sections.
TEXT_WIDTH = 100


def paragraph(text: str, indent: str = "  ") -> list[str]:
    """``text`` wrapped to TEXT_WIDTH columns, every line indented."""
    wrapper = textwrap.TextWrapper(
        TEXT_WIDTH, initial_indent=indent, subsequent_indent=indent, break_on_hyphens=False, break_long_words=False
    )
    return wrapper.wrap(text)


def nan_buffers(result: RunResult, numbers: list[int]) -> list[int]:
    """Those of the buffers ``numbers`` that hold NaN at some position."""
    return [n for n in numbers if np.isnan(result.buffers[n]).any()]


def nan_positions(result: RunResult, numbers: list[int]) -> list[int]:
    """The positions (1-based) where any of the buffers ``numbers`` holds NaN."""
    bad: set[int] = set()
    for n in numbers:
        bad.update(int(k) + 1 for k in np.flatnonzero(np.isnan(result.buffers[n])))
    return sorted(bad)


def numbers_text(items: Sequence[object]) -> str:
    """``1``, ``1 and 5``, ``1, 5 and 9``."""
    text = [str(n) for n in items]
    return text[0] if len(text) == 1 else ", ".join(text[:-1]) + " and " + text[-1]


def buffers_text(storage: EchoStorage, numbers: list[int]) -> str:
    """``3 (BUFKE1 -1 1) and 5 (BUFKX1 9 1)``."""
    return numbers_text([f"{n} ({storage.buffer(n).label()})" for n in numbers])


def shown_coordinates(result: RunResult) -> list[int]:
    """The co-ordinates listed at each limit position: every moving one of a small model, otherwise those that
    BUFX0 buffers record."""
    moving = [c.number for c in result.model.coordinates if c.moving]
    if len(moving) <= SHORT_MODEL:
        return moving
    return sorted({b.args[0] for b in result.storage.buffers if b.keyword == "BUFX0"})


def limit_lines(result: RunResult, said: Said | None = None) -> list[str]:
    """The LIMIT POSITIONS section: the range of det(D^c), every located limit position, and the positions
    without transfer functions. Nothing without a motion."""
    report = result.report
    if report.steps == 0:
        return []
    out = ["LIMIT POSITIONS"]
    det = np.abs(result.det)
    if not np.isfinite(det[1:]).any():
        out += paragraph(
            "det(D^c) was not computed (a run with det=False): no sign change of it was watched for, and only a "
            "driven input stopped at its limit position would be located."
        )
    else:
        k_min, k_max = int(np.nanargmin(det)), int(np.nanargmax(det))
        unit = det_unit(result.model)
        out += paragraph(
            f"det(D^c), the measure of transfer quality, ranges from {np.nanmin(result.det):.6g} "
            f"to {with_unit(f'{np.nanmax(result.det):.6g}', unit)}; its magnitude is smallest at position "
            f"{k_min + 1} ({det[k_min]:.3g}) and largest at position {k_max + 1} ({det[k_max]:.3g}). Its value "
            "depends on units and on the choice of rows: compare it only along one run. Where it is zero, an input "
            "is in a limit position."
        )
    limits = report.located_limits
    if not limits:
        out += ["", "  no limit position met"]
    shown = shown_coordinates(result)
    said = said or Said()
    # The co-ordinates' unit, when they share one (in the deck's units, as the core's report gives them).
    units = {said.unit(said.coords.get(i, {"length": 1})) for i in shown}
    in_unit = f" [{units.pop().strip()}]" if len(units) == 1 and "" not in units else ""
    for number, limit in enumerate(limits, 1):
        out.append("")
        head = paragraph(f"{limit.where}: {limit.what(report.input_names)}", "      ")
        out += [f"  {number:2d}. {head[0].lstrip()}", *head[1:]]
        out += paragraph(limit.values(report.input_names), "      ")
        if shown:
            values = [f"{i:>4d} = {limit.coords[i - 1]:<17.10g}" for i in shown]
            out.append(f"      co-ordinates there{in_unit}:")
            out += [f"      {'  '.join(values[k : k + 4])}".rstrip() for k in range(0, len(values), 4)]
    if report.singular_positions:
        positions = report.singular_positions
        nan = nan_buffers(result, [b.number for b in result.storage.buffers])
        which = "Buffer" if len(nan) == 1 else "Buffers"
        holds = (
            f" {which} {buffers_text(result.storage, nan)}, made from them, hold{'s' if len(nan) == 1 else ''} NaN "
            "there (nan in the tables and the data set); every other value is a number."
            if nan
            else ""
        )
        out += ["", f"  positions without transfer functions: {numbers_text(positions)}"]
        out += paragraph(
            f"D^c is singular at {'this position' if len(positions) == 1 else 'these positions'}: the mechanism is "
            f"in a limit position of its input there, and no transfer functions exist.{holds}",
            "    ",
        )
    out.append("")
    return out


def write_data_set_notes(result: RunResult, path: Path, data: Path | None = None) -> Path:
    """The note beside the data set ``data`` (default ``<stem>.csv``) that holds NaN: where, and why."""
    stem = result.deck.stem
    data = data if data is not None else path.with_name(f"{stem}.csv")
    saved = result.storage.savedata
    nan = nan_buffers(result, saved)
    positions = nan_positions(result, saved)
    singular = result.report.singular_positions
    lines = [
        f"Notes on {data.name}, the data set of {result.deck}",
        "",
        "Row 1 holds each column's buffer number and name, row k + 1 the values at position k."
        if data.suffix == ".csv"
        else "The column position holds the position numbers; every other column one buffer, named by its number "
        "and name.",
        "",
    ]
    lines += paragraph(
        f"nan: column{'s' if len(nan) > 1 else ''} {buffers_text(result.storage, nan)} "
        f"hold{'s' if len(nan) == 1 else ''} nan at position{'s' if len(positions) > 1 else ''} "
        f"{numbers_text(positions)} and nowhere else. "
        + (
            f"D^c is singular at position{'s' if len(singular) > 1 else ''} {numbers_text(singular)}: the mechanism "
            "is in a limit position of its input there, so no transfer functions (and no velocities or "
            "accelerations made from them) exist."
            if singular
            else ""
        ),
        "",
    )
    if result.report.located_limits:
        lines += ["", f"Limit positions located (details in LIMIT POSITIONS of {stem}.prt):"]
        lines += [f"  {limit.where}: {limit.values()}" for limit in result.report.located_limits]
    with atomic_text(path) as f:
        f.write("\n".join(lines) + "\n")
    return path
