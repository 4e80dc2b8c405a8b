//! Inverse dynamics checked against closed forms derived here by hand
//! (a pendulum, a slider-crank with masses, gravity and a gas force), the
//! energy balance of a four-bar with every kind of load, the stresses
//! against the virtual work of gravity (finite differences of V over the
//! prescribed values), and numbering independence.

use crate::common_dynamics as models;

use mechfem_core::dynamics::{Body, Dynamics};
use mechfem_core::{run, InputMotion, Motion, Params, Quantity, Recorder};
use models::{fourbar, run_dynamics, slider_crank, Fourbar, SliderCrank};
use std::f64::consts::PI;

const G: f64 = 9.81;

fn close(a: f64, b: f64, scale: f64, tol: f64) -> bool {
    (a - b).abs() <= tol * scale
}

/// A pendulum P -> Q of length l, its angle the input, swinging as
/// theta(t) = theta0 + a sin(w t): the drive torque is
/// `m l^2 theta'' + m g l cos(theta)`, the bar force
/// `sigma = -m l theta'^2 + m g sin(theta)` (positive pushing Q away from P)
/// and the frame's reaction at P is `m a_Q - m g`.
#[test]
fn pendulum_matches_its_closed_form() {
    let (l, m, theta0, amp, w): (f64, f64, f64, f64, f64) = (0.8, 2.5, -1.2, 0.9, 3.0);
    for on_body in [false, true] {
        let (mech, mut state, mut dynamics) = models::pendulum(l, theta0, m);
        let (xp, yp, bar) = (0, 1, 0);
        // The same mass as a point at Q, or as a body on the bar with its centre at Q.
        if on_body {
            dynamics.point_masses.clear();
            dynamics.bodies.push(Body { element: bar, mass: m, u: l, v: 0.0, inertia: 0.0 });
        }
        let steps = 200;
        let dt = 2.0 * PI / w / steps as f64;
        let rows = (0..=steps)
            .map(|k| {
                let t = k as f64 * dt;
                let (s, c) = (w * t).sin_cos();
                [t, theta0 + amp * s, amp * w * c, -amp * w * w * s]
            })
            .collect();
        let motion = Motion { steps, dt, inputs: vec![InputMotion::Table { rows }] };
        let q = vec![
            Quantity::Time,
            Quantity::Drive(0),
            Quantity::Sigma(0),
            Quantity::Reaction(xp),
            Quantity::Reaction(yp),
            Quantity::Mred(0, 0),
            Quantity::Ekin,
        ];
        let rec = run_dynamics(&mech, &mut state, &motion, dynamics, &q);
        let w_q = q.len();
        for row in rec.data().chunks(w_q) {
            let t = row[0];
            let (s, c) = (w * t).sin_cos();
            let (th, thd, thdd) = (theta0 + amp * s, amp * w * c, -amp * w * w * s);
            let tau = m * l * l * thdd + m * G * l * th.cos();
            let sigma = -m * l * thd * thd + m * G * th.sin();
            // For the body, the bar's length row carries nothing: the body hangs from P.
            let sigma = if on_body { 0.0 } else { sigma };
            let a_q = [-l * thdd * th.sin() - l * thd * thd * th.cos(), l * thdd * th.cos() - l * thd * thd * th.sin()];
            let scale = m * G * l + m * l * l * amp * w * w;
            assert!(close(row[1], tau, scale, 1e-10), "t {t}: drive {} vs {tau}", row[1]);
            assert!(close(row[2], sigma, scale / l, 1e-10), "t {t}: bar force {} vs {sigma}", row[2]);
            assert!(close(row[3], m * a_q[0], scale / l, 1e-10), "t {t}: reaction x {}", row[3]);
            assert!(close(row[4], m * a_q[1] + m * G, scale / l, 1e-10), "t {t}: reaction y {}", row[4]);
            assert!(close(row[5], m * l * l, m * l * l, 1e-10));
            assert!(close(row[6], 0.5 * m * l * l * thd * thd, scale, 1e-10));
        }
    }
}

/// A slider-crank at constant crank speed with a mass on crank and rod, a
/// slider mass, gravity and a gas force on the slider: the drive torque is
/// `w^2 sum(m c' . c'' + J phi' phi'') - sum(m g . c') - F s'`, and the
/// guide's normal force follows from the rod's moment balance about its
/// centre and the slider's balance.
#[test]
fn slider_crank_matches_its_closed_form() {
    let sc = SliderCrank::default();
    let (mech, mut state, dynamics) = slider_crank(&sc, 0.3);
    let steps = 360;
    let w = 12.0;
    let dt = 4.0 * PI / w / steps as f64;
    let motion = Motion { steps, dt, inputs: vec![InputMotion::Relative { delta: 4.0 * PI }] };
    let q = vec![
        Quantity::Input(0),
        Quantity::Drive(0),
        Quantity::Reaction(sc.yg),
        Quantity::Reaction(sc.x0),
        Quantity::Reaction(sc.y0),
        Quantity::Reaction(sc.xg),
        Quantity::Power,
    ];
    let rec = run_dynamics(&mech, &mut state, &motion, dynamics, &q);
    assert_eq!(rec.positions(), steps + 1);
    for row in rec.data().chunks(q.len()) {
        let e = sc.exact(row[0], w);
        let scale = e.tau_scale;
        assert!(close(row[1], e.tau, scale, 1e-9), "theta {}: drive {} vs {}", row[0], row[1], e.tau);
        assert!(close(row[2], e.normal, scale, 1e-9), "theta {}: normal {} vs {}", row[0], row[2], e.normal);
        assert!(close(row[3], e.r0[0], scale, 1e-9), "theta {}: A0 x {} vs {}", row[0], row[3], e.r0[0]);
        assert!(close(row[4], e.r0[1], scale, 1e-9), "theta {}: A0 y {} vs {}", row[0], row[4], e.r0[1]);
        assert!(row[5].abs() <= 1e-9 * scale, "the guide takes no force along itself");
        assert!(close(row[6], e.tau * w, scale * w, 1e-9));
    }
}

/// Along a motion with speed and acceleration changing, the drives' power
/// plus the power of the non-conservative loads equals d(T + V)/dt, the
/// rate taken by a central difference of order six in time.
#[test]
fn drive_power_balances_the_rate_of_energy() {
    let model = fourbar(&Fourbar::default());
    let (mech, mut state) = (&model.mech, model.state.clone());
    let steps = 8000;
    let dt = 2.5e-4;
    let (th0, w0, alpha) = (0.3, 4.0, 6.0);
    let rows = (0..=steps)
        .map(|k| {
            let t = k as f64 * dt;
            [t, th0 + w0 * t + 0.5 * alpha * t * t, w0 + alpha * t, alpha]
        })
        .collect();
    let motion = Motion { steps, dt, inputs: vec![InputMotion::Table { rows }] };
    let q = vec![Quantity::Ekin, Quantity::Epot, Quantity::Power, Quantity::Drive(0)];
    let mut rec = Recorder::new(q.clone(), false).with_dynamics(models::inverse(mech, model.dynamics.clone()));
    let report = run(mech, &mut state, Some(&motion), &Params::default(), &mut rec).unwrap();
    assert!(report.stop.is_none());
    let e: Vec<f64> = rec.data().chunks(4).map(|r| r[0] + r[1]).collect();
    let power: Vec<f64> = rec.data().chunks(4).map(|r| r[2]).collect();
    // The loads' power at each position, from a recorder that keeps it.
    let load_power = models::load_power(&model, &motion);
    let c = [-1.0 / 60.0, 3.0 / 20.0, -3.0 / 4.0, 0.0, 3.0 / 4.0, -3.0 / 20.0, 1.0 / 60.0];
    let scale = power.iter().zip(&load_power).fold(0.0f64, |m, (p, l)| m.max((p + l).abs()));
    assert!(scale > 1.0, "the test must exercise real power, got {scale}");
    for k in 3..steps - 3 {
        let rate: f64 = (0..7).map(|i| c[i] * e[k + i - 3]).sum::<f64>() / dt;
        let balance = power[k] + load_power[k];
        assert!(close(balance, rate, scale, 1e-9), "position {k}: {balance} vs d(T+V)/dt {rate}");
    }
}

/// In a static position (no motion), sigma_r = dV/d eps_r: the stress of
/// every prescribed row against central differences of the potential energy
/// of gravity and a spring over the row's prescribed value.
#[test]
fn static_stresses_are_the_derivatives_of_the_potential() {
    let model = fourbar(&Fourbar::default());
    let (mech, state) = (&model.mech, &model.state);
    let loads = models::conservative(&model.dynamics.loads);
    let statics = Dynamics { loads, forces: vec![], ..model.dynamics.clone() };
    let n = mech.n_prescribed();
    let mut q: Vec<Quantity> = (0..n).map(Quantity::Sigma).collect();
    q.push(Quantity::Epot);
    let eval = |target: &[f64]| {
        let mut s = state.clone();
        s.target.copy_from_slice(target);
        let mut rec = Recorder::new(q.clone(), false).with_dynamics(models::inverse(mech, statics.clone()));
        run(mech, &mut s, None, &Params { tol: 1e-14, ..Params::default() }, &mut rec).unwrap();
        rec.data().to_vec()
    };
    let base = eval(&state.target);
    let h = 1e-5;
    for r in 0..n {
        let (mut up, mut down) = (state.target.clone(), state.target.clone());
        up[r] += h;
        down[r] -= h;
        let dv = (eval(&up)[n] - eval(&down)[n]) / (2.0 * h);
        assert!(close(base[r], dv, base[r].abs().max(1.0), 1e-7), "row {r}: sigma {} vs dV/deps {dv}", base[r]);
    }
}

/// Numbering the co-ordinates and elements differently changes nothing
/// but the order of the results.
#[test]
fn results_do_not_depend_on_numbering() {
    let a = Fourbar::default();
    let b = Fourbar { permuted: true };
    let steps = 90;
    let motion = Motion { steps, dt: 0.01, inputs: vec![InputMotion::Relative { delta: 2.0 * PI }] };
    let results = [&a, &b].map(|fb| {
        let model = fourbar(fb);
        let mut q: Vec<Quantity> = model.fixed.into_iter().map(Quantity::Reaction).collect();
        q.extend([Quantity::Drive(0), Quantity::Ekin, Quantity::Epot, Quantity::Power, Quantity::Mred(0, 0)]);
        q.extend(model.rows.iter().map(|&r| Quantity::Sigma(r)));
        let mut state = model.state.clone();
        run_dynamics(&model.mech, &mut state, &motion, model.dynamics, &q).data().to_vec()
    });
    assert_eq!(results[0].len(), results[1].len());
    let scale = results[0].iter().fold(0.0f64, |m, v| m.max(v.abs()));
    for (x, y) in results[0].iter().zip(&results[1]) {
        assert!(close(*x, *y, scale, 1e-11), "{x} vs {y}");
    }
}
