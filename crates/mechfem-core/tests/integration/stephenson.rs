//! det(D^c) of a Stephenson-2 six-bar modelled with binary elements and two
//! fixed angles (theory fig. 5.4.2), compared along the motion with the
//! closed form of eq. 5.40.

use mechfem_core::{run, ElementType, InputMotion, MechanismBuilder, Motion, Params, Quantity, Recorder, Term};

#[test]
fn det_matches_eq_5_40_along_the_motion() {
    let mut b = MechanismBuilder::new();
    let a0 = [b.fixed(0.0), b.fixed(0.0)];
    let f0 = [b.fixed(4.0), b.fixed(0.0)];
    let mut point = |x: f64, y: f64| [b.moving(x), b.moving(y)];
    let (pa, pb, pc, pd, pe) =
        (point(0.0, 0.4), point(-1.9, -0.99), point(-0.08, -1.14), point(3.24, -2.81), point(2.73, 1.76));
    let bar =
        |b: &mut MechanismBuilder, p: [usize; 2], q: [usize; 2]| b.element(ElementType::Bin, &[p[0], p[1], q[0], q[1]]);
    let e1 = bar(&mut b, a0, pa);
    let e2 = bar(&mut b, pa, pb);
    let e3 = bar(&mut b, pa, pc);
    let e4 = bar(&mut b, pb, pd);
    let e5 = bar(&mut b, pc, pe);
    let e6 = bar(&mut b, f0, pd);
    let e7 = bar(&mut b, f0, pe);
    for e in [e1, e2, e3] {
        b.prescribe(&[Term::new(e, 0)]);
    }
    b.prescribe(&[Term::new(e2, 1), Term::scaled(e3, 1, -1.0)]);
    for e in [e4, e5, e6] {
        b.prescribe(&[Term::new(e, 0)]);
    }
    b.prescribe(&[Term::new(e6, 1), Term::scaled(e7, 1, -1.0)]);
    b.prescribe(&[Term::new(e7, 0)]);
    b.input(&[Term::new(e1, 1)]);
    let (mech, mut state) = b.build().unwrap();
    let mut rec = Recorder::new(vec![Quantity::Det], true);
    let motion =
        Motion { steps: 120, dt: 1.0, inputs: vec![InputMotion::Relative { delta: 2.0 * std::f64::consts::PI }] };
    let report = run(&mech, &mut state, Some(&motion), &Params::default(), &mut rec).unwrap();
    // This geometry lets the crank turn a full revolution.
    assert!(report.stop.is_none(), "{report:?}");
    let n = mech.n_coords();
    let mut sign = 0.0;
    for k in 0..rec.positions() {
        let x = &rec.coords()[k * n..(k + 1) * n];
        let p = |i: usize| (x[2 * i], x[2 * i + 1]);
        // Points in co-ordinate order: A0, F0, A, B, C, D, E.
        let (a0, f0, a, bb, c, d, e) = (p(0), p(1), p(2), p(3), p(4), p(5), p(6));
        let polar = |p: (f64, f64), q: (f64, f64)| ((q.0 - p.0).hypot(q.1 - p.1), (q.1 - p.1).atan2(q.0 - p.0));
        let (l1, _) = polar(a0, a);
        let (l2, b2) = polar(a, bb);
        let (l3, b3) = polar(a, c);
        let (_, b4) = polar(bb, d);
        let (_, b5) = polar(c, e);
        let (l6, b6) = polar(f0, d);
        let (l7, b7) = polar(f0, e);
        let closed =
            (b4 - b6).sin() * (b3 - b5).sin() / (l1 * l2 * l7) - (b5 - b7).sin() * (b2 - b4).sin() / (l1 * l3 * l6);
        let det = rec.data()[k];
        if k == 0 {
            // Row order and co-ordinate order fix an overall sign.
            sign = (det / closed).signum();
        }
        assert!(
            (det - sign * closed).abs() < 1e-10 * (1.0 + closed.abs()),
            "position {k}: det {det}, eq. 5.40 {closed}"
        );
    }
}
