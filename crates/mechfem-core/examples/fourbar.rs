//! A four-bar with a coupler point, built and run from Rust.
//!
//! Run with `cargo run -p mechfem-core --example fourbar`.
//!
//! The steps are those of every model: place co-ordinates (fixed or moving,
//! rough values are fine for the moving ones), put elements on them, say
//! which form parameters are held constant, which one is the input and
//! which ones are outputs, build, set the prescribed values, and run a
//! motion with an observer that records what you want per position.

use mechfem_core::{
    run, ElementType, FormRef, InputMotion, MechanismBuilder, Motion, Params, Quantity, Recorder, Term,
};
use std::f64::consts::PI;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut b = MechanismBuilder::new();

    // Fixed pivots A0 = (0, 0) and B0 = (3.2, 0).
    let (xa0, ya0) = (b.fixed(0.0), b.fixed(0.0));
    let (xb0, yb0) = (b.fixed(3.2), b.fixed(0.0));
    // Moving points A (crank pin), B (rocker pin) and C (coupler point),
    // roughly where they are at crank angle 0.
    let (xa, ya) = (b.moving(1.0), b.moving(0.0));
    let (xb, yb) = (b.moving(2.7), b.moving(2.5));
    let (xc, yc) = (b.moving(1.0), b.moving(1.8));

    // Crank A0-A and rocker B0-B are binary elements; the coupler is a
    // ternary-2 on A, B with C at local (u, v) in the frame along A->B.
    let crank = b.element(ElementType::Bin, &[xa0, ya0, xa, ya]);
    let coupler = b.element(ElementType::Tr2, &[xa, ya, xb, yb, xc, yc]);
    let rocker = b.element(ElementType::Bin, &[xb0, yb0, xb, yb]);

    // Constant form parameters (rows of D^c), then the input (the crank's
    // angle), then an output: the coupler's angle.
    let lenl = ElementType::Bin.form_index("LENL").unwrap();
    let angb = ElementType::Bin.form_index("ANGB").unwrap();
    let [tr2_lenl, tr2_angb, tr2_lenu, tr2_lenv] =
        ["LENL", "ANGB", "LENU", "LENV"].map(|name| ElementType::Tr2.form_index(name).unwrap());
    b.prescribe(&[Term::new(crank, lenl)]);
    b.prescribe(&[Term::new(coupler, tr2_lenl)]);
    b.prescribe(&[Term::new(rocker, lenl)]);
    b.prescribe(&[Term::new(coupler, tr2_lenu)]);
    b.prescribe(&[Term::new(coupler, tr2_lenv)]);
    b.input(&[Term::new(crank, angb)]);
    b.dependent(&[Term::new(coupler, tr2_angb)]);

    let (mech, mut state) = b.build()?;
    // The prescribed values default to those at the rough co-ordinates;
    // give the exact ones. Position 1 is adjusted to them.
    let (u, v) = (1.8 * 0.6f64.cos(), 1.8 * 0.6f64.sin());
    state.target.copy_from_slice(&[1.0, 3.0, 2.5, u, v, 0.0]);

    // One crank revolution in 12 steps of 30 degrees at 1 rad/s.
    let steps = 12;
    let dt = 2.0 * PI / steps as f64;
    let motion = Motion { steps, dt, inputs: vec![InputMotion::Relative { delta: 2.0 * PI }] };
    let coupler_angle = FormRef::Dependent(0);
    let mut rec = Recorder::new(
        vec![
            Quantity::Input(0),
            Quantity::X0(xc),
            Quantity::X0(yc),
            Quantity::Vx(xc),
            Quantity::Vx(yc),
            Quantity::E0(coupler_angle),
            Quantity::Ke1(coupler_angle, 0),
            Quantity::Det,
        ],
        false,
    );
    let report = run(&mech, &mut state, Some(&motion), &Params::default(), &mut rec)?;
    println!("adjusted position 1 in {} Newton iterations; {} positions", report.adjust.iterations, report.positions);
    if let Some(stop) = &report.stop {
        println!("stopped after position {}: {}", stop.last_good + 1, stop.error);
    }

    println!(
        "{:>6} {:>9} {:>9} {:>9} {:>9} {:>9} {:>9} {:>9}",
        "crank", "xC", "yC", "vxC", "vyC", "coupler", "d/dcrank", "det"
    );
    let w = rec.quantities().len();
    for row in rec.data().chunks(w) {
        let (crank_deg, coupler_deg) = (row[0].to_degrees(), row[5].to_degrees());
        println!(
            "{crank_deg:6.1} {:9.5} {:9.5} {:9.5} {:9.5} {coupler_deg:9.3} {:9.5} {:9.5}",
            row[1], row[2], row[3], row[4], row[6], row[7]
        );
    }
    Ok(())
}
