"""A stiff mechanism for the simulation benchmarks: a four-bar whose rocker is held by a spring and a strong viscous
damper (a viscous coupling), its crank turned by a constant torque from rest, simulated for 5 s. The deck is
``benches/decks/stiff_fourbar.mec`` (``python benches/stiff_fourbar.py`` writes it again); this module also holds
the mechanism's equation of motion in its crank angle, derived by hand, for the peers (vectorised NumPy).

The mechanism (SI units): crank O->A of 0.1 m about O = (0, 0), coupler A->B of 0.35 m, rocker Q->B of 0.25 m about
Q = (0.3, 0); uniform bars of 30, 60 and 45 g (centres half-way, J = m l^2 / 12). A torque of 400 N m on the
crank; on the rocker's angle psi a spring of 2000 N m/rad (relaxed at the start) and a damper of 4000 N m s.
Started at rest at a crank angle of 1 rad, the crank creeps forward until the spring balances the torque (it turns
by 1.1 rad in the 5 s): the slow eigenvalue of the linearised equation is 0.4 to 4.2 /s (about k / c = 0.5 /s
once moving), the fast one 5e5 to 8e5 /s (the crank's speed relaxes within some 2e-6 s). Their ratio, the
stiffness ratio, is 1.2e5 to 2e6 along the motion; the benchmark prints it.

The equation, with q the crank angle, phi the coupler's and psi the rocker's angle, ' = d/dq:

    loop  a e^(iq) + b e^(i phi) - c e^(i psi) = x_Q
    d/dq: b phi' e^(i phi) - c psi' e^(i psi) = -a e^(iq)                     (times i, dropped)
    d2:   b phi'' e^(i phi) - c psi'' e^(i psi) = -i (a e^(iq) + b phi'^2 e^(i phi) - c psi'^2 e^(i psi))
    T  = M(q) q_dot^2 / 2,  M = J_O + m2 |G'|^2 + J2 phi'^2 + J_Q psi'^2,  G = A + (b/2) e^(i phi)
    M q'' + (m2 G'.G'' + J2 phi' phi'' + J_Q psi' psi'') q'^2 = torque - (k (psi - psi0) + c psi' q') psi'

with J_O = m1 a^2 / 3 and J_Q = m3 c^2 / 3 about the pivots.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import numpy as np

DECK = Path(__file__).resolve().parent / "decks" / "stiff_fourbar.mec"

A, B, C, XQ = 0.1, 0.35, 0.25, 0.3
M1, M2, M3 = 0.03, 0.06, 0.045
J2 = M2 * B * B / 12.0
J_O, J_Q = M1 * A * A / 3.0, M3 * C * C / 3.0
TORQUE, K, DAMPING = 400.0, 2000.0, 4000.0
Q0 = 1.0
T_END, OUTPUTS = 5.0, 500


class _Scalar:
    """NumPy's names for the functions of ``math``: one state is computed in floats, far faster than in arrays."""

    cos, sin, hypot, arccos, arctan2 = math.cos, math.sin, math.hypot, math.acos, math.atan2


def _xp(q: Any) -> Any:
    return np if isinstance(q, np.ndarray) and q.ndim > 0 else _Scalar


def angles(q: Any) -> tuple[Any, Any]:
    """The coupler's and the rocker's angle at crank angles ``q`` (the assembly with B above the line A->Q)."""
    xp = _xp(q)
    ax, ay = A * xp.cos(q), A * xp.sin(q)
    dx, dy = XQ - ax, -ay
    dist = xp.hypot(dx, dy)
    alpha = xp.arccos((B * B + dist * dist - C * C) / (2.0 * B * dist))
    phi = xp.arctan2(dy, dx) + alpha
    bx, by = ax + B * xp.cos(phi), ay + B * xp.sin(phi)
    psi = xp.arctan2(by, bx - XQ)
    return phi, psi


PSI0 = float(angles(Q0)[1])


def transfer(q: Any) -> tuple[Any, ...]:
    """phi, psi and their first and second derivatives with respect to q, at crank angles ``q``."""
    xp = _xp(q)
    phi, psi = angles(q)
    cq, sq, cf, sf, cp, sp = xp.cos(q), xp.sin(q), xp.cos(phi), xp.sin(phi), xp.cos(psi), xp.sin(psi)
    # [b cf, -c cp; b sf, -c sp] [x; y] = [r1; r2], by Cramer's rule.
    det = -B * cf * C * sp + C * cp * B * sf

    def solve(r1: Any, r2: Any) -> tuple[Any, Any]:
        return (-r1 * C * sp + C * cp * r2) / det, (B * cf * r2 - B * sf * r1) / det

    phi1, psi1 = solve(-A * cq, -A * sq)
    # -i (a e^(iq) + b phi'^2 e^(i phi) - c psi'^2 e^(i psi)): -i (x + i y) = y - i x.
    ex = A * cq + B * phi1**2 * cf - C * psi1**2 * cp
    ey = A * sq + B * phi1**2 * sf - C * psi1**2 * sp
    phi2, psi2 = solve(ey, -ex)
    return phi, psi, phi1, psi1, phi2, psi2


def terms(q: Any) -> tuple[Any, Any, Any, Any]:
    """M(q), the velocity term's factor h(q) (M q'' + h q'^2 = ...), psi - psi0 and psi' at crank angles ``q``."""
    xp = _xp(q)
    phi, psi, phi1, psi1, phi2, psi2 = transfer(q)
    cq, sq, cf, sf = xp.cos(q), xp.sin(q), xp.cos(phi), xp.sin(phi)
    gx1, gy1 = -A * sq - 0.5 * B * phi1 * sf, A * cq + 0.5 * B * phi1 * cf
    gx2 = -A * cq - 0.5 * B * (phi2 * sf + phi1**2 * cf)
    gy2 = -A * sq + 0.5 * B * (phi2 * cf - phi1**2 * sf)
    mass = J_O + M2 * (gx1 * gx1 + gy1 * gy1) + J2 * phi1 * phi1 + J_Q * psi1 * psi1
    h = M2 * (gx1 * gx2 + gy1 * gy2) + J2 * phi1 * phi2 + J_Q * psi1 * psi2
    return mass, h, psi - PSI0, psi1


def ode_rhs(t: float, y: Any) -> Any:
    """(q, q') -> (q', q''); ``y`` is 2 values or 2 x k (SciPy's ``vectorized``)."""
    # One state (SciPy's vectorised solvers pass it as a column too) in floats, several as arrays.
    one = y.ndim == 1 or y.shape[1] == 1
    q, w = y.ravel().tolist() if one else (y[0], y[1])
    mass, h, stretch, psi1 = terms(q)
    acc = (TORQUE - (K * stretch + DAMPING * psi1 * w) * psi1 - h * w * w) / mass
    return np.array([w, acc]).reshape(y.shape) if one else np.array([w, acc])


def residual(t: float, y: Any, yp: Any, res: Any) -> None:
    """The equation as an implicit ODE for IDA: q' - w = 0, M w' + h w^2 - Q = 0."""
    q, w = y.tolist()
    mass, h, stretch, psi1 = terms(q)
    res[0] = yp[0] - w
    res[1] = mass * yp[1] + h * w * w - TORQUE + (K * stretch + DAMPING * psi1 * w) * psi1


def jacobian(t: float, y: Any, yp: Any, res: Any, cj: float, jj: Any) -> None:
    """The residual's Jacobian ``dres/dy + cj dres/dyp`` for IDA: by hand, but for dh/dq (a central difference)."""
    q, w, wp = float(y[0]), float(y[1]), float(yp[1])
    mass, h, stretch, psi1 = terms(q)
    _, _, _, _, _, psi2 = transfer(q)
    dq = 1e-6
    h_q = (terms(q + dq)[1] - terms(q - dq)[1]) / (2 * dq)
    jj[0, 0], jj[0, 1] = cj, -1.0
    jj[1, 0] = 2 * h * wp + h_q * w * w + K * psi1 * psi1 + K * stretch * psi2 + 2 * DAMPING * psi1 * psi2 * w
    jj[1, 1] = cj * mass + 2 * h * w + DAMPING * psi1 * psi1


def reference_states() -> tuple[Any, Any]:
    """The crank angle and speed at every output, by Radau at 1e-10 (for the stiffness ratio along the motion)."""
    from scipy.integrate import solve_ivp

    times = np.linspace(0.0, T_END, OUTPUTS + 1)
    sol = solve_ivp(ode_rhs, (0.0, T_END), [Q0, 0.0], method="Radau", t_eval=times, rtol=1e-10, atol=1e-10,
                    vectorized=True)  # fmt: skip
    return sol.y[0], sol.y[1]


def eigenvalues(q: Any, w: Any, dq: float = 1e-6) -> Any:
    """The eigenvalues (k x 2, complex) of the linearised equation at states (q, w), the Jacobian by central
    differences."""
    y = np.array([q, w], dtype=float)
    jac = np.empty((y.shape[1], 2, 2))
    for j, step in enumerate((dq, dq * max(1.0, float(np.abs(w).max())))):
        e = np.zeros((2, 1))
        e[j] = step
        jac[:, :, j] = ((ode_rhs(0.0, y + e) - ode_rhs(0.0, y - e)) / (2 * step)).T
    return np.linalg.eigvals(jac)


def stiffness_ratio(q: Any, w: Any) -> Any:
    """|lambda_max| / |lambda_min| of the linearised equation at states (q, w)."""
    lam = np.abs(eigenvalues(q, w))
    return lam.max(axis=1) / lam.min(axis=1)


def deck_text() -> str:
    phi, psi = angles(Q0)
    ax, ay = A * math.cos(Q0), A * math.sin(Q0)
    bx, by = ax + B * math.cos(phi), ay + B * math.sin(phi)
    return "\n".join(
        [
            "; A stiff mechanism: a four-bar whose rocker is held by a spring (2000 N m/rad) and a strong viscous",
            "; damper (4000 N m s), its crank turned from rest by a constant torque of 400 N m, for 5 s. The crank's",
            "; speed relaxes within some 2e-6 s, the motion creeps on over seconds: a stiffness ratio above 1e5.",
            "; The benchmark of benches/bench_work_precision.py, written by benches/stiff_fourbar.py; SI units.",
            "; Points: O 1 2, Q 3 4 (fixed); A 5 6, B 7 8.",
            "DYN SIM",
            "TOPOLOGY",
            "ELEM\t1\tBIN\t1 2 5 6 ; crank O->A",
            "\t2\tBIN\t5 6 7 8 ; coupler A->B",
            "\t3\tBIN\t3 4 7 8 ; rocker Q->B",
            "FORM",
            "\t1\tLENL\t1 1",
            "\t2\tLENL\t2 2",
            "\t3\tLENL\t3 3",
            "\t4\tANGB\t1 4 ; the crank angle, the input",
            "\t5\tANGB\t3 -1 ; the rocker angle psi",
            "NRDOF\t1",
            "",
            "GEOMETRY",
            "XFIX\t1\t0.0",
            "XFIX\t2\t0.0",
            f"XFIX\t3\t{XQ!r}",
            "XFIX\t4\t0.0",
            f"XMOV\t5\t{ax!r}",
            f"XMOV\t6\t{ay!r}",
            f"XMOV\t7\t{bx!r}",
            f"XMOV\t8\t{by!r}",
            f"PARA\t1\t{A!r}",
            f"PARA\t2\t{B!r}",
            f"PARA\t3\t{C!r}",
            f"PARA\t4\t{Q0!r}",
            "",
            "DYNAMICS",
            "; element, mass (kg), centre (u, v) in the element's frame (m), J about the centre (kg m^2)",
            f"MASS\t1\t{M1}\t{A / 2!r}\t0\t{M1 * A * A / 12.0!r}",
            f"\t2\t{M2}\t{B / 2!r}\t0\t{J2!r}",
            f"\t3\t{M3}\t{C / 2!r}\t0\t{M3 * C * C / 12.0!r}",
            f"LOAD\t4\t{TORQUE} ; the torque on the crank (N m)",
            f"SPRING\t-1\t{K}\t{PSI0!r}\t{DAMPING} ; the viscous coupling on the rocker",
            "",
            "MOVEMENT",
            f"TSTEPE\t{OUTPUTS}\t{T_END / OUTPUTS!r}",
            "MOV_DYN\t1\t0.0",
            "INTTOL\t1E-8\t1E-8",
            "",
            "STORAGE",
            "  BUFTIME\t1",
            "  BUFINP\t1\t2 ; the crank angle",
            "  BUFVE\t4\t3 ; the crank's speed",
            "  BUFE0\t-1\t4 ; the rocker angle",
            "  SAVEDATA 1 2 3 4",
            "",
        ]
    )


if __name__ == "__main__":
    DECK.parent.mkdir(exist_ok=True)
    DECK.write_text(deck_text())
    print(f"wrote {DECK}")
    print(f"stiffness ratio at the start: {stiffness_ratio(np.array([Q0]), np.array([0.0]))[0]:.3g}")
