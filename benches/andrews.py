"""Andrews' squeezing mechanism for the simulation benchmarks: its data, the mechfem deck, and the benchmark's own
equations of motion in its seven angles for the peers (vectorised NumPy).

The data are those of ``crates/mechfem-core/tests/andrews.rs`` (E. Hairer and G. Wanner, *Solving Ordinary
Differential Equations II*, section VII.7; the Test Set for IVP Solvers of the University of Bari, problem
``andrews``), which says where they come from and how the mechanism is modelled with BIN and TR2 elements. The deck
``benches/decks/andrews.mec`` is written by :func:`deck_text` (``python benches/andrews.py`` writes it again).

The peers integrate the benchmark's equations, ``M(q) q'' = f(q, q') - G(q)^T lam`` with the three loop closures
``g(q) = 0`` through the point E, in one of two forms:

* the index-1 ODE form (14 states), ``[M G^T; G 0] [q''; lam] = [f; -G' q']`` solved at every evaluation, for the
  ODE solvers (SciPy); the constraints are then only kept by the integration's accuracy (they drift);
* the stabilised index-2 form of Gear, Gupta and Leimkuhler (GGL, 26 unknowns), for a DAE solver (IDA):
  ``q' = v - G^T mu``, ``M v' = f - G^T lam``, ``g(q) = 0``, ``G v = 0``, with lam and mu algebraic.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import numpy as np

DECK = Path(__file__).resolve().parent / "decks" / "andrews.mec"

# Masses (kg), moments of inertia about the centres (kg m^2), in the benchmark's numbering of bodies 1..7.
M = [0.04325, 0.00365, 0.02373, 0.00706, 0.07050, 0.00706, 0.05498]
I = [2.194e-6, 4.410e-7, 5.255e-6, 5.667e-7, 1.169e-5, 5.667e-7, 1.912e-5]  # noqa: E741
XA, YA, XB, YB, XC, YC = -0.06934, -0.00227, -0.03635, 0.03273, 0.014, 0.072
D, DA, E, EA, RR, RA = 28e-3, 115e-4, 2e-2, 1421e-5, 7e-3, 92e-5
SS, SA, SB, SC, SD = 35e-3, 1874e-5, 1043e-5, 18e-3, 2e-2
TA, TB, U, UA, UB, ZF, ZT, FA = 2308e-5, 916e-5, 4e-2, 1228e-5, 449e-5, 2e-2, 4e-2, 1421e-5
MOM, C0, L0 = 0.033, 4530.0, 0.07785

# The published consistent initial angles beta, Theta, gamma, Phi, delta, Omega, epsilon (at rest) and the
# published reference at t = 0.03 (PSIDE at 1e-14; it carries about 2.7e-10 of error itself).
Q0 = np.array(
    [
        -0.06171389001427645,
        0.0,
        0.45527981916307037,
        0.22266839016588588,
        0.48736497954384256,
        -0.22266839016588588,
        1.2305474445498212,
    ]
)
Q_PUBLISHED = np.array(
    [
        15.81077119629904,
        -15.75637105984298,
        0.04082224013073101,
        -0.5347301163226948,
        0.5244099658805304,
        0.5347301163226948,
        1.048080741042263,
    ]
)
NAMES = ["beta", "Theta", "gamma", "Phi", "delta", "Omega", "epsilon"]
T_END, OUTPUTS = 0.03, 30

# The deck's buffers of the seven angles: beta is the input, the others dependent form parameters read with an
# offset (deck_text says which).
BUFFERS = [1, 2, 3, 4, 5, 6, 7]
OFFSETS = np.array([0.0, -math.pi, math.pi / 2, math.pi / 2, 0.0, -math.pi / 2, math.pi / 2])


def rot(angle: float, u: float, v: float) -> tuple[float, float]:
    s, c = math.sin(angle), math.cos(angle)
    return u * c - v * s, u * s + v * c


def deck_text() -> str:
    """The mechfem deck of the squeezer (numbering and offsets as in ``crates/mechfem-core/tests/andrews.rs``)."""
    beta, theta, gamma, _, delta, _, epsilon = Q0
    p = rot(beta, RR, 0.0)
    e = tuple(a + b for a, b in zip(p, rot(beta + theta, -D, 0.0), strict=True))
    d = tuple(a + b for a, b in zip((XB, YB), rot(gamma, SD, -SC), strict=True))
    g = tuple(a + b for a, b in zip((XA, YA), rot(delta, ZT, 0.0), strict=True))
    h = tuple(a + b for a, b in zip((XA, YA), rot(epsilon, 0.0, -U), strict=True))
    fixed = [0.0, 0.0, XA, YA, XB, YB, XC, YC]
    moving = [*p, *e, *d, *g, *h]
    lines = [
        "; Andrews' squeezing mechanism (Hairer and Wanner, Solving ODEs II, VII.7; the Bari IVP test set), from",
        "; rest under its drive torque, 0.03 s: the benchmark of benches/bench_work_precision.py. Written by",
        "; benches/andrews.py from the data of crates/mechfem-core/tests/andrews.rs; SI units.",
        "; Points: O 1 2, A 3 4, B 5 6, C 7 8 (fixed); P 9 10, E 11 12, D 13 14, G 15 16, H 17 18.",
        "DYN SIM",
        "TOPOLOGY",
        "ELEM\t1\tBIN\t1 2 9 10 ; body 1, the crank O->P",
        "\t2\tBIN\t9 10 11 12 ; body 2, P->E",
        "\t3\tTR2\t5 6 11 12 13 14 ; body 3, B->E, carrying D",
        "\t4\tBIN\t3 4 15 16 ; body 5, A->G",
        "\t5\tBIN\t15 16 11 12 ; body 4, G->E",
        "\t6\tBIN\t3 4 17 18 ; body 7, A->H",
        "\t7\tBIN\t17 18 11 12 ; body 6, H->E",
        "\t8\tBIN\t7 8 13 14 ; the spring C->D",
        "FORM",
        "\t1\tLENL\t1 1",
        "\t2\tLENL\t2 2",
        "\t3\tLENL\t3 3",
        "\t4\tLENU\t3 4",
        "\t5\tLENV\t3 5",
        "\t6\tLENL\t4 6",
        "\t7\tLENL\t5 7",
        "\t8\tLENL\t6 8",
        "\t9\tLENL\t7 9",
        "\t10\tANGB\t1 10 ; beta, the input",
        "\t11\tLENL\t8 -1 ; the spring's length",
        "\t12\tANGB\t2 -2 1.0 ; Theta + pi",
        "\t13\tANGB\t1 -2 -1.0",
        "\t14\tANGB\t3 -3 ; gamma - pi/2",
        "\t15\tANGB\t5 -4 1.0 ; Phi - pi/2",
        "\t16\tANGB\t4 -4 -1.0",
        "\t17\tANGB\t4 -5 ; delta",
        "\t18\tANGB\t7 -6 1.0 ; Omega + pi/2",
        "\t19\tANGB\t6 -6 -1.0",
        "\t20\tANGB\t6 -7 ; epsilon - pi/2",
        "NRDOF\t1",
        "",
        "GEOMETRY",
    ]
    lines += [f"XFIX\t{i + 1}\t{v!r}" for i, v in enumerate(fixed)]
    lines += [f"XMOV\t{i + 9}\t{v!r}" for i, v in enumerate(moving)]
    lines += [f"PARA\t{r}\t{v!r}" for r, v in enumerate([RR, D, SS, SC, SD, ZT, E, U, ZF, float(beta)], 1)]
    lines += [
        "",
        "DYNAMICS",
        "; element, mass (kg), centre (u, v) in the element's frame (m), J about the centre (kg m^2)",
        f"MASS\t1\t{M[0]}\t{RA}\t0\t{I[0]}",
        f"\t2\t{M[1]}\t{DA}\t0\t{I[1]}",
        f"\t3\t{M[2]}\t{SA}\t{SB}\t{I[2]}",
        f"\t4\t{M[4]}\t{TA}\t{TB}\t{I[4]}",
        f"\t5\t{M[3]}\t{E - EA!r}\t0\t{I[3]}",
        f"\t6\t{M[6]}\t{UA}\t{UB}\t{I[6]}",
        f"\t7\t{M[5]}\t{ZF - FA!r}\t0\t{I[5]}",
        f"LOAD\t10\t{MOM} ; the drive torque",
        f"SPRING\t-1\t{C0}\t{L0} ; the spring C->D",
        "",
        "MOVEMENT",
        f"TSTEPE\t{OUTPUTS}\t{T_END / OUTPUTS!r}",
        "MOV_DYN\t1\t0.0",
        "INTTOL\t1E-10\t1E-10",
        "ACCURACY\t1E-10",
        "",
        "STORAGE",
        "  BUFINP\t1\t1 ; beta",
        *(f"  BUFE0\t-{k}\t{k} ; {NAMES[k - 1]} {-OFFSETS[k - 1]:+.6f}" for k in range(2, 8)),
        "  BUFTIME\t8",
        "  SAVEDATA 8 1 2 3 4 5 6 7",
        "",
    ]
    return "\n".join(lines)


def angles(buffers: dict[int, Any]) -> Any:
    """The seven benchmark angles at every output (outputs x 7) from a run of the deck."""
    return np.stack([np.asarray(buffers[b]) for b in BUFFERS], axis=1) + OFFSETS


# --- the benchmark's equations --------------------------------------------------------------------------------------
#
# The loops through E: the crank side (O -> P -> E) minus each of the other three sides (B -> E; A -> G -> E;
# A -> H -> E). An arm of length r at angle c . q + offset; ARM_W[k, a] is the arm's sign (+ crank side, - other)
# times r in loop k.
_ARMS = [  # (loop or None for the crank side, r, angles summed, offset)
    (None, RR, [1, 0, 0, 0, 0, 0, 0], 0.0),
    (None, D, [1, 1, 0, 0, 0, 0, 0], math.pi),
    (0, SS, [0, 0, 1, 0, 0, 0, 0], -math.pi / 2),
    (1, ZT, [0, 0, 0, 0, 1, 0, 0], 0.0),
    (1, E, [0, 0, 0, 1, 1, 0, 0], -math.pi / 2),
    (2, U, [0, 0, 0, 0, 0, 0, 1], -math.pi / 2),
    (2, ZF, [0, 0, 0, 0, 0, 1, 1], 0.0),
]
# Where each loop's other side starts: B, A, A (the crank side starts at O, the origin).
LOOP_START = np.array([[XB, YB], [XA, YA], [XA, YA]])
ARM_C = np.array([a[2] for a in _ARMS], dtype=float)
ARM_O = np.array([a[3] for a in _ARMS])
ARM_W = np.array([[a[1] if a[0] is None else (-a[1] if a[0] == k else 0.0) for a in _ARMS] for k in range(3)])


def _mass_constant() -> Any:
    e_ea, zf_fa = E - EA, ZF - FA
    m = np.zeros((7, 7))
    m[0, 0] = M[0] * RA * RA + M[1] * (RR * RR + DA * DA) + I[0] + I[1]
    m[0, 1] = m[1, 0] = M[1] * DA * DA + I[1]
    m[1, 1] = M[1] * DA * DA + I[1]
    m[2, 2] = M[2] * (SA * SA + SB * SB) + I[2]
    m[3, 3] = M[3] * e_ea * e_ea + I[3]
    m[3, 4] = m[4, 3] = M[3] * e_ea * e_ea + I[3]
    m[4, 4] = M[3] * (ZT * ZT + e_ea * e_ea) + M[4] * (TA * TA + TB * TB) + I[3] + I[4]
    m[5, 5] = M[5] * zf_fa * zf_fa + I[5]
    m[5, 6] = m[6, 5] = M[5] * zf_fa * zf_fa + I[5]
    m[6, 6] = M[5] * (zf_fa * zf_fa + U * U) + M[6] * (UA * UA + UB * UB) + I[5] + I[6]
    return m


def mass_and_force(q: Any, v: Any) -> tuple[Any, Any]:
    """M(q) (k x 7 x 7) and f(q, v) (k x 7) for k states given as columns (7 x k)."""
    k = q.shape[1]
    theta, gamma, phi, omega = q[1], q[2], q[3], q[5]
    beta_d, theta_d, phi_d, delta_d, omega_d, eps_d = v[0], v[1], v[3], v[4], v[5], v[6]
    e_ea, zf_fa = E - EA, ZF - FA
    ct, sp, so = np.cos(theta), np.sin(phi), np.sin(omega)
    m = np.zeros((k, 7, 7))
    m[:, 0, 0] = M[0] * RA * RA + M[1] * (RR * RR - 2.0 * DA * RR * ct + DA * DA) + I[0] + I[1]
    m[:, 0, 1] = m[:, 1, 0] = M[1] * (DA * DA - DA * RR * ct) + I[1]
    m[:, 1, 1] = M[1] * DA * DA + I[1]
    m[:, 2, 2] = M[2] * (SA * SA + SB * SB) + I[2]
    m[:, 3, 3] = M[3] * e_ea * e_ea + I[3]
    m[:, 3, 4] = m[:, 4, 3] = M[3] * (e_ea * e_ea + ZT * e_ea * sp) + I[3]
    m[:, 4, 4] = M[3] * (ZT * ZT + 2.0 * ZT * e_ea * sp + e_ea * e_ea) + M[4] * (TA * TA + TB * TB) + I[3] + I[4]
    m[:, 5, 5] = M[5] * zf_fa * zf_fa + I[5]
    m[:, 5, 6] = m[:, 6, 5] = M[5] * (zf_fa * zf_fa - U * zf_fa * so) + I[5]
    m[:, 6, 6] = M[5] * (zf_fa * zf_fa - 2.0 * U * zf_fa * so + U * U) + M[6] * (UA * UA + UB * UB) + I[5] + I[6]
    # The spring C->D on gamma: D = B + (SD, -SC) turned by gamma.
    sg, cg = np.sin(gamma), np.cos(gamma)
    dpx, dpy = SD * cg + SC * sg, SD * sg - SC * cg
    dx, dy = XB + dpx - XC, YB + dpy - YC
    length = np.hypot(dx, dy)
    pull = -C0 * (length - L0) / length
    st, cp, co = np.sin(theta), np.cos(phi), np.cos(omega)
    f = np.empty((k, 7))
    f[:, 0] = MOM - M[1] * DA * RR * theta_d * (theta_d + 2.0 * beta_d) * st
    f[:, 1] = M[1] * DA * RR * beta_d * beta_d * st
    f[:, 2] = pull * (dx * -dpy + dy * dpx)
    f[:, 3] = M[3] * ZT * e_ea * delta_d * delta_d * cp
    f[:, 4] = -M[3] * ZT * e_ea * phi_d * (phi_d + 2.0 * delta_d) * cp
    f[:, 5] = -M[5] * U * zf_fa * eps_d * eps_d * co
    f[:, 6] = M[5] * U * zf_fa * omega_d * (omega_d + 2.0 * eps_d) * co
    return m, f


def constraints(q: Any) -> tuple[Any, Any, Any, Any]:
    """For k states (7 x k): g(q) (k x 6), G(q) (k x 6 x 7), and the arms' sines and cosines (arms x k)."""
    a = ARM_C @ q + ARM_O[:, None]
    s, c = np.sin(a), np.cos(a)
    k = q.shape[1]
    g = np.empty((k, 6))
    g[:, 0::2] = (ARM_W @ c).T - LOOP_START[:, 0]
    g[:, 1::2] = (ARM_W @ s).T - LOOP_START[:, 1]
    jac = np.empty((k, 6, 7))
    jac[:, 0::2, :] = np.einsum("la,ak,aj->klj", ARM_W, -s, ARM_C)
    jac[:, 1::2, :] = np.einsum("la,ak,aj->klj", ARM_W, c, ARM_C)
    return g, jac, s, c


def _one(q: list[float], v: list[float]) -> tuple[Any, list[float]]:
    """M(q) and f(q, v) at one state, in scalar arithmetic (a NumPy call per entry costs more than the entry)."""
    theta, gamma, phi, omega = q[1], q[2], q[3], q[5]
    beta_d, theta_d, _, phi_d, delta_d, omega_d, eps_d = v
    e_ea, zf_fa = E - EA, ZF - FA
    ct, st = math.cos(theta), math.sin(theta)
    sp, cp = math.sin(phi), math.cos(phi)
    so, co = math.sin(omega), math.cos(omega)
    m = _M_CONST.copy()
    m[0, 0] += -2.0 * M[1] * DA * RR * ct
    m[0, 1] = m[1, 0] = m[0, 1] - M[1] * DA * RR * ct
    m[3, 4] = m[4, 3] = m[3, 4] + M[3] * ZT * e_ea * sp
    m[4, 4] += 2.0 * M[3] * ZT * e_ea * sp
    m[5, 6] = m[6, 5] = m[5, 6] - M[5] * U * zf_fa * so
    m[6, 6] -= 2.0 * M[5] * U * zf_fa * so
    sg, cg = math.sin(gamma), math.cos(gamma)
    dpx, dpy = SD * cg + SC * sg, SD * sg - SC * cg
    dx, dy = XB + dpx - XC, YB + dpy - YC
    length = math.hypot(dx, dy)
    pull = -C0 * (length - L0) / length
    f = [
        MOM - M[1] * DA * RR * theta_d * (theta_d + 2.0 * beta_d) * st,
        M[1] * DA * RR * beta_d * beta_d * st,
        pull * (dx * -dpy + dy * dpx),
        M[3] * ZT * e_ea * delta_d * delta_d * cp,
        -M[3] * ZT * e_ea * phi_d * (phi_d + 2.0 * delta_d) * cp,
        -M[5] * U * zf_fa * eps_d * eps_d * co,
        M[5] * U * zf_fa * omega_d * (omega_d + 2.0 * eps_d) * co,
    ]
    return m, f


def ode_rhs(t: float, y: Any) -> Any:
    """The index-1 ODE form: (q, q') -> (q', q''); ``y`` is 14 values or 14 x k (SciPy's ``vectorized``)."""
    if y.ndim == 1 or y.shape[1] == 1:
        # One state: SciPy's vectorised solvers pass it as a column too.
        q, v = y[:7].ravel(), y[7:].ravel()
        m, f = _one(q.tolist(), v.tolist())
        a = ARM_C @ q + ARM_O
        s, c = np.sin(a), np.cos(a)
        rate2 = (ARM_C @ v) ** 2
        lhs = np.zeros((13, 13))
        lhs[:7, :7] = m
        lhs[7::2, :7] = (ARM_W * -s) @ ARM_C
        lhs[8::2, :7] = (ARM_W * c) @ ARM_C
        lhs[:7, 7:] = lhs[7:, :7].T
        b = np.empty(13)
        b[:7] = f
        b[7::2] = ARM_W @ (c * rate2)
        b[8::2] = ARM_W @ (s * rate2)
        return np.concatenate([v, np.linalg.solve(lhs, b)[:7]]).reshape(y.shape)
    q, v = y[:7], y[7:]
    m, f = mass_and_force(q, v)
    _, jac, s, c = constraints(q)
    rate2 = (ARM_C @ v) ** 2
    k = y.shape[1]
    lhs = np.zeros((k, 13, 13))
    lhs[:, :7, :7] = m
    lhs[:, 7:, :7] = jac
    lhs[:, :7, 7:] = jac.transpose(0, 2, 1)
    b = np.empty((k, 13))
    b[:, :7] = f
    b[:, 7::2] = (ARM_W @ (c * rate2)).T
    b[:, 8::2] = (ARM_W @ (s * rate2)).T
    acc = np.linalg.solve(lhs, b[..., None])[:, :7, 0].T
    return np.concatenate([v, acc])


_M_CONST = _mass_constant()


def consistent_start() -> tuple[Any, Any]:
    """The GGL state at t = 0 (q0, v = 0, lam from the consistent accelerations, mu = 0) and its derivative."""
    y = np.concatenate([Q0, np.zeros(7)])
    q, v = Q0[:, None], np.zeros((7, 1))
    m, f = mass_and_force(q, v)
    _, jac, _, _ = constraints(q)
    a = np.zeros((13, 13))
    a[:7, :7], a[7:, :7], a[:7, 7:] = m[0], jac[0], jac[0].T
    b = np.concatenate([f[0], np.zeros(6)])
    sol = np.linalg.solve(a, b)
    y_ggl = np.concatenate([y, sol[7:], np.zeros(6)])
    yp_ggl = np.concatenate([np.zeros(7), sol[:7], np.zeros(12)])
    return y_ggl, yp_ggl


def ggl_residual(t: float, y: Any, yp: Any, res: Any) -> None:
    """The GGL form's residual (26 values) into ``res``."""
    q, v = y[:7], y[7:14]
    m, f = _one(q.tolist(), v.tolist())
    a = ARM_C @ q + ARM_O
    s, c = np.sin(a), np.cos(a)
    jac = np.empty((6, 7))
    jac[0::2] = (ARM_W * -s) @ ARM_C
    jac[1::2] = (ARM_W * c) @ ARM_C
    res[:7] = yp[:7] - v + y[20:26] @ jac
    res[7:14] = m @ yp[7:14] - f + y[14:20] @ jac
    res[14:20:2] = ARM_W @ c - LOOP_START[:, 0]
    res[15:20:2] = ARM_W @ s - LOOP_START[:, 1]
    res[20:26] = jac @ v


def ggl_jacobian(t: float, y: Any, yp: Any, res: Any, cj: float, jj: Any) -> None:
    """The GGL residual's Jacobian ``dres/dy + cj dres/dyp`` (26 x 26) into ``jj``, derived by hand (checked
    against central differences by ``tests/docs/test_bench_simulation.py``)."""
    q, v, vp, lam, mu = y[:7], y[7:14], yp[7:14], y[14:20], y[20:26]
    m, _ = _one(q.tolist(), v.tolist())
    a = ARM_C @ q + ARM_O
    s, c = np.sin(a), np.cos(a)
    g = np.empty((6, 7))
    g[0::2] = (ARM_W * -s) @ ARM_C
    g[1::2] = (ARM_W * c) @ ARM_C
    theta, gamma, phi, omega = float(q[1]), float(q[2]), float(q[3]), float(q[5])
    bd, td, _, pd, dd, od, ed = v.tolist()
    e_ea, zf_fa = E - EA, ZF - FA
    st, ct, sp, cp, so, co = (
        math.sin(theta),
        math.cos(theta),
        math.sin(phi),
        math.cos(phi),
        math.sin(omega),
        math.cos(omega),
    )
    k1, k3, k5 = M[1] * DA * RR, M[3] * ZT * e_ea, M[5] * U * zf_fa
    # d(M v')/dq: M depends on theta, phi and omega.
    dmv = np.zeros((7, 7))
    dmv[0, 1], dmv[1, 1] = 2 * k1 * st * vp[0] + k1 * st * vp[1], k1 * st * vp[0]
    dmv[3, 3], dmv[4, 3] = k3 * cp * vp[4], k3 * cp * vp[3] + 2 * k3 * cp * vp[4]
    dmv[5, 5], dmv[6, 5] = -k5 * co * vp[6], -k5 * co * vp[5] - 2 * k5 * co * vp[6]
    # df/dq and df/dv.
    dfq, dfv = np.zeros((7, 7)), np.zeros((7, 7))
    dfq[0, 1] = -k1 * td * (td + 2 * bd) * ct
    dfv[0, 0], dfv[0, 1] = -2 * k1 * td * st, -k1 * (2 * td + 2 * bd) * st
    dfq[1, 1], dfv[1, 0] = k1 * bd * bd * ct, 2 * k1 * bd * st
    sg, cg = math.sin(gamma), math.cos(gamma)
    dpx, dpy = SD * cg + SC * sg, SD * sg - SC * cg
    dx, dy = XB + dpx - XC, YB + dpy - YC
    length = math.hypot(dx, dy)
    tau = -dx * dpy + dy * dpx
    dtau = dpy * dpy - dx * dpx + dpx * dpx - dy * dpy
    pull = -C0 * (length - L0) / length
    dpull = -C0 * L0 * (tau / length) / length**2
    dfq[2, 2] = dpull * tau + pull * dtau
    dfq[3, 3], dfv[3, 4] = -k3 * dd * dd * sp, 2 * k3 * dd * cp
    dfq[4, 3] = k3 * pd * (pd + 2 * dd) * sp
    dfv[4, 3], dfv[4, 4] = -k3 * (2 * pd + 2 * dd) * cp, -2 * k3 * pd * cp
    dfq[5, 5], dfv[5, 6] = k5 * ed * ed * so, -2 * k5 * ed * co
    dfq[6, 5] = -k5 * od * (od + 2 * ed) * so
    dfv[6, 5], dfv[6, 6] = k5 * (2 * od + 2 * ed) * co, 2 * k5 * od * co

    # d(G^T lam)/dq and d(G^T mu)/dq: sum over the arms of C_a C_a^T times a weight; d(G v)/dq.
    def gt_dq(x: Any) -> Any:
        kappa = -c * (ARM_W.T @ x[0::2]) - s * (ARM_W.T @ x[1::2])
        return ARM_C.T @ (kappa[:, None] * ARM_C)

    rate = ARM_C @ v
    jj[:] = 0.0
    jj[:7, :7] = cj * np.eye(7) + gt_dq(mu)
    jj[:7, 7:14] = -np.eye(7)
    jj[:7, 20:26] = g.T
    jj[7:14, :7] = dmv - dfq + gt_dq(lam)
    jj[7:14, 7:14] = cj * m - dfv
    jj[7:14, 14:20] = g.T
    jj[14:20, :7] = g
    jj[20:26:2, :7] = (ARM_W * (-c * rate)) @ ARM_C
    jj[21:26:2, :7] = (ARM_W * (-s * rate)) @ ARM_C
    jj[20:26, 7:14] = g


def write_deck() -> None:
    DECK.parent.mkdir(exist_ok=True)
    DECK.write_text(deck_text())


if __name__ == "__main__":
    write_deck()
    print(f"wrote {DECK}")
