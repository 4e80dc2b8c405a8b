//! Pinion and rack on a ternary-1 frame (theory section 5.4.6, fig. 5.4.12,
//! eq. 5.38): the rack is the frame (P, beta_b), Q a point on it, and the
//! pinion's angle beta_a turns with the distance Q covers along the rack.

use super::local::{local_coordinate, Axis, FrameAngle};
use super::{Dimension, Element, FormEval, Order, MAX_COORDS};
use crate::error::ElementError;

/// Pinion and rack `RK1`: co-ordinates `xP yP beta_b xQ yQ i beta_a`,
/// form parameter `GEAR`: `g = i*(beta_a - beta_b) - u` with u the
/// co-ordinate of Q along the rack frame; `i = +-R`.
pub struct Rk1;

impl Element for Rk1 {
    const NAME: &'static str = "RK1";
    const COORDS: &'static [&'static str] = &["xP", "yP", "beta_b", "xQ", "yQ", "i", "beta_a"];
    const FORMS: &'static [&'static str] = &["GEAR"];
    const COORD_DIMENSIONS: &'static [Dimension] = &[
        Dimension::Length,
        Dimension::Length,
        Dimension::Angle,
        Dimension::Length,
        Dimension::Length,
        Dimension::Length,
        Dimension::Angle,
    ];
    const FORM_DIMENSIONS: &'static [Dimension] = &[Dimension::Length];

    fn eval(_form: usize, x: &[f64], _branch: &mut f64, order: Order, out: &mut FormEval) -> Result<(), ElementError> {
        const N: usize = 7;
        let (bb, i, ba) = (x[2], x[5], x[6]);
        let mut grad = [0.0; MAX_COORDS];
        grad[2] = 1.0;
        let frame = FrameAngle { c: bb.cos(), s: bb.sin(), grad, hess: [[0.0; MAX_COORDS]; MAX_COORDS] };
        // Start from u, then g = i*(beta_a - beta_b) - u.
        local_coordinate(Axis::U, x, 0, 3, &frame, N, order, out);
        out.value = i * (ba - bb) - out.value;
        if order >= Order::First {
            for g in out.grad[..N].iter_mut() {
                *g = -*g;
            }
            out.grad[6] += i;
            out.grad[2] -= i;
            out.grad[5] += ba - bb;
        }
        if order >= Order::Second {
            for row in out.hess[..N].iter_mut() {
                for h in row[..N].iter_mut() {
                    *h = -*h;
                }
            }
            out.hess[5][6] += 1.0;
            out.hess[6][5] += 1.0;
            out.hess[5][2] -= 1.0;
            out.hess[2][5] -= 1.0;
        }
        Ok(())
    }
}
