//! A design study on every core: 64 variants of the supply mechanism (the
//! coupler angle kappa, row 5, over a range), each turning the crank once
//! in 720 positions with second-order transfer functions, run by
//! `mechfem_core::batch::map` on one worker and on every core. The ratio of
//! the two times is the parallel speed-up.

mod common;

use common::{turn, Touch};
use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use mechfem_core::{batch, run, TransferOrder};
use std::hint::black_box;

const VARIANTS: usize = 64;

fn bench(c: &mut Criterion) {
    let deck = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/supply/supply.mec");
    let model = mechfem_deck::load(deck).expect("the supply deck compiles");
    let motion = turn(720);
    let study = |workers: usize| {
        batch::map(VARIANTS, workers, |k| {
            let mut state = model.state.clone();
            state.target[4] = -5.30 + 0.25 * k as f64 / VARIANTS as f64;
            let mut touch = Touch(0.0, Some(TransferOrder::Second));
            let report = run(&model.mechanism, &mut state, Some(&motion), &model.params, &mut touch).unwrap();
            assert!(report.stop.is_none());
            touch.0
        })
    };
    let mut group = c.benchmark_group("batch");
    group.sample_size(10);
    group.throughput(Throughput::Elements((VARIANTS * 720) as u64));
    for workers in [1, batch::available_workers()] {
        group.bench_function(format!("supply_{VARIANTS}x720/workers_{workers}"), |b| {
            b.iter(|| black_box(study(workers)))
        });
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
