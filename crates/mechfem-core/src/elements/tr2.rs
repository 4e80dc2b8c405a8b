//! Ternary-2: a binary element with a point R given in the frame at P along
//! P->Q (theory, section 5.4.4, fig. 5.4.6).

use super::local::{local_coordinate, spread_pq, Axis, FrameAngle, Polar};
use super::{tracked_atan2, Bin, Element, FormEval, Order};
use crate::error::ElementError;

/// Ternary-2 `TR2`: co-ordinates `xP yP xQ yQ xR yR`, form parameters
/// `LENL`, `ANGB` (as the binary P->Q), `LENU`, `LENV` (R in that frame).
pub struct Tr2;

impl Element for Tr2 {
    const NAME: &'static str = "TR2";
    const COORDS: &'static [&'static str] = &["xP", "yP", "xQ", "yQ", "xR", "yR"];
    const FORMS: &'static [&'static str] = &["LENL", "ANGB", "LENU", "LENV"];

    fn eval(form: usize, x: &[f64], branch: &mut f64, order: Order, out: &mut FormEval) -> Result<(), ElementError> {
        const N: usize = 6;
        if form < 2 {
            Bin::eval(form, &x[..4], branch, order, out)?;
            // Bin filled the 4 x 4 block; R does not enter l or beta.
            if order >= Order::First {
                out.grad[4..N].fill(0.0);
            }
            if order >= Order::Second {
                for k in 0..N {
                    for l in 0..N {
                        if k >= 4 || l >= 4 {
                            out.hess[k][l] = 0.0;
                        }
                    }
                }
            }
            return Ok(());
        }
        let (dx, dy) = (x[2] - x[0], x[3] - x[1]);
        let p = Polar::new(dx, dy).ok_or(ElementError::CoincidentPoints)?;
        // Keep the element's angle memory in step even though u, v only need c, s.
        tracked_atan2(dy, dx, branch);
        let mut beta = FormEval::default();
        let (g, h) = p.angle_derivs();
        spread_pq(g, h, 0, 2, N, order, &mut beta);
        let frame = FrameAngle { c: p.c, s: p.s, grad: beta.grad, hess: beta.hess };
        let axis = if form == 2 { Axis::U } else { Axis::V };
        local_coordinate(axis, x, 0, 4, &frame, N, order, out);
        Ok(())
    }
}
