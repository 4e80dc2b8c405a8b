"""Limit positions, free motion and transfer quality (theory, section 5.5): the decks of examples/limits
checked against closed forms derived here, and the messages and print-file sections that report them.

Deck constants are repeated here on purpose: a change to a deck that is not made here too fails its test.
"""

from __future__ import annotations

import csv
import math
import re
from functools import cache
from pathlib import Path

import numpy as np
import numpy.typing as npt
import pytest

import mechfem
from conftest import ROOT, Cli

Array = npt.NDArray[np.float64]

LIMITS = ROOT / "examples" / "limits"

#: A located limit position against its closed form.
LOCATED = 1e-8


@cache
def run(name: str) -> mechfem.RunResult:
    """The example ``examples/limits/<name>.mec``, run once per test session."""
    return mechfem.run_deck(LIMITS / f"{name}.mec")


def flat(text: str) -> str:
    """``text`` with every run of white space made one blank, so wrapped paragraphs can be searched."""
    return " ".join(text.split())


def point(x: Array, i: int) -> Array:
    """The point whose x is co-ordinate ``i`` (deck numbering) and whose y is co-ordinate ``i + 1``."""
    return np.asarray(x[..., i - 1 : i + 1])


def distance(p: Array, q: Array) -> Array:
    return np.asarray(np.hypot(*(q - p).T))


def passed(result: mechfem.RunResult) -> list[mechfem.Limit]:
    return [limit for limit in result.report.limits if limit.kind == "passed"]


def det_changes_sign_at(result: mechfem.RunResult, limit: mechfem.Limit) -> bool:
    """det(D^c) has opposite signs at the two positions that enclose ``limit``."""
    return bool(result.det[limit.after - 1] * result.det[limit.after] < 0.0)


def suggested_free_motion(message: str) -> tuple[str, float]:
    """The ``MOV_FREE j ds`` line a stop message suggests, and its ds."""
    match = re.search(r"`(MOV_FREE 1 (\S+))`", message)
    assert match, message
    return match.group(1), float(match.group(2))


# Non-Grashof four-bar: free motion traces the whole coupler curve -------------------------------

# examples/limits/nongrashof.mec: crank a, coupler b, rocker c, frame d; K at (u, v) in the coupler's frame.
NG_A, NG_B, NG_C, NG_D, NG_U, NG_V = 1.5, 1.2, 1.4, 2.0, 0.6, 0.5
NG_STEPS, NG_DS = 901, 0.02
# The crank's limits: coupler and rocker stretched in line, |A B0| = b + c. (The folded variant,
# |A B0| = |b - c| = 0.2, is out of the crank's reach: |a - d| = 0.5.)
NG_LIMIT = math.acos((NG_A**2 + NG_D**2 - (NG_B + NG_C) ** 2) / (2 * NG_A * NG_D))


def test_nongrashof_is_non_grashof_and_its_crank_limits_exist() -> None:
    lengths = sorted([NG_A, NG_B, NG_C, NG_D])
    assert lengths[0] + lengths[3] > lengths[1] + lengths[2]
    assert abs(NG_A - NG_D) > abs(NG_B - NG_C)
    assert 0.0 < NG_LIMIT < math.pi


def test_nongrashof_every_position_satisfies_the_constraints() -> None:
    r = run("nongrashof")
    assert r.report.complete and r.positions == NG_STEPS + 1
    x = r.coords
    a0, b0, a, b, k = point(x, 1), point(x, 3), point(x, 5), point(x, 7), point(x, 9)
    np.testing.assert_allclose(distance(a0, a), NG_A, atol=1e-9)
    np.testing.assert_allclose(distance(a, b), NG_B, atol=1e-9)
    np.testing.assert_allclose(distance(b0, b), NG_C, atol=1e-9)
    e = (b - a) / NG_B
    n = np.stack([-e[:, 1], e[:, 0]], axis=1)
    np.testing.assert_allclose(np.einsum("ij,ij->i", k - a, e), NG_U, atol=1e-9)
    np.testing.assert_allclose(np.einsum("ij,ij->i", k - a, n), NG_V, atol=1e-9)
    # Each step moves ds along the tangent, then the correction: the co-ordinates move about ds.
    steps = np.linalg.norm(np.diff(x[:, 4:10], axis=0), axis=1)
    np.testing.assert_allclose(steps, NG_DS, rtol=0.1)
    assert float(np.mean(steps)) == pytest.approx(NG_DS, rel=0.01)


def test_nongrashof_coupler_curve_is_one_closed_curve() -> None:
    r = run("nongrashof")
    x = r.coords[:, 4:10]  # every moving co-ordinate
    start = x[0]
    gap = np.linalg.norm(x - start, axis=1)
    half = len(gap) // 2
    back = half + int(np.argmin(gap[half:]))
    # One loop is just exceeded: the mechanism comes back a few steps before the last position ...
    assert 0 < len(gap) - 1 - back <= 3
    assert gap[back] < NG_DS

    # ... and passes through its first position: the start lies on the chord into or out of ``back``.
    def off_chord(p: Array, q: Array) -> float:
        t = float(np.clip((start - p) @ (q - p) / ((q - p) @ (q - p)), 0.0, 1.0))
        return float(np.linalg.norm(p + t * (q - p) - start))

    assert min(off_chord(x[back - 1], x[back]), off_chord(x[back], x[back + 1])) < 1e-5
    # The coupler point never came near its start in between: one curve, traced once.
    k = r.coords[:, 8:10]
    assert np.min(np.linalg.norm(k[20 : back - 20] - k[0], axis=1)) > 5 * NG_DS


def test_nongrashof_crank_passes_both_closed_form_limits() -> None:
    r = run("nongrashof")
    beta1 = r.buffers[1]
    assert np.all(np.abs(beta1) <= NG_LIMIT + 1e-9)
    limits = passed(r)
    assert len(limits) == 2 and len(r.report.limits) == 2
    got = sorted(limit.inputs[0] for limit in limits)
    assert got == pytest.approx([-NG_LIMIT, NG_LIMIT], abs=LOCATED)
    for limit in limits:
        assert abs(limit.det) < 1e-12
        assert det_changes_sign_at(r, limit)
        # At a limit coupler and rocker lie in line: A is b + c away from B0.
        c = np.asarray(limit.coords)
        assert float(distance(point(c, 5), point(c, 3))) == pytest.approx(NG_B + NG_C, abs=LOCATED)
    # Transfer functions exist at every position computed: no NaN anywhere.
    assert r.report.singular_positions == []
    assert not any(np.isnan(b).any() for b in r.buffers.values())


def test_nongrashof_print_file_lists_the_limit_positions(cli: Cli, tmp_path: Path) -> None:
    proc = cli("run", LIMITS / "nongrashof.mec", "-o", tmp_path)
    assert proc.returncode == 0, proc.stderr
    text = flat((tmp_path / "nongrashof.prt").read_text())
    section = text[text.index("LIMIT POSITIONS") :]
    for limit in passed(run("nongrashof")):
        where = f"between positions {limit.after} and {limit.after + 1}"
        assert f"{where}: free motion passes a limit position of the input of DOF 1 (row 6: beta1)" in section
        assert f"beta1 = {limit.inputs[0]:.12g} rad" in section
        assert "limit position: free motion passes" in proc.stdout and where in proc.stdout
    listed = [float(v) for v in re.findall(r"beta1 = (\S+) rad,", section)]
    assert sorted(listed) == pytest.approx([-NG_LIMIT, NG_LIMIT], abs=LOCATED)
    assert "co-ordinates there:" in section
    assert "positions without transfer functions" not in section
    assert not (tmp_path / "nongrashof.notes.txt").exists()
    assert "nan" not in (tmp_path / "nongrashof.csv").read_text()


@pytest.mark.filterwarnings("ignore::mechfem.IncompleteRunWarning")  # the motion stops on purpose
def test_nongrashof_driven_by_its_crank_stops_at_its_limit(tmp_path: Path) -> None:
    deck = tmp_path / "driven.mec"
    deck.write_text(
        (LIMITS / "nongrashof.mec")
        .read_text()
        .replace("TSTEPE 901", "TSTEPE 30")
        .replace("MOV_FREE 1 0.02", "MOV_RELE 1 3.0")
    )
    r = mechfem.run_deck(deck)
    stop = r.report.stop
    assert stop is not None and stop.limit is not None and stop.limit.kind == "input_limit"
    assert stop.limit.inputs[0] == pytest.approx(NG_LIMIT, abs=LOCATED)
    reason = flat(r.report.stop_reason() or "")
    assert f"reached its limit position at beta1 = {stop.limit.inputs[0]:.12g} rad" in reason
    assert "kept in the result" in reason
    line, ds = suggested_free_motion(reason)
    assert ds > 0.0  # the crank was turning forward


# Stephenson-2 six-bar: det(D^c) against eq. 5.40 ------------------------------------------------


def eq_5_40(x: Array) -> Array:
    """det(D^c) of the Stephenson-2 mechanism (theory eq. 5.40) from its co-ordinates (positions x N).

    Co-ordinates: A0 1-2, F0 3-4, A 5-6, B 7-8, C 9-10, D 11-12, E 13-14; bars 1 A0A, 2 AB, 3 AC, 4 BD,
    5 CE, 6 F0D, 7 F0E.
    """
    a0, f0, a, b, c, d, e = (point(x, i) for i in (1, 3, 5, 7, 9, 11, 13))

    def polar(p: Array, q: Array) -> tuple[Array, Array]:
        v = q - p
        return np.hypot(v[:, 0], v[:, 1]), np.arctan2(v[:, 1], v[:, 0])

    l1, _ = polar(a0, a)
    l2, b2 = polar(a, b)
    l3, b3 = polar(a, c)
    _, b4 = polar(b, d)
    _, b5 = polar(c, e)
    l6, b6 = polar(f0, d)
    l7, b7 = polar(f0, e)
    return np.asarray(
        np.sin(b4 - b6) * np.sin(b3 - b5) / (l1 * l2 * l7) - np.sin(b5 - b7) * np.sin(b2 - b4) / (l1 * l3 * l6)
    )


def test_stephenson_turns_fully_and_det_follows_eq_5_40() -> None:
    r = run("stephenson")
    assert r.report.complete and r.positions == 73
    assert r.buffers[1][-1] - r.buffers[1][0] == pytest.approx(2 * math.pi, abs=1e-12)
    closed = eq_5_40(r.coords)
    # Row order and co-ordinate order fix one overall sign, taken at position 1.
    sign = np.sign(r.buffers[2][0] / closed[0])
    np.testing.assert_allclose(r.buffers[2], sign * closed, rtol=0, atol=1e-10 * (1 + np.max(np.abs(closed))))
    assert np.array_equal(r.buffers[2], r.det)
    # The two fixed angles stay fixed.
    for b in (3, 4):
        np.testing.assert_allclose(r.buffers[b], r.buffers[b][0], atol=1e-10)
    assert r.report.limits == [] and r.report.warnings == []


def test_stephenson_print_file_reports_transfer_quality(tmp_path: Path) -> None:
    r = run("stephenson")
    from mechfem.output.files import print_file_lines

    text = flat("\n".join(print_file_lines(r)))
    k = int(np.argmin(np.abs(r.det)))
    assert f"smallest at position {k + 1}" in text
    assert "no limit position met" in text


# Stephenson-2 with a lengthened fixed link: two limit positions of the crank --------------------

ST_F0 = 7.0  # x of F0 in stephenson_limits.mec


@pytest.mark.filterwarnings("ignore::mechfem.IncompleteRunWarning")  # the motion stops on purpose
def test_stephenson_limits_driven_run_stops_at_the_first_limit(cli: Cli, tmp_path: Path) -> None:
    proc = cli("run", LIMITS / "stephenson_limits.mec", "-o", tmp_path)
    assert proc.returncode == 3
    r = run("stephenson_limits")
    stop = r.report.stop
    assert stop is not None and stop.limit is not None and stop.limit.kind == "input_limit"
    k = stop.last_good
    assert r.positions == k and stop.limit.after == k
    # The crank turned forward from 90 degrees and stopped before its limit; eq. 5.40 vanishes there.
    limit = stop.limit.inputs[0]
    assert r.buffers[1][-1] < limit < stop.inputs[0]
    assert abs(float(eq_5_40(np.asarray([stop.limit.coords]))[0])) < LOCATED
    message = flat(proc.stderr)
    prt = flat((tmp_path / "stephenson_limits.prt").read_text())
    for text in (message, prt[prt.index("MOTION STOPPED") :]):
        assert f"The motion stopped after position {k} of 73" in text
        assert f"the input of DOF 1 (row 10: beta1) reached its limit position at beta1 = {limit:.12g} rad" in text
        assert f"between positions {k} and {k + 1}" in text
        assert f"Positions 1 to {k} were computed and are all written" in text
        assert "`MOV_FREE 1 " in text
    section = prt[prt.index("LIMIT POSITIONS") : prt.index("MOTION STOPPED")]
    assert f"between positions {k} and {k + 1}: the input of DOF 1 (row 10: beta1) reaches its limit" in section
    with (tmp_path / "stephenson_limits.csv").open() as f:
        assert len(list(csv.reader(f))) == 1 + k


@pytest.mark.filterwarnings("ignore::mechfem.IncompleteRunWarning")  # the motion stops on purpose
def test_stephenson_limits_suggested_free_motion_passes_both_limits(tmp_path: Path) -> None:
    driven = run("stephenson_limits")
    line, ds = suggested_free_motion(driven.report.stop_reason() or "")
    assert ds > 0.0
    deck = tmp_path / "stephenson_free.mec"
    deck.write_text((LIMITS / "stephenson_limits.mec").read_text().replace("MOV_RELE 1 6.283185307179586", line))
    r = mechfem.run_deck(deck)
    assert r.report.complete, r.report.stop_reason()
    limits = passed(r)
    values = [limit.inputs[0] for limit in limits]
    assert len(limits) >= 2
    # The crank turns back at the limit the driven run found, then at its mirror image: |A F0| depends
    # on cos(beta1) only, so both limits are where A is as far from F0 as the chain reaches.
    first = driven.report.stop.limit.inputs[0]  # type: ignore[union-attr]
    assert values[0] == pytest.approx(first, abs=LOCATED)
    assert values[1] == pytest.approx(-first, abs=LOCATED)
    reach = [float(distance(point(np.asarray(lm.coords), 5), np.array([ST_F0, 0.0]))) for lm in limits]
    assert max(reach) - min(reach) < LOCATED
    a = point(r.coords, 5)
    assert np.max(distance(a, np.array([ST_F0, 0.0]))) <= reach[0] + 1e-9
    for limit in limits:
        assert det_changes_sign_at(r, limit)
        assert abs(float(eq_5_40(np.asarray([limit.coords]))[0])) < LOCATED
    assert np.all(np.abs(r.buffers[1]) <= abs(first) + 1e-9)


# Slider-crank driven by its slider: the dead centres ----------------------------------------------

# examples/limits/slider_dead_centre*.mec: crank a, connecting rod b, no offset.
SC_A, SC_B = 1.0, 3.0
SC_FAR, SC_NEAR = SC_B + SC_A, SC_B - SC_A  # xB at the dead centres: stretched and folded


@pytest.mark.filterwarnings("ignore::mechfem.IncompleteRunWarning")  # the motion stops on purpose
def test_slider_driven_stops_at_the_dead_centre(cli: Cli, tmp_path: Path) -> None:
    proc = cli("run", LIMITS / "slider_dead_centre.mec", "-o", tmp_path)
    assert proc.returncode == 3
    r = run("slider_dead_centre")
    stop = r.report.stop
    assert stop is not None and stop.limit is not None and stop.limit.kind == "input_limit"
    assert stop.limit.inputs[0] == pytest.approx(SC_FAR, abs=LOCATED)
    assert abs(stop.limit.det) < 1e-12
    # Crank and rod in line along the x axis.
    c = np.asarray(stop.limit.coords)
    assert c[2:5] == pytest.approx([SC_A, 0.0, SC_FAR], abs=1e-7)
    k = stop.last_good
    assert r.positions == k == 13
    assert np.all(r.buffers[1] < SC_FAR)
    message = flat(proc.stderr)
    assert "the input of DOF 1 (row 3: s) reached its limit position at s = 4," in message
    assert f"between positions {k} and {k + 1}" in message
    assert f"Positions 1 to {k} were computed and are all written to the output files" in message
    line, ds = suggested_free_motion(message)
    # ds: about the co-ordinate step of the driven run, in the direction the slider was driven.
    moved = np.linalg.norm(np.diff(r.coords[:, 2:5], axis=0), axis=1)
    assert ds == pytest.approx(float(np.mean(moved)), rel=0.05)
    prt = flat((tmp_path / "slider_dead_centre.prt").read_text())
    assert line in prt[prt.index("MOTION STOPPED") :]


def test_slider_free_motion_passes_both_dead_centres_and_turns_the_crank(cli: Cli, tmp_path: Path) -> None:
    r = run("slider_dead_centre_free")
    assert r.report.complete
    x_b, beta1 = r.buffers[1], r.buffers[2]
    assert np.all((x_b >= SC_NEAR - 1e-9) & (x_b <= SC_FAR + 1e-9))
    limits = passed(r)
    assert [limit.inputs[0] for limit in limits] == pytest.approx([SC_FAR, SC_NEAR], abs=LOCATED)
    for limit in limits:
        assert det_changes_sign_at(r, limit)
    # The crank keeps turning one way through both dead centres: a full revolution and a little more.
    assert np.all(np.diff(beta1) < 0.0)
    assert beta1[0] - beta1[-1] > 2 * math.pi
    # Every position satisfies the constraints.
    x = r.coords
    np.testing.assert_allclose(distance(point(x, 1), point(x, 3)), SC_A, atol=1e-9)
    np.testing.assert_allclose(distance(point(x, 3), point(x, 5)), SC_B, atol=1e-9)
    proc = cli("run", LIMITS / "slider_dead_centre_free.mec", "-o", tmp_path)
    assert proc.returncode == 0, proc.stderr
    assert proc.stdout.count("limit position: free motion passes a limit position of the input of DOF 1") == 2


def test_free_motion_from_a_dead_centre_writes_nan_only_there(cli: Cli, tmp_path: Path) -> None:
    # Position 1 exactly at the stretched dead centre: D^c is singular there.
    text = (LIMITS / "slider_dead_centre_free.mec").read_text()
    for old, new in (
        ("XMOV 3 0.5", "XMOV 3 1.0"),
        ("     4 0.866", "     4 0.0"),
        ("     5 3.372", "     5 4.0"),
        ("PARA 1 1.0\n     2 3.0\n     3 3.3722813232690143", "PARA 1 1.0\n     2 3.0\n     3 4.0"),
    ):
        assert old in text
        text = text.replace(old, new)
    deck = tmp_path / "deck" / "dead_centre.mec"
    deck.parent.mkdir()
    deck.write_text(text)
    r = mechfem.run_deck(deck)
    assert r.report.complete
    assert r.report.singular_positions == [1]
    assert np.isnan(r.buffers[3][0]) and not np.isnan(r.buffers[3][1:]).any()
    assert [limit.inputs[0] for limit in passed(r)] == pytest.approx([SC_NEAR, SC_FAR], abs=LOCATED)

    proc = cli("run", deck, "-o", tmp_path / "out")
    assert proc.returncode == 0, proc.stderr
    with (tmp_path / "out" / "dead_centre.csv").open() as f:
        header, *rows = list(csv.reader(f))
    nan_cells = [(k + 1, header[c]) for k, row in enumerate(rows) for c, v in enumerate(row) if v == "nan"]
    assert nan_cells == [(1, "3 dtheta/ds")]
    notes = flat((tmp_path / "out" / "dead_centre.notes.txt").read_text())
    assert "column 3 (BUFKE1 -1 1) holds nan at position 1 and nowhere else" in notes
    assert "D^c is singular at position 1" in notes
    prt = flat((tmp_path / "out" / "dead_centre.prt").read_text())
    assert "positions without transfer functions: 1" in prt
    assert "Buffer 3 (BUFKE1 -1 1), made from them, holds NaN there" in prt
    assert "D^c is singular at position 1" in proc.stderr

    # A check computes position 1 as the run does: a free motion may start in a limit position ...
    proc = cli("check", deck)
    assert proc.returncode == 0, proc.stderr
    assert "position 1 is a limit position of the input" in proc.stdout
    assert mechfem.check_deck(deck).det == 0.0
    # ... a driven one cannot: the slider's position does not fix the crank there.
    driven = deck.with_name("driven.mec")
    driven.write_text(text.replace("MOV_FREE 1 0.05", "MOV_RELE 1 -0.5"))
    with pytest.raises(mechfem.LimitPositionError) as info:
        mechfem.check_deck(driven)
    assert info.value.coords == [4]


# Position 1 with a singular D^c: mechfem check names the rows and co-ordinates --------------------


def test_check_names_a_superfluous_row_that_conflicts_with_fixed_points(cli: Cli, tmp_path: Path) -> None:
    # Row 3 is the length of a bar between the two fixed points, prescribed longer than their distance.
    deck = tmp_path / "superfluous.mec"
    deck.write_text((ROOT / "tests" / "decks" / "superfluous.mec").read_text() + "PARA 3 4.5\n")
    proc = cli("check", deck)
    assert proc.returncode == 1
    message = flat(proc.stderr)
    assert "position 1 cannot be computed" in message
    assert "prescribed row 3 is superfluous" in message
    assert "Traceback" not in proc.stderr
    with pytest.raises(mechfem.LimitPositionError) as info:
        mechfem.check_deck(deck)
    assert info.value.rows == [3]


def test_check_names_the_coordinates_a_missing_constraint_leaves_free(cli: Cli, tmp_path: Path) -> None:
    # Row 3 repeats the crank's length instead of the rocker's: B and K can swing about A.
    deck = tmp_path / "missing.mec"
    text = (LIMITS / "nongrashof.mec").read_text()
    deck.write_text(text.replace("     3 LENL 3 3", "     3 LENL 1 3").replace("     3 1.4\n", "     3 1.5\n"))
    proc = cli("check", deck)
    assert proc.returncode == 1
    message = flat(proc.stderr)
    assert "prescribed rows 1, 3 are linearly dependent" in message
    coords = re.search(r"co-ordinates ([\d, ]+)(?: \([^)]*\))? can move", message)
    assert coords, message
    assert sorted(int(c) for c in coords.group(1).split(", ")) == [7, 8, 9, 10]
    with pytest.raises(mechfem.LimitPositionError) as info:
        mechfem.check_deck(deck)
    assert sorted(info.value.coords) == [7, 8, 9, 10] and sorted(info.value.rows) == [1, 3]


# Stop messages in general ---------------------------------------------------------------------------


def test_stop_message_of_a_two_dof_motion_suggests_no_free_motion() -> None:
    stop = mechfem.Stop(5, [1.0, 2.0], [0.9, 1.9], "no_convergence", "Newton iteration did not converge", None)
    text = stop.describe(11, ["row 5: ANGB(1)", "row 6: ANGB(2)"], 0.1, written=True)
    assert "after position 5 of 11" in text and "input 2 = 1.9" in text
    assert "Positions 1 to 5 were computed and are all written to the output files" in text
    assert "`MOV_FREE" not in text and "needs a mechanism with one degree of freedom" in text


def test_stop_message_of_free_motion_suggests_a_smaller_step() -> None:
    stop = mechfem.Stop(5, [], [0.9], "no_convergence", "Newton iteration did not converge", None)
    text = stop.describe(11, ["row 5: ANGB(1)"], 0.1)
    assert "the free-motion step from input 1 = 0.9 failed" in text
    assert "smaller ds in MOV_FREE" in text and "kept in the result" in text


def test_stop_message_suggests_free_motion_in_the_driven_direction() -> None:
    stop = mechfem.Stop(5, [1.0], [1.1], "branch_jump", "the correction went farther", None)
    assert "`MOV_FREE 1 -0.12`" in stop.describe(11, ["row 5: ANGB(1)"], 0.1234)


# A four-bar that just fails to turn: the motion stops at its limit whatever the step ----------------

# examples/limits/locked_fourbar.mec: frame, crank, coupler, rocker; the crank starts at LK_START.
LK_DIMS = (70.0, 20.0, 50.0, 39.996)
LK_START = math.radians(2.5)


def lock_angle(r1: float, r2: float, r3: float, r4: float) -> float:
    """The crank angle at which coupler and rocker lie stretched in line: |A B0| = r3 + r4."""
    return math.acos((r1**2 + r2**2 - (r3 + r4) ** 2) / (2 * r1 * r2))


def fourbar_closed_form(dims: tuple[float, ...], theta: Array) -> Array:
    """A and B (columns ax, ay, bx, by) at crank angles ``theta``, B to the left of A -> B0."""
    r1, r2, r3, r4 = dims
    a = np.stack([r2 * np.cos(theta), r2 * np.sin(theta)], axis=1)
    e = np.array([r1, 0.0]) - a
    le = np.hypot(*e.T)
    u = e / le[:, None]
    along = (r3**2 - r4**2 + le**2) / (2 * le)
    across = np.sqrt(r3**2 - along**2)
    b = a + along[:, None] * u + across[:, None] * np.stack([-u[:, 1], u[:, 0]], axis=1)
    return np.asarray(np.hstack([a, b]))


def assembly_mode(coords: Array, r1: float) -> Array:
    """The sign of (B - A) x (B0 - A) at every position: which of the two assembly branches B is on."""
    a, b = point(coords, 5), point(coords, 7)
    ab, ab0 = b - a, np.array([r1, 0.0]) - a
    return np.asarray(np.sign(ab[:, 0] * ab0[:, 1] - ab[:, 1] * ab0[:, 0]))


def fourbar_deck(tmp_path: Path, dims: tuple[float, ...], steps: int, start: float) -> Path:
    """The locked four-bar's deck with other dimensions, step count and start angle."""
    r1, r2, r3, r4 = dims
    b = [float(v) for v in fourbar_closed_form(dims, np.array([start]))[0]]
    text = (LIMITS / "locked_fourbar.mec").read_text()
    for old, new in [
        ("TSTEPE 36", f"TSTEPE {steps}"),
        ("     3 70.0 ", f"     3 {r1!r} "),
        (
            "PARA 1 20.0\n     2 50.0\n     3 39.996\n     4 0.04363323129985824",
            f"PARA 1 {r2!r}\n     2 {r3!r}\n     3 {r4!r}\n     4 {start!r}",
        ),
        ("XMOV 5 20.0 ", f"XMOV 5 {b[0] + 0.01!r} "),
        ("     6 0.9\n", f"     6 {b[1]!r}\n"),
        ("     7 54.0 ", f"     7 {b[2] + 0.01!r} "),
        ("     8 36.7\n", f"     8 {b[3]!r}\n"),
    ]:
        assert old in text, old
        text = text.replace(old, new)
    deck = tmp_path / f"fourbar_{steps}.mec"
    deck.write_text(text)
    return deck


def test_locked_fourbar_limit_is_where_coupler_and_rocker_align() -> None:
    limit = lock_angle(*LK_DIMS)
    assert limit == pytest.approx(3.118914551, abs=1e-9)
    r1, r2, r3, r4 = LK_DIMS
    assert r1 + r2 - r3 - r4 == pytest.approx(0.004)
    # A step of 10 degrees from 172.5 would land beyond the locked zone (178.70 to 181.30 degrees).
    assert math.degrees(limit) < 182.5 and math.degrees(2 * math.pi - limit) < 182.5


@pytest.mark.filterwarnings("ignore::mechfem.IncompleteRunWarning")  # the motion stops on purpose
def test_locked_fourbar_stops_at_its_limit_on_its_branch_at_any_step_count(tmp_path: Path) -> None:
    limit = lock_angle(*LK_DIMS)
    for steps in (18, 36, 72, 360):
        deck = fourbar_deck(tmp_path, LK_DIMS, steps, LK_START)
        for det in (True, False):
            r = mechfem.run_deck(deck, det=det)
            what = f"{steps} steps, det={det}"
            stop = r.report.stop
            assert stop is not None and stop.limit is not None and stop.limit.kind == "input_limit", what
            assert stop.limit.inputs[0] == pytest.approx(limit, abs=LOCATED), what
            theta = r.buffers[1]
            assert len(theta) == stop.last_good and np.all(theta < limit), what
            # Every position reported is on the branch of position 1, where the closed form puts it.
            mode = assembly_mode(r.coords, LK_DIMS[0])
            assert np.all(mode == mode[0]), what
            got = np.column_stack([r.buffers[b] for b in (2, 3, 4, 5)])
            np.testing.assert_allclose(got, fourbar_closed_form(LK_DIMS, theta), atol=1e-7, err_msg=what)


@pytest.mark.filterwarnings("ignore::mechfem.IncompleteRunWarning")  # the motion stops on purpose
def test_locked_fourbar_cli_exits_3_at_the_limit(cli: Cli, tmp_path: Path) -> None:
    proc = cli("run", LIMITS / "locked_fourbar.mec", "-o", tmp_path)
    assert proc.returncode == 3, proc.stderr
    message = flat(proc.stderr)
    assert "The motion stopped after position 18 of 37" in message
    match = re.search(r"reached its limit position at theta = (\S+) rad, located between positions 18 and 19", message)
    assert match, message
    assert float(match.group(1)) == pytest.approx(lock_angle(*LK_DIMS), abs=LOCATED)
    with (tmp_path / "locked_fourbar.csv").open() as f:
        assert len(list(csv.reader(f))) == 1 + 18


@pytest.mark.parametrize("dims", [(4.0, 1.0, 3.5, 3.0), (1.0, 3.0, 3.5, 3.2)], ids=["crank_rocker", "double_crank"])
def test_grashof_fourbars_turn_in_ten_steps_without_a_stop(tmp_path: Path, dims: tuple[float, ...]) -> None:
    # Grashof, with the crank (crank-rocker) or the frame (double crank) the shortest link.
    lengths = sorted(dims)
    assert lengths[0] + lengths[3] < lengths[1] + lengths[2] and min(dims[:2]) == lengths[0]
    for det in (True, False):
        r = mechfem.run_deck(fourbar_deck(tmp_path, dims, 10, 0.0), det=det)
        assert r.report.complete and r.positions == 11, r.report.stop_reason()
        theta = r.buffers[1]
        np.testing.assert_allclose(theta, np.linspace(0.0, 2 * math.pi, 11), atol=1e-12)
        got = np.column_stack([r.buffers[b] for b in (2, 3, 4, 5)])
        np.testing.assert_allclose(got, fourbar_closed_form(dims, theta), atol=1e-8)
