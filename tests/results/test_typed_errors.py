"""Errors are typed and worded in the core; the binding maps types and fields, and a front end adds only what is
its own to say (how the command line raises a limit)."""

from __future__ import annotations

import pytest
from tests.conftest import ROOT

import mechfem
import mechfem._core as _core
from mechfem._util import limits

FOURBAR = ROOT / "examples" / "fourbar" / "fourbar.mec"


def test_a_refused_run_carries_the_cores_facts_and_the_deck_path_says_how_to_raise_the_limit() -> None:
    with pytest.raises(mechfem.ResourceError) as err:
        mechfem.run_deck(FOURBAR, memory_limit=1)
    e = err.value
    positions, values = e.positions, e.values  # type: ignore[attr-defined]
    assert positions > 1 and values > 1
    assert e.need == positions * values * 24 and e.limit == 1  # type: ignore[attr-defined]
    assert str(e).endswith(f"or raise the limit {limits.RAISE_DECK_LIMIT}")
    assert f"({positions} positions x {values} values)" in str(e)


def test_the_cores_refusal_names_no_front_ends_option() -> None:
    model = _core.Model.from_path(FOURBAR)
    with pytest.raises(mechfem.ResourceError) as err:
        model.run(memory_limit=1)
    assert str(err.value).endswith("or raise the limit")
    assert "--memory-limit" not in str(err.value) and "MECHFEM_MEMORY_LIMIT" not in str(err.value)


def test_a_named_models_refusal_is_in_the_python_apis_words(monkeypatch: pytest.MonkeyPatch) -> None:
    m = mechfem.Mechanism.from_deck(FOURBAR)
    monkeypatch.setenv("MECHFEM_MEMORY_LIMIT", "1")
    with pytest.raises(mechfem.ResourceError) as err:
        m.run()
    assert "the Motion's steps" in str(err.value) and "--memory-limit" not in str(err.value)
