//! Forward dynamics checked against what must hold whatever the integrator:
//! a pendulum's exact period at a large amplitude (complete elliptic
//! integral), conservation of T + V over many swings of a four-bar with
//! masses, the work-energy balance under a constant drive torque and a
//! spring, and the round trip inverse -> forward dynamics.

use crate::common_dynamics as models;

use mechfem_core::dynamics::{Body, Dynamics, Integration, Load, LoadKind, PointMass};
use mechfem_core::run::{simulate, simulate_within, InverseDynamics};
use mechfem_core::{
    run, ElementType, FormRef, InputMotion, Mechanism, MechanismBuilder, Motion, Params, Quantity, Recorder, State,
    Term,
};
use std::f64::consts::PI;

const G: f64 = 9.81;

/// K(k) by the arithmetic-geometric mean: K = pi / (2 agm(1, sqrt(1 - k^2))).
fn elliptic_k(k: f64) -> f64 {
    let (mut a, mut b) = (1.0f64, (1.0 - k * k).sqrt());
    // The mean converges quadratically: a handful of rounds reach the last bit.
    for _ in 0..40 {
        (a, b) = (0.5 * (a + b), (a * b).sqrt());
    }
    PI / (2.0 * a)
}

fn tight() -> Integration {
    Integration::new(1e-12, 1e-12)
}

/// Simulates `steps` steps of `dt` with input 0 free from rest, recording `q`.
fn free_run(
    mech: &Mechanism,
    state: &mut State,
    dynamics: &Dynamics,
    steps: usize,
    dt: f64,
    q: &[Quantity],
) -> Vec<f64> {
    let motion = Motion { steps, dt, inputs: vec![InputMotion::Dynamic { v0: 0.0 }] };
    let mut rec = Recorder::new(q.to_vec(), false).with_dynamics(InverseDynamics::new(mech, dynamics.clone()));
    let params = Params { tol: 1e-12, ..Params::default() };
    let report = simulate(mech, state, &motion, &params, &tight(), dynamics, &mut rec).unwrap();
    assert!(report.run.stop.is_none(), "{:?}", report.run.stop);
    assert_eq!(rec.positions(), steps + 1);
    assert!(report.steps > 0 && report.evaluations > report.steps);
    rec.data().to_vec()
}

/// Released from rest at 170 degrees from the bottom, the pendulum is back
/// after the period `4 sqrt(l/g) K(sin(theta0/2))` and on the other side
/// after half of it.
#[test]
fn pendulum_period_at_a_large_amplitude_is_exact() {
    let (l, amplitude) = (0.8, 170f64.to_radians());
    let theta0 = -PI / 2.0 + amplitude;
    let period = 4.0 * (l / G).sqrt() * elliptic_k((amplitude / 2.0).sin());
    let (mech, mut state, dynamics) = models::pendulum(l, theta0, 2.0);
    let steps = 200;
    let q = [Quantity::Input(0), Quantity::Ve(FormRef::Prescribed(1)), Quantity::Time];
    let data = free_run(&mech, &mut state, &dynamics, steps, period / steps as f64, &q);
    let at = |k: usize| &data[k * 3..k * 3 + 3];
    assert!((at(steps)[2] - period).abs() < 1e-12 * period);
    assert!((at(steps)[0] - theta0).abs() < 1e-8, "after a period: {} vs {theta0}", at(steps)[0]);
    assert!(at(steps)[1].abs() < 1e-7 * (G / l).sqrt(), "speed after a period: {}", at(steps)[1]);
    let other = -PI / 2.0 - amplitude;
    assert!((at(steps / 2)[0] - other).abs() < 1e-8, "after half a period: {} vs {other}", at(steps / 2)[0]);
}

/// A four-bar with bodies on every link and a flywheel, released from rest
/// under gravity without damping, keeps T + V through more than 20 swings.
#[test]
fn a_four_bar_swinging_under_gravity_keeps_its_energy() {
    let model = models::fourbar(&models::Fourbar::default());
    let dynamics = Dynamics { loads: vec![], forces: vec![], gravity: [0.0, -G], ..model.dynamics.clone() };
    let mut state = model.state.clone();
    let q = [Quantity::Ekin, Quantity::Epot, Quantity::Input(0)];
    let data = free_run(&model.mech, &mut state, &dynamics, 8000, 0.01, &q);
    let energy: Vec<f64> = data.chunks(3).map(|r| r[0] + r[1]).collect();
    let swing =
        data.chunks(3).map(|r| r[1]).fold(f64::MIN, f64::max) - data.chunks(3).map(|r| r[1]).fold(f64::MAX, f64::min);
    assert!(swing > 1.0, "the four-bar must really swing: V varies by {swing}");
    // Count the swings: sign changes of the crank's speed.
    let angles: Vec<f64> = data.chunks(3).map(|r| r[2]).collect();
    let turns = angles.windows(3).filter(|w| (w[1] - w[0]) * (w[2] - w[1]) < 0.0).count();
    assert!(turns >= 40, "only {turns} turning points");
    let drift = energy.iter().map(|e| (e - energy[0]).abs()).fold(0.0, f64::max);
    assert!(drift < 1e-8 * swing, "T + V drifts by {drift} (swing of V {swing})");
}

/// A constant drive torque Q on the free crank of a slider-crank with a
/// torsion spring, under gravity: T + V - Q (q - q0) stays constant.
#[test]
fn work_of_a_constant_torque_goes_into_the_energy() {
    let sc = models::SliderCrank::default();
    let (mech, mut state, mut dynamics) = models::slider_crank(&sc, 0.3);
    dynamics.forces.clear();
    let q0 = state.target[3];
    let torque = 4.0;
    dynamics.loads = vec![
        Load { form: FormRef::Prescribed(3), kind: LoadKind::Constant(torque) },
        // A torsion spring on the crank.
        Load { form: FormRef::Prescribed(3), kind: LoadKind::Spring { k: 3.0, e0: 0.5, c: 0.0 } },
    ];
    let q = [Quantity::Ekin, Quantity::Epot, Quantity::Input(0)];
    let data = free_run(&mech, &mut state, &dynamics, 500, 0.002, &q);
    let balance: Vec<f64> = data.chunks(3).map(|r| r[0] + r[1] - torque * (r[2] - q0)).collect();
    let work = data.chunks(3).map(|r| torque * (r[2] - q0)).fold(0.0, f64::max);
    assert!(work > 10.0, "the torque must do real work: {work}");
    let drift = balance.iter().map(|b| (b - balance[0]).abs()).fold(0.0, f64::max);
    assert!(drift < 1e-8 * work, "T + V - W drifts by {drift} of {work}");
}

/// The drive torque inverse dynamics finds for a prescribed motion, applied
/// as a tabulated load to the free input, reproduces that motion.
#[test]
fn inverse_then_forward_dynamics_gives_the_motion_back() {
    let sc = models::SliderCrank::default();
    let (mech, state, dynamics) = models::slider_crank(&sc, 0.3);
    let (steps, dt) = (20000, 1e-5);
    let (th0, w0, alpha) = (0.3, 8.0, 30.0);
    let rows: Vec<[f64; 4]> = (0..=steps)
        .map(|k| {
            let t = k as f64 * dt;
            [t, th0 + w0 * t + 0.5 * alpha * t * t, w0 + alpha * t, alpha]
        })
        .collect();
    let prescribed = Motion { steps, dt, inputs: vec![InputMotion::Table { rows: rows.clone() }] };
    let mut rec = Recorder::new(vec![Quantity::Time, Quantity::Drive(0)], false)
        .with_dynamics(InverseDynamics::new(&mech, dynamics.clone()));
    run(&mech, &mut state.clone(), Some(&prescribed), &Params::default(), &mut rec).unwrap();
    let torque: Vec<[f64; 2]> = rec.data().chunks(2).map(|r| [r[0], r[1]]).collect();
    let mut forward = dynamics.clone();
    forward.loads.push(Load { form: FormRef::Prescribed(3), kind: LoadKind::Table(torque) });
    let motion = Motion { steps: 40, dt: dt * 500.0, inputs: vec![InputMotion::Dynamic { v0: w0 }] };
    let mut out = Recorder::new(vec![Quantity::Time, Quantity::Input(0)], false);
    let mut s = state.clone();
    let params = Params { tol: 1e-12, ..Params::default() };
    let tol = Integration::new(1e-10, 1e-10);
    let report = simulate(&mech, &mut s, &motion, &params, &tol, &forward, &mut out).unwrap();
    assert!(report.run.stop.is_none(), "{:?}", report.run.stop);
    for r in out.data().chunks(2) {
        let want = th0 + w0 * r[0] + 0.5 * alpha * r[0] * r[0];
        // The torque is linear between its rows, within dt^2/8 |tau''| of
        // the exact one: the motion agrees to that, integrated.
        assert!((r[1] - want).abs() < 1e-7, "t {}: {} vs {want}", r[0], r[1]);
    }
}

/// A mass that cannot move a free degree of freedom is refused before
/// anything is integrated, and a body on the bar alone does move it.
#[test]
fn a_free_input_without_mass_is_refused() {
    let (mech, mut state, mut dynamics) = models::pendulum(1.0, 0.3, 1.0);
    dynamics.point_masses.clear();
    let motion = Motion { steps: 10, dt: 0.01, inputs: vec![InputMotion::Dynamic { v0: 0.0 }] };
    let mut rec = Recorder::new(vec![Quantity::Input(0)], false);
    let err = simulate(&mech, &mut state, &motion, &Params::default(), &tight(), &dynamics, &mut rec).unwrap_err();
    assert!(err.to_string().contains("no mass"), "{err}");
    dynamics.bodies.push(Body { element: 0, mass: 1.0, u: 0.5, v: 0.0, inertia: 0.0 });
    simulate(&mech, &mut state, &motion, &Params::default(), &tight(), &dynamics, &mut rec).unwrap();
}

/// A slider-crank whose slider is the free degree of freedom, pushed towards
/// the outer dead centre: the slider cannot move the crank through it, and
/// the simulation stops there with that reason instead of creeping on.
#[test]
fn a_free_input_stops_at_its_limit_position() {
    use mechfem_core::dynamics::Force;
    let (r, l, th) = (0.1f64, 0.3f64, 1.0f64);
    let mut b = MechanismBuilder::new();
    let (x0, y0, yb) = (b.fixed(0.0), b.fixed(0.0), b.fixed(0.0));
    let (xa, ya) = (b.moving(r * th.cos()), b.moving(r * th.sin()));
    let xb = b.moving(r * th.cos() + (l * l - (r * th.sin()).powi(2)).sqrt());
    let crank = b.element(ElementType::Bin, &[x0, y0, xa, ya]);
    let rod = b.element(ElementType::Bin, &[xa, ya, xb, yb]);
    let slider = b.element(ElementType::Crd, &[xb]);
    b.prescribe(&[Term::new(crank, 0)]);
    b.prescribe(&[Term::new(rod, 0)]);
    b.input(&[Term::new(slider, 0)]);
    let (mech, mut state) = b.build().unwrap();
    let dynamics = Dynamics {
        bodies: vec![Body { element: crank, mass: 1.0, u: 0.05, v: 0.0, inertia: 1e-3 }],
        point_masses: vec![PointMass { x: xb, y: yb, mass: 0.5 }],
        forces: vec![Force { x: xb, y: yb, f: [50.0, 0.0] }],
        ..Dynamics::default()
    };
    let motion = Motion { steps: 200, dt: 0.005, inputs: vec![InputMotion::Dynamic { v0: 0.0 }] };
    let mut rec = Recorder::new(vec![Quantity::Input(0)], false);
    let report = simulate(&mech, &mut state, &motion, &Params::default(), &tight(), &dynamics, &mut rec).unwrap();
    let stop = report.run.stop.expect("the slider cannot pass its dead centre");
    assert!(stop.error.to_string().contains("limit position"), "{}", stop.error);
    let reached = rec.data().iter().fold(f64::MIN, |m, &x| m.max(x));
    assert!(reached < r + l && reached > r + l - 1e-2, "the slider stops just short of r + l: {reached}");
}

/// A spring of stiffness 1e12 on a pendulum's angle swings it with a period
/// of microseconds against outputs every 10 ms: the simulation stops with
/// a reason once the step budget it was given is used up (or the motion is
/// found stiff), keeping the outputs reached, instead of creeping on.
#[test]
fn a_very_stiff_spring_stops_the_simulation_within_its_step_budget() {
    let theta0 = -1.0;
    let (mech, mut state, mut dynamics) = models::pendulum(0.8, theta0, 2.0);
    dynamics
        .loads
        .push(Load { form: FormRef::Prescribed(1), kind: LoadKind::Spring { k: 1e12, e0: theta0 + 0.1, c: 0.0 } });
    let motion = Motion { steps: 100, dt: 0.01, inputs: vec![InputMotion::Dynamic { v0: 0.0 }] };
    let mut rec = Recorder::new(vec![Quantity::Input(0)], false);
    let report = simulate_within(
        &mech,
        &mut state,
        &motion,
        &Params::default(),
        &Integration::default(),
        &dynamics,
        Some(5000),
        &mut rec,
    )
    .unwrap();
    let stop = report.run.stop.expect("the simulation must stop early");
    assert!(report.steps + report.rejected <= 5000, "{} + {} steps", report.steps, report.rejected);
    let reason = stop.error.to_string();
    assert!(reason.contains("step budget") || reason.contains("stiff"), "{reason}");
    assert!(rec.positions() < motion.steps + 1 && rec.data().iter().all(|v| v.is_finite()));
}

/// A pendulum of mass `m` and length `l` from `theta0` with a torsion
/// spring-damper `k`, `c` (free angle `e0`) on its angle, simulated for
/// `steps` outputs `dt` apart at the default tolerances: the angle, T and V
/// at every output, and the report's stop.
fn settle(l: f64, m: f64, theta0: f64, (k, e0, c): (f64, f64, f64), steps: usize, dt: f64) -> Vec<[f64; 3]> {
    let (mech, mut state, mut dynamics) = models::pendulum(l, theta0, m);
    dynamics.loads.push(Load { form: FormRef::Prescribed(1), kind: LoadKind::Spring { k, e0, c } });
    let motion = Motion { steps, dt, inputs: vec![InputMotion::Dynamic { v0: 0.0 }] };
    let q = vec![Quantity::Input(0), Quantity::Ekin, Quantity::Epot];
    let mut rec = Recorder::new(q, false).with_dynamics(InverseDynamics::new(&mech, dynamics.clone()));
    let report =
        simulate(&mech, &mut state, &motion, &Params::default(), &Integration::default(), &dynamics, &mut rec).unwrap();
    assert!(report.run.stop.is_none(), "{:?}", report.run.stop);
    assert_eq!(rec.positions(), steps + 1);
    rec.data().chunks(3).map(|r| [r[0], r[1], r[2]]).collect()
}

/// The energy T + V never grows from one output to the next by more than
/// rounding (the damper only takes energy out), and the motion really
/// settled: its last tenth holds T below `1e-12` of the energy it lost.
fn check_settling(out: &[[f64; 3]]) {
    let energy: Vec<f64> = out.iter().map(|r| r[1] + r[2]).collect();
    let lost = energy[0] - energy.last().unwrap();
    assert!(lost > 1.0, "the damper must take energy out: {lost}");
    for (k, w) in energy.windows(2).enumerate() {
        assert!(w[1] <= w[0] + 1e-10 * lost, "T + V grows after output {k}: {} to {}", w[0], w[1]);
    }
    let tail = &out[out.len() - out.len() / 10..];
    assert!(tail.iter().all(|r| r[1] < 1e-12 * lost), "still moving: T = {:e}", tail[0][1]);
}

/// A damped pendulum released 1 rad from the bottom settles within a
/// minute and then hangs at rest for over an hour: a motion at rest is not
/// stiff, and the simulation runs to its end, the pendulum hanging straight
/// down (theta = -pi/2) to 1e-8 rad.
#[test]
fn a_damped_pendulum_settles_and_rests_to_the_end() {
    let out = settle(0.7, 1.5, -PI / 2.0 + 1.0, (0.0, 0.0, 0.3), 500, 10.0);
    check_settling(&out);
    let theta = out.last().unwrap()[0];
    assert!((theta + PI / 2.0).abs() < 1e-8, "the pendulum rests at {theta}, not at -pi/2");
}

/// A pendulum on a torsion spring-damper settles where the spring holds the
/// weight, `k (theta - e0) + m g l cos(theta) = 0`, and rests there to the
/// end of 3000 s.
#[test]
fn a_damped_spring_settles_at_its_static_equilibrium() {
    let (l, m, k, e0) = (0.7, 1.5, 20.0, 0.0);
    let out = settle(l, m, 0.5, (k, e0, 0.8), 300, 10.0);
    check_settling(&out);
    // The static equilibrium by Newton from the resting angle found.
    let mut theta = out.last().unwrap()[0];
    let rest = theta;
    for _ in 0..50 {
        let f = k * (theta - e0) + m * G * l * theta.cos();
        theta -= f / (k - m * G * l * theta.sin());
    }
    assert!((k * (theta - e0) + m * G * l * theta.cos()).abs() < 1e-12);
    assert!((rest - theta).abs() < 1e-8, "rests at {rest}, the equilibrium is {theta}");
}
