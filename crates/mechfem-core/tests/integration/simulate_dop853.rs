//! The explicit method of order 8 (DOP853) on a mechanism with a closed
//! form: a pendulum swinging 2 rad from the bottom, whose angle is
//! `2 asin(k sn(K - w t, k))` from the bottom (k = sin(theta0 / 2),
//! w = sqrt(g / l), sn Jacobi's elliptic function).

use crate::common_dynamics as models;

use mechfem_core::dynamics::{Integration, Integrator, StopWhen};
use mechfem_core::run::{simulate, SimReport};
use mechfem_core::{InputMotion, Motion, Params, Quantity, Recorder};
use std::f64::consts::PI;

const G: f64 = 9.81;
const L: f64 = 0.9;
const AMPLITUDE: f64 = 2.0;

/// Jacobi's sn(u, k) by the arithmetic-geometric mean (Abramowitz and
/// Stegun 16.4), and K(k).
fn sn_and_k(u: f64, k: f64) -> (f64, f64) {
    let (mut a, mut b) = (1.0f64, (1.0 - k * k).sqrt());
    let (mut aa, mut cc) = (vec![a], vec![k]);
    while cc.last().unwrap().abs() > 1e-17 && aa.len() < 40 {
        let c = 0.5 * (a - b);
        (a, b) = (0.5 * (a + b), (a * b).sqrt());
        aa.push(a);
        cc.push(c);
    }
    let n = aa.len() - 1;
    let mut phi = 2f64.powi(n as i32) * a * u;
    for i in (1..=n).rev() {
        phi = 0.5 * (phi + (cc[i] / aa[i] * phi.sin()).asin());
    }
    (phi.sin(), PI / (2.0 * a))
}

/// The pendulum's input angle at time `t` (the bottom is -pi/2).
fn exact(t: f64) -> f64 {
    let k = (AMPLITUDE / 2.0).sin();
    let (_, kk) = sn_and_k(0.0, k);
    let (sn, _) = sn_and_k(kk - (G / L).sqrt() * t, k);
    -PI / 2.0 + 2.0 * (k * sn).asin()
}

/// The pendulum simulated from rest for `steps` outputs over `span` by
/// `integrator` at `tol` (the Newton tolerance following from it): the
/// largest error of the angle over the outputs, and the report.
fn swing(
    integrator: Integrator,
    tol: f64,
    steps: usize,
    span: f64,
    stop_when: Option<StopWhen>,
) -> (f64, SimReport, Vec<f64>) {
    let (mech, mut state, dynamics) = models::pendulum(L, -PI / 2.0 + AMPLITUDE, 1.3);
    let motion = Motion { steps, dt: span / steps as f64, inputs: vec![InputMotion::Dynamic { v0: 0.0 }] };
    let mut rec = Recorder::new(vec![Quantity::Time, Quantity::Input(0)], false);
    let mut integration = Integration::new(tol, tol);
    (integration.integrator, integration.stop_when) = (integrator, stop_when);
    let params = Params { tol: integration.newton_tolerance(), ..Params::default() };
    let report = simulate(&mech, &mut state, &motion, &params, &integration, &dynamics, &mut rec).unwrap();
    assert!(report.run.stop.is_none(), "{:?}", report.run.stop);
    let data = rec.data().to_vec();
    let err = data.chunks(2).map(|r| (r[1] - exact(r[0])).abs()).fold(0.0, f64::max);
    (err, report, data)
}

/// The closed form itself: at rest at the start, at the bottom after a
/// quarter period, and its acceleration there g sin(theta0) / l.
#[test]
fn the_closed_form_is_the_pendulum() {
    let k = (AMPLITUDE / 2.0).sin();
    let quarter = (L / G).sqrt() * sn_and_k(0.0, k).1;
    assert!((exact(0.0) - (-PI / 2.0 + AMPLITUDE)).abs() < 1e-14);
    assert!((exact(quarter) + PI / 2.0).abs() < 1e-13);
    let h = 1e-4;
    let acc = (exact(h) - 2.0 * exact(0.0) + exact(-h)) / (h * h);
    assert!((acc + G * AMPLITUDE.sin() / L).abs() < 1e-5, "{acc}");
}

/// DOP853's error over 200 outputs, most of them inside its long steps,
/// stays within a small multiple of the tolerance and falls with it as
/// the error of its steps does (about in proportion): the outputs come
/// from its dense output of order 7, as accurate as its steps. Its error
/// there is no larger than at the ends of steps: the largest error of ten
/// runs that end at ten times spread over the swing (each ending with a
/// step there).
#[test]
fn dop853_outputs_are_as_accurate_as_its_steps_and_fall_with_the_tolerance() {
    let mut errors = Vec::new();
    for tol in [1e-6, 1e-8, 1e-10] {
        let (err, report, _) = swing(Integrator::Dop853, tol, 200, 2.0, None);
        assert!(err < 30.0 * tol, "tolerance {tol:e}: error {err:e}");
        assert!(report.steps < 100, "{} steps: the outputs must come from inside the steps", report.steps);
        let ends = (1..=10).map(|i| swing(Integrator::Dop853, tol, 1, 0.2 * i as f64, None).0).fold(0.0, f64::max);
        assert!(err < 20.0 * ends, "tolerance {tol:e}: {err:e} over 200 outputs, up to {ends:e} at steps' ends");
        errors.push(err);
    }
    // A fifth-order interpolant in steps growing as tol^(-1/8) would fall
    // only as tol^(3/4): 1e3 over these four decades.
    assert!(errors[0] > 3e3 * errors[2], "errors {errors:?}");
}

/// At a tight tolerance DOP853 needs fewer evaluations than Dormand-Prince
/// 5(4), for no larger an error, and it evaluates its dense output only in
/// steps that hold an output: 11 evaluations per step attempted, 1 more
/// per step accepted, 3 more per step with outputs, 1 per output.
#[test]
fn dop853_is_cheaper_than_dopri5_at_a_tight_tolerance() {
    let (e8, r8, _) = swing(Integrator::Dop853, 1e-11, 20, 2.0, None);
    let (e5, r5, _) = swing(Integrator::Dopri5, 1e-11, 20, 2.0, None);
    assert!(e8 <= e5, "dop853 {e8:e}, dopri5 {e5:e}");
    assert!(
        (r8.evaluations as f64) < 0.7 * r5.evaluations as f64,
        "dop853 {} evaluations, dopri5 {}",
        r8.evaluations,
        r5.evaluations
    );
    let attempts = r8.steps + r8.rejected;
    // The first derivative, the first step's choice, the start's accelerations.
    let least = 11 * attempts + r8.steps + 20 + 3;
    assert!(r8.evaluations >= least && r8.evaluations <= least + 3 * 20, "{} for {attempts}", r8.evaluations);
}

/// STOPWHEN under DOP853 is located on its dense output to the closed
/// form's quarter period.
#[test]
fn dop853_locates_a_stopwhen_crossing() {
    let k = (AMPLITUDE / 2.0).sin();
    let quarter = (L / G).sqrt() * sn_and_k(0.0, k).1;
    let stop = StopWhen { quantity: Quantity::Input(0), buffer: 1, value: -PI / 2.0 };
    let (_, report, data) = swing(Integrator::Dop853, 1e-11, 200, 2.0, Some(stop));
    let event = report.event.expect("the pendulum reaches the bottom");
    assert!((event.time - quarter).abs() < 1e-9, "stopped at {}, the quarter period is {quarter}", event.time);
    assert!((data[data.len() - 1] + PI / 2.0).abs() < 1e-9);
}

/// Without ACCURACY the Newton tolerance follows from INTTOL: a tenth of
/// it, a thousandth for DOP853 (whose error estimate takes the positions'
/// residual for error), within [1e-14, 1e-10].
#[test]
fn dop853_derives_a_tighter_newton_tolerance() {
    let mut i = Integration::new(1e-10, 1e-9);
    assert_eq!(i.newton_tolerance(), 0.1 * 1e-10);
    i.integrator = Integrator::Dop853;
    assert!((i.newton_tolerance() - 1e-13).abs() < 1e-27);
    assert_eq!(Integration { rtol: 1e-6, atol: 1e-6, ..i }.newton_tolerance(), 1e-10);
    assert_eq!(Integration { rtol: 1e-12, ..i }.newton_tolerance(), 1e-14);
}
