//! A crank-rocker four-bar with a coupler point, checked against a
//! closed-form solution of the loop a e^{i theta} + b e^{i delta} = d + c e^{i gamma}
//! and its first and second derivatives, over several crank revolutions.

use crate::common_fourbar as fourbar;

use fourbar::{A, ALPHA, B, C, D, P};
use mechfem_core::{
    run, FormRef, InputMotion, Kinematics, Mechanism, Motion, Observer, Params, Quantity, Recorder, State,
};
use std::f64::consts::PI;

/// Closed form at crank angle theta (open branch, B above the line A-B0).
struct Exact {
    a: [f64; 2],
    b: [f64; 2],
    c: [f64; 2],
    da: [f64; 2],
    db: [f64; 2],
    dc: [f64; 2],
    dda: [f64; 2],
    ddb: [f64; 2],
    ddc: [f64; 2],
    delta: f64,
    ddelta: f64,
    dddelta: f64,
}

fn exact(theta: f64) -> Exact {
    let a = [A * theta.cos(), A * theta.sin()];
    let (ex, ey) = (D - a[0], -a[1]);
    let e = ex.hypot(ey);
    let phi = ey.atan2(ex);
    let psi = ((B * B + e * e - C * C) / (2.0 * B * e)).acos();
    let delta = phi + psi;
    let b = [a[0] + B * delta.cos(), a[1] + B * delta.sin()];
    let gamma = (b[1]).atan2(b[0] - D);
    // Velocity loop: i a e^{it} + i b d' e^{id} = i c g' e^{ig}; solve for d', g'.
    let dd = A * (gamma - theta).sin() / (B * (delta - gamma).sin());
    let dg = A * (theta - delta).sin() / (C * (gamma - delta).sin());
    // Acceleration loop: -a e^{it} + b (i d'' - d'^2) e^{id} = c (i g'' - g'^2) e^{ig}.
    // Unknowns d'', g'': real and imaginary parts of
    //   i b d'' e^{id} - i c g'' e^{ig} = a e^{it} + b d'^2 e^{id} - c g'^2 e^{ig}.
    let rx = A * theta.cos() + B * dd * dd * delta.cos() - C * dg * dg * gamma.cos();
    let ry = A * theta.sin() + B * dd * dd * delta.sin() - C * dg * dg * gamma.sin();
    // i e^{id} = (-sin d, cos d)
    let (m11, m12, m21, m22) = (-B * delta.sin(), C * gamma.sin(), B * delta.cos(), -C * gamma.cos());
    let det = m11 * m22 - m12 * m21;
    let ddd = (rx * m22 - m12 * ry) / det;
    let ddg = (m11 * ry - m21 * rx) / det;
    let da = [-A * theta.sin(), A * theta.cos()];
    let dda = [-A * theta.cos(), -A * theta.sin()];
    let db = [-C * dg * gamma.sin(), C * dg * gamma.cos()];
    let ddb = [-C * (ddg * gamma.sin() + dg * dg * gamma.cos()), C * (ddg * gamma.cos() - dg * dg * gamma.sin())];
    let k = delta + ALPHA;
    let c = [a[0] + P * k.cos(), a[1] + P * k.sin()];
    let dc = [da[0] - P * dd * k.sin(), da[1] + P * dd * k.cos()];
    let ddc = [dda[0] - P * (ddd * k.sin() + dd * dd * k.cos()), dda[1] + P * (ddd * k.cos() - dd * dd * k.sin())];
    Exact { a, b, c, da, db, dc, dda, ddb, ddc, delta, ddelta: dd, dddelta: ddd }
}

/// The shared four-bar with its estimates at the closed form, each moved by
/// `rough`.
fn model(theta0: f64, rough: f64) -> (Mechanism, State) {
    let e = exact(theta0);
    let mut estimates = [0.0; 6];
    for (k, p) in [e.a, e.b, e.c].iter().enumerate() {
        estimates[2 * k] = p[0] + rough;
        estimates[2 * k + 1] = p[1] - rough;
    }
    fourbar::model(estimates, theta0)
}

fn quantities() -> Vec<Quantity> {
    let mut q = vec![Quantity::Input(0)];
    for i in 4..10 {
        q.push(Quantity::X0(i));
        q.push(Quantity::Kx1 { coord: i, j: 0 });
        q.push(Quantity::Kx2 { coord: i, j: 0, m: 0 });
        q.push(Quantity::Vx(i));
        q.push(Quantity::Ax(i));
    }
    q.extend([
        Quantity::E0(FormRef::Dependent(0)),
        Quantity::Ke1(FormRef::Dependent(0), 0),
        Quantity::Ke2(FormRef::Dependent(0), 0, 0),
        Quantity::Det,
    ]);
    q
}

fn close(what: &str, got: f64, want: f64, tol: f64) {
    assert!((got - want).abs() <= tol * (1.0 + want.abs()), "{what}: got {got}, closed form {want}");
}

#[test]
fn fourbar_matches_closed_form_over_three_revolutions() {
    let theta0 = 0.3;
    let (mech, mut state) = model(theta0, 0.0);
    let (steps, turns) = (3 * 72, 3.0);
    let omega = 2.0; // rad per time unit
    let dt = turns * 2.0 * PI / steps as f64 / omega;
    let motion = Motion { steps, dt, inputs: vec![InputMotion::Relative { delta: turns * 2.0 * PI }] };
    let mut rec = Recorder::new(quantities(), false);
    let report = run(&mech, &mut state, Some(&motion), &Params::default(), &mut rec).unwrap();
    assert!(report.stop.is_none(), "{:?}", report.stop);
    assert_eq!(rec.positions(), steps + 1);
    let w = rec.quantities().len();
    for k in 0..=steps {
        let row = &rec.data()[k * w..(k + 1) * w];
        let theta = theta0 + turns * 2.0 * PI * k as f64 / steps as f64;
        close("input", row[0], theta, 1e-14);
        let e = exact(theta);
        let pts = [(e.a, e.da, e.dda), (e.b, e.db, e.ddb), (e.c, e.dc, e.ddc)];
        for (p, (x, dx, ddx)) in pts.iter().enumerate() {
            for axis in 0..2 {
                let base = 1 + 5 * (2 * p + axis);
                close("x", row[base], x[axis], 1e-10);
                close("x'", row[base + 1], dx[axis], 1e-9);
                close("x''", row[base + 2], ddx[axis], 1e-8);
                close("velocity", row[base + 3], omega * dx[axis], 1e-9);
                close("acceleration", row[base + 4], omega * omega * ddx[axis], 1e-8);
            }
        }
        // The coupler angle is tracked continuously: compare modulo 2 pi.
        let wrap = (row[w - 4] - e.delta) / (2.0 * PI);
        close("coupler angle", wrap - wrap.round(), 0.0, 1e-10);
        close("coupler angle'", row[w - 3], e.ddelta, 1e-9);
        close("coupler angle''", row[w - 2], e.dddelta, 1e-8);
        assert!(row[w - 1] != 0.0 && row[w - 1].is_finite());
    }
}

#[test]
fn rough_initial_position_is_adjusted_to_prescribed_lengths() {
    let theta0 = 1.1;
    let (mech, mut state) = model(theta0, 0.15);
    let mut rec = Recorder::new(vec![], false);
    let report = run(&mech, &mut state, None, &Params::default(), &mut rec).unwrap();
    assert!(report.adjust.iterations >= 2);
    assert!(report.adjust.initial_deformations.iter().any(|d| d.abs() > 0.05));
    let e = exact(theta0);
    for (k, v) in [e.a, e.b, e.c].iter().flat_map(|p| p.iter()).enumerate() {
        close("adjusted co-ordinate", state.x[4 + k], *v, 1e-10);
    }
    for r in 0..mech.n_prescribed() {
        let v = state.prescribed_value(&mech, r).unwrap();
        assert!((v - state.target[r]).abs() < 1e-10);
    }
}

#[test]
fn transfer_functions_match_finite_differences_along_the_path() {
    let (mech, mut state) = model(0.0, 0.0);
    let steps = 2000;
    let motion = Motion { steps, dt: 1.0, inputs: vec![InputMotion::Relative { delta: 2.0 * PI }] };
    let q = vec![Quantity::X0(8), Quantity::Kx1 { coord: 8, j: 0 }, Quantity::Kx2 { coord: 8, j: 0, m: 0 }];
    let mut rec = Recorder::new(q, false);
    run(&mech, &mut state, Some(&motion), &Params { tol: 1e-13, ..Params::default() }, &mut rec).unwrap();
    let (x, x1, x2) = (rec.column(0), rec.column(1), rec.column(2));
    let h = 2.0 * PI / steps as f64;
    for k in 1..steps {
        close("fd first order", (x[k + 1] - x[k - 1]) / (2.0 * h), x1[k], 1e-5);
        close("fd second order", (x1[k + 1] - x1[k - 1]) / (2.0 * h), x2[k], 1e-5);
    }
}

/// Records like a [`Recorder`] and asks the run to stop once `stop_after`
/// positions are done, as Ctrl-C does through the Python binding.
struct StopAfter {
    rec: Recorder,
    stop_after: usize,
}

impl mechfem_core::Observer for StopAfter {
    fn position(&mut self, view: &mechfem_core::PositionView<'_>) {
        self.rec.position(view);
    }
    fn stop_requested(&self) -> bool {
        self.rec.positions() >= self.stop_after
    }
}

#[test]
fn a_driven_motion_stops_when_its_observer_asks() {
    let (mech, mut state) = model(0.3, 0.0);
    let motion = Motion { steps: 72, dt: 0.1, inputs: vec![InputMotion::Relative { delta: 2.0 * PI }] };
    let mut obs = StopAfter { rec: Recorder::new(quantities(), false), stop_after: 11 };
    let report = run(&mech, &mut state, Some(&motion), &Params::default(), &mut obs).unwrap();
    assert_eq!(obs.rec.positions(), 11);
    assert_eq!(report.positions, 11);
    let stop = report.stop.expect("the run reports why it stopped");
    assert_eq!(stop.last_good, 10);
    assert!(matches!(stop.error, mechfem_core::SolveError::Interrupted));
    close("last input", stop.last_inputs[0], 0.3 + 2.0 * PI * 10.0 / 72.0, 1e-14);
}

#[test]
fn a_run_of_positions_only_matches_the_closed_form_at_fine_and_coarse_steps() {
    // Positions only predict by extrapolation and factorise D^c only now
    // and then: at every step size the positions must still be exact. Its
    // blocks are all 2 x 2 (crank pin, dyad, coupler point), so that it is
    // solved by Cramer's rule, here and in every test of this file.
    let theta0 = 0.3;
    assert_eq!(Kinematics::new(&model(theta0, 0.0).0).block_sizes(), vec![2, 2, 2]);
    let x0: Vec<Quantity> = (4..10).map(Quantity::X0).collect();
    for steps in [3 * 36, 3 * 360, 3 * 20_000] {
        let (mech, mut state) = model(theta0, 0.0);
        let motion = Motion { steps, dt: 1.0, inputs: vec![InputMotion::Relative { delta: 6.0 * PI }] };
        let mut rec = Recorder::new(x0.clone(), false);
        assert_eq!(rec.transfer_order(), None);
        let report = run(&mech, &mut state, Some(&motion), &Params::default(), &mut rec).unwrap();
        // At ten-degree steps a few predictions miss by more than 1 % of
        // their move, and those steps are subdivided (so the stepper keeps
        // the branch); at finer steps none does.
        assert!(report.stop.is_none(), "{steps}: {report:?}");
        assert!(report.subdivided_steps <= if steps == 3 * 36 { steps / 10 } else { 0 }, "{steps}: {report:?}");
        for k in 0..=steps {
            let e = exact(theta0 + 6.0 * PI * k as f64 / steps as f64);
            let want = [e.a[0], e.a[1], e.b[0], e.b[1], e.c[0], e.c[1]];
            for (got, want) in rec.data()[6 * k..6 * k + 6].iter().zip(want) {
                close("x", *got, want, 1e-10);
            }
        }
    }
}
