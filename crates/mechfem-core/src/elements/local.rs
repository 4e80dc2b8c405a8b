//! Shared calculus for elements built from a difference vector d = Q - P
//! (lengths and `atan2` angles) and for points in a rotating local frame
//! (the u, v form parameters of the ternary and rack elements).

use super::{FormEval, Order, MAX_COORDS};

/// Length and direction of d = (dx, dy), with gradients and Hessians taken
/// with respect to (dx, dy).
pub(crate) struct Polar {
    pub l: f64,
    pub c: f64,
    pub s: f64,
}

impl Polar {
    /// `None` when d has zero or non-finite length.
    #[inline]
    pub fn new(dx: f64, dy: f64) -> Option<Polar> {
        let l = dx.hypot(dy);
        (l > 0.0 && l.is_finite()).then(|| Polar { l, c: dx / l, s: dy / l })
    }

    /// d l / d(dx, dy) and the Hessian (eq. 5.23 with P's sign folded in).
    #[inline]
    pub fn length_derivs(&self) -> ([f64; 2], [[f64; 2]; 2]) {
        let (c, s, l) = (self.c, self.s, self.l);
        ([c, s], [[s * s / l, -s * c / l], [-s * c / l, c * c / l]])
    }

    /// d beta / d(dx, dy) and the Hessian (eq. 5.24).
    #[inline]
    pub fn angle_derivs(&self) -> ([f64; 2], [[f64; 2]; 2]) {
        let (c, s, l) = (self.c, self.s, self.l);
        let l2 = l * l;
        let (s2, c2) = (2.0 * s * c, c * c - s * s);
        ([-s / l, c / l], [[s2 / l2, -c2 / l2], [-c2 / l2, -s2 / l2]])
    }
}

/// Writes the derivatives of a function of d = Q - P into `out`, where P's
/// co-ordinates sit at local indices `ip, ip+1` and Q's at `iq, iq+1`.
/// Entries of other co-ordinates are zeroed for the first `n`.
#[inline]
pub(crate) fn spread_pq(
    g: [f64; 2],
    h: [[f64; 2]; 2],
    ip: usize,
    iq: usize,
    n: usize,
    order: Order,
    out: &mut FormEval,
) {
    if order >= Order::First {
        out.grad[..n].fill(0.0);
        for a in 0..2 {
            out.grad[ip + a] = -g[a];
            out.grad[iq + a] = g[a];
        }
    }
    if order >= Order::Second {
        zero_hess(n, out);
        for a in 0..2 {
            for b in 0..2 {
                out.hess[ip + a][ip + b] = h[a][b];
                out.hess[iq + a][iq + b] = h[a][b];
                out.hess[ip + a][iq + b] = -h[a][b];
                out.hess[iq + a][ip + b] = -h[a][b];
            }
        }
    }
}

/// Zeroes the leading n x n block of the Hessian.
#[inline]
pub(crate) fn zero_hess(n: usize, out: &mut FormEval) {
    for row in out.hess.iter_mut().take(n) {
        row[..n].fill(0.0);
    }
}

/// Which local co-ordinate of a point R in a frame at P with angle beta.
#[derive(Clone, Copy, PartialEq, Eq)]
pub(crate) enum Axis {
    /// `u`, along the frame's first axis.
    U,
    /// `v`, perpendicular to it.
    V,
}

/// The frame angle's first and second derivatives with respect to the
/// element's co-ordinates, and its cosine and sine.
pub(crate) struct FrameAngle {
    pub c: f64,
    pub s: f64,
    pub grad: [f64; MAX_COORDS],
    pub hess: [[f64; MAX_COORDS]; MAX_COORDS],
}

/// u or v of point R (indices `ir, ir+1`) in the frame with origin P
/// (indices `ip, ip+1`) and angle beta:
/// `u = dxr*c + dyr*s`, `v = -dxr*s + dyr*c` with (dxr, dyr) = R - P.
///
/// With e = (c, s), m = (-s, c) and J the map x -> R - P, the chain rule gives
/// `grad u = J'e + v grad beta`, `grad v = J'm - u grad beta`, and
/// `hess u = a b' + b a' - u b b' + v hess beta` (a = J'm, b = grad beta),
/// `hess v = -(e_ b' + b e_') - v b b' - u hess beta` (e_ = J'e).
pub(crate) fn local_coordinate(
    axis: Axis,
    x: &[f64],
    ip: usize,
    ir: usize,
    frame: &FrameAngle,
    n: usize,
    order: Order,
    out: &mut FormEval,
) {
    let (dxr, dyr) = (x[ir] - x[ip], x[ir + 1] - x[ip + 1]);
    let (c, s) = (frame.c, frame.s);
    let u = dxr * c + dyr * s;
    let v = -dxr * s + dyr * c;
    out.value = if axis == Axis::U { u } else { v };
    if order < Order::First {
        return;
    }
    // J'w for w = e and w = m: +w at R, -w at P.
    let jt = |w: [f64; 2]| {
        let mut r = [0.0; MAX_COORDS];
        r[ir] += w[0];
        r[ir + 1] += w[1];
        r[ip] -= w[0];
        r[ip + 1] -= w[1];
        r
    };
    let je = jt([c, s]);
    let jm = jt([-s, c]);
    let b = &frame.grad;
    for k in 0..n {
        out.grad[k] = match axis {
            Axis::U => je[k] + v * b[k],
            Axis::V => jm[k] - u * b[k],
        };
    }
    if order < Order::Second {
        return;
    }
    for k in 0..n {
        for l in 0..n {
            out.hess[k][l] = match axis {
                Axis::U => jm[k] * b[l] + b[k] * jm[l] - u * b[k] * b[l] + v * frame.hess[k][l],
                Axis::V => -(je[k] * b[l] + b[k] * je[l]) - v * b[k] * b[l] - u * frame.hess[k][l],
            };
        }
    }
}
