//! Gear pair with the transmission ratio as a co-ordinate (theory section
//! 5.4.5, fig. 5.4.9, eq. 5.36).

use super::local::zero_hess;
use super::{Dimension, Element, FormEval, Order};
use crate::error::ElementError;

/// Gear pair `GR1`: co-ordinates `beta_a beta_b beta_c i`, form parameter
/// `GEAR`: `g = i*beta_a + (1 - i)*beta_b - beta_c`, the assembly angle.
/// beta_b is the angle of the bar carrying both wheel centres; i is the
/// ratio d(beta_c - beta_b) / d(beta_a - beta_b) (negative for two outer
/// gears). Usually i is a fixed co-ordinate; a moving i models a variator.
pub struct Gr1;

impl Element for Gr1 {
    const NAME: &'static str = "GR1";
    const COORDS: &'static [&'static str] = &["beta_a", "beta_b", "beta_c", "i"];
    const FORMS: &'static [&'static str] = &["GEAR"];
    const COORD_DIMENSIONS: &'static [Dimension] =
        &[Dimension::Angle, Dimension::Angle, Dimension::Angle, Dimension::Ratio];
    const FORM_DIMENSIONS: &'static [Dimension] = &[Dimension::Angle];

    fn eval(_form: usize, x: &[f64], _branch: &mut f64, order: Order, out: &mut FormEval) -> Result<(), ElementError> {
        let (ba, bb, bc, i) = (x[0], x[1], x[2], x[3]);
        out.value = i * ba + (1.0 - i) * bb - bc;
        if order >= Order::First {
            out.grad[..4].copy_from_slice(&[i, 1.0 - i, -1.0, ba - bb]);
        }
        if order >= Order::Second {
            zero_hess(4, out);
            // Only the ratio multiplies an angle.
            out.hess[0][3] = 1.0;
            out.hess[3][0] = 1.0;
            out.hess[1][3] = -1.0;
            out.hess[3][1] = -1.0;
        }
        Ok(())
    }

    // Always inlined into the second-order products (ElementType::second_at).
    #[inline(always)]
    fn second(_form: usize, _x: &[f64], _first: &FormEval, a: &[f64], b: &[f64]) -> f64 {
        (a[0] - a[1]) * b[3] + a[3] * (b[0] - b[1])
    }
}
