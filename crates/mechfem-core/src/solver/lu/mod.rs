//! LU factorisation with partial pivoting, in place, on a buffer that is
//! allocated once per model. One factorisation of D^c serves every first-
//! and second-order solve at a position.
//!
//! D^c is sparse: each row touches the few co-ordinates of its elements.
//! [`Lu::for_pattern`] chooses the storage from the pattern, once per model:
//!
//! * blocks ([`blocks`]): rows and columns ordered so that D^c is block lower
//!   triangular, each diagonal block factorised on its own. The blocks are
//!   the groups of co-ordinates that must be solved together (a dyad of a
//!   four-bar is one); the rest of D^c only enters the solves.
//! * a band ([`band`]): a large block whose rows and columns reverse
//!   Cuthill-McKee gathers into a narrow band; only the band is factorised,
//!   so the cost grows with the number of elements rather than its cube.
//! * dense ([`dense`]): anything else, with fixed-size code up to 16.

mod band;
mod blocks;
mod dense;

use super::ordering::{band_order, block_order};
use band::Band;
use blocks::Blocks;
use dense::Dense;

/// An n x n matrix and, after [`Lu::factor`], its LU factors.
#[derive(Debug, Clone)]
pub struct Lu {
    store: Store,
}

#[derive(Debug, Clone)]
enum Store {
    Dense(Dense),
    Band(Band),
    Blocks(Blocks),
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
    /// i, the columns `rows[i]` (columns may repeat): blocks when the
    /// pattern splits into more than one, otherwise a band when the matrix
    /// is large and its band cheap to factorise, otherwise dense. Cold: it
    /// runs once for every structure of D^c on a thread (the solver keeps
    /// what it chose), and is kept out of the workspace's constructor.
    #[cold]
    pub fn for_pattern(n: usize, rows: &[Vec<usize>]) -> Lu {
        if let Some(order) = block_order(n, rows) {
            if order.starts.len() > 2 {
                return Lu { store: Store::Blocks(Blocks::new(n, rows, order)) };
            }
        }
        Self::unsplit(n, rows)
    }

    /// [`Self::for_pattern`] for a pattern that does not split into blocks.
    fn unsplit(n: usize, rows: &[Vec<usize>]) -> Lu {
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
            Store::Blocks(b) => b.n,
        }
    }

    /// Whether the matrix, or one of its blocks, is stored as a band (see
    /// [`Lu::for_pattern`]).
    pub fn is_banded(&self) -> bool {
        match &self.store {
            Store::Dense(_) => false,
            Store::Band(_) => true,
            Store::Blocks(b) => b.blocks.iter().any(blocks::Block::is_banded),
        }
    }

    /// The sizes of the diagonal blocks that are factorised on their own
    /// (one block, of size n, when the matrix does not split).
    pub fn block_sizes(&self) -> Vec<usize> {
        match &self.store {
            Store::Blocks(b) => b.blocks.iter().map(blocks::Block::n).collect(),
            _ => vec![self.n()],
        }
    }

    /// Sets every entry to zero before assembly.
    pub fn clear(&mut self) {
        self.values_mut().fill(0.0);
    }

    /// Position of entry (i, j) in [`Self::values_mut`], if it is stored.
    pub(crate) fn position(&self, i: usize, j: usize) -> Option<usize> {
        match &self.store {
            Store::Dense(d) => Some(i * d.n + j),
            Store::Band(b) => b.position(b.row_new[i], b.col_new[j]),
            Store::Blocks(b) => b.position(i, j),
        }
    }

    /// The stored entries, for assembly through [`Self::position`].
    pub(crate) fn values_mut(&mut self) -> &mut [f64] {
        match &mut self.store {
            Store::Dense(d) => &mut d.a,
            Store::Band(b) => &mut b.a,
            Store::Blocks(b) => &mut b.a,
        }
    }

    pub(crate) fn values(&self) -> &[f64] {
        match &self.store {
            Store::Dense(d) => &d.a,
            Store::Band(b) => &b.a,
            Store::Blocks(b) => &b.a,
        }
    }

    /// Adds `v` to entry (i, j).
    ///
    /// # Panics
    /// When the matrix is banded or split into blocks and (i, j) lies
    /// outside the pattern it was made for.
    #[cfg(test)]
    pub fn add(&mut self, i: usize, j: usize, v: f64) {
        let p = self.position(i, j).expect("entry outside the pattern of a sparse matrix");
        self.values_mut()[p] += v;
    }

    /// Replaces row i by the unit row e_col (the row of a single-co-ordinate
    /// element, used for the temporary input of free motion).
    ///
    /// # Panics
    /// When the matrix is not dense and (i, col) lies outside its pattern:
    /// free motion uses dense storage.
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
            Store::Blocks(_) => panic!("a unit row needs dense or banded storage"),
        }
    }

    /// Entry (i, j) of the matrix (before factorisation; entries outside
    /// the pattern of a sparse matrix are zero).
    pub fn get(&self, i: usize, j: usize) -> f64 {
        self.position(i, j).map_or(0.0, |p| self.values()[p])
    }

    /// Factorises in place. A pivot counts as zero when it is below
    /// `n * eps` times the largest entry of its column in the original
    /// matrix (n and the column of the diagonal block, for blocks): the
    /// column is then, to working precision, a combination of the others.
    pub fn factor(&mut self) -> Result<(), SingularPivot> {
        match &mut self.store {
            Store::Dense(d) => d.factor(),
            Store::Band(b) => b.factor(),
            Store::Blocks(b) => b.factor(),
        }
    }

    /// Solves A y = b in place (b becomes y), using the factors; `work`
    /// holds at least n values.
    pub fn solve(&self, b: &mut [f64], work: &mut [f64]) {
        match &self.store {
            Store::Dense(d) => d.solve(b, work),
            Store::Band(m) => m.solve(b, work),
            Store::Blocks(m) => m.solve(b, work),
        }
    }

    /// Solves A y = b and A z = c in place, as two [`Lu::solve`]s but in
    /// one pass where D^c is stored in blocks; `work` holds at least 2n
    /// values.
    pub fn solve_two(&self, b: &mut [f64], c: &mut [f64], work: &mut [f64]) {
        match &self.store {
            Store::Blocks(m) => m.solve_two(b, c, work),
            _ => {
                self.solve(b, work);
                self.solve(c, work);
            }
        }
    }

    /// The determinant of every diagonal block from the last factorisation,
    /// in the order the blocks are solved (one, det itself, when the
    /// matrix does not split): their signs tell the assembly branch of each
    /// group of co-ordinates found together (see [`Self::block_columns`]).
    pub fn block_dets(&self, out: &mut Vec<f64>) {
        out.clear();
        match &self.store {
            Store::Blocks(b) => b.block_dets(out),
            _ => out.push(self.det()),
        }
    }

    /// The columns of every diagonal block, in the order of [`Self::block_dets`].
    pub fn block_columns(&self) -> Vec<Vec<usize>> {
        match &self.store {
            Store::Blocks(b) => b.block_columns(),
            _ => vec![(0..self.n()).collect()],
        }
    }

    /// Determinant from the factors.
    pub fn det(&self) -> f64 {
        match &self.store {
            Store::Dense(d) => d.det(),
            Store::Band(b) => b.det(),
            Store::Blocks(b) => b.det(),
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
    fn block_determinants_tell_each_block_mirrored() {
        // Lower block triangular after scrambling: {0, 1}, then {2, 3} (2 x 2:
        // Cramer's rule), then with a block of three the dense factors.
        for third in [false, true] {
            let n = if third { 5 } else { 4 };
            let entries = |flip: f64| {
                let mut e = vec![(0, 0, 2.0), (0, 1, 1.0), (1, 0, 1.0), (1, 1, 3.0), (2, 0, 0.5)];
                e.extend([(2, 2, 1.0), (2, 3, 2.0 * flip), (3, 2, 3.0), (3, 3, 1.0 * flip), (3, 1, 0.25)]);
                if third {
                    e.extend([(2, 4, 1.0), (4, 2, 0.5), (4, 3, 1.0), (4, 4, 2.0)]);
                }
                e
            };
            let dets = |flip: f64| {
                let rows: Vec<Vec<usize>> =
                    (0..n).map(|i| entries(flip).iter().filter(|e| e.0 == i).map(|e| e.1).collect()).collect();
                let mut lu = Lu::for_pattern(n, &rows);
                for (i, j, v) in entries(flip) {
                    lu.add(i, j, v);
                }
                lu.factor().unwrap();
                let mut out = Vec::new();
                lu.block_dets(&mut out);
                assert!((out.iter().product::<f64>().abs() - lu.det().abs()).abs() < 1e-12 * lu.det().abs());
                assert_eq!(lu.block_columns().len(), out.len());
                out
            };
            let (a, b) = (dets(1.0), dets(-1.0));
            assert_eq!(a.len(), 2);
            assert!(a[0] * b[0] > 0.0 && a[1] * b[1] < 0.0, "{a:?} {b:?}");
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
            agree_after_factoring(&mut band, &mut dense);
        }
    }

    /// Factorises both; their determinants and the solutions of one
    /// right-hand side agree to 1e-10.
    fn agree_after_factoring(lu: &mut Lu, dense: &mut Lu) {
        let n = dense.n();
        lu.factor().unwrap();
        dense.factor().unwrap();
        let (dl, dd) = (lu.det(), dense.det());
        assert!((dl - dd).abs() <= 1e-10 * dd.abs(), "det {dl} vs {dd}");
        let rhs: Vec<f64> = (0..n).map(|i| (0.3 * i as f64).cos()).collect();
        let (mut yl, mut yd, mut w) = (rhs.clone(), rhs, vec![0.0; n]);
        lu.solve(&mut yl, &mut w);
        dense.solve(&mut yd, &mut w);
        let scale = yd.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        for (a, b) in yl.iter().zip(&yd) {
            assert!((a - b).abs() <= 1e-10 * scale, "{a} vs {b}");
        }
        // Two right-hand sides in one pass: each exactly as solved alone.
        let rhs2: Vec<f64> = (0..n).map(|i| 1.0 / (1.0 + i as f64)).collect();
        let (mut y1, mut y2, mut alone) = (yd.clone(), rhs2.clone(), rhs2);
        let mut w2 = vec![0.0; 2 * n];
        lu.solve_two(&mut y1, &mut y2, &mut w2);
        lu.solve(&mut alone, &mut w);
        let mut again = yd.clone();
        lu.solve(&mut again, &mut w);
        assert_eq!((y1, y2), (again, alone));
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

    /// A matrix of diagonal blocks of sizes 1, 2, 3 and a chain of 61 (one
    /// strongly connected block), with entries left of the blocks, rows and
    /// columns scrambled.
    fn block_matrix(rng: &mut Rng) -> (usize, Vec<(usize, usize, f64)>) {
        let (m, chain) = chain_matrix(20, rng);
        let mut entries = vec![(0, 0, 2.5), (1, 1, 0.0), (1, 2, 1.5), (2, 1, -0.7), (2, 2, 0.4), (2, 0, 3.0)];
        entries.extend([(3, 3, 1.0), (3, 4, 2.0), (4, 4, 0.5), (4, 5, -1.0), (5, 3, 0.25), (5, 5, 2.0)]);
        entries.extend([(4, 1, 0.9), (5, 0, -2.0)]);
        entries.extend(chain.into_iter().map(|(i, j, v)| (i + 6, j + 6, v)));
        entries.extend([(10, 2, 1.25), (30, 5, -0.5), (50, 0, 0.75)]);
        let n = m + 6;
        let (row, col) = (|i: usize| (i * 11 + 5) % n, |j: usize| (j * 13 + 2) % n);
        (n, entries.into_iter().map(|(i, j, v)| (row(i), col(j), v)).collect())
    }

    fn filled(n: usize, entries: &[(usize, usize, f64)]) -> (Lu, Lu) {
        let mut rows = vec![Vec::new(); n];
        for &(i, j, _) in entries {
            rows[i].push(j);
        }
        let (mut split, mut dense) = (Lu::for_pattern(n, &rows), Lu::new(n));
        for lu in [&mut split, &mut dense] {
            lu.clear();
            for &(i, j, v) in entries {
                lu.add(i, j, v);
            }
        }
        (split, dense)
    }

    #[test]
    fn blocks_give_the_dense_solution_and_determinant() {
        let (n, entries) = block_matrix(&mut Rng::new(5));
        let (mut split, mut dense) = filled(n, &entries);
        assert_eq!(split.block_sizes(), vec![1, 2, 3, 61]);
        assert!(split.is_banded(), "the block of 61 is a band");
        for &(i, j, _) in &entries {
            assert_eq!(split.get(i, j), dense.get(i, j));
        }
        agree_after_factoring(&mut split, &mut dense);
    }

    #[test]
    fn a_singular_block_is_reported_in_original_columns() {
        let (n, entries) = block_matrix(&mut Rng::new(8));
        // The 2 x 2 block [[0, 1.5], [-0.7, 0.4]] made singular: row 2 = row 1.
        let col = |j: usize| (j * 13 + 2) % n;
        let r2 = (2 * 11 + 5) % n;
        let mut entries: Vec<_> =
            entries.into_iter().filter(|e| e.0 != r2 || (e.1 != col(1) && e.1 != col(2))).collect();
        entries.extend([(r2, col(1), 0.0), (r2, col(2), 1.5)]);
        let (mut split, _) = filled(n, &entries);
        let s = split.factor().unwrap_err();
        assert!(s.column == col(1) || s.column == col(2), "{s:?}");
    }

    /// Whether the last factorisation left the blocks for Cramer's rule.
    fn by_cramer(lu: &Lu) -> bool {
        matches!(&lu.store, Store::Blocks(b) if b.cramer)
    }

    #[test]
    fn blocks_of_one_and_two_are_solved_by_cramers_rule() {
        // Blocks of 1, 2, 2 and 1 (a slider, two dyads, a gear), with
        // entries left of them; rows and columns scrambled; a zero diagonal
        // entry in a 2 x 2 block, which LU would have to pivot.
        let mut entries = vec![(0, 0, 2.5), (1, 1, 0.0), (1, 2, 1.5), (2, 1, -0.7), (2, 2, 0.4), (1, 0, 3.0)];
        entries.extend([(3, 3, 1e-3), (3, 4, 2.0), (4, 3, 0.5), (4, 4, -1.0), (3, 2, 0.25), (4, 0, -2.0)]);
        entries.extend([(5, 5, -4.0), (5, 3, 0.9), (5, 1, 0.6)]);
        let n = 6;
        let (row, col) = (|i: usize| (i * 5 + 2) % n, |j: usize| (j * 5 + 1) % n);
        let entries: Vec<_> = entries.into_iter().map(|(i, j, v)| (row(i), col(j), v)).collect();
        let (mut split, mut dense) = filled(n, &entries);
        assert_eq!(split.block_sizes(), vec![1, 2, 2, 1]);
        agree_after_factoring(&mut split, &mut dense);
        assert!(by_cramer(&split));
        // The blocks are left as assembled.
        assert!(entries.iter().all(|&(i, j, v)| split.get(i, j) == v));
        // A block of three is factorised.
        let mut three = filled(3, &[(0, 0, 1.0), (0, 1, 1.0), (1, 1, 1.0), (1, 2, 1.0), (2, 0, 1.0), (2, 2, 1.0)]).0;
        three.factor().unwrap();
        assert!(!by_cramer(&three));
    }

    #[test]
    fn a_singular_small_block_is_reported_in_original_columns() {
        // A slider (column 0) and a dyad (columns 1, 2) whose rows are
        // [2, 4] and [1, d]: singular at d = 2.
        let dyad = |d: f64| {
            let mut lu = filled(3, &[(0, 0, 1.0), (1, 1, 2.0), (1, 2, 4.0), (2, 1, 1.0), (2, 2, d), (2, 0, 1.0)]).0;
            assert_eq!(lu.block_sizes(), vec![1, 2]);
            lu.factor().map(|()| by_cramer(&lu))
        };
        // The factorisation's test: nearly dependent rows pass, dependent
        // ones and NaN do not, and the column is named.
        assert_eq!(dyad(2.0 + 1e-12), Ok(true));
        for d in [2.0, 2.0 + 1e-15, f64::NAN] {
            let s = dyad(d).unwrap_err();
            assert!(s.column == 1 || s.column == 2, "{d}: {s:?}");
        }
        let slider = |p: f64| {
            let mut lu = filled(2, &[(0, 0, p), (1, 1, 1.0), (1, 0, 1.0)]).0;
            lu.factor()
        };
        assert!(slider(1e-300).is_ok());
        assert_eq!(slider(0.0).unwrap_err().column, 0);
        assert_eq!(slider(f64::INFINITY).unwrap_err().column, 0);
    }

    #[test]
    fn small_matrices_stay_dense() {
        let rows = vec![vec![0, 1], vec![1, 2], vec![2, 0]];
        assert!(!Lu::for_pattern(3, &rows).is_banded());
    }
}
