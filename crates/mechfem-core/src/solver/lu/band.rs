//! Banded storage: a large D^c whose rows and columns were reordered into
//! a narrow band.

use super::{is_zero_pivot, parity, SingularPivot};

/// A band matrix: after reordering, row r has entries in columns
/// `r - kl ..= r + ku`; elimination with row interchanges fills up to
/// `r + ku + kl`. Row r stores columns `r - kl ..= r + ku + kl` at
/// `a[r*w..(r+1)*w]`. Multipliers stay where they were computed and the
/// interchanges `piv` are applied in order during the solve (as LAPACK's
/// banded LU does).
#[derive(Debug, Clone)]
pub(super) struct Band {
    pub(super) n: usize,
    kl: usize,
    ku: usize,
    pub(super) w: usize,
    pub(super) a: Vec<f64>,
    pub(super) row_new: Vec<usize>,
    pub(super) col_new: Vec<usize>,
    col_old: Vec<usize>,
    piv: Vec<usize>,
    scale: Vec<f64>,
    sign: f64,
    /// Sign of the row and column reordering: det(A) = order_sign det(reordered).
    order_sign: f64,
}

impl Band {
    pub(super) fn new(n: usize, row_new: Vec<usize>, col_new: Vec<usize>, kl: usize, ku: usize) -> Band {
        let w = 2 * kl + ku + 1;
        let mut col_old = vec![0; n];
        for (old, &new) in col_new.iter().enumerate() {
            col_old[new] = old;
        }
        let order_sign = parity(&row_new) * parity(&col_new);
        Band {
            n,
            kl,
            ku,
            w,
            a: vec![0.0; n * w],
            row_new,
            col_new,
            col_old,
            piv: vec![0; n],
            scale: vec![0.0; n],
            sign: 1.0,
            order_sign,
        }
    }

    /// Position of reordered entry (r, c) of the original band.
    #[inline]
    pub(super) fn position(&self, r: usize, c: usize) -> Option<usize> {
        (c + self.kl >= r && c <= r + self.ku).then(|| r * self.w + c + self.kl - r)
    }

    pub(super) fn det(&self) -> f64 {
        (0..self.n).fold(self.sign * self.order_sign, |p, i| p * self.a[i * self.w + self.kl])
    }

    pub(super) fn factor(&mut self) -> Result<(), SingularPivot> {
        let (n, kl, ku, w) = (self.n, self.kl, self.ku, self.w);
        self.scale.fill(0.0);
        for r in 0..n {
            for c in r.saturating_sub(kl)..(r + ku + 1).min(n) {
                let v = self.a[r * w + c + kl - r].abs();
                self.scale[c] = self.scale[c].max(v);
            }
        }
        self.sign = 1.0;
        let a = &mut self.a;
        for k in 0..n {
            let last = (k + kl).min(n - 1);
            let end = (k + ku + kl).min(n - 1);
            // Entry (i, k) of row i sits at i*w + k + kl - i.
            let at = |i: usize| i * w + k + kl - i;
            let mut p = k;
            let mut best = a[at(k)].abs();
            for i in k + 1..=last {
                let v = a[at(i)].abs();
                if v > best {
                    best = v;
                    p = i;
                }
            }
            if is_zero_pivot(best, n, self.scale[k]) {
                return Err(SingularPivot { column: self.col_old[k], pivot: a[at(p)] });
            }
            self.piv[k] = p;
            let len = end - k + 1;
            if p != k {
                let (top, bottom) = a.split_at_mut(at(p));
                top[at(k)..at(k) + len].swap_with_slice(&mut bottom[..len]);
                self.sign = -self.sign;
            }
            let (top, bottom) = a.split_at_mut((k + 1) * w);
            let pivot_row = &top[at(k)..at(k) + len];
            let pivot = pivot_row[0];
            for i in k + 1..=last {
                let start = at(i) - (k + 1) * w;
                let row = &mut bottom[start..start + len];
                let f = row[0] / pivot;
                row[0] = f;
                if f != 0.0 {
                    for (x, &y) in row[1..].iter_mut().zip(&pivot_row[1..]) {
                        *x -= f * y;
                    }
                }
            }
        }
        Ok(())
    }

    pub(super) fn solve(&self, b: &mut [f64], work: &mut [f64]) {
        let (n, kl, w) = (self.n, self.kl, self.w);
        let (a, z) = (&self.a, &mut work[..n]);
        for (i, &r) in self.row_new.iter().enumerate() {
            z[r] = b[i];
        }
        for k in 0..n {
            let p = self.piv[k];
            if p != k {
                z.swap(k, p);
            }
            let zk = z[k];
            if zk != 0.0 {
                for i in k + 1..=(k + kl).min(n - 1) {
                    z[i] -= a[i * w + k + kl - i] * zk;
                }
            }
        }
        let span = self.ku + kl;
        for r in (0..n).rev() {
            let end = (r + span).min(n - 1);
            let row = &a[r * w + kl..r * w + kl + (end - r) + 1];
            let s: f64 = row[1..].iter().zip(&z[r + 1..=end]).map(|(x, y)| x * y).sum();
            z[r] = (z[r] - s) / row[0];
        }
        for (j, &c) in self.col_new.iter().enumerate() {
            b[j] = z[c];
        }
    }
}
