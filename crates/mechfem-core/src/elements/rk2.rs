//! Pinion and rack on a ternary-2 frame (theory section 5.4.6): as RK1, but
//! the rack's angle is that of P->Q, a form parameter rather than a
//! co-ordinate, and R is the point that travels along it.

use super::local::{local_coordinate, spread_pq, Axis, FrameAngle, Polar};
use super::{tracked_atan2, Dimension, Element, FormEval, Order};
use crate::error::ElementError;

/// Pinion and rack `RK2`: co-ordinates `xP yP xQ yQ xR yR i beta_a`, form
/// parameter `GEAR`: `g = i*(beta_a - beta_b) - u`, beta_b the angle of
/// P->Q (tracked continuously), u the co-ordinate of R along P->Q.
pub struct Rk2;

impl Element for Rk2 {
    const NAME: &'static str = "RK2";
    const COORDS: &'static [&'static str] = &["xP", "yP", "xQ", "yQ", "xR", "yR", "i", "beta_a"];
    const FORMS: &'static [&'static str] = &["GEAR"];
    const COORD_DIMENSIONS: &'static [Dimension] = &[
        Dimension::Length,
        Dimension::Length,
        Dimension::Length,
        Dimension::Length,
        Dimension::Length,
        Dimension::Length,
        Dimension::Length,
        Dimension::Angle,
    ];
    const FORM_DIMENSIONS: &'static [Dimension] = &[Dimension::Length];

    fn eval(_form: usize, x: &[f64], branch: &mut f64, order: Order, out: &mut FormEval) -> Result<(), ElementError> {
        const N: usize = 8;
        let (dx, dy) = (x[2] - x[0], x[3] - x[1]);
        let p = Polar::new(dx, dy).ok_or(ElementError::CoincidentPoints)?;
        let bb = tracked_atan2(dy, dx, branch);
        let (i, ba) = (x[6], x[7]);
        let mut beta = FormEval::default();
        let (g, h) = p.angle_derivs();
        spread_pq(g, h, 0, 2, N, order, &mut beta);
        let frame = FrameAngle { c: p.c, s: p.s, grad: beta.grad, hess: beta.hess };
        local_coordinate(Axis::U, x, 0, 4, &frame, N, order, out);
        out.value = i * (ba - bb) - out.value;
        if order >= Order::First {
            for k in 0..N {
                out.grad[k] = -out.grad[k] - i * beta.grad[k];
            }
            out.grad[7] += i;
            out.grad[6] += ba - bb;
        }
        if order >= Order::Second {
            for k in 0..N {
                for l in 0..N {
                    out.hess[k][l] = -out.hess[k][l] - i * beta.hess[k][l];
                }
            }
            // d2/di d(beta_a) = 1, d2/di dx = -d beta_b/dx.
            out.hess[6][7] += 1.0;
            out.hess[7][6] += 1.0;
            for k in 0..4 {
                out.hess[6][k] -= beta.grad[k];
                out.hess[k][6] -= beta.grad[k];
            }
        }
        Ok(())
    }
}
