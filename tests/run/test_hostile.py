"""Numerically hostile decks: each gives a correct result or a clear error, never a NaN passed on.

Correct results are checked against the closed form of the four-bar example (``test_examples.FourBar``),
derived independently of mechfem.
"""

from __future__ import annotations

import cmath
import math
import re
from pathlib import Path

import numpy as np
import pytest

import mechfem
from conftest import ROOT
from docs.test_examples import FB_A, FB_B, FB_C, FB_D, FourBar, assert_close

FOURBAR = ROOT / "examples" / "fourbar" / "fourbar.mec"
COORD_LINE = re.compile(r"^(\s*(?:XFIX|XMOV)?\s+)(\d+)(\s+)(\S+)", re.I)
PARA_LINE = re.compile(r"^(\s*(?:PARA)?\s+)(\d+)(\s+)(\S+)", re.I)


def fourbar_deck(
    tmp_path: Path, scale: float = 1.0, steps: int | None = None, turn: float | None = None, name: str = "fb"
) -> Path:
    """The four-bar example with every length multiplied by ``scale`` (angles kept), and optionally another
    TSTEPE step count and crank turn."""
    out, block, keyword = [], "", ""
    for line in FOURBAR.read_text().splitlines():
        code = line.split(";")[0]
        word = code.split()[0].upper() if code.split() else ""
        if word in {"TOPOLOGY", "GEOMETRY", "MOVEMENT", "STORAGE"}:
            block = word
        if block == "GEOMETRY" and word and not word[0].isdigit():
            keyword = word
        if block == "GEOMETRY" and keyword in {"XFIX", "XMOV"} and (m := COORD_LINE.match(code)):
            line = f"{m[1]}{m[2]}{m[3]}{float(m[4]) * scale!r}"
        elif block == "GEOMETRY" and keyword == "PARA" and (m := PARA_LINE.match(code)) and int(m[2]) <= 5:
            line = f"{m[1]}{m[2]}{m[3]}{float(m[4]) * scale!r}"
        elif word == "TSTEPE" and steps is not None:
            line = f"TSTEPE {steps} {1.44 / steps!r}"
        elif word == "MOV_RELE" and turn is not None:
            line = f"MOV_RELE 1 {turn!r}"
        out.append(line)
    path = tmp_path / f"{name}.mec"
    path.write_text("\n".join(out) + "\n")
    return path


def assert_fourbar_exact(r: mechfem.RunResult, scale: float = 1.0, rtol: float = 1e-9) -> None:
    """Coupler point, its transfer functions and the rocker angle against the closed form."""
    assert r.report.complete, r.report.stop_reason()
    fb = FourBar(r.buffers[1])
    assert_close("x_C", r.buffers[11] / scale, fb.C.real, rtol=rtol)
    assert_close("y_C", r.buffers[12] / scale, fb.C.imag, rtol=rtol)
    assert_close("d x_C / d t2", r.buffers[13] / scale, fb.Cp.real, rtol=rtol)
    assert_close("d2 y_C / d t2^2", r.buffers[16] / scale, fb.Cpp.imag, rtol=rtol)
    # The rocker angle is tracked continuously: compare it modulo 2 pi.
    assert_close("t4", np.angle(np.exp(1j * (r.buffers[21] - fb.t4))), 0.0 * fb.t4, scale=1.0, rtol=rtol)
    assert_close("t4'", r.buffers[22], fb.t4p, rtol=rtol)


@pytest.mark.parametrize("scale", [1e-6, 1e6])
def test_tiny_and_huge_units_give_the_same_mechanism(tmp_path: Path, scale: float) -> None:
    r = mechfem.run_deck(fourbar_deck(tmp_path, scale))
    assert_fourbar_exact(r, scale)
    # det(D^c) of rows l1, l, u, v, l3, t2 scales as 1/length (see test_examples).
    base = mechfem.run_deck(FOURBAR)
    assert_close("det(D^c)", r.det * scale, base.det, rtol=1e-9)


def test_angles_of_many_revolutions(tmp_path: Path) -> None:
    # 1000 crank revolutions, 100 steps each: the input reaches 6283 rad, and positions repeat.
    turns = 1000
    r = mechfem.run_deck(fourbar_deck(tmp_path, steps=100 * turns, turn=2 * math.pi * turns))
    assert_fourbar_exact(r, rtol=1e-8)
    assert r.buffers[1][-1] == pytest.approx(2 * math.pi * turns, rel=1e-12)
    first, last = r.coords[:101], r.coords[-101:]
    np.testing.assert_allclose(last, first, rtol=0, atol=1e-8)


@pytest.mark.large_run
def test_a_million_steps(tmp_path: Path) -> None:
    r = mechfem.run_deck(fourbar_deck(tmp_path, steps=1_000_000, turn=20 * math.pi))
    assert r.report.positions == 1_000_001
    assert_fourbar_exact(r)
    assert np.isfinite(r.coords).all()


# Near a limit position: the rocker driven to within 1e-8 rad of the end of its swing ---------------------

# tests/decks/rocker.mec, with the coupler 3.5 instead of 4 so that the rocker swings between the stretched
# position (|B - A0| = a + b) and the folded one (|B - A0| = b - a) and never turns around.
ROCKER = """KIN ANA
TOPOLOGY
ELEM 1 BIN 1 2 5 6
     2 BIN 5 6 7 8
     3 BIN 3 4 7 8
FORM 1 LENL 1 1
     2 LENL 2 2
     3 LENL 3 3
     4 ANGB 3 4
     5 ANGB 1 -1
NRDOF 1
GEOMETRY
XFIX 1 0.0
     2 0.0
     3 {d!r}
     4 0.0
XMOV 5 {ax!r}
     6 {ay!r}
     7 {bx!r}
     8 {by!r}
PARA 1 {a!r}
     2 {b!r}
     3 {c!r}
     4 {g0!r}
MOVEMENT
TSTEPE {steps}
MOV_ABSE 1 {g1!r}
STORAGE
BUFINP 1 1
BUFE0 -1 2
BUFKE1 -1 1 3
BUFDET 4
"""


def rocker_position(g: float) -> tuple[complex, complex]:
    """B from the rocker angle g; A on the crank circle at distance b from B, on the side of the crank
    angle's first position (below the line A0 -> B)."""
    a, b, c, d = FB_A, FB_B, FB_C, FB_D
    B = d + c * cmath.exp(1j * g)
    L = abs(B)
    e = B / L
    along = (a * a - b * b + L * L) / (2 * L)
    A = (along - 1j * math.sqrt(max(a * a - along * along, 0.0))) * e
    return A, B


def stretched_angle() -> float:
    """Rocker angle where crank and coupler are in line (|B| = a + b): a limit position of the rocker."""
    a, b, c, d = FB_A, FB_B, FB_C, FB_D
    return math.acos(((a + b) ** 2 - d * d - c * c) / (2 * c * d))


def rocker_deck(tmp_path: Path, g0: float, g1: float, steps: int) -> Path:
    A, B = rocker_position(g0)
    text = ROCKER.format(
        a=FB_A, b=FB_B, c=FB_C, d=FB_D, ax=A.real, ay=A.imag, bx=B.real, by=B.imag, g0=g0, g1=g1, steps=steps
    )
    path = tmp_path / "rocker.mec"
    path.write_text(text)
    return path


def test_nearly_singular_dc_still_gives_the_exact_position(tmp_path: Path) -> None:
    limit = stretched_angle()
    g1 = limit + 1e-8
    r = mechfem.run_deck(rocker_deck(tmp_path, 2.0, g1, 50))
    assert r.report.complete, r.report.stop_reason()
    A, _ = rocker_position(g1)
    # The crank angle is exact to about sqrt(eps): near the limit it moves like the square root of the
    # rocker's distance from it, so the solver's residual is amplified accordingly.
    assert r.buffers[2][-1] == pytest.approx(cmath.phase(A), abs=1e-6)
    assert abs(r.det[-1]) < 1e-3 * np.max(np.abs(r.det))
    assert np.isfinite(r.buffers[3]).all()


@pytest.mark.filterwarnings("ignore::mechfem.IncompleteRunWarning")  # the motion stops on purpose
def test_driven_past_the_limit_stops_there_with_a_reason(tmp_path: Path) -> None:
    limit = stretched_angle()
    r = mechfem.run_deck(rocker_deck(tmp_path, 2.0, limit - 0.1, 50))
    stop = r.report.stop
    assert stop is not None
    assert stop.limit is not None and stop.limit.inputs[0] == pytest.approx(limit, abs=1e-6)
    k = r.report.positions
    # Every position kept is finite and exact.
    assert np.isfinite(r.coords).all() and np.isfinite(r.buffers[3]).all()
    A = np.array([rocker_position(g)[0] for g in r.buffers[1]])
    np.testing.assert_allclose(r.coords[:k, 4] + 1j * r.coords[:k, 5], A, atol=1e-9)
    assert "limit position" in r.report.stop_reason()


# Lengths of zero, and points that come together ------------------------------------------------------------


@pytest.mark.parametrize("length", ["0.0", "1.0e-400", "-1.0"])
def test_a_bar_of_zero_or_negative_length_is_a_clear_error(tmp_path: Path, length: str) -> None:
    deck = tmp_path / "zero.mec"
    deck.write_text(re.sub(r"(?m)^PARA 1 1.0$", f"PARA 1 {length}", FOURBAR.read_text()))
    with pytest.raises(mechfem.DeckError) as caught:
        mechfem.run_deck(deck)
    message = str(caught.value)
    assert "length" in message and "zero.mec:" in message


@pytest.mark.filterwarnings("ignore::mechfem.IncompleteRunWarning")  # the motion stops on purpose
def test_coinciding_points_during_the_motion_stop_it_clearly(tmp_path: Path) -> None:
    # A bar whose prescribed length is the input, driven from 1 through 0 to -1: at length 0 its points
    # coincide and its angle no longer exists.
    deck = tmp_path / "shrink.mec"
    deck.write_text(
        "KIN ANA\nTOPOLOGY\nELEM 1 BIN 1 2 3 4\nFORM 1 ANGB 1 1\n 2 LENL 1 2\nNRDOF 1\n"
        "GEOMETRY\nXFIX 1 0\n 2 0\nXMOV 3 1\n 4 0\nPARA 1 0\n 2 1\n"
        "MOVEMENT\nTSTEPE 20\nMOV_ABSE 1 -1\nSTORAGE\nBUFX0 3 1\nBUFKX1 3 1 2\n"
    )
    r = mechfem.run_deck(deck)
    assert not r.report.complete
    k = r.report.positions
    assert 1 <= k <= 11
    assert np.isfinite(r.buffers[1]).all() and np.isfinite(r.buffers[2]).all()
    np.testing.assert_allclose(r.buffers[1], 1.0 - 0.1 * np.arange(k), atol=1e-12)
    assert r.report.stop_reason() is not None
