//! Gear pair with the two radii as co-ordinates (theory section 5.4.5): the
//! relation of GR1 with `i = -R_a / R_c`. The radii need not match the
//! centre distance, so the same element models a chain or a belt without
//! slip (a negative radius: wheels turning the same way, or a ring gear).

use super::local::zero_hess;
use super::{Dimension, Element, FormEval, Order};
use crate::error::ElementError;

/// Gear pair `GR2`: co-ordinates `beta_a beta_b beta_c R_a R_c`, form
/// parameter `GEAR`: `g = beta_b - beta_c + i*(beta_a - beta_b)`, `i = -R_a/R_c`.
pub struct Gr2;

impl Element for Gr2 {
    const NAME: &'static str = "GR2";
    const COORDS: &'static [&'static str] = &["beta_a", "beta_b", "beta_c", "R_a", "R_c"];
    const FORMS: &'static [&'static str] = &["GEAR"];
    const COORD_DIMENSIONS: &'static [Dimension] =
        &[Dimension::Angle, Dimension::Angle, Dimension::Angle, Dimension::Length, Dimension::Length];
    const FORM_DIMENSIONS: &'static [Dimension] = &[Dimension::Angle];

    fn eval(_form: usize, x: &[f64], _branch: &mut f64, order: Order, out: &mut FormEval) -> Result<(), ElementError> {
        let (ba, bb, bc, ra, rc) = (x[0], x[1], x[2], x[3], x[4]);
        if ra == 0.0 {
            return Err(ElementError::ZeroRadius { name: "R_a" });
        }
        if rc == 0.0 {
            return Err(ElementError::ZeroRadius { name: "R_c" });
        }
        let i = -ra / rc;
        let w = ba - bb;
        out.value = bb - bc + i * w;
        // Derivatives of the ratio with respect to the radii.
        let (i_a, i_c) = (-1.0 / rc, ra / (rc * rc));
        let (i_ac, i_cc) = (1.0 / (rc * rc), -2.0 * ra / (rc * rc * rc));
        if order >= Order::First {
            out.grad[..5].copy_from_slice(&[i, 1.0 - i, -1.0, w * i_a, w * i_c]);
        }
        if order >= Order::Second {
            zero_hess(5, out);
            let mut set = |k: usize, l: usize, v: f64| {
                out.hess[k][l] = v;
                out.hess[l][k] = v;
            };
            set(0, 3, i_a);
            set(0, 4, i_c);
            set(1, 3, -i_a);
            set(1, 4, -i_c);
            set(3, 4, w * i_ac);
            set(4, 4, w * i_cc);
        }
        Ok(())
    }

    // Always inlined into the second-order products (ElementType::second_at).
    #[inline(always)]
    fn second(_form: usize, x: &[f64], _first: &FormEval, a: &[f64], b: &[f64]) -> f64 {
        let (ba, bb, ra, rc) = (x[0], x[1], x[3], x[4]);
        if ra == 0.0 || rc == 0.0 {
            return f64::NAN;
        }
        let w = ba - bb;
        let (i_a, i_c) = (-1.0 / rc, ra / (rc * rc));
        let (i_ac, i_cc) = (1.0 / (rc * rc), -2.0 * ra / (rc * rc * rc));
        let sym = |k: usize, l: usize| a[k] * b[l] + a[l] * b[k];
        i_a * (sym(0, 3) - sym(1, 3)) + i_c * (sym(0, 4) - sym(1, 4)) + w * i_ac * sym(3, 4) + w * i_cc * a[4] * b[4]
    }
}
