//! The first-order variation of a body's motion and of the generalised
//! forces it spreads, for a variation of the co-ordinates, their
//! velocities and accelerations and of the centre (u, v): what the design
//! sensitivities of inverse dynamics are made of.
//!
//! With the frame angle's variation `d(beta)` (the angle co-ordinate's own,
//! or `(d x d(Q - P)) / l^2` for a bar), the centre's offset varies as
//! `dw = d(beta) w_perp + R(beta) (du, dv)`, and every formula of the
//! parent module differentiates by the product rule; for a bar,
//! `d(l^2) = 2 d . d(Q - P)`.

use super::{cross, dot, BodyMotion, Frame};

/// A first-order variation of everything a body's motion depends on.
#[derive(Debug, Clone, Copy)]
pub struct Variation<'a> {
    /// Of the co-ordinates (all N).
    pub x: &'a [f64],
    /// Of their velocities.
    pub xd: &'a [f64],
    /// Of their accelerations.
    pub xdd: &'a [f64],
    /// Of the centre's u.
    pub u: f64,
    /// Of the centre's v.
    pub v: f64,
}

fn perp(a: [f64; 2]) -> [f64; 2] {
    [-a[1], a[0]]
}

impl Frame {
    /// The variation of `w = R(beta) (u, v)` and of the frame angle.
    fn pose_variation(&self, x: &[f64], u: f64, v: f64, dx: &[f64], du: f64, dv: f64) -> ([f64; 2], f64) {
        let pose = self.pose(x, u, v);
        let unit = self.pose(x, 1.0, 0.0).w;
        let dbeta = match *self {
            Frame::Angle { beta, .. } => dx[beta],
            Frame::Bar { p, q } => {
                let d = Self::bar(p, q, x);
                cross(d, Self::bar(p, q, dx)) / dot(d, d)
            }
        };
        // R(beta) (du, dv) with R's columns (c, s) and (-s, c).
        let turned = [unit[0] * du - unit[1] * dv, unit[1] * du + unit[0] * dv];
        ([dbeta * pose.w_perp[0] + turned[0], dbeta * pose.w_perp[1] + turned[1]], dbeta)
    }

    /// The variation of [`Self::motion`] for the variation `d`.
    pub fn motion_variation(
        &self,
        x: &[f64],
        xd: &[f64],
        xdd: &[f64],
        u: f64,
        v: f64,
        d: &Variation<'_>,
    ) -> BodyMotion {
        let pose = self.pose(x, u, v);
        let (w, wp) = (pose.w, pose.w_perp);
        let (dw, _) = self.pose_variation(x, u, v, d.x, d.u, d.v);
        let dwp = perp(dw);
        let p = self.origin();
        let (bd, bdd, dbd, dbdd) = match *self {
            Frame::Angle { beta, .. } => (xd[beta], xdd[beta], d.xd[beta], d.xdd[beta]),
            Frame::Bar { p, q } => {
                let (e, ed, edd) = (Self::bar(p, q, x), Self::bar(p, q, xd), Self::bar(p, q, xdd));
                let (de, ded, dedd) = (Self::bar(p, q, d.x), Self::bar(p, q, d.xd), Self::bar(p, q, d.xdd));
                let l2 = dot(e, e);
                let dl2 = 2.0 * dot(e, de);
                let bd = cross(e, ed) / l2;
                let dbd = (cross(de, ed) + cross(e, ded)) / l2 - bd * dl2 / l2;
                // beta_ddot = a - 2 beta_dot b.
                let a = cross(e, edd) / l2;
                let da = (cross(de, edd) + cross(e, dedd)) / l2 - a * dl2 / l2;
                let b = dot(e, ed) / l2;
                let db = (dot(de, ed) + dot(e, ded)) / l2 - b * dl2 / l2;
                (bd, a - 2.0 * bd * b, dbd, da - 2.0 * (dbd * b + bd * db))
            }
        };
        let comp = |k: usize| {
            (
                d.x[p[k]] + dw[k],
                d.xd[p[k]] + dbd * wp[k] + bd * dwp[k],
                d.xdd[p[k]] + dbdd * wp[k] + bdd * dwp[k] - 2.0 * bd * dbd * w[k] - bd * bd * dw[k],
            )
        };
        let (c0, c1) = (comp(0), comp(1));
        BodyMotion { c: [c0.0, c1.0], c_dot: [c0.1, c1.1], c_ddot: [c0.2, c1.2], beta_dot: dbd, beta_ddot: dbdd }
    }

    /// The variation of [`Self::spread_terms`] (same co-ordinates, same
    /// order) for the variation `d` of the co-ordinates and centre and the
    /// variations `df`, `dm` of the force and moment.
    #[allow(clippy::too_many_arguments)]
    pub fn spread_terms_variation(
        &self,
        x: &[f64],
        u: f64,
        v: f64,
        (f, m): ([f64; 2], f64),
        d: &Variation<'_>,
        (df, dm): ([f64; 2], f64),
    ) -> [(usize, f64); 5] {
        let pose = self.pose(x, u, v);
        let (dw, _) = self.pose_variation(x, u, v, d.x, d.u, d.v);
        let p = self.origin();
        let moment = m + dot(f, pose.w_perp);
        let dmoment = dm + dot(df, pose.w_perp) + dot(f, perp(dw));
        let none = (usize::MAX, 0.0);
        match *self {
            Frame::Angle { beta, .. } => [(p[0], df[0]), (p[1], df[1]), (beta, dmoment), none, none],
            Frame::Bar { p, q } => {
                let (e, de) = (Self::bar(p, q, x), Self::bar(p, q, d.x));
                let l2 = dot(e, e);
                let k = 1.0 / l2;
                let dk = -2.0 * dot(e, de) / (l2 * l2);
                let dgx = -(de[1] * k * moment + e[1] * dk * moment + e[1] * k * dmoment);
                let dgy = de[0] * k * moment + e[0] * dk * moment + e[0] * k * dmoment;
                [(p[0], df[0] - dgx), (p[1], df[1] - dgy), (q[0], dgx), (q[1], dgy), none]
            }
        }
    }
}
