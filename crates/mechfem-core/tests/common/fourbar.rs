//! The crank-rocker four-bar with a coupler point that the tests and the
//! benches share: co-ordinates 1..4 fixed (A0, B0), 5..10 moving (A, B, C).
//! The coupler is a ternary-2 on A, B with C at local (u, v); the crank angle
//! is the input and the coupler angle a dependent form parameter.

use mechfem_core::{ElementType, Mechanism, MechanismBuilder, State, Term};

/// Crank A0A.
pub const A: f64 = 1.0;
/// Coupler AB.
pub const B: f64 = 3.0;
/// Rocker B0B.
pub const C: f64 = 2.5;
/// Frame A0B0.
pub const D: f64 = 3.2;
/// Coupler point: distance from A.
pub const P: f64 = 1.8;
/// Coupler point: angle from AB.
pub const ALPHA: f64 = 0.6;

/// The model with the moving co-ordinates at `estimates` (xA yA xB yB xC yC)
/// and every prescribed value set, the crank angle to `theta0`; not adjusted.
pub fn model(estimates: [f64; 6], theta0: f64) -> (Mechanism, State) {
    let mut b = MechanismBuilder::new();
    let f = [b.fixed(0.0), b.fixed(0.0), b.fixed(D), b.fixed(0.0)];
    let m: Vec<usize> = estimates.iter().map(|&v| b.moving(v)).collect();
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
    state.target.copy_from_slice(&[A, B, C, P * ALPHA.cos(), P * ALPHA.sin(), theta0]);
    (mech, state)
}
