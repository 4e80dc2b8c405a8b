//! The design sensitivity of a transmission angle (BUFTRA) against
//! central differences of whole runs of the supply mechanism.

use mechfem_core::design::evaluate;
use mechfem_core::{DesignVar, Params, Quantity, State};

fn supply() -> mechfem_deck::Compiled {
    mechfem_deck::load(format!("{}/../../examples/supply/supply.mec", env!("CARGO_MANIFEST_DIR"))).unwrap()
}

/// mu between the coupler (element 2) and the rocker (element 3), and
/// between the arm (4) and the long link (5), at every position.
const Q: [Quantity; 2] = [Quantity::Transmission(1, 2), Quantity::Transmission(3, 4)];

fn at(c: &mechfem_deck::Compiled, vars: &[DesignVar], values: &[f64]) -> mechfem_core::design::DesignRun {
    let mut state: State = c.state.clone();
    for (v, x) in vars.iter().zip(values) {
        match *v {
            DesignVar::Row(r) => state.target[r] = *x,
            DesignVar::Fixed(i) => state.x[i] = *x,
        }
    }
    let params = Params { tol: 1e-13, ..Params::default() };
    evaluate(&c.mechanism, &mut state, c.motion.as_ref().unwrap(), &params, vars, &Q, &[]).unwrap()
}

#[test]
fn transmission_angle_sensitivities_against_central_differences() {
    let c = supply();
    // kappa, a coupler length, a frame pivot's x.
    let vars = [DesignVar::Row(4), DesignVar::Row(6), DesignVar::Fixed(4)];
    let x0: Vec<f64> = vec![-5.25, 0.71771, 1.04091];
    let base = at(&c, &vars, &x0);
    let mut largest = 0.0_f64;
    for (v, _) in vars.iter().enumerate() {
        let h = 1e-5 * x0[v].abs().max(1.0);
        let (mut plus, mut minus) = (x0.clone(), x0.clone());
        plus[v] += h;
        minus[v] -= h;
        let (p, m) = (at(&c, &vars, &plus), at(&c, &vars, &minus));
        for q in 0..base.values.len() {
            let fd = (p.values[q] - m.values[q]) / (2.0 * h);
            let g = base.gradient[q * vars.len() + v];
            largest = largest.max(g.abs());
            assert!((fd - g).abs() < 1e-6 * (1.0 + g.abs()), "{:?} at value {q}: {fd} vs {g}", vars[v]);
        }
    }
    assert!(largest > 0.1, "the angles do not depend on the design: {largest}");
}
