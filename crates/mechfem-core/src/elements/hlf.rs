//! Half beam: a point and an orientation carried as a co-ordinate
//! (theory, section 5.4.3). Used for wheels and as an angular reference.

use super::local::zero_hess;
use super::{Dimension, Element, FormEval, Order};
use crate::error::ElementError;

/// Half beam `HLF`: co-ordinates `xP yP beta`, form parameter `ANGV = beta`.
pub struct Hlf;

impl Element for Hlf {
    const NAME: &'static str = "HLF";
    const COORDS: &'static [&'static str] = &["xP", "yP", "beta"];
    const FORMS: &'static [&'static str] = &["ANGV"];
    const COORD_DIMENSIONS: &'static [Dimension] = &[Dimension::Length, Dimension::Length, Dimension::Angle];
    const FORM_DIMENSIONS: &'static [Dimension] = &[Dimension::Angle];

    fn depends(_form: usize) -> u32 {
        0b100
    }

    fn eval(_form: usize, x: &[f64], _branch: &mut f64, order: Order, out: &mut FormEval) -> Result<(), ElementError> {
        // The angle is a co-ordinate: never wrapped.
        out.value = x[2];
        if order >= Order::First {
            out.grad[..3].copy_from_slice(&[0.0, 0.0, 1.0]);
        }
        if order >= Order::Second {
            zero_hess(3, out);
        }
        Ok(())
    }

    // Always inlined into the second-order products (ElementType::second_at).
    #[inline(always)]
    fn second(_form: usize, _x: &[f64], _first: &FormEval, _a: &[f64], _b: &[f64]) -> f64 {
        0.0
    }
}
