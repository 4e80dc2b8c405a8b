"""What a run did crosses the binding as the compiled module's own typed objects (``_core.Report``, ``Adjust``,
``Limit``, ``Stop``): read through attributes, 1-based, equal when they tell the same, picklable; the Python
:class:`~mechfem.RunReport` says them in words as before."""

from __future__ import annotations

import pickle
from pathlib import Path

import pytest

import mechfem
from mechfem import _core

ROOT = Path(__file__).resolve().parents[2]
LIMITS = ROOT / "examples" / "limits"
FOURBAR = ROOT / "examples" / "fourbar" / "fourbar.mec"

# The dead-centre deck stops on purpose.
pytestmark = pytest.mark.filterwarnings("ignore::mechfem.IncompleteRunWarning")


def test_a_stopped_runs_report_is_typed_and_one_based() -> None:
    # slider_dead_centre.mec drives the crank into the dead centre: the motion stops at a located limit.
    result = mechfem.run_deck(LIMITS / "slider_dead_centre.mec")
    r = result._raw.report
    assert type(r) is _core.Report and type(r.adjust) is _core.Adjust
    assert r.positions == result.positions and r.stop is not None and type(r.stop) is _core.Stop
    stop = r.stop
    assert stop.last_good == r.positions  # 1-based: the last position computed
    assert stop.limit is not None and stop.limit.kind == "input_limit"
    assert stop.limit.after == stop.last_good
    assert stop.message and stop.parts
    # The Python report tells the same.
    py = result.report
    assert py.stop is not None and py.stop.last_good == stop.last_good and py.stop.kind == stop.kind
    assert py.stop.limit is not None and py.stop.limit.det == stop.limit.det
    assert py.adjust.initial_deformations == r.adjust.initial_deformations
    assert result.stop_reason() is not None


def test_limits_met_on_the_way_are_typed() -> None:
    # nongrashof.mec moves freely through limit positions of its input.
    r = mechfem.run_deck(LIMITS / "nongrashof.mec")._raw.report
    kinds = {x.kind for x in r.limits}
    assert "passed" in kinds and all(type(x) is _core.Limit for x in r.limits)
    assert all(1 <= x.after < r.positions for x in r.limits)


def test_reports_compare_by_value_and_survive_a_pickle() -> None:
    for deck in (LIMITS / "slider_dead_centre.mec", LIMITS / "nongrashof.mec", FOURBAR):
        r = mechfem.run_deck(deck)._raw.report
        back = pickle.loads(pickle.dumps(r))
        assert back == r and back is not r
        assert back.stop == r.stop and back.limits == r.limits and back.adjust == r.adjust
    a = _core.Adjust(3, 1, [0.5, -0.25], 1e-12)
    assert a != _core.Adjust(3, 1, [0.5, -0.25], 2e-12)
    limit = _core.Limit("passed", 4, [1.0], [0.0, 1.0], 0.0)
    assert (limit.kind, limit.after) == ("passed", 4) and limit != _core.Limit("near_zero", 4, [1.0], [0.0, 1.0], 0.0)


def test_a_pickled_result_keeps_its_report() -> None:
    result = mechfem.run_deck(LIMITS / "slider_dead_centre.mec")
    back = pickle.loads(pickle.dumps(result))
    assert back._raw.report == result._raw.report
    assert back.stop_reason() == result.stop_reason()


def test_a_check_hands_its_adjustment_typed() -> None:
    check = mechfem.check_deck(FOURBAR)
    assert check.adjust.iterations >= 1 and check.adjust.stages >= 1
    assert check.adjust.residual < 1e-9


def test_a_report_reads_as_the_call_that_makes_it() -> None:
    r = mechfem.run_deck(LIMITS / "slider_dead_centre.mec")._raw.report
    assert r.stop is not None and r.stop.limit is not None
    text = repr(r)
    assert text.startswith(f"Report(adjust=Adjust(iterations={r.adjust.iterations}, ")
    assert f"positions={r.positions}, steps={r.steps}" in text and f"last_good={r.stop.last_good}" in text
    assert f"kind={r.stop.kind!r}".replace("'", '"') in text and 'limit=Limit(kind="input_limit"' in text
