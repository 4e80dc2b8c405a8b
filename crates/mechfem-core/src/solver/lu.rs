//! Dense LU factorisation with partial pivoting, in place, on a buffer that
//! is allocated once per model. One factorisation of D^c serves every
//! first- and second-order solve at a position.

/// An n x n matrix (row-major) and, after [`Lu::factor`], its LU factors.
#[derive(Debug, Clone)]
pub struct Lu {
    n: usize,
    a: Vec<f64>,
    perm: Vec<usize>,
    sign: f64,
    scale: Vec<f64>,
}

/// Where elimination broke down: column and pivot.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SingularPivot {
    /// Column of the failing pivot.
    pub column: usize,
    /// Its value.
    pub pivot: f64,
}

impl Lu {
    /// Storage for an n x n matrix, zeroed.
    pub fn new(n: usize) -> Lu {
        Lu { n, a: vec![0.0; n * n], perm: (0..n).collect(), sign: 1.0, scale: vec![0.0; n] }
    }
    /// Size n.
    pub fn n(&self) -> usize {
        self.n
    }
    /// Sets every entry to zero before assembly.
    pub fn clear(&mut self) {
        self.a.fill(0.0);
    }
    /// Adds `v` to entry (i, j).
    #[inline]
    pub fn add(&mut self, i: usize, j: usize, v: f64) {
        self.a[i * self.n + j] += v;
    }
    /// Replaces row i by the unit row e_col (the row of a single-co-ordinate
    /// element, used for the temporary input of free motion).
    pub fn set_unit_row(&mut self, i: usize, col: usize) {
        let n = self.n;
        self.a[i * n..(i + 1) * n].fill(0.0);
        self.a[i * n + col] = 1.0;
    }
    /// Entry (i, j) of the matrix (before factorisation) or of the factors.
    pub fn get(&self, i: usize, j: usize) -> f64 {
        self.a[i * self.n + j]
    }

    /// Factorises in place. A pivot counts as zero when it is below
    /// `n * eps` times the largest entry of its column in the original
    /// matrix: the column is then, to working precision, a combination of
    /// the others.
    pub fn factor(&mut self) -> Result<(), SingularPivot> {
        let n = self.n;
        for j in 0..n {
            self.scale[j] = (0..n).fold(0.0f64, |m, i| m.max(self.a[i * n + j].abs()));
            self.perm[j] = j;
        }
        self.sign = 1.0;
        for k in 0..n {
            let mut p = k;
            let mut best = self.a[k * n + k].abs();
            for i in k + 1..n {
                let v = self.a[i * n + k].abs();
                if v > best {
                    best = v;
                    p = i;
                }
            }
            let floor = (n as f64) * f64::EPSILON * self.scale[k];
            // A NaN pivot compares as unordered and counts as zero too.
            if best.partial_cmp(&floor) != Some(std::cmp::Ordering::Greater) {
                return Err(SingularPivot { column: k, pivot: self.a[p * n + k] });
            }
            if p != k {
                for j in 0..n {
                    self.a.swap(k * n + j, p * n + j);
                }
                self.perm.swap(k, p);
                self.sign = -self.sign;
            }
            let pivot = self.a[k * n + k];
            for i in k + 1..n {
                let f = self.a[i * n + k] / pivot;
                self.a[i * n + k] = f;
                if f != 0.0 {
                    for j in k + 1..n {
                        self.a[i * n + j] -= f * self.a[k * n + j];
                    }
                }
            }
        }
        Ok(())
    }

    /// Solves A y = b in place (b becomes y), using the factors.
    pub fn solve(&self, b: &mut [f64], work: &mut [f64]) {
        let n = self.n;
        for i in 0..n {
            work[i] = b[self.perm[i]];
        }
        for i in 0..n {
            let mut s = work[i];
            for j in 0..i {
                s -= self.a[i * n + j] * work[j];
            }
            work[i] = s;
        }
        for i in (0..n).rev() {
            let mut s = work[i];
            for j in i + 1..n {
                s -= self.a[i * n + j] * work[j];
            }
            work[i] = s / self.a[i * n + i];
        }
        b[..n].copy_from_slice(&work[..n]);
    }

    /// Determinant from the factors.
    pub fn det(&self) -> f64 {
        (0..self.n).fold(self.sign, |d, i| d * self.a[i * self.n + i])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

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
}
