"""The element catalogue and the solver's defaults come from the core: the binding's view of them equals the
documented catalogue (docs/deck.md) and the documented defaults, and the Python front's tables are that view.

The Rust side checks the same facts (crates/mechfem-core/src/elements/mod.rs, catalogue_tests)."""

from __future__ import annotations

import re

import pytest

import mechfem
from conftest import ROOT
from mechfem import _core
from mechfem.model import catalogue, loads, motion, parts

# What each co-ordinate and form parameter measures, written out from the theory (independent of the code):
# L a length, A an angle, R a ratio, * whatever its co-ordinate is.
DIMENSIONS = {
    "BIN": ("LLLL", "LA"),
    "HLF": ("LLA", "A"),
    "TR1": ("LLALL", "ALL"),
    "TR2": ("LLLLLL", "LALL"),
    "GR1": ("AAAR", "A"),
    "GR2": ("AAALL", "A"),
    "RK1": ("LLALLLA", "L"),
    "RK2": ("LLLLLLLA", "L"),
    "BLT": ("LLALLALL", "LAL"),
    "CRD": ("*", "*"),
}
LETTER = {"length": "L", "angle": "A", "ratio": "R", "any": "*"}
SLOTS = {
    "BIN": "PP",
    "HLF": "Pa",
    "TR1": "PaP",
    "TR2": "PPP",
    "GR1": "aaas",
    "GR2": "aaass",
    "RK1": "PaPsa",
    "RK2": "PPPsa",
    "BLT": "PaPass",
    "CRD": "s",
}


def documented() -> dict[str, tuple[list[str], list[str]]]:
    """docs/deck.md's element table: each type's co-ordinates and form parameters, in order."""
    out: dict[str, tuple[list[str], list[str]]] = {}
    text = (ROOT / "docs" / "deck.md").read_text()
    for m in re.finditer(r"^\| `([A-Z0-9]{3})` \| [^|]+ \| ([^|]+) \| ([^|]+) \|$", text, re.M):
        out[m.group(1)] = (m.group(2).split(), re.findall(r"`([A-Z]{4})`", m.group(3)))
    return out


def test_the_catalogue_is_the_documented_one() -> None:
    table = documented()
    got = _core.catalogue()
    assert [e.type for e in got] == list(table)
    for e in got:
        names, forms = table[e.type]
        assert [n for n, _ in e.coordinates] == names
        assert [f for f, _ in e.forms] == forms
        coords, form_dims = DIMENSIONS[e.type]
        assert "".join(LETTER[k] for _, k in e.coordinates) == coords, e.type
        assert "".join(LETTER[k] for _, k in e.forms) == form_dims, e.type
        assert e.slots == SLOTS[e.type]
    assert [e.type for e in got if e.frame] == ["BIN", "HLF", "TR1", "TR2"]


def test_the_python_tables_are_the_cores() -> None:
    core = {e.type: e for e in _core.catalogue()}
    assert catalogue.FORMS == {t: tuple(f for f, _ in e.forms) for t, e in core.items()}
    assert catalogue.SLOTS == SLOTS
    assert loads.FRAMES == ("BIN", "HLF", "TR1", "TR2")
    # Every form parameter has a Python name, and no Python name is left for one the core does not have.
    assert set(parts.ATTRIBUTES) == {f for fs in catalogue.FORMS.values() for f in fs}
    assert set(parts.ELEMENT_WORDS) == set(core)


def test_the_defaults_are_the_documented_ones() -> None:
    # docs/deck.md and the spec: ACCURACY 1e-10, MAXITER 25; the reader refuses MAXITER > 1000, TSTEPE > 1e7.
    assert _core.DEFAULTS.accuracy == 1e-10
    assert _core.DEFAULTS.max_iter == 25
    assert (_core.DEFAULTS.max_iter_limit, _core.DEFAULTS.max_steps) == (1000, 10_000_000)
    assert (catalogue.DEFAULT_ACCURACY, catalogue.DEFAULT_MAX_ITER) == (1e-10, 25)
    assert (motion.MAX_ITER, motion.MAX_STEPS) == (1000, 10_000_000)


def test_the_limits_are_the_deck_readers() -> None:
    # A motion at the limit is accepted by the Python checks, one above is refused, naming the core's limit.
    limit = _core.DEFAULTS.max_iter_limit
    mechfem.Motion.by(1, 1.0, max_iter=limit)
    with pytest.raises(ValueError, match=f"max_iter must be from 1 to {limit}"):
        mechfem.Motion.by(1, 1.0, max_iter=limit + 1)


def test_a_racks_gear_is_a_length_and_a_gear_pairs_an_angle() -> None:
    # g = i (beta_a - beta_b) - u on a rack (i the pinion's radius, u a distance), an assembly angle on a gear pair.
    assert catalogue.form_dimension("RK1", "GEAR") == catalogue.form_dimension("RK2", "GEAR") == "length"
    assert catalogue.form_dimension("GR1", "GEAR") == catalogue.form_dimension("GR2", "GEAR") == "angle"
