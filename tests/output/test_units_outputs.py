"""Every output of a deck with UNITS speaks its units and names: the data set's header, the print file (its units
line, the model echo, the DYNAMICS echo and summary, the adjustment, the simulation, the limit positions), and a
number that looks like the wrong unit is warned about wherever a designer writes one.

The decks are made from the examples by the hand-written conversion rules of ``test_names_units``.
"""

from __future__ import annotations

import csv
import math
import re
import warnings
from pathlib import Path

import pytest

import mechfem
from deck.test_names_units import DEG, EXAMPLES, SUPPLY_NAMES, L, converted, fourbar_mm_deg, run, supply_rules
from mechfem.output.files import write_outputs

ROOT = Path(__file__).resolve().parents[2]
MS = 1000.0
DYN_UNITS = "UNITS LENGTH mm ANGLE deg MASS kg FORCE N TIME ms"


def outputs(result: mechfem.RunResult, tmp_path: Path) -> tuple[list[str], str]:
    """The data set's header and the print file's text of ``result``."""
    write_outputs(result, tmp_path / "out")
    stem = result.deck.stem
    with open(tmp_path / "out" / f"{stem}.csv", newline="") as f:
        header = next(csv.reader(f))
    return header, (tmp_path / "out" / f"{stem}.prt").read_text()


def supply_dyn(tmp_path: Path) -> tuple[mechfem.RunResult, mechfem.RunResult]:
    """The supply mechanism's inverse dynamics with a point mass and a force at its named point K, in SI and in
    mm, kg, N and ms."""
    source = (EXAMPLES / "supply" / "supply_dyn.mec").read_text()
    source = re.sub(r"^(GRAVITY.*)$", r"\1\nPMASS 13 14 0.05\nFORCE 13 14 0 -1", source, count=1, flags=re.M)
    si = run(tmp_path, "supply_dyn_si.mec", source)
    mm = run(tmp_path, "supply_dyn_mm.mec", converted(source, supply_rules(MS), DYN_UNITS, SUPPLY_NAMES))
    return si, mm


def numbers(line: str) -> list[float]:
    return [float(x) for x in re.findall(r"-?\d+(?:\.\d+)?(?:e[-+]?\d+)?", line)]


def line_with(text: str, start: str) -> str:
    return next(x.strip() for x in text.splitlines() if x.strip().startswith(start))


def test_the_data_set_header_gives_each_buffers_unit_with_units_and_none_without(tmp_path: Path) -> None:
    header, _ = outputs(run(tmp_path, "fourbar_mm.mec", fourbar_mm_deg()), tmp_path)
    assert "1 phi [deg]" in header and "22 dpsi/dphi [-]" in header and "13 dC.x/dphi [mm/deg]" in header
    header, _ = outputs(mechfem.run_deck(EXAMPLES / "fourbar" / "fourbar.mec"), tmp_path)
    assert not any("[" in cell for cell in header)
    assert all(int(cell.split()[0]) > 0 for cell in header)


def test_the_print_file_says_the_units_and_gives_the_dynamics_in_the_decks_numbers(tmp_path: Path) -> None:
    si, mm = supply_dyn(tmp_path)
    _, text = outputs(mm, tmp_path)
    assert "units: LENGTH mm ANGLE deg MASS kg FORCE N TIME ms" in text
    # GRAVITY as the deck gives it, 9.81 m/s² in mm/ms², not the core's SI number.
    gravity = line_with(text, "GRAVITY")
    assert gravity.endswith("mm/ms²") and numbers(gravity) == pytest.approx([0.0, -9.81e-3])
    body = line_with(text, "MASS      element 5")
    assert numbers(body)[1:] == pytest.approx([1.0, 339.0, 0.0, 38400.0]) and "kg·mm²" in body
    # The point mass and the force are named by their NAMES point, the load by its row's name.
    assert "PMASS     point K: m 0.05 kg" in text
    assert "FORCE     point K: (0, -1) N" in text
    assert line_with(text, "LOAD").startswith("LOAD      psi: constant -2000 N·mm")
    # The echo of the model: a value and a co-ordinate with its unit.
    assert re.search(r"^\s+5\s+-?[\d.]+ deg\s+ANGB\(2\) - ANGB\(4\)\s+= kappa$", text, re.M)
    assert re.search(r"^\s+13\s+XMOV\s+\S+\s+\S+ mm\s+= K\.x$", text, re.M)
    # The adjustment's deformation of the kappa row is in degrees: the SI deck's in radians times 180/pi.
    _, si_text = outputs(si, tmp_path / "si")
    mm_row5, si_row5 = line_with(text, "row    5:"), line_with(si_text, "row    5:")
    assert mm_row5.endswith("deg") and numbers(mm_row5)[1] == pytest.approx(numbers(si_row5)[1] * DEG)
    # The summary: the drive in N·mm at an input in degrees, the energies in mJ (N·mm of work), power in W (N·mm/ms).
    drive, si_drive = line_with(text, "drive of DOF 1"), line_with(si_text, "drive of DOF 1")
    assert "N·mm at position" in drive and "deg)," in drive
    assert numbers(drive)[1] == pytest.approx(numbers(si_drive)[1] * L, rel=1e-8)
    assert "W" in line_with(text, "work of the drives").split()
    assert line_with(text, "kinetic energy").endswith("mJ")
    # Without UNITS the print file says so and shows no unit.
    assert "units: none declared" in si_text and "N·mm" not in si_text


def test_a_simulation_in_milliseconds_reports_its_times_in_milliseconds(tmp_path: Path) -> None:
    deck = """DYN SIM
UNITS LENGTH cm ANGLE deg MASS g FORCE kN TIME ms
TOPOLOGY
ELEM 1 BIN 1 2 3 4
FORM 1 LENL 1 1
     2 ANGB 1 2
NRDOF 1
GEOMETRY
XFIX 1 0.0
     2 0.0
XMOV 3 100.0
     4 0.0
PARA 1 100.0
     2 0.0
NAMES
POINT 3 4 bob
ROW 2 theta
DYNAMICS
PMASS 3 4 2000
GRAVITY 0 -0.000981
MOVEMENT
TSTEPE 20 50
MOV_DYN 1 0
STOPWHEN 2 -60
STORAGE
BUFTIME 1
BUFINP 1 2
SAVEDATA 1 2
END
"""
    result = run(tmp_path, "pendulum_ms.mec", deck)
    _, text = outputs(result, tmp_path)
    reached = line_with(text, "time reached")
    assert reached.endswith(" ms")
    # The pendulum of length 1 m falls from horizontal to 60 degrees below in some hundreds of milliseconds.
    assert 100.0 < numbers(reached)[0] < 1000.0
    assert numbers(reached)[0] == pytest.approx(float(result.buffers[1][-1]), rel=1e-9)
    stop = line_with(text, "stopped by STOPWHEN")
    # The value crossed is STOPWHEN's own, in degrees, as are the inputs there.
    assert "buffer 2 crossed -60 at time" in stop
    assert "ms (inputs" in stop and stop.endswith("deg)")
    assert result.simulation is not None and result.simulation.reached == pytest.approx(numbers(reached)[0])
    assert numbers(stop.split("inputs")[1])[0] == pytest.approx(-60.0, abs=1e-6)
    assert "T + V:" in text and line_with(text, "T + V:").count("kN·cm") == 3
    assert math.isfinite(numbers(line_with(text, "T + V:"))[0])


def test_a_limit_position_is_said_in_degrees_and_by_the_inputs_name(tmp_path: Path) -> None:
    source = (ROOT / "examples" / "limits" / "locked_fourbar.mec").read_text()
    text = source.replace("KIN ANA", "KIN ANA\nUNITS LENGTH mm ANGLE deg", 1)
    text = text.replace("0.04363323129985824", "2.5").replace("MOV_RELE 1 6.283185307179586", "MOV_RELE 1 360")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", mechfem.IncompleteRunWarning)
        result = run(tmp_path, "locked_mm.mec", text)
    limit = result.report.stop.limit  # type: ignore[union-attr]
    assert limit is not None
    # theta = acos((70² + 20² - 89.996²) / (2 70 20)) = 178.70 degrees, where coupler and rocker lie in line.
    theta = math.degrees(math.acos((70**2 + 20**2 - 89.996**2) / (2 * 70 * 20)))
    assert limit.inputs[0] == pytest.approx(theta, abs=1e-3)
    # The co-ordinates of A there are in millimetres: A lies on the crank circle of radius 20.
    assert math.hypot(limit.coords[4], limit.coords[5]) == pytest.approx(20.0, rel=1e-6)
    reason = result.report.stop_reason()
    assert reason is not None and "theta" in reason and f"{theta:.4f}"[:6] in reason


@pytest.mark.parametrize(
    ("change", "words"),
    [
        (lambda t: t.replace("MOV_RELE 1 720.0", "MOV_RELE 1 6.283185307179586"), "the motion's step"),
        (lambda t: re.sub(r"^PARA 6 \S+", "PARA 6 1.5707963", t, count=1, flags=re.M), "the prescribed value"),
    ],
)
def test_an_angle_in_radians_in_a_degree_deck_is_warned_about(tmp_path: Path, change: object, words: str) -> None:
    text = change(fourbar_mm_deg())  # type: ignore[operator]
    with pytest.warns(mechfem.UnitWarning, match=rf"{words} .* is an angle in degrees, but looks like radians"):
        run(tmp_path, "slip.mec", text)


def test_a_bound_on_an_angle_that_looks_like_degrees_is_warned_about(tmp_path: Path) -> None:
    source = (EXAMPLES / "supply" / "supply_opt.mec").read_text()
    # A bound of 180 on psi (buffer 100), an angle in radians: the designer meant degrees.
    bounded = re.sub(r"^(OPTIMISE.*)$", r"\1\nBOUND 100 -180 180", source, count=1, flags=re.M)
    assert bounded != source
    path = tmp_path / "bound.mec"
    path.write_text(bounded)
    with pytest.warns(mechfem.UnitWarning) as caught:
        mechfem.check_deck(path)
    said = [str(w.message) for w in caught]
    assert any("the lower bound -180 is an angle in radians, but looks like degrees" in m for m in said), said
    assert any("the upper bound 180" in m for m in said), said


def _crank(angle: str, start: float) -> mechfem.Mechanism:
    m = mechfem.Mechanism("crank", length="mm", angle=angle)
    m.bar("arm", m.fixed("O", 0, 0), m.point("T", 100, 0), length=100.0, angle=mechfem.Driven(start=start, name="phi"))
    return m


def _unit_warnings(m: mechfem.Mechanism, motion: mechfem.Motion) -> list[str]:
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        m.run(motion)
    return [str(w.message) for w in caught if issubclass(w.category, mechfem.UnitWarning)]


def test_a_mechanism_warns_once_of_a_start_value_or_a_step_in_the_wrong_unit() -> None:
    # A start value of pi/2 where angles are degrees.
    said = _unit_warnings(_crank("deg", 1.5708), mechfem.Motion.by(4, 90))
    assert len(said) == 1 and "start value 1.5708 of the angle input 'phi'" in said[0]
    # A step of 2 pi where angles are degrees.
    said = _unit_warnings(_crank("deg", 30.0), mechfem.Motion.by(4, 6.2832))
    assert len(said) == 1 and "step 6.2832" in said[0] and "looks like radians" in said[0]
    # 720 radians: Python's warning only, not the core's as well.
    said = _unit_warnings(_crank("rad", 0.5), mechfem.Motion.by(4, 720))
    assert len(said) == 1 and "by 720 rad" in said[0]
    # Nothing to say of ordinary numbers.
    assert _unit_warnings(_crank("deg", 30.0), mechfem.Motion.by(4, 90)) == []
    assert _unit_warnings(_crank("rad", 0.5), mechfem.Motion.by(4, 6.2832)) == []


def test_a_kept_model_warns_of_a_wrong_unit_at_every_run_and_checks_again_after_a_change() -> None:
    # The run on a kept model skips the check of units only while it has nothing to say.
    m, looks_like_radians = _crank("deg", 30.0), mechfem.Motion.by(4, 6.2832)
    for _ in range(3):
        said = _unit_warnings(m, looks_like_radians)
        assert len(said) == 1 and "step 6.2832" in said[0]
    quiet = mechfem.Motion.by(4, 90)
    assert _unit_warnings(m, quiet) == [] and _unit_warnings(m, quiet) == []
    # A start value changed in place to one that looks like radians is a new shape: checked, and said.
    m.set("phi", 1.5708)
    said = _unit_warnings(m, quiet)
    assert len(said) == 1 and "start value 1.5708" in said[0]
