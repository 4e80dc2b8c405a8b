"""``RunResult.to_pandas()`` carries the unit of every column in ``attrs["units"]`` (and ``table_units()`` gives
the same mapping): the model's units, or those ``unit=`` asks for, matching the numbers in the columns."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

import mechfem
from conftest import fourbar_mm_deg, mechfem_command
from mechfem import Motion

pytest.importorskip("pandas")

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


@pytest.fixture(scope="module")
def result() -> mechfem.RunResult:
    return fourbar_mm_deg().run(Motion.by(12, 360))


def test_every_column_has_its_unit_in_the_models_units(result: mechfem.RunResult) -> None:
    frame = result.to_pandas()
    units = frame.attrs["units"]
    assert list(units) == list(frame.columns) and units == result.table_units()
    assert units["time"] == "s" and units["phi"] == "deg" and units["phi_dot"] == "deg/s"
    assert (units["psi"], units["psi'"], units["psi''"]) == ("deg", "-", "1/deg")
    assert (units["psi_dot"], units["psi_ddot"]) == ("deg/s", "deg/s²")
    assert (units["A.x"], units["A.x'"], units["A.x''"]) == ("mm", "mm/deg", "mm/deg²")
    assert units["B.y_dot"] == "mm/s"


def test_unit_changes_the_columns_and_their_units_together(result: mechfem.RunResult) -> None:
    deg, rad, metres = result.to_pandas(), result.to_pandas(unit="rad"), result.to_pandas(unit="m")
    per_degree = 180.0 / math.pi
    assert rad.attrs["units"]["psi"] == "rad" and rad.attrs["units"]["A.x'"] == "mm/rad"
    assert rad.attrs["units"]["A.x''"] == "mm/rad²" and rad.attrs["units"]["A.x"] == "mm"
    np.testing.assert_allclose(rad["A.x'"], deg["A.x'"] * per_degree, rtol=1e-12)
    np.testing.assert_allclose(rad["psi"], np.radians(deg["psi"]), rtol=1e-12)
    assert metres.attrs["units"]["A.x"] == "m" and metres.attrs["units"]["A.x'"] == "m/deg"
    np.testing.assert_allclose(metres["A.x"], deg["A.x"] / 1000.0, rtol=1e-12)
    # A ratio of two angles is the same number in either unit.
    assert rad.attrs["units"]["psi'"] == "-"
    np.testing.assert_array_equal(rad["psi'"], deg["psi'"])


def test_a_deck_without_units_gives_angles_in_radians_and_no_length_unit() -> None:
    units = mechfem.run_deck(EXAMPLES / "fourbar" / "fourbar.mec").to_pandas().attrs["units"]
    assert units["phi"] == "rad" and units["time"] == "s"
    assert units["A.x"] == "" and units["det"] == ""


def test_the_dynamics_columns_carry_the_units_of_their_buffers() -> None:
    result = mechfem.run_deck(EXAMPLES / "supply" / "supply_dyn.mec")
    units = result.to_pandas().attrs["units"]
    by_name = {b.name: b.unit for b in result.storage.buffers}
    for column in ("drive(alpha)", "Ekin", "Epot", "power", "sigma(link.length)", "reaction(A0.x)"):
        assert units[column] == by_name[column] != ""
    assert (units["drive(alpha)"], units["Ekin"], units["power"]) == ("N·m", "J", "W")
    assert units["A.x"] == "m" and units["alpha"] == "rad"


def test_a_named_models_dynamics_columns_are_in_its_units() -> None:
    m = fourbar_mm_deg({"length": "mm", "mass": "kg", "force": "N"})
    m.mass("coupler", 0.2, J=0.01)
    units = m.run(Motion.by(4, 360)).to_pandas().attrs["units"]
    # A torque in N·mm, work of the same exponents in mJ, power in mW (N·mm/s).
    assert units["drive(phi)"] == "N·mm" and units["Ekin"] == units["Epot"] == "mJ" and units["power"] == "mW"


def test_a_column_says_its_unit_as_the_data_set_header_does(tmp_path: Path) -> None:
    """The same quantity, a second-order transfer function in mm/deg², recorded by a deck's buffer and written to
    the data set by the command: the table's unit and the data set header's are one string."""
    import subprocess

    storage = mechfem.Storage().buffer(1, "BUFX0", "A.x").buffer(2, "BUFKX2", "A.x", "phi")
    deck = tmp_path / "fourbar.mec"
    storage.savedata = [1, 2]
    fourbar_mm_deg().save_deck(deck, Motion.by(12, 360), storage=storage)
    p = subprocess.run([*mechfem_command(), "run", str(deck), "-o", str(tmp_path / "out"), "--no-media"], text=True)
    assert p.returncode == 0
    header = (tmp_path / "out" / "fourbar.csv").read_text().splitlines()[0]
    assert "[mm/deg²]" in header, header
    assert mechfem.run_deck(deck).table_units()["A.x''"] == "mm/deg²"
