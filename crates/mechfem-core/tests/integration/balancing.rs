//! The balancing example (examples/balancing.rs) against its closed form:
//! the RMS shaking force of a centred slider-crank over a turn at constant
//! speed is smallest where the crank's first moment balances the rotating
//! mass and half the reciprocating one, `m1 u1 = -r (m_A + m_rec / 2)`,
//! `v1 = 0`, with the rod split into its equivalent point masses at A and B
//! (its centre a from A: `m_A = m2 (l - a) / l`, `m_B = m2 a / l`).
//! Exact over 72 equally spaced positions: the piston's acceleration has the
//! first harmonic `-r w^2 cos(theta)` and otherwise only even ones, which an
//! even number of samples does not alias onto the first.

#[path = "../../examples/balancing.rs"]
mod example;

#[test]
fn counterweight_matches_the_closed_form() {
    let c = example::deck();
    let d = c.dynamics.as_ref().unwrap();
    let (crank, rod, piston) = (d.bodies[0], d.bodies[1], d.point_masses[0]);
    let (r, l) = (c.state.target[0], c.state.target[1]);
    let m_a = rod.mass * (l - rod.u) / l;
    let m_rec = rod.mass * rod.u / l + piston.mass;
    let u_star = -r * (m_a + 0.5 * m_rec) / crank.mass;
    let b = example::balance(&c, 2);
    let (u0, _, rms0) = b.history[0];
    let (u1, v1, rms1) = b.history[1];
    let (u2, v2, rms2) = b.history[2];
    // One step lands on the optimum (the force is linear in the centre); the next stays.
    assert!((u1 - u_star).abs() < 1e-9 * r, "u after one step {u1} against the closed form {u_star}");
    assert!(v1.abs() < 1e-9 * r, "v after one step {v1}");
    assert!((u2 - u_star).abs() < 1e-9 * r && v2.abs() < 1e-9 * r);
    assert!((rms2 - rms1).abs() < 1e-9 * rms1);
    // The unbalanced crank shakes far more.
    assert!(u0 > 0.0 && rms0 > 2.0 * rms1, "{rms0} against {rms1}");
    // What is left is the reciprocating mass's: half its primary force
    // (amplitude m_rec r w^2) remains in each direction, RMS m_rec r w^2 / 2,
    // with its secondary and higher harmonics on top (an RMS of 0.5 of their
    // amplitude each, r / l of the primary for the secondary).
    let w = 50.0 * std::f64::consts::PI;
    let primary = 0.5 * m_rec * r * w * w;
    assert!(rms1 > primary && rms1 < primary * (1.0 + r / l), "RMS {rms1} against the primary {primary}");
}
