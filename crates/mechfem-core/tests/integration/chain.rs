//! A chain of four-bar loops (see `common/chain.rs`): D^c is factorised
//! loop by loop, and the positions are checked loop by loop against the
//! closed form of the four-bar, including the transfer functions of the
//! last rocker.

use crate::common_chain as chain;

use chain::{chain, exact};
use mechfem_core::{
    run, FormRef, InputMotion, Kinematics, Motion, Observer, Params, PositionView, Quantity, Recorder, TransferOrder,
};
use std::f64::consts::PI;

const LOOPS: usize = 40;

fn close(what: &str, got: f64, want: f64, tol: f64) {
    assert!((got - want).abs() <= tol * (1.0 + want.abs()), "{what}: got {got}, closed form {want}");
}

/// The last rocker's angle by the closed form, continued across 2 pi.
fn last_rocker(theta: f64, near: f64) -> f64 {
    let g = *exact(LOOPS, theta).1.last().unwrap();
    g + 2.0 * PI * ((near - g) / (2.0 * PI)).round()
}

#[test]
fn a_chain_is_factorised_loop_by_loop() {
    // The first crank pin alone, then every coupler-rocker dyad (the
    // rocker pin with the crank pin it carries is solved with the next
    // loop's coupler): blocks of two, whatever the length of the chain.
    let (mech, _) = chain(LOOPS, 0.2);
    assert_eq!(mech.n_moving(), 4 * LOOPS);
    let kin = Kinematics::new(&mech);
    assert_eq!(kin.block_sizes(), vec![2; 2 * LOOPS]);
    assert!(!kin.is_banded());
}

#[test]
fn every_workspace_of_a_mechanism_shares_its_plan() {
    // D^c's storage is chosen by the first workspace and cloned into the
    // later ones, also those of a clone of the mechanism: each must
    // compute exactly what the first did, made after the first has
    // factorised its own copy (the plan itself holds no factors).
    let (mech, mut state) = chain(LOOPS, 0.2);
    let mut first = Kinematics::new(&mech);
    first.transfer(&mech, &mut state, TransferOrder::Second).expect("not a limit position");
    let copy = mech.clone();
    for m in [&mech, &copy] {
        let mut kin = Kinematics::new(m);
        assert_eq!(kin.block_sizes(), first.block_sizes());
        kin.transfer(m, &mut state.clone(), TransferOrder::Second).expect("not a limit position");
        assert_eq!(kin.det().to_bits(), first.det().to_bits());
        assert!(kin.x1(0).iter().zip(first.x1(0)).all(|(a, b)| a.to_bits() == b.to_bits()));
        assert!(kin.x2(0, 0).iter().zip(first.x2(0, 0)).all(|(a, b)| a.to_bits() == b.to_bits()));
    }
}

#[test]
fn chain_follows_the_closed_form_through_a_revolution() {
    let theta0 = 0.2;
    let (mech, mut state) = chain(LOOPS, theta0);
    let steps = 72;
    let motion = Motion { steps, dt: 1.0, inputs: vec![InputMotion::Relative { delta: 2.0 * PI }] };
    let last = FormRef::Dependent(LOOPS - 1);
    let mut q = vec![Quantity::Input(0), Quantity::E0(last), Quantity::Ke1(last, 0), Quantity::Ke2(last, 0, 0)];
    q.push(Quantity::Det);
    let mut rec = Recorder::new(q, true);
    let report = run(&mech, &mut state, Some(&motion), &Params::default(), &mut rec).unwrap();
    assert!(report.stop.is_none(), "{:?}", report.stop);
    let n = mech.n_coords();
    for k in 0..=steps {
        let row = &rec.data()[k * 5..(k + 1) * 5];
        let theta = row[0];
        let (points, _) = exact(LOOPS, theta);
        let x = &rec.coords()[k * n..(k + 1) * n];
        for (l, p) in points.iter().enumerate() {
            for (i, v) in p.iter().enumerate() {
                // Moving co-ordinates follow the LOOPS + 1 fixed pivots (2 each).
                close("co-ordinate", x[2 * (LOOPS + 1) + 4 * l + i], *v, 1e-9);
            }
        }
        close("last rocker angle", row[1], last_rocker(theta, row[1]), 1e-9);
        // Central differences of the closed form.
        let h = 1e-4;
        let (gp, gm) = (last_rocker(theta + h, row[1]), last_rocker(theta - h, row[1]));
        close("last rocker angle'", row[2], (gp - gm) / (2.0 * h), 1e-6);
        close("last rocker angle''", row[3], (gp - 2.0 * row[1] + gm) / (h * h), 1e-4);
        assert!(row[4].is_finite() && row[4] != 0.0);
    }
}

/// Counts positions and keeps the last co-ordinates, reading positions only.
struct Positions(Vec<f64>, usize);

impl Observer for Positions {
    fn position(&mut self, view: &PositionView<'_>) {
        self.0.extend_from_slice(&view.state.x);
        self.1 += 1;
        assert!(view.kin.order().is_none() || view.index == 0);
    }
    fn transfer_order(&self) -> Option<TransferOrder> {
        None
    }
}

#[test]
fn positions_only_run_of_the_chain_reaches_the_same_positions() {
    let (mech, start) = chain(LOOPS, 0.2);
    let motion = Motion { steps: 500, dt: 1.0, inputs: vec![InputMotion::Relative { delta: 2.0 * PI }] };
    let mut full = Recorder::new(vec![Quantity::Ke2(FormRef::Dependent(0), 0, 0)], true);
    run(&mech, &mut start.clone(), Some(&motion), &Params::default(), &mut full).unwrap();
    let mut fast = Positions(Vec::new(), 0);
    let report = run(&mech, &mut start.clone(), Some(&motion), &Params::default(), &mut fast).unwrap();
    assert!(report.stop.is_none());
    assert_eq!(fast.1, 501);
    for (a, b) in fast.0.iter().zip(full.coords()) {
        assert!((a - b).abs() < 1e-9, "{a} vs {b}");
    }
}
