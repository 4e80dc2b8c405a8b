//! Balancing a slider-crank with exact gradients: the centre of mass of the
//! crank (with its counterweight, its mass fixed) that makes the RMS
//! shaking force over a turn smallest, found by Gauss-Newton on the shaking
//! force at every position with the design sensitivities of inverse
//! dynamics (`mechfem_core::dynamic_design`).
//!
//! The shaking force is linear in the centre (u, v), so Gauss-Newton lands
//! on the optimum in one step; the second confirms it. The closed form it
//! is checked against (docs/optimisation.md, "Balancing"): with the rod
//! split into its equivalent masses at the crank pin A and the piston B,
//! the optimum puts the crank's first moment opposite the pin,
//! `m1 u1 = -r (m_A + m_rec / 2)`, `v1 = 0`: the rotating mass fully
//! balanced and half the reciprocating mass's primary force.
//!
//! Run: `cargo run -p mechfem-core --example balancing`.

use mechfem_core::dynamic_design::evaluate;
use mechfem_core::dynamics::{Component, MassVar};
use mechfem_core::{DesignVar, Quantity};
use nalgebra::{DMatrix, DVector};

/// The deck of the example.
pub fn deck() -> mechfem_deck::Compiled {
    let path = format!("{}/../../examples/balancing/slider_crank_dyn.mec", env!("CARGO_MANIFEST_DIR"));
    mechfem_deck::load(path).expect("the example deck compiles")
}

/// The result of balancing: the centre (u, v) at each iterate and the RMS
/// shaking force there.
pub struct Balanced {
    /// (u, v, RMS shaking force) of the start and every iterate.
    pub history: Vec<(f64, f64, f64)>,
}

/// The RMS shaking force over the deck's positions at the crank's centre
/// `(u, v)`, its gradient's Gauss-Newton step, from one run.
fn step(c: &mechfem_deck::Compiled, u: f64, v: f64) -> (f64, [f64; 2]) {
    let mut dynamics = c.dynamics.clone().expect("a DYN ANA deck");
    let vars = [MassVar::CentreU(0), MassVar::CentreV(0)];
    vars[0].set(&mut dynamics, u);
    vars[1].set(&mut dynamics, v);
    let q = [Quantity::Shaking(Component::X), Quantity::Shaking(Component::Y)];
    let mut state = c.state.clone();
    let motion = c.motion.as_ref().expect("a motion");
    let none: [DesignVar; 0] = [];
    let run = evaluate(&c.mechanism, &mut state, motion, &c.params, &dynamics, &none, &vars, &q).expect("runs");
    // Residuals: both components at every position; Jacobian from the sensitivities.
    let n = run.positions * 2;
    let r = DVector::from_column_slice(&run.values);
    let j = DMatrix::from_row_slice(n, 2, &run.gradient);
    let rms = (r.norm_squared() / run.positions as f64).sqrt();
    let normal = j.transpose() * &j;
    let dx = normal.lu().solve(&(-(j.transpose() * r))).expect("the shaking force depends on the centre");
    (rms, [dx[0], dx[1]])
}

/// Gauss-Newton from the deck's centre of the crank's mass.
pub fn balance(c: &mechfem_deck::Compiled, iterations: usize) -> Balanced {
    let body = c.dynamics.as_ref().expect("a DYN ANA deck").bodies[0];
    let (mut u, mut v) = (body.u, body.v);
    let mut history = Vec::new();
    for _ in 0..iterations {
        let (rms, dx) = step(c, u, v);
        history.push((u, v, rms));
        u += dx[0];
        v += dx[1];
    }
    history.push((u, v, step(c, u, v).0));
    Balanced { history }
}

#[allow(dead_code)] // the test includes this file for `balance`
fn main() {
    let c = deck();
    let b = balance(&c, 2);
    println!("iterate  u (m)         v (m)         RMS shaking force (N)");
    for (k, (u, v, rms)) in b.history.iter().enumerate() {
        println!("{k:7}  {u:12.9}  {v:12.9}  {rms:12.6}");
    }
}
