//! A driven motion never leaves the assembly branch it started on.
//!
//! The locked four-bar: frame r1 = 70, crank r2 = 20, coupler r3 = 50,
//! rocker r4 = 39.996, so r1 + r2 - r3 - r4 = +0.004. The crank cannot turn
//! through theta = pi: it locks where coupler and rocker lie stretched in
//! line, |A B0| = r3 + r4, at cos(theta) = (r1^2 + r2^2 - (r3 + r4)^2) /
//! (2 r1 r2), theta = 3.1189 (178.70 degrees), and the locked zone reaches
//! to 2 pi - theta. Beyond it both assembly branches exist again. Started at
//! 2.5 degrees, 18, 36 and 72 steps a turn each have a step that jumps over
//! the whole zone; each must stop at the limit all the same, as 360 steps
//! do, without a position on the other branch.
//!
//! The crank-rocker and the double crank turned in 10 steps: no stop, and
//! every position is the closed-form one.

use mechfem_core::{
    run, ElementType, InputMotion, LimitKind, Mechanism, MechanismBuilder, Motion, Params, Quantity, Recorder, State,
    Term,
};

/// Frame, crank, coupler, rocker.
const LOCKED: [f64; 4] = [70.0, 20.0, 50.0, 39.996];
const CRANK_ROCKER: [f64; 4] = [4.0, 1.0, 3.5, 3.0];
const DOUBLE_CRANK: [f64; 4] = [1.0, 3.0, 3.5, 3.2];

/// The crank angle at which coupler and rocker lie stretched in line.
fn limit_angle([r1, r2, r3, r4]: [f64; 4]) -> f64 {
    ((r1 * r1 + r2 * r2 - (r3 + r4) * (r3 + r4)) / (2.0 * r1 * r2)).acos()
}

/// The rocker pin B at crank angle `theta` on the branch where B lies to the
/// left of A -> B0 (`side` = 1) or to its right (-1): the crank pin A, then
/// B from |AB| = r3 and |B0 B| = r4.
fn closed_form([r1, r2, r3, r4]: [f64; 4], theta: f64, side: f64) -> [f64; 4] {
    let a = [r2 * theta.cos(), r2 * theta.sin()];
    let (ex, ey) = (r1 - a[0], -a[1]);
    let e = ex.hypot(ey);
    let along = (r3 * r3 - r4 * r4 + e * e) / (2.0 * e);
    let across = (r3 * r3 - along * along).sqrt();
    let (ux, uy) = (ex / e, ey / e);
    [a[0], a[1], a[0] + along * ux - side * across * uy, a[1] + along * uy + side * across * ux]
}

/// The assembly mode: the sign of (B - A) x (B0 - A).
fn orientation(r1: f64, p: &[f64]) -> f64 {
    let (bx, by, cx, cy) = (p[2] - p[0], p[3] - p[1], r1 - p[0], -p[1]);
    (bx * cy - by * cx).signum()
}

/// The four-bar with its crank at `theta0`, rocker pin to the left of
/// A -> B0 (seen from A: B0 to the right of A -> B).
fn model(dims: [f64; 4], theta0: f64) -> (Mechanism, State) {
    let [r1, r2, r3, r4] = dims;
    let guess = closed_form(dims, theta0, 1.0);
    let mut b = MechanismBuilder::new();
    let f = [b.fixed(0.0), b.fixed(0.0), b.fixed(r1), b.fixed(0.0)];
    // Rough estimates: the adjustment finds the position nearby.
    let m: Vec<usize> = guess.iter().map(|&v| b.moving(v + 0.01)).collect();
    let crank = b.element(ElementType::Bin, &[f[0], f[1], m[0], m[1]]);
    let coupler = b.element(ElementType::Bin, &[m[0], m[1], m[2], m[3]]);
    let rocker = b.element(ElementType::Bin, &[f[2], f[3], m[2], m[3]]);
    for t in [Term::new(crank, 0), Term::new(coupler, 0), Term::new(rocker, 0)] {
        b.prescribe(&[t]);
    }
    b.input(&[Term::new(crank, 1)]);
    let (mech, mut state) = b.build().unwrap();
    state.target[..4].copy_from_slice(&[r2, r3, r4, theta0]);
    (mech, state)
}

/// A turn of the crank in `steps` steps from `theta0`, positions only or
/// with the second-order transfer functions (and det(D^c)).
fn turn(dims: [f64; 4], theta0: f64, steps: usize, second: bool) -> (Recorder, mechfem_core::RunReport) {
    let (mech, mut state) = model(dims, theta0);
    let mut q = vec![Quantity::Input(0), Quantity::X0(4), Quantity::X0(5), Quantity::X0(6), Quantity::X0(7)];
    if second {
        q.push(Quantity::Kx2 { coord: 6, j: 0, m: 0 });
    }
    let mut rec = Recorder::new(q, false);
    let motion = Motion { steps, dt: 1.0, inputs: vec![InputMotion::Relative { delta: std::f64::consts::TAU }] };
    let report = run(&mech, &mut state, Some(&motion), &Params::default(), &mut rec).unwrap();
    (rec, report)
}

/// Crank angle and A, B at every position recorded.
fn positions(rec: &Recorder, second: bool) -> Vec<[f64; 5]> {
    let width = if second { 6 } else { 5 };
    rec.data().chunks(width).map(|r| [r[0], r[1], r[2], r[3], r[4]]).collect()
}

#[test]
fn the_locked_four_bar_stops_at_its_limit_at_any_step_count() {
    let limit = limit_angle(LOCKED);
    assert!((limit - 3.118_914_551).abs() < 1e-9, "{limit}");
    let theta0 = 2.5f64.to_radians();
    for second in [false, true] {
        for steps in [18, 36, 72, 360] {
            let (rec, report) = turn(LOCKED, theta0, steps, second);
            let what = format!("{steps} steps, second order {second}");
            let stop = report.stop.as_ref().unwrap_or_else(|| panic!("{what}: no stop"));
            let located = stop.limit.as_ref().unwrap_or_else(|| panic!("{what}: no limit: {stop:?}"));
            assert_eq!(located.kind, LimitKind::InputLimit, "{what}");
            assert!((located.inputs[0] - limit).abs() < 1e-8, "{what}: stopped at {}", located.inputs[0]);
            // Every position reported is on the branch of position 1, where
            // the closed form puts it.
            let got = positions(&rec, second);
            assert_eq!(got.len(), stop.last_good + 1, "{what}");
            for (k, p) in got.iter().enumerate() {
                assert!(p[0] < limit, "{what}: position {} at {} beyond the limit", k + 1, p[0]);
                assert_eq!(orientation(LOCKED[0], &p[1..]), orientation(LOCKED[0], &got[0][1..]), "{what}: {k}");
                let want = closed_form(LOCKED, p[0], 1.0);
                for (g, w) in p[1..].iter().zip(want) {
                    assert!((g - w).abs() < 1e-7, "{what}: position {}: {g} vs {w}", k + 1);
                }
            }
        }
    }
}

#[test]
fn crank_rocker_and_double_crank_turn_in_ten_steps_without_a_stop() {
    for dims in [CRANK_ROCKER, DOUBLE_CRANK] {
        let [r1, r2, ..] = dims;
        // Grashof, with the crank (crank-rocker) or the frame (double
        // crank) the shortest link: the crank turns fully.
        let mut sorted = dims;
        sorted.sort_by(f64::total_cmp);
        assert!(sorted[0] + sorted[3] < sorted[1] + sorted[2] && r2.min(r1) == sorted[0]);
        for second in [false, true] {
            let (rec, report) = turn(dims, 0.0, 10, second);
            assert!(report.stop.is_none(), "{dims:?}: {:?}", report.stop);
            let got = positions(&rec, second);
            assert_eq!(got.len(), 11);
            for (k, p) in got.iter().enumerate() {
                let theta = k as f64 * std::f64::consts::TAU / 10.0;
                assert!((p[0] - theta).abs() < 1e-12);
                let want = closed_form(dims, theta, 1.0);
                for (g, w) in p[1..].iter().zip(want) {
                    assert!((g - w).abs() < 1e-8, "{dims:?} position {}: {g} vs {w}", k + 1);
                }
            }
        }
    }
}

#[test]
fn free_motion_of_the_locked_four_bar_turns_back_at_its_limits() {
    // Free motion passes the limits, where the crank turns back: it rocks
    // between -limit and +limit and never crosses the locked zone, with
    // steps up to twice the zone's width (A moves 0.9 across it). (Far
    // longer steps see the two sides of the zone as one smooth path.)
    let limit = limit_angle(LOCKED);
    for ds in [0.5, 1.0, 2.0] {
        let (mech, mut state) = model(LOCKED, 2.5f64.to_radians());
        let mut rec = Recorder::new(vec![Quantity::Input(0)], false);
        // A path long enough for both limits (a full rocking is about 400).
        let steps = (600.0 / ds) as usize;
        let motion = Motion { steps, dt: 1.0, inputs: vec![InputMotion::Free { ds }] };
        let report = run(&mech, &mut state, Some(&motion), &Params::default(), &mut rec).unwrap();
        assert!(report.stop.is_none(), "ds {ds}: {:?}", report.stop);
        let reached = rec.data().iter().fold(0.0f64, |m, t| m.max(t.abs()));
        assert!(reached <= limit + 1e-9, "ds {ds}: the crank reached {reached}");
        let passed: Vec<f64> =
            report.limits.iter().filter(|l| l.kind == LimitKind::Passed).map(|l| l.inputs[0]).collect();
        assert!(passed.len() >= 2, "ds {ds}: {passed:?}");
        for p in passed {
            assert!((p.abs() - limit).abs() < 1e-8, "ds {ds}: a limit at {p}");
        }
    }
}
