//! Mistakes in a model and motions that cannot be carried out come back as
//! typed errors or as a stop in the run report, never as a panic or a NaN.

use mechfem_core::{
    run, ElementError, ElementType, InputMotion, LimitKind, Mechanism, MechanismBuilder, ModelError, Motion, Observer,
    Params, Piece, PositionView, Quantity, Recorder, SolveError, State, Term, Unsupported,
};

/// Crank-rocker four-bar (Grashof, crank shortest): crank A0A, coupler AB,
/// rocker B0B, frame A0B0.
const A: f64 = 1.0;
const B: f64 = 3.0;
const C: f64 = 2.5;
const D: f64 = 3.2;

/// An observer that keeps nothing.
struct Ignore;

impl Observer for Ignore {
    fn position(&mut self, _: &PositionView<'_>) {}
}

/// Four-bar on co-ordinates A0 (0, 1), B0 (2, 3) fixed and A (4, 5), B (6, 7)
/// moving, at crank angle `theta` with B above the frame line. Elements:
/// 0 crank, 1 coupler, 2 rocker, 3 a bar between the fixed pivots.
fn fourbar_builder(theta: f64) -> MechanismBuilder {
    let a = [A * theta.cos(), A * theta.sin()];
    let (ex, ey) = (D - a[0], -a[1]);
    let e = ex.hypot(ey);
    let delta = ey.atan2(ex) + ((B * B + e * e - C * C) / (2.0 * B * e)).acos();
    let bp = [a[0] + B * delta.cos(), a[1] + B * delta.sin()];
    let mut b = MechanismBuilder::new();
    let f = [b.fixed(0.0), b.fixed(0.0), b.fixed(D), b.fixed(0.0)];
    let m = [b.moving(a[0]), b.moving(a[1]), b.moving(bp[0]), b.moving(bp[1])];
    b.element(ElementType::Bin, &[f[0], f[1], m[0], m[1]]);
    b.element(ElementType::Bin, &[m[0], m[1], m[2], m[3]]);
    b.element(ElementType::Bin, &[f[2], f[3], m[2], m[3]]);
    b.element(ElementType::Bin, &[f[0], f[1], f[2], f[3]]);
    b
}

/// The crank-rocker with the rocker angle as its input.
fn rocker_driven(theta: f64) -> (Mechanism, State) {
    let mut b = fourbar_builder(theta);
    b.prescribe(&[Term::new(0, 0)]);
    b.prescribe(&[Term::new(1, 0)]);
    b.prescribe(&[Term::new(2, 0)]);
    b.input(&[Term::new(2, 1)]);
    b.build().unwrap()
}

#[test]
fn more_rows_than_moving_coordinates_is_not_square() {
    let mut b = fourbar_builder(0.5);
    b.prescribe(&[Term::new(0, 0)]);
    b.prescribe(&[Term::new(1, 0)]);
    b.prescribe(&[Term::new(2, 0)]);
    b.prescribe(&[Term::new(1, 1)]);
    b.input(&[Term::new(0, 1)]);
    assert_eq!(b.build().unwrap_err(), ModelError::NotSquare { n_rows: 5, n_moving: 4 });
}

#[test]
fn fewer_rows_than_moving_coordinates_is_not_square() {
    let mut b = fourbar_builder(0.5);
    b.prescribe(&[Term::new(0, 0)]);
    b.input(&[Term::new(0, 1)]);
    assert_eq!(b.build().unwrap_err(), ModelError::NotSquare { n_rows: 2, n_moving: 4 });
}

#[test]
fn unknown_coordinate_is_reported_with_element_and_index() {
    let mut b = MechanismBuilder::new();
    let (x0, y0) = (b.fixed(0.0), b.fixed(0.0));
    let (xa, ya) = (b.moving(1.0), b.moving(0.0));
    let crank = b.element(ElementType::Bin, &[x0, y0, xa, ya]);
    let bad = b.element(ElementType::Bin, &[xa, ya, 7, y0]);
    b.prescribe(&[Term::new(crank, 0)]);
    b.input(&[Term::new(crank, 1)]);
    assert_eq!(b.build().unwrap_err(), ModelError::UnknownCoordinate { element: bad, coordinate: 7, n_coords: 4 });
}

#[test]
fn unknown_element_and_form_are_reported() {
    let mut b = fourbar_builder(0.5);
    b.prescribe(&[Term::new(0, 0)]);
    b.prescribe(&[Term::new(1, 0)]);
    b.prescribe(&[Term::new(9, 0)]);
    b.input(&[Term::new(0, 1)]);
    assert_eq!(b.build().unwrap_err(), ModelError::UnknownElement { element: 9, n_elements: 4 });
    let mut b = fourbar_builder(0.5);
    b.prescribe(&[Term::new(0, 0)]);
    b.prescribe(&[Term::new(1, 0)]);
    b.prescribe(&[Term::new(2, 2)]);
    b.input(&[Term::new(0, 1)]);
    assert_eq!(b.build().unwrap_err(), ModelError::UnknownForm { element: 2, ty: "BIN", form: 2 });
}

#[test]
fn coinciding_points_of_a_binary_are_reported_at_build() {
    let mut b = MechanismBuilder::new();
    let (x0, y0) = (b.fixed(0.0), b.fixed(0.0));
    let (xa, ya) = (b.moving(1.0), b.moving(0.5));
    let (xb, yb) = (b.moving(1.0), b.moving(0.5));
    let crank = b.element(ElementType::Bin, &[x0, y0, xa, ya]);
    let rod = b.element(ElementType::Bin, &[xa, ya, xb, yb]);
    b.prescribe(&[Term::new(crank, 0)]);
    b.prescribe(&[Term::new(rod, 0)]);
    b.prescribe(&[Term::new(rod, 1)]);
    b.input(&[Term::new(crank, 1)]);
    let err = b.build().unwrap_err();
    assert_eq!(err, ModelError::Element { element: rod, source: ElementError::CoincidentPoints });
}

#[test]
fn non_finite_coordinate_is_reported_at_build() {
    let mut b = MechanismBuilder::new();
    b.fixed(0.0);
    b.moving(f64::NAN);
    assert_eq!(b.build().unwrap_err(), ModelError::NonFiniteCoordinate { coordinate: 1 });
}

/// Theory section 5.3.1: the bar between the two fixed pivots has only fixed
/// co-ordinates, so prescribing its length (instead of the rocker length)
/// gives D^c a zero row.
#[test]
fn prescribing_the_superfluous_frame_bar_makes_dc_singular() {
    let mut b = fourbar_builder(0.5);
    b.prescribe(&[Term::new(0, 0)]);
    b.prescribe(&[Term::new(1, 0)]);
    b.prescribe(&[Term::new(3, 0)]);
    b.input(&[Term::new(0, 1)]);
    let (mech, mut state) = b.build().unwrap();
    let motion = Motion { steps: 10, dt: 1.0, inputs: vec![InputMotion::Relative { delta: 1.0 }] };
    let err = run(&mech, &mut state, Some(&motion), &Params::default(), &mut Ignore).unwrap_err();
    assert!(matches!(err, SolveError::Singular { .. }), "{err:?}");
    assert!(state.x.iter().all(|v| v.is_finite()));
}

/// Lengths 1, 1, 1 cannot reach across a frame of 3.2: there is no position
/// to adjust to.
#[test]
fn lengths_that_cannot_close_the_loop_fail_without_nan() {
    for (rough_start, lengths) in [(0.5, [1.0, 1.0, 1.0]), (2.0, [0.5, 1.0, 0.5]), (4.0, [A, B, 8.0])] {
        let mut b = fourbar_builder(rough_start);
        b.prescribe(&[Term::new(0, 0)]);
        b.prescribe(&[Term::new(1, 0)]);
        b.prescribe(&[Term::new(2, 0)]);
        b.input(&[Term::new(0, 1)]);
        let (mech, mut state) = b.build().unwrap();
        state.target[..3].copy_from_slice(&lengths);
        let mut rec = Recorder::new(vec![Quantity::X0(4)], true);
        let err = run(&mech, &mut state, None, &Params::default(), &mut rec).unwrap_err();
        assert!(matches!(err, SolveError::NoConvergence { .. } | SolveError::Singular { .. }), "{lengths:?}: {err:?}");
        if let SolveError::NoConvergence { residual, .. } = err {
            assert!(residual.is_finite() && residual > 1e-3, "{residual}");
        }
        assert_eq!(rec.positions(), 0);
        assert!(state.x.iter().all(|v| v.is_finite()), "{:?}", state.x);
    }
}

#[test]
fn free_motion_of_two_inputs_and_short_tables_are_reported_as_unsupported() {
    // Crank and rocker angles both driven, the coupler length free: two DOF.
    let mut b = fourbar_builder(0.5);
    b.prescribe(&[Term::new(0, 0)]);
    b.prescribe(&[Term::new(2, 0)]);
    b.input(&[Term::new(0, 1)]);
    b.input(&[Term::new(2, 1)]);
    let (mech, mut state) = b.build().unwrap();
    let inputs = vec![InputMotion::Free { ds: 0.1 }, InputMotion::Relative { delta: 0.1 }];
    let free = Motion { steps: 4, dt: 1.0, inputs };
    let err = run(&mech, &mut state, Some(&free), &Params::default(), &mut Ignore).unwrap_err();
    assert!(matches!(err, SolveError::Unsupported(_)), "{err:?}");
    let (mech, mut state) = rocker_driven(0.5);
    let rows = vec![[0.0, 2.0, 0.0, 0.0], [1.0, 2.1, 0.0, 0.0]];
    let short = Motion { steps: 4, dt: 1.0, inputs: vec![InputMotion::Table { rows }] };
    let err = run(&mech, &mut state, Some(&short), &Params::default(), &mut Ignore).unwrap_err();
    assert!(matches!(err, SolveError::Unsupported(_)), "{err:?}");
}

/// The rocker of a crank-rocker swings between the angles at which crank
/// and coupler are stretched out (|A0B| = B + A) and folded (|A0B| = B - A).
/// Driving the rocker angle past either limit stops the run there: the
/// report says where, and every position handed out before is a valid
/// assembly.
#[test]
fn driving_the_rocker_past_its_limit_stops_with_every_observed_position_valid() {
    // |B0 + C e^{i gamma}|^2 = D^2 + C^2 + 2 D C cos(gamma) = (B +- A)^2.
    let limit = |r: f64| ((r * r - D * D - C * C) / (2.0 * D * C)).acos();
    let (stretched, folded) = (limit(B + A), limit(B - A));
    // Steps of 0.05 rad put both limits well inside a step.
    for (delta, beyond) in [(-2.0, stretched), (2.0, folded)] {
        let (mech, mut state) = rocker_driven(2.5);
        let gamma0 = state.target[3];
        assert!(gamma0 > stretched + 0.1 && gamma0 < folded - 0.1, "{gamma0}");
        let steps = 40;
        let h = delta / steps as f64;
        let motion = Motion { steps, dt: 0.1, inputs: vec![InputMotion::Relative { delta }] };
        let mut rec = Recorder::new(vec![Quantity::Input(0), Quantity::Det], true);
        let report = run(&mech, &mut state, Some(&motion), &Params::default(), &mut rec).unwrap();
        let stop = report.stop.expect("the rocker cannot pass its limit");
        let last_good = ((beyond - gamma0) / h).floor() as usize;
        assert_eq!(stop.last_good, last_good, "{stop:?}");
        assert_eq!(report.positions, last_good + 1);
        assert_eq!(rec.positions(), last_good + 1);
        assert!((stop.last_inputs[0] - (gamma0 + h * last_good as f64)).abs() < 1e-12, "{stop:?}");
        assert!((stop.inputs[0] - (gamma0 + h * (last_good + 1) as f64)).abs() < 1e-12, "{stop:?}");
        assert!((stop.last_inputs[0] - beyond) * (stop.inputs[0] - beyond) < 0.0, "{stop:?}");
        assert!(
            matches!(
                stop.error,
                SolveError::NoConvergence { .. } | SolveError::Singular { .. } | SolveError::BranchJump { .. }
            ),
            "{stop:?}"
        );
        // The limit is located: at the closed-form angle, with crank and
        // coupler in line (A = A0 + A / (B +- A) * (B - A0)).
        let limit = stop.limit.as_ref().expect("the limit position is located");
        assert_eq!((limit.kind, limit.after), (LimitKind::InputLimit, last_good));
        assert!((limit.inputs[0] - beyond).abs() < 1e-9, "{limit:?}, closed form {beyond}");
        let ratio = if beyond == stretched { A / (B + A) } else { -A / (B - A) };
        for axis in 0..2 {
            assert!((limit.coords[4 + axis] - ratio * limit.coords[6 + axis]).abs() < 1e-6, "{limit:?}");
        }
        // Every observed position closes the loop with the prescribed lengths
        // and has the rocker at its input angle.
        let n = mech.n_coords();
        for k in 0..rec.positions() {
            let x = &rec.coords()[k * n..(k + 1) * n];
            let gamma = gamma0 + h * k as f64;
            assert!((rec.column(0)[k] - gamma).abs() < 1e-12);
            let dist = |p: usize, q: usize| (x[q] - x[p]).hypot(x[q + 1] - x[p + 1]);
            let tol = 1e-9;
            assert!((dist(0, 4) - A).abs() < tol, "crank length at {k}");
            assert!((dist(4, 6) - B).abs() < tol, "coupler length at {k}");
            assert!((dist(2, 6) - C).abs() < tol, "rocker length at {k}");
            assert!(((x[7] - x[3]).atan2(x[6] - x[2]) - gamma).abs() < tol, "rocker angle at {k}");
            assert!(rec.column(1)[k].is_finite() && rec.column(1)[k] != 0.0);
        }
    }
}

/// After a stop the state is the last position that was observed, with the
/// inputs of `Stop::last_inputs`, not a sub-step between it and the limit.
#[test]
fn a_stopped_run_leaves_the_state_at_the_last_observed_position() {
    let (mech, mut state) = rocker_driven(2.5);
    let motion = Motion { steps: 40, dt: 0.1, inputs: vec![InputMotion::Relative { delta: 2.0 }] };
    let mut rec = Recorder::new(vec![], true);
    let report = run(&mech, &mut state, Some(&motion), &Params::default(), &mut rec).unwrap();
    let stop = report.stop.unwrap();
    let n = mech.n_coords();
    assert_eq!(&state.x[..], &rec.coords()[stop.last_good * n..(stop.last_good + 1) * n]);
    assert_eq!(state.target[mech.input_row(0)], stop.last_inputs[0]);
}

/// A slider: one moving co-ordinate, driven by itself (CRD).
fn slider() -> (Mechanism, State) {
    let mut b = MechanismBuilder::new();
    let x = b.moving(0.5);
    b.element(ElementType::Crd, &[x]);
    b.input(&[Term::new(0, 0)]);
    b.build().unwrap()
}

#[test]
fn a_motion_whose_input_velocity_overflows_is_refused() {
    let (mech, mut state) = slider();
    let motion = Motion { steps: 1, dt: 1e-308, inputs: vec![InputMotion::Relative { delta: 10.0 }] };
    let result = run(&mech, &mut state, Some(&motion), &Params::default(), &mut Ignore);
    assert_eq!(result.unwrap_err(), SolveError::NonFinite);
}

#[test]
fn free_motion_with_an_infinite_step_stops_instead_of_halving_for_ever() {
    let (mech, mut state) = slider();
    let motion = Motion { steps: 3, dt: 1.0, inputs: vec![InputMotion::Free { ds: f64::INFINITY }] };
    let report = run(&mech, &mut state, Some(&motion), &Params::default(), &mut Ignore).unwrap();
    let stop = report.stop.expect("the first step cannot be made");
    assert_eq!((stop.last_good, stop.error), (0, SolveError::NonFinite));
    assert_eq!(state.x, vec![0.5]);
}

#[test]
fn adjusting_between_opposite_extremes_does_not_overflow() {
    let (mech, mut state) = slider();
    state.x[0] = -1e308;
    state.target[0] = 1e308;
    let report = run(&mech, &mut state, None, &Params::default(), &mut Ignore).unwrap();
    assert!(report.adjust.stages > 1);
    assert_eq!((state.x[0], state.target[0]), (1e308, 1e308));
}

/// A refusal's message is its pieces joined in the deck's words, and the
/// deck terms in it are pieces of their own, for a front end to word.
#[test]
fn refusals_say_the_deck_terms_as_pieces_of_their_own() {
    let err = SolveError::Unsupported(Unsupported::DynamicWithoutMass);
    assert_eq!(
        err.to_string(),
        "a degree of freedom that moves under the forces (MOV_DYN) has no mass or inertia to move"
    );
    assert_eq!(
        Unsupported::DynamicNeedsSimulation.to_string(),
        "an input that moves under the forces (MOV_DYN) needs a simulation (DYN SIM)"
    );
    let terms: Vec<&str> = Unsupported::FreeNeedsOneDof
        .pieces()
        .iter()
        .filter_map(|p| if let Piece::Term(t) = p { Some(t.code()) } else { None })
        .collect();
    assert_eq!(terms, ["free_motion"]);
}
