"""A converter of decks from metres and radians to millimetres and degrees that knows nothing of a deck but the
dimensions the deck reader gives its co-ordinates, rows, inputs and buffers (``Labels``): the tests that compare a
deck's results with its own written again in mm and degrees share it. Each number a deck gives is multiplied by its
unit's factor (a length by 1000, an angle by 180/pi, a derived unit by the product of its exponents' factors): XFIX
and XMOV by the co-ordinate's dimension, PARA by the row's, MOV_RELE and MOV_ABSE by the input's, a MOV_FUNC table's
values, speeds and accelerations by the input's (its time left in seconds), ACCURACY and MOV_FREE's step as lengths;
in DYNAMICS a centre of mass as a length, a moment of inertia as mass x length² (an INERTIA on a length is a mass),
gravity as an acceleration, a LOAD, a MOTOR's stall torque and a SPRING as the generalised force on their row (work
over the row's unit, an angle not counted: a torque in N·mm), the rest by the row's unit; MOV_DYN's speed and
STOPWHEN's value by the input's and the buffer's unit, a TOL's and TOLX's tolerance by its row's and co-ordinate's.
In OPTIMISE, a VARY's range by its row's unit, a VARYX's by its co-ordinate's, a VARYFRAME's as an angle, a VARYM's
as what it varies (a centre as a length, J as mass x length²), a TARGET file's values and a TARGETAT's, TARGETEXT's
and BOUND's values by their buffer's unit, FREETIME's WITHIN by its input's; weights stay (a deck's objective is the
sum of its squared misses in the core's units, whatever its UNITS). Masses, forces and times stay in kg, N and s."""

from __future__ import annotations

import math
from collections.abc import Sequence
from pathlib import Path

import mechfem._core as _core

LENGTH, ANGLE = 1000.0, 180.0 / math.pi


def factor(dims: Sequence[int]) -> float:
    """What a number of the exponents ``dims`` (length, angle, mass, force, time) is multiplied by from m and rad to
    mm and degrees."""
    return float(LENGTH ** dims[0] * ANGLE ** dims[1])


def words(line: str) -> list[str]:
    return line.split(";")[0].split()


SI_UNITS = "UNITS LENGTH m ANGLE rad MASS kg FORCE N TIME s"


def generalised_force(row: Sequence[int]) -> float:
    """The factor of a load on a row of the exponents ``row``: work over the row's length (an angle not counted)."""
    return LENGTH ** (1 - row[0])


LISTS = ("XFIX", "XMOV", "PARA", "MASS", "PMASS", "INERTIA", "VARY", "VARYX", "TOL", "TOLX")
"""The keywords of a list of numbered items: a line that starts with a number goes on with the list."""


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
        if head in LISTS:
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
    elif block in ("XFIX", "XMOV", "VARYX", "TOLX"):
        # A value, a range or a tolerance of a co-ordinate.
        values = [v * factor(labels.coordinate(number)[3]) for v in values]
    elif block in ("PARA", "VARY", "TOL"):
        values = [v * factor(labels.row(number)[3]) for v in values]
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
    if head == "VARYFRAME":
        return f"VARYFRAME {w[1]} {float(w[2]) * ANGLE!r} {float(w[3]) * ANGLE!r}"
    if head == "VARYM":
        # A mass stays in kg; a centre of mass is a length, a moment of inertia mass x length² (an INERTIA on a
        # length is a mass).
        f = {"U": LENGTH, "V": LENGTH, "J": LENGTH**2}.get(w[1].upper(), 1.0)
        if w[1].upper() == "INERTIA" and labels.coordinate(int(w[2]))[3][0] != 1:
            f = LENGTH**2
        return f"VARYM {w[1]} {w[2]} {float(w[3]) * f!r} {float(w[4]) * f!r}"
    if head in ("TARGETAT", "TARGETEXT", "BOUND"):
        # The value (or range) is the last number but a weight: TARGETAT b k value [w], TARGETEXT b bref value
        # [w], BOUND b lo hi.
        f = factor(labels.buffer(int(w[1]))[3])
        at = {"TARGETAT": [3], "TARGETEXT": [3], "BOUND": [2, 3]}[head]
        return " ".join(repr(float(v) * f) if k in at else v for k, v in enumerate(w))
    if head == "FREETIME" and "WITHIN" in [v.upper() for v in w]:
        # FREETIME r ORDERED WITHIN w: the sweep in the input's unit.
        f = factor(labels.row(int(w[1]))[3])
        return " ".join(w[:-1] + [repr(float(w[-1]) * f)])
    if head == "TARGET":
        f = factor(labels.buffer(int(w[1]))[3])
        rows = (tables / w[2]).read_text().splitlines()
        kept = ("#", "*", ";")
        # A value may be followed by a comment.
        converted = [r if not r.strip() or r.strip()[0] in kept else repr(float(r.split(";")[0]) * f) for r in rows]
        (out_dir / w[2]).write_text("\n".join(converted) + "\n")
    if head == "MOV_FUNC":
        f = factor(labels.input(int(w[1]))[5])
        rows = [r.split() for r in (tables / w[2]).read_text().splitlines() if r.strip() and r[0] != "#"]
        converted = [" ".join([r[0], *[repr(float(v) * f) for v in r[1:]]]) for r in rows]
        (out_dir / w[2]).write_text("\n".join(converted) + "\n")
    return None
