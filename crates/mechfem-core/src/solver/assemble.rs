//! Assembly element by element (remark 1 after eq. 5.26): every single form
//! parameter of a set of rows is evaluated once into a cache, from which the
//! rows' values, D^c, and the second-order products are summed. Nothing is
//! allocated here; the cache is sized once per model, and so is the list of
//! places in D^c's storage that each term's gradient goes to.

use super::lu::Lu;
use crate::elements::{FormEval, Order, MAX_COORDS};
use crate::error::SolveError;
use crate::model::{Mechanism, Over, Rows, FIXED};

/// Marker for "this co-ordinate has no entry in D^c" (it is fixed).
pub(crate) const NO_ENTRY: usize = usize::MAX;

/// Evaluates every term of `rows` at `x` up to `order`, storing the results
/// in `cache` (one entry per flat term) and the combined row values (eq. 5.33)
/// in `values`.
pub(crate) fn eval_rows(
    rows: &Rows,
    x: &[f64],
    branch: &mut [f64],
    order: Order,
    cache: &mut [FormEval],
    values: &mut [f64],
) -> Result<(), SolveError> {
    for ((t, s), out) in rows.terms().iter().zip(rows.slots()).zip(cache.iter_mut()) {
        s.ty.eval_at(t.form, &s.coords, x, &mut branch[t.element], order, out)
            .map_err(|source| SolveError::Element { element: t.element, source })?;
    }
    let values = &mut values[..rows.len()];
    if rows.plain() {
        for (v, e) in values.iter_mut().zip(cache.iter()) {
            *v = e.value;
        }
    } else {
        values.fill(0.0);
        for ((t, e), &row) in rows.terms().iter().zip(cache.iter()).zip(rows.row_of()) {
            values[row] += t.factor * e.value;
        }
    }
    if !values.iter().fold(true, |ok, v| ok & v.is_finite()) {
        return Err(SolveError::NonFinite);
    }
    Ok(())
}

/// Where every term's gradient goes in D^c's storage: for prescribed term
/// k and the element's co-ordinate a, `positions[k][a]` (or [`NO_ENTRY`]).
pub(crate) fn dc_positions(mech: &Mechanism, lu: &Lu) -> Vec<[usize; MAX_COORDS]> {
    let rows = &mech.prescribed;
    let mut positions = vec![[NO_ENTRY; MAX_COORDS]; rows.terms().len()];
    for i in 0..rows.len() {
        for k in rows.range(i) {
            for (a, c) in moving_columns(rows, k) {
                positions[k][a] = lu.position(i, c).expect("D^c's storage holds its pattern");
            }
        }
    }
    positions
}

/// The co-ordinates of prescribed term k that it depends on and that move:
/// (position in the element, column of D^c).
fn moving_columns(rows: &Rows, k: usize) -> impl Iterator<Item = (usize, usize)> + '_ {
    let (t, s) = (&rows.terms()[k], &rows.slots()[k]);
    let mask = s.ty.depends(t.form);
    (0..s.n).filter(move |&a| mask & (1 << a) != 0 && s.cols[a] != FIXED).map(move |a| (a, s.cols[a]))
}

/// The structural non-zeros of D^c: the columns of every prescribed row
/// (the moving co-ordinates its form parameters depend on).
pub(crate) fn dc_pattern(mech: &Mechanism) -> Vec<Vec<usize>> {
    let rows = &mech.prescribed;
    (0..rows.len()).map(|i| rows.range(i).flat_map(|k| moving_columns(rows, k).map(|(_, c)| c)).collect()).collect()
}

/// Writes D^c (rows: prescribed rows, columns: moving co-ordinates) from a
/// cache of the prescribed rows filled to at least first order.
///
/// With `overwrite` (see [`writes_every_place_once`]), each place is
/// written rather than added to, and the storage is not cleared first.
pub(crate) fn fill_dc(
    mech: &Mechanism,
    cache: &[FormEval],
    positions: &[[usize; MAX_COORDS]],
    overwrite: bool,
    lu: &mut Lu,
) {
    if !overwrite {
        lu.clear();
    }
    let values = lu.values_mut();
    let rows = &mech.prescribed;
    for (((t, s), e), pos) in rows.terms().iter().zip(rows.slots()).zip(cache).zip(positions) {
        for a in 0..s.n {
            if pos[a] != NO_ENTRY {
                let v = t.factor * e.grad[a];
                if overwrite {
                    values[pos[a]] = v;
                } else {
                    values[pos[a]] += v;
                }
            }
        }
    }
}

/// Whether `positions` write every place of D^c's storage (of `len`
/// places) exactly once, so that assembly need not clear it first.
pub(crate) fn writes_every_place_once(positions: &[[usize; MAX_COORDS]], len: usize) -> bool {
    let mut count = vec![0u32; len];
    for &p in positions.iter().flatten().filter(|&&p| p != NO_ENTRY) {
        count[p] += 1;
    }
    count.iter().all(|&c| c == 1)
}

/// `sum_k D_{row,k} a_k`: the row's gradient times a vector `over` the
/// moving co-ordinates (fixed co-ordinates do not move) or over every
/// co-ordinate.
pub(crate) fn grad_dot(rows: &Rows, cache: &[FormEval], row: usize, a: &[f64], over: Over) -> f64 {
    let mut s = 0.0;
    for k in rows.range(row) {
        let ae = rows.slots()[k].gather(a, over);
        let g: f64 = (0..rows.slots()[k].n).map(|p| cache[k].grad[p] * ae[p]).sum();
        s += rows.terms()[k].factor * g;
    }
    s
}

/// `sum_kl D_{row,kl} a_k b_l` for every row into `out`: the second-order
/// products of eqs. 5.22 and 5.28, summed element by element from each
/// element's second derivative along the directions (no Hessian is formed),
/// with `cache` the rows' evaluation at `x` to first order or more, and
/// `a`, `b` vectors `over` the columns of D^c or every co-ordinate.
pub(crate) fn second_products(
    rows: &Rows,
    x: &[f64],
    cache: &[FormEval],
    (a, b): (&[f64], &[f64]),
    over: Over,
    out: &mut [f64],
) {
    out[..rows.len()].fill(0.0);
    for (((t, slot), first), &row) in rows.terms().iter().zip(rows.slots()).zip(cache).zip(rows.row_of()) {
        out[row] += t.factor * slot.ty.second_at(t.form, (&slot.coords, slot.indices(over)), x, first, a, b);
    }
}
