//! Ternary-1: a half beam with a point R given in its local frame
//! (theory, section 5.4.4, fig. 5.4.5). Defined for every position, also
//! when R coincides with P.

use super::local::{diff, local_coordinate, local_second, zero_hess, Axis, FrameAngle};
use super::{Dimension, Element, FormEval, Order, MAX_COORDS};
use crate::error::ElementError;

/// Ternary-1 `TR1`: co-ordinates `xP yP beta xR yR`, form parameters
/// `ANGV = beta`, `LENU`, `LENV` (R in the frame at P with angle beta).
pub struct Tr1;

impl Element for Tr1 {
    const NAME: &'static str = "TR1";
    const COORDS: &'static [&'static str] = &["xP", "yP", "beta", "xR", "yR"];
    const FORMS: &'static [&'static str] = &["ANGV", "LENU", "LENV"];
    const COORD_DIMENSIONS: &'static [Dimension] =
        &[Dimension::Length, Dimension::Length, Dimension::Angle, Dimension::Length, Dimension::Length];
    const FORM_DIMENSIONS: &'static [Dimension] = &[Dimension::Angle, Dimension::Length, Dimension::Length];

    /// ANGV is the angle co-ordinate alone.
    fn depends(form: usize) -> u32 {
        if form == 0 {
            0b00100
        } else {
            0b11111
        }
    }

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
        let axis = if form == 1 { Axis::U } else { Axis::V };
        let (s, c) = x[2].sin_cos();
        if order == Order::Second {
            let mut grad = [0.0; MAX_COORDS];
            grad[2] = 1.0;
            let frame = FrameAngle { c, s, grad, hess: [[0.0; MAX_COORDS]; MAX_COORDS] };
            local_coordinate(axis, x, 0, 3, &frame, N, order, out);
        }
        // u = r.e, v = r.m with r = R - P, e = (c, s), m = (-s, c), and
        // de/dbeta = m, dm/dbeta = -e.
        let r = diff(x, 0, 3);
        let (u, v) = (c * r[0] + s * r[1], c * r[1] - s * r[0]);
        if order >= Order::First {
            out.aux[..4].copy_from_slice(&[c, s, u, v]);
        }
        if order == Order::Second {
            return Ok(());
        }
        let (w, d_beta, value) = match axis {
            Axis::U => ([c, s], v, u),
            Axis::V => ([-s, c], -u, v),
        };
        out.value = value;
        if order >= Order::First {
            out.grad[..N].copy_from_slice(&[-w[0], -w[1], d_beta, w[0], w[1]]);
        }
        Ok(())
    }

    // Always inlined into the second-order products (ElementType::second_at).
    #[inline(always)]
    fn second(form: usize, _x: &[f64], first: &FormEval, a: &[f64], b: &[f64]) -> f64 {
        if form == 0 {
            return 0.0;
        }
        let axis = if form == 1 { Axis::U } else { Axis::V };
        let [c, s, u, v, ..] = first.aux;
        local_second(axis, (c, s), (u, v), (diff(a, 0, 3), diff(b, 0, 3)), (a[2], b[2]), 0.0)
    }
}
