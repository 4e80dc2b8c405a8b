"""Every kinematic example, written again in millimetres and degrees by a converter that knows nothing of it but the
dimensions the deck reader gives its co-ordinates, rows and inputs (``Labels``), gives the SI deck's results
converted: every buffer, every co-ordinate and det(D^c) at every position, and the same limit positions.

The converter multiplies each number a deck gives by its unit's factor (a length by 1000, an angle by 180/pi, a
derived unit by the product of its exponents' factors): XFIX and XMOV by the co-ordinate's dimension, PARA by the
row's, MOV_RELE and MOV_ABSE by the input's, a MOV_FUNC table's values, speeds and accelerations by the input's
(its time left in seconds), ACCURACY and MOV_FREE's step as lengths. A deck with UNITS of its own is left out, and
so is every mode but KIN ANA (the dynamic and design decks have tests of their own in ``test_names_units.py``)."""

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


def kinematic_examples() -> list[Path]:
    out = []
    for deck in sorted((ROOT / "examples").rglob("*.mec")):
        lines = [words(line) for line in deck.read_text().splitlines()]
        keywords = {w[0].upper() for w in lines if w}
        mode = next(" ".join(w[:2]).upper() for w in lines if w)
        if mode == "KIN ANA" and "UNITS" not in keywords:
            out.append(deck)
    return out


def in_mm_and_degrees(text: str, labels: _core.Labels, tables: Path, out_dir: Path) -> str:
    """The deck ``text`` with every number converted and the UNITS line after its mode line; its MOV_FUNC tables
    (in the folder ``tables``) written converted into ``out_dir``."""
    out, block, moded = [], "", False
    for line in text.splitlines():
        w = words(line)
        if not w:
            out.append(line)
            continue
        head = w[0].upper()
        if not moded:
            out += [line, "UNITS LENGTH mm ANGLE deg"]
            moded = True
            continue
        if head in ("XFIX", "XMOV", "PARA"):
            block, w = head, w[1:]
        elif not w[0].lstrip("-").isdigit():
            block = ""
        if block and len(w) == 2:
            number, value = int(w[0]), float(w[1])
            dims = labels.coordinate(number)[3] if block != "PARA" else labels.row(number)[3]
            line = f"{block if head == block else ''} {number} {value * factor(dims)!r}"
        elif head in ("MOV_RELE", "MOV_ABSE"):
            j = int(w[1])
            line = f"{head} {j} {float(w[2]) * factor(labels.input(j)[5])!r}"
        elif head in ("ACCURACY", "MOV_FREE"):
            line = f"{' '.join(w[:-1])} {float(w[-1]) * LENGTH!r}"
        elif head == "MOV_FUNC":
            f = factor(labels.input(int(w[1]))[5])
            rows = [r.split() for r in (tables / w[2]).read_text().splitlines() if r.strip() and r[0] != "#"]
            converted = [" ".join([r[0], *[repr(float(v) * f) for v in r[1:]]]) for r in rows]
            (out_dir / w[2]).write_text("\n".join(converted) + "\n")
        out.append(line)
    return "\n".join(out) + "\n"


@pytest.mark.parametrize("deck", kinematic_examples(), ids=lambda p: p.stem)
def test_a_kinematic_example_in_mm_and_degrees_gives_the_si_results_converted(deck: Path, tmp_path: Path) -> None:
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
