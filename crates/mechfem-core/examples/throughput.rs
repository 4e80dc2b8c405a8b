//! Positions per second of the core on the four-bar of
//! `benches/bench_peers.py` (crank 1, coupler 3, rocker 2.5, frame 3.2,
//! coupler point 1.8 from A at 0.6 rad from A->B), one crank turn on one
//! core, for each thing a run can compute at every position: positions
//! only, first-order or second-order transfer functions.
//!
//! ```text
//! cargo run --release -p mechfem-core --example throughput -- [STEPS ...] [--repeat R] [--min-time S] [--mode MODE]
//! ```
//!
//! Prints one JSON object per line: `{"steps": .., "mode": .., "seconds": ..,
//! "positions_per_second": .., "runs": .., "coupler_last": [x, y]}`, the
//! time being the best of the runs: at least R (default 5), and more until
//! they have taken S seconds in all (default 0), as `bench_peers.py` times
//! every tool. Without STEPS: 360 and 100000. `--mode` (positions, first,
//! second or recorded) times that mode only, for profiling.
//!
//! `recorded` is the second order with every position recorded as the
//! Python API's `Mechanism.run` records it: the full [`Layout`]'s
//! [`TransferRecord`] and every co-ordinate, in tables sized up front. It
//! is the core's own share of such a run, which the bench times beside it.

use mechfem_core::run::{Layout, TransferRecord};
use mechfem_core::{
    run, ElementType, InputMotion, Mechanism, MechanismBuilder, Motion, Observer, Params, PositionView, TransferOrder,
};
use std::f64::consts::PI;
use std::time::Instant;

/// The most runs `--min-time` adds.
const MAX_RUNS: usize = 1_000_000;

/// Keeps the coupler point of the last position; asks for `order`.
struct Last([f64; 2], Option<TransferOrder>);

impl Observer for Last {
    fn position(&mut self, view: &PositionView<'_>) {
        self.0 = [view.state.x[8], view.state.x[9]];
    }
    fn transfer_order(&self) -> Option<TransferOrder> {
        self.1
    }
}

/// Records every position as `Mechanism.run` does: the full layout's
/// record and every co-ordinate.
struct Recorded<'a> {
    layout: &'a Layout,
    record: TransferRecord,
    coords: Vec<f64>,
}

impl<'a> Recorded<'a> {
    fn new(layout: &'a Layout, mech: &Mechanism, positions: usize) -> Recorded<'a> {
        let record = TransferRecord::new(layout, mech, positions);
        Recorded { layout, record, coords: Vec::with_capacity(positions * mech.n_coords()) }
    }

    /// The coupler point at the last position recorded.
    fn coupler(&self) -> [f64; 2] {
        let n = self.coords.len();
        [self.coords[n - 2], self.coords[n - 1]]
    }
}

impl Observer for Recorded<'_> {
    fn position(&mut self, view: &PositionView<'_>) {
        self.record.push(self.layout, view, None);
        self.coords.extend_from_slice(&view.state.x);
    }
    fn transfer_order(&self) -> Option<TransferOrder> {
        Some(TransferOrder::Second)
    }
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut steps_list = Vec::new();
    let mut repeat = 5usize;
    let mut min_time = 0.0f64;
    let mut only: Option<String> = None;
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        if a == "--repeat" {
            repeat = args.next().ok_or("--repeat needs a number")?.parse()?;
        } else if a == "--min-time" {
            min_time = args.next().ok_or("--min-time needs a number of seconds")?.parse()?;
        } else if a == "--mode" {
            only = Some(args.next().ok_or("--mode needs positions, first or second")?);
        } else {
            steps_list.push(a.parse::<usize>()?);
        }
    }
    if steps_list.is_empty() {
        steps_list = vec![360, 100_000];
    }

    let (a, b, c, d, p, alpha) = (1.0, 3.0, 2.5, 3.2, 1.8, 0.6f64);
    let mut builder = MechanismBuilder::new();
    let f = [builder.fixed(0.0), builder.fixed(0.0), builder.fixed(d), builder.fixed(0.0)];
    let m: Vec<usize> = [1.0, 0.0, 2.725, 2.4545, 1.02, 1.8].iter().map(|&v| builder.moving(v)).collect();
    let crank = builder.element(ElementType::Bin, &[f[0], f[1], m[0], m[1]]);
    let coupler = builder.element(ElementType::Tr2, &[m[0], m[1], m[2], m[3], m[4], m[5]]);
    let rocker = builder.element(ElementType::Bin, &[f[2], f[3], m[2], m[3]]);
    let term = mechfem_core::Term::new;
    builder.prescribe(&[term(crank, 0)]);
    builder.prescribe(&[term(coupler, 0)]);
    builder.prescribe(&[term(rocker, 0)]);
    builder.prescribe(&[term(coupler, 2)]);
    builder.prescribe(&[term(coupler, 3)]);
    builder.input(&[term(crank, 1)]);
    let (mech, mut start) = builder.build()?;
    start.target.copy_from_slice(&[a, b, c, p * alpha.cos(), p * alpha.sin(), 0.0]);

    let params = Params::default();
    let layout = Layout::full(&mech, false);
    for steps in steps_list {
        let motion = Motion { steps, dt: 1.0, inputs: vec![InputMotion::Relative { delta: 2.0 * PI }] };
        for (mode, order) in [
            ("positions", None),
            ("first", Some(TransferOrder::First)),
            ("second", Some(TransferOrder::Second)),
            ("recorded", Some(TransferOrder::Second)),
        ] {
            if only.as_deref().is_some_and(|m| m != mode) {
                continue;
            }
            let mut best = f64::INFINITY;
            let mut last = [f64::NAN; 2];
            let (mut runs, mut total) = (0usize, 0.0f64);
            while runs < repeat.max(1) || (total < min_time && runs < MAX_RUNS) {
                let mut state = start.clone();
                let t = Instant::now();
                let (report, coupler) = if mode == "recorded" {
                    // The tables are made (and freed) in the timed run, as the API's are.
                    let mut rec = Recorded::new(&layout, &mech, steps + 1);
                    (run(&mech, &mut state, Some(&motion), &params, &mut rec)?, rec.coupler())
                } else {
                    let mut obs = Last([f64::NAN; 2], order);
                    (run(&mech, &mut state, Some(&motion), &params, &mut obs)?, obs.0)
                };
                let seconds = t.elapsed().as_secs_f64();
                best = best.min(seconds);
                (runs, total) = (runs + 1, total + seconds);
                if let Some(stop) = report.stop {
                    return Err(format!("the motion stopped: {:?}", stop.error).into());
                }
                last = coupler;
            }
            println!(
                "{{\"steps\": {steps}, \"mode\": \"{mode}\", \"seconds\": {best:e}, \"positions_per_second\": {:e}, \"runs\": {runs}, \"coupler_last\": [{}, {}]}}",
                steps as f64 / best,
                last[0],
                last[1]
            );
        }
    }
    Ok(())
}
