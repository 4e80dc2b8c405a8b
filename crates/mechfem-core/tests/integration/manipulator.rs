//! The two-DOF manipulator of theory fig. 5.3.5: a point M joined to the fixed
//! points P1 and P2 by two binary elements whose lengths l1, l2 are both
//! inputs. Checked against the closed form of the intersection of two
//! circles: positions, every first and second derivative (the mixed one in
//! both orders), timed motion with two simultaneous inputs, and the full
//! inverse and second order of D^c.

use mechfem_core::{
    adjust, run, ElementType, InputMotion, Kinematics, Mechanism, MechanismBuilder, Motion, Params, Quantity, Recorder,
    State, Term, TransferOrder,
};

const P1: [f64; 2] = [0.0, 0.0];
const P2: [f64; 2] = [4.0, 0.5];

/// Co-ordinates of M (columns 0 and 1 of D^c).
const XM: usize = 4;
const YM: usize = 5;

/// Closed form for M at input lengths l = (l1, l2), on the side `side` (+1:
/// left of P1->P2, -1: right).
///
/// With d = |P1P2|, unit vectors e along P1->P2 and n = e turned by +90 deg,
/// M = P1 + xi e + eta n, where xi = (l1^2 - l2^2 + d^2) / (2 d) and
/// eta = side * sqrt(l1^2 - xi^2). The derivatives follow from
/// xi_1 = l1/d, xi_2 = -l2/d, xi_11 = 1/d, xi_22 = -1/d, xi_12 = 0 and from
/// differentiating eta^2 = l1^2 - xi^2 once and twice.
struct Exact {
    m: [f64; 2],
    /// dm[j][axis] = d M_axis / d l_j.
    dm: [[f64; 2]; 2],
    /// ddm[j][k][axis] = d2 M_axis / d l_j d l_k.
    ddm: [[[f64; 2]; 2]; 2],
}

fn exact(l: [f64; 2], side: f64) -> Exact {
    let (dx, dy) = (P2[0] - P1[0], P2[1] - P1[1]);
    let d = dx.hypot(dy);
    let e = [dx / d, dy / d];
    let n = [-e[1], e[0]];
    let xi = (l[0] * l[0] - l[1] * l[1] + d * d) / (2.0 * d);
    let dxi = [l[0] / d, -l[1] / d];
    let ddxi = [[1.0 / d, 0.0], [0.0, -1.0 / d]];
    let eta = side * (l[0] * l[0] - xi * xi).sqrt();
    // eta eta_j = l1 delta_j0 - xi xi_j
    let delta = |j: usize, k: usize| f64::from(u8::from(j == k));
    let deta: [f64; 2] = std::array::from_fn(|j| (l[0] * delta(j, 0) - xi * dxi[j]) / eta);
    // eta_k eta_j + eta eta_jk = delta_j0 delta_k0 - xi_k xi_j - xi xi_jk
    let ddeta: [[f64; 2]; 2] = std::array::from_fn(|j| {
        std::array::from_fn(|k| {
            (delta(j, 0) * delta(k, 0) - dxi[j] * dxi[k] - xi * ddxi[j][k] - deta[j] * deta[k]) / eta
        })
    });
    let at = |a: f64, b: f64| [a * e[0] + b * n[0], a * e[1] + b * n[1]];
    let m0 = at(xi, eta);
    Exact {
        m: [P1[0] + m0[0], P1[1] + m0[1]],
        dm: std::array::from_fn(|j| at(dxi[j], deta[j])),
        ddm: std::array::from_fn(|j| std::array::from_fn(|k| at(ddxi[j][k], ddeta[j][k]))),
    }
}

/// Inputs: 0 the length P1-M, 1 the length P2-M. No constant rows.
fn model(l: [f64; 2], side: f64, rough: f64) -> (Mechanism, State) {
    let e = exact(l, side);
    let mut b = MechanismBuilder::new();
    let f = [b.fixed(P1[0]), b.fixed(P1[1]), b.fixed(P2[0]), b.fixed(P2[1])];
    let (xm, ym) = (b.moving(e.m[0] + rough), b.moving(e.m[1] - rough));
    assert_eq!((xm, ym), (XM, YM));
    let bar1 = b.element(ElementType::Bin, &[f[0], f[1], xm, ym]);
    let bar2 = b.element(ElementType::Bin, &[f[2], f[3], xm, ym]);
    b.input(&[Term::new(bar1, 0)]);
    b.input(&[Term::new(bar2, 0)]);
    let (mech, mut state) = b.build().unwrap();
    assert_eq!((mech.n_moving(), mech.n_dof(), mech.n_prescribed()), (2, 2, 2));
    state.target.copy_from_slice(&l);
    (mech, state)
}

fn close(what: &str, k: usize, got: f64, want: f64, tol: f64) {
    assert!((got - want).abs() <= tol * (1.0 + want.abs()), "{what} at position {k}: got {got}, closed form {want}");
}

/// Every recorded quantity with its closed form at input lengths `l`,
/// input velocities `v` and input accelerations `a`.
fn expected(l: [f64; 2], side: f64, v: [f64; 2], a: [f64; 2]) -> Vec<(Quantity, f64, &'static str)> {
    let e = exact(l, side);
    let mut q = vec![(Quantity::Input(0), l[0], "input 0"), (Quantity::Input(1), l[1], "input 1")];
    for (axis, coord) in [XM, YM].into_iter().enumerate() {
        q.push((Quantity::X0(coord), e.m[axis], "x"));
        for j in 0..2 {
            q.push((Quantity::Kx1 { coord, j }, e.dm[j][axis], "dx/dl_j"));
            for m in 0..2 {
                q.push((Quantity::Kx2 { coord, j, m }, e.ddm[j][m][axis], "d2x/dl_j dl_m"));
            }
        }
        // eq. 5.29 and eq. 5.30 written out for two inputs.
        let vel = (0..2).map(|j| e.dm[j][axis] * v[j]).sum();
        let mut acc = 0.0;
        for j in 0..2 {
            acc += e.dm[j][axis] * a[j];
            for m in 0..2 {
                acc += e.ddm[j][m][axis] * v[j] * v[m];
            }
        }
        q.push((Quantity::Vx(coord), vel, "velocity"));
        q.push((Quantity::Ax(coord), acc, "acceleration"));
    }
    q
}

/// Runs `motion` and compares every position with the closed form; `input`
/// gives the input values, velocities and accelerations at position k.
fn check_run(l0: [f64; 2], side: f64, rough: f64, motion: &Motion, input: impl Fn(usize) -> [[f64; 2]; 3]) {
    let (mech, mut state) = model(l0, side, rough);
    let quantities = expected(l0, side, [0.0; 2], [0.0; 2]).iter().map(|q| q.0).collect();
    let mut rec = Recorder::new(quantities, false);
    let report = run(&mech, &mut state, Some(motion), &Params::default(), &mut rec).unwrap();
    assert!(report.stop.is_none(), "{:?}", report.stop);
    assert_eq!(rec.positions(), motion.steps + 1);
    let w = rec.quantities().len();
    for k in 0..=motion.steps {
        let [l, v, a] = input(k);
        let row = &rec.data()[k * w..(k + 1) * w];
        for (c, (q, want, what)) in expected(l, side, v, a).into_iter().enumerate() {
            assert_eq!(rec.quantities()[c], q);
            close(what, k, row[c], want, 1e-9);
        }
    }
}

#[test]
fn transfer_functions_of_both_inputs_match_closed_form() {
    let (l0, delta, steps, dt) = ([3.0, 3.4], [0.8, -0.9], 40, 0.05);
    for (side, rough) in [(1.0, 0.0), (-1.0, 0.2)] {
        let inputs = delta.iter().map(|&d| InputMotion::Relative { delta: d }).collect();
        let motion = Motion { steps, dt, inputs };
        let v = [delta[0] / (steps as f64 * dt), delta[1] / (steps as f64 * dt)];
        check_run(l0, side, rough, &motion, |k| {
            let f = k as f64 / steps as f64;
            [[l0[0] + f * delta[0], l0[1] + f * delta[1]], v, [0.0; 2]]
        });
    }
}

#[test]
fn two_simultaneous_input_motions_give_closed_form_velocities_and_accelerations() {
    // Input 0 moves at constant speed (Relative); input 1 follows a table
    // l2(t) = 3.2 + 0.5 sin(3 t), so both its velocity and acceleration vary.
    let (steps, dt) = (120, 0.025);
    let (l1_0, dl1) = (2.8, 1.1);
    let l2 = |t: f64| [3.2 + 0.5 * (3.0 * t).sin(), 1.5 * (3.0 * t).cos(), -4.5 * (3.0 * t).sin()];
    let rows = (0..=steps)
        .map(|k| {
            let t = k as f64 * dt;
            let [v, vd, vdd] = l2(t);
            [t, v, vd, vdd]
        })
        .collect();
    let motion = Motion { steps, dt, inputs: vec![InputMotion::Relative { delta: dl1 }, InputMotion::Table { rows }] };
    let v1 = dl1 / (steps as f64 * dt);
    check_run([l1_0, l2(0.0)[0]], 1.0, 0.0, &motion, |k| {
        let t = k as f64 * dt;
        let [v, vd, vdd] = l2(t);
        [[l1_0 + dl1 * k as f64 / steps as f64, v], [v1, vd], [0.0, vdd]]
    });
}

/// Every prescribed form parameter is an input here, so the full inverse is
/// the first-order transfer function (section 5.3.3) and eq. 5.28 gives
/// every second derivative.
#[test]
fn full_inverse_and_second_order_all_match_closed_form() {
    for (l, side) in [([3.0, 3.4], 1.0), ([2.5, 2.2], 1.0), ([3.7, 2.6], -1.0), ([1.5, 3.0], -1.0)] {
        let (mech, mut state) = model(l, side, 0.1);
        let mut kin = Kinematics::new(&mech);
        let mut f = vec![0.0; 4];
        let mut f2 = vec![0.0; 8];
        assert!(kin.inverse(&mut f).is_err(), "no transfer functions yet");
        adjust(&mech, &mut state, &mut kin, &Params::default()).unwrap();
        kin.transfer(&mech, &mut state, TransferOrder::First).unwrap();
        kin.inverse(&mut f).unwrap();
        assert!(kin.second_order_all(&mech, &f, &mut f2).is_err(), "second order not computed yet");
        kin.transfer(&mech, &mut state, TransferOrder::Second).unwrap();
        kin.second_order_all(&mech, &f, &mut f2).unwrap();
        let e = exact(l, side);
        for axis in 0..2 {
            close("x", 0, state.x[XM + axis], e.m[axis], 1e-10);
            for k in 0..2 {
                close("F^cp", k, f[k * 2 + axis], e.dm[k][axis], 1e-9);
                close("transfer x'", k, kin.x1(k)[axis], e.dm[k][axis], 1e-9);
                for m in 0..2 {
                    close("F_{c,kl}", k, f2[(k * 2 + m) * 2 + axis], e.ddm[k][m][axis], 1e-9);
                    close("transfer x''", k, kin.x2(k, m)[axis], e.ddm[k][m][axis], 1e-9);
                }
            }
        }
    }
}

/// The closed form itself, against central differences, so that a slip in
/// it cannot hide behind an equal slip in the solver.
#[test]
fn closed_form_derivatives_match_central_differences() {
    let h = 1e-5;
    for (l, side) in [([3.0, 3.4], 1.0), ([3.7, 2.6], -1.0)] {
        let e = exact(l, side);
        for j in 0..2 {
            let shifted = |s: f64| {
                let mut p = l;
                p[j] += s;
                exact(p, side)
            };
            let (plus, minus) = (shifted(h), shifted(-h));
            for axis in 0..2 {
                close("fd first", j, (plus.m[axis] - minus.m[axis]) / (2.0 * h), e.dm[j][axis], 1e-8);
                for m in 0..2 {
                    let fd = (plus.dm[m][axis] - minus.dm[m][axis]) / (2.0 * h);
                    close("fd second", j, fd, e.ddm[j][m][axis], 1e-8);
                }
            }
        }
    }
}
