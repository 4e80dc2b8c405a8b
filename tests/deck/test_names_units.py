"""A deck in millimetres and degrees (UNITS) with NAMES gives the SI deck's results converted, with its names.

The decks in other units are made here from the examples by hand-written rules (which number is a length, which
an angle), and every buffer is compared with the SI run times the factor its unit implies, written out by hand
(mm/deg is 1000 * pi/180 of m/rad).
"""

from __future__ import annotations

import math
import re
import shutil
import warnings
from collections.abc import Callable
from pathlib import Path

import numpy as np
import pytest

import mechfem
from bare_examples import BARE_EXAMPLES
from mechfem.errors import DeckError

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = BARE_EXAMPLES

L = 1000.0  # m -> mm
DEG = 180.0 / math.pi  # rad -> deg

Rule = Callable[[list[float]], list[float]]


def _number(text: str) -> float:
    return float(text.replace("d", "e").replace("D", "E"))


def converted(text: str, rules: dict[str, Rule], head: str, names: str) -> str:
    """``text`` with the numbers of each keyword's lines changed by ``rules[keyword](numbers)`` (comments
    dropped), the line ``head`` after the mode line and the NAMES block ``names`` before MOVEMENT."""
    out: list[str] = []
    keyword = ""
    for line in text.splitlines():
        words = line.split(";", 1)[0].split()
        if not words:
            continue
        if re.match(r"^[A-Za-z_]", words[0]):
            keyword, lead, args = words[0].upper(), [words[0]], words[1:]
        else:
            lead, args = [], words
        if keyword == "MOVEMENT" and names:
            out.append(names.rstrip("\n"))
            names = ""
        rule = rules.get(keyword)
        if rule is None or not args or not all(re.match(r"^[-+.\d]", a) for a in args):
            out.append(line.split(";", 1)[0])
            continue
        old = [_number(a) for a in args]
        new = rule(old)
        lead = lead or [keyword]
        out.append(" ".join([*lead, *(a if v == o else repr(v) for a, o, v in zip(args, old, new, strict=True))]))
    out.insert(1, head)
    if names:
        out.append(names.rstrip("\n"))
    return "\n".join(out) + "\n"


def run(tmp_path: Path, name: str, text: str) -> mechfem.RunResult:
    path = tmp_path / name
    path.write_text(text)
    return mechfem.run_deck(path)


def by_number(result: mechfem.RunResult) -> dict[int, tuple[str, str]]:
    return {b.number: (b.name, b.unit) for b in result.storage.buffers}


def close(a: np.ndarray, b: np.ndarray, rtol: float = 1e-9) -> None:
    scale = max(float(np.max(np.abs(b))), 1e-300)
    np.testing.assert_allclose(a, b, rtol=0, atol=rtol * scale)


# -- the four-bar ---------------------------------------------------------------------------------------------

FOURBAR_NAMES = """NAMES
POINT 1 2 A0
POINT 3 4 B0
POINT 5 6 A
POINT 7 8 B
POINT 9 10 C
ELEM 1 crank
ELEM 2 coupler
ELEM 3 rocker
ROW 6 phi
DEP 1 psi
BUF 30 transmission quality
"""


def fourbar_mm_deg() -> str:
    text = (EXAMPLES / "fourbar" / "fourbar.mec").read_text()
    rules: dict[str, Rule] = {
        "XFIX": lambda v: [v[0], v[1] * L],
        "XMOV": lambda v: [v[0], v[1] * L],
        "PARA": lambda v: [v[0], v[1] * (DEG if v[0] == 6 else L)],
        "MOV_RELE": lambda v: [v[0], v[1] * DEG],
    }
    return converted(text, rules, "UNITS LENGTH mm ANGLE deg", FOURBAR_NAMES)


def test_fourbar_in_mm_and_degrees_gives_the_si_results_converted(tmp_path: Path) -> None:
    si = mechfem.run_deck(EXAMPLES / "fourbar" / "fourbar.mec")
    mm = run(tmp_path, "fourbar_mm.mec", fourbar_mm_deg())
    assert mm.positions == si.positions == 145
    rad = math.pi / 180
    factors = {
        1: DEG, 2: 1.0, 11: L, 12: L, 13: L * rad, 14: L * rad, 15: L * rad**2, 16: L * rad**2,
        17: L, 18: L, 19: L, 20: L, 21: DEG, 22: 1.0, 23: rad, 24: DEG, 25: DEG,
        # det(D^c): five length rows and the crank angle over six moving lengths.
        30: DEG / L,
    }  # fmt: skip
    for number, factor in factors.items():
        close(mm.buffers[number], si.buffers[number] * factor)
    assert mm.model.units == {"length": "mm", "angle": "deg", "mass": None, "force": None, "time": "s"}
    assert [c.adjusted for c in mm.model.coordinates] == pytest.approx([c.adjusted * L for c in si.model.coordinates])
    labels = by_number(mm)
    assert labels[1] == ("phi", "deg")
    assert labels[2] == ("time", "s")
    assert labels[11] == ("C.x", "mm")
    assert labels[13] == ("dC.x/dphi", "mm/deg")
    assert labels[15] == ("d2C.x/dphi^2", "mm/deg²")
    assert labels[17] == ("vC.x", "mm/s")
    assert labels[19] == ("aC.y", "mm/s²") or labels[20] == ("aC.y", "mm/s²")
    assert labels[21] == ("psi", "deg")
    assert labels[22] == ("dpsi/dphi", "-")
    assert labels[23] == ("d2psi/dphi^2", "1/deg")
    assert labels[24] == ("vpsi", "deg/s")
    assert labels[30] == ("transmission quality", "deg/mm")
    assert [p.name for p in mm.model.points] == ["A0", "B0", "A", "B", "C"]
    assert [e.name for e in mm.model.elements] == ["crank", "coupler", "rocker"]


def test_a_deck_without_names_keeps_todays_labels_and_no_units(tmp_path: Path) -> None:
    si = mechfem.run_deck(EXAMPLES / "fourbar" / "fourbar.mec")
    labels = by_number(si)
    assert labels[11] == ("x9", "")
    assert labels[13] == ("dx9/dinput1", "")
    assert labels[21] == ("ANGB(3)", "")
    assert labels[22] == ("dANGB(3)/dinput1", "")
    assert labels[1] == ("ANGB(1)", "")
    assert si.model.units == dict.fromkeys(["length", "angle", "mass", "force", "time"])
    assert all(c.name is None for c in si.model.coordinates)


def test_units_in_si_give_bit_identical_results(tmp_path: Path) -> None:
    si = mechfem.run_deck(EXAMPLES / "fourbar" / "fourbar.mec")
    text = (EXAMPLES / "fourbar" / "fourbar.mec").read_text().replace("KIN ANA", "KIN ANA\nUNITS LENGTH m ANGLE rad", 1)
    same = run(tmp_path, "fourbar_si.mec", text)
    for number, column in si.buffers.items():
        assert np.array_equal(same.buffers[number], column)
    assert by_number(same)[13] == ("dx9/dinput1", "m/rad")


# -- the supply mechanism, kinematics and inverse dynamics ----------------------------------------------------

SUPPLY_NAMES = """NAMES
POINT 13 14 K
ROW 5 kappa
ROW 12 phi
DEP 1 psi
"""
LENGTH_ROWS = {1, 2, 3, 4, 6, 7, 8, 9, 10, 11}


def supply_rules(time: float) -> dict[str, Rule]:
    return {
        "XFIX": lambda v: [v[0], v[1] * L],
        "XMOV": lambda v: [v[0], v[1] * L],
        "PARA": lambda v: [v[0], v[1] * (L if v[0] in LENGTH_ROWS else DEG)],
        "MOV_RELE": lambda v: [v[0], v[1] * DEG],
        "VARY": lambda v: [v[0], v[1] * DEG, v[2] * DEG],
        # u along the element in mm, the inertia in kg mm^2
        "MASS": lambda v: [v[0], v[1], v[2] * L, v[3] * L, v[4] * L * L],
        "GRAVITY": lambda v: [x * L / time**2 for x in v],
        # a torque on an angle, in N mm
        "LOAD": lambda v: [v[0], v[1] * L],
        "TSTEPE": lambda v: [v[0], *(x * time for x in v[1:])],
        # a torsion spring in N mm/deg about a free angle in deg, its damper in N mm time/deg
        "SPRING": lambda v: [v[0], v[1] * L / DEG, v[2] * DEG, v[3] * L / DEG * time],
        # a motor's stall torque in N mm, its no-load speed in deg/time
        "MOTOR": lambda v: [v[0], v[1] * L, v[2] * DEG / time],
        "MOV_DYN": lambda v: [v[0], v[1] * DEG / time],
    }


def test_supply_mechanism_in_mm_and_degrees(tmp_path: Path) -> None:
    si = mechfem.run_deck(EXAMPLES / "supply" / "supply.mec")
    text = converted(
        (EXAMPLES / "supply" / "supply.mec").read_text(), supply_rules(1.0), "UNITS LENGTH mm ANGLE deg", SUPPLY_NAMES
    )
    mm = run(tmp_path, "supply_mm.mec", text)
    for number, factor in {99: DEG, 100: DEG, 101: 1.0, 102: math.pi / 180}.items():
        close(mm.buffers[number], si.buffers[number] * factor)
    labels = by_number(mm)
    assert labels[101] == ("dpsi/dphi", "-")
    assert labels[99] == ("phi", "deg")


def test_supply_inverse_dynamics_in_mm_degrees_and_milliseconds(tmp_path: Path) -> None:
    si = mechfem.run_deck(EXAMPLES / "supply" / "supply_dyn.mec")
    ms = 1000.0
    text = converted(
        (EXAMPLES / "supply" / "supply_dyn.mec").read_text(),
        supply_rules(ms),
        "UNITS LENGTH mm ANGLE deg MASS kg FORCE N TIME ms",
        SUPPLY_NAMES,
    )
    mm = run(tmp_path, "supply_dyn_mm.mec", text)
    factors = {
        99: DEG, 100: DEG,
        110: L,  # drive torque N mm
        111: L, 112: L,  # energies N mm
        113: L / ms,  # power N mm / ms
        114: 1.0,  # the force in a length row, N
        115: 1.0, 116: 1.0,  # reactions on the frame's lengths, N
        117: L * L,  # reduced inertia, kg mm^2
    }  # fmt: skip
    for number, factor in factors.items():
        close(mm.buffers[number], si.buffers[number] * factor, rtol=1e-8)
    labels = by_number(mm)
    assert labels[110] == ("drive(phi)", "N·mm")
    assert labels[113] == ("power", "W")
    assert labels[117] == ("M(phi,phi)", "kg·mm²")
    assert labels[114][1] == "N"


def test_supply_simulation_in_mm_degrees_and_milliseconds(tmp_path: Path) -> None:
    ms = 1000.0
    source = (EXAMPLES / "supply" / "supply_sim.mec").read_text().replace("TSTEPE 800 2.5E-3", "TSTEPE 100 2E-2")
    source = "".join(
        s for s in source.splitlines(keepends=True) if not re.match(r"\s*(ANIMATE|BEGINPIC|ENDPIC|PLOT)", s)
    )
    si = run(tmp_path, "supply_sim_si.mec", source)
    text = converted(source, supply_rules(ms), "UNITS LENGTH mm ANGLE deg MASS kg FORCE N TIME ms", SUPPLY_NAMES)
    mm = run(tmp_path, "supply_sim_mm.mec", text)
    assert mm.positions == si.positions == 101
    factors = {98: ms, 99: DEG, 100: DEG, 101: DEG / ms, 111: L, 112: L, 114: 1.0, 115: 1.0, 116: 1.0}
    for number, factor in factors.items():
        close(mm.buffers[number], si.buffers[number] * factor, rtol=1e-7)
    assert by_number(mm)[101] == ("vphi", "deg/ms")


def test_kin_opt_with_vary_and_targets_in_degrees(tmp_path: Path) -> None:
    """The supply mechanism's kappa optimised from a deck in mm and degrees (VARY in degrees) and from the SI deck
    (24 steps, to be quick): the same design, and the final design deck keeps UNITS and gets kappa in degrees."""
    from mechfem.design import optimise_deck

    source = (EXAMPLES / "supply" / "supply_opt.mec").read_text().replace("TSTEPE 72", "TSTEPE 24")
    source = "".join(
        s for s in source.splitlines(keepends=True) if not re.match(r"\s*(ANIMATE|BEGINPIC|ENDPIC|PLOT)", s)
    )
    text = converted(source, supply_rules(1.0), "UNITS LENGTH mm ANGLE deg", SUPPLY_NAMES)
    assert "VARY 5 -315.12" in text
    kappa = {}
    for name, deck_text in [("si", source), ("mm", text)]:
        deck = _write(tmp_path, f"supply_opt_{name}.mec", deck_text)
        outcome = optimise_deck.optimise(deck, optimise_deck.describe(deck).optimise)  # type: ignore[arg-type]
        written = optimise_deck.write_design_deck(outcome, tmp_path / name).read_text()
        kappa[name] = float(re.search(r"^\s*(?:PARA)?\s+5 (\S+)", written, re.M).group(1))  # type: ignore[union-attr]
        if name == "mm":
            assert "UNITS LENGTH mm ANGLE deg" in written
            # The co-ordinates of the final design's position 1 are written in millimetres.
            x9 = float(re.search(r"^XMOV 9 (\S+)", written, re.M).group(1))  # type: ignore[union-attr]
            assert 100 < abs(x9) < 1000
    assert abs(kappa["mm"] - kappa["si"] * DEG) < 1e-6 * DEG
    assert abs(kappa["si"] - (-5.17514)) < 1e-2


def _write(tmp_path: Path, name: str, text: str) -> Path:
    path = tmp_path / name
    path.write_text(text)
    return path


# -- mistakes -------------------------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("line", "words"),
    [
        ("NAMES\nPIONT 1 2 A\n", "not a kind of name"),
        ("NAMES\nPOINT 1 2 A-B\n", "is not a name"),
        ("NAMES\nELEM 1 crank\nELEM 2 crank\n", "given to two elements"),
        ("NAMES\nCOORD 99 s\n", "does not have"),
        ("UNITS LENGTH furlong\n", "not a unit of length"),
    ],
)
def test_a_bad_names_or_units_line_is_a_deck_error(tmp_path: Path, line: str, words: str) -> None:
    text = re.sub(
        r"^MOVEMENT", line + "MOVEMENT", (EXAMPLES / "fourbar" / "fourbar.mec").read_text(), count=1, flags=re.M
    )
    with pytest.raises(DeckError, match=words):
        run(tmp_path, "bad.mec", text)


# -- every example: SI units change no bit --------------------------------------------------------------------


@pytest.mark.parametrize("deck", sorted(EXAMPLES.glob("**/*.mec")), ids=lambda p: p.stem)
def test_an_example_in_si_units_gives_its_results_bit_for_bit(deck: Path, tmp_path: Path) -> None:

    from mechfem import _core

    text = deck.read_text()
    if re.search(r"^\s*UNITS\b", text, re.M):
        pytest.skip("the example declares its units")
    folder = tmp_path / deck.parent.name
    shutil.copytree(deck.parent, folder)
    mode = re.search(r"^\s*(KIN|DYN)\s+\w+.*$", text, re.M)
    assert mode is not None
    si = folder / deck.name
    si.write_text(text[: mode.end()] + "\nUNITS LENGTH m ANGLE rad MASS kg FORCE N TIME s" + text[mode.end() :])
    a, b = _core.run_deck(deck), _core.run_deck(si)
    for key in ("table", "coords"):
        assert np.array_equal(
            np.asarray(getattr(a, key)).view(np.uint64), np.asarray(getattr(b, key)).view(np.uint64)
        ), key


def test_an_angle_that_looks_like_degrees_is_warned_about(tmp_path: Path) -> None:
    from mechfem import _core

    text = (EXAMPLES / "fourbar" / "fourbar.mec").read_text().replace("MOV_RELE 1 12.566370614359172", "MOV_RELE 1 720")
    with pytest.warns(_core.UnitWarning, match=r"720 is an angle in radians, but looks like degrees") as caught:
        run(tmp_path, "degrees.mec", text)
    assert "UNITS ANGLE deg" in str(caught[0].message)
    # The same deck saying so is taken in degrees, without a warning.
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        result = run(tmp_path, "said.mec", text.replace("KIN ANA", "KIN ANA\nUNITS ANGLE deg", 1))
    assert result.buffers[1][-1] == pytest.approx(720.0)
