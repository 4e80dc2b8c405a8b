//! A chain of crank-rocker four-bar loops, the large mechanism of the tests
//! and benches: the rocker of loop k carries the crank of loop k + 1, so one
//! input drives every loop. The pivots sit on the x axis, D apart; loop k
//! turns about O_k (crank) and O_{k+1} (rocker). Each loop has 4 moving
//! co-ordinates (its crank pin A_k and rocker pin B_k) and 4 rows of D^c, so
//! D^c is 4N x 4N and sparse: every row touches at most two loops.

use mechfem_core::{ElementType, Mechanism, MechanismBuilder, State, Term};

/// Crank, coupler, rocker and frame of every loop.
pub const A: f64 = 1.0;
pub const B: f64 = 3.0;
pub const C: f64 = 2.5;
pub const D: f64 = 3.2;
/// Angle of the next crank from the rocker's direction.
pub const PHI: f64 = -1.9;

/// The co-ordinates (A_k, B_k for every loop) and the rocker angles at
/// input angle `theta`, from the closed form of each loop (open branch).
pub fn exact(loops: usize, theta: f64) -> (Vec<[f64; 4]>, Vec<f64>) {
    let (mut points, mut rockers) = (Vec::with_capacity(loops), Vec::with_capacity(loops));
    let mut crank = theta;
    for k in 0..loops {
        let (ox, rx) = (D * k as f64, D * (k + 1) as f64);
        let a = [ox + A * crank.cos(), A * crank.sin()];
        let (ex, ey) = (rx - a[0], -a[1]);
        let e = ex.hypot(ey);
        let delta = ey.atan2(ex) + ((B * B + e * e - C * C) / (2.0 * B * e)).acos();
        let b = [a[0] + B * delta.cos(), a[1] + B * delta.sin()];
        let gamma = b[1].atan2(b[0] - rx);
        points.push([a[0], a[1], b[0], b[1]]);
        rockers.push(gamma);
        crank = gamma + PHI;
    }
    (points, rockers)
}

/// The chain at input angle `theta`, at its exact position, with the crank
/// angle as the input and every rocker angle as a dependent form parameter
/// (dependent k is the rocker of loop k).
pub fn chain(loops: usize, theta: f64) -> (Mechanism, State) {
    assert!(loops >= 1);
    let (points, _) = exact(loops, theta);
    let mut b = MechanismBuilder::new();
    let pivots: Vec<[usize; 2]> = (0..=loops).map(|k| [b.fixed(D * k as f64), b.fixed(0.0)]).collect();
    let pins: Vec<[usize; 4]> = points.iter().map(|p| p.map(|v| b.moving(v))).collect();
    let crank = b.element(ElementType::Bin, &[pivots[0][0], pivots[0][1], pins[0][0], pins[0][1]]);
    b.prescribe(&[Term::new(crank, 0)]);
    let mut rockers = Vec::with_capacity(loops);
    for k in 0..loops {
        let [ax, ay, bx, by] = pins[k];
        let coupler = b.element(ElementType::Bin, &[ax, ay, bx, by]);
        b.prescribe(&[Term::new(coupler, 0)]);
        let [ox, oy] = pivots[k + 1];
        if k + 1 < loops {
            // The rocker is a ternary-2 that carries the next crank pin.
            let next = pins[k + 1];
            let rocker = b.element(ElementType::Tr2, &[ox, oy, bx, by, next[0], next[1]]);
            for form in [0, 2, 3] {
                b.prescribe(&[Term::new(rocker, form)]);
            }
            rockers.push(rocker);
        } else {
            let rocker = b.element(ElementType::Bin, &[ox, oy, bx, by]);
            b.prescribe(&[Term::new(rocker, 0)]);
            rockers.push(rocker);
        }
    }
    b.input(&[Term::new(crank, 1)]);
    for &r in &rockers {
        b.dependent(&[Term::new(r, 1)]);
    }
    let (mech, mut state) = b.build().expect("the chain is a valid model");
    // Exact prescribed values: lengths, the next crank pin at (A cos PHI, A sin PHI)
    // in the rocker's frame, and the input.
    let mut r = 0;
    state.target[r] = A;
    r += 1;
    for k in 0..loops {
        state.target[r] = B;
        state.target[r + 1] = C;
        r += 2;
        if k + 1 < loops {
            state.target[r] = A * PHI.cos();
            state.target[r + 1] = A * PHI.sin();
            r += 2;
        }
    }
    state.target[r] = theta;
    (mech, state)
}
