"""The simulation work-precision benchmark's own parts (benches/bench_work_precision.py): its decks are the ones its
modules write, the peers' hand-derived equations and Jacobians agree with finite differences and with mechfem, and
the harness runs mechfem and a peer on a problem. The benchmark itself is not run here (it takes minutes); peers
that are not installed (scikit-sundae, Exudyn: they live in .venv-bench) skip their part."""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pytest

BENCHES = Path(__file__).resolve().parents[2] / "benches"
sys.path.insert(0, str(BENCHES))

import andrews  # noqa: E402
import stiff_fourbar  # noqa: E402


def test_the_decks_are_the_ones_their_modules_write() -> None:
    assert andrews.DECK.read_text() == andrews.deck_text()
    assert stiff_fourbar.DECK.read_text() == stiff_fourbar.deck_text()


def central_jacobian(residual, y: np.ndarray, yp: np.ndarray, cj: float, h: float = 1e-6) -> np.ndarray:  # type: ignore[no-untyped-def]
    """``dres/dy + cj dres/dyp`` by central differences (y and yp moved together, yp by cj times the step)."""
    n = len(y)
    jac = np.zeros((n, n))
    for j in range(n):
        for sign in (1.0, -1.0):
            dy, dyp = y.copy(), yp.copy()
            dy[j] += sign * h
            dyp[j] += sign * h * cj
            r = np.zeros(n)
            residual(0.0, dy, dyp, r)
            jac[:, j] += sign * r / (2 * h)
    return jac


def test_andrews_ggl_jacobian_against_central_differences() -> None:
    rng = np.random.default_rng(7)
    y0, yp0 = andrews.consistent_start()
    r = np.zeros(26)
    andrews.ggl_residual(0.0, y0, yp0, r)
    assert np.abs(r).max() < 1e-14  # the published start is consistent
    for _ in range(2):
        y = y0 + rng.normal(size=26) * np.r_[np.full(7, 0.3), np.full(7, 50.0), np.ones(12)]
        yp = yp0 + rng.normal(size=26) * 100.0
        jac = np.zeros((26, 26))
        andrews.ggl_jacobian(0.0, y, yp, r, 123.0, jac)
        fd = central_jacobian(andrews.ggl_residual, y, yp, 123.0)
        assert np.abs(jac - fd).max() < 1e-8 * np.abs(fd).max()


def test_andrews_ode_form_one_state_and_many_agree() -> None:
    rng = np.random.default_rng(3)
    states = np.r_[andrews.Q0, np.zeros(7)][:, None] + rng.normal(size=(14, 3)) * 0.2
    many = andrews.ode_rhs(0.0, states)
    for k in range(3):
        one = andrews.ode_rhs(0.0, states[:, k])
        assert np.abs(one - many[:, k]).max() < 1e-9 * np.abs(many[:, k]).max()


def test_stiff_fourbar_transfer_functions_and_jacobian_against_differences() -> None:
    q, h = np.array([0.5, 1.0, 2.0, 4.0]), 1e-5
    phi, psi, phi1, psi1, phi2, psi2 = stiff_fourbar.transfer(q)
    (phi_f, psi_f), (phi_b, psi_b) = stiff_fourbar.angles(q + h), stiff_fourbar.angles(q - h)
    assert np.abs((phi_f - phi_b) / (2 * h) - phi1).max() < 1e-8
    assert np.abs((psi_f - psi_b) / (2 * h) - psi1).max() < 1e-8
    assert np.abs((phi_f - 2 * phi + phi_b) / h**2 - phi2).max() < 1e-4
    assert np.abs((psi_f - 2 * psi + psi_b) / h**2 - psi2).max() < 1e-4
    # The velocity term is half the derivative of the mass: M q'' + M'/2 q'^2 = Q (Lagrange).
    mass_f, mass_b = stiff_fourbar.terms(q + h)[0], stiff_fourbar.terms(q - h)[0]
    assert np.abs((mass_f - mass_b) / (4 * h) - stiff_fourbar.terms(q)[1]).max() < 1e-9
    y, yp = np.array([1.3, 0.4]), np.array([0.3, -2.0])
    jac = np.zeros((2, 2))
    stiff_fourbar.jacobian(0.0, y, yp, None, 7.0, jac)
    fd = central_jacobian(stiff_fourbar.residual, y, yp, 7.0)
    assert np.abs(jac - fd).max() < 1e-7 * np.abs(fd).max()


def test_the_stiff_fourbar_is_stiff_at_its_start() -> None:
    assert stiff_fourbar.stiffness_ratio(np.array([stiff_fourbar.Q0]), np.array([0.0]))[0] > 1e5


def test_the_harness_runs_mechfem_and_scipy_on_andrews_and_they_agree() -> None:
    pytest.importorskip("scipy")
    import bench_work_precision as bench
    from sim_solvers import Mechfem, Scipy, deck_at, interpolate

    (problem,) = bench.problems(["andrews"])
    assert "INTEGRATOR\timplicit" in deck_at(problem.deck.read_text(), 1e-6, "implicit")
    runs = {}
    for solver, tol in ((Mechfem(None), 1e-7), (Scipy("DOP853"), 1e-5)):
        solver.build(problem)
        runs[solver.name] = solver.run(tol)
    mech, dop = runs["mechfem"], runs["SciPy DOP853"]
    assert mech.values.shape == dop.values.shape == (31, 7)
    assert mech.evaluations and mech.evaluations > 100
    # Both follow the benchmark to its own accuracy, and reach the published angles at t = 0.03.
    assert problem.error(mech.values, dop.values) < 1e-3
    assert np.abs(mech.values[-1] - andrews.Q_PUBLISHED).max() < 1e-4
    assert interpolate([(1e-6, 1.0), (1e-8, 4.0)], 1e-7) == pytest.approx(2.0)


def test_ida_solves_the_ggl_form_of_andrews() -> None:
    pytest.importorskip("sksundae")
    import bench_work_precision as bench
    from sim_solvers import Ida

    (problem,) = bench.problems(["andrews"])
    ida = Ida(jacobian=True)
    ida.build(problem)
    run = ida.run(1e-6)
    assert np.abs(run.values[-1] - andrews.Q_PUBLISHED).max() < 1e-2


def test_exudyn_models_andrews_as_the_deck_does() -> None:
    pytest.importorskip("exudyn")
    import bench_work_precision as bench
    from sim_exudyn import Exudyn

    (problem,) = bench.problems(["andrews"])
    exudyn = Exudyn()
    exudyn.build(problem)
    run = exudyn.run(960)  # 32 steps an output: an error of about 1e-3 rad
    assert np.abs(run.values[0] - andrews.Q0).max() < 1e-12
    assert np.abs(run.values[-1] - andrews.Q_PUBLISHED).max() < 1e-2
