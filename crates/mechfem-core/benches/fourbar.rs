//! The four-bar with coupler point of `tests/fourbar.rs`: one Newton
//! position, the transfer functions at one position, and a whole crank turn
//! in 360 and in 100 000 positions, computing positions only, first order
//! or second order at each (see `common`); plus the turn in 360 positions
//! with a recorder, as a deck run records.
//!
//! Every group reports its throughput in positions, so criterion's `thrpt`
//! line reads as positions per second. `make bench` runs the peers'
//! comparison (`benches/bench_peers.py`); `docs/performance.md` has figures.

mod common;

use common::{cycle_benches, fourbar, position_benches, turn};
use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use mechfem_core::{run, FormRef, Params, Quantity, Recorder};
use std::hint::black_box;

fn bench(c: &mut Criterion) {
    let (mech, start) = fourbar();
    let mut group = c.benchmark_group("fourbar");
    position_benches(&mut group, "", &mech, &start);
    cycle_benches(&mut group, "", &mech, &start, 360);
    group.sample_size(10);
    cycle_benches(&mut group, "", &mech, &start, 100_000);
    group.sample_size(100);

    // The turn with a recorder of a few quantities.
    let quantities = vec![
        Quantity::X0(8),
        Quantity::X0(9),
        Quantity::Vx(8),
        Quantity::Ax(9),
        Quantity::E0(FormRef::Dependent(0)),
        Quantity::Ke2(FormRef::Dependent(0), 0, 0),
        Quantity::Det,
    ];
    let motion = turn(360);
    group.throughput(Throughput::Elements(360));
    group.bench_function("cycle_360_recorded", |b| {
        b.iter(|| {
            let mut state = start.clone();
            let mut rec = Recorder::new(quantities.clone(), false);
            run(&mech, &mut state, Some(&motion), &Params::default(), &mut rec).unwrap();
            black_box(rec.positions())
        })
    });
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
