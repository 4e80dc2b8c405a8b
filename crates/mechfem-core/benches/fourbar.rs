//! The four-bar with coupler point of `tests/fourbar.rs`: the cost of one
//! Newton position, of the transfer functions at one position, and of a
//! full crank revolution in 360 positions with and without recording.
//!
//! Groups that cover a revolution report their throughput in positions, so
//! criterion's `thrpt` line reads as positions per second.

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use mechfem_core::solver::correct;
use mechfem_core::{
    adjust, run, ElementType, FormRef, InputMotion, Kinematics, Mechanism, MechanismBuilder, Motion, Observer, Params,
    PositionView, Quantity, Recorder, State, Term, TransferOrder,
};
use std::f64::consts::PI;
use std::hint::black_box;

const A: f64 = 1.0; // crank A0A
const B: f64 = 3.0; // coupler AB
const C: f64 = 2.5; // rocker B0B
const D: f64 = 3.2; // frame A0B0
const P: f64 = 1.8; // coupler point: distance from A
const ALPHA: f64 = 0.6; // coupler point: angle from AB
const POSITIONS: usize = 360;

/// The four-bar at crank angle 0, from rough co-ordinates adjusted once.
fn model() -> (Mechanism, State) {
    let mut b = MechanismBuilder::new();
    let f = [b.fixed(0.0), b.fixed(0.0), b.fixed(D), b.fixed(0.0)];
    let m: Vec<usize> = [1.0, 0.0, 2.5, 2.4, 1.5, 2.0].iter().map(|&v| b.moving(v)).collect();
    let crank = b.element(ElementType::Bin, &[f[0], f[1], m[0], m[1]]);
    let coupler = b.element(ElementType::Tr2, &[m[0], m[1], m[2], m[3], m[4], m[5]]);
    let rocker = b.element(ElementType::Bin, &[f[2], f[3], m[2], m[3]]);
    b.prescribe(&[Term::new(crank, 0)]);
    b.prescribe(&[Term::new(coupler, 0)]);
    b.prescribe(&[Term::new(rocker, 0)]);
    b.prescribe(&[Term::new(coupler, 2)]);
    b.prescribe(&[Term::new(coupler, 3)]);
    b.input(&[Term::new(crank, 1)]);
    b.dependent(&[Term::new(coupler, 1)]);
    let (mech, mut state) = b.build().unwrap();
    state.target.copy_from_slice(&[A, B, C, P * ALPHA.cos(), P * ALPHA.sin(), 0.0]);
    let mut kin = Kinematics::new(&mech);
    adjust(&mech, &mut state, &mut kin, &Params::default()).unwrap();
    (mech, state)
}

/// An observer that only touches what it is given.
struct Touch(f64);

impl Observer for Touch {
    fn position(&mut self, view: &PositionView<'_>) {
        self.0 += view.state.x[4];
    }
}

fn fourbar(c: &mut Criterion) {
    let (mech, start) = model();
    let params = Params::default();
    let input = mech.input_row(0);
    let step = 2.0 * PI / POSITIONS as f64;
    let motion = Motion { steps: POSITIONS, dt: 0.01, inputs: vec![InputMotion::Relative { delta: 2.0 * PI }] };

    let mut group = c.benchmark_group("fourbar");

    // (a) Plain Newton (eqs. 5.18, 5.19) from the previous position, one
    // degree of crank angle per position, no prediction.
    group.throughput(Throughput::Elements(POSITIONS as u64));
    let (mut state, mut kin) = (start.clone(), Kinematics::new(&mech));
    group.bench_function("newton_position", |b| {
        b.iter(|| {
            state.x.copy_from_slice(&start.x);
            state.target.copy_from_slice(&start.target);
            state.branch.copy_from_slice(&start.branch);
            for _ in 0..POSITIONS {
                state.target[input] += step;
                black_box(correct(&mech, &mut state, &mut kin, &params).unwrap());
            }
        })
    });

    // (b) det(D^c), all first- and second-order transfer functions and the
    // dependent coupler angle at one position (one factorisation).
    group.throughput(Throughput::Elements(1));
    let (mut state, mut kin) = (start.clone(), Kinematics::new(&mech));
    group.bench_function("transfer_second_order", |b| {
        b.iter(|| {
            kin.transfer(&mech, &mut state, TransferOrder::Second).unwrap();
            black_box(kin.det())
        })
    });

    // A full revolution through `run`: prediction, correction and transfer
    // functions at every position, observed but not recorded.
    group.throughput(Throughput::Elements(POSITIONS as u64 + 1));
    group.bench_function("cycle_360", |b| {
        b.iter(|| {
            let mut state = start.clone();
            let mut touch = Touch(0.0);
            run(&mech, &mut state, Some(&motion), &params, &mut touch).unwrap();
            black_box(touch.0)
        })
    });

    // (c) The same revolution with a recorder of a few quantities.
    let quantities = vec![
        Quantity::X0(8),
        Quantity::X0(9),
        Quantity::Vx(8),
        Quantity::Ax(9),
        Quantity::E0(FormRef::Dependent(0)),
        Quantity::Ke2(FormRef::Dependent(0), 0, 0),
        Quantity::Det,
    ];
    group.bench_function("cycle_360_recorded", |b| {
        b.iter(|| {
            let mut state = start.clone();
            let mut rec = Recorder::new(quantities.clone(), false);
            run(&mech, &mut state, Some(&motion), &params, &mut rec).unwrap();
            black_box(rec.positions())
        })
    });
    group.finish();
}

criterion_group!(benches, fourbar);
criterion_main!(benches);
