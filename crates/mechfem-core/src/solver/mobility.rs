//! Why D^c is singular: a rank-revealing elimination (complete pivoting)
//! of D^c and of its transpose gives the rows that conflict (a left null
//! vector: e.g. a superfluous element between fixed points, theory remark
//! after eq. 5.13) and the co-ordinates that can still move with every
//! prescribed value held (a right null vector: a missing constraint, or a
//! limit position of an input).

use super::transfer::Kinematics;
use crate::error::SolveError;
use crate::model::{Mechanism, State};

/// The result of [`diagnose`].
#[derive(Debug, Clone, PartialEq)]
pub struct Mobility {
    /// Numerical rank of D^c.
    pub rank: usize,
    /// Size of D^c.
    pub n: usize,
    /// Prescribed rows (0-based) that take part in a dependency among the
    /// rows, largest weight first.
    pub dependent_rows: Vec<usize>,
    /// Moving co-ordinates (0-based global indices) that move in a motion
    /// allowed by every row, largest share first.
    pub free_coords: Vec<usize>,
}

/// Analyses D^c at the state's co-ordinates.
pub fn diagnose(mech: &Mechanism, state: &mut State) -> Result<Mobility, SolveError> {
    let n = mech.n_moving();
    let mut kin = Kinematics::dense(mech);
    kin.evaluate(mech, state)?;
    kin.assemble(mech);
    let a: Vec<f64> = (0..n * n).map(|k| kin.lu.get(k / n, k % n)).collect();
    let at: Vec<f64> = (0..n * n).map(|k| a[(k % n) * n + k / n]).collect();
    let (rank, right) = null_vector(&a, n);
    let (_, left) = null_vector(&at, n);
    let pick = |v: Option<Vec<f64>>| -> Vec<usize> {
        let Some(v) = v else { return Vec::new() };
        let big = v.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        let mut idx: Vec<usize> = (0..n).filter(|&i| v[i].abs() > 1e-6 * big).collect();
        idx.sort_by(|&i, &j| v[j].abs().total_cmp(&v[i].abs()));
        idx
    };
    let free_coords = pick(right).into_iter().map(|c| mech.moving_coords()[c]).collect();
    Ok(Mobility { rank, n, dependent_rows: pick(left), free_coords })
}

/// Rank of the n x n matrix `a` (row-major) by complete pivoting, and one
/// vector of its null space when it is rank-deficient.
fn null_vector(a: &[f64], n: usize) -> (usize, Option<Vec<f64>>) {
    let mut m = a.to_vec();
    let scale = m.iter().fold(0.0f64, |s, x| s.max(x.abs()));
    let tol = (n.max(1) as f64) * 1e3 * f64::EPSILON * scale.max(f64::MIN_POSITIVE);
    let mut cols: Vec<usize> = (0..n).collect();
    let mut rank = 0;
    while rank < n {
        // Largest remaining entry.
        let (mut pi, mut pj, mut best) = (rank, rank, 0.0);
        for i in rank..n {
            for j in rank..n {
                let v = m[i * n + j].abs();
                if v > best {
                    (pi, pj, best) = (i, j, v);
                }
            }
        }
        if best <= tol {
            break;
        }
        for j in 0..n {
            m.swap(rank * n + j, pi * n + j);
        }
        for i in 0..n {
            m.swap(i * n + rank, i * n + pj);
        }
        cols.swap(rank, pj);
        let p = m[rank * n + rank];
        for j in 0..n {
            m[rank * n + j] /= p;
        }
        for i in 0..n {
            if i != rank {
                let f = m[i * n + rank];
                if f != 0.0 {
                    for j in 0..n {
                        m[i * n + j] -= f * m[rank * n + j];
                    }
                }
            }
        }
        rank += 1;
    }
    if rank == n {
        return (rank, None);
    }
    // Reduced echelon form [I R; 0 0] in permuted columns: set the first
    // free variable to 1, the pivot variables follow from -R.
    let mut z = vec![0.0; n];
    z[cols[rank]] = 1.0;
    for i in 0..rank {
        z[cols[i]] = -m[i * n + rank];
    }
    (rank, Some(z))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::elements::ElementType;
    use crate::model::{MechanismBuilder, Term};

    #[test]
    fn names_the_superfluous_row_and_the_free_coordinates() {
        // A point on a crank whose length is prescribed twice over, once by
        // a bar between the two fixed points (a superfluous element): the
        // second row has a zero gradient, and the point may still turn.
        let mut b = MechanismBuilder::new();
        let f = [b.fixed(0.0), b.fixed(0.0), b.fixed(2.0), b.fixed(0.0)];
        let (xa, ya) = (b.moving(1.0), b.moving(0.5));
        let crank = b.element(ElementType::Bin, &[f[0], f[1], xa, ya]);
        let frame = b.element(ElementType::Bin, &[f[0], f[1], f[2], f[3]]);
        b.prescribe(&[Term::new(crank, 0)]);
        b.prescribe(&[Term::new(frame, 0)]);
        let (mech, mut state) = b.build().unwrap();
        let m = diagnose(&mech, &mut state).unwrap();
        assert_eq!(m.rank, 1);
        assert_eq!(m.dependent_rows, vec![1]);
        assert_eq!(m.free_coords.len(), 2);
    }
}
