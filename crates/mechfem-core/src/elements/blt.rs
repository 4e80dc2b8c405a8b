//! Belt over two wheels (theory section 5.4.7, fig. 5.4.15): wheel a at P
//! with angle beta_a and radius R_P, wheel c at Q with beta_c and R_Q, joined
//! by the bar P->Q.
//!
//! With l = |PQ|, beta_b its angle, d = R_P - R_Q, the free span is
//! `l* = sqrt(l^2 - d^2)`, the tangent points lie at
//! `phi = beta_b + pi/2 - asin(d/l)` from each centre, and
//! `BELT = R_P (beta_a - phi) + l* + R_Q (phi - beta_c)`.
//! Writing `BELT = R_P beta_a - R_Q beta_c + G(l, beta_b, d)` with
//! `G = l* - d phi` gives the compact derivatives used below:
//! `G_l = l*/l`, `G_beta = -d`, `G_d = -phi`, `G_ll = d^2/(l^2 l*)`,
//! `G_ld = -d/(l l*)`, `G_beta d = -1`, `G_dd = 1/l*`.

use super::local::{spread_pq, zero_hess, Polar};
use super::{tracked_atan2, Bin, Dimension, Element, FormEval, Order};
use crate::error::ElementError;

/// Belt `BLT`: co-ordinates `xP yP beta_a xQ yQ beta_c R_P R_Q`, form
/// parameters `LENL`, `ANGB` (of P->Q) and `BELT` (belt length from a mark
/// on wheel a to a mark on wheel c). One negative radius: crossed belt.
pub struct Blt;

/// Positions of the bar's co-ordinates within the element.
const PQ: [usize; 4] = [0, 1, 3, 4];

impl Element for Blt {
    const NAME: &'static str = "BLT";
    const COORDS: &'static [&'static str] = &["xP", "yP", "beta_a", "xQ", "yQ", "beta_c", "R_P", "R_Q"];
    const FORMS: &'static [&'static str] = &["LENL", "ANGB", "BELT"];
    const COORD_DIMENSIONS: &'static [Dimension] = &[
        Dimension::Length,
        Dimension::Length,
        Dimension::Angle,
        Dimension::Length,
        Dimension::Length,
        Dimension::Angle,
        Dimension::Length,
        Dimension::Length,
    ];
    const FORM_DIMENSIONS: &'static [Dimension] = &[Dimension::Length, Dimension::Angle, Dimension::Length];

    /// The bar P->Q involves neither the wheels' angles nor their radii.
    fn depends(form: usize) -> u32 {
        if form < 2 {
            0b0001_1011
        } else {
            0b1111_1111
        }
    }

    fn eval(form: usize, x: &[f64], branch: &mut f64, order: Order, out: &mut FormEval) -> Result<(), ElementError> {
        const N: usize = 8;
        let bar = [x[0], x[1], x[3], x[4]];
        if form < 2 {
            let mut b = FormEval::default();
            Bin::eval(form, &bar, branch, order, &mut b)?;
            out.value = b.value;
            scatter_bar(&b, order, out, N);
            return Ok(());
        }
        let (dx, dy) = (bar[2] - bar[0], bar[3] - bar[1]);
        let p = Polar::new(dx, dy).ok_or(ElementError::CoincidentPoints)?;
        let beta = tracked_atan2(dy, dx, branch);
        let (ba, bc, rp, rq) = (x[2], x[5], x[6], x[7]);
        let (l, d) = (p.l, rp - rq);
        if l <= d.abs() {
            return Err(ElementError::NoBeltSpan { l, d: d.abs() });
        }
        let ls = ((l - d) * (l + d)).sqrt();
        let phi = beta + std::f64::consts::FRAC_PI_2 - (d / l).asin();
        out.value = rp * ba - rq * bc + ls - d * phi;
        if order == Order::Value {
            return Ok(());
        }
        let (g_l, g_b, g_d) = (ls / l, -d, -phi);
        // Length and angle of the bar with their derivatives in element order.
        let (mut lf, mut bf) = (FormEval::default(), FormEval::default());
        let (gl, hl) = p.length_derivs();
        spread_pq(gl, hl, 0, 2, 4, order, &mut lf);
        let (gb, hb) = p.angle_derivs();
        spread_pq(gb, hb, 0, 2, 4, order, &mut bf);
        out.grad[..N].fill(0.0);
        for (a, &k) in PQ.iter().enumerate() {
            out.grad[k] = g_l * lf.grad[a] + g_b * bf.grad[a];
        }
        out.grad[2] = rp;
        out.grad[5] = -rq;
        out.grad[6] = ba + g_d;
        out.grad[7] = -bc - g_d;
        if order < Order::Second {
            return Ok(());
        }
        let (g_ll, g_ld, g_bd, g_dd) = (d * d / (l * l * ls), -d / (l * ls), -1.0, 1.0 / ls);
        zero_hess(N, out);
        for (a, &k) in PQ.iter().enumerate() {
            for (b, &m) in PQ.iter().enumerate() {
                out.hess[k][m] = g_l * lf.hess[a][b] + g_b * bf.hess[a][b] + g_ll * lf.grad[a] * lf.grad[b];
            }
            // d = R_P - R_Q: +1 for R_P, -1 for R_Q.
            let cross = g_ld * lf.grad[a] + g_bd * bf.grad[a];
            out.hess[k][6] = cross;
            out.hess[6][k] = cross;
            out.hess[k][7] = -cross;
            out.hess[7][k] = -cross;
        }
        out.hess[2][6] = 1.0;
        out.hess[6][2] = 1.0;
        out.hess[5][7] = -1.0;
        out.hess[7][5] = -1.0;
        out.hess[6][6] = g_dd;
        out.hess[7][7] = g_dd;
        out.hess[6][7] = -g_dd;
        out.hess[7][6] = -g_dd;
        Ok(())
    }
}

/// Copies a bar form (evaluated on xP yP xQ yQ) into the element's order.
fn scatter_bar(b: &FormEval, order: Order, out: &mut FormEval, n: usize) {
    if order >= Order::First {
        out.grad[..n].fill(0.0);
        for (a, &k) in PQ.iter().enumerate() {
            out.grad[k] = b.grad[a];
        }
    }
    if order >= Order::Second {
        zero_hess(n, out);
        for (a, &k) in PQ.iter().enumerate() {
            for (c, &m) in PQ.iter().enumerate() {
                out.hess[k][m] = b.hess[a][c];
            }
        }
    }
}
