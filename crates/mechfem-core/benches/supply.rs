//! The supply mechanism of a high-speed punching machine (theory section
//! 5.6.6, Table 5.1: 12 moving co-ordinates), read from
//! `examples/supply/supply.mec`: one Newton position, the transfer functions
//! at one position, and a turn of the input crank in 360 and 100 000
//! positions (see `common`); plus the turn in 360 positions recording the
//! deck's own buffers (the output angle, its first-
//! and second-order transfer functions).

mod common;

use common::{cycle_benches, position_benches, turn};
use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use mechfem_core::{run, Quantity, Recorder};
use std::hint::black_box;

fn bench(c: &mut Criterion) {
    let deck = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/supply/supply.mec");
    let model = mechfem_deck::load(deck).expect("the supply deck compiles");
    let (mech, mut start) = (model.mechanism, model.state);
    // Position 1 adjusted once, as every run starts from it.
    let mut kin = mechfem_core::Kinematics::new(&mech);
    mechfem_core::adjust(&mech, &mut start, &mut kin, &model.params).unwrap();
    let mut group = c.benchmark_group("supply");
    position_benches(&mut group, "", &mech, &start);
    cycle_benches(&mut group, "", &mech, &start, 360);
    group.sample_size(10);
    cycle_benches(&mut group, "", &mech, &start, 100_000);
    group.sample_size(100);

    let quantities: Vec<Quantity> = model.buffers.iter().map(|b| b.quantity).collect();
    let motion = turn(360);
    group.throughput(Throughput::Elements(360));
    group.bench_function("cycle_360_recorded", |b| {
        b.iter(|| {
            let mut state = start.clone();
            let mut rec = Recorder::new(quantities.clone(), false);
            run(&mech, &mut state, Some(&motion), &model.params, &mut rec).unwrap();
            black_box(rec.positions())
        })
    });
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
