//! The positions a one-DOF mechanism reached, kept as Newton's divided
//! differences for predicting the next one by polynomial extrapolation in
//! the input value.
//!
//! The order adapts to the step: terms are added while they still matter
//! (the stepper counts a ten-thousandth of the tolerance as mattering) and
//! still shrink. Fine steps need the quadratic or the cubic, coarse ones up
//! to degree seven, which at one-degree steps of a four-bar's crank
//! predicts the position to about 1e-10, so that most positions need no
//! Newton iteration at all. A term that no longer shrinks is made of the
//! deformations the positions were accepted with, amplified, and is left
//! out.
//!
//! The stepper may leave positions out ([`History::skip`]); the next
//! extrapolations then reach further ahead of the last position kept.

use crate::sizes::by_size;

/// Most positions kept (the degree of the extrapolation is one less).
const MAX_POINTS: usize = 8;

/// Divided differences of the last positions, newest first: row k holds
/// x[q_0, ..., q_k] (q_0 the newest input value), so that the polynomial
/// through them is x_0 + x[q_0, q_1](t - q_0) + x[q_0, q_1, q_2](t - q_0)(t - q_1) + ...
pub(super) struct History {
    n: usize,
    q: [f64; MAX_POINTS],
    diff: Vec<f64>,
    /// Scratch of [`History::push`]: one row of new differences.
    carry: Vec<f64>,
    /// The largest magnitude in each row of `diff` (a term's size without
    /// a pass over its row at every extrapolation).
    row_max: [f64; MAX_POINTS],
    /// Rows held.
    len: usize,
    /// Rows kept up to date: one more than the last extrapolation used,
    /// or more after [`History::deepen`].
    depth: usize,
    /// Terms beyond the constant the last extrapolation used.
    used: usize,
    /// A term below this changes no prediction that matters.
    tiny: f64,
    /// Positions reached since the last one added.
    skipped: usize,
}

impl History {
    /// A history for `n` moving co-ordinates; a term below `tiny` is
    /// negligible.
    pub(super) fn new(n: usize, tiny: f64) -> History {
        History {
            n,
            q: [0.0; MAX_POINTS],
            diff: vec![0.0; MAX_POINTS * n],
            carry: vec![0.0; n],
            row_max: [0.0; MAX_POINTS],
            len: 0,
            depth: 3,
            used: 0,
            tiny,
            skipped: 0,
        }
    }

    pub(super) fn clear(&mut self) {
        self.len = 0;
        self.skipped = 0;
    }

    /// Notes a position reached and not added.
    pub(super) fn skip(&mut self) {
        self.skipped += 1;
    }

    /// Positions reached since the last one added.
    pub(super) fn skipped(&self) -> usize {
        self.skipped
    }

    /// Adds the moving co-ordinates `x` reached at input value `q`.
    pub(super) fn push(&mut self, q: f64, x: &[f64]) {
        // Two positions at one input value have no divided difference: the
        // new one starts the history afresh.
        let keep = self.len.min(self.depth - 1);
        let len = if self.q[..keep].contains(&q) { 1 } else { keep + 1 };
        let mut inv = [0.0; MAX_POINTS];
        for k in 0..len - 1 {
            inv[k] = 1.0 / (q - self.q[k]);
        }
        self.q.copy_within(0..len - 1, 1);
        self.q[0] = q;
        // x[q, r_0..r_{k-1}] = (x[q, r_0..r_{k-2}] - x[r_0..r_{k-1}]) / (q - r_{k-1}).
        // Row by row, the new differences of every co-ordinate carried from
        // one row to the next (each co-ordinate's arithmetic is that of a
        // pass down its own column). The rows follow one another: for up to
        // 16 co-ordinates, a count known to the compiler keeps what is carried
        // in registers, where a carry through memory would wait for its own
        // store at every row (at coarse steps, where every row is kept, this
        // loop is a fifth of a positions-only run).
        let (diff, carry, inv) = (&mut self.diff, &mut self.carry, &inv[..len]);
        let row_max = by_size!(self.n, differences, (diff, x, inv), differences_in(diff, &mut carry[..self.n], x, inv));
        self.row_max = row_max;
        self.len = len;
        self.skipped = 0;
    }
}

/// [`differences_in`] of `N` co-ordinates, carried in an array of `N`.
fn differences<const N: usize>(diff: &mut [f64], x: &[f64], inv: &[f64]) -> [f64; MAX_POINTS] {
    differences_in(diff, &mut [0.0; N], x, inv)
}

/// The rows of divided differences `diff` (`carry.len()` co-ordinates a
/// row) with the position `x` added, what row k carries on multiplied by
/// `inv[k]`; the largest magnitude that went into each row.
#[inline(always)]
fn differences_in(diff: &mut [f64], carry: &mut [f64], x: &[f64], inv: &[f64]) -> [f64; MAX_POINTS] {
    carry.copy_from_slice(&x[..carry.len()]);
    let mut row_max = [0.0f64; MAX_POINTS];
    for ((row, &ik), largest) in diff.chunks_exact_mut(carry.len().max(1)).zip(inv).zip(&mut row_max) {
        for (old, new) in row.iter_mut().zip(carry.iter_mut()) {
            difference(old, new, ik, largest);
        }
    }
    row_max
}

/// [`weighted_in`] of `N` co-ordinates, the sum kept in an array of `N`.
fn weighted<const N: usize>(diff: &[f64], weights: &[f64], out: &mut [f64]) {
    let mut sum = [0.0f64; N];
    weighted_in(diff, weights, &mut sum);
    out[..N].copy_from_slice(&sum);
}

/// `out` = row 0 of `diff` (`out.len()` co-ordinates a row) plus row k
/// times `weights[k]` for every k from 1 on, added in that order.
#[inline(always)]
fn weighted_in(diff: &[f64], weights: &[f64], out: &mut [f64]) {
    let n = out.len();
    out.copy_from_slice(&diff[..n]);
    for (row, &w) in diff.chunks_exact(n.max(1)).zip(weights).skip(1) {
        for (o, v) in out.iter_mut().zip(row) {
            *o += w * v;
        }
    }
}

/// One co-ordinate's step down a row: the difference `new` carried from the
/// row above goes into the row (`old`) and the next row's is carried on;
/// `largest` keeps the largest magnitude carried in.
#[inline(always)]
fn difference(old: &mut f64, new: &mut f64, ik: f64, largest: &mut f64) {
    // (`f64::max` minds NaN, at thrice the cost; a NaN is left out either way.)
    if new.abs() > *largest {
        *largest = new.abs();
    }
    let next = (*new - *old) * ik;
    *old = *new;
    *new = next;
}

impl History {
    /// The extrapolation to input value `t` into `out`. `false` (and `out`
    /// untouched) with fewer than three positions, or for a step more than
    /// twice as long as the last one (counting the positions skipped since
    /// the last one added as steps of that length).
    pub(super) fn extrapolate(&mut self, t: f64, out: &mut [f64]) -> bool {
        let n = self.n;
        // (Written so that a NaN refuses too.)
        let short = (t - self.q[0]).abs() <= (2 + self.skipped) as f64 * (self.q[0] - self.q[1]).abs();
        if self.len < 3 || !short {
            return false;
        }
        // The weight of each row used: which rows are used depends on their
        // sizes only, and the sum is then made in one pass.
        let mut weights = [0.0; MAX_POINTS];
        let (mut w, mut last, mut used) = (1.0, f64::INFINITY, 0);
        for k in 1..self.len {
            w *= t - self.q[k - 1];
            let size = w.abs() * self.row_max[k];
            // Always the quadratic; beyond it, only terms that matter and shrink.
            let useful = size >= self.tiny && size < last;
            if k >= 3 && !useful {
                break;
            }
            weights[k] = w;
            last = size;
            used = k;
        }
        let (diff, weights) = (&self.diff, &weights[..=used]);
        by_size!(n, weighted, (diff, weights, out), weighted_in(diff, weights, out));
        // Rows beyond those used cost time at every position; the next one
        // is added when a prediction falls short (`deepen`), and kept while
        // it matters.
        self.depth = (used + 1).max(3);
        self.used = used;
        true
    }

    /// Keeps one more row from now on: the last extrapolation was not
    /// accurate enough to be accepted without correction.
    pub(super) fn deepen(&mut self) {
        self.depth = (self.depth + 1).min(MAX_POINTS);
    }

    /// The degree of the last extrapolation.
    pub(super) fn degree(&self) -> usize {
        self.used
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_polynomial_is_extrapolated_exactly() {
        // A cubic in two co-ordinates at uneven input values: the cubic term
        // is needed and the quartic one is zero.
        let f = |q: f64| [1.0 + 2.0 * q - q * q + 0.5 * q * q * q, (q - 0.3) * (q + 0.2)];
        let mut h = History::new(2, 1e-14);
        // As after a prediction that needed correcting.
        h.deepen();
        for q in [0.0, 0.1, 0.25, 0.3, 0.42] {
            h.push(q, &f(q));
        }
        let mut out = [0.0; 2];
        assert!(h.extrapolate(0.6, &mut out));
        let want = f(0.6);
        assert!((out[0] - want[0]).abs() < 1e-13 && (out[1] - want[1]).abs() < 1e-13, "{out:?} vs {want:?}");
    }

    #[test]
    fn a_smooth_curve_gets_the_degree_it_needs() {
        // sin at one-degree steps: the quadratic misses by about 1e-6, the
        // full history by about 1e-16.
        let step = 1f64.to_radians();
        let mut h = History::new(1, 1e-12);
        let mut worst = 0.0f64;
        for i in 0..40 {
            let q = i as f64 * step;
            let mut out = [0.0];
            if h.extrapolate(q, &mut out) {
                let error = (out[0] - q.sin()).abs();
                // As a Newton correction would report it.
                if error > 1e-12 {
                    h.deepen();
                }
                if i >= 20 {
                    worst = worst.max(error);
                }
            }
            h.push(q, &[q.sin()]);
        }
        assert!(worst < 1e-12, "{worst}");
        assert!(h.degree() >= 5, "degree {}", h.degree());
    }

    #[test]
    fn positions_skipped_are_extrapolated_past() {
        // A cubic at steps of 0.1: after two positions left out, the
        // extrapolation three steps ahead of the last one kept is exact.
        let f = |q: f64| 2.0 - q + 0.3 * q * q * q;
        let mut h = History::new(1, 1e-14);
        h.deepen();
        for q in [0.0, 0.1, 0.2, 0.3] {
            h.push(q, &[f(q)]);
        }
        let mut out = [0.0];
        // One step ahead, then (skipping) two and three.
        for (k, t) in [0.4, 0.5, 0.6].into_iter().enumerate() {
            assert!(h.extrapolate(t, &mut out), "step {k}");
            assert!((out[0] - f(t)).abs() < 1e-13, "{} vs {}", out[0], f(t));
            h.skip();
        }
        assert_eq!(h.skipped(), 3);
        // Five steps ahead is within (2 + 3) steps; six is not.
        assert!(h.extrapolate(0.79, &mut out) && !h.extrapolate(0.81, &mut out));
        // Adding a position starts the count again.
        h.push(0.4, &[f(0.4)]);
        assert_eq!(h.skipped(), 0);
    }

    #[test]
    fn the_same_input_value_twice_starts_afresh() {
        let mut h = History::new(1, 1e-12);
        for q in [0.0, 0.1, 0.2, 0.2] {
            h.push(q, &[q]);
        }
        assert_eq!(h.len, 1);
        assert!(!h.extrapolate(0.3, &mut [0.0]));
        assert!(h.diff.iter().all(|v| v.is_finite()));
    }
}
