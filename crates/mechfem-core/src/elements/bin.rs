//! Binary (truss) element: two points P, Q; length and angle of P->Q
//! (theory eqs. 5.2-5.7, 5.23, 5.24).

use super::local::{diff, spread_pq, Polar};
use super::{tracked_atan2, Dimension, Element, FormEval, Order};
use crate::error::ElementError;

/// Binary element `BIN`: co-ordinates `xP yP xQ yQ`, form parameters
/// `LENL` (length) and `ANGB` (angle of P->Q, tracked continuously).
pub struct Bin;

impl Element for Bin {
    const NAME: &'static str = "BIN";
    const COORDS: &'static [&'static str] = &["xP", "yP", "xQ", "yQ"];
    const FORMS: &'static [&'static str] = &["LENL", "ANGB"];
    const COORD_DIMENSIONS: &'static [Dimension] =
        &[Dimension::Length, Dimension::Length, Dimension::Length, Dimension::Length];
    const FORM_DIMENSIONS: &'static [Dimension] = &[Dimension::Length, Dimension::Angle];

    fn eval(form: usize, x: &[f64], branch: &mut f64, order: Order, out: &mut FormEval) -> Result<(), ElementError> {
        let (dx, dy) = (x[2] - x[0], x[3] - x[1]);
        if order == Order::Value {
            // The length, or the angle, and nothing else. The squared
            // length is positive and finite exactly when the length is, so
            // the angle needs no square root.
            let l2 = dx * dx + dy * dy;
            if !(l2 > 0.0 && l2.is_finite()) {
                return Err(ElementError::CoincidentPoints);
            }
            out.value = if form == 0 { l2.sqrt() } else { tracked_atan2(dy, dx, branch) };
            return Ok(());
        }
        let p = Polar::new(dx, dy).ok_or(ElementError::CoincidentPoints)?;
        out.value = if form == 0 { p.l } else { tracked_atan2(dy, dx, branch) };
        if order == Order::Second {
            let (g, h) = if form == 0 { p.length_derivs() } else { p.angle_derivs() };
            spread_pq(g, h, 0, 2, 4, order, out);
        } else {
            // d l / d(dx, dy) = (c, s); d beta / d(dx, dy) = (-s, c) / l.
            let g = if form == 0 { [p.c, p.s] } else { [-p.s * p.r, p.c * p.r] };
            out.grad[..4].copy_from_slice(&[-g[0], -g[1], g[0], g[1]]);
        }
        p.stash(&mut out.aux);
        Ok(())
    }

    // Always inlined into the second-order products (ElementType::second_at).
    #[inline(always)]
    fn second(form: usize, _x: &[f64], first: &FormEval, a: &[f64], b: &[f64]) -> f64 {
        let p = Polar::unstash(&first.aux);
        let (da, db) = (diff(a, 0, 2), diff(b, 0, 2));
        if form == 0 {
            p.length_second(da, db)
        } else {
            p.angle_second(da, db)
        }
    }
}
