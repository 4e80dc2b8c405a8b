//! Single co-ordinate element: lets one co-ordinate be prescribed or driven,
//! and serves as the temporary input of free motion (theory, section 5.5.3).

use super::local::zero_hess;
use super::{Dimension, Element, FormEval, Order};
use crate::error::ElementError;

/// Single co-ordinate `CRD`: co-ordinate `x`, form parameter `COOR = x`.
pub struct Crd;

impl Element for Crd {
    const NAME: &'static str = "CRD";
    const COORDS: &'static [&'static str] = &["x"];
    const FORMS: &'static [&'static str] = &["COOR"];
    const COORD_DIMENSIONS: &'static [Dimension] = &[Dimension::Any];
    const FORM_DIMENSIONS: &'static [Dimension] = &[Dimension::Any];

    fn eval(_form: usize, x: &[f64], _branch: &mut f64, order: Order, out: &mut FormEval) -> Result<(), ElementError> {
        out.value = x[0];
        if order >= Order::First {
            out.grad[0] = 1.0;
        }
        if order >= Order::Second {
            zero_hess(1, out);
        }
        Ok(())
    }

    // Always inlined into the second-order products (ElementType::second_at).
    #[inline(always)]
    fn second(_form: usize, _x: &[f64], _first: &FormEval, _a: &[f64], _b: &[f64]) -> f64 {
        0.0
    }
}
