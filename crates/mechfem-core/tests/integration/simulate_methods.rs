//! The integration methods of a simulation: a stiff mechanism integrated
//! implicitly against a converged reference and against the cost of the
//! explicit method, the automatic choice switching, and a STOPWHEN event
//! located against a closed form.

use crate::common_dynamics as models;

use mechfem_core::dynamics::{Integration, Integrator, Load, LoadKind, StopWhen};
use mechfem_core::run::{simulate, InverseDynamics, SimReport};
use mechfem_core::{FormRef, InputMotion, Motion, Params, Quantity, Recorder};
use std::f64::consts::PI;

const G: f64 = 9.81;

/// The four-bar of the common models with a stiff spring and a stronger
/// damper on its rocker angle (k = c = 3e6): the damper makes a fast mode
/// (|lambda| = c e'^2 / M) and the spring a slow creep towards its free
/// angle (|lambda| = k / c = 1/s), whose ratio `c^2 e'^2 / (k M)` is
/// checked to exceed 1e5. Simulated `span` seconds with outputs every
/// 0.05 s by `integrator` at `tol`: the crank angle at every output, and
/// the report.
fn stiff_fourbar(integrator: Integrator, tol: f64, span: f64) -> (Vec<f64>, SimReport, f64) {
    let model = models::fourbar(&models::Fourbar::default());
    let mut dynamics = model.dynamics.clone();
    let rocker = FormRef::Dependent(0);
    let e0 = model.state.clone().dependent_value(&model.mech, 0).unwrap() + 0.2;
    let (k, c) = (3e6, 3e6);
    dynamics.loads.push(Load { form: rocker, kind: LoadKind::Spring { k, e0, c } });
    let steps = (span / 0.05).round() as usize;
    let motion = Motion { steps, dt: 0.05, inputs: vec![InputMotion::Dynamic { v0: 0.0 }] };
    let q = vec![Quantity::Input(0), Quantity::Mred(0, 0), Quantity::Ke1(rocker, 0)];
    let mut rec = Recorder::new(q, false).with_dynamics(InverseDynamics::new(&model.mech, dynamics.clone()));
    let mut integration = Integration::new(tol, tol);
    integration.integrator = integrator;
    let params = Params { tol: integration.newton_tolerance(), ..Params::default() };
    let mut state = model.state.clone();
    let report = simulate(&model.mech, &mut state, &motion, &params, &integration, &dynamics, &mut rec).unwrap();
    let explicit_stops = integrator == Integrator::Dopri5 && report.run.stop.is_some();
    assert!(report.run.stop.is_none() || explicit_stops, "{integrator:?}: {:?}", report.run.stop);
    let data = rec.data();
    let (m, e1) = (data[1], data[2]);
    let ratio = c * c * e1 * e1 / (k * m);
    (data.chunks(3).map(|r| r[0]).collect(), report, ratio)
}

/// Integrated implicitly at 1e-10, the stiff four-bar follows a reference of
/// Radau IIA at 1e-14 (which Radau IIA at 1e-13 matches to 1e-8) to 1e-6
/// rad over 3 s. The explicit method's steps are held by stability, and
/// its cost at the rate it goes until it stops as stiff, over 3 s, is more
/// than 50 times the implicit method's.
#[test]
fn a_stiff_four_bar_runs_implicitly_at_a_fiftieth_of_the_explicit_cost() {
    let (reference, _, ratio) = stiff_fourbar(Integrator::Radau5, 1e-14, 3.0);
    assert!(ratio > 1e5, "stiffness ratio {ratio:e}");
    let (check, _, _) = stiff_fourbar(Integrator::Radau5, 1e-13, 3.0);
    let (implicit, report, _) = stiff_fourbar(Integrator::Radau5, 1e-10, 3.0);
    let moved = (reference.last().unwrap() - reference[0]).abs();
    assert!(moved > 0.05, "the crank must move: {moved}");
    for k in 0..reference.len() {
        assert!((check[k] - reference[k]).abs() < 1e-8, "reference not converged at output {k}");
        let err = (implicit[k] - reference[k]).abs();
        assert!(err < 1e-6, "implicit at 1e-10: error {err:e} at output {k}");
    }
    // The explicit method, stopped as stiff where its steps fall below
    // 1/2000 of the output interval, costs at its rate so far over 3 s.
    let (_, explicit, _) = stiff_fourbar(Integrator::Dopri5, 1e-9, 3.0);
    let stop = explicit.run.stop.as_ref().expect("the explicit method stops on the stiff motion");
    assert!(stop.error.to_string().contains("stiff"), "{}", stop.error);
    let explicit_cost = explicit.evaluations as f64 * 3.0 / explicit.reached;
    assert!(
        explicit_cost > 50.0 * report.evaluations as f64,
        "explicit {} evaluations to {} s, implicit {} over 3 s",
        explicit.evaluations,
        explicit.reached,
        report.evaluations
    );
    assert!(report.jacobians > 0 && report.segments.iter().all(|s| s.method == Integrator::Radau5));
}

/// The automatic choice starts explicitly and goes over to Radau IIA on the
/// stiff four-bar, matching the reference as the implicit method does, and
/// says where it switched.
#[test]
fn the_automatic_choice_switches_to_the_implicit_method_where_the_motion_is_stiff() {
    let (reference, _, _) = stiff_fourbar(Integrator::Radau5, 1e-14, 3.0);
    let (auto, report, _) = stiff_fourbar(Integrator::Auto, 1e-10, 3.0);
    assert_eq!(report.segments.first().unwrap().method, Integrator::Dopri5);
    assert!(report.segments.iter().any(|s| s.method == Integrator::Radau5), "{:?}", report.segments);
    let ends: Vec<f64> = report.segments.iter().flat_map(|s| [s.from, s.to]).collect();
    assert!(ends.windows(2).all(|w| w[0] <= w[1]) && *ends.last().unwrap() == 3.0, "{ends:?}");
    for k in 0..reference.len() {
        assert!((auto[k] - reference[k]).abs() < 1e-6, "auto: error at output {k}");
    }
}

/// K(k) by the arithmetic-geometric mean.
fn elliptic_k(k: f64) -> f64 {
    let (mut a, mut b) = (1.0f64, (1.0 - k * k).sqrt());
    for _ in 0..40 {
        (a, b) = (0.5 * (a + b), (a * b).sqrt());
    }
    PI / (2.0 * a)
}

/// A pendulum released from rest 2 rad from the bottom, stopped by
/// `STOPWHEN` where its angle reaches the bottom (-pi/2): a quarter of the
/// period `4 sqrt(l/g) K(sin(theta0/2))`, located to 1e-9 s, and the last
/// position is there, after the outputs before it.
#[test]
fn stopwhen_ends_a_pendulum_at_the_bottom_after_a_quarter_period() {
    let (l, amplitude) = (0.9, 2.0f64);
    let quarter = (l / G).sqrt() * elliptic_k((amplitude / 2.0).sin());
    let (mech, mut state, dynamics) = models::pendulum(l, -PI / 2.0 + amplitude, 1.3);
    let motion = Motion { steps: 100, dt: 0.01, inputs: vec![InputMotion::Dynamic { v0: 0.0 }] };
    let mut rec = Recorder::new(vec![Quantity::Time, Quantity::Input(0)], false);
    let mut integration = Integration::new(1e-11, 1e-11);
    integration.stop_when = Some(StopWhen { quantity: Quantity::Input(0), buffer: 7, value: -PI / 2.0 });
    let params = Params { tol: integration.newton_tolerance(), ..Params::default() };
    let report = simulate(&mech, &mut state, &motion, &params, &integration, &dynamics, &mut rec).unwrap();
    assert!(report.run.stop.is_none(), "{:?}", report.run.stop);
    let event = report.event.expect("the pendulum reaches the bottom");
    assert_eq!((event.buffer, event.value), (7, -PI / 2.0));
    assert!((event.time - quarter).abs() < 1e-9, "stopped at {}, the quarter period is {quarter}", event.time);
    assert!((report.reached - event.time).abs() == 0.0);
    let data = rec.data();
    let whole = (quarter / 0.01).floor() as usize;
    assert_eq!(rec.positions(), whole + 2, "outputs up to {quarter} and the event");
    let (t, theta) = (data[data.len() - 2], data[data.len() - 1]);
    assert_eq!(t, event.time);
    assert!((theta + PI / 2.0).abs() < 1e-9, "the last angle is {theta}");
    assert!((event.inputs[0] + PI / 2.0).abs() < 1e-9);
}
