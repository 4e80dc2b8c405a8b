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
    /// 1 / l.
    pub r: f64,
}

impl Polar {
    /// `None` when d has zero or non-finite length. The length is
    /// `sqrt(dx^2 + dy^2)`: mechanism dimensions are far from the range
    /// where the squares over- or underflow, and it is several times
    /// cheaper than `hypot`.
    #[inline]
    pub fn new(dx: f64, dy: f64) -> Option<Polar> {
        let l = (dx * dx + dy * dy).sqrt();
        (l > 0.0 && l.is_finite()).then(|| {
            let r = 1.0 / l;
            Polar { l, c: dx * r, s: dy * r, r }
        })
    }

    /// Keeps the direction and reciprocal length in `aux[0..3]`.
    #[inline]
    pub fn stash(&self, aux: &mut [f64]) {
        aux[..3].copy_from_slice(&[self.c, self.s, self.r]);
    }

    /// The direction and reciprocal length kept by [`Self::stash`] (the
    /// length itself is not needed by the second derivatives).
    #[inline]
    pub fn unstash(aux: &[f64]) -> Polar {
        Polar { l: 1.0 / aux[2], c: aux[0], s: aux[1], r: aux[2] }
    }

    /// `e . w` for the unit vector e = (c, s) along d.
    #[inline]
    pub fn along(&self, w: [f64; 2]) -> f64 {
        self.c * w[0] + self.s * w[1]
    }

    /// `m . w` for the unit normal m = (-s, c) of d.
    #[inline]
    pub fn across(&self, w: [f64; 2]) -> f64 {
        self.c * w[1] - self.s * w[0]
    }

    /// Second derivative of the length along the changes `p`, `q` of d:
    /// `(m . p)(m . q) / l`.
    #[inline]
    pub fn length_second(&self, p: [f64; 2], q: [f64; 2]) -> f64 {
        self.across(p) * self.across(q) * self.r
    }

    /// Second derivative of the angle along the changes `p`, `q` of d:
    /// `-((e . p)(m . q) + (m . p)(e . q)) / l^2`.
    #[inline]
    pub fn angle_second(&self, p: [f64; 2], q: [f64; 2]) -> f64 {
        -(self.along(p) * self.across(q) + self.across(p) * self.along(q)) * (self.r * self.r)
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

/// The change of Q - P along the direction `w`, with P's co-ordinates at
/// local indices `ip, ip+1` and Q's at `iq, iq+1`.
#[inline]
pub(crate) fn diff(w: &[f64], ip: usize, iq: usize) -> [f64; 2] {
    [w[iq] - w[ip], w[iq + 1] - w[ip + 1]]
}

/// Second derivative of u (or v) of point R in a frame at P with angle
/// beta, along the directions `p` and `q` (see [`local_coordinate`] for the
/// Hessian it contracts). `(c, s)` is the frame's direction, `(u, v)` the
/// point's local co-ordinates, `rp`, `rq` the changes of R - P along p, q,
/// `bp`, `bq` the changes of beta along p, q and `hb` the second derivative
/// of beta along p, q.
#[inline]
pub(crate) fn local_second(
    axis: Axis,
    (c, s): (f64, f64),
    (u, v): (f64, f64),
    (rp, rq): ([f64; 2], [f64; 2]),
    (bp, bq): (f64, f64),
    hb: f64,
) -> f64 {
    let along = |w: [f64; 2]| c * w[0] + s * w[1];
    let across = |w: [f64; 2]| c * w[1] - s * w[0];
    match axis {
        Axis::U => across(rp) * bq + bp * across(rq) - u * bp * bq + v * hb,
        Axis::V => -(along(rp) * bq + bp * along(rq)) - v * bp * bq - u * hb,
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
