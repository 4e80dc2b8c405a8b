//! Dense storage: a small D^c, or a diagonal block of a larger one, with
//! fixed-size code paths up to 16. The factorisation works on borrowed
//! storage ([`Factors`]) so that blocks factorise in place in their
//! matrix's buffer.

use super::{is_zero_pivot, SingularPivot};
use crate::sizes::by_size;

/// Dense row-major storage of a whole matrix with its factors.
#[derive(Debug, Clone)]
pub(super) struct Dense {
    pub(super) n: usize,
    pub(super) a: Vec<f64>,
    perm: Vec<usize>,
    sign: f64,
    scale: Vec<f64>,
    inv_diag: Vec<f64>,
}

/// One n x n matrix, row-major in `a`, and after [`Factors::factor`] its
/// factors in place: `perm[i]` is the row of the matrix now at row i,
/// `inv_diag[i]` the reciprocal of U's diagonal entry i. `scale` is n
/// values of workspace.
pub(super) struct Factors<'a> {
    pub n: usize,
    pub a: &'a mut [f64],
    pub perm: &'a mut [usize],
    pub inv_diag: &'a mut [f64],
    pub scale: &'a mut [f64],
}

impl Dense {
    pub(super) fn new(n: usize) -> Dense {
        Dense { n, a: vec![0.0; n * n], perm: (0..n).collect(), sign: 1.0, scale: vec![0.0; n], inv_diag: vec![0.0; n] }
    }

    pub(super) fn factor(&mut self) -> Result<(), SingularPivot> {
        let (a, perm, inv_diag, scale) = (&mut self.a, &mut self.perm, &mut self.inv_diag, &mut self.scale);
        self.sign = Factors { n: self.n, a, perm, inv_diag, scale }.factor()?;
        Ok(())
    }

    pub(super) fn det(&self) -> f64 {
        det(self.n, &self.a, self.sign)
    }

    pub(super) fn solve(&self, b: &mut [f64], work: &mut [f64]) {
        solve(self.n, &self.a, &self.perm, &self.inv_diag, b, work);
    }
}

/// The determinant of factors with row-interchange sign `sign`.
#[inline]
pub(super) fn det(n: usize, a: &[f64], sign: f64) -> f64 {
    match n {
        // The blocks of sliders and dyads, multiplied in the loop's order.
        1 => sign * a[0],
        2 => sign * a[0] * a[3],
        _ => (0..n).fold(sign, |p, i| p * a[i * n + i]),
    }
}

/// Solves with the factors of [`Factors::factor`]: b becomes the solution;
/// `work` holds n values (sizes above 16 only).
#[inline]
pub(super) fn solve(n: usize, a: &[f64], perm: &[usize], inv_diag: &[f64], b: &mut [f64], work: &mut [f64]) {
    match n {
        1 => b[0] *= inv_diag[0],
        2 => [b[0], b[1]] = solve_2(a, perm[0], [inv_diag[0], inv_diag[1]], [b[0], b[1]]),
        _ => by_size!(n, solve_fixed, (a, perm, inv_diag, b), solve_general(n, a, perm, inv_diag, b, work)),
    }
}

/// [`solve`] of a 2 x 2 block, written out: `perm0` is `perm[0]`, `inv`
/// the reciprocal diagonal, `b` the right-hand side.
#[inline(always)]
pub(super) fn solve_2(a: &[f64], perm0: usize, inv: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    let (b0, b1) = if perm0 == 0 { (b[0], b[1]) } else { (b[1], b[0]) };
    let y1 = (b1 - a[2] * b0) * inv[1];
    [(b0 - a[1] * y1) * inv[0], y1]
}

fn solve_general(n: usize, a: &[f64], perm: &[usize], inv_diag: &[f64], b: &mut [f64], work: &mut [f64]) {
    let (a, w) = (&a[..n * n], &mut work[..n]);
    for (wi, &p) in w.iter_mut().zip(perm) {
        *wi = b[p];
    }
    for i in 1..n {
        let row = &a[i * n..i * n + i];
        let s: f64 = row.iter().zip(&w[..i]).map(|(x, y)| x * y).sum();
        w[i] -= s;
    }
    for i in (0..n).rev() {
        let row = &a[i * n + i + 1..(i + 1) * n];
        let s: f64 = row.iter().zip(&w[i + 1..]).map(|(x, y)| x * y).sum();
        w[i] = (w[i] - s) * inv_diag[i];
    }
    b[..n].copy_from_slice(w);
}

impl Factors<'_> {
    /// LU with partial pivoting in place; returns the sign of the row
    /// interchanges. Sizes one and two are written out here, and the code
    /// that picks a path by size is called from size three on: through it,
    /// the blocks of sliders and dyads cost about thrice as many
    /// instructions.
    #[inline]
    pub(super) fn factor(self) -> Result<f64, SingularPivot> {
        match self.n {
            1 => factor_1(self),
            2 => factor_2(self),
            _ => self.factor_larger(),
        }
    }

    /// [`Self::factor`] from size three on.
    #[inline(never)]
    fn factor_larger(self) -> Result<f64, SingularPivot> {
        by_size!(self.n, factor_fixed, (self), self.factor_general())
    }

    fn factor_general(self) -> Result<f64, SingularPivot> {
        let n = self.n;
        let a = &mut self.a[..n * n];
        let scale = &mut self.scale[..n];
        scale.fill(0.0);
        for row in a.chunks_exact(n) {
            for (s, v) in scale.iter_mut().zip(row) {
                *s = s.max(v.abs());
            }
        }
        for (j, p) in self.perm.iter_mut().enumerate() {
            *p = j;
        }
        let mut sign = 1.0;
        for k in 0..n {
            let mut p = k;
            let mut best = a[k * n + k].abs();
            for i in k + 1..n {
                let v = a[i * n + k].abs();
                if v > best {
                    best = v;
                    p = i;
                }
            }
            if is_zero_pivot(best, n, scale[k]) {
                return Err(SingularPivot { column: k, pivot: a[p * n + k] });
            }
            if p != k {
                let (top, bottom) = a.split_at_mut(p * n);
                top[k * n..(k + 1) * n].swap_with_slice(&mut bottom[..n]);
                self.perm.swap(k, p);
                sign = -sign;
            }
            let (top, bottom) = a.split_at_mut((k + 1) * n);
            let pivot_row = &top[k * n + k..(k + 1) * n];
            let inv = 1.0 / pivot_row[0];
            self.inv_diag[k] = inv;
            for row in bottom.chunks_exact_mut(n) {
                let f = row[k] * inv;
                row[k] = f;
                if f != 0.0 {
                    for (x, &y) in row[k + 1..].iter_mut().zip(&pivot_row[1..]) {
                        *x -= f * y;
                    }
                }
            }
        }
        Ok(sign)
    }
}

/// A 1 x 1 block (a slider's co-ordinate, a gear's angle).
#[inline(always)]
fn factor_1(d: Factors<'_>) -> Result<f64, SingularPivot> {
    let p = d.a[0];
    if is_zero_pivot(p.abs(), 1, p.abs()) {
        return Err(SingularPivot { column: 0, pivot: p });
    }
    d.perm[0] = 0;
    d.inv_diag[0] = 1.0 / p;
    Ok(1.0)
}

/// A 2 x 2 block (the joint of a dyad), written out: through the general
/// fixed-size path, copying the factors back costs more than computing them.
#[inline(always)]
fn factor_2(d: Factors<'_>) -> Result<f64, SingularPivot> {
    let [a00, a01, a10, a11] = [d.a[0], d.a[1], d.a[2], d.a[3]];
    let scale = [a00.abs().max(a10.abs()), a01.abs().max(a11.abs())];
    let swap = a10.abs() > a00.abs();
    let (p, q, r, s) = if swap { (a10, a11, a00, a01) } else { (a00, a01, a10, a11) };
    if is_zero_pivot(p.abs(), 2, scale[0]) {
        return Err(SingularPivot { column: 0, pivot: p });
    }
    let inv0 = 1.0 / p;
    let l = r * inv0;
    let u = s - l * q;
    if is_zero_pivot(u.abs(), 2, scale[1]) {
        return Err(SingularPivot { column: 1, pivot: u });
    }
    d.a[0] = p;
    d.a[1] = q;
    d.a[2] = l;
    d.a[3] = u;
    d.perm[0] = usize::from(swap);
    d.perm[1] = usize::from(!swap);
    d.inv_diag[0] = inv0;
    d.inv_diag[1] = 1.0 / u;
    Ok(if swap { -1.0 } else { 1.0 })
}

/// [`Factors::factor_general`] for n = N, on a copy in fixed-size arrays;
/// rows are interchanged through an index and put in pivot order when the
/// factors are copied back. Each elimination step is its own instance of
/// [`eliminate`], so that every loop has a length known when compiling.
fn factor_fixed<const N: usize>(d: Factors<'_>) -> Result<f64, SingularPivot> {
    let mut a = [[0.0f64; N]; N];
    for (row, src) in a.iter_mut().zip(d.a.chunks_exact(N)) {
        row.copy_from_slice(src);
    }
    let mut scale = [0.0f64; N];
    for row in &a {
        for j in 0..N {
            let v = row[j].abs();
            if v > scale[j] {
                scale[j] = v;
            }
        }
    }
    let mut rows = [0usize; N];
    for (j, p) in rows.iter_mut().enumerate() {
        *p = j;
    }
    let mut inv_diag = [0.0f64; N];
    let mut sign = 1.0;
    macro_rules! steps {
        ($($k:literal)*) => {
            $( eliminate::<N, $k>(&mut a, &mut rows, &scale, &mut inv_diag, &mut sign)?; )*
        };
    }
    steps!(0 1 2 3 4 5 6 7 8 9 10 11 12 13 14 15);
    for ((dst, &r), p) in d.a.chunks_exact_mut(N).zip(&rows).zip(d.perm.iter_mut()) {
        dst.copy_from_slice(&a[r]);
        *p = r;
    }
    d.inv_diag[..N].copy_from_slice(&inv_diag);
    Ok(sign)
}

/// Step K of the elimination of [`factor_fixed`] (nothing when K >= N).
#[inline(always)]
fn eliminate<const N: usize, const K: usize>(
    a: &mut [[f64; N]; N],
    rows: &mut [usize; N],
    scale: &[f64; N],
    inv_diag: &mut [f64; N],
    sign: &mut f64,
) -> Result<(), SingularPivot> {
    if K >= N {
        return Ok(());
    }
    let mut p = K;
    let mut best = a[rows[K]][K].abs();
    for i in K + 1..N {
        let v = a[rows[i]][K].abs();
        if v > best {
            best = v;
            p = i;
        }
    }
    if is_zero_pivot(best, N, scale[K]) {
        return Err(SingularPivot { column: K, pivot: a[rows[p]][K] });
    }
    if p != K {
        rows.swap(K, p);
        *sign = -*sign;
    }
    let pivot_row = a[rows[K]];
    let inv = 1.0 / pivot_row[K];
    inv_diag[K] = inv;
    for i in K + 1..N {
        let row = &mut a[rows[i]];
        let f = row[K] * inv;
        row[K] = f;
        for j in K + 1..N {
            row[j] -= f * pivot_row[j];
        }
    }
    Ok(())
}

/// [`solve_general`] for n = N.
#[inline]
fn solve_fixed<const N: usize>(a: &[f64], perm: &[usize], inv_diag: &[f64], b: &mut [f64]) {
    let mut w = [0.0f64; N];
    for (wi, &p) in w.iter_mut().zip(perm) {
        *wi = b[p];
    }
    let a = &a[..N * N];
    for i in 1..N {
        let row = &a[i * N..i * N + N];
        let mut s = w[i];
        for j in 0..i {
            s -= row[j] * w[j];
        }
        w[i] = s;
    }
    let inv = &inv_diag[..N];
    for i in (0..N).rev() {
        let row = &a[i * N..i * N + N];
        let mut s = w[i];
        for j in i + 1..N {
            s -= row[j] * w[j];
        }
        w[i] = s * inv[i];
    }
    b[..N].copy_from_slice(&w);
}
