"""Every example, written again in millimetres and degrees by a converter that knows nothing of it but the dimensions
the deck reader gives its co-ordinates, rows, inputs and buffers (``Labels``), gives the SI deck's results converted:
every buffer (drive torques, reactions and energies included), every co-ordinate and det(D^c) at every position, and
the same limit positions.

The converter multiplies each number a deck gives by its unit's factor (a length by 1000, an angle by 180/pi, a
derived unit by the product of its exponents' factors): XFIX and XMOV by the co-ordinate's dimension, PARA by the
row's, MOV_RELE and MOV_ABSE by the input's, a MOV_FUNC table's values, speeds and accelerations by the input's
(its time left in seconds), ACCURACY and MOV_FREE's step as lengths; in DYNAMICS a centre of mass as a length, a
moment of inertia as mass x length² (an INERTIA on a length is a mass), gravity as an acceleration, a LOAD, a
MOTOR's stall torque and a SPRING as the generalised force on their row (work over the row's unit, an angle not
counted: a torque in N·mm), the rest by the row's unit; MOV_DYN's speed and STOPWHEN's value by the input's and the
buffer's unit. Masses, forces and times stay in kg, N and s. A deck with UNITS other than SI's is left out, and so
is one with an OPTIMISE block (``test_names_units.py`` and ``tests/design`` have those in mm and degrees)."""

from __future__ import annotations

import math
from collections.abc import Sequence
from pathlib import Path

import numpy as np
import pytest

import mechfem
import mechfem._core as _core
from conftest import ROOT

LENGTH, ANGLE = 1000.0, 180.0 / math.pi


def factor(dims: Sequence[int]) -> float:
    """What a number of the exponents ``dims`` (length, angle, mass, force, time) is multiplied by from m and rad to
    mm and degrees."""
    return float(LENGTH ** dims[0] * ANGLE ** dims[1])


def words(line: str) -> list[str]:
    return line.split(";")[0].split()


SI_UNITS = "UNITS LENGTH m ANGLE rad MASS kg FORCE N TIME s"


def examples() -> list[Path]:
    """The examples without an OPTIMISE block, without UNITS or with SI's."""
    out = []
    for deck in sorted((ROOT / "examples").rglob("*.mec")):
        lines = [words(line) for line in deck.read_text().splitlines()]
        units = [" ".join(w) for w in lines if w and w[0].upper() == "UNITS"]
        if units in ([], [SI_UNITS]) and not any(w[0].upper() == "OPTIMISE" for w in lines if w):
            out.append(deck)
    return out


def generalised_force(row: Sequence[int]) -> float:
    """The factor of a load on a row of the exponents ``row``: work over the row's length (an angle not counted)."""
    return LENGTH ** (1 - row[0])


def in_mm_and_degrees(text: str, labels: _core.Labels, tables: Path, out_dir: Path) -> str:
    """The deck ``text`` with every number converted and the UNITS line after its mode line; its MOV_FUNC tables
    (in the folder ``tables``) written converted into ``out_dir``."""
    out, block, moded = [], "", False
    for line in text.splitlines():
        w = words(line)
        if not w or w[0].upper() == "UNITS":
            out.append("" if w else line)
            continue
        head = w[0].upper()
        if not moded:
            out += [line, "UNITS LENGTH mm ANGLE deg"]
            moded = True
            continue
        if head in ("XFIX", "XMOV", "PARA", "MASS", "PMASS", "INERTIA"):
            block = head
            out.append(f"{head} {item(block, w[1:], labels)}")
        elif w[0].lstrip("-").isdigit() and block:
            out.append(f"  {item(block, w, labels)}")
        else:
            block = ""
            out.append(statement(head, w, labels, tables, out_dir) or line)
    return "\n".join(out) + "\n"


def item(block: str, w: list[str], labels: _core.Labels) -> str:
    """One item of a list of numbered items (``number value ...``) of the keyword ``block``, converted."""
    number, values = int(w[0]), [float(v) for v in w[1:]]
    if block == "MASS":
        # m u v [J]: the centre of mass a length, the moment of inertia mass x length².
        values = [values[0], values[1] * LENGTH, values[2] * LENGTH, *[j * LENGTH**2 for j in values[3:]]]
    elif block == "INERTIA":
        # On an angle (or a pure number) a moment of inertia, on a length a mass.
        values = [values[0] * (1.0 if labels.coordinate(number)[3][0] == 1 else LENGTH**2)]
    elif block in ("XFIX", "XMOV"):
        values = [values[0] * factor(labels.coordinate(number)[3])]
    elif block == "PARA":
        values = [values[0] * factor(labels.row(number)[3])]
    return f"{number} {' '.join(map(repr, values))}"


def statement(head: str, w: list[str], labels: _core.Labels, tables: Path, out_dir: Path) -> str | None:
    """A statement with numbers of their own units, converted (None for one without)."""
    if head == "GRAVITY":
        return f"GRAVITY {float(w[1]) * LENGTH!r} {float(w[2]) * LENGTH!r}"
    if head in ("LOAD", "SPRING", "MOTOR"):
        row = labels.row(int(w[1]))[3]
        q, e = generalised_force(row), factor(row)
        rule = {"LOAD": [q], "SPRING": [q / e, e, q / e], "MOTOR": [q, e]}[head]
        return f"{head} {w[1]} {' '.join(repr(float(v) * f) for v, f in zip(w[2:], rule, strict=False))}"
    if head in ("MOV_RELE", "MOV_ABSE", "MOV_DYN"):
        return f"{head} {w[1]} {float(w[2]) * factor(labels.input(int(w[1]))[5])!r}"
    if head in ("ACCURACY", "MOV_FREE"):
        return f"{' '.join(w[:-1])} {float(w[-1]) * LENGTH!r}"
    if head == "STOPWHEN":
        return f"STOPWHEN {w[1]} {float(w[2]) * factor(labels.buffer(int(w[1]))[3])!r}"
    if head == "MOV_FUNC":
        f = factor(labels.input(int(w[1]))[5])
        rows = [r.split() for r in (tables / w[2]).read_text().splitlines() if r.strip() and r[0] != "#"]
        converted = [" ".join([r[0], *[repr(float(v) * f) for v in r[1:]]]) for r in rows]
        (out_dir / w[2]).write_text("\n".join(converted) + "\n")
    return None


@pytest.mark.parametrize("deck", examples(), ids=lambda p: p.stem)
def test_an_example_in_mm_and_degrees_gives_the_si_results_converted(deck: Path, tmp_path: Path) -> None:
    labels = mechfem.check_deck(deck).model.labels
    assert labels is not None
    mm = tmp_path / deck.name
    mm.write_text(in_mm_and_degrees(deck.read_text(), labels, deck.parent, tmp_path))
    # A limit position on the way stops both runs alike; the positions up to it are compared.
    with pytest.MonkeyPatch.context() as mp:
        mp.setattr("warnings.showwarning", lambda *a, **k: None)
        si_run, mm_run = mechfem.run_deck(deck), mechfem.run_deck(mm)
    assert mm_run.positions == si_run.positions
    mm_labels = mm_run.model.labels
    assert mm_labels is not None
    # The limit positions located on the way: the same, their inputs and co-ordinates converted.
    assert [(lim.kind, lim.after) for lim in mm_run.report.limits] == [(k.kind, k.after) for k in si_run.report.limits]
    for a, b in zip(si_run.report.limits, mm_run.report.limits, strict=True):
        inputs = [v * factor(mm_labels.input(j + 1)[5]) for j, v in enumerate(a.inputs)]
        coords = [v * factor(mm_labels.coordinate(i + 1)[3]) for i, v in enumerate(a.coords)]
        np.testing.assert_allclose(b.inputs, inputs, rtol=1e-7, atol=1e-7)
        np.testing.assert_allclose(b.coords, coords, rtol=1e-7, atol=1e-6)
    for b in si_run.buffers:
        want = np.asarray(si_run.buffers[b]) * factor(mm_labels.buffer(b)[3])
        scale = max(1.0, float(np.nanmax(np.abs(want)))) if np.isfinite(want).any() else 1.0
        np.testing.assert_allclose(mm_run.buffers[b], want, rtol=1e-8, atol=1e-9 * scale, err_msg=f"buffer {b}")
    for i in range(si_run.coords.shape[1]):
        want = si_run.coords[:, i] * factor(mm_labels.coordinate(i + 1)[3])
        scale = max(1.0, float(np.max(np.abs(want))))
        np.testing.assert_allclose(mm_run.coords[:, i], want, rtol=1e-8, atol=1e-9 * scale, err_msg=f"x{i + 1}")
    want = si_run.det * factor(mm_labels.det()[3])
    np.testing.assert_allclose(mm_run.det, want, rtol=1e-7, atol=1e-9 * float(np.nanmax(np.abs(want))))
