//! Block lower triangular storage: rows and columns reordered (see
//! [`block_order`](crate::solver::ordering::block_order)) so that every row
//! touches only its own diagonal block and earlier ones. Each diagonal
//! block is factorised on its own: in place when dense, through an [`Lu`] of
//! its own when it is large enough for a band; when every block is of one
//! or two, only by its determinant, for Cramer's rule. The entries left of the
//! blocks are kept row by row and only enter the solves. det(D^c) is the
//! product of the blocks' determinants, so D^c is singular exactly when a
//! block is.

use super::dense::{self, Factors};
use super::{is_zero_pivot, parity, Lu, SingularPivot};
use crate::solver::ordering::BlockOrder;

#[derive(Debug, Clone)]
pub(super) struct Blocks {
    pub(super) n: usize,
    /// Every block's storage in turn, then the entries left of the blocks.
    pub(super) a: Vec<f64>,
    pub(super) blocks: Vec<Block>,
    /// Where the entries left of the blocks start in `a`.
    left_base: usize,
    row_new: Vec<usize>,
    col_new: Vec<usize>,
    col_old: Vec<usize>,
    /// The block of every reordered row (and column).
    block_of: Vec<usize>,
    /// Reordered row r's entries left of its block: reordered columns
    /// `left_cols[left_ptr[r]..left_ptr[r + 1]]`, values at the same places
    /// after `left_base` in `a`.
    left_ptr: Vec<usize>,
    left_cols: Vec<usize>,
    /// Row order and U's reciprocal diagonal of the dense blocks, by
    /// reordered row, and workspace.
    perm: Vec<usize>,
    inv_diag: Vec<f64>,
    scale: Vec<f64>,
    order_sign: f64,
    /// Every block in original rows and columns when all are dense and of
    /// size one or two (empty otherwise), for the solves by Cramer's rule.
    small: Vec<Small>,
    /// The original column of every entry left of the blocks.
    left_old: Vec<usize>,
    /// Whether the last factorisation left every block as assembled, with
    /// the reciprocal of its determinant in `inv_diag` at its first row, for
    /// Cramer's rule (see [`Self::factor`]).
    pub(super) cramer: bool,
    /// det of the whole matrix from that factorisation.
    cramer_det: f64,
}

/// A block of one or two in the original numbering: Cramer's rule reads
/// the right-hand side and writes the solution in place, without the
/// passes into and out of the block order (a good part of the solve of a
/// mechanism of sliders and dyads, whose blocks are all of one or two).
#[derive(Debug, Clone)]
struct Small {
    /// Original rows and columns; a block of one repeats its own.
    rows: [usize; 2],
    cols: [usize; 2],
    two: bool,
    /// Its first reordered row (where its reciprocal determinant is) and
    /// its storage.
    start: usize,
    base: usize,
    /// Its rows' entries left of the block: `ptr[i]..ptr[i + 1]` after
    /// `left_base` in `a` (columns in `left_old`).
    ptr: [usize; 3],
}

/// A diagonal block: reordered rows and columns `start..end`, its storage
/// at `a[base..]`.
#[derive(Debug, Clone)]
pub(super) struct Block {
    start: usize,
    end: usize,
    base: usize,
    /// Sign of the row interchanges of a dense block.
    sign: f64,
    /// A large block stored as a band; its entries are copied in to factorise.
    band: Option<Lu>,
}

impl Block {
    pub(super) fn n(&self) -> usize {
        self.end - self.start
    }

    pub(super) fn is_banded(&self) -> bool {
        self.band.is_some()
    }

    fn len(&self) -> usize {
        self.band.as_ref().map_or(self.n() * self.n(), |lu| lu.values().len())
    }
}

impl Blocks {
    pub(super) fn new(n: usize, rows: &[Vec<usize>], order: BlockOrder) -> Blocks {
        let BlockOrder { row_new, col_new, starts } = order;
        let n_blocks = starts.len() - 1;
        let mut block_of = vec![0; n];
        for b in 0..n_blocks {
            block_of[starts[b]..starts[b + 1]].fill(b);
        }
        let mut col_old = vec![0; n];
        for (old, &new) in col_new.iter().enumerate() {
            col_old[new] = old;
        }
        // Every reordered row's columns, split into its block's and the rest.
        let mut inside: Vec<Vec<usize>> = vec![Vec::new(); n];
        let mut left: Vec<Vec<usize>> = vec![Vec::new(); n];
        for (i, cols) in rows.iter().enumerate() {
            let r = row_new[i];
            for &c in cols {
                let c = col_new[c];
                if block_of[c] == block_of[r] {
                    inside[r].push(c - starts[block_of[r]]);
                } else {
                    left[r].push(c);
                }
            }
        }
        let mut blocks = Vec::with_capacity(n_blocks);
        let mut base = 0;
        for b in 0..n_blocks {
            let (start, end) = (starts[b], starts[b + 1]);
            let lu = Lu::unsplit(end - start, &inside[start..end]);
            let block = Block { start, end, base, sign: 1.0, band: lu.is_banded().then_some(lu) };
            base += block.len();
            blocks.push(block);
        }
        let mut left_ptr = vec![0];
        let mut left_cols = Vec::new();
        for mut cols in left {
            cols.sort_unstable();
            cols.dedup();
            left_cols.extend(cols);
            left_ptr.push(left_cols.len());
        }
        let order_sign = parity(&row_new) * parity(&col_new);
        let mut row_old = vec![0; n];
        for (old, &new) in row_new.iter().enumerate() {
            row_old[new] = old;
        }
        let all_small = blocks.iter().all(|b| b.band.is_none() && b.n() <= 2);
        let small = if all_small {
            let last = |b: &Block| b.end - 1;
            blocks
                .iter()
                .map(|b| Small {
                    rows: [row_old[b.start], row_old[last(b)]],
                    cols: [col_old[b.start], col_old[last(b)]],
                    two: b.n() == 2,
                    start: b.start,
                    base: b.base,
                    ptr: [left_ptr[b.start], left_ptr[b.start + 1], left_ptr[b.end]],
                })
                .collect()
        } else {
            Vec::new()
        };
        let left_old = left_cols.iter().map(|&c| col_old[c]).collect();
        Blocks {
            n,
            a: vec![0.0; base + left_cols.len()],
            blocks,
            left_base: base,
            row_new,
            col_new,
            col_old,
            block_of,
            left_ptr,
            left_cols,
            perm: vec![0; n],
            inv_diag: vec![0.0; n],
            scale: vec![0.0; n],
            order_sign,
            small,
            left_old,
            cramer: false,
            cramer_det: f64::NAN,
        }
    }

    /// Position of original entry (i, j) in `a`, if it is in the pattern.
    pub(super) fn position(&self, i: usize, j: usize) -> Option<usize> {
        let (r, c) = (self.row_new[i], self.col_new[j]);
        let blk = &self.blocks[self.block_of[r]];
        if (blk.start..blk.end).contains(&c) {
            let (r, c) = (r - blk.start, c - blk.start);
            return match &blk.band {
                Some(lu) => lu.position(r, c).map(|p| blk.base + p),
                None => Some(blk.base + r * blk.n() + c),
            };
        }
        let range = self.left_ptr[r]..self.left_ptr[r + 1];
        let k = self.left_cols[range.clone()].binary_search(&c).ok()?;
        Some(self.left_base + range.start + k)
    }

    /// Factorises every block. Blocks of one and two only (the sliders and
    /// dyads of a mechanism made of them) are left as they are and solved
    /// by Cramer's rule: their determinants are all a factorisation needs,
    /// and a block's solve is then two products and a difference per
    /// unknown, where the block solve's time goes into the chain from
    /// block to block. A block that fails [`Self::cramer`]'s test is
    /// factorised after all, which names the column that failed.
    pub(super) fn factor(&mut self) -> Result<(), SingularPivot> {
        self.cramer = !self.small.is_empty() && self.cramer();
        if self.cramer {
            return Ok(());
        }
        for blk in &mut self.blocks {
            let (s, e, m) = (blk.start, blk.end, blk.n());
            let storage = &mut self.a[blk.base..blk.base + blk.len()];
            let result = match &mut blk.band {
                Some(lu) => {
                    lu.values_mut().copy_from_slice(storage);
                    lu.factor()
                }
                None => Factors {
                    n: m,
                    a: storage,
                    perm: &mut self.perm[s..e],
                    inv_diag: &mut self.inv_diag[s..e],
                    scale: &mut self.scale[s..e],
                }
                .factor()
                .map(|sign| blk.sign = sign),
            };
            result.map_err(|p| SingularPivot { column: self.col_old[s + p.column], pivot: p.pivot })?;
        }
        Ok(())
    }

    /// Block forward substitution: each block's right-hand side less the
    /// entries left of it times the solution found so far. `work` holds n
    /// values.
    pub(super) fn solve(&self, b: &mut [f64], work: &mut [f64]) {
        if self.cramer {
            self.solve_small([b], work);
        } else {
            self.solve_k([b], work);
        }
    }

    /// [`Self::solve`] for two right-hand sides at once; `work` holds 2n
    /// values.
    pub(super) fn solve_two(&self, b: &mut [f64], c: &mut [f64], work: &mut [f64]) {
        if self.cramer {
            self.solve_small([b, c], work);
        } else {
            self.solve_k([b, c], work);
        }
    }

    /// The solve for K right-hand sides together. Its time goes into the
    /// chain from block to block (each waits for the unknowns before it),
    /// so independent right-hand sides in one pass overlap their chains;
    /// blocks of one and two are solved inline, without a call.
    fn solve_k<const K: usize>(&self, mut rhs: [&mut [f64]; K], work: &mut [f64]) {
        let n = self.n;
        if n == 0 {
            return;
        }
        let mut chunks = work.chunks_exact_mut(n);
        let mut z: [&mut [f64]; K] = std::array::from_fn(|_| chunks.next().expect("K n values of workspace"));
        for (zk, bk) in z.iter_mut().zip(rhs.iter()) {
            for (&r, &v) in self.row_new.iter().zip(bk.iter()) {
                zk[r] = v;
            }
        }
        let left = &self.a[self.left_base..];
        for blk in &self.blocks {
            let (s, e) = (blk.start, blk.end);
            for r in s..e {
                let range = self.left_ptr[r]..self.left_ptr[r + 1];
                let mut v: [f64; K] = std::array::from_fn(|k| z[k][r]);
                for (&c, &l) in self.left_cols[range.clone()].iter().zip(&left[range]) {
                    for (vk, zk) in v.iter_mut().zip(z.iter()) {
                        *vk -= l * zk[c];
                    }
                }
                for (zk, vk) in z.iter_mut().zip(v) {
                    zk[r] = vk;
                }
            }
            match (&blk.band, e - s) {
                (None, 1) => {
                    let d = self.inv_diag[s];
                    for zk in z.iter_mut() {
                        zk[s] *= d;
                    }
                }
                (None, 2) => {
                    let a = &self.a[blk.base..blk.base + 4];
                    let (p0, inv) = (self.perm[s], [self.inv_diag[s], self.inv_diag[s + 1]]);
                    for zk in z.iter_mut() {
                        [zk[s], zk[s + 1]] = dense::solve_2(a, p0, inv, [zk[s], zk[s + 1]]);
                    }
                }
                // `rhs` is free until the end: the blocks' workspace.
                (None, m) => {
                    for (zk, bk) in z.iter_mut().zip(rhs.iter_mut()) {
                        let a = &self.a[blk.base..];
                        dense::solve(m, a, &self.perm[s..e], &self.inv_diag[s..e], &mut zk[s..e], &mut bk[..m]);
                    }
                }
                (Some(lu), m) => {
                    for (zk, bk) in z.iter_mut().zip(rhs.iter_mut()) {
                        lu.solve(&mut zk[s..e], &mut bk[..m]);
                    }
                }
            }
        }
        for (zk, bk) in z.iter().zip(rhs.iter_mut()) {
            for (j, &c) in self.col_new.iter().enumerate() {
                bk[j] = zk[c];
            }
        }
    }

    /// [`Self::solve_k`] by Cramer's rule on blocks left as assembled (see
    /// [`Self::factor`]), in the original numbering: the right-hand sides
    /// are copied to `work` (K n values), and each block's unknowns are
    /// written in place as soon as they are known, for the blocks after it.
    fn solve_small<const K: usize>(&self, mut x: [&mut [f64]; K], work: &mut [f64]) {
        let n = self.n;
        let mut chunks = work.chunks_exact_mut(n.max(1));
        let mut b: [&mut [f64]; K] = std::array::from_fn(|_| chunks.next().expect("K n values of workspace"));
        for (bk, xk) in b.iter_mut().zip(x.iter()) {
            bk[..n].copy_from_slice(&xk[..n]);
        }
        let left = &self.a[self.left_base..];
        for blk in &self.small {
            let inv = self.inv_diag[blk.start];
            let v0 = self.reduced(blk, 0, &b, &x, left);
            if blk.two {
                let v1 = self.reduced(blk, 1, &b, &x, left);
                let a = &self.a[blk.base..blk.base + 4];
                for ((xk, b0), b1) in x.iter_mut().zip(v0).zip(v1) {
                    xk[blk.cols[0]] = (b0 * a[3] - a[1] * b1) * inv;
                    xk[blk.cols[1]] = (a[0] * b1 - a[2] * b0) * inv;
                }
            } else {
                for (xk, b0) in x.iter_mut().zip(v0) {
                    xk[blk.cols[0]] = b0 * inv;
                }
            }
        }
    }

    /// Row `i` of the block `blk`: its right-hand sides `b` less its entries
    /// left of the block (`left`) times the unknowns `x` found so far. Always
    /// inlined: a closure here was left a call in the Python module's build.
    #[inline(always)]
    fn reduced<const K: usize>(
        &self,
        blk: &Small,
        i: usize,
        b: &[&mut [f64]; K],
        x: &[&mut [f64]; K],
        left: &[f64],
    ) -> [f64; K] {
        let mut v: [f64; K] = std::array::from_fn(|k| b[k][blk.rows[i]]);
        let range = blk.ptr[i]..blk.ptr[i + 1];
        for (&c, &l) in self.left_old[range.clone()].iter().zip(&left[range]) {
            for (vk, xk) in v.iter_mut().zip(x.iter()) {
                *vk -= l * xk[c];
            }
        }
        v
    }

    /// The determinant of every block of one or two as assembled, its
    /// reciprocal kept for the solves, and det of the whole matrix; false
    /// when a block counts as singular by the test of the factorisation (a
    /// 2 x 2 block's determinant is the product of its two pivots, which
    /// must each exceed 2 eps times the largest entry of their column).
    fn cramer(&mut self) -> bool {
        let mut det = self.order_sign;
        for blk in &self.blocks {
            let s = blk.start;
            let d = if blk.n() == 1 {
                let p = self.a[blk.base];
                if is_zero_pivot(p.abs(), 1, p.abs()) {
                    return false;
                }
                p
            } else {
                let a = &self.a[blk.base..blk.base + 4];
                let d = a[0] * a[3] - a[1] * a[2];
                // The pivots' product against that of their columns' scales
                // (compared, not `f64::max`, which minds NaN at thrice the
                // cost: a NaN entry makes d NaN, which fails anyway).
                let larger = |x: f64, y: f64| if x.abs() > y.abs() { x.abs() } else { y.abs() };
                if is_zero_pivot(d.abs(), 2, larger(a[0], a[2]) * larger(a[1], a[3])) {
                    return false;
                }
                d
            };
            self.inv_diag[s] = 1.0 / d;
            det *= d;
        }
        self.cramer_det = det;
        true
    }

    /// Every block's determinant in turn (see [`Lu::block_dets`]); a block
    /// left as assembled for Cramer's rule keeps its reciprocal.
    pub(super) fn block_dets(&self, out: &mut Vec<f64>) {
        out.extend(self.blocks.iter().map(|blk| match &blk.band {
            Some(lu) => lu.det(),
            None if self.cramer => 1.0 / self.inv_diag[blk.start],
            None => dense::det(blk.n(), &self.a[blk.base..], blk.sign),
        }));
    }

    /// Every block's columns in the original numbering.
    pub(super) fn block_columns(&self) -> Vec<Vec<usize>> {
        self.blocks.iter().map(|blk| (blk.start..blk.end).map(|c| self.col_old[c]).collect()).collect()
    }

    pub(super) fn det(&self) -> f64 {
        if self.cramer {
            return self.cramer_det;
        }
        self.blocks.iter().fold(self.order_sign, |p, blk| {
            p * match &blk.band {
                Some(lu) => lu.det(),
                None => dense::det(blk.n(), &self.a[blk.base..], blk.sign),
            }
        })
    }
}
