//! Binary (truss) element: two points P, Q; length and angle of P->Q
//! (theory eqs. 5.2-5.7, 5.23, 5.24).

use super::local::{spread_pq, Polar};
use super::{tracked_atan2, Element, FormEval, Order};
use crate::error::ElementError;

/// Binary element `BIN`: co-ordinates `xP yP xQ yQ`, form parameters
/// `LENL` (length) and `ANGB` (angle of P->Q, tracked continuously).
pub struct Bin;

impl Element for Bin {
    const NAME: &'static str = "BIN";
    const COORDS: &'static [&'static str] = &["xP", "yP", "xQ", "yQ"];
    const FORMS: &'static [&'static str] = &["LENL", "ANGB"];

    fn eval(form: usize, x: &[f64], branch: &mut f64, order: Order, out: &mut FormEval) -> Result<(), ElementError> {
        let (dx, dy) = (x[2] - x[0], x[3] - x[1]);
        let p = Polar::new(dx, dy).ok_or(ElementError::CoincidentPoints)?;
        let (g, h) = if form == 0 {
            out.value = p.l;
            p.length_derivs()
        } else {
            out.value = tracked_atan2(dy, dx, branch);
            p.angle_derivs()
        };
        spread_pq(g, h, 0, 2, 4, order, out);
        Ok(())
    }
}
