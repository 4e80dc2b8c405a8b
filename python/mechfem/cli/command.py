"""The ``mechfem`` command.

    mechfem run DECK [-o OUTDIR] [--report | --no-media] [--format csv|npz|parquet] [--max-frames N]
                     [--memory-limit SIZE] [--quiet]
                                   run the deck, write DECK-stem.prt (and the data set DECK-stem.csv, .npz or
                                   .parquet with SAVEDATA), the pictures and the animation to OUTDIR; --report
                                   adds the interactive DECK-stem.html, --no-media leaves out pictures, animation
                                   and report; a KIN OPT deck is optimised first and its final design written as
                                   DECK-stem_opt.mec, whose run gives the outputs
    mechfem report DECK [-o OUTDIR] [--memory-limit SIZE] [--quiet]
                                   run the deck and write only the interactive report DECK-stem.html
    mechfem check DECK [--quiet]   read the deck and compute position 1 only

A progress bar on stderr names each phase (computing, data set, print file, pictures, animation, report) when
stderr is a terminal; each output file is announced on stdout as soon as it is complete. --quiet says nothing
but errors.
    mechfem draw DECK [-o OUTDIR] [--position N] [--format dxf,svg] [--no-paths] [--units UNIT] [--quiet]
                                   run the deck and write the mechanism at position N (default 1) with the paths
                                   of its moving points as DECK-stem_posN.dxf and .svg

Exit status:

    0    complete: every position computed and every output written
    1    nothing computed: a mistake in the deck or the command, position 1 cannot be computed, the results would
         not fit in the memory limit, an optimisation that cannot start, or an output file that cannot be written
    2    a wrong command line
    3    the motion (or simulation, or the optimisation's final run) stopped early: the results up to there are
         written, and stderr says why
    4    an internal error of mechfem (a bug)
    130  Ctrl-C (a run writes every position computed before it)

Messages go to stderr as one short paragraph, never a traceback.
"""

from __future__ import annotations

import argparse
import sys
import warnings
from pathlib import Path
from typing import TYPE_CHECKING, Any

import mechfem
import mechfem._core as _core
from mechfem._util.limits import DEFAULT_MEMORY_LIMIT, ENV, memory_limit, parse_size
from mechfem._util.progress import Console, ProgressBar
from mechfem.design import engine as design
from mechfem.design import optimise_deck
from mechfem.errors import (
    AssemblyError,
    ConvergenceError,
    DeckError,
    LimitPositionError,
    MechfemError,
    RunInterrupted,
)
from mechfem.output.datasets import FORMATS, pyarrow
from mechfem.output.files import FinishOnInterrupt, det_words, write_outputs
from mechfem.output.media import Media
from mechfem.output.output_folder import locked, plan
from mechfem.report.html import write_report
from mechfem.results.words import count
from mechfem.viz.animation import MAX_FRAMES

if TYPE_CHECKING:
    from mechfem._core import OptimiseBlock

EXIT_OK = 0
EXIT_FAILED = 1
EXIT_STOPPED = 3
EXIT_INTERNAL = 4
EXIT_INTERRUPTED = 130


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="mechfem",
        description="Finite-element kinematics of planar mechanisms, driven by RUNMEC-style decks.",
    )
    parser.add_argument("--version", action="version", version=f"mechfem {mechfem.__version__}")
    commands = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")
    run = commands.add_parser("run", help="run a deck and write its print file and data set")
    run.add_argument("deck", type=Path, metavar="DECK", help="the deck to run")
    add_outdir(run, "the output files")
    media = run.add_mutually_exclusive_group()
    media.add_argument(
        "--report", action="store_true", help="also write the interactive report DECK-stem.html (one offline file)"
    )
    media.add_argument(
        "--no-media",
        action="store_true",
        help="write no pictures, animation or report, only the print file and the data set (for big runs)",
    )
    run.add_argument(
        "--format",
        choices=FORMATS,
        default="csv",
        help="the data set's format: csv (text), npz (numpy) or parquet (needs mechfem[parquet]); default csv",
    )
    run.add_argument(
        "--max-frames",
        type=frame_count,
        default=MAX_FRAMES,
        metavar="N",
        help=f"most frames of the animation, 2..{MAX_FRAMES} (default {MAX_FRAMES}); longer runs are subsampled",
    )
    add_memory_limit(run)
    add_quiet(run)
    run.set_defaults(func=cmd_run)
    rep = commands.add_parser("report", help="run a deck and write only its interactive report (HTML)")
    rep.add_argument("deck", type=Path, metavar="DECK", help="the deck to run")
    add_outdir(rep, "DECK-stem.html")
    add_memory_limit(rep)
    add_quiet(rep)
    rep.set_defaults(func=cmd_report)
    check = commands.add_parser("check", help="read a deck and compute its first position only")
    check.add_argument("deck", type=Path, metavar="DECK", help="the deck to check")
    add_quiet(check, "the exit status alone says whether the deck is valid")
    check.set_defaults(func=cmd_check)
    add_draw(commands)
    from mechfem.studio_app.command import add_studio

    add_studio(commands)
    return parser


def add_outdir(parser: argparse.ArgumentParser, what: str) -> None:
    parser.add_argument(
        "-o",
        "--outdir",
        type=Path,
        default=None,
        metavar="OUTDIR",
        help=f"folder for {what} (created if needed; default: the deck's folder)",
    )


def add_quiet(parser: argparse.ArgumentParser, why: str = "the exit status is the same") -> None:
    parser.add_argument(
        "-q", "--quiet", action="store_true", help=f"print nothing but errors: no progress bar, no file list ({why})"
    )


def add_memory_limit(parser: argparse.ArgumentParser) -> None:
    parser.add_argument(
        "--memory-limit",
        type=size,
        default=None,
        metavar="SIZE",
        help=f"most memory the results may take, e.g. 512M or 8G (default ${ENV} or "
        f"{DEFAULT_MEMORY_LIMIT // 1024**3}G); a deck asking for more is refused before it runs",
    )


def size(text: str) -> int:
    """``--memory-limit``: a size such as 512M or 8G."""
    try:
        return parse_size(text)
    except ValueError as e:
        raise argparse.ArgumentTypeError(str(e)) from None


def run_with_progress(deck: Path, limit: int | None, bar: ProgressBar | None = None) -> tuple[mechfem.RunResult, bool]:
    """Runs a deck with the progress ``bar`` on standard error (default: one of its own, shown on a terminal
    only and cleared after the run), in the phase "computing". Returns the result and whether Ctrl-C stopped it
    (the result then holds the positions computed before)."""
    own = bar is None
    progress = ProgressBar() if bar is None else bar
    progress.phase("computing", unit="positions")
    try:
        # A stopped motion is said once, with the exit status (exit_status), not as a Python warning.
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", mechfem.IncompleteRunWarning)
            return mechfem.run_deck(deck, progress=progress, memory_limit=limit), False
    except RunInterrupted as e:
        return e.result, True
    finally:
        if own:
            progress.close()


def exit_status(deck: Path, result: mechfem.RunResult, interrupted: bool, console: Console | None = None) -> int:
    """After the outputs are written: says why the motion stopped early, if it did, and gives the exit status."""
    say = console if console is not None else Console(ProgressBar(show=False))
    reason = result.report.stop_reason(written=True)
    if interrupted:
        if reason is None:
            reason = f"All {count(result.report.positions, 'position')} had been computed and are written."
        say.error(f"mechfem: {deck}: interrupted. {reason}")
        return EXIT_INTERRUPTED
    if reason is not None:
        say.error(f"error: {deck}: {reason}")
        return EXIT_STOPPED
    return EXIT_OK


def cmd_run(args: argparse.Namespace) -> int:
    deck: Path = args.deck
    outdir: Path = args.outdir if args.outdir is not None else deck.parent
    if args.format == "parquet":
        pyarrow()  # before anything is computed: a missing pyarrow is said at once
    plan(deck, outdir, data_format=args.format, media=not args.no_media, report=args.report).check()
    with locked(outdir, deck.stem):
        opt = optimisation(deck)
        if opt is not None:
            return run_optimisation(args, deck, outdir, opt)
        result, interrupted = run_with_progress(deck, args.memory_limit, args.console.bar)
        return finish_run(args, deck, outdir, result, interrupted)


def optimisation(deck: Path) -> OptimiseBlock | None:
    """The OPTIMISE block of a KIN OPT deck or a DYN ANA deck that has one; None for any other deck, or a deck that
    cannot be read (the run then says why)."""
    try:
        text = _core.read_deck_text(deck)
    except DeckError:
        return None
    if optimise_deck.deck_mode(text) not in ("KIN OPT", "DYN ANA"):
        return None
    return optimise_deck.describe(deck).optimise


def mode_of(deck: Path) -> str:
    """The mode line of a deck that reads (``KIN OPT``, ``DYN ANA``)."""
    return optimise_deck.deck_mode(_core.read_deck_text(deck))


def run_optimisation(args: argparse.Namespace, deck: Path, outdir: Path, opt: OptimiseBlock) -> int:
    """Optimises the design of a KIN OPT deck, writes it as ``<stem>_opt.mec`` and runs that deck as a KIN ANA
    run whose outputs are named after ``deck`` and whose print file has the OPTIMISATION section."""
    history: list[design.Iteration] = []
    console: Console = args.console

    def report(it: design.Iteration) -> None:
        history.append(it)
        console.bar.advance()
        console.note(optimise_deck.iteration_line(it))

    console.note(f"{deck}: optimising {optimise_deck.names_and_lines(opt)}")
    console.bar.phase("optimising", unit="iterations")
    try:
        s = optimise_deck.optimise(deck, opt, report)
    except optimise_deck.OptimisationError as e:
        console.error(str(e))
        return EXIT_FAILED
    except KeyboardInterrupt:
        for path in optimise_deck.write_interrupted(deck, opt, history, outdir):
            console.say(f"wrote {path}")
        done = count(max(len(history) - 1, 0), "iteration")
        console.error(f"mechfem: {deck}: interrupted during the optimisation after {done}.")
        return EXIT_INTERRUPTED
    written_deck = optimise_deck.write_design_deck(s, outdir)
    result, interrupted = run_with_progress(written_deck, args.memory_limit, console.bar)
    result = result.replace(deck=deck)
    values = optimise_deck.values_line(optimise_deck.stated(s).problem, s.x, result.model, opt)
    console.say(
        f"{deck}: {'optimised' if s.success else 'optimiser stopped'} in {count(s.runs, 'mechanism run')}: "
        f"objective {s.start_objective:.4g} -> {s.objective:.4g}; {values}"
    )
    lines = optimise_deck.print_lines(s, written_deck, result.model)
    section = None
    if args.report and not args.no_media and not interrupted:
        from mechfem.report.optimum_report import deck_section

        section = deck_section(s, result, args.memory_limit)
    status = finish_run(args, deck, outdir, result, interrupted, lines, [written_deck], section)
    if not s.success:
        console.note(f"warning: {deck}: the optimiser did not converge: {s.message}")
    missed = optimise_deck.unreached(s)
    if missed is not None:
        console.note(
            f"note: {deck}: the targets are not all reached: the largest difference left is "
            f"{optimise_deck.missed_value(s, missed, result.model)} (the target on line {missed[1]}); the "
            "design found is the nearest the optimiser could get, and the print "
            "file lists every target's difference"
        )
    return status


def finish_run(
    args: argparse.Namespace,
    deck: Path,
    outdir: Path,
    result: mechfem.RunResult,
    interrupted: bool,
    lines: list[str] | None = None,
    files: list[Path] | None = None,
    optimisation: dict[str, Any] | None = None,
) -> int:
    """Writes every output of a run, saying each file as soon as it is complete, and gives the exit status;
    ``lines`` are added to the print file and ``files`` (written before) to the list of files written, and
    ``optimisation`` (a KIN OPT deck's) to the report. With ``--no-media`` only the data set and the print file
    are written."""
    console: Console = args.console
    media = (
        None
        if args.no_media
        else Media(result, outdir, max_frames=args.max_frames, report=args.report, optimisation=optimisation)
    )
    report = result.report
    console.say(f"{deck}: {count(report.positions, 'position')} computed")
    for path in files or []:
        console.say(f"wrote {path}")

    def wrote(path: Path, what: str = "") -> None:
        console.say(f"wrote {path}" + (f" ({what})" if what else ""))

    # Ctrl-C while the data set and the print file are written finishes them (a second one abandons the file being
    # written), then leaves out the pictures, the animation and the report.
    with FinishOnInterrupt() as ctrl_c:
        try:
            write_outputs(
                result,
                outdir,
                lambda: [*(lines or []), *(media.print_lines() if media is not None and not ctrl_c.pressed else [])],
                args.format,
                console.bar,
                wrote,
            )
        except KeyboardInterrupt:
            console.error(
                f"mechfem: {deck}: interrupted twice while the outputs were written: the file being written was "
                "abandoned (any earlier version of it is left as it was); the files said above are complete."
            )
            return EXIT_INTERRUPTED
    if ctrl_c.pressed:
        interrupted = True
        if media is not None:
            console.note(f"note: {deck}: the pictures, animation and report are not written (Ctrl-C)")
    elif media is not None:
        media.write(console.bar, wrote)
        for note in media.notes:
            console.say(f"note: {note}")
    console.bar.close()
    for limit in report.limits:
        if limit.kind == "passed":
            console.say(f"limit position: {limit.describe(report.input_names)}")
    for w in report.warnings:
        console.note(f"warning: {deck}: {w}")
    return exit_status(deck, result, interrupted, console)


def frame_count(text: str) -> int:
    """``--max-frames``: an integer from 2 to MAX_FRAMES."""
    try:
        n = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"not a whole number: {text!r}") from None
    if not 2 <= n <= MAX_FRAMES:
        raise argparse.ArgumentTypeError(f"must be from 2 to {MAX_FRAMES}, not {n}")
    return n


def cmd_report(args: argparse.Namespace) -> int:
    deck: Path = args.deck
    outdir: Path = args.outdir if args.outdir is not None else deck.parent
    console: Console = args.console
    plan(deck, outdir, data_format=None, media=False, report=True).check()
    if optimisation(deck) is not None:
        console.note(
            f"note: {deck} is a {mode_of(deck)} deck: this report shows its start design; "
            "`mechfem run --report` optimises it and reports the final design"
        )
    with locked(outdir, deck.stem):
        result, interrupted = run_with_progress(deck, args.memory_limit, console.bar)
        console.say(f"{deck}: {count(result.report.positions, 'position')} computed")
        console.bar.phase("report")
        path = write_report(result, outdir)
    console.bar.close()
    console.say(f"wrote {path} (open it in a web browser)")
    return exit_status(deck, result, interrupted, console)


def cmd_check(args: argparse.Namespace) -> int:
    deck: Path = args.deck
    c = mechfem.check_deck(deck)
    if args.quiet:
        return EXIT_OK
    a = c.adjust
    print(f"{deck}: the deck is valid")
    opt = optimisation(deck)
    if opt is not None:
        print(
            f"  {mode_of(deck)}: position 1 of the start design; the optimisation varies "
            f"{optimise_deck.names_and_lines(opt)}"
        )
    print(
        f"  {c.n_coords} co-ordinates ({c.n_coords - c.n_moving} fixed, {c.n_moving} moving), "
        f"{count(c.n_prescribed, 'prescribed row')}, {count(c.n_dependent, 'dependent form parameter')}, "
        f"{c.n_dof} DOF"
    )
    largest = a.largest()
    if largest is not None and a.iterations > 0:
        print(
            f"  position 1: adjusted in {a.iterations} Newton iterations "
            f"(largest initial deformation {largest[1]:.6g} in row {largest[0]}; remaining {a.residual:.3g})"
        )
    else:
        print(f"  position 1: the given co-ordinates fit (remaining deformation {a.residual:.3g})")
    print(f"  {det_words(c.model, c.det, 10).replace(' =', ' at position 1:', 1)}")
    # The adjusted position is what a run starts from: show it beside the estimate.
    print("  moving co-ordinates at position 1:")
    print(f"  {'no':>6} {'given':>16} {'position 1':>16}")
    for coord in c.model.coordinates:
        if coord.moving:
            print(f"  {coord.number:>6} {coord.given:>16.10g} {coord.adjusted:>16.10g}")
    if c.det == 0.0:
        print(
            "  position 1 is a limit position of the input: D^c is singular there and no transfer functions exist "
            "(free motion starts from it)"
        )
    return EXIT_OK


def add_draw(commands: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    """The ``draw`` command: the mechanism's drawing at one position as DXF and SVG."""
    from mechfem.viz import export

    draw = commands.add_parser("draw", help="run a deck and write the mechanism at one position as DXF and SVG")
    draw.add_argument("deck", type=Path, metavar="DECK", help="the deck to run")
    add_outdir(draw, "DECK-stem_posN.dxf and .svg")
    draw.add_argument(
        "--position", type=position_number, default=1, metavar="N", help="the position to draw (default 1)"
    )
    draw.add_argument(
        "--format",
        type=draw_formats,
        default=None,
        metavar="FORMATS",
        help="dxf, svg or both as dxf,svg (default both, or SVG alone when ezdxf, which DXF needs, is not "
        "installed: pip install 'mechfem[dxf]')",
    )
    draw.add_argument("--no-paths", action="store_true", help="leave out the paths of the moving points")
    draw.add_argument(
        "--units",
        choices=list(export.DXF_UNITS),
        default=None,
        help="the deck's length unit, declared in the DXF file (co-ordinates are not scaled; default unitless)",
    )
    add_memory_limit(draw)
    add_quiet(draw)
    draw.set_defaults(func=cmd_draw)


def position_number(text: str) -> int:
    """``--position``: a whole number from 1."""
    try:
        n = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"not a whole number: {text!r}") from None
    if n < 1:
        raise argparse.ArgumentTypeError(f"positions are numbered from 1, not {n}")
    return n


def draw_formats(text: str) -> list[str]:
    """``--format``: formats separated by commas, each dxf or svg."""
    from mechfem.viz import export

    wanted = [f.strip().lower() for f in text.split(",") if f.strip()]
    wrong = [f for f in wanted if f not in export.FORMATS]
    if wrong or not wanted:
        raise argparse.ArgumentTypeError(f"{text!r}: give dxf, svg or dxf,svg")
    return list(dict.fromkeys(wanted))


def cmd_draw(args: argparse.Namespace) -> int:
    from mechfem.viz import export

    deck: Path = args.deck
    outdir: Path = args.outdir if args.outdir is not None else deck.parent
    console: Console = args.console
    formats: list[str] = args.format
    if formats is None:
        # Asked for nothing in particular: the SVG needs nothing more, so it is written without the DXF.
        formats = list(export.FORMATS) if export.dxf_available() else ["svg"]
        if "dxf" not in formats:
            console.note(
                "note: writing the SVG only: the DXF needs ezdxf, which is not installed (pip install "
                "'mechfem[dxf]', or pip install ezdxf)"
            )
    elif "dxf" in formats and not export.dxf_available():
        console.error(
            "error: writing DXF needs ezdxf, which is not installed: pip install 'mechfem[dxf]' (or pip install "
            "ezdxf), or ask for SVG only with --format svg"
        )
        return EXIT_FAILED
    names = [f"{deck.stem}_pos{args.position}.{fmt}" for fmt in formats]
    plan(deck, outdir, drawings=names).check()
    if optimisation(deck) is not None:
        console.note(
            f"note: {deck} is a {mode_of(deck)} deck: this drawing shows its start design; "
            "`mechfem run` optimises it and writes the final design as a deck, which `mechfem draw` draws"
        )
    with locked(outdir, deck.stem):
        result, interrupted = run_with_progress(deck, args.memory_limit, console.bar)
        console.bar.close()
        if args.position > result.positions:
            console.error(
                f"error: {deck}: --position {args.position}: the run has {count(result.positions, 'position')}, "
                f"so --position must be from 1 to {result.positions}"
            )
            return EXIT_FAILED
        files = export.draw_files(result, outdir, args.position, formats, not args.no_paths, args.units)
    console.say(f"{deck}: {count(result.positions, 'position')} computed")
    for path in files:
        console.say(f"wrote {path}")
    return exit_status(deck, result, interrupted, console)


_HINTS: dict[type[MechfemError], str] = {
    AssemblyError: "Check the co-ordinates of the elements named.",
    ConvergenceError: "Check the XMOV estimates and the PARA values: the estimates must be near a position that "
    "fits, and angles are taken as principal values in (-pi, pi].",
    LimitPositionError: "The mechanism is in a limit position, or the model cannot move as described: check the "
    "FORM destinations, NRDOF and which co-ordinates are XFIX or XMOV.",
}


def error_message(deck: Path, error: MechfemError) -> str:
    """One paragraph for a failed command."""
    if isinstance(error, DeckError):
        return str(error)
    for kind, hint in _HINTS.items():
        if isinstance(error, kind):
            return f"error: {deck}: position 1 cannot be computed: {error}. {hint}"
    return f"error: {deck}: {error}"


def main(argv: list[str] | None = None) -> int:
    """Runs the command line; returns the exit status."""
    parser = build_parser()
    args = parser.parse_args(argv)
    deck: Path = args.deck
    if "memory_limit" in args and args.memory_limit is None:
        try:
            args.memory_limit = memory_limit()
        except ValueError as e:
            parser.error(str(e))
    quiet = bool(getattr(args, "quiet", False))
    # One bar (and one way of writing lines past it) for the whole command; cleared before any error is said.
    args.console = Console(ProgressBar(show=False if quiet else None), quiet)
    try:
        try:
            # A warning of mechfem's names its deck, line and fix: said as it is, not with Python's source line.
            with warnings.catch_warnings():
                warnings.showwarning = lambda message, *_, **__: args.console.note(str(message))
                return int(args.func(args))
        finally:
            args.console.close()
    except MechfemError as e:
        print(error_message(deck, e), file=sys.stderr)
    except KeyboardInterrupt:
        print("mechfem: interrupted", file=sys.stderr)
        return EXIT_INTERRUPTED
    except OSError as e:
        where = f" {e.filename}" if e.filename else ""
        print(f"error: cannot write the output{where}: {e.strerror or e}", file=sys.stderr)
    except Exception as e:  # the command line never shows a traceback
        print(
            f"mechfem: internal error while running {deck} ({type(e).__name__}: {e}). "
            "This is a bug in mechfem; please report it together with the deck.",
            file=sys.stderr,
        )
        return EXIT_INTERNAL
    return EXIT_FAILED


if __name__ == "__main__":
    sys.exit(main())
