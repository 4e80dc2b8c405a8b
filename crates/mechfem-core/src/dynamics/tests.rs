//! The body frames against finite differences and their duality, the load
//! laws, and the model's checks.

use super::*;
use crate::model::{MechanismBuilder, Term};

/// Co-ordinates of a bar frame (P, Q) and an angle frame (P, beta), with
/// velocities and accelerations, all as smooth functions of time.
fn path(t: f64) -> [f64; 7] {
    [
        0.3 + 0.2 * t * t,
        -0.1 + 0.5 * t.sin(),
        1.7 + 0.4 * (1.3 * t).cos(),
        0.9 - 0.3 * t,
        0.2 * t + 0.1 * t * t * t,
        0.0,
        0.0,
    ]
}

fn frames() -> [Frame; 2] {
    [Frame::Bar { p: [0, 1], q: [2, 3] }, Frame::Angle { p: [0, 1], beta: 4 }]
}

#[test]
fn body_motion_is_the_time_derivative_of_the_centre() {
    let (t, h) = (0.7, 1e-4);
    let d = |k: i32| path(t + f64::from(k) * h);
    let xd: Vec<f64> = (0..7).map(|i| (d(1)[i] - d(-1)[i]) / (2.0 * h)).collect();
    let xdd: Vec<f64> = (0..7).map(|i| (d(1)[i] - 2.0 * d(0)[i] + d(-1)[i]) / (h * h)).collect();
    let (u, v) = (0.8, -0.35);
    for frame in frames() {
        let m = frame.motion(&d(0), &xd, &xdd, u, v);
        let c = |k: i32| frame.centre(&d(k), u, v);
        for a in 0..2 {
            let vel = (c(1)[a] - c(-1)[a]) / (2.0 * h);
            let acc = (c(1)[a] - 2.0 * c(0)[a] + c(-1)[a]) / (h * h);
            assert!((m.c[a] - c(0)[a]).abs() < 1e-15);
            assert!((m.c_dot[a] - vel).abs() < 1e-7, "{frame:?} velocity {a}: {} vs {vel}", m.c_dot[a]);
            assert!((m.c_ddot[a] - acc).abs() < 1e-5, "{frame:?} acceleration {a}: {} vs {acc}", m.c_ddot[a]);
        }
        let (cd, bd) = frame.velocity(&d(0), &xd, u, v);
        assert_eq!((cd, bd), (m.c_dot, m.beta_dot));
    }
}

/// The generalised forces of a force and a moment do the same virtual work
/// on any co-ordinate velocity as the force on the centre's velocity and
/// the moment on the frame's angular velocity.
#[test]
fn spread_forces_do_the_work_of_the_force_and_moment() {
    let x = path(0.4);
    let xd = [0.3, -1.1, 0.7, 0.25, -0.9, 0.0, 0.0];
    let (f, m, u, v) = ([2.5, -1.5], 0.6, -0.4, 1.3);
    for frame in frames() {
        let mut out = [0.0; 7];
        frame.spread(&x, u, v, f, m, &mut out);
        let (cd, bd) = frame.velocity(&x, &xd, u, v);
        let work: f64 = out.iter().zip(&xd).map(|(a, b)| a * b).sum();
        let expected = f[0] * cd[0] + f[1] * cd[1] + m * bd;
        assert!((work - expected).abs() < 1e-13, "{frame:?}: {work} vs {expected}");
    }
}

#[test]
fn loads_follow_their_laws() {
    let form = FormRef::Prescribed(0);
    let table = Load { form, kind: LoadKind::Table(vec![[0.0, 1.0], [1.0, 3.0], [1.0, 5.0], [2.0, 4.0]]) };
    assert_eq!(table.value(-1.0, 0.0, 0.0), 1.0);
    assert_eq!(table.value(0.5, 0.0, 0.0), 2.0);
    assert_eq!(table.value(1.5, 0.0, 0.0), 4.5);
    assert_eq!(table.value(9.0, 0.0, 0.0), 4.0);
    let spring = Load { form, kind: LoadKind::Spring { k: 10.0, e0: 2.0, c: 0.5 } };
    assert_eq!(spring.value(0.0, 2.5, 4.0), -5.0 - 2.0);
    assert_eq!(spring.potential(2.5), 1.25);
    let motor = Load { form, kind: LoadKind::Motor { t0: 8.0, w0: 4.0 } };
    assert_eq!(motor.value(0.0, 0.0, 1.0), 6.0);
    assert_eq!(motor.value(0.0, 0.0, 4.0), 0.0);
    assert_eq!(motor.potential(3.0), 0.0);
}

#[test]
fn the_model_is_checked_against_the_mechanism() {
    let mut b = MechanismBuilder::new();
    let (x0, y0) = (b.fixed(0.0), b.fixed(0.0));
    let (xa, ya) = (b.moving(1.0), b.moving(0.2));
    let (t, r) = (b.fixed(2.0), b.moving(0.5));
    let crank = b.element(ElementType::Bin, &[x0, y0, xa, ya]);
    let gear = b.element(ElementType::Gr1, &[t, r, xa, t]);
    b.prescribe(&[Term::new(crank, 0)]);
    b.prescribe(&[Term::new(gear, 0)]);
    b.input(&[Term::new(crank, 1)]);
    let (mech, _) = b.build().unwrap();
    let body = |element, mass| Body { element, mass, u: 0.5, v: 0.0, inertia: 0.1 };
    let with = |d: Dynamics| d.check(&mech);
    assert_eq!(with(Dynamics { bodies: vec![body(crank, 1.0)], ..Dynamics::default() }), Ok(()));
    assert_eq!(
        with(Dynamics { bodies: vec![body(gear, 1.0)], ..Dynamics::default() }),
        Err(DynamicsError::NoFrame { element: gear, ty: "GR1" })
    );
    assert!(matches!(
        with(Dynamics { bodies: vec![body(crank, -1.0)], ..Dynamics::default() }),
        Err(DynamicsError::BadNumber { what: "mass", .. })
    ));
    assert!(matches!(
        with(Dynamics { bodies: vec![body(5, 1.0)], ..Dynamics::default() }),
        Err(DynamicsError::UnknownElement { element: 5, .. })
    ));
    let point = PointMass { x: 9, y: 0, mass: 1.0 };
    assert!(matches!(
        with(Dynamics { point_masses: vec![point], ..Dynamics::default() }),
        Err(DynamicsError::UnknownCoordinate { coordinate: 9, .. })
    ));
    let load = |form, kind| Dynamics { loads: vec![Load { form, kind }], ..Dynamics::default() };
    assert!(matches!(
        with(load(FormRef::Dependent(0), LoadKind::Constant(1.0))),
        Err(DynamicsError::UnknownForm { .. })
    ));
    assert!(matches!(
        with(load(FormRef::Prescribed(2), LoadKind::Motor { t0: 1.0, w0: 0.0 })),
        Err(DynamicsError::BadNumber { what: "motor no-load speed", .. })
    ));
    assert!(matches!(
        with(load(FormRef::Prescribed(2), LoadKind::Table(vec![[1.0, 0.0], [0.5, 0.0]]))),
        Err(DynamicsError::BadNumber { must: "increasing", .. })
    ));
    let _ = r;
}
