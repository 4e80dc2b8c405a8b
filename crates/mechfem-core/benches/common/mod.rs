//! What the benches share: the four-bar of `tests/fourbar.rs`, an observer
//! that asks a run for positions only, first or second order, and the
//! groups every mechanism is measured with.

#![allow(dead_code)]

use criterion::{BenchmarkGroup, Throughput};
use mechfem_core::solver::correct;
use mechfem_core::{
    adjust, run, InputMotion, Kinematics, Mechanism, Motion, Observer, Params, PositionView, State, TransferOrder,
};
use std::f64::consts::PI;
use std::hint::black_box;

#[path = "../../tests/common/fourbar.rs"]
mod shared_fourbar;

/// The crank-rocker four-bar with a coupler point and the coupler angle as
/// a dependent form parameter (`tests/common/fourbar.rs`), adjusted to crank
/// angle 0.
pub fn fourbar() -> (Mechanism, State) {
    let (mech, mut state) = shared_fourbar::model([1.0, 0.0, 2.5, 2.4, 1.5, 2.0], 0.0);
    let mut kin = Kinematics::new(&mech);
    adjust(&mech, &mut state, &mut kin, &Params::default()).unwrap();
    (mech, state)
}

/// An observer that asks for `order` and touches only the position.
pub struct Touch(pub f64, pub Option<TransferOrder>);

impl Observer for Touch {
    fn position(&mut self, view: &PositionView<'_>) {
        self.0 += view.state.x[view.mech.moving_coords()[0]];
    }
    fn transfer_order(&self) -> Option<TransferOrder> {
        self.1
    }
}

/// What a cycle computes at every position, with the name of its bench.
pub const MODES: [(&str, Option<TransferOrder>); 3] =
    [("positions", None), ("first", Some(TransferOrder::First)), ("second", Some(TransferOrder::Second))];

/// One turn of the (first) input in `steps` steps.
pub fn turn(steps: usize) -> Motion {
    Motion { steps, dt: 0.01, inputs: vec![InputMotion::Relative { delta: 2.0 * PI }] }
}

/// The name of bench `what` of the mechanism `label` (no prefix when the
/// group is the mechanism's own).
fn id(label: &str, what: &str) -> String {
    if label.is_empty() {
        what.to_string()
    } else {
        format!("{label}/{what}")
    }
}

/// The benches of one position of a mechanism (`label`):
///
/// * `newton`: one Newton position, the input moved by 1/360 of a turn from
///   a converged position, without prediction (eqs. 5.18, 5.19);
/// * `transfer`: det(D^c), all first- and second-order transfer functions
///   and the dependent form parameters at one position (one factorisation).
pub fn position_benches<M: criterion::measurement::Measurement>(
    group: &mut BenchmarkGroup<'_, M>,
    label: &str,
    mech: &Mechanism,
    start: &State,
) {
    let params = Params::default();
    let input = mech.input_row(0);
    group.throughput(Throughput::Elements(1));
    let (mut state, mut kin) = (start.clone(), Kinematics::new(mech));
    let mut k = 0usize;
    group.bench_function(id(label, "newton"), |b| {
        b.iter(|| {
            // Walk round the turn so that every position is a fresh one.
            if k.is_multiple_of(360) {
                state.clone_from(start);
            }
            k += 1;
            state.target[input] += 2.0 * PI / 360.0;
            black_box(correct(mech, &mut state, &mut kin, &params).unwrap())
        })
    });
    let (mut state, mut kin) = (start.clone(), Kinematics::new(mech));
    group.bench_function(id(label, "transfer"), |b| {
        b.iter(|| {
            kin.transfer(mech, &mut state, TransferOrder::Second).unwrap();
            black_box(kin.det())
        })
    });
}

/// `cycle_<steps>_<mode>`: a whole turn of a mechanism (`label`) through
/// `run` in `steps` steps (prediction, correction, and what the mode asks
/// for at every position), in positions per second.
pub fn cycle_benches<M: criterion::measurement::Measurement>(
    group: &mut BenchmarkGroup<'_, M>,
    label: &str,
    mech: &Mechanism,
    start: &State,
    steps: usize,
) {
    let params = Params::default();
    let motion = turn(steps);
    group.throughput(Throughput::Elements(steps as u64));
    for (mode, order) in MODES {
        group.bench_function(id(label, &format!("cycle_{steps}_{mode}")), |b| {
            b.iter(|| {
                let mut state = start.clone();
                let mut touch = Touch(0.0, order);
                let report = run(mech, &mut state, Some(&motion), &params, &mut touch).unwrap();
                assert!(report.stop.is_none());
                black_box(touch.0)
            })
        });
    }
}
