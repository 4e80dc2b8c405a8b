"""Names and units of every quantity a person reads: python/mechfem/results/labels.py and its uses in the data set, the
print file and the pictures.

The expected names and units are written by hand from the element catalogue (docs/elements.md: which form
parameter and which co-ordinate is an angle, a length or a ratio) and the buffer table (docs/deck.md).
"""

from __future__ import annotations

import csv
import math
import re
from pathlib import Path

import pytest
from matplotlib.figure import Figure

import mechfem
from conftest import ROOT, SUPPLY
from mechfem.model.echo import ModelNames
from mechfem.model.mechanism import Driven, Mechanism, Motion, Output, Storage
from mechfem.output.files import print_file_lines, write_data_set
from mechfem.results.labels import Label, buffer_labels, label, over, point_name, squared
from mechfem.results.result import RunResult
from mechfem.viz.plots import picture_figure

EVERY_ELEMENT = ROOT / "tests" / "decks" / "every_element.mec"
SUPPLY_DYN = ROOT / "examples" / "supply" / "supply_dyn.mec"

# The every-element deck with a buffer of every kinematic keyword. Its rows: 1 LENL(2), 2 ANGB(2), 3 GEAR(1) of
# the rack RK2, 4 BELT(6), 5 GEAR(8) of the gear pair GR2, 6 GEAR(10) of GR1, 7 LENU(11), ..., 12 COOR(3) on x1 (a
# point's x: the input, a length); dependent 1 is ANGV(4). Co-ordinate 8 is the pinion's angle, 7 the rack's i
# (its radius, a length), 18 a GR2 radius and 23 GR1's ratio.
KINEMATIC_BUFFERS = """STORAGE
BUFINP 1 1
BUFTIME 2
BUFDET 3
BUFE0 1 10
BUFE0 2 11
BUFE0 3 12
BUFE0 4 13
BUFE0 5 14
BUFE0 6 15
BUFE0 7 16
BUFE0 12 17
BUFE0 -1 18
BUFX0 1 20
BUFX0 8 21
BUFX0 7 22
BUFX0 18 23
BUFX0 23 24
BUFKX1 8 1 30
BUFKX2 1 1 31
BUFKX2 8 1 1 32
BUFVX 1 33
BUFAX 8 34
BUFKE1 -1 1 40
BUFKE2 -1 1 41
BUFVE -1 42
BUFAE -1 43
BUFKE1 4 1 44
PRINTBUF
"""

EXPECTED_KINEMATIC: dict[int, tuple[str, str, str]] = {
    1: ("COOR(3)", "length", "input"),
    2: ("time", "s", "time"),
    3: ("det(D^c)", "length/rad", "det"),  # the rows' units over the moving co-ordinates'
    10: ("LENL(2)", "length", "position"),
    11: ("ANGB(2)", "rad", "position"),
    12: ("GEAR(1)", "length", "position"),  # a rack's g is an assembly length
    13: ("BELT(6)", "length", "position"),
    14: ("GEAR(8)", "rad", "position"),  # a gear pair's g is an assembly angle
    15: ("GEAR(10)", "rad", "position"),
    16: ("LENU(11)", "length", "position"),
    17: ("COOR(3)", "length", "position"),
    18: ("ANGV(4)", "rad", "position"),
    20: ("x1", "length", "position"),
    21: ("x8", "rad", "position"),
    22: ("x7", "length", "position"),
    23: ("x18", "length", "position"),
    24: ("x23", "", "position"),
    30: ("dx8/dinput1", "rad/length", "first order"),
    31: ("d2x1/dinput1^2", "1/length", "second order"),
    32: ("d2x8/dinput1^2", "rad/length^2", "second order"),
    33: ("vx1", "length/s", "velocity"),
    34: ("ax8", "rad/s^2", "acceleration"),
    40: ("dANGV(4)/dinput1", "rad/length", "first order"),
    41: ("d2ANGV(4)/dinput1^2", "rad/length^2", "second order"),
    42: ("vANGV(4)", "rad/s", "velocity"),
    43: ("aANGV(4)", "rad/s^2", "acceleration"),
    44: ("dBELT(6)/dinput1", "", "first order"),
}


@pytest.fixture(scope="module")
def kinematic(tmp_path_factory: pytest.TempPathFactory) -> RunResult:
    text = EVERY_ELEMENT.read_text()
    deck = tmp_path_factory.mktemp("labels") / "every_buffer.mec"
    deck.write_text(text[: text.index("STORAGE")] + KINEMATIC_BUFFERS)
    return mechfem.run_deck(deck)


def unnamed(deck: Path) -> str:
    """The text of ``deck`` without its NAMES block: the labels of the deck's numbers."""
    lines = deck.read_text().splitlines()
    if "NAMES" not in lines:
        return "\n".join(lines) + "\n"
    start = lines.index("NAMES")
    end = next(
        k
        for k in range(start + 1, len(lines))
        if lines[k][:1].isalpha()
        and lines[k].split()[0].isupper()
        and lines[k].split()[0] not in ("POINT", "COORD", "ELEM", "ROW", "DEP", "BUF")
    )
    return "\n".join(lines[:start] + lines[end:]) + "\n"


@pytest.fixture(scope="module")
def supply(tmp_path_factory: pytest.TempPathFactory) -> RunResult:
    deck = tmp_path_factory.mktemp("labels") / "supply.mec"
    deck.write_text(unnamed(SUPPLY))
    return mechfem.run_deck(deck)


def test_every_kinematic_buffer_keyword_has_its_name_unit_and_kind(kinematic: RunResult) -> None:
    labels = buffer_labels(kinematic)
    assert {n: (x.name, x.base, x.kind) for n, x in labels.items()} == EXPECTED_KINEMATIC
    # Without UNITS a label shows an angle in rad, a pure number as -, and no unit where a length, force or mass
    # takes part.
    rad = {11, 14, 15, 18, 21}
    shown_units = {2: "s", 24: "-", 34: "rad/s²", 42: "rad/s", 43: "rad/s²", 44: "-"} | dict.fromkeys(rad, "rad")
    assert {n: x.unit for n, x in labels.items() if x.unit} == shown_units


def test_a_label_gives_the_header_cell_the_axis_and_the_words(supply: RunResult) -> None:
    x = label(supply, 101)
    assert x.header() == "101 dANGB(8)/dinput1"
    assert x.axis() == "dANGB(8)/dinput1 [-]"
    assert x.text == "first-order transfer function of ANGB(8) (dependent form parameter 1) with respect to input 1"
    assert label(supply, 99) == Label(99, "ANGB(1)", "rad", "input", "value of input 1 (ANGB(1))", base="rad")
    assert label(supply, 102).axis() == "d2ANGB(8)/dinput1^2 [1/rad]"
    assert Label(1, "det(D^c)", "", "det", "").axis() == "det(D^c)"


def test_a_combined_row_is_named_by_its_formula_without_spaces(tmp_path: Path) -> None:
    # Row 5 of the supply deck is ANGB(2) - ANGB(4), the angle in the coupler plane.
    deck = tmp_path / "combined.mec"
    deck.write_text(unnamed(SUPPLY).replace("  BUFINP  1  99\n", "  BUFINP  1  99\n  BUFE0 5 98\n  BUFKE1 5 1 97\n"))
    result = mechfem.run_deck(deck)
    assert (label(result, 98).name, label(result, 98).base) == ("ANGB(2)-ANGB(4)", "rad")
    # The derivative brackets the combination so that the name reads unambiguously.
    assert label(result, 97).name == "d(ANGB(2)-ANGB(4))/dinput1"


def test_dynamics_buffers_carry_force_torque_energy_power_and_mass(tmp_path: Path) -> None:
    deck = tmp_path / "dyn.mec"
    extra = "  BUFSIG 5 120\n  BUFSIG 12 121\n  BUFREA 3 122\n"
    deck.write_text(unnamed(SUPPLY_DYN).replace("  PRINTBUF\n", extra + "  PRINTBUF\n"))
    labels = buffer_labels(mechfem.run_deck(deck))
    got = {n: (x.name, x.base, x.kind) for n, x in labels.items() if n >= 110}
    assert got == {
        110: ("drive(ANGB(1))", "torque", "force"),  # the input is an angle: its drive is a torque
        111: ("Ekin", "energy", "energy"),
        112: ("Epot", "energy", "energy"),
        113: ("power", "power", "power"),
        114: ("sigma(LENL(5))", "force", "force"),  # row 6, a length: an axial force
        115: ("reaction(x1)", "force", "force"),
        116: ("reaction(x2)", "force", "force"),
        117: ("M(1,1)", "mass·length^2", "mass"),  # the reduced inertia at a crank
        120: ("sigma(ANGB(2)-ANGB(4))", "torque", "force"),
        121: ("sigma(ANGB(1))", "torque", "force"),
        122: ("reaction(x3)", "force", "force"),
    }


def test_units_of_derivatives_divide_by_each_input() -> None:
    assert over("rad", "rad") == "rad/rad"
    assert over("", "rad") == "1/rad"
    assert over("rad", "") == "rad"
    assert over("length", squared("rad", "length")) == "length/(rad·length)"
    assert over("rad", squared("rad", "rad")) == "rad/rad^2"
    assert squared("", "rad") == "rad"


def test_a_mixed_second_order_derivative_names_both_inputs(tmp_path: Path) -> None:
    deck = tmp_path / "manipulator.mec"
    deck.write_text(unnamed(ROOT / "examples" / "manipulator" / "manipulator.mec"))
    result = mechfem.run_deck(deck)
    # BUFKX2 5 1 2 23: d2 xM / d l1 d l2, both inputs actuator lengths.
    assert (label(result, 23).name, label(result, 23).base) == ("d2x5/dinput1dinput2", "1/length")
    assert label(result, 23).text.endswith("with respect to input 1 and input 2")


def fourbar() -> Mechanism:
    m = Mechanism("fourbar")
    a0, b0 = m.fixed("A0", 0.0, 0.0), m.fixed("B0", 4.0, 0.0)
    a, b, c = m.point("A", 1.0, 0.0), m.point("B", 3.5, 2.5), m.point("C", 1.5, 2.0)
    m.bar("crank", a0, a, length=1.0, angle=Driven(start=0.0, name="phi"))
    coupler = m.ternary2("coupler", a, b, c, length=3.5, u=1.5, v=1.2)
    rocker = m.bar("rocker", b0, b, length=3.0, angle=Output("psi"))
    m.output("transmission", coupler.angle - rocker.angle)
    m.output("reach", m.bar("B0C", b0, c).length)
    return m


def test_a_named_model_is_labelled_with_its_own_names() -> None:
    storage = (
        Storage()
        .buffer(1, "BUFINP", "phi")
        .buffer(2, "BUFKE1", "psi", "phi")
        .buffer(3, "BUFVX", "C.x")
        .buffer(4, "BUFE0", "transmission")
        .buffer(5, "BUFKX2", "C.y", "phi")
        .buffer(6, "BUFX0", "A.y")
    )
    storage.picture("coupler", ("PLOTHODO", "C"))
    a = fourbar().run(Motion.by(12, 2 * math.pi), storage)
    result = a.run_result()
    got = {n: (x.name, x.base) for n, x in buffer_labels(result).items()}
    assert got == {
        1: ("phi", "rad"),
        2: ("dpsi/dphi", ""),
        3: ("vC.x", "length/s"),
        4: ("transmission", "rad"),
        5: ("d2C.y/dphi^2", "length/rad^2"),
        6: ("A.y", "length"),
    }
    ix, iy = _point_coords(a, "C")
    fig = picture_figure(result, 0)
    assert isinstance(fig, Figure)
    ax = fig.axes[0]
    # The model gives no unit of length: none is shown.
    assert (ax.get_xlabel(), ax.get_ylabel()) == ("C.x", "C.y")
    assert any(line.get_label() == "path of C" for line in ax.lines)
    assert point_name(result, ix, iy) == "C"


def _point_coords(a: mechfem.Analysis, name: str) -> tuple[int, int]:
    p = a.mechanism[name]
    return a.numbering.coord_number[p.x], a.numbering.coord_number[p.y]  # type: ignore[union-attr]


def test_analysis_plot_puts_outputs_of_different_units_in_panels_of_their_own() -> None:
    a = fourbar().run(Motion.by(12, 2 * math.pi))
    fig = a.plot()
    assert isinstance(fig, Figure)
    mechanism, angles, lengths = fig.axes
    assert angles.get_ylabel() == "psi, transmission [rad]"
    assert lengths.get_ylabel() == "reach"
    assert (angles.get_xlabel(), lengths.get_xlabel()) == ("", "phi [rad]")
    assert angles.get_shared_x_axes().joined(angles, lengths)


def test_the_data_set_header_holds_number_and_name(supply: RunResult, tmp_path: Path) -> None:
    path = write_data_set(supply, tmp_path / "supply.csv")
    with path.open(newline="") as f:
        header = next(csv.reader(f))
    assert header == ["99 ANGB(1)", "100 ANGB(8)", "101 dANGB(8)/dinput1", "102 d2ANGB(8)/dinput1^2"]
    # A program takes the number as the first word of the cell.
    assert [int(cell.split()[0]) for cell in header] == supply.storage.savedata


def test_a_name_with_a_comma_is_quoted_in_the_header(supply: RunResult, tmp_path: Path) -> None:
    names = ModelNames(coordinates=[], prescribed=["a"] * 12, dependent=["angle, output"], inputs=["crank"])
    named = supply.replace(names=names)
    path = write_data_set(named, tmp_path / "named.csv")
    first = path.read_text().splitlines()[0]
    assert first.startswith('99 crank,"100 angle, output","101 d(angle, output)/dcrank"')
    with path.open(newline="") as f:
        header = next(csv.reader(f))
    assert header[1] == "100 angle, output" and len(header) == 4


def test_the_print_file_has_a_legend_and_named_column_heads(supply: RunResult) -> None:
    lines = print_file_lines(supply)
    k = lines.index("BUFFERS")
    legend = [re.split(r"\s{2,}", line.strip()) for line in lines[k + 1 : k + 6]]
    assert legend == [
        ["no", "name", "unit", "deck line", "what it holds"],
        ["99", "ANGB(1)", "rad", "BUFINP 1", "value of input 1 (ANGB(1))"],
        ["100", "ANGB(8)", "rad", "BUFE0 -1", "ANGB(8) (dependent form parameter 1)"],
        [
            "101",
            "dANGB(8)/dinput1",
            "-",
            "BUFKE1 -1 1",
            "first-order transfer function of ANGB(8) (dependent form parameter 1) with respect to input 1",
        ],
        [
            "102",
            "d2ANGB(8)/dinput1^2",
            "1/rad",
            "BUFKE2 -1 1 1",
            "second-order transfer function of ANGB(8) (dependent form parameter 1) with respect to input 1 (twice)",
        ],
    ]
    head = lines.index("  position                99               100               101                  102")
    assert lines[head + 1].split() == ["ANGB(1)", "ANGB(8)", "dANGB(8)/dinput1", "d2ANGB(8)/dinput1^2"]
    # Columns stay aligned: every name and value ends where its number does, and a name longer than the usual
    # 18 characters widens its column.
    ends = [m.end() for m in re.finditer(r"\S+", lines[head])][1:]
    for line in lines[head + 1 : head + 2 + supply.positions]:
        assert [m.end() for m in re.finditer(r"\S+", line)][-4:] == ends
    first = lines[head + 2].split()
    assert first[0] == "1" and float(first[1]) == pytest.approx(float(f"{supply.buffers[99][0]:.10g}"), abs=0)


def test_labels_survive_a_pickle_as_the_cores_table(supply: RunResult) -> None:
    import pickle

    named = mechfem.run_deck(SUPPLY_DYN)
    for result in (supply, named):
        back = pickle.loads(pickle.dumps(result))
        assert buffer_labels(back) == buffer_labels(result)
        labels, table = result.model.labels, back.model.labels
        assert labels is not None and table is not None
        assert table.det() == labels.det() and table.input(1) == labels.input(1)
        assert table.scale([0, 1, 0, 0, 0]) == labels.scale([0, 1, 0, 0, 0])
