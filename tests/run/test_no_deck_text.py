"""Runs, design, optimisation and studies of a Python model hand it to the typed builder: no deck text is written or
read on their way (the deck writer and every entry of the compiled module that takes deck text raise here), not even
for a model the compiler refuses or a value no deck can state, and the results are those of the deck text of the same
model, bit for bit."""

from __future__ import annotations

import math
from collections.abc import Iterator
from concurrent.futures import ThreadPoolExecutor
from typing import Any

import numpy as np
import pytest

import mechfem
import mechfem._core as _core
from mechfem import Driven, Mechanism, Motion, Q
from mechfem.deck import deckio
from mechfem.model.mechanism import Table
from mechfem.model.storage import Storage
from mechfem.run import building
from model.test_model_api import supply
from studies.test_batch import fourbar, stroke

MOTION = Motion.by(36, 2 * math.pi)


@pytest.fixture
def no_deck_text(monkeypatch: pytest.MonkeyPatch) -> Iterator[None]:
    """The deck writer, and the compiled module's readers of deck text, raise."""

    def refuse(*args: Any, **kwargs: Any) -> Any:
        raise AssertionError("deck text was written or read")

    monkeypatch.setattr(deckio, "write", refuse)
    monkeypatch.setattr(deckio, "write_text", refuse)
    monkeypatch.setattr(_core, "DesignModel", refuse)
    monkeypatch.setattr(_core, "run_deck_text", refuse)
    real = _core.run_deck_variants

    def variants(texts: list[Any], *args: Any, **kwargs: Any) -> Any:
        assert all(isinstance(t, _core.ModelBuilder) for t in texts), "a study was given deck text"
        return real(texts, *args, **kwargs)

    monkeypatch.setattr(_core, "run_deck_variants", variants)
    yield


def test_the_deck_writer_is_refused_by_the_fixture(no_deck_text: None) -> None:
    with pytest.raises(AssertionError, match="deck text"):
        fourbar().to_deck(MOTION)


def test_optimize_and_sensitivity_write_no_deck(no_deck_text: None) -> None:
    opt = mechfem.optimize(
        fourbar(),
        {"rocker.length": (2.5, 3.5), "B0.x": (3.5, 4.5)},
        targets=[mechfem.TargetAt(Q("psi"), 10, 1.6)],
        motion=MOTION,
        steps=4,
    )
    assert opt.objective < opt.start_objective and opt.runs > 1
    r = fourbar().run(MOTION)
    s = r.sensitivity(Q("psi"), ["rocker.length", "B0.x"])
    assert s.shape == (r.positions, 2) and np.all(np.isfinite(s))


def test_studies_write_no_deck(no_deck_text: None) -> None:
    one = mechfem.sweep(fourbar(), {"rocker.length": [2.9, 3.1]}, {"stroke": stroke}, motion=MOTION, progress=False)
    fn = mechfem.sweep(fourbar, {"rocker": [2.9, 3.1]}, {"stroke": stroke}, motion=MOTION, progress=False)
    with ThreadPoolExecutor(2) as ex:
        far = mechfem.sweep(
            fourbar, {"rocker": [2.9, 3.1]}, {"stroke": stroke}, motion=MOTION, progress=False, executor=ex
        )
    assert np.array_equal(one["stroke"], fn["stroke"]) and np.array_equal(fn["stroke"], far["stroke"])
    many = mechfem.run_many([fourbar(2.9), fourbar(3.1)], MOTION, progress=False)
    assert [stroke(a) for a in many] == list(one["stroke"])  # type: ignore[arg-type]
    tol = mechfem.tolerance_study(fourbar(), {"rocker.length": 0.01}, {"stroke": stroke}, n=4, seed=1, motion=MOTION)
    assert len(tol.study["stroke"]) == 4


def test_a_failing_variant_is_worded_in_the_models_names_without_a_deck(no_deck_text: None) -> None:
    # A rocker too short to reach: position 1 cannot be assembled, which the run finds, not the deck reader.
    study = mechfem.sweep(fourbar, {"rocker": [3.0, 0.1]}, {"stroke": stroke}, motion=MOTION, progress=False)
    assert list(study["ok"]) == [True, False]
    assert "fourbar" in study["error"][1] and "B" in study["error"][1]


def _evaluations(model: Any, x: list[float]) -> tuple[Any, ...]:
    d = model.evaluate(x)
    return d.values, d.gradient, d.position_one


def test_the_built_design_model_is_the_deck_texts_bit_for_bit() -> None:
    from mechfem.design.optimise import _Deck, _variable

    m = supply()
    motion = Motion.by(24, 2 * math.pi)
    deck = _Deck(m)
    buffers = [deck.buffer(Q("delta")), deck.buffer(Q("delta", 2)), deck.buffer(Q("B.y"))]
    built = building.builder(m, motion, deck.storage)
    written = deckio.write(m, motion, deck.storage)
    variables = [_variable(m, built.numbering, n)[:2] for n in ["kappa", "B0.x", "rod.length"]]
    with deckio.tables_dir(written.tables) as base:
        from_text = _core.DesignModel(written.text, written.path, base, variables, buffers, [])
        from_items = built.builder.design(base, variables, buffers, [])
    assert from_text.start() == from_items.start()
    for x in (from_text.start(), [v * 1.001 for v in from_text.start()]):
        a, b = _evaluations(from_text, x), _evaluations(from_items, x)
        assert np.array_equal(a[0], b[0]) and np.array_equal(a[1], b[1]) and a[2] == b[2]


def test_a_study_is_the_deck_texts_bit_for_bit() -> None:
    m = supply()
    motion = Motion.by(24, 2 * math.pi)
    built = building.builder(m, motion, None)
    written = deckio.write(m, motion, None)
    variants: list[tuple[int, list[tuple[int, int, float]]]] = [(0, []), (0, [(1, 5, -5.2)]), (0, [(0, 1, 0.01)])]
    with deckio.tables_dir(written.tables) as base:
        a = _core.run_deck_variants([written.text], variants, "v.mec", base, 1, None, None, 2)
        b = _core.run_deck_variants([built.builder], variants, "v.mec", base, 1, None, None, 2)
    for x, y in zip(a, b, strict=True):
        assert not isinstance(x, Exception) and not isinstance(y, Exception)
        assert x.report.stop is None and y.report.stop is None
        for name in ("table", "coords"):
            assert np.array_equal(getattr(x, name), getattr(y, name))


def _failure(m: Mechanism) -> mechfem.MechfemError:
    with pytest.raises(mechfem.MechfemError) as info:
        m.run(MOTION)
    return info.value


def test_a_run_that_fails_is_worded_without_a_deck_as_its_deck_would_word_it(monkeypatch: pytest.MonkeyPatch) -> None:
    from mechfem.deck.explain import translate

    # The rocker cannot reach the coupler: position 1 cannot be assembled. Its deck text's run, worded for the model.
    deck = deckio.write(fourbar(0.1), MOTION, None)
    with pytest.raises(mechfem.MechfemError) as raw:
        _core.run_deck_text(deck.text, deck.path, ".", True, None, 2)
    by_text = translate(raw.value, deck, "fourbar")
    kept = fourbar()
    kept.run(MOTION)
    kept.set("rocker.length", 0.1)

    def refuse(*args: Any, **kwargs: Any) -> Any:
        raise AssertionError("deck text was written")

    monkeypatch.setattr(deckio, "write", refuse)
    # A model built afresh, and a kept one given numbers it cannot assemble.
    for err in (_failure(fourbar(0.1)), _failure(kept)):
        assert type(err) is type(by_text) and str(err) == str(by_text)
        assert "'fourbar'" in str(err)


def test_a_variant_the_deck_reader_refuses_is_worded_as_its_run_words_it() -> None:
    m = fourbar()
    m.point("Z", 0.0, 1.0)  # on no element: the deck reader refuses its co-ordinates
    with pytest.raises(mechfem.DeckError) as single:
        m.run(MOTION)
    (out,) = mechfem.run_many([m], MOTION, progress=False)
    assert isinstance(out, mechfem.DeckError) and str(out) == str(single.value)
    for field in ("line", "column", "text", "kind", "name", "deck"):
        assert getattr(out, field) == getattr(single.value, field)


def _coincident() -> Mechanism:
    m = Mechanism("coincident")
    m.bar("crank", m.fixed("A0", 0.0, 0.0), m.point("A", 0.0, 0.0), length=1.0, angle=Driven())
    return m


def _refused(m: Mechanism, motion: Motion | None = MOTION) -> Any:
    with pytest.raises(mechfem.DeckError) as info:
        m.run(motion)
    e: Any = info.value
    # Nothing of a deck: no written text, no line of one.
    assert e.deck is None and e.line is None and e.column is None and e.text is None
    assert "line" not in str(e) and ".mec" not in str(e)
    return e


def test_a_model_the_compiler_refuses_is_worded_without_a_deck(no_deck_text: None) -> None:
    unused = fourbar()
    unused.point("Z", 0.0, 1.0)
    e = _refused(unused)
    assert str(e) == (
        "the point 'Z' of the mechanism 'fourbar' is used by no element; connect it to an element, or leave it out"
    )
    assert e.name == "Z.x" and e.what == "co-ordinate" and e.kind == "coordinate_unused"

    e = _refused(_coincident(), None)
    assert str(e).startswith(
        "the bar 'crank' (A0, A) cannot be evaluated at the given co-ordinates: its points A0 and A coincide, so the "
        "direction A0->A is undefined"
    )
    assert e.kind == "model" and e.element == 1

    short = fourbar()
    short.set("crank.length", 0.0)
    e = _refused(short)
    assert "'crank.length' prescribes the length of the bar 'crank' (A0, A) as 0, but a length must be" in str(e)
    assert e.name == "crank.length" and e.what == "prescribed"


def test_a_kept_model_given_coincident_points_is_worded_without_a_deck(no_deck_text: None) -> None:
    m = fourbar()
    m.run(MOTION)
    m.set("A", (0.0, 0.0))  # onto A0: the kept model meets it in the core, the model built afresh in its compiler
    e = _refused(m)
    assert str(e).startswith("the bar 'crank' (A0, A) cannot be evaluated at the given co-ordinates: its points A0")


def test_free_motion_of_a_dynamic_model_names_the_input_without_a_deck(no_deck_text: None) -> None:
    from model.test_dynamics_api import pendulum

    e = _refused(pendulum(), Motion.free(10, 0.01))
    assert "free motion (Motion.free, Free) cannot drive the mechanism 'pendulum'" in str(e)
    assert e.name == "theta" and e.what == "motion of input"


def test_a_value_no_deck_can_state_is_named_without_a_deck(no_deck_text: None) -> None:
    with pytest.raises(ValueError, match=r"file name \(Table\.file\) cannot hold blanks or ';': 'a b'"):
        fourbar().run(Motion(2, {None: Table(np.zeros(3), file="a b")}))
    storage = Storage()
    storage.printbuf = [1.5]
    with pytest.raises(ValueError, match=r"Storage.printbuf: 1.5 is not a whole number"):
        fourbar().run(MOTION, storage=storage)
    with pytest.raises(KeyError, match="cranck"):
        fourbar().run(Motion.by(4, {"cranck.angle": 1.0}))
