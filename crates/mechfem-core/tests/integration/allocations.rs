//! A run allocates its workspace once: the number of heap allocations does
//! not grow with the number of positions, whatever the run computes at each
//! one and however D^c is stored. Counted by `allocation_counter`, whose
//! global allocator counts the allocations of the measuring thread (a count,
//! not a timing).

use crate::common_chain as chain;

use mechfem_core::{
    run, ElementType, InputMotion, Mechanism, MechanismBuilder, Motion, Observer, Params, PositionView, State, Term,
    TransferOrder,
};
use std::f64::consts::PI;

/// Reads what a run computed at every position without allocating.
struct Touch(f64, Option<TransferOrder>);

impl Observer for Touch {
    fn position(&mut self, view: &PositionView<'_>) {
        self.0 += view.state.x[4] + view.kin.det().abs().min(1.0);
    }
    fn transfer_order(&self) -> Option<TransferOrder> {
        self.1
    }
}

fn fourbar() -> (Mechanism, State) {
    let mut b = MechanismBuilder::new();
    let f = [b.fixed(0.0), b.fixed(0.0), b.fixed(3.2), b.fixed(0.0)];
    let m: Vec<usize> = [1.0, 0.0, 2.7, 2.5, 1.0, 1.8].iter().map(|&v| b.moving(v)).collect();
    let crank = b.element(ElementType::Bin, &[f[0], f[1], m[0], m[1]]);
    let coupler = b.element(ElementType::Tr2, &[m[0], m[1], m[2], m[3], m[4], m[5]]);
    let rocker = b.element(ElementType::Bin, &[f[2], f[3], m[2], m[3]]);
    for t in [Term::new(crank, 0), Term::new(coupler, 0), Term::new(rocker, 0)] {
        b.prescribe(&[t]);
    }
    b.prescribe(&[Term::new(coupler, 2)]);
    b.prescribe(&[Term::new(coupler, 3)]);
    b.input(&[Term::new(crank, 1)]);
    b.dependent(&[Term::new(coupler, 1)]);
    let (mech, mut state) = b.build().unwrap();
    state.target.copy_from_slice(&[1.0, 3.0, 2.5, 1.8 * 0.6f64.cos(), 1.8 * 0.6f64.sin(), 0.0]);
    (mech, state)
}

/// Allocations of a run of `steps` steps (one crank revolution; 900 steps
/// move the window of input values of `motion/schedule.rs` on three times).
fn count(mech: &Mechanism, start: &State, steps: usize, order: Option<TransferOrder>) -> usize {
    let motion = Motion { steps, dt: 0.01, inputs: vec![InputMotion::Relative { delta: 2.0 * PI }] };
    let mut state = start.clone();
    let mut touch = Touch(0.0, order);
    let mut report = None;
    let info = allocation_counter::measure(|| {
        report = Some(run(mech, &mut state, Some(&motion), &Params::default(), &mut touch).unwrap());
    });
    let report = report.unwrap();
    assert!(report.stop.is_none() && report.positions == steps + 1);
    assert!(touch.0.is_finite());
    info.count_total as usize
}

#[test]
fn allocations_do_not_grow_with_the_number_of_positions() {
    let small = chain::chain(2, 0.3);
    let blocks = chain::chain(40, 0.3);
    for (name, (mech, start)) in [("four-bar", fourbar()), ("chain of 2", small), ("chain of 40 (in blocks)", blocks)] {
        // The first workspace of a mechanism also makes its plan of D^c's
        // storage, which the later ones clone.
        let first = count(&mech, &start, 90, None);
        for order in [None, Some(TransferOrder::First), Some(TransferOrder::Second)] {
            let few = count(&mech, &start, 90, order);
            let many = count(&mech, &start, 900, order);
            // The workspace itself is allocated: the counter is live.
            assert!(few > 0, "no allocation counted at all");
            assert_eq!(few, many, "{name}, {order:?}: {few} allocations for 90 steps, {many} for 900");
            assert!(order.is_some() || few < first, "{name}: the plan was made again ({few} against {first})");
        }
    }
}

/// Allocations of a simulation of the four-bar swinging from rest with its
/// coupler as a body, 50 outputs, at tolerance `tol`.
fn count_simulation(tol: f64) -> (usize, usize) {
    use mechfem_core::dynamics::{Body, Dynamics, Integration};
    use mechfem_core::run::simulate;
    let (mech, state) = fourbar();
    let dynamics = Dynamics {
        bodies: vec![Body { element: 1, mass: 2.0, u: 1.0, v: 0.5, inertia: 0.2 }],
        gravity: [0.0, -9.81],
        ..Dynamics::default()
    };
    let motion = Motion { steps: 50, dt: 0.02, inputs: vec![InputMotion::Dynamic { v0: 0.0 }] };
    let (mut s, mut touch) = (state.clone(), Touch(0.0, Some(TransferOrder::Second)));
    let integration = Integration::new(tol, tol);
    let mut steps = 0;
    let info = allocation_counter::measure(|| {
        let report = simulate(&mech, &mut s, &motion, &Params::default(), &integration, &dynamics, &mut touch).unwrap();
        assert!(report.run.stop.is_none());
        steps = report.steps;
    });
    (info.count_total as usize, steps)
}

#[test]
fn a_simulation_allocates_nothing_per_step() {
    // The first workspace of the four-bar on this thread chooses D^c's
    // storage, which the later ones clone.
    count_simulation(1e-6);
    let (coarse, few_steps) = count_simulation(1e-6);
    let (fine, many_steps) = count_simulation(1e-11);
    assert!(many_steps > 3 * few_steps, "{few_steps} and {many_steps} steps");
    assert_eq!(coarse, fine, "{coarse} allocations for {few_steps} steps, {fine} for {many_steps}");
}

/// Computes every design sensitivity at every position.
struct Sensitive(mechfem_core::Sensitivity, f64);

impl Observer for Sensitive {
    fn position(&mut self, view: &PositionView<'_>) {
        self.0.compute(view.mech, view.kin, view.state, TransferOrder::Second).unwrap();
        self.1 += self.0.dx2(4, 0, 0, 0) + self.0.dep2(0, 0, 0, 6);
    }
}

#[test]
fn design_sensitivities_allocate_nothing_per_position() {
    use mechfem_core::{DesignVar, Sensitivity};
    let (mech, start) = fourbar();
    let vars: Vec<DesignVar> = (0..mech.n_prescribed()).map(DesignVar::Row).chain([DesignVar::Fixed(2)]).collect();
    let count = |steps: usize| {
        let motion = Motion { steps, dt: 0.01, inputs: vec![InputMotion::Relative { delta: 2.0 * PI }] };
        let mut obs = Sensitive(Sensitivity::new(&mech, &vars).unwrap(), 0.0);
        let mut state = start.clone();
        let info = allocation_counter::measure(|| {
            run(&mech, &mut state, Some(&motion), &Params::default(), &mut obs).unwrap();
        });
        assert!(obs.1.is_finite());
        info.count_total
    };
    // The first run chooses D^c's storage for the model, once.
    count(10);
    assert_eq!(count(100), count(900), "allocations grew with the positions");
}
