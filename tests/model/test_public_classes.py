"""``mechfem.X`` is the class a user is handed and passes where an X is asked for: the parts a Mechanism is built
of, and the storage it is run with. What a run echoes of its model has classes of its own (``Echo*``)."""

from __future__ import annotations

import mechfem
from mechfem.model.echo import EchoCoordinate, EchoElement, EchoRow, EchoStorage


def _fourbar() -> tuple[mechfem.Mechanism, list[object]]:
    m = mechfem.Mechanism("fourbar")
    a0, b0 = m.fixed("A0", 0.0, 0.0), m.fixed("B0", 4.0, 0.0)
    a, b = m.point("A", 1.0, 0.0), m.point("B", 3.5, 2.5)
    crank = m.bar("crank", a0, a, length=1.0, angle=mechfem.Driven(start=0.0, name="phi"))
    m.bar("coupler", a, b, length=3.5)
    m.bar("rocker", b0, b, length=3.0, angle=mechfem.Output("psi"))
    phi = m["phi"]
    return m, [crank, phi]


def test_the_parts_a_mechanism_hands_out_are_the_public_classes() -> None:
    m, (crank, phi) = _fourbar()
    assert isinstance(crank, mechfem.Element)
    assert isinstance(phi, mechfem.Row)
    assert isinstance(m.scalar("s", 0.2), mechfem.Coordinate)


def test_the_storage_a_mechanism_runs_with_is_mechfem_storage() -> None:
    m, _ = _fourbar()
    storage = mechfem.Storage().buffer(1, "BUFE0", "psi").picture("psi", ("PLOTFUNC", 1, 1))
    assert isinstance(storage.pictures[0], mechfem.Picture)
    r = m.run(mechfem.Motion.by(3, 0.3), storage)
    assert len(r.storage.buffers) == 1


def test_a_runs_echo_has_classes_of_its_own() -> None:
    r = _fourbar()[0].run(mechfem.Motion.by(3, 0.3))
    assert isinstance(r.model.elements[0], EchoElement) and not isinstance(r.model.elements[0], mechfem.Element)
    assert isinstance(r.model.prescribed[0], EchoRow)
    assert isinstance(r.model.coordinates[0], EchoCoordinate)
    assert isinstance(r.storage, EchoStorage)
