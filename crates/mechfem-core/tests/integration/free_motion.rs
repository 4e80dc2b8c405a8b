//! Limit positions and free motion on a non-Grashof four-bar (theory
//! section 5.5.3, fig. 5.5.6): its input crank can only rock between two
//! limit angles where coupler and rocker lie in line, at
//! cos(theta) = (a^2 + d^2 - (b + c)^2) / (2 a d).

use mechfem_core::{
    run, ElementType, InputMotion, LimitKind, Mechanism, MechanismBuilder, Motion, Params, Quantity, Recorder,
    SolveError, State, Term,
};

const A: f64 = 1.5;
const B: f64 = 1.2;
const C: f64 = 1.4;
const D: f64 = 2.0;

fn theta_max() -> f64 {
    ((A * A + D * D - (B + C) * (B + C)) / (2.0 * A * D)).acos()
}

/// Crank A0A, coupler AB, rocker B0B, coupler point K on a ternary-2.
fn model(theta0: f64) -> (Mechanism, State) {
    let a = [A * theta0.cos(), A * theta0.sin()];
    let mut b = MechanismBuilder::new();
    let f = [b.fixed(0.0), b.fixed(0.0), b.fixed(D), b.fixed(0.0)];
    // Rough guesses: the adjustment finds the closed position nearby.
    let m: Vec<usize> = [a[0], a[1], 1.9, 1.3, 0.9, 1.6].iter().map(|&v| b.moving(v)).collect();
    let crank = b.element(ElementType::Bin, &[f[0], f[1], m[0], m[1]]);
    let coupler = b.element(ElementType::Tr2, &[m[0], m[1], m[2], m[3], m[4], m[5]]);
    let rocker = b.element(ElementType::Bin, &[f[2], f[3], m[2], m[3]]);
    for t in
        [Term::new(crank, 0), Term::new(coupler, 0), Term::new(rocker, 0), Term::new(coupler, 2), Term::new(coupler, 3)]
    {
        b.prescribe(&[t]);
    }
    b.input(&[Term::new(crank, 1)]);
    let (mech, mut state) = b.build().unwrap();
    state.target[..5].copy_from_slice(&[A, B, C, 0.6, 0.5]);
    state.target[5] = theta0;
    (mech, state)
}

#[test]
fn free_motion_traces_the_whole_closed_coupler_curve() {
    let (mech, mut state) = model(0.2);
    let q = vec![Quantity::Input(0), Quantity::X0(8), Quantity::X0(9), Quantity::Det];
    let mut rec = Recorder::new(q, true);
    let motion = Motion { steps: 900, dt: 1.0, inputs: vec![InputMotion::Free { ds: 0.02 }] };
    let report = run(&mech, &mut state, Some(&motion), &Params::default(), &mut rec).unwrap();
    assert!(report.stop.is_none(), "{:?}", report.stop);
    assert_eq!(rec.positions(), 901);
    // Every position satisfies every constraint.
    let n = mech.n_coords();
    for k in 0..rec.positions() {
        let mut s = state.clone();
        s.x.copy_from_slice(&rec.coords()[k * n..(k + 1) * n]);
        for r in 0..5 {
            let v = s.prescribed_value(&mech, r).unwrap();
            assert!((v - s.target[r]).abs() < 1e-9, "row {r} at position {k}: {v}");
        }
    }
    // The input reaches both limits, located precisely.
    let tm = theta_max();
    let passed: Vec<f64> = report.limits.iter().filter(|l| l.kind == LimitKind::Passed).map(|l| l.inputs[0]).collect();
    assert!(passed.len() >= 2, "{:?}", report.limits);
    assert!(passed.iter().any(|&t| (t - tm).abs() < 1e-8), "{passed:?} vs {tm}");
    assert!(passed.iter().any(|&t| (t + tm).abs() < 1e-8), "{passed:?} vs {}", -tm);
    let inputs = rec.column(0);
    let (lo, hi) = inputs.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), &v| (l.min(v), h.max(v)));
    assert!(hi <= tm + 1e-9 && lo >= -tm - 1e-9);
    // The coupler curve closes: after going round, the point comes back to
    // within one step of where it started.
    let (kx, ky) = (rec.column(1), rec.column(2));
    let back = (200..kx.len()).find(|&k| (kx[k] - kx[0]).hypot(ky[k] - ky[0]) < 0.02);
    assert!(back.is_some(), "the coupler curve did not close");
}

#[test]
fn driven_crank_stops_at_its_limit_and_says_where() {
    let (mech, mut state) = model(0.2);
    let mut rec = Recorder::new(vec![Quantity::Input(0)], false);
    let motion = Motion { steps: 30, dt: 1.0, inputs: vec![InputMotion::Relative { delta: 3.0 }] };
    let report = run(&mech, &mut state, Some(&motion), &Params::default(), &mut rec).unwrap();
    let stop = report.stop.expect("the crank cannot turn past its limit");
    assert_eq!(rec.positions(), stop.last_good + 1);
    assert!(rec.column(0).iter().all(|&t| t <= theta_max()));
    assert!(matches!(
        stop.error,
        SolveError::NoConvergence { .. } | SolveError::Singular { .. } | SolveError::BranchJump { .. }
    ));
    let limit = stop.limit.expect("the limit is located");
    assert_eq!(limit.kind, LimitKind::InputLimit);
    assert!((limit.inputs[0] - theta_max()).abs() < 1e-8, "{} vs {}", limit.inputs[0], theta_max());
    assert!(limit.det.abs() < 1e-6);
}
