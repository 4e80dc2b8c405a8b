"""The frame length as a quantity a design is bounded in: the distance between two fixed points.

Published path-synthesis problems give a four-bar's frame by its length r1 and angle, and bound r1 (within [0, 60],
say). mechfem places the frame by its pivots A0 and B0, so the length is a function of the design variables alone,
r1 = |B0 - A0|, with no run of the mechanism. ``Bound(FrameLength("A0", "B0"), lo, hi)`` bounds it: an inequality
for SLSQP beside the bounds on buffers, with the exact gradient (the unit vector along the frame, on the pivots'
co-ordinates that are varied). A frame angle (:class:`~mechfem.design.frame_angle.FrameAngle`) turns both pivots
together, so it does not change the length; the variables ``B0.x``, ``B0.y`` (before the turn) give it.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from mechfem.design.engine import DesignBound, FloatArray

if TYPE_CHECKING:
    from mechfem.model.mechanism import Mechanism


@dataclass(frozen=True)
class FrameLength:
    """The distance between the fixed points ``first`` and ``second`` (their names: a four-bar's frame pivots), in
    the model's length unit; for a :class:`~mechfem.design.optimise.Bound`."""

    first: str = "A0"
    second: str = "B0"


def design_bound(mechanism: Mechanism, length: FrameLength, lo: float, hi: float, names: Sequence[str]) -> DesignBound:
    """The bound ``lo <= |second - first| <= hi`` on the design variables ``names`` (in the engine's order: a pivot's
    co-ordinate not among them keeps the mechanism's value)."""
    fixed = {p.name for p in mechanism.points if p.fixed}
    for name in (length.first, length.second):
        if name not in fixed:
            raise ValueError(f"the frame length's end {name!r} is not a fixed point of the mechanism")
    keys = [f"{p}.{k}" for p in (length.first, length.second) for k in "xy"]
    where = [names.index(k) if k in names else None for k in keys]
    if all(k is None for k in where):
        raise ValueError(
            f"the frame length {length.first}-{length.second} does not vary: no co-ordinate of it is varied"
        )
    if not float(lo) <= float(hi):
        raise ValueError(f"the frame length's range ({lo}, {hi}) is empty")
    constant = [float(mechanism[k].value) for k in keys]

    def f(x: FloatArray) -> tuple[float, FloatArray]:
        v = [constant[i] if k is None else float(x[k]) for i, k in enumerate(where)]
        dx, dy = v[2] - v[0], v[3] - v[1]
        d = math.hypot(dx, dy)
        g = np.zeros(len(x))
        if d > 0.0:
            for k, sign in zip(where, (-dx / d, -dy / d, dx / d, dy / d), strict=True):
                if k is not None:
                    g[k] += sign
        return d, g

    return DesignBound(f"frame length {length.first}-{length.second}", f, float(lo), float(hi))


__all__ = ["FrameLength", "design_bound"]
