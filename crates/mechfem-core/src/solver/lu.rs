//! LU factorisation with partial pivoting, in place, on a buffer that is
//! allocated once per model. One factorisation of D^c serves every first-
//! and second-order solve at a position.
//!
//! Small matrices are stored dense. D^c of a large mechanism is sparse: each
//! row touches the few co-ordinates of its elements. [`Lu::for_pattern`]
//! then reorders rows and columns into a narrow band (reverse Cuthill-McKee)
//! and factorises only the band, so the cost grows with the number of
//! elements rather than with its cube.

use super::ordering::band_order;

/// An n x n matrix and, after [`Lu::factor`], its LU factors.
#[derive(Debug, Clone)]
pub struct Lu {
    store: Store,
}

#[derive(Debug, Clone)]
enum Store {
    Dense(Dense),
    Band(Band),
}

/// Where elimination broke down: column and pivot.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SingularPivot {
    /// Column of the failing pivot.
    pub column: usize,
    /// Its value.
    pub pivot: f64,
}

/// Below this size a matrix is always stored dense.
const BAND_MIN_N: usize = 32;

impl Lu {
    /// Dense storage for an n x n matrix, zeroed.
    pub fn new(n: usize) -> Lu {
        Lu { store: Store::Dense(Dense::new(n)) }
    }

    /// Storage for an n x n matrix whose structural non-zeros are, in row
    /// i, the columns `rows[i]` (columns may repeat). A large matrix whose
    /// pattern can be ordered into a band that is cheap to factorise gets
    /// banded storage; any other gets dense storage.
    pub fn for_pattern(n: usize, rows: &[Vec<usize>]) -> Lu {
        if n >= BAND_MIN_N {
            if let Some(o) = band_order(n, rows) {
                // Flops of banded against dense elimination.
                let band = (n * o.kl * (o.kl + o.ku + 1)) as f64;
                let dense = (n as f64).powi(3) / 3.0;
                if 4.0 * band < dense {
                    return Lu { store: Store::Band(Band::new(n, o.row_new, o.col_new, o.kl, o.ku)) };
                }
            }
        }
        Lu::new(n)
    }

    /// Size n.
    pub fn n(&self) -> usize {
        match &self.store {
            Store::Dense(d) => d.n,
            Store::Band(b) => b.n,
        }
    }

    /// Whether the matrix is stored as a band (see [`Lu::for_pattern`]).
    pub fn is_banded(&self) -> bool {
        matches!(self.store, Store::Band(_))
    }

    /// Sets every entry to zero before assembly.
    pub fn clear(&mut self) {
        match &mut self.store {
            Store::Dense(d) => d.a.fill(0.0),
            Store::Band(b) => b.a.fill(0.0),
        }
    }

    /// Position of entry (i, j) in [`Self::values_mut`], if it is stored.
    pub(crate) fn position(&self, i: usize, j: usize) -> Option<usize> {
        match &self.store {
            Store::Dense(d) => Some(i * d.n + j),
            Store::Band(b) => b.position(b.row_new[i], b.col_new[j]),
        }
    }

    /// The stored entries, for assembly through [`Self::position`].
    pub(crate) fn values_mut(&mut self) -> &mut [f64] {
        match &mut self.store {
            Store::Dense(d) => &mut d.a,
            Store::Band(b) => &mut b.a,
        }
    }

    /// Adds `v` to entry (i, j).
    ///
    /// # Panics
    /// When the matrix is banded and (i, j) lies outside the pattern it was
    /// made for.
    #[inline]
    pub fn add(&mut self, i: usize, j: usize, v: f64) {
        let p = self.position(i, j).expect("entry outside the pattern of a banded matrix");
        self.values_mut()[p] += v;
    }

    /// Replaces row i by the unit row e_col (the row of a single-co-ordinate
    /// element, used for the temporary input of free motion).
    ///
    /// # Panics
    /// When the matrix is banded and (i, col) lies outside its band: free
    /// motion uses dense storage.
    pub fn set_unit_row(&mut self, i: usize, col: usize) {
        match &mut self.store {
            Store::Dense(d) => {
                let n = d.n;
                d.a[i * n..(i + 1) * n].fill(0.0);
                d.a[i * n + col] = 1.0;
            }
            Store::Band(b) => {
                let r = b.row_new[i];
                let p = b.position(r, b.col_new[col]).expect("unit row outside the band of a banded matrix");
                b.a[r * b.w..(r + 1) * b.w].fill(0.0);
                b.a[p] = 1.0;
            }
        }
    }

    /// Entry (i, j) of the matrix (before factorisation; for a banded
    /// matrix, entries outside the band are zero).
    pub fn get(&self, i: usize, j: usize) -> f64 {
        self.position(i, j).map_or(0.0, |p| match &self.store {
            Store::Dense(d) => d.a[p],
            Store::Band(b) => b.a[p],
        })
    }

    /// Factorises in place. A pivot counts as zero when it is below
    /// `n * eps` times the largest entry of its column in the original
    /// matrix: the column is then, to working precision, a combination of
    /// the others.
    pub fn factor(&mut self) -> Result<(), SingularPivot> {
        match &mut self.store {
            Store::Dense(d) => d.factor(),
            Store::Band(b) => b.factor(),
        }
    }

    /// Solves A y = b in place (b becomes y), using the factors; `work`
    /// holds at least n values.
    pub fn solve(&self, b: &mut [f64], work: &mut [f64]) {
        match &self.store {
            Store::Dense(d) => d.solve(b, work),
            Store::Band(m) => m.solve(b, work),
        }
    }

    /// Determinant from the factors.
    pub fn det(&self) -> f64 {
        match &self.store {
            Store::Dense(d) => (0..d.n).fold(d.sign, |p, i| p * d.a[i * d.n + i]),
            Store::Band(b) => (0..b.n).fold(b.sign * b.order_sign, |p, i| p * b.a[i * b.w + b.kl]),
        }
    }
}

/// Whether a pivot of magnitude `best` counts as zero in a column whose
/// largest original entry is `scale` (a NaN pivot counts as zero too).
#[inline]
fn is_zero_pivot(best: f64, n: usize, scale: f64) -> bool {
    let floor = (n as f64) * f64::EPSILON * scale;
    best.partial_cmp(&floor) != Some(std::cmp::Ordering::Greater)
}

/// Dense row-major storage; `perm[i]` is the original row now at row i,
/// `inv_diag[i]` the reciprocal of U's diagonal entry i.
#[derive(Debug, Clone)]
struct Dense {
    n: usize,
    a: Vec<f64>,
    perm: Vec<usize>,
    sign: f64,
    scale: Vec<f64>,
    inv_diag: Vec<f64>,
}

/// Calls `$f::<N>` for the sizes that have a fixed-size path, `$general`
/// for the others.
macro_rules! by_size {
    ($n:expr, $f:ident, ($($arg:expr),*), $general:expr) => {
        match $n {
            1 => $f::<1>($($arg),*),
            2 => $f::<2>($($arg),*),
            3 => $f::<3>($($arg),*),
            4 => $f::<4>($($arg),*),
            5 => $f::<5>($($arg),*),
            6 => $f::<6>($($arg),*),
            7 => $f::<7>($($arg),*),
            8 => $f::<8>($($arg),*),
            9 => $f::<9>($($arg),*),
            10 => $f::<10>($($arg),*),
            11 => $f::<11>($($arg),*),
            12 => $f::<12>($($arg),*),
            13 => $f::<13>($($arg),*),
            14 => $f::<14>($($arg),*),
            15 => $f::<15>($($arg),*),
            16 => $f::<16>($($arg),*),
            _ => $general,
        }
    };
}

impl Dense {
    fn new(n: usize) -> Dense {
        Dense { n, a: vec![0.0; n * n], perm: (0..n).collect(), sign: 1.0, scale: vec![0.0; n], inv_diag: vec![0.0; n] }
    }

    fn factor(&mut self) -> Result<(), SingularPivot> {
        by_size!(self.n, factor_fixed, (self), self.factor_general())
    }

    fn factor_general(&mut self) -> Result<(), SingularPivot> {
        let n = self.n;
        let a = &mut self.a[..n * n];
        self.scale.fill(0.0);
        for row in a.chunks_exact(n) {
            for (s, v) in self.scale.iter_mut().zip(row) {
                *s = s.max(v.abs());
            }
        }
        for (j, p) in self.perm.iter_mut().enumerate() {
            *p = j;
        }
        self.sign = 1.0;
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
            if is_zero_pivot(best, n, self.scale[k]) {
                return Err(SingularPivot { column: k, pivot: a[p * n + k] });
            }
            if p != k {
                let (top, bottom) = a.split_at_mut(p * n);
                top[k * n..(k + 1) * n].swap_with_slice(&mut bottom[..n]);
                self.perm.swap(k, p);
                self.sign = -self.sign;
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
        Ok(())
    }

    fn solve(&self, b: &mut [f64], work: &mut [f64]) {
        by_size!(self.n, solve_fixed, (self, b), self.solve_general(b, work))
    }

    fn solve_general(&self, b: &mut [f64], work: &mut [f64]) {
        let n = self.n;
        let (a, w) = (&self.a[..n * n], &mut work[..n]);
        for (wi, &p) in w.iter_mut().zip(&self.perm) {
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
            w[i] = (w[i] - s) * self.inv_diag[i];
        }
        b[..n].copy_from_slice(w);
    }
}

/// [`Dense::factor_general`] for n = N, on a copy in fixed-size arrays;
/// rows are interchanged through an index and put in pivot order when the
/// factors are copied back. Each elimination step is its own instance of
/// [`eliminate`], so that every loop has a length known when compiling.
fn factor_fixed<const N: usize>(d: &mut Dense) -> Result<(), SingularPivot> {
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
    d.sign = sign;
    Ok(())
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

/// [`Dense::solve_general`] for n = N.
fn solve_fixed<const N: usize>(d: &Dense, b: &mut [f64]) {
    let mut w = [0.0f64; N];
    for (wi, &p) in w.iter_mut().zip(&d.perm) {
        *wi = b[p];
    }
    let a = &d.a[..N * N];
    for i in 1..N {
        let row = &a[i * N..i * N + N];
        let mut s = w[i];
        for j in 0..i {
            s -= row[j] * w[j];
        }
        w[i] = s;
    }
    let inv = &d.inv_diag[..N];
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

/// A band matrix: after reordering, row r has entries in columns
/// `r - kl ..= r + ku`; elimination with row interchanges fills up to
/// `r + ku + kl`. Row r stores columns `r - kl ..= r + ku + kl` at
/// `a[r*w..(r+1)*w]`. Multipliers stay where they were computed and the
/// interchanges `piv` are applied in order during the solve (as LAPACK's
/// banded LU does).
#[derive(Debug, Clone)]
struct Band {
    n: usize,
    kl: usize,
    ku: usize,
    w: usize,
    a: Vec<f64>,
    row_new: Vec<usize>,
    col_new: Vec<usize>,
    col_old: Vec<usize>,
    piv: Vec<usize>,
    scale: Vec<f64>,
    sign: f64,
    /// Sign of the row and column reordering: det(A) = order_sign det(reordered).
    order_sign: f64,
}

/// +1 for an even permutation, -1 for an odd one.
fn parity(p: &[usize]) -> f64 {
    let mut seen = vec![false; p.len()];
    let mut transpositions = 0;
    for s in 0..p.len() {
        let mut i = s;
        let mut len = 0;
        while !seen[i] {
            seen[i] = true;
            i = p[i];
            len += 1;
        }
        transpositions += len.max(1) - 1;
    }
    if transpositions % 2 == 0 {
        1.0
    } else {
        -1.0
    }
}

impl Band {
    fn new(n: usize, row_new: Vec<usize>, col_new: Vec<usize>, kl: usize, ku: usize) -> Band {
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
    fn position(&self, r: usize, c: usize) -> Option<usize> {
        (c + self.kl >= r && c <= r + self.ku).then(|| r * self.w + c + self.kl - r)
    }

    fn factor(&mut self) -> Result<(), SingularPivot> {
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

    fn solve(&self, b: &mut [f64], work: &mut [f64]) {
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::elements::fd::Rng;

    #[test]
    fn solves_and_gives_determinant() {
        let m = [[0.0, 2.0, 1.0], [1.0, 1.0, 0.0], [3.0, 0.0, 4.0]];
        let mut lu = Lu::new(3);
        for i in 0..3 {
            for j in 0..3 {
                lu.add(i, j, m[i][j]);
            }
        }
        lu.factor().unwrap();
        // det = 0*(4-0) - 2*(4-0) + 1*(0-3) = -11
        assert!((lu.det() + 11.0).abs() < 1e-12);
        let mut b = [3.0, 2.0, 7.0];
        let mut w = [0.0; 3];
        lu.solve(&mut b, &mut w);
        for i in 0..3 {
            let r: f64 = (0..3).map(|j| m[i][j] * b[j]).sum();
            assert!((r - [3.0, 2.0, 7.0][i]).abs() < 1e-12);
        }
    }

    #[test]
    fn reports_a_singular_matrix() {
        let mut lu = Lu::new(2);
        for (i, j, v) in [(0, 0, 1.0), (0, 1, 2.0), (1, 0, 2.0), (1, 1, 4.0)] {
            lu.add(i, j, v);
        }
        assert!(lu.factor().is_err());
    }

    /// A scrambled sparse matrix of blocks coupled in a chain, with a last
    /// row that touches the first columns (like the input row of a chain of
    /// loops), some zero diagonal entries so that pivoting is needed.
    fn chain_matrix(blocks: usize, rng: &mut Rng) -> (usize, Vec<(usize, usize, f64)>) {
        let n = 3 * blocks + 1;
        let mut entries = Vec::new();
        for blk in 0..blocks {
            for r in 0..3 {
                let row = 3 * blk + r;
                for c in (3 * blk).saturating_sub(2)..(3 * blk + 4).min(n) {
                    if (row + c) % 4 != 0 {
                        entries.push((row, c, rng.uniform(-1.0, 1.0)));
                    }
                }
            }
        }
        entries.push((n - 1, 0, 0.7));
        entries.push((n - 1, n - 1, 0.3));
        let scramble = |i: usize| (i * 7 + 3) % n;
        (n, entries.into_iter().map(|(i, j, v)| (scramble(i), j, v)).collect())
    }

    #[test]
    fn banded_storage_gives_the_dense_solution_and_determinant() {
        let mut rng = Rng::new(11);
        for blocks in [20, 60] {
            let (n, entries) = chain_matrix(blocks, &mut rng);
            let mut rows = vec![Vec::new(); n];
            for &(i, j, _) in &entries {
                rows[i].push(j);
            }
            let mut band = Lu::for_pattern(n, &rows);
            assert!(band.is_banded(), "{n} x {n} chain should be banded");
            let mut dense = Lu::new(n);
            for lu in [&mut band, &mut dense] {
                lu.clear();
                for &(i, j, v) in &entries {
                    lu.add(i, j, v);
                }
            }
            assert_eq!(band.get(entries[5].0, entries[5].1), dense.get(entries[5].0, entries[5].1));
            band.factor().unwrap();
            dense.factor().unwrap();
            let (db, dd) = (band.det(), dense.det());
            assert!((db - dd).abs() <= 1e-10 * dd.abs(), "det {db} vs {dd}");
            let rhs: Vec<f64> = (0..n).map(|i| (i as f64).sin()).collect();
            let (mut yb, mut yd, mut w) = (rhs.clone(), rhs.clone(), vec![0.0; n]);
            band.solve(&mut yb, &mut w);
            dense.solve(&mut yd, &mut w);
            let scale = yd.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            for (a, b) in yb.iter().zip(&yd) {
                assert!((a - b).abs() <= 1e-10 * scale, "{a} vs {b}");
            }
        }
    }

    #[test]
    fn banded_storage_reports_a_singular_matrix_in_original_columns() {
        let (n, mut entries) = chain_matrix(20, &mut Rng::new(3));
        // Make column 10 a copy of column 11 in every row.
        let copy: Vec<(usize, usize, f64)> =
            entries.iter().filter(|e| e.1 == 11).map(|&(i, _, v)| (i, 10, v)).collect();
        entries.retain(|e| e.1 != 10);
        entries.extend(copy);
        let mut rows = vec![Vec::new(); n];
        for &(i, j, _) in &entries {
            rows[i].push(j);
        }
        let mut lu = Lu::for_pattern(n, &rows);
        for &(i, j, v) in &entries {
            lu.add(i, j, v);
        }
        let s = lu.factor().unwrap_err();
        assert!(s.column == 10 || s.column == 11, "{s:?}");
    }

    #[test]
    fn small_matrices_stay_dense() {
        let rows = vec![vec![0, 1], vec![1, 2], vec![2, 0]];
        assert!(!Lu::for_pattern(3, &rows).is_banded());
    }
}
