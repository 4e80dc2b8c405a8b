"""The four-bar a new design starts from: a crank-rocker with a coupler point, its crank turning once in 360 steps.

Grashof's condition holds (shortest + longest = 1 + 4 < 3.5 + 3 = the other two), so the crank, next to the frame,
turns all the way round; the coupler point C sits 1.5 along the coupler A->B and 1.2 to its left. Angles are in
degrees, so that every dimension and chart speaks them.
"""

from __future__ import annotations

from mechfem.model.mechanism import Mechanism
from mechfem.model.motion import Motion
from mechfem.model.parts import Driven, Output
from mechfem.model.storage import Storage

#: Positions per turn of the template's crank, plus the first one again.
STEPS = 360


def four_bar(steps: int = STEPS) -> Mechanism:
    """A crank-rocker four-bar: fixed pivots A0 (0, 0) and B0 (4, 0); crank A0-A 1, coupler A-B 3.5 carrying C at
    (u, v) = (1.5, 1.2), rocker B0-B 3 whose angle is the output ``psi``; the crank angle ``phi`` turns from 0
    through 360 deg in ``steps`` steps."""
    m = Mechanism("fourbar", angle="deg")
    a0, b0 = m.fixed("A0", 0.0, 0.0), m.fixed("B0", 4.0, 0.0)
    # Start estimates of the moving points: B above the frame line chooses that assembly branch.
    a = m.point("A", 1.0, 0.0)
    b = m.point("B", 3.2, 2.8)
    c = m.point("C", 1.9, 1.5)
    m.bar("crank", a0, a, length=1.0, angle=Driven(0.0, name="phi"))
    m.ternary2("coupler", a, b, c, length=3.5, u=1.5, v=1.2)
    m.bar("rocker", b0, b, length=3.0, angle=Output("psi"))
    m.motion = Motion.by(steps, 360.0, unit="deg")
    # What a saved design's data set and report hold: the crank and rocker angles, the rocker's transfer
    # functions, the coupler point's path, det(D^c) and the transmission angle between coupler and rocker.
    m.storage = (
        Storage(printbuf=[1, 2, 5, 6], savedata=[1, 2, 3, 4, 5, 6, 7, 8])
        .buffer(1, "BUFINP", "phi")
        .buffer(2, "BUFE0", "psi")
        .buffer(3, "BUFKE1", "psi", "phi")
        .buffer(4, "BUFKE2", "psi", "phi")
        .buffer(5, "BUFX0", "C.x")
        .buffer(6, "BUFX0", "C.y")
        .buffer(7, "BUFDET")
        .buffer(8, "BUFTRA", "coupler", "rocker")
        .picture("coupler curve", ("PLOTHODO", "C"))
        .picture("rocker angle and its transfer functions", ("PLOTFUNC", 1, 2), ("PLOTFUNC", 1, 3), ("PLOTFUNC", 1, 4))
        .picture("transmission angle", ("PLOTFUNC", 1, 8))
    )
    return m


__all__ = ["STEPS", "four_bar"]
