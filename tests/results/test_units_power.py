"""A power at the edges: drive x speed of an input given in degrees is a power in the deck's units (the speed taken
per radian), and a power's unit is the watt where the deck's units make one."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import mechfem
from deck.test_names_units import fourbar_mm_deg
from mechfem.model.units import Units, symbol
from mechfem.report.dynamics import energy_balance, input_power
from mechfem.results.labels import shown
from output.test_units_outputs import supply_dyn

ROOT = Path(__file__).resolve().parents[2]


def test_the_power_on_an_input_in_degrees_is_the_drives_power_and_its_work_is_the_si_work_converted(
    tmp_path: Path,
) -> None:
    si, mm = supply_dyn(tmp_path)
    for r in (si, mm):
        assert r.dynamic is not None
        on_input = input_power(r)
        assert on_input is not None
        # One input in DYN ANA: drive x speed is the drives' power BUFPOW.
        np.testing.assert_allclose(
            on_input[:, 0], r.dynamic.power, rtol=1e-9, atol=1e-9 * np.abs(r.dynamic.power).max()
        )
    # N·mm/ms is the watt: the same numbers as the SI deck's; its work in N·mm is the SI work in N·m times 1000.
    np.testing.assert_allclose(input_power(mm), input_power(si), rtol=1e-8, atol=1e-8)
    b_si, b_mm = energy_balance(si), energy_balance(mm)
    assert b_si is not None and b_mm is not None
    np.testing.assert_allclose(b_mm.inputs_work, 1e3 * b_si.inputs_work, rtol=1e-6, atol=1e-9)


def test_a_powers_unit_is_the_watt_where_the_units_make_one() -> None:
    mm_ms = Units(length="mm", angle="deg", mass="kg", force="N", time="ms")
    assert shown("power", mm_ms) == "W" and symbol(mm_ms.as_dict(), force=1, length=1, time=-1) == "W"
    assert shown("power", Units(length="mm", force="N")) == "mW"
    assert shown("power", Units(length="in", force="N")) == "N·in/s"
    # A torque keeps force x length; work of the same exponents is named by the joule where the units make one.
    assert shown("torque", mm_ms) == "N·mm" and shown("energy", mm_ms) == "mJ"
    assert shown("energy", Units(length="m", force="N")) == "J"
    assert shown("energy", Units(length="mm", force="kN")) == "J"
    assert shown("energy", Units(length="in", force="N")) == "N·in"
    assert symbol(mm_ms.as_dict(), True, force=1, length=1) == "mJ"
    assert symbol(mm_ms.as_dict(), force=1, length=1) == "N·mm"


def test_a_model_in_mm_read_from_a_deck_without_accuracy_writes_none_and_reads_back_unchanged(tmp_path: Path) -> None:
    deck = tmp_path / "fourbar_mm.mec"
    deck.write_text(fourbar_mm_deg())
    first = mechfem.Mechanism.from_deck(deck)
    assert first.motion is not None and first.motion.accuracy is None
    text = first.to_deck()
    assert "ACCURACY" not in text
    again = tmp_path / "again.mec"
    again.write_text(text)
    second = mechfem.Mechanism.from_deck(again).to_deck()
    # Only the comment naming the model's source differs, and the numbers by rounding (read in mm, computed in m).
    assert len(second.splitlines()) == len(text.splitlines())
    for a, b in zip(second.splitlines()[1:], text.splitlines()[1:], strict=True):
        wa, wb = [_word(w) for w in a.split()], [_word(w) for w in b.split()]
        assert [w for w in wa if isinstance(w, str)] == [w for w in wb if isinstance(w, str)]
        numbers = [w for w in wb if isinstance(w, float)]
        assert [w for w in wa if isinstance(w, float)] == pytest.approx(numbers, rel=1e-13), a


def _word(w: str) -> float | str:
    try:
        return float(w)
    except ValueError:
        return w


def test_the_command_line_says_a_unit_warning_as_the_deck_reader_words_it(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    from mechfem.cli.command import main

    deck = tmp_path / "turn.mec"
    deck.write_text(fourbar_mm_deg().replace("MOV_RELE 1 720.0", "MOV_RELE 1 12.566370614359172"))
    assert "MOV_RELE 1 12.566370614359172" in deck.read_text()
    assert main(["run", str(deck), "-o", str(tmp_path / "out"), "--no-media"]) == 0
    err = capsys.readouterr().err
    assert "warning: the motion's step" in err and "turn.mec:" in err
    # Not Python's form of a warning: no source file of mechfem, no class name.
    assert "UnitWarning" not in err and ".py:" not in err


def test_a_dxf_drawing_of_a_deck_in_mm_says_its_unit_is_the_millimetre(tmp_path: Path) -> None:
    pytest.importorskip("ezdxf")
    import ezdxf

    from mechfem.viz import export

    deck = tmp_path / "fourbar_mm.mec"
    deck.write_text(fourbar_mm_deg())
    [dxf] = export.draw_files(mechfem.run_deck(deck), tmp_path / "out", formats=["dxf"])
    assert ezdxf.readfile(dxf).header["$INSUNITS"] == export.DXF_UNITS["mm"]
    # A deck without UNITS stays unitless; a unit asked for wins.
    plain = mechfem.run_deck(ROOT / "examples" / "fourbar" / "fourbar.mec")
    [dxf] = export.draw_files(plain, tmp_path / "plain", formats=["dxf"])
    assert ezdxf.readfile(dxf).header["$INSUNITS"] == 0
    [dxf] = export.draw_files(plain, tmp_path / "m", formats=["dxf"], units="m")
    assert ezdxf.readfile(dxf).header["$INSUNITS"] == export.DXF_UNITS["m"]


def test_a_label_asked_for_by_a_number_the_model_lacks_is_an_index_error_worded_by_the_core() -> None:
    labels = mechfem.run_deck(ROOT / "examples" / "fourbar" / "fourbar.mec").model.labels
    assert labels is not None
    with pytest.raises(IndexError, match=r"^no co-ordinate 99$"):
        labels.coordinate(99)
    with pytest.raises(IndexError, match=r"^no buffer 999$"):
        labels.buffer(999)
