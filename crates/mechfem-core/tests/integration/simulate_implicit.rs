//! The implicit method (Radau IIA) on its own: its error falls with the
//! tolerance, it integrates mechanisms with many free DOFs, and the
//! automatic choice reaches a tight tolerance on a stiff motion at the
//! implicit method's cost.

use crate::common_dynamics as models;

use mechfem_core::dynamics::{Dynamics, Integration, Integrator, Load, LoadKind, PointMass};
use mechfem_core::run::{simulate, InverseDynamics, SimReport};
use mechfem_core::{ElementType, FormRef, InputMotion, MechanismBuilder, Motion, Params, Quantity, Recorder, Term};

const G: f64 = 9.81;

/// The stiff four-bar of `simulate_methods.rs` (damper and spring of 3e6 on
/// its rocker angle, a stiffness ratio above 1e5) over `span` seconds,
/// outputs every 0.05 s: the crank angle at every output, and the report.
fn stiff_fourbar(integrator: Integrator, tol: f64, span: f64) -> (Vec<f64>, SimReport) {
    let model = models::fourbar(&models::Fourbar::default());
    let mut dynamics = model.dynamics.clone();
    let e0 = model.state.clone().dependent_value(&model.mech, 0).unwrap() + 0.2;
    dynamics.loads.push(Load { form: FormRef::Dependent(0), kind: LoadKind::Spring { k: 3e6, e0, c: 3e6 } });
    let steps = (span / 0.05).round() as usize;
    let motion = Motion { steps, dt: 0.05, inputs: vec![InputMotion::Dynamic { v0: 0.0 }] };
    let mut rec = Recorder::new(vec![Quantity::Input(0)], false);
    let mut integration = Integration::new(tol, tol);
    integration.integrator = integrator;
    let params = Params { tol: integration.newton_tolerance(), ..Params::default() };
    let mut state = model.state.clone();
    let report = simulate(&model.mech, &mut state, &motion, &params, &integration, &dynamics, &mut rec).unwrap();
    assert!(report.run.stop.is_none(), "{integrator:?} at {tol:e}: {:?}", report.run.stop);
    (rec.data().to_vec(), report)
}

fn max_error(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| (x - y).abs()).fold(0.0, f64::max)
}

/// On the stiff four-bar, Radau IIA's error against a reference at 1e-13
/// falls by more than a factor of 5 for every factor of 100 in the
/// tolerance, and the automatic choice at 1e-12 (explicit until the motion
/// turns stiff) costs no more than three times what Radau IIA alone does.
#[test]
fn the_implicit_error_falls_with_the_tolerance_on_a_stiff_four_bar() {
    let span = 0.5;
    let (reference, _) = stiff_fourbar(Integrator::Radau5, 1e-13, span);
    let moved = (reference.last().unwrap() - reference[0]).abs();
    assert!(moved > 0.01, "the crank must move: {moved}");
    let errors: Vec<f64> = [1e-6, 1e-8, 1e-10]
        .iter()
        .map(|&tol| max_error(&stiff_fourbar(Integrator::Radau5, tol, span).0, &reference))
        .collect();
    assert!(errors[0] > 5.0 * errors[1] && errors[1] > 5.0 * errors[2], "errors {errors:?}");
    assert!(errors[2] < 1e-7, "errors {errors:?}");
    let (_, implicit) = stiff_fourbar(Integrator::Radau5, 1e-12, span);
    let (auto, report) = stiff_fourbar(Integrator::Auto, 1e-12, span);
    assert!(max_error(&auto, &reference) < 1e-8, "auto at 1e-12: {:e}", max_error(&auto, &reference));
    assert!(
        report.evaluations < 3 * implicit.evaluations,
        "auto {} evaluations, Radau IIA {}: {:?}",
        report.evaluations,
        implicit.evaluations,
        report.segments
    );
}

/// A chain of four pendulums hinged end to end (bars of 0.3 to 0.6 m, a
/// point mass at every hinge and at the end, each bar's angle a free DOF),
/// released from rest under gravity: integrated by Radau IIA it keeps
/// T + V, and it follows the explicit method's motion.
#[test]
fn a_chain_of_four_pendulums_runs_implicitly_and_keeps_its_energy() {
    let lengths = [0.5, 0.3, 0.6, 0.4];
    let angles: [f64; 4] = [0.3, -0.2, 0.9, -1.2];
    let masses = [1.0, 0.7, 1.3, 0.5];
    let mut b = MechanismBuilder::new();
    let (mut x, mut y) = (b.fixed(0.0), b.fixed(0.0));
    let (mut px, mut py) = (0.0, 0.0);
    let mut point_masses = Vec::new();
    for i in 0..4 {
        (px, py) = (px + lengths[i] * angles[i].cos(), py + lengths[i] * angles[i].sin());
        let (xn, yn) = (b.moving(px), b.moving(py));
        let bar = b.element(ElementType::Bin, &[x, y, xn, yn]);
        b.prescribe(&[Term::new(bar, 0)]);
        b.input(&[Term::new(bar, 1)]);
        point_masses.push(PointMass { x: xn, y: yn, mass: masses[i] });
        (x, y) = (xn, yn);
    }
    let (mech, state) = b.build().unwrap();
    let dynamics = Dynamics { point_masses, gravity: [0.0, -G], ..Dynamics::default() };
    let run = |integrator: Integrator, tol: f64| {
        let motion = Motion { steps: 50, dt: 0.01, inputs: vec![InputMotion::Dynamic { v0: 0.0 }; 4] };
        let q = vec![Quantity::Input(0), Quantity::Input(1), Quantity::Input(2), Quantity::Input(3)];
        let q = [q, vec![Quantity::Ekin, Quantity::Epot]].concat();
        let mut rec = Recorder::new(q, false).with_dynamics(InverseDynamics::new(&mech, dynamics.clone()));
        let mut integration = Integration::new(tol, tol);
        integration.integrator = integrator;
        let params = Params { tol: integration.newton_tolerance(), ..Params::default() };
        let mut s = state.clone();
        let report = simulate(&mech, &mut s, &motion, &params, &integration, &dynamics, &mut rec).unwrap();
        assert!(report.run.stop.is_none(), "{integrator:?}: {:?}", report.run.stop);
        assert_eq!(rec.positions(), 51);
        (rec.data().chunks(6).map(|r| r.to_vec()).collect::<Vec<_>>(), report)
    };
    let (implicit, report) = run(Integrator::Radau5, 1e-10);
    assert!(report.jacobians > 0 && report.segments.iter().all(|s| s.method == Integrator::Radau5));
    let energy: Vec<f64> = implicit.iter().map(|r| r[4] + r[5]).collect();
    let swing = implicit.iter().map(|r| r[4]).fold(0.0, f64::max);
    assert!(swing > 1.0, "the chain must swing: T reaches {swing}");
    let drift = energy.iter().map(|e| (e - energy[0]).abs()).fold(0.0, f64::max);
    assert!(drift < 1e-7 * swing, "T + V drifts by {drift:e} (T reaches {swing})");
    let (explicit, _) = run(Integrator::Dopri5, 1e-11);
    for (k, (a, b)) in implicit.iter().zip(&explicit).enumerate() {
        assert!(max_error(&a[..4], &b[..4]) < 1e-6, "output {k}: {a:?} vs {b:?}");
    }
}
