//! Ternary-1: a half beam with a point R given in its local frame
//! (theory, section 5.4.4, fig. 5.4.5). Defined for every position, also
//! when R coincides with P.

use super::local::{local_coordinate, zero_hess, Axis, FrameAngle};
use super::{Element, FormEval, Order, MAX_COORDS};
use crate::error::ElementError;

/// Ternary-1 `TR1`: co-ordinates `xP yP beta xR yR`, form parameters
/// `ANGV = beta`, `LENU`, `LENV` (R in the frame at P with angle beta).
pub struct Tr1;

impl Element for Tr1 {
    const NAME: &'static str = "TR1";
    const COORDS: &'static [&'static str] = &["xP", "yP", "beta", "xR", "yR"];
    const FORMS: &'static [&'static str] = &["ANGV", "LENU", "LENV"];

    fn eval(form: usize, x: &[f64], _branch: &mut f64, order: Order, out: &mut FormEval) -> Result<(), ElementError> {
        const N: usize = 5;
        if form == 0 {
            out.value = x[2];
            if order >= Order::First {
                out.grad[..N].copy_from_slice(&[0.0, 0.0, 1.0, 0.0, 0.0]);
            }
            if order >= Order::Second {
                zero_hess(N, out);
            }
            return Ok(());
        }
        let mut grad = [0.0; MAX_COORDS];
        grad[2] = 1.0;
        let frame = FrameAngle { c: x[2].cos(), s: x[2].sin(), grad, hess: [[0.0; MAX_COORDS]; MAX_COORDS] };
        let axis = if form == 1 { Axis::U } else { Axis::V };
        local_coordinate(axis, x, 0, 3, &frame, N, order, out);
        Ok(())
    }
}
