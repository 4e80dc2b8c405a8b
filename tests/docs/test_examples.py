"""The example decks: every one runs through the command line and writes its files, and what each
example is meant to show is checked against closed forms derived here, independently of mechfem.

Closed forms are compared within 1e-9 of the largest magnitude of the quantity over the run (the
solver's own error is about 1e-12). Deck constants are repeated here on purpose: a change to a deck
that is not made here too fails its test.
"""

from __future__ import annotations

import csv
import re
from functools import cache
from pathlib import Path

import numpy as np
import numpy.typing as npt
import pytest

import mechfem
from conftest import ROOT, Cli, stops_on_purpose

Array = npt.NDArray[np.float64]

EXAMPLES = ROOT / "examples"
DECKS = sorted(EXAMPLES.rglob("*.mec"))
RTOL = 1e-9
TSTEPE = re.compile(r"^\s*TSTEPE\s+(\S+)", re.I | re.M)


@cache
def run(name: str) -> mechfem.RunResult:
    """The example ``examples/<name>/<name>.mec``, run once per test session."""
    result = mechfem.run_deck(EXAMPLES / name / f"{name}.mec")
    assert result.report.complete, result.report.stop_reason()
    return result


def assert_close(what: str, got: Array, want: Array, scale: float | None = None, rtol: float = RTOL) -> None:
    """|got - want| <= rtol * scale at every position; scale defaults to max |want|."""
    got, want = np.broadcast_arrays(np.asarray(got, dtype=float), np.asarray(want, dtype=float))
    assert np.all(np.isfinite(got)), f"{what}: not finite"
    if scale is None:
        scale = float(np.max(np.abs(want)))
    err = np.abs(got - want)
    k = int(np.argmax(err))
    assert err[k] <= rtol * scale, (
        f"{what}: position {k + 1}: got {got[k]!r}, want {want[k]!r} (error {err[k]:.3g}, allowed {rtol * scale:.3g})"
    )


def deck_steps(deck: Path) -> int:
    """The n of the deck's TSTEPE line (0 without a MOVEMENT block)."""
    match = TSTEPE.search(deck.read_text())
    return int(float(match.group(1).replace("d", "e").replace("D", "e"))) if match else 0


# Every deck ----------------------------------------------------------------------------------


def test_there_are_examples() -> None:
    names = {d.parent.name for d in DECKS}
    assert {"fourbar", "slider_crank", "manipulator", "supply"} <= names


@pytest.mark.filterwarnings("ignore::mechfem.IncompleteRunWarning")  # the motion stops on purpose
@pytest.mark.parametrize("deck", DECKS, ids=lambda d: str(d.relative_to(EXAMPLES)))
def test_example_runs_and_writes_print_file_and_data_set(cli: Cli, tmp_path: Path, deck: Path) -> None:
    proc = cli("run", deck, "-o", tmp_path)
    stops = stops_on_purpose(deck)
    assert proc.returncode == (3 if stops else 0), proc.stderr
    prt, data = tmp_path / f"{deck.stem}.prt", tmp_path / f"{deck.stem}.csv"
    assert prt.is_file() and data.is_file(), proc.stdout

    with data.open(newline="") as f:
        header, *rows = list(csv.reader(f))
    # A KIN OPT deck's outputs are the run of its final design.
    optimised = tmp_path / f"{deck.stem}_opt.mec"
    result = mechfem.run_deck(optimised if optimised.exists() else deck)
    if stops:
        # Every position up to the stop is written.
        assert "MOTION STOPPED" in prt.read_text()
        assert result.report.stop is not None
        assert len(rows) == result.report.positions < deck_steps(deck) + 1
    else:
        assert len(rows) == deck_steps(deck) + 1
    assert all(len(r) == len(header) for r in rows)

    # The data set holds exactly the buffers SAVEDATA names, as the run computed them.
    assert [int(h.split()[0]) for h in header] == result.storage.savedata
    values = np.array(rows, dtype=float)
    for col, number in enumerate(result.storage.savedata):
        assert np.array_equal(values[:, col], result.buffers[number], equal_nan=True), f"buffer {number}"


# Four-bar: coupler point and rocker against the loop equations -------------------------------

# examples/fourbar/fourbar.mec: crank a, coupler b, rocker c, frame d; C at (u, v) on the coupler.
FB_A, FB_B, FB_C, FB_D, FB_U, FB_V = 1.0, 3.5, 3.0, 4.0, 1.5, 1.2
FB_STEPS, FB_DT, FB_TURN = 144, 0.01, 4 * np.pi
FB_SPEED = FB_TURN / (FB_STEPS * FB_DT)


class FourBar:
    """Closed form of the four-bar A0 = 0, B0 = d (complex plane) at crank angles t2.

    Loop a e^{i t2} + b e^{i t3} = d + c e^{i t4}. B is the intersection of the circles (A, b) and
    (B0, c) to the left of A -> B0. Differentiating the loop once and twice and projecting on the
    directions of the coupler and of the rocker gives t3', t4', t3'', t4''.
    """

    def __init__(self, t2: Array) -> None:
        a, b, c, d = FB_A, FB_B, FB_C, FB_D
        self.t2 = t2
        A = a * np.exp(1j * t2)
        L = np.abs(d - A)
        e = (d - A) / L
        along = (b * b - c * c + L * L) / (2 * L)
        B = A + (along + 1j * np.sqrt(b * b - along * along)) * e
        t3, t4 = np.angle(B - A), np.angle(B - d)
        t3p = a * np.sin(t4 - t2) / (b * np.sin(t3 - t4))
        t4p = a * np.sin(t2 - t3) / (c * np.sin(t4 - t3))
        t3pp = (-a * np.cos(t2 - t4) - b * t3p**2 * np.cos(t3 - t4) + c * t4p**2) / (b * np.sin(t3 - t4))
        t4pp = (a * np.cos(t2 - t3) + b * t3p**2 - c * t4p**2 * np.cos(t4 - t3)) / (c * np.sin(t4 - t3))
        z = (FB_U + 1j * FB_V) * np.exp(1j * t3)  # C - A
        self.t3, self.t4, self.t4p, self.t4pp = t3, t4, t4p, t4pp
        self.C = A + z
        self.Cp = 1j * A + 1j * t3p * z
        self.Cpp = -A + (1j * t3pp - t3p**2) * z


def test_fourbar_crank_turns_twice_at_constant_speed() -> None:
    r = run("fourbar")
    k = np.arange(FB_STEPS + 1)
    assert_close("crank angle", r.buffers[1], FB_TURN * k / FB_STEPS)
    assert_close("time", r.buffers[2], FB_DT * k)
    assert r.report.warnings == []


def test_fourbar_coupler_point_position_and_transfer_functions() -> None:
    r = run("fourbar")
    fb = FourBar(r.buffers[1])
    assert_close("x_C", r.buffers[11], fb.C.real)
    assert_close("y_C", r.buffers[12], fb.C.imag)
    assert_close("d x_C / d t2", r.buffers[13], fb.Cp.real)
    assert_close("d y_C / d t2", r.buffers[14], fb.Cp.imag)
    assert_close("d2 x_C / d t2^2", r.buffers[15], fb.Cpp.real)
    assert_close("d2 y_C / d t2^2", r.buffers[16], fb.Cpp.imag)


def test_fourbar_coupler_point_velocity_and_acceleration() -> None:
    r = run("fourbar")
    fb = FourBar(r.buffers[1])
    w = FB_SPEED  # constant: no t2'' term
    assert_close("v_xC", r.buffers[17], w * fb.Cp.real)
    assert_close("v_yC", r.buffers[18], w * fb.Cp.imag)
    assert_close("a_xC", r.buffers[19], w * w * fb.Cpp.real)
    assert_close("a_yC", r.buffers[20], w * w * fb.Cpp.imag)


def test_fourbar_rocker_angle_as_dependent_form_parameter() -> None:
    r = run("fourbar")
    fb = FourBar(r.buffers[1])
    w = FB_SPEED
    assert_close("t4", r.buffers[21], fb.t4)
    assert_close("t4'", r.buffers[22], fb.t4p)
    assert_close("t4''", r.buffers[23], fb.t4pp)
    assert_close("t4 dot", r.buffers[24], w * fb.t4p)
    assert_close("t4 dot dot", r.buffers[25], w * w * fb.t4pp)


def test_fourbar_det_is_sine_of_transmission_angle_over_crank_length() -> None:
    # D^c (rows l1, l, u, v, l3, t2; columns xA yA xB yB xC yC): C enters only the rows u, v, a
    # rotation with determinant 1; what is left splits into the crank's rows l1, t2 on A
    # (determinant 1/a) and the rows l, l3 on B, with determinant sin(t4 - t3).
    r = run("fourbar")
    fb = FourBar(r.buffers[1])
    assert_close("det(D^c)", r.buffers[30], np.sin(fb.t4 - fb.t3) / FB_A)
    assert_close("det(D^c) from the run", r.det, r.buffers[30], rtol=0.0, scale=1.0)


# Slider-crank: timed motion with a non-constant input speed ----------------------------------

# examples/slider_crank: crank a, rod l, slider on y = e; crank.dat: t2 = 0.25 + 10 t + 10 t^2.
SC_A, SC_L, SC_E = 1.0, 3.0, 0.3
SC_STEPS, SC_DT = 100, 0.005


def crank_angle(t: Array) -> tuple[Array, Array, Array]:
    """Angle, speed and acceleration of the crank at times t, as crank.dat was written."""
    return 0.25 + 10 * t + 10 * t * t, 10 + 20 * t, np.full_like(t, 20.0)


def test_slider_crank_input_comes_from_the_file() -> None:
    r = run("slider_crank")
    t = r.buffers[1]
    assert_close("time", t, SC_DT * np.arange(SC_STEPS + 1))
    assert_close("crank angle", r.buffers[2], crank_angle(t)[0])
    # More than a full turn, and the speed doubles on the way.
    assert r.buffers[2][-1] - r.buffers[2][0] > 2 * np.pi


def test_slider_crank_slider_position_velocity_acceleration() -> None:
    r = run("slider_crank")
    th, thd, thdd = crank_angle(r.buffers[1])
    # B = A + (w, h): h = e - a sin t2 is the rod's rise, w = sqrt(l^2 - h^2) its run.
    h, hp, hpp = SC_E - SC_A * np.sin(th), -SC_A * np.cos(th), SC_A * np.sin(th)
    w = np.sqrt(SC_L**2 - h**2)
    wp = -h * hp / w
    wpp = -(hp**2 + h * hpp) / w - (h * hp) ** 2 / w**3
    x, xp, xpp = SC_A * np.cos(th) + w, -SC_A * np.sin(th) + wp, -SC_A * np.cos(th) + wpp
    assert_close("x_B", r.buffers[3], x)
    assert_close("y_B", r.buffers[8], np.full_like(x, SC_E))
    assert_close("x_B'", r.buffers[6], xp)
    assert_close("x_B''", r.buffers[7], xpp)
    assert_close("v_B", r.buffers[4], xp * thd)
    # eq. 5.30 with one input: x'' t2dot^2 + x' t2ddot. The second term is far above the tolerance.
    assert np.max(np.abs(xp * thdd)) > 1e-3 * np.max(np.abs(r.buffers[5]))
    assert_close("a_B", r.buffers[5], xpp * thd**2 + xp * thdd)

    # The connecting rod: sin(phi) = h / l, cos(phi) = w / l.
    phi, php = np.arctan2(h, w), hp / w
    phpp = (hpp * w - hp * wp) / w**2
    assert_close("phi", r.buffers[9], phi)
    assert_close("phi dot", r.buffers[10], php * thd)
    assert_close("phi dot dot", r.buffers[11], phpp * thd**2 + php * thdd)


# Manipulator: two inputs moving at once ------------------------------------------------------

# examples/manipulator: M on actuators of lengths l1 from A0 = (0, 0) and l2 from B0 = (d, 0).
MP_D = 1.2
MP_STEPS, MP_DT = 50, 0.02
MP_L1, MP_DL1 = 1.0, 0.4  # MOV_RELE 1 0.4
MP_L2, MP_L2_END = 0.9, 0.6  # MOV_ABSE 2 0.6


def test_manipulator_all_derivatives_and_timed_motion() -> None:
    r = run("manipulator")
    k = np.arange(MP_STEPS + 1)
    T = MP_STEPS * MP_DT
    l1 = MP_L1 + MP_DL1 * k / MP_STEPS
    l2 = MP_L2 + (MP_L2_END - MP_L2) * k / MP_STEPS
    v1, v2 = MP_DL1 / T, (MP_L2_END - MP_L2) / T
    assert_close("time", r.buffers[1], MP_DT * k)
    assert_close("l1", r.buffers[2], l1)
    assert_close("l2", r.buffers[3], l2)

    # x from the difference of the two circle equations, y from the first; the derivatives of
    # y follow from differentiating y^2 = l1^2 - x^2 once and twice.
    d = MP_D
    x = (l1**2 - l2**2 + d * d) / (2 * d)
    y = np.sqrt(l1**2 - x**2)
    x1, x2 = l1 / d, -l2 / d
    x11, x22, x12 = np.full_like(x, 1 / d), np.full_like(x, -1 / d), np.zeros_like(x)
    y1, y2 = (l1 - x * x1) / y, -x * x2 / y
    y11 = (1 - x1**2 - x * x11 - y1**2) / y
    y22 = (-(x2**2) - x * x22 - y2**2) / y
    y12 = (-x1 * x2 - x * x12 - y1 * y2) / y

    assert_close("x_M", r.buffers[4], x)
    assert_close("y_M", r.buffers[5], y)
    assert_close("d x_M / d l1", r.buffers[11], x1)
    assert_close("d x_M / d l2", r.buffers[12], x2)
    assert_close("d y_M / d l1", r.buffers[13], y1)
    assert_close("d y_M / d l2", r.buffers[14], y2)
    assert_close("d2 x_M / d l1^2", r.buffers[21], x11)
    assert_close("d2 x_M / d l2^2", r.buffers[22], x22)
    assert_close("d2 x_M / d l1 d l2", r.buffers[23], x12, scale=1 / d)
    assert_close("d2 y_M / d l1^2", r.buffers[24], y11)
    assert_close("d2 y_M / d l2^2", r.buffers[25], y22)
    assert_close("d2 y_M / d l1 d l2", r.buffers[26], y12)

    # eqs. 5.29, 5.30 with two inputs at constant speed: the mixed term counts twice.
    assert_close("v_xM", r.buffers[31], x1 * v1 + x2 * v2)
    assert_close("v_yM", r.buffers[32], y1 * v1 + y2 * v2)
    assert_close("a_xM", r.buffers[33], x11 * v1**2 + 2 * x12 * v1 * v2 + x22 * v2**2)
    assert_close("a_yM", r.buffers[34], y11 * v1**2 + 2 * y12 * v1 * v2 + y22 * v2**2)
    assert np.max(np.abs(2 * y12 * v1 * v2)) > 1e-3 * np.max(np.abs(r.buffers[34]))

    # D^c = [[x/l1, y/l1], [(x - d)/l2, y/l2]].
    assert_close("det(D^c)", r.buffers[40], d * y / (l1 * l2))


# Supply mechanism: the output link dwells without jerk ---------------------------------------


def test_supply_crank_turns_one_full_revolution() -> None:
    r = run("supply")
    inp = r.buffers[99]
    assert len(inp) == 73
    assert_close("crank angle", inp, inp[0] + 2 * np.pi * np.arange(73) / 72, scale=2 * np.pi)


def test_supply_output_acceleration_vanishes_in_both_limit_positions() -> None:
    # At a constant input speed w the output's acceleration is w^2 times buffer 102, so it is
    # enough to look at 102 where the first-order transfer function 101 changes sign.
    r = run("supply")
    first, second = r.buffers[101], r.buffers[102]
    # One revolution: 72 steps from position 1 back to the same position 73.
    changes = np.nonzero(np.sign(first[:-1]) * np.sign(first[1:]) < 0)[0]
    assert len(changes) == 2, f"limit positions of the output after positions {changes + 1}"
    biggest = np.max(np.abs(second))
    for k in changes:
        f = first[k] / (first[k] - first[k + 1])
        at_limit = second[k] + f * (second[k + 1] - second[k])
        assert abs(at_limit) < 0.05 * biggest, f"between positions {k + 1} and {k + 2}: {at_limit} of {biggest}"


# The deck reference's worked example is the four-bar deck --------------------------------------

WORKED = re.compile(r"^## A worked example.*?\n(.*?)(?=^## |\Z)", re.S | re.M)


def worked_example() -> str:
    section = WORKED.search((ROOT / "docs" / "deck.md").read_text())
    assert section, "docs/deck.md has no '## A worked example' section"
    return section.group(1)


def excerpt(text: str, heading: str) -> list[str]:
    """The lines of the first ``text`` block below ``### heading``."""
    match = re.search(rf"^### {heading}\n.*?^```text\n(.*?)^```", text, re.S | re.M)
    assert match, f"no text block below '### {heading}'"
    return match.group(1).splitlines()


def alike(shown: str, real: str) -> bool:
    """The same line, numbers equal to 1e-9 relative (or 1e-12 absolute: rounding noise)."""
    a, b = re.split(r"[\s,]+", shown.strip()), re.split(r"[\s,]+", real.strip())
    if len(a) != len(b):
        return False
    for x, y in zip(a, b, strict=True):
        if x == y:
            continue
        try:
            if not np.isclose(float(x), float(y), rtol=1e-9, atol=1e-12):
                return False
        except ValueError:
            return False
    return True


def appears_in_order(lines: list[str], text: str) -> None:
    """Every line of an excerpt except ``...`` is a line of ``text``, in the same order."""
    real = text.splitlines()
    at = 0
    for line in lines:
        if line == "...":
            continue
        found = next((k for k in range(at, len(real)) if alike(line, real[k])), None)
        assert found is not None, f"not in the output (after line {at}): {line!r}"
        at = found + 1


def test_deck_reference_worked_example_is_the_fourbar_deck() -> None:
    blocks = re.findall(r"^```mec\n(.*?)^```", worked_example(), re.S | re.M)
    assert "".join(blocks) == (EXAMPLES / "fourbar" / "fourbar.mec").read_text()


def test_deck_reference_worked_example_shows_real_output(cli: Cli, tmp_path: Path) -> None:
    proc = cli("run", EXAMPLES / "fourbar" / "fourbar.mec", "-o", tmp_path)
    assert proc.returncode == 0, proc.stderr
    text = worked_example()
    appears_in_order(excerpt(text, "The print file"), (tmp_path / "fourbar.prt").read_text())
    appears_in_order(excerpt(text, "The data set"), (tmp_path / "fourbar.csv").read_text())


@pytest.mark.parametrize("page", ["README.md", "deck.md"])
def test_docs_links_exist(page: str) -> None:
    path = ROOT / "docs" / page
    for target in re.findall(r"\]\(([^)#:]+)\)", path.read_text()):
        assert (path.parent / target).exists(), f"docs/{page} links to {target}, which does not exist"
