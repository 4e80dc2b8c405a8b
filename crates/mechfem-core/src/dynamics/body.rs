//! The frame an element gives a rigid body, and the body's motion and
//! forces expressed in the mechanism's co-ordinates.
//!
//! A body's centre is `c = P + R(beta) (u, v)`: its frame has its origin at
//! the element's first point P and its u-axis at the element's angle beta
//! (the angle of P->Q for BIN and TR2, the angle co-ordinate for HLF and
//! TR1). With `w = R(beta) (u, v)` and `w_perp` = w turned a quarter turn
//! counter-clockwise:
//!
//! * `c_dot = P_dot + beta_dot w_perp`,
//! * `c_ddot = P_ddot + beta_ddot w_perp - beta_dot^2 w`,
//! * a force F at c and a moment M on the body do the virtual work
//!   `F . dP + (M + F . w_perp) d(beta)`, which [`Frame::spread`] writes as
//!   generalised forces on the co-ordinates of P and of beta.
//!
//! For the angle of a bar P->Q, with `d = Q - P` and `l^2 = d . d`:
//! `beta_dot = (d x d_dot) / l^2` and
//! `beta_ddot = (d x d_ddot) / l^2 - 2 (d x d_dot)(d . d_dot) / l^4`.

use crate::elements::ElementType;

mod sensitivity;
pub use sensitivity::Variation;

/// Where a body's frame comes from: its origin P and its angle.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Frame {
    /// The angle is a co-ordinate of its own (HLF, TR1).
    Angle {
        /// Co-ordinate indices of P.
        p: [usize; 2],
        /// Co-ordinate index of the angle.
        beta: usize,
    },
    /// The angle is that of the bar P->Q (BIN, TR2).
    Bar {
        /// Co-ordinate indices of P.
        p: [usize; 2],
        /// Co-ordinate indices of Q.
        q: [usize; 2],
    },
}

/// The motion of a body's centre and frame at one instant.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BodyMotion {
    /// Centre of mass.
    pub c: [f64; 2],
    /// Its velocity.
    pub c_dot: [f64; 2],
    /// Its acceleration.
    pub c_ddot: [f64; 2],
    /// Angular velocity of the frame.
    pub beta_dot: f64,
    /// Angular acceleration of the frame.
    pub beta_ddot: f64,
}

/// The frame's direction and the centre's offset in the plane.
struct Pose {
    /// `R(beta) (u, v)`.
    w: [f64; 2],
    /// `w` turned a quarter turn counter-clockwise.
    w_perp: [f64; 2],
}

fn cross(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[1] - a[1] * b[0]
}

fn dot(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[0] + a[1] * b[1]
}

impl Frame {
    /// The frame of an element of type `ty` on co-ordinates `coords` (in
    /// the type's order); `None` for types without one (gears, racks,
    /// belts, single co-ordinates).
    pub fn of(ty: ElementType, coords: &[usize]) -> Option<Frame> {
        match ty {
            ElementType::Bin | ElementType::Tr2 => {
                Some(Frame::Bar { p: [coords[0], coords[1]], q: [coords[2], coords[3]] })
            }
            ElementType::Hlf | ElementType::Tr1 => Some(Frame::Angle { p: [coords[0], coords[1]], beta: coords[2] }),
            _ => None,
        }
    }

    fn origin(&self) -> [usize; 2] {
        match *self {
            Frame::Angle { p, .. } | Frame::Bar { p, .. } => p,
        }
    }

    /// `Q - P` of a bar frame at `x` (a vector of co-ordinates).
    fn bar(p: [usize; 2], q: [usize; 2], x: &[f64]) -> [f64; 2] {
        [x[q[0]] - x[p[0]], x[q[1]] - x[p[1]]]
    }

    fn pose(&self, x: &[f64], u: f64, v: f64) -> Pose {
        let (c, s) = match *self {
            Frame::Angle { beta, .. } => (x[beta].cos(), x[beta].sin()),
            Frame::Bar { p, q } => {
                let d = Self::bar(p, q, x);
                let l = d[0].hypot(d[1]);
                (d[0] / l, d[1] / l)
            }
        };
        let w = [u * c - v * s, u * s + v * c];
        Pose { w, w_perp: [-w[1], w[0]] }
    }

    /// The frame's angular velocity for co-ordinate velocities `xd`.
    fn beta_dot(&self, x: &[f64], xd: &[f64]) -> f64 {
        match *self {
            Frame::Angle { beta, .. } => xd[beta],
            Frame::Bar { p, q } => {
                let d = Self::bar(p, q, x);
                cross(d, Self::bar(p, q, xd)) / dot(d, d)
            }
        }
    }

    /// The unit vector of the frame's u-axis at co-ordinates `x`: the
    /// element's first side (P->Q of BIN and TR2, the angle co-ordinate of
    /// HLF and TR1); NaN where P and Q of a bar coincide.
    pub fn direction(&self, x: &[f64]) -> [f64; 2] {
        self.pose(x, 1.0, 0.0).w
    }

    /// The generalised forces [`Self::spread`] adds, as `(co-ordinate,
    /// value)` terms (at most five; unused ones hold `(usize::MAX, 0)`),
    /// so that the share of one body at one co-ordinate can be kept apart.
    pub fn spread_terms(&self, x: &[f64], u: f64, v: f64, f: [f64; 2], m: f64) -> [(usize, f64); 5] {
        let pose = self.pose(x, u, v);
        let p = self.origin();
        let moment = m + dot(f, pose.w_perp);
        let none = (usize::MAX, 0.0);
        match *self {
            Frame::Angle { beta, .. } => [(p[0], f[0]), (p[1], f[1]), (beta, moment), none, none],
            Frame::Bar { p, q } => {
                let d = Self::bar(p, q, x);
                let (gx, gy) = (-d[1] / dot(d, d) * moment, d[0] / dot(d, d) * moment);
                [(p[0], f[0] - gx), (p[1], f[1] - gy), (q[0], gx), (q[1], gy), none]
            }
        }
    }

    /// The centre `(u, v)` at co-ordinates `x`.
    pub fn centre(&self, x: &[f64], u: f64, v: f64) -> [f64; 2] {
        let w = self.pose(x, u, v).w;
        let p = self.origin();
        [x[p[0]] + w[0], x[p[1]] + w[1]]
    }

    /// The centre's velocity and the frame's angular velocity for
    /// co-ordinate velocities `xd` (or first-order transfer functions).
    pub fn velocity(&self, x: &[f64], xd: &[f64], u: f64, v: f64) -> ([f64; 2], f64) {
        let pose = self.pose(x, u, v);
        let p = self.origin();
        let bd = self.beta_dot(x, xd);
        ([xd[p[0]] + bd * pose.w_perp[0], xd[p[1]] + bd * pose.w_perp[1]], bd)
    }

    /// Position, velocity and acceleration of the centre `(u, v)` and the
    /// frame's angular velocity and acceleration, for co-ordinates `x`,
    /// their velocities `xd` and accelerations `xdd`.
    pub fn motion(&self, x: &[f64], xd: &[f64], xdd: &[f64], u: f64, v: f64) -> BodyMotion {
        let pose = self.pose(x, u, v);
        let p = self.origin();
        let (bd, bdd) = match *self {
            Frame::Angle { beta, .. } => (xd[beta], xdd[beta]),
            Frame::Bar { p, q } => {
                let (d, dd, ddd) = (Self::bar(p, q, x), Self::bar(p, q, xd), Self::bar(p, q, xdd));
                let l2 = dot(d, d);
                let bd = cross(d, dd) / l2;
                (bd, cross(d, ddd) / l2 - 2.0 * bd * dot(d, dd) / l2)
            }
        };
        let (w, wp) = (pose.w, pose.w_perp);
        BodyMotion {
            c: [x[p[0]] + w[0], x[p[1]] + w[1]],
            c_dot: [xd[p[0]] + bd * wp[0], xd[p[1]] + bd * wp[1]],
            c_ddot: [xdd[p[0]] + bdd * wp[0] - bd * bd * w[0], xdd[p[1]] + bdd * wp[1] - bd * bd * w[1]],
            beta_dot: bd,
            beta_ddot: bdd,
        }
    }

    /// Adds to `out` (one entry per co-ordinate) the generalised forces of
    /// a force `f` at the centre `(u, v)` and a moment `m` on the body:
    /// the coefficients of the virtual work `f . dc + m d(beta)` in the
    /// co-ordinates' variations.
    pub fn spread(&self, x: &[f64], u: f64, v: f64, f: [f64; 2], m: f64, out: &mut [f64]) {
        let pose = self.pose(x, u, v);
        let p = self.origin();
        out[p[0]] += f[0];
        out[p[1]] += f[1];
        let moment = m + dot(f, pose.w_perp);
        match *self {
            Frame::Angle { beta, .. } => out[beta] += moment,
            Frame::Bar { p, q } => {
                // d(beta) = (d x d(Q - P)) / l^2.
                let d = Self::bar(p, q, x);
                let (gx, gy) = (-d[1] / dot(d, d) * moment, d[0] / dot(d, d) * moment);
                out[q[0]] += gx;
                out[q[1]] += gy;
                out[p[0]] -= gx;
                out[p[1]] -= gy;
            }
        }
    }
}
