//! The transmission angle between two elements (BUFTRA): the angle mu in
//! [0, pi] between their first sides, P->Q of BIN and TR2, the direction of
//! the angle co-ordinate of HLF and TR1.
//!
//! With theta_a, theta_b the sides' directions and `Delta = theta_b -
//! theta_a`, `mu = atan2(|sin Delta|, cos Delta)`, so `d mu = sgn(sin Delta)
//! d Delta`; the direction of a bar d = Q - P changes by `d theta = (d x
//! d(d)) / |d|^2`. A designer watches `|mu - 90 deg|`: the further from a
//! right angle, the less of the driving force turns the output.

use crate::dynamics::Frame;
use crate::model::Mechanism;
use crate::solver::Sensitivity;

fn frame(mech: &Mechanism, e: usize) -> Option<Frame> {
    let el = mech.elements().get(e)?;
    Frame::of(el.ty, el.coords())
}

/// The transmission angle between the first sides of elements `a` and `b`
/// at co-ordinates `x`, in [0, pi]; NaN for an element without a frame or a
/// bar whose ends meet.
pub fn transmission_angle(mech: &Mechanism, x: &[f64], a: usize, b: usize) -> f64 {
    let (Some(fa), Some(fb)) = (frame(mech, a), frame(mech, b)) else { return f64::NAN };
    let (ua, ub) = (fa.direction(x), fb.direction(x));
    // atan2 of cross and dot keeps full accuracy near 0 and pi, where
    // arccos of the dot product loses half the digits.
    (ua[0] * ub[1] - ua[1] * ub[0]).abs().atan2(ua[0] * ub[0] + ua[1] * ub[1])
}

/// The derivative of the side's direction angle with respect to design
/// variable `var` of `s`.
fn direction_sensitivity(f: Frame, x: &[f64], s: &Sensitivity, var: usize) -> f64 {
    match f {
        Frame::Angle { beta, .. } => s.dx(beta, var),
        Frame::Bar { p, q } => {
            let d = [x[q[0]] - x[p[0]], x[q[1]] - x[p[1]]];
            let dd = [s.dx(q[0], var) - s.dx(p[0], var), s.dx(q[1], var) - s.dx(p[1], var)];
            (d[0] * dd[1] - d[1] * dd[0]) / (d[0] * d[0] + d[1] * d[1])
        }
    }
}

/// The derivative of [`transmission_angle`] with respect to design
/// variable `var` of `s` (computed at this position).
pub fn transmission_sensitivity(mech: &Mechanism, x: &[f64], s: &Sensitivity, var: usize, a: usize, b: usize) -> f64 {
    let (Some(fa), Some(fb)) = (frame(mech, a), frame(mech, b)) else { return f64::NAN };
    let (ua, ub) = (fa.direction(x), fb.direction(x));
    let sin_delta = ua[0] * ub[1] - ua[1] * ub[0];
    let d_delta = direction_sensitivity(fb, x, s, var) - direction_sensitivity(fa, x, s, var);
    sin_delta.signum() * d_delta
}
