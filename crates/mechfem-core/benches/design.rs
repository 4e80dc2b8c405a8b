//! What a design evaluation costs against a plain run: the supply mechanism
//! (`examples/supply/supply.mec`) turned once in 360 positions, recording its
//! output's second-order transfer function (a) alone, (b) with its design
//! sensitivities to one and to all eleven constant rows, and (c) as the
//! optimiser evaluates a design: with the output's two dead positions
//! located exactly and their sensitivities.

mod common;

use common::turn;
use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use mechfem_core::design::{evaluate, ExtremumSpec};
use mechfem_core::{run, DesignVar, FormRef, Quantity, Recorder};
use std::hint::black_box;

fn bench(c: &mut Criterion) {
    let deck = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/supply/supply.mec");
    let model = mechfem_deck::load(deck).expect("the supply deck compiles");
    let (mech, mut start) = (model.mechanism, model.state);
    let mut kin = mechfem_core::Kinematics::new(&mech);
    mechfem_core::adjust(&mech, &mut start, &mut kin, &model.params).unwrap();
    let out = FormRef::Dependent(0);
    let tf2 = Quantity::Ke2(out, 0, 0);
    let motion = turn(360);
    let mut group = c.benchmark_group("design");
    group.throughput(Throughput::Elements(360));
    group.bench_function("run_360", |b| {
        b.iter(|| {
            let mut state = start.clone();
            let mut rec = Recorder::new(vec![tf2], false);
            run(&mech, &mut state, Some(&motion), &model.params, &mut rec).unwrap();
            black_box(rec.positions())
        })
    });
    let one = [DesignVar::Row(4)];
    let all: Vec<DesignVar> = (0..mech.n_prescribed() - 1).map(DesignVar::Row).collect();
    for (name, vars) in [("sensitivities_1_360", &one[..]), ("sensitivities_11_360", &all[..])] {
        group.bench_function(name, |b| {
            b.iter(|| {
                let mut state = start.clone();
                let r = evaluate(&mech, &mut state, &motion, &model.params, vars, &[tf2], &[]).unwrap();
                black_box(r.positions)
            })
        });
    }
    let dead = [ExtremumSpec { quantity: tf2, reference: Quantity::E0(out) }];
    group.bench_function("design_with_extrema_1_360", |b| {
        b.iter(|| {
            let mut state = start.clone();
            let r = evaluate(&mech, &mut state, &motion, &model.params, &one, &[tf2], &dead).unwrap();
            black_box(r.extrema.len())
        })
    });
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
