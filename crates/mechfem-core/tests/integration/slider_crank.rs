//! An offset slider-crank, checked against its closed form over several crank
//! revolutions: positions, transfer functions of first and second order, the
//! connecting-rod angle as a dependent form parameter, timed motion with a
//! non-zero input acceleration, and the full inverse and second order of D^c.
//!
//! Crank A0A (length A) turns about the origin; connecting rod AB (length B);
//! slider B runs on the line y = E. The slider is a binary element from a
//! fixed guide point G = (-L, E) to B whose angle is held at 0 and whose
//! length is free.

use mechfem_core::{
    run, ElementType, FormRef, InputMotion, Kinematics, Mechanism, MechanismBuilder, Motion, Params, Quantity,
    Recorder, State, Term, TransferOrder,
};
use std::f64::consts::PI;

const A: f64 = 1.0; // crank A0A
const B: f64 = 3.5; // connecting rod AB
const E: f64 = 0.6; // offset of the slider line
const L: f64 = 10.0; // guide point G at (-L, E)

/// Co-ordinate indices: A0 and G fixed, A and B moving (columns 0..4 of D^c).
const XA: usize = 4;
const YA: usize = 5;
const XB: usize = 6;
const YB: usize = 7;

/// Closed form at crank angle theta. With u = E - A sin(theta) and
/// r = sqrt(B^2 - u^2), the slider is at s = A cos(theta) + r and the rod
/// angle is phi = atan2(u, r).
struct Exact {
    /// Crank point A and its first and second derivatives.
    a: [f64; 2],
    da: [f64; 2],
    dda: [f64; 2],
    /// Slider position s and its derivatives.
    s: f64,
    ds: f64,
    dds: f64,
    /// Connecting-rod angle and its derivatives.
    phi: f64,
    dphi: f64,
    ddphi: f64,
    /// u and r, for the partial derivatives with respect to the lengths.
    u: f64,
    r: f64,
}

fn exact(theta: f64) -> Exact {
    let (sin, cos) = theta.sin_cos();
    let u = E - A * sin;
    let du = -A * cos;
    let ddu = A * sin;
    let r = (B * B - u * u).sqrt();
    // r r' = -u u';  r' r' + r r'' = -u' u' - u u''
    let dr = -u * du / r;
    let ddr = (-du * du - u * ddu - dr * dr) / r;
    // tan(phi) = u / r, so phi' = (u' r - u r') / (u^2 + r^2) = (u' r - u r') / B^2
    let dphi = (du * r - u * dr) / (B * B);
    let ddphi = (ddu * r - u * ddr) / (B * B);
    Exact {
        a: [A * cos, A * sin],
        da: [-A * sin, A * cos],
        dda: [-A * cos, -A * sin],
        s: A * cos + r,
        ds: -A * sin + dr,
        dds: -A * cos + ddr,
        phi: u.atan2(r),
        dphi,
        ddphi,
        u,
        r,
    }
}

/// Prescribed rows: 0 crank length, 1 rod length, 2 guide angle, 3 crank
/// angle (the input). Dependent: 0 rod angle, 1 guide length.
fn model(theta0: f64, rough: f64) -> (Mechanism, State) {
    let e = exact(theta0);
    let mut b = MechanismBuilder::new();
    let f = [b.fixed(0.0), b.fixed(0.0), b.fixed(-L), b.fixed(E)];
    let m: Vec<usize> = [e.a[0], e.a[1], e.s, E].iter().map(|&v| b.moving(v + rough)).collect();
    let crank = b.element(ElementType::Bin, &[f[0], f[1], m[0], m[1]]);
    let rod = b.element(ElementType::Bin, &[m[0], m[1], m[2], m[3]]);
    let guide = b.element(ElementType::Bin, &[f[2], f[3], m[2], m[3]]);
    b.prescribe(&[Term::new(crank, 0)]);
    b.prescribe(&[Term::new(rod, 0)]);
    b.prescribe(&[Term::new(guide, 1)]);
    b.input(&[Term::new(crank, 1)]);
    b.dependent(&[Term::new(rod, 1)]);
    b.dependent(&[Term::new(guide, 0)]);
    let (mech, mut state) = b.build().unwrap();
    assert_eq!((mech.n_moving(), mech.n_dof()), (4, 1));
    state.target.copy_from_slice(&[A, B, 0.0, theta0]);
    (mech, state)
}

fn close(what: &str, k: usize, got: f64, want: f64, tol: f64) {
    assert!((got - want).abs() <= tol * (1.0 + want.abs()), "{what} at position {k}: got {got}, closed form {want}");
}

/// Every recorded quantity with its closed form at crank angle theta, for
/// input velocity `w` and acceleration `alpha`.
fn expected(theta: f64, w: f64, alpha: f64) -> Vec<(Quantity, f64, &'static str)> {
    let e = exact(theta);
    let rod = FormRef::Dependent(0);
    let guide = FormRef::Dependent(1);
    // eq. 5.29 and 5.30 for one input: v = x' w, a = x'' w^2 + x' alpha.
    let vel = |d1: f64| d1 * w;
    let acc = |d1: f64, d2: f64| d2 * w * w + d1 * alpha;
    let mut q = vec![(Quantity::Input(0), theta, "input")];
    for (i, x, d1, d2) in
        [(XA, e.a[0], e.da[0], e.dda[0]), (YA, e.a[1], e.da[1], e.dda[1]), (XB, e.s, e.ds, e.dds), (YB, E, 0.0, 0.0)]
    {
        q.push((Quantity::X0(i), x, "x"));
        q.push((Quantity::Kx1 { coord: i, j: 0 }, d1, "x'"));
        q.push((Quantity::Kx2 { coord: i, j: 0, m: 0 }, d2, "x''"));
        q.push((Quantity::Vx(i), vel(d1), "velocity"));
        q.push((Quantity::Ax(i), acc(d1, d2), "acceleration"));
    }
    for (f, v, d1, d2) in [(rod, e.phi, e.dphi, e.ddphi), (guide, e.s + L, e.ds, e.dds)] {
        q.push((Quantity::E0(f), v, "form parameter"));
        q.push((Quantity::Ke1(f, 0), d1, "form parameter'"));
        q.push((Quantity::Ke2(f, 0, 0), d2, "form parameter''"));
        q.push((Quantity::Ve(f), vel(d1), "form parameter velocity"));
        q.push((Quantity::Ae(f), acc(d1, d2), "form parameter acceleration"));
    }
    // The guide angle stays at 0; the crank angle is the input itself.
    q.push((Quantity::E0(FormRef::Prescribed(2)), 0.0, "guide angle"));
    q.push((Quantity::E0(FormRef::Prescribed(3)), theta, "crank angle"));
    q.push((Quantity::Ve(FormRef::Prescribed(3)), w, "crank velocity"));
    q.push((Quantity::Ae(FormRef::Prescribed(3)), alpha, "crank acceleration"));
    // det D^c: rows (crank length, crank angle) involve A only, rows (rod
    // length, guide angle) close the block of B, so by eq. 5.39
    // det = (1/A) * (cos(phi) / |GB|); moving the input row from last to
    // second place takes two row swaps, which leaves the sign.
    q.push((Quantity::Det, e.phi.cos() / (A * (e.s + L)), "det D^c"));
    q
}

/// Runs `motion` and compares every position with the closed form;
/// `input` gives theta, theta_dot and theta_ddot at position k.
fn check_run(theta0: f64, rough: f64, motion: &Motion, input: impl Fn(usize) -> [f64; 3]) {
    let (mech, mut state) = model(theta0, rough);
    let quantities: Vec<Quantity> = expected(theta0, 0.0, 0.0).iter().map(|q| q.0).collect();
    let mut rec = Recorder::new(quantities, false);
    let report = run(&mech, &mut state, Some(motion), &Params::default(), &mut rec).unwrap();
    assert!(report.stop.is_none(), "{:?}", report.stop);
    assert_eq!(rec.positions(), motion.steps + 1);
    let w = rec.quantities().len();
    for k in 0..=motion.steps {
        let [theta, omega, alpha] = input(k);
        let row = &rec.data()[k * w..(k + 1) * w];
        for (c, (q, want, what)) in expected(theta, omega, alpha).into_iter().enumerate() {
            assert_eq!(rec.quantities()[c], q);
            close(what, k, row[c], want, 1e-9);
        }
    }
}

#[test]
fn slider_crank_matches_closed_form_over_three_revolutions() {
    let (theta0, steps, turns, omega) = (0.4, 3 * 72, 3.0, 2.0);
    let dt = turns * 2.0 * PI / steps as f64 / omega;
    let motion = Motion { steps, dt, inputs: vec![InputMotion::Relative { delta: turns * 2.0 * PI }] };
    check_run(theta0, 0.0, &motion, |k| [theta0 + turns * 2.0 * PI * k as f64 / steps as f64, omega, 0.0]);
}

#[test]
fn slider_crank_turning_backwards_from_a_rough_start_matches_closed_form() {
    let (theta0, steps, turns) = (-2.0, 2 * 48, -2.0);
    let motion = Motion { steps, dt: 0.01, inputs: vec![InputMotion::Relative { delta: turns * 2.0 * PI }] };
    let omega = turns * 2.0 * PI / (steps as f64 * 0.01);
    check_run(theta0, 0.05, &motion, |k| [theta0 + turns * 2.0 * PI * k as f64 / steps as f64, omega, 0.0]);
}

#[test]
fn accelerating_crank_gives_closed_form_velocities_and_accelerations() {
    // theta(t) = theta0 + w t + alpha t^2 / 2 over about 3.3 revolutions.
    let (theta0, w, alpha) = (0.1, 2.0, 0.5);
    let (steps, dt) = (300, 0.02);
    let at = |k: usize| {
        let t = k as f64 * dt;
        [theta0 + w * t + 0.5 * alpha * t * t, w + alpha * t, alpha]
    };
    let rows = (0..=steps).map(|k| [k as f64 * dt, at(k)[0], at(k)[1], at(k)[2]]).collect();
    let motion = Motion { steps, dt, inputs: vec![InputMotion::Table { rows }] };
    check_run(theta0, 0.0, &motion, at);
    assert!(at(steps)[0] - theta0 > 3.0 * 2.0 * PI);
}

/// The full inverse (eq. 5.16a) holds the derivatives with respect to every
/// prescribed form parameter, also the constant ones: here the crank length
/// and the rod length. With u = E - A sin(theta), r = sqrt(B^2 - u^2) and
/// s = A cos(theta) + r:
/// ds/dA = cos + u sin / r, ds/dB = B / r, ds/dtheta = -A sin + A u cos / r,
/// d2s/dA2 = -B^2 sin^2 / r^3, d2s/dB2 = -u^2 / r^3, d2s/dA dB = -B u sin / r^3,
/// d2s/dB dtheta = -A B u cos / r^3, d2s/dA dtheta = -sin - B^2 A sin cos / r^3 + u cos / r.
#[test]
fn full_inverse_and_second_order_match_partial_derivatives_in_the_lengths() {
    for theta in [0.3, 1.7, 2.9, 4.4, 5.8] {
        let (mech, mut state) = model(theta, 0.01);
        let mut kin = Kinematics::new(&mech);
        mechfem_core::adjust(&mech, &mut state, &mut kin, &Params::default()).unwrap();
        kin.transfer(&mech, &mut state, TransferOrder::Second).unwrap();
        let n = mech.n_moving();
        let mut f = vec![0.0; n * n];
        let mut f2 = vec![0.0; n * n * n];
        kin.inverse(&mut f).unwrap();
        kin.second_order_all(&mech, &f, &mut f2).unwrap();
        let e = exact(theta);
        let (sn, cs, u, r) = (theta.sin(), theta.cos(), e.u, e.r);
        let r3 = r * r * r;
        // Rows 0 (A), 1 (B), 3 (theta); column 2 of D^c is x_B, column 0 is x_A.
        let (ra, rb, rt, xa, xb) = (0, 1, 3, 0, 2);
        let first = [
            (ra, xb, cs + u * sn / r),
            (rb, xb, B / r),
            (rt, xb, e.ds),
            (ra, xa, cs),
            (rb, xa, 0.0),
            (rt, xa, e.da[0]),
            (ra, 1, sn),
            (rt, 1, e.da[1]),
        ];
        for (k, col, want) in first {
            close("d x / d eps", k, f[k * n + col], want, 1e-9);
        }
        let second = [
            (ra, ra, xb, -B * B * sn * sn / r3),
            (rb, rb, xb, -u * u / r3),
            (ra, rb, xb, -B * u * sn / r3),
            (rb, rt, xb, -A * B * u * cs / r3),
            (ra, rt, xb, -sn - B * B * A * sn * cs / r3 + u * cs / r),
            (rt, rt, xb, e.dds),
            (ra, rt, xa, -sn),
            (ra, ra, xa, 0.0),
            (rt, rt, 1, e.dda[1]),
        ];
        for (k, l, col, want) in second {
            close("d2 x / d eps_k d eps_l", k, f2[(k * n + l) * n + col], want, 1e-9);
            close("d2 x / d eps_l d eps_k", l, f2[(l * n + k) * n + col], want, 1e-9);
        }
        // The input's column of the inverse is the first-order transfer function.
        for col in 0..n {
            assert_eq!(f[rt * n + col], kin.x1(0)[col]);
        }
    }
}
