//! Ternary-2: a binary element with a point R given in the frame at P along
//! P->Q (theory, section 5.4.4, fig. 5.4.6).

use super::local::{diff, local_coordinate, local_second, spread_pq, Axis, FrameAngle, Polar};
use super::{Bin, Dimension, Element, FormEval, Order};
use crate::error::ElementError;

/// Ternary-2 `TR2`: co-ordinates `xP yP xQ yQ xR yR`, form parameters
/// `LENL`, `ANGB` (as the binary P->Q), `LENU`, `LENV` (R in that frame).
///
/// Only `ANGB` reads and updates the element's angle memory: u and v need
/// the direction of P->Q, not its angle.
pub struct Tr2;

impl Element for Tr2 {
    const NAME: &'static str = "TR2";
    const COORDS: &'static [&'static str] = &["xP", "yP", "xQ", "yQ", "xR", "yR"];
    const FORMS: &'static [&'static str] = &["LENL", "ANGB", "LENU", "LENV"];
    const COORD_DIMENSIONS: &'static [Dimension] = &[
        Dimension::Length,
        Dimension::Length,
        Dimension::Length,
        Dimension::Length,
        Dimension::Length,
        Dimension::Length,
    ];
    const FORM_DIMENSIONS: &'static [Dimension] =
        &[Dimension::Length, Dimension::Angle, Dimension::Length, Dimension::Length];

    /// The bar P->Q does not involve R.
    fn depends(form: usize) -> u32 {
        if form < 2 {
            0b001111
        } else {
            0b111111
        }
    }

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
        let axis = if form == 2 { Axis::U } else { Axis::V };
        if order == Order::Second {
            let mut beta = FormEval::default();
            let (g, h) = p.angle_derivs();
            spread_pq(g, h, 0, 2, N, order, &mut beta);
            let frame = FrameAngle { c: p.c, s: p.s, grad: beta.grad, hess: beta.hess };
            local_coordinate(axis, x, 0, 4, &frame, N, order, out);
        }
        // u = r.e, v = r.m with r = R - P; the frame angle beta has gradient
        // (s/l, -c/l) at P and (-s/l, c/l) at Q, and de/dbeta = m, dm/dbeta = -e.
        let r = diff(x, 0, 4);
        let (u, v) = (p.along(r), p.across(r));
        if order >= Order::First {
            p.stash(&mut out.aux);
            out.aux[3] = u;
            out.aux[4] = v;
        }
        if order == Order::Second {
            return Ok(());
        }
        let (w, d_beta, value) = match axis {
            Axis::U => ([p.c, p.s], v, u),
            Axis::V => ([-p.s, p.c], -u, v),
        };
        out.value = value;
        if order >= Order::First {
            let (gx, gy) = (-p.s * p.r * d_beta, p.c * p.r * d_beta);
            out.grad[..N].copy_from_slice(&[-w[0] - gx, -w[1] - gy, gx, gy, w[0], w[1]]);
        }
        Ok(())
    }

    // Always inlined into the second-order products (ElementType::second_at).
    #[inline(always)]
    fn second(form: usize, _x: &[f64], first: &FormEval, a: &[f64], b: &[f64]) -> f64 {
        let p = Polar::unstash(&first.aux);
        let (da, db) = (diff(a, 0, 2), diff(b, 0, 2));
        match form {
            0 => p.length_second(da, db),
            1 => p.angle_second(da, db),
            _ => {
                let axis = if form == 2 { Axis::U } else { Axis::V };
                let (u, v) = (first.aux[3], first.aux[4]);
                let (bp, bq) = (p.across(da) * p.r, p.across(db) * p.r);
                let rs = (diff(a, 0, 4), diff(b, 0, 4));
                local_second(axis, (p.c, p.s), (u, v), rs, (bp, bq), p.angle_second(da, db))
            }
        }
    }
}
