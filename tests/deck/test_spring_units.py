"""A spring and a damper in a model's own units: the supply mechanism's simulation with a torsion spring and a
viscous damper on its output angle, written in mm, degrees and milliseconds (stiffness in N·mm/deg, damping in
N·mm·ms/deg), moves as the SI deck does, and the same model built through Python's typed builder
(``Mechanism.from_deck``) gives the deck reader's results bit for bit."""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
from test_names_units import DEG, EXAMPLES, SUPPLY_NAMES, L, close, converted, run, supply_rules

import mechfem

MS = 1000.0


def _source() -> str:
    text = (EXAMPLES / "supply" / "supply_sim.mec").read_text()
    text = text.replace("TSTEPE 800 2.5E-3", "TSTEPE 100 2E-2")
    # A spring of 5 N m/rad about 1 rad, beside the damper of 0.8 N m s/rad.
    text = re.sub(r"SPRING\s+-1\s+0\s+0\s+0\.8", "SPRING -1 5.0 1.0 0.8", text)
    assert "SPRING -1 5.0 1.0 0.8" in text
    return "".join(s for s in text.splitlines(keepends=True) if not re.match(r"\s*(ANIMATE|BEGINPIC|ENDPIC|PLOT)", s))


def test_a_spring_and_a_damper_in_mm_degrees_and_ms_move_as_in_si(tmp_path: Path) -> None:
    source = _source()
    si = run(tmp_path, "spring_si.mec", source)
    text = converted(source, supply_rules(MS), "UNITS LENGTH mm ANGLE deg MASS kg FORCE N TIME ms", SUPPLY_NAMES)
    assert "SPRING -1 " + repr(5.0 * L / DEG) in text
    mm = run(tmp_path, "spring_mm.mec", text)
    assert mm.positions == si.positions == 101
    factors = {98: MS, 99: DEG, 100: DEG, 101: DEG / MS, 111: L, 112: L, 114: 1.0, 115: 1.0, 116: 1.0}
    for number, factor in factors.items():
        close(mm.buffers[number], si.buffers[number] * factor, rtol=1e-7)
    # The spring changes the motion: without it the output angle ends elsewhere.
    loose = run(tmp_path, "loose_si.mec", source.replace("SPRING -1 5.0 1.0 0.8", "SPRING -1 0 0 0.8"))
    assert abs(loose.buffers[100][-1] - si.buffers[100][-1]) > 1e-3


def test_the_typed_builder_reads_a_spring_in_the_models_units_as_the_deck_reader_does(tmp_path: Path) -> None:
    text = converted(_source(), supply_rules(MS), "UNITS LENGTH mm ANGLE deg MASS kg FORCE N TIME ms", SUPPLY_NAMES)
    path = tmp_path / "spring_mm.mec"
    path.write_text(text)
    deck = mechfem.run_deck(path)
    built = mechfem.Mechanism.from_deck(path).run(order=None)
    assert sorted(built.buffers) == sorted(deck.buffers)
    for number in deck.buffers:
        assert np.array_equal(np.asarray(built.buffers[number]), np.asarray(deck.buffers[number]), equal_nan=True)
