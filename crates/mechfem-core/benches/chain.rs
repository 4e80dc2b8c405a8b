//! How the cost grows with the size of a mechanism: chains of 10, 100 and
//! 1000 four-bar loops (`tests/common/chain.rs`; 4 moving co-ordinates and
//! 4 rows of D^c per loop, D^c factorised in one 2 x 2 block per pin). Per size:
//! one Newton position, the transfer functions at one position, and a turn
//! of the first crank in 360 positions (see `common`).
//! Throughput is in positions; divide by the loops for the cost per loop.

mod common;

#[path = "../tests/common/chain.rs"]
mod chain;

use common::{cycle_benches, position_benches};
use criterion::{criterion_group, criterion_main, Criterion};
use mechfem_core::{adjust, Kinematics, Params};

fn bench(c: &mut Criterion) {
    let mut group = c.benchmark_group("chain");
    for loops in [10, 100, 1000] {
        let (mech, mut start) = chain::chain(loops, 0.2);
        let mut kin = Kinematics::new(&mech);
        adjust(&mech, &mut start, &mut kin, &Params::default()).unwrap();
        if loops >= 100 {
            group.sample_size(10);
        }
        let label = format!("loops_{loops}");
        position_benches(&mut group, &label, &mech, &start);
        cycle_benches(&mut group, &label, &mech, &start, 360);
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
