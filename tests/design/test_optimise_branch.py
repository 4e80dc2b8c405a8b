"""Every design of an optimisation is evaluated on the assembly branch of the start design, whatever was evaluated
before: a design's values do not depend on the order designs are evaluated in, a design whose motion jumps to the
other branch is infeasible and said so, and the final design of a synthesis evaluated afresh has the objective the
optimiser reported."""

from __future__ import annotations

import dataclasses
import os
import subprocess
from pathlib import Path

import numpy as np
import pytest

from conftest import ROOT, mechfem_command
from mechfem import _core
from mechfem.design import engine as design
from mechfem.design import optimise_deck

FOURBAR = """; a crank-rocker four-bar; variables: the frame pivot B0 (XFIX 3, 4) and the rocker length (PARA 3)
KIN OPT
TOPOLOGY
ELEM 1 BIN 1 2 5 6
     2 BIN 5 6 7 8
     3 BIN 3 4 7 8
FORM 1 LENL 1 1
     2 LENL 2 2
     3 LENL 3 3
     4 ANGB 1 4
NRDOF 1
GEOMETRY
XFIX 1 0.0
     2 0.0
     3 3.2
     4 0.0
XMOV 5 1.0
     6 0.0
     7 3.0
     8 2.4
PARA 1 1.0
     2 3.0
     3 2.5
     4 0.0
MOVEMENT
TSTEPE 36
MOV_RELE 1 6.283185307179586
OPTIMISE
VARYX 3 1.0 6.0
VARYX 4 -4.0 4.0
VARY 3 1.5 4.0
BUFX0 8 1                     ; B.y
TARGETAT 1 1 2.0
STORAGE
BUFINP 1 3
PRINTBUF 3 1
END
"""
START = [3.2, 0.0, 2.5]
MIRRORING = [1.5, 2.0, 3.5]
"""From the start design's position 1, Newton assembles this design with B mirrored about A-B0."""
JUMPING = [1.7343402713614078, 3.7876737360951287, 2.1636385787969443]
"""A design whose crank cannot turn fully: 36 steps jump over its limit position onto the other branch."""


@pytest.fixture
def deck(tmp_path: Path) -> Path:
    path = tmp_path / "fourbar.mec"
    path.write_text(FOURBAR)
    return path


def model(deck: Path) -> _core.DesignModel:
    """B.y at every position, the design variables B0 and the rocker length."""
    return _core.DesignModel(FOURBAR, os.fspath(deck), os.fspath(deck.parent), [(0, 3), (0, 4), (1, 3)], [1], [])


def orientation(d: _core.Evaluation, x: list[float]) -> float:
    """The sign of the triangle A, B, B0 at position 1: which of the dyad's two assemblies it is."""
    c = np.asarray(d.position_one)
    a, b, b0 = c[4:6], c[6:8], np.array(x[:2])
    u, v = b - a, b0 - a
    return float(np.sign(u[0] * v[1] - u[1] * v[0]))


def same(d: _core.Evaluation, e: _core.Evaluation) -> bool:
    keys = ("feasible", "reason", "positions", "position_one")
    return all(getattr(d, k) == getattr(e, k) for k in keys) and all(
        np.array_equal(np.asarray(getattr(d, k)), np.asarray(getattr(e, k))) for k in ("values", "gradient")
    )


def test_a_design_evaluated_after_a_design_on_the_other_branch_is_evaluated_on_its_own(deck: Path) -> None:
    m = model(deck)
    first = m.evaluate(START)
    mirroring = m.evaluate(MIRRORING)
    again = m.evaluate(START)
    assert first.feasible and mirroring.feasible and again.feasible
    # Bit for bit, and on the start design's branch, as a fresh model evaluates them.
    assert same(first, again)
    assert same(mirroring, model(deck).evaluate(MIRRORING))
    assert orientation(mirroring, MIRRORING) == orientation(first, START)


def test_designs_in_any_order_give_the_same_values(deck: Path) -> None:
    rng = np.random.default_rng(7)
    designs = [[rng.uniform(1.0, 6.0), rng.uniform(-4.0, 4.0), rng.uniform(1.5, 4.0)] for _ in range(40)]
    designs += [MIRRORING, JUMPING, START]
    forward = model(deck)
    seen = [forward.evaluate(x) for x in designs]
    backward = model(deck)
    order = rng.permutation(len(designs))
    for k in order:
        assert same(backward.evaluate(designs[k]), seen[k]), designs[k]
    feasible = [(d, x) for d, x in zip(seen, designs, strict=True) if d.feasible]
    assert len(feasible) > 10
    assert {orientation(d, x) for d, x in feasible} == {orientation(seen[-1], START)}


def test_a_motion_that_jumps_to_the_other_branch_is_infeasible_and_said_so(deck: Path) -> None:
    d = model(deck).evaluate(JUMPING)
    assert not d.feasible
    # A stepper that stops at the limit position itself makes the design infeasible as a motion that stops; one
    # that steps over it onto the other branch is caught by the orientation of the dyad.
    assert d.reason_kind in ("left_branch", "stopped")
    if d.reason_kind == "left_branch":
        assert d.reason == (
            "the motion changes assembly branch between positions 25 and 26: co-ordinates 7, 8 flip to their "
            "mirrored assembly (the determinant of their group in D^c changes sign: a limit position jumped over, or "
            "a change point where two branches meet)"
        )


def test_an_infeasible_start_design_makes_every_design_infeasible(deck: Path) -> None:
    m = model(deck)
    # B0 at (6, 4) is 6.4 from A, farther than coupler and rocker (3 + 1.5) reach: no position 1, so no branch.
    start = m.start_at([6.0, 4.0, 1.5])
    assert not start.feasible and start.reason_kind != "stopped"
    d = m.evaluate(START)
    assert not d.feasible and d.reason_kind == "start"
    assert d.reason == f"the start design is infeasible: {start.reason}"


def test_a_start_design_whose_motion_stops_still_sets_the_branch_of_its_position_one(deck: Path) -> None:
    m = model(deck)
    start = m.start_at(JUMPING)
    # The stepper stops at the crank's limit position instead of stepping over it.
    assert not start.feasible and start.reason_kind == "stopped"
    # Its position 1 has B on the other side of A-B0 than the deck's own design has: every design now assembles so.
    assert orientation(start, JUMPING) != orientation(model(deck).evaluate(START), START)
    d = m.evaluate(START)
    assert d.feasible and orientation(d, START) == orientation(start, JUMPING)


def test_the_start_design_chosen_sets_the_branch(deck: Path) -> None:
    m = model(deck)
    start = m.start_at(MIRRORING)
    # Assembled from the deck's co-ordinates, that start lies on the other branch than the deck's own design, and
    # so does every design evaluated after it, the deck's own included.
    d, own = m.evaluate(START), model(deck).evaluate(START)
    assert start.feasible and d.feasible and own.feasible
    assert orientation(d, START) == orientation(start, MIRRORING) == -orientation(own, START)


def test_the_report_counts_the_designs_whose_motion_changes_branch(deck: Path) -> None:
    text = FOURBAR.replace("TARGETAT 1 1 2.0", "TARGETAT 1 1 -2.0\nTARGETAT 1 10 -1.0")
    deck.write_text(text)
    opt = optimise_deck.describe(deck).optimise
    assert opt is not None
    p = optimise_deck.problem(deck, text, opt)
    s = design.solve(p)
    assert s.infeasible == sum(k for k, _ in s.reasons.values()) > 0
    lines = "\n".join(
        optimise_deck.print_lines(dataclasses.replace(s, deck=optimise_deck.DeckProblem(deck, opt, p)), None)
    )
    for kind, (n, first) in s.reasons.items():
        assert f"{n} infeasible: {optimise_deck.INFEASIBLE_KINDS[kind]} (the first: {first})" in lines
    # The optimiser meets designs whose motion jumps over a limit position: said, unless the stepper stops there.
    assert set(s.reasons) & {"left_branch", "stopped"}
    if "left_branch" in s.reasons:
        assert "the motion changes assembly branch" in s.reasons["left_branch"][1]


def test_a_synthesis_returns_the_objective_of_its_final_design_evaluated_afresh(tmp_path: Path) -> None:
    """Function generation (examples/synthesis/function.mec) optimised by ``mechfem run``, then its final design
    run as the written KIN ANA deck in a new process: the targets' sum of squares there is the objective the
    optimiser printed; and a fresh model gives the final design the optimiser's objective bit for bit."""
    for name in ("function.mec", "function.dat"):
        text = (ROOT / "examples" / "synthesis" / name).read_text()
        lines = [s for s in text.splitlines(keepends=True) if not s.lstrip().startswith(("BEGINPIC", "PLOT", "ENDPIC"))]
        (tmp_path / name).write_text("".join(lines))
    deck = tmp_path / "function.mec"
    run = [*mechfem_command(), "run"]
    p = subprocess.run([*run, str(deck), "-o", str(tmp_path / "opt")], capture_output=True, text=True)
    assert p.returncode == 0, p.stderr
    printed = (tmp_path / "opt" / "function.prt").read_text()
    final = float(printed.split("objective: start ")[1].split("final ")[1].split()[0])
    p = subprocess.run(
        [*run, str(tmp_path / "opt" / "function_opt.mec"), "-o", str(tmp_path / "again")],
        capture_output=True,
        text=True,
    )
    assert p.returncode == 0, p.stderr
    phi = np.loadtxt(tmp_path / "again" / "function_opt.csv", delimiter=",", skiprows=1)[:, 1]
    wanted = np.loadtxt(deck.parent / "function.dat")
    assert abs(float(np.sum((phi - wanted) ** 2)) - final) <= 1e-9 * final

    opt = optimise_deck.describe(deck).optimise
    assert opt is not None
    problem = optimise_deck.problem(deck, deck.read_text(), opt)
    s = design.solve(problem)
    fresh = design.Evaluator(problem)
    fresh.start_at(s.x_start)
    assert design.objective(problem, fresh(s.x))[0] == s.objective
    assert abs(s.objective - final) <= 1e-9 * final
