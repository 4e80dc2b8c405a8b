"""What the report adds for a DYN deck (python/mechfem/report/dynamics.py): the power of each input's drive or motor,
the energy balance, the pin forces as arrows and the shaking force as a polar plot, checked against the run's own
buffers and the motor's law, not against the module's own arithmetic."""

from __future__ import annotations

import warnings
from typing import Any

import numpy as np
import pytest

import mechfem
from conftest import ROOT
from mechfem.report import dynamics as rd
from mechfem.report.charts import Columns, dynamics_cards
from mechfem.report.html import report_data, report_positions
from mechfem.results.result import RunResult
from mechfem.results.result_tables import run_units

SIM = ROOT / "examples" / "supply" / "supply_sim.mec"
FORCES = ROOT / "examples" / "supply" / "supply_forces.mec"


def run(deck: Any) -> RunResult:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return mechfem.run_deck(deck)


@pytest.fixture(scope="module")
def sim() -> RunResult:
    return run(SIM)


@pytest.fixture(scope="module")
def forces() -> RunResult:
    return run(FORCES)


def column(data: dict[str, Any], key: str) -> np.ndarray:
    return np.array([np.nan if v is None else v for v in data["columns"][key]["values"]], dtype=np.float64)


def card(data: dict[str, Any], start: str) -> dict[str, Any]:
    found = [c for c in data["cards"] if c["title"].startswith(start)]
    assert len(found) == 1, [c["title"] for c in data["cards"]]
    return found[0]


def test_the_motor_of_a_simulation_delivers_its_law_and_its_power(sim: RunResult) -> None:
    # MOTOR 12 12.0 70.0: T = 12 (1 - w / 70) at the input's speed w, which the deck records itself (BUFVE 12 101).
    speed = sim.buffers[101]
    torque = 12.0 * (1.0 - speed / 70.0)
    np.testing.assert_allclose(sim.dynamic.drive[:, 0], torque, rtol=1e-9, atol=1e-9)
    power = rd.input_power(sim)
    assert power is not None
    np.testing.assert_allclose(power[:, 0], torque * speed, rtol=1e-9, atol=1e-9)
    # BUFPOW is the stresses' power: for an input the forces move, only the rounding of the equations of motion.
    assert np.max(np.abs(sim.dynamic.power)) < 1e-6 * np.max(np.abs(power))


def test_the_energy_balance_of_a_simulation_closes(sim: RunResult) -> None:
    bal = rd.energy_balance(sim)
    assert bal is not None
    # The motor spins the mechanism up (T + V grows by about 62 J in 2 s) against the brakes, which dissipate.
    assert bal.change[-1] > 50.0 and bal.inputs_work[-1] > bal.change[-1] and bal.loads_work[-1] < -100.0
    # The bound the docs state: the residual stays below 1e-4 of the largest term (2.4e-5 at dt = 2.5 ms).
    assert bal.relative_residual() < 1e-4
    # Without the brakes' work it would not close: the check can fail.
    unbraked = rd.EnergyBalance(bal.time, bal.change, bal.inputs_work, 0.0 * bal.loads_work)
    assert unbraked.relative_residual() > 0.5


def test_the_simulation_report_charts_the_motor_and_the_balance(sim: RunResult) -> None:
    # The cards alone (report_data would also draw the mechanism at each of the 801 positions).
    cols = Columns(report_positions(sim.positions), run_units(sim))
    data = {"cards": dynamics_cards(sim, cols), "columns": cols.table, "frames": list(cols.frames)}
    power = card(data, "power of the drives and motors against time")
    key = power["charts"][0]["series"][0]["y"]
    frames = np.asarray(data["frames"])
    np.testing.assert_allclose(column(data, key), (sim.dynamic.drive[:, 0] * sim.buffers[101])[frames], rtol=6e-6)
    balance = card(data, "energy balance against time")
    residual = balance["charts"][1]["series"][0]["y"]
    assert data["columns"][residual]["kind"] == "residual"
    assert np.nanmax(np.abs(column(data, residual))) < 1e-4 * rd.energy_balance(sim).scale()  # type: ignore[union-attr]


def test_in_inverse_dynamics_the_inputs_power_is_the_drives_power(forces: RunResult) -> None:
    power = rd.input_power(forces)
    assert power is not None
    np.testing.assert_allclose(power[:, 0], forces.buffers[113], rtol=1e-9, atol=1e-9)  # BUFPOW 113
    bal = rd.energy_balance(forces)
    assert bal is not None and bal.relative_residual() < 1e-3  # 72 positions a turn


def test_the_pin_force_arrows_are_the_runs_pin_forces_at_the_largest(forces: RunResult) -> None:
    data = report_data(forces)
    pins = card(data, "pin forces")
    frames = np.asarray(data["frames"])
    frame = pins["jump"]["frame"]
    chart = pins["charts"][0]
    series = chart["series"]
    names = [s["name"] for s in series]
    assert names[:2] == ["crank on A", "rocker on B"] and names[-1] == "reaction at M0"
    # Each arrow against the run's own answer by name: pin_force(element, point), reaction(point).
    expected = {
        "crank on A": forces.pin_force("crank", "A"),
        "rocker on B": forces.pin_force("rocker", "B"),
        "link on K": forces.pin_force("link", "K"),
        "link on G": forces.pin_force("link", "G"),
        "rod on H": forces.pin_force("rod", "H"),
        "output on M": forces.pin_force("output", "M"),
        **{f"reaction at {p}": forces.reaction(p) for p in ("A0", "B0", "G0", "M0")},
    }
    assert set(names) == set(expected)
    largest = 0.0
    for s in series:
        f = expected[s["name"]][frames]
        np.testing.assert_allclose([column(data, s["fx"])[frame], column(data, s["fy"])[frame]], f[frame], rtol=6e-6)
        np.testing.assert_allclose(column(data, s["fx"]), f[:, 0], rtol=6e-6, atol=1e-9)
        # The arrow starts at the pin.
        point = forces.value(s["short"])[frames[frame]]
        np.testing.assert_allclose([column(data, s["x"])[frame], column(data, s["y"])[frame]], point, rtol=6e-6)
        largest = max(largest, float(np.max(np.hypot(f[:, 0], f[:, 1]))))
    # The position is where the largest of them occurs, and its arrow is a quarter of the mechanism's size.
    at = max(float(np.hypot(*expected[n][frames[frame]])) for n in names)
    assert at == pytest.approx(largest, rel=1e-12)
    x0, x1, y0, y1 = data["scene"]["bounds"]
    assert largest * chart["force_scale"] == pytest.approx(rd.ARROW_SHARE * np.hypot(x1 - x0, y1 - y0), rel=1e-9)


def test_the_polar_plot_is_the_shaking_force(forces: RunResult) -> None:
    data = report_data(forces)
    shaking = card(data, "shaking force")
    polar, moment = shaking["charts"]
    frames = np.asarray(data["frames"])
    expected = forces.shaking()[frames]
    assert polar["equal"] and polar["origin"]
    s = polar["series"][0]
    np.testing.assert_allclose(column(data, s["x"]), expected[:, 0], rtol=6e-6, atol=1e-9)
    np.testing.assert_allclose(column(data, s["y"]), expected[:, 1], rtol=6e-6, atol=1e-9)
    # BUFSHAKE 150: x, y and the moment in 150, 151, 152.
    np.testing.assert_allclose(expected, np.column_stack([forces.buffers[150 + k][frames] for k in range(3)]))
    np.testing.assert_allclose(column(data, moment["series"][0]["y"]), expected[:, 2], rtol=6e-6, atol=1e-9)
    assert moment["type"] == "function" and moment["x"] == "in1"


def test_a_kinematic_report_has_no_dynamics_cards() -> None:
    data = report_data(run(ROOT / "examples" / "supply" / "supply.mec"))
    titles = " ".join(c["title"] for c in data["cards"])
    assert "pin forces" not in titles and "energy balance" not in titles and "shaking" not in titles


def test_a_named_models_balance_closes_with_a_motor_on_its_driven_input() -> None:
    from model.test_dynamics_api import pendulum, swing

    m = pendulum()
    m.motor(m["theta"], 5.0, 8.0)
    r = m.run(swing())
    power = rd.input_power(r)
    assert power is not None
    np.testing.assert_allclose(power[:, 0], r.power(), rtol=1e-9, atol=1e-9)
    bal = rd.energy_balance(r)
    assert bal is not None
    # The motor (5 N m at rest, none at 8 rad/s) does work beside the drive: without it the balance would not close.
    assert np.max(np.abs(bal.loads_work)) > 0.1 * bal.scale()
    assert bal.relative_residual() < 1e-4
