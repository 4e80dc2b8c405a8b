"""``mechfem run`` of a ``KIN OPT`` deck: the OPTIMISE block as a :class:`mechfem.design.engine.Problem`, solved, the
final design written as ``<stem>_opt.mec`` (mode ``KIN ANA``) and the print file's OPTIMISATION section.

The command runs the written deck as any ``KIN ANA`` deck; this module only states the problem, writes the deck
and says what the optimiser did.
"""

from __future__ import annotations

import dataclasses
import math
import os
from collections.abc import Callable, Iterable
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

import mechfem._core as _core
from mechfem._util.atomic import atomic_text
from mechfem.design import deck_synthesis, dynamic_design, frame_angle
from mechfem.design import engine as design
from mechfem.design import rules as design_rules
from mechfem.errors import MechfemError
from mechfem.model.catalogue import coordinate_dimensions, form_dimension
from mechfem.model.echo import Model
from mechfem.model.units import Units
from mechfem.results.labels import buffer_name, coordinate_units, core_input, core_value, row_unit, shown
from mechfem.results.words import count

if TYPE_CHECKING:
    from mechfem._core import DeckDescription, OptimiseBlock
    from mechfem.design.optimum import Optimum


class OptimisationError(MechfemError):
    """The optimisation cannot start: its start design is infeasible, or the OPTIMISE block asks for something
    the model cannot give. ``str()`` is the whole message, naming the deck and the line."""


def deck_mode(text: str) -> str:
    """The mode line of a deck (its first line with words, upper case, e.g. ``KIN OPT``), read without compiling
    anything; "" for a deck without words."""
    for line in text.lstrip("\ufeff").splitlines():
        words = line.split(";", 1)[0].split()
        if words:
            return " ".join(words[:2]).upper()
    return ""


def describe(deck: Path) -> DeckDescription:
    """The deck's description (its OPTIMISE block as ``optimise``)."""
    return _core.describe_deck_text(_core.read_deck_text(deck), os.fspath(deck), os.fspath(deck_dir(deck)))


def deck_dir(deck: Path) -> Path:
    return deck.parent if deck.parent != Path("") else Path(".")


def problem(deck: Path, text: str, opt: OptimiseBlock) -> design.Problem:
    """The OPTIMISE block in the engine's terms (deck numbering; positions 0-based, NaN where not compared)."""
    terms: list[design.ValuesTerm | design.AtTerm | design.ExtremumTerm] = []
    for t in opt.targets:
        if t.kind == "values":
            values = np.array([math.nan if v is None else v for v in t.values or []], dtype=np.float64)
            terms.append(design.ValuesTerm(t.buffer, values, t.weight))
        elif t.kind == "at":
            terms.append(design.AtTerm(t.buffer, (t.position or 1) - 1, t.value or 0.0, t.weight))
        else:
            terms.append(design.ExtremumTerm(t.buffer, t.reference or 0, t.value or 0.0, t.weight))
    objective = opt.objective
    periodic = [design_rules.full_turn(v.lo, v.hi) for v in opt.vary]
    if any(periodic):
        angles = angle_variables(_core.describe_deck_text(text, os.fspath(deck), os.fspath(deck_dir(deck))), opt)
        periodic = [p and a for p, a in zip(periodic, angles, strict=True)]
    masses = opt.mass_vary
    dynamic = deck_mode(text) == "DYN ANA"
    model = (dynamic_design.dynamic_deck_model if dynamic else design.deck_model)(
        text, os.fspath(deck), os.fspath(deck_dir(deck))
    )
    return design.Problem(
        model=model,
        variables=block_variables(opt),
        names=block_names(opt),
        lo=np.array([v.lo for v in opt.vary] + [m.lo for m in masses], dtype=np.float64),
        hi=np.array([v.hi for v in opt.vary] + [m.hi for m in masses], dtype=np.float64),
        terms=terms,
        bounds=[(b.buffer, b.lo, b.hi) for b in opt.bounds],
        objective=None
        if objective is None
        else (1 if objective.sense == "minimise" else -1, objective.reduce, objective.buffer),
        objective_with=None if objective is None else objective.with_buffer,
        steps=opt.steps,
        tol=opt.tol,
        stop=None if (ftol := opt.ftol) is None else design_rules.FTol(*ftol),
        periodic=periodic + [False] * len(masses) if any(periodic) else [],
    )


def angle_variables(described: DeckDescription, opt: OptimiseBlock) -> list[bool]:
    """Whether each design variable is an angle, as the catalogue says of the form parameters of its row (VARY)
    or of the elements' slots its co-ordinate fills (VARYX)."""
    types = {e.number: e.type for e in described.elements}
    rows = {r.dest: r for r in described.prescribed}
    out = []
    for v in opt.vary:
        if v.kind == 1:
            terms = rows[v.number].terms if v.number in rows else []
            out.append(bool(terms) and all(form_dimension(types[t.element], t.form) == "angle" for t in terms))
        else:
            slots = [
                k
                for e in described.elements
                for i, k in zip(e.coords, coordinate_dimensions(e.type), strict=False)
                if i == v.number
            ]
            out.append(bool(slots) and all(k == "angle" for k in slots))
    return out


def block_variables(opt: OptimiseBlock) -> list[tuple[int, int]]:
    """``(kind, number)`` of every design variable of the block: VARY and VARYX, then VARYM."""
    return [(v.kind, v.number) for v in opt.vary] + [(m.kind, m.number) for m in opt.mass_vary]


def block_names(opt: OptimiseBlock) -> list[str]:
    """The name of every design variable of the block (``PARA 5``, ``XFIX 3``, ``U 1``), in its order."""
    return [variable_name(v.kind, v.number) for v in opt.vary] + [
        dynamic_design.mass_name(m.kind, m.number) for m in opt.mass_vary
    ]


def variable_name(kind: int, number: int) -> str:
    """``PARA 5`` for a prescribed row, ``XFIX 3`` for a fixed co-ordinate."""
    return f"{'PARA' if kind == 1 else 'XFIX'} {number}"


def variable_labels(p: design.Problem, model: Model | None) -> list[tuple[str, str]]:
    """The name and unit of each design variable as the deck names them (``kappa``, ``deg``): a row's or
    co-ordinate's NAMES name, else :func:`variable_name`; the unit from its kind and the deck's UNITS ("" where
    the deck gives none). Without the model echo, the deck numbers."""
    if model is None:
        return [(name, "") for name in p.names]
    units = Units.of(model.units)
    coords = coordinate_units(model)
    out = []
    for (kind, number), fallback in zip(p.variables, p.names, strict=True):
        if kind in dynamic_design.MASS_UNITS:
            out.append((fallback, shown(dynamic_design.MASS_UNITS[kind], units)))
        elif kind not in (0, 1):
            # A frame angle or the input at a free-timed point: named by the problem, in the deck's angle unit.
            out.append((fallback, shown("rad", units)))
        elif kind == 1 and 0 < number <= len(model.prescribed):
            row = model.prescribed[number - 1]
            out.append((row.name or fallback, shown(row_unit(model, row, coords), units)))
        elif 0 < number <= len(model.coordinates):
            out.append((model.coordinates[number - 1].name or fallback, shown(coords.get(number, "length"), units)))
        else:
            out.append((fallback, ""))
    return out


def deck_scales(opt: OptimiseBlock | None, p: design.Problem) -> list[float]:
    """What each design variable's number in the optimiser is multiplied by to give it in the deck's units (1 for a
    deck without UNITS): every variable is in the core's units, a VARY, VARYX or VARYM variable, the frame angle
    (VARYFRAME) and the input at a FREETIME point alike."""
    given = [] if opt is None else [v.scale for v in opt.vary] + [m.scale for m in opt.mass_vary]
    frame = 1.0 if opt is None or opt.frame is None else opt.frame.scale
    timing = 1.0 if opt is None or opt.free_time is None else opt.free_time.scale
    out, k = [], 0
    for var in p.variables:
        kind = var[0]
        if var == frame_angle.SENTINEL:
            out.append(frame)
        elif kind in (0, 1) or kind in dynamic_design.MASS_UNITS:
            out.append(given[k] if k < len(given) else 1.0)
            k += 1
        else:
            # (2, k): the input at FREETIME point k.
            out.append(timing if kind == 2 else 1.0)
    return out


def values_line(p: design.Problem, x: Iterable[float], model: Model | None, opt: OptimiseBlock | None = None) -> str:
    """``kappa = -296.5 deg, B0.x = 0.3``: the variables' values (``x``, the optimiser's numbers) by name, in the
    deck's units."""
    labels = variable_labels(p, model)
    return ", ".join(
        f"{name} = {v * f:.10g}" + (f" {unit}" if unit and unit != "-" else "")
        for (name, unit), v, f in zip(labels, x, deck_scales(opt, p), strict=True)
    )


def iteration_line(it: design.Iteration) -> str:
    """One line of progress on standard error."""
    return (
        f"  iteration {it.number}: objective {it.objective:.4g}, largest violation {it.violation:.3g}, "
        f"step {it.step:.2g}, {count(it.runs, 'run')}"
    )


@dataclass
class DeckProblem:
    """A deck's OPTIMISE block as the engine solves it: the deck, the block as read, the engine's problem (deck
    numbering, the core's units) and how FREETIME, FULLROT and VARYFRAME write the final design."""

    path: Path
    block: OptimiseBlock
    problem: design.Problem
    synthesis: deck_synthesis.Synthesis | None = None


def stated(optimum: Optimum) -> DeckProblem:
    """The deck's problem of a deck's optimum; a ValueError for an optimum of :func:`mechfem.optimize`, which has
    no deck (its mechanism is the design found)."""
    if optimum.deck is None:
        raise ValueError("this is an optimum of mechfem.optimize, not of a deck's OPTIMISE block: it has no deck")
    return optimum.deck


def unreached(optimum: Optimum) -> tuple[float, int] | None:
    """The largest difference of a deck's target from its value and that target's line, when some target is missed
    by more than 1e-6 of its size; None when every target is met."""
    deck = stated(optimum)
    worst: tuple[float, int] | None = None
    for t, term, (d, _) in zip(deck.block.targets, deck.problem.terms, optimum.misses, strict=True):
        size = np.nanmax(np.abs(term.values)) if isinstance(term, design.ValuesTerm) else abs(term.value)
        if d > 1e-6 * max(1.0, float(size)) and (worst is None or d > worst[0]):
            worst = (d, t.line)
    return worst


def missed_value(optimum: Optimum, missed: tuple[float, int], model: Model | None) -> str:
    """The largest difference :func:`unreached` gives, in the units of its target's buffer."""
    buffer = next((t.buffer for t in stated(optimum).block.targets if t.line == missed[1]), 0)
    return core_value(model, buffer, missed[0], ".4g")


def optimise(deck: Path, opt: OptimiseBlock, report: Callable[[design.Iteration], object] | None = None) -> Optimum:
    """Solves the deck's OPTIMISE block from its own design; raises :class:`OptimisationError` when it cannot
    start. The optimum's ``deck`` holds the problem solved; it has no mechanism (:func:`write_design_deck` writes
    the final design)."""
    text = _core.read_deck_text(deck)
    try:
        syn = deck_synthesis.synthesis(deck, opt, problem(deck, text, opt))
    except deck_synthesis.SynthesisError as e:
        raise OptimisationError(str(e)) from None
    p = syn.problem
    try:
        optimum = design.solve(p, report=report)
    except design.Infeasible as e:
        raise OptimisationError(
            f"error: {deck}: the optimisation (OPTIMISE, line {opt.line}) cannot start: {e}. The start design "
            f"is the deck's own (the PARA and XFIX values of the variables, {names_and_lines(opt)}): change it, or "
            "its XMOV estimates, so that position 1 can be assembled and the whole motion run."
        ) from None
    except design.NonFiniteObjective as e:
        objective = opt.objective
        if e.term is not None:
            line = opt.targets[e.term].line
        else:
            line = opt.line if objective is None else objective.line
        raise OptimisationError(
            f"error: {deck}: line {line}: {e}; bring the values asked for and the weights nearer to what the "
            "mechanism's buffers can take, in consistent units"
        ) from None
    except ValueError as e:
        raise OptimisationError(
            f"error: {deck}: the OPTIMISE block (line {opt.line}) cannot be evaluated: {e}."
        ) from None
    return dataclasses.replace(optimum, deck=DeckProblem(deck, opt, p, syn))


def names_and_lines(opt: OptimiseBlock) -> str:
    keyword = {0: "VARYX", 1: "VARY"}
    named = [f"{variable_name(v.kind, v.number)} ({keyword[v.kind]} on line {v.line})" for v in opt.vary]
    named += [f"{m.item} {m.number} (VARYM on line {m.line})" for m in opt.mass_vary]
    if frame := opt.frame:
        named.append(f"the frame angle (VARYFRAME on line {frame.line})")
    return ", ".join(named)


def write_design_deck(optimum: Optimum, outdir: Path) -> Path:
    """Writes a deck's final design as ``<outdir>/<stem>_opt.mec`` (mode KIN ANA): the PARA and XFIX values of the
    variables and the XMOV estimates (the final design's position 1) replaced, MOV_FUNC files named from there."""
    deck, final = stated(optimum), optimum.x
    variables, x = deck.problem.variables, final
    if deck.synthesis is not None:
        variables, x = deck.synthesis.written(final)
        # The mass model's variables (DYN ANA) are written as they are.
        masses = [(k, v) for k, v in enumerate(deck.problem.variables) if v[0] in dynamic_design.MASS_UNITS]
        variables = [*variables, *(v for _, v in masses)]
        x = np.append(x, [final[k] for k, _ in masses])
    return write_design(deck.path, variables, x, optimum.position_one, outdir)


def write_design(
    deck: Path, variables: list[tuple[int, int]], x: np.ndarray, position_one: list[float], outdir: Path
) -> Path:
    """Writes the design ``x`` of ``variables`` as ``<outdir>/<stem>_opt.mec``; ``position_one`` (deck order, may
    be empty) replaces the XMOV estimates."""
    described = describe(deck)
    moving = {c.number for c in described.coordinates if c.moving}
    masses = [(k, n, float(v)) for (k, n), v in zip(variables, x, strict=True) if k >= 10]
    rows = [(n, float(v)) for (k, n), v in zip(variables, x, strict=True) if k == 1]
    coords = [(n, float(v)) for (k, n), v in zip(variables, x, strict=True) if k == 0]
    coords += [(i + 1, float(v)) for i, v in enumerate(position_one) if i + 1 in moving]
    outdir.mkdir(parents=True, exist_ok=True)
    source = deck_dir(deck).resolve()
    file_dir = None if source == outdir.resolve() else Path(os.path.relpath(source, outdir.resolve()))
    text = _core.read_deck_text(deck)
    if masses:
        text = _core.deck_with_masses(text, os.fspath(deck), masses)
    text = _core.optimised_deck_text(text, os.fspath(deck), rows, coords, file_dir)
    path = outdir / f"{deck.stem}_opt.mec"
    with atomic_text(path) as f:
        f.write(text)
    return path


def print_lines(s: Optimum, written: Path | None, model: Model | None = None) -> list[str]:
    """The print file's OPTIMISATION section of a deck's optimum; the variables named as ``model`` (the final
    design's echo) names them."""
    deck = stated(s)
    p, block = deck.problem, deck.block
    out = ["OPTIMISATION", f"  method: {s.method}; OPTIMISE block at line {block.line}"]
    out += history_lines(s.history)
    out += [
        "",
        "  design variables:",
        f"  {'variable':>10} {'unit':>6} {'start':>18} {'final':>18} {'lower':>14} {'upper':>14}",
    ]
    labels = variable_labels(p, model)
    scales = deck_scales(block, p)
    for (name, unit), x0, x, lo, hi, f in zip(labels, s.x_start, s.x, p.lo, p.hi, scales, strict=True):
        out.append(f"  {name:>10} {unit:>6} {x0 * f:>18.12g} {x * f:>18.12g} {lo * f:>14.8g} {hi * f:>14.8g}")
    out += [
        "",
        f"  objective: start {s.start_objective:.10g}, final {s.objective:.10g}",
        f"  {count(s.runs, 'mechanism run')} in {s.seconds:.3g} s"
        + (f" ({s.infeasible} of them met an infeasible design and were stepped back from)" if s.infeasible else ""),
    ]
    out += infeasible_lines(s)
    out.append(f"  {'converged' if s.success else 'did not converge'}: {s.message}")
    if s.extrema:
        out += ["", "  targets at extrema, at the final design:"]
        for t, at, value in s.extrema:
            out.append(
                f"    {buffer_name(model, t.buffer)} at an extremum of {buffer_name(model, t.reference)}, "
                f"{core_input(model, 1, at)}: {core_value(model, t.buffer, value, '.6e')} "
                f"(target {core_value(model, t.buffer, t.value)})"
            )
    # A TARGETEXT whose reference has no extremum along the motion adds nothing to the objective: said here.
    found = {id(t) for t, _, _ in s.extrema}
    for term in p.terms:
        if isinstance(term, design.ExtremumTerm) and id(term) not in found:
            out.append(
                f"  TARGETEXT {term.buffer} {term.reference}: buffer {term.reference} has no extremum along the motion "
                "at the final design, so this target contributes nothing to the objective"
            )
    if block.targets:
        out += ["", "  targets at the final design (the largest difference from the value asked for):"]
        for target, (d, k) in zip(block.targets, s.misses, strict=True):
            where = f" at position {k + 1}" if k is not None else ""
            kw = {"values": "TARGET", "at": "TARGETAT", "extremum": "TARGETEXT"}[target.kind]
            b = target.buffer
            out.append(f"  {kw} on line {target.line} ({buffer_name(model, b)}): {core_value(model, b, d)}{where}")
    if written is not None:
        mode = deck_mode(written.read_text(encoding="utf-8"))
        out.append(f"  final design: {written.name} (mode {mode}); the model and tables above are its run")
    return [*out, ""]


INFEASIBLE_KINDS = {
    "other_branch": "position 1 only on another assembly branch than the start design's",
    "left_branch": "the motion changes assembly branch",
    "stopped": "the motion stops",
    "position_one": "position 1 cannot be computed",
    "extrema": "another number of extrema",
}


def infeasible_lines(s: Optimum) -> list[str]:
    """The infeasible designs met, by kind of reason, each with the first one's reason. Every design, the final one
    included, is evaluated on the start design's assembly branch; one that cannot be is among these."""
    out = []
    for kind, (n, first) in s.reasons.items():
        out.append(f"    {n} infeasible: {INFEASIBLE_KINDS.get(kind, kind)} (the first: {first})")
    return out


def history_lines(history: list[design.Iteration]) -> list[str]:
    out = [f"  {'iteration':>9} {'objective':>18} {'violation':>12} {'step':>12} {'runs':>6}"]
    for it in history:
        out.append(f"  {it.number:>9} {it.objective:>18.10e} {it.violation:>12.4g} {it.step:>12.4g} {it.runs:>6}")
    return out


def interrupted_lines(
    deck: Path, opt: OptimiseBlock, history: list[design.Iteration], written: Path | None
) -> list[str]:
    """The print file of an optimisation stopped by Ctrl-C: the history so far, and the design it had reached."""
    from mechfem._version import __version__

    out = [f"mechfem {__version__} - print file", f"deck: {deck}", "", "OPTIMISATION (interrupted)"]
    out.append(f"  OPTIMISE block at line {opt.line}; variables: {names_and_lines(opt)}")
    out += history_lines(history)
    if written is None or not history:
        return [*out, "", "  interrupted by Ctrl-C before the first iteration: no design was written", ""]
    out += ["", "  design reached at the last iteration:"]
    names = block_names(opt)
    for name, x in zip(names, history[-1].x, strict=False):
        out.append(f"  {name:>10} {x:>18.12g}")
    return [*out, "", f"  interrupted by Ctrl-C: that design is written as {written.name} (mode KIN ANA)", ""]


def write_interrupted(deck: Path, opt: OptimiseBlock, history: list[design.Iteration], outdir: Path) -> list[Path]:
    """Writes the history so far and, once there is an iteration, the design it reached as ``<stem>_opt.mec``."""
    outdir.mkdir(parents=True, exist_ok=True)
    written: Path | None = None
    if history:
        variables = block_variables(opt)
        written = write_design(deck, variables, history[-1].x[: len(variables)], [], outdir)
    path = outdir / f"{deck.stem}.prt"
    with atomic_text(path) as f:
        f.write("\n".join(interrupted_lines(deck, opt, history, written)) + "\n")
    return [path] if written is None else [written, path]
