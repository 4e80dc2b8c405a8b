//! Assembly element by element (remark 1 after eq. 5.26): every single form
//! parameter of a set of rows is evaluated once into a cache, from which the
//! rows' values, D^c, and the second-order products are summed. Nothing is
//! allocated here; the cache is sized once per model.

use super::lu::Lu;
use crate::elements::{FormEval, Order};
use crate::error::SolveError;
use crate::model::{Mechanism, Rows, FIXED};

/// Evaluates every term of `rows` at `x` up to `order`, storing the results
/// in `cache` (one entry per flat term) and the combined row values (eq. 5.33)
/// in `values`.
pub(crate) fn eval_rows(
    mech: &Mechanism,
    rows: &Rows,
    x: &[f64],
    branch: &mut [f64],
    order: Order,
    cache: &mut [FormEval],
    values: &mut [f64],
) -> Result<(), SolveError> {
    for (t, out) in rows.terms().iter().zip(cache.iter_mut()) {
        mech.eval_term(t, x, branch, order, out)?;
    }
    for (i, v) in values.iter_mut().enumerate().take(rows.len()) {
        *v = rows.range(i).map(|k| rows.terms()[k].factor * cache[k].value).sum();
        if !v.is_finite() {
            return Err(SolveError::NonFinite);
        }
    }
    Ok(())
}

/// Writes D^c (rows: prescribed rows, columns: moving co-ordinates) from a
/// cache filled to at least first order.
pub(crate) fn fill_dc(mech: &Mechanism, cache: &[FormEval], lu: &mut Lu) {
    lu.clear();
    let rows = &mech.prescribed;
    for i in 0..rows.len() {
        for k in rows.range(i) {
            let t = &rows.terms()[k];
            for (a, &c) in mech.elements()[t.element].coords().iter().enumerate() {
                let col = mech.column(c);
                if col != FIXED {
                    lu.add(i, col, t.factor * cache[k].grad[a]);
                }
            }
        }
    }
}

/// `sum_k D_{row,k} a_k`: the row's gradient times a vector over the moving
/// co-ordinates (fixed co-ordinates do not move).
pub(crate) fn grad_dot(mech: &Mechanism, rows: &Rows, cache: &[FormEval], row: usize, a: &[f64]) -> f64 {
    let mut s = 0.0;
    for k in rows.range(row) {
        let t = &rows.terms()[k];
        let mut g = 0.0;
        for (p, &c) in mech.elements()[t.element].coords().iter().enumerate() {
            let col = mech.column(c);
            if col != FIXED {
                g += cache[k].grad[p] * a[col];
            }
        }
        s += t.factor * g;
    }
    s
}

/// `sum_kl D_{row,kl} a_k b_l`: the second-order product of eq. 5.22/5.28,
/// summed element by element from a cache filled to second order.
pub(crate) fn hess_product(mech: &Mechanism, rows: &Rows, cache: &[FormEval], row: usize, a: &[f64], b: &[f64]) -> f64 {
    let mut s = 0.0;
    for k in rows.range(row) {
        let t = &rows.terms()[k];
        let coords = mech.elements()[t.element].coords();
        let mut h = 0.0;
        for (p, &cp) in coords.iter().enumerate() {
            let colp = mech.column(cp);
            if colp == FIXED {
                continue;
            }
            let mut hb = 0.0;
            for (q, &cq) in coords.iter().enumerate() {
                let colq = mech.column(cq);
                if colq != FIXED {
                    hb += cache[k].hess[p][q] * b[colq];
                }
            }
            h += a[colp] * hb;
        }
        s += t.factor * h;
    }
    s
}
