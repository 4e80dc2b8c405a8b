"""One path-synthesis problem for a crank-rocker four-bar, with prescribed timing: plain data and a closed-form
evaluator in NumPy (no mechfem, no pylinkage), shared by ``bench_synthesis.py`` and by whatever optimiser is
compared on it.

The problem is constructed, not taken from the literature. Its targets are the coupler-point positions of a known
four-bar, the one of ``bench_peers.py`` and ``examples/fourbar`` (crank 1, coupler 3, rocker 2.5, frame 3.2 along
x; the coupler point 1.8 from the crank pin A at 0.6 rad from A->B), at ten crank angles 36 degrees apart, so the
known optimum is that four-bar with error 0. (The classic published cases have only best-known errors; they are
stated in examples/synthesis/benchmarks.py and compared in bench_published.py.)

Geometry. Frame pivots A0 = (0, 0) (fixed) and B0 = (x_b0, y_b0); crank A0A of length ``a`` at the prescribed angle
theta from the global x axis, counter-clockwise; coupler AB of length ``b``; rocker B0B of length ``c``; the coupler
point P = A + u e + v n, e the unit vector from A to B, n = e turned by +90 degrees (to the left of A->B). B is the
intersection of the circles (A, b) and (B0, c) on the side of the line A->B0 given by ``branch``: +1 to the left
(counter-clockwise), -1 to the right. The known four-bar, at theta = 0, has A = (1, 0), B = (2.725, 2.4545) above
the frame line, P = (1.0226, 1.8000): branch +1, which is the branch of every design here.

Design variables (7): ``x_b0, y_b0, a, b, c, u, v``. The error of a design is the sum over the ten crank angles of
the squared distance between its coupler point and the target; it is ``inf`` when the crank cannot make a full turn
(the RRR dyad cannot be assembled at some crank angle of the turn: Grashof's condition with the crank able to
rotate, |b - c| <= |d - a| and d + a <= b + c with d = |A0B0|), which includes every prescribed angle, so a finite
error is that of a four-bar that runs through all ten points in one continuous turn on one branch.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

NAMES = ("x_b0", "y_b0", "a", "b", "c", "u", "v")

# The known four-bar (the optimum): bench_peers.py's, with its coupler point (1.8, 0.6 rad) in (u, v).
_P, _ALPHA = 1.8, 0.6
OPTIMUM = np.array([3.2, 0.0, 1.0, 3.0, 2.5, _P * math.cos(_ALPHA), _P * math.sin(_ALPHA)])

# Crank angles: ten positions, every 36 degrees from 0 (one full turn, counter-clockwise).
THETAS = np.deg2rad(np.arange(10) * 36.0)

BRANCH = +1

# The start box (bounds of every variable) and the start design for a local method: a crank-rocker that runs
# through a full turn on branch +1, clearly off the optimum (error 17.59, against 0).
LOWER = np.array([1.0, -2.0, 0.5, 1.5, 1.0, -1.0, -1.0])
UPPER = np.array([5.0, 2.0, 2.0, 5.0, 4.0, 3.0, 3.0])
START = np.array([2.8, 0.4, 1.2, 2.6, 2.8, 1.0, 1.4])


def _split(design: np.ndarray) -> tuple[float, ...]:
    x_b0, y_b0, a, b, c, u, v = (float(x) for x in np.asarray(design, dtype=float))
    return x_b0, y_b0, a, b, c, u, v


def full_turn(design: np.ndarray) -> bool:
    """Whether the crank can make a full turn: the dyad assembles at every crank angle (lengths positive)."""
    x_b0, y_b0, a, b, c, _, _ = _split(design)
    if min(a, b, c) <= 0.0:
        return False
    d = math.hypot(x_b0, y_b0)
    return abs(b - c) <= abs(d - a) and d + a <= b + c


def coupler_points(design: np.ndarray, thetas: np.ndarray = THETAS, branch: int = BRANCH) -> np.ndarray:
    """The coupler point P at each crank angle, shape (len(thetas), 2); rows of NaN where the dyad cannot be
    assembled at that angle. Closed form: B is the intersection of circles (A, b) and (B0, c) on side ``branch``
    of the line A->B0."""
    x_b0, y_b0, a, b, c, u, v = _split(design)
    thetas = np.asarray(thetas, dtype=float)
    ax, ay = a * np.cos(thetas), a * np.sin(thetas)
    dx, dy = x_b0 - ax, y_b0 - ay  # A -> B0
    d2 = dx * dx + dy * dy
    d = np.sqrt(d2)
    with np.errstate(invalid="ignore", divide="ignore"):
        along = (b * b - c * c + d2) / (2.0 * d)  # from A along A->B0 to the chord's foot
        h = np.sqrt(b * b - along * along)  # NaN when the circles do not meet
        ex, ey = dx / d, dy / d
        bx = ax + along * ex - branch * h * ey
        by = ay + along * ey + branch * h * ex
        cx, cy = (bx - ax) / b, (by - ay) / b  # unit vector A -> B
    px = ax + u * cx - v * cy
    py = ay + u * cy + v * cx
    return np.column_stack([px, py])


# The targets: the optimum's coupler points at the prescribed crank angles.
TARGETS = coupler_points(OPTIMUM)


def error(design: np.ndarray) -> float:
    """Sum over the prescribed crank angles of the squared distance to the target; inf if the crank cannot make a
    full turn (so in particular if the linkage cannot be assembled at some prescribed angle)."""
    if not full_turn(design):
        return math.inf
    p = coupler_points(design)
    e = float(np.sum((p - TARGETS) ** 2))
    return e if math.isfinite(e) else math.inf


@dataclass(frozen=True)
class Problem:
    """The problem as one object, for an optimiser: names, box, start, known optimum, crank angles, targets, and
    its error function (``problem.error(design)``)."""

    names: tuple[str, ...]
    lower: np.ndarray
    upper: np.ndarray
    start: np.ndarray
    optimum: np.ndarray
    optimum_error: float
    thetas: np.ndarray
    targets: np.ndarray
    branch: int

    def error(self, design: np.ndarray) -> float:
        return error(design)

    def coupler_points(self, design: np.ndarray) -> np.ndarray:
        return coupler_points(design, self.thetas, self.branch)


PROBLEM = Problem(NAMES, LOWER, UPPER, START, OPTIMUM, 0.0, THETAS, TARGETS, BRANCH)


if __name__ == "__main__":
    np.set_printoptions(precision=6, suppress=True)
    print("variables:", ", ".join(NAMES))
    print("lower:    ", LOWER)
    print("upper:    ", UPPER)
    print("start:    ", START, " error", error(START))
    print("optimum:  ", OPTIMUM, " error", error(OPTIMUM))
    print("crank angles (deg):", np.rad2deg(THETAS))
    print("targets:\n", TARGETS)
