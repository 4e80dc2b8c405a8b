//! Position analysis by Newton-Raphson (theory section 5.3.4, fig. 5.3.6):
//! correction of the moving co-ordinates until every kinematic deformation
//! eps(x) - eps^p is below the tolerance, and the adjustment of a rough
//! initial position to the prescribed values.

use super::params::Params;
use super::transfer::Kinematics;
use crate::elements::Order;
use crate::error::SolveError;
use crate::model::{Mechanism, State};

/// How a Newton correction went.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct NewtonInfo {
    /// Iterations (corrections) made.
    pub iterations: usize,
    /// Factorisations of D^c made (the other iterations reused one).
    pub factorisations: usize,
    /// Largest deformation before the first iteration.
    pub initial: f64,
    /// Largest deformation at the end.
    pub residual: f64,
}

/// A temporary input (theory section 5.5.3): prescribed row `row` is
/// replaced by the single co-ordinate in column `col`, held at `value`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TempInput {
    /// The prescribed row it replaces (the original input's row).
    pub row: usize,
    /// Column of D^c (moving co-ordinate) that becomes the input.
    pub col: usize,
    /// The value that co-ordinate is held at.
    pub value: f64,
}

/// Deformations of all prescribed rows into `kin.rhs`, from an evaluation
/// to `order` into `kin`'s cache; returns (largest |deformation|, whether
/// every row is within its tolerance).
fn deformations(
    mech: &Mechanism,
    state: &mut State,
    kin: &mut Kinematics,
    tol: f64,
    temp: Option<TempInput>,
    order: Order,
) -> Result<(f64, bool), SolveError> {
    kin.evaluate_to(mech, state, order)?;
    let (mut largest, mut ok, mut finite) = (0.0f64, true, true);
    for i in 0..mech.n_prescribed() {
        let r = match temp {
            Some(t) if t.row == i => state.x[mech.moving_coords()[t.col]] - t.value,
            _ => kin.row_values[i] - state.target[i],
        };
        kin.rhs[i] = r;
        // Compared, not `f64::max`: that minds NaN at thrice the cost, and
        // `finite` takes care of NaN here.
        if r.abs() > largest {
            largest = r.abs();
        }
        finite &= r.is_finite();
        // A row whose value is so large that tol is below its resolution
        // is held to 16 ulp of the value instead.
        ok &= r.abs() <= tol || r.abs() <= 16.0 * f64::EPSILON * state.target[i].abs();
    }
    // A deformation that is not finite is never within the tolerance (an
    // infinite target would make the tolerance infinite too).
    Ok(if finite { (largest, ok) } else { (f64::NAN, false) })
}

/// A correction with a factorisation of D^c from an earlier point must
/// shrink the largest deformation at least this much; otherwise D^c is
/// factorised afresh.
const CHORD_CONTRACTION: f64 = 0.05;

/// Newton correction at fixed prescribed values (eqs. 5.18, 5.19): repeats
/// D^c dx = -(eps(x) - eps^p) until every deformation is within
/// `params.tol`. Uses `kin` as workspace; its transfer functions are stale
/// afterwards. The last evaluation, at the converged position, is left in
/// `kin` (the prescribed rows and their deformations) so that the transfer
/// functions there need no second one.
///
/// When `kin` holds a factorisation of D^c from a nearby position (the
/// previous one of a motion) and one correction with it is expected to
/// suffice (judged by how much the last such correction shrank the
/// deformations), it is used as it is (a chord step); otherwise, and after a
/// chord step that did not shrink the deformations twentyfold, D^c is
/// assembled and factorised at the current point.
pub fn correct(
    mech: &Mechanism,
    state: &mut State,
    kin: &mut Kinematics,
    params: &Params,
) -> Result<NewtonInfo, SolveError> {
    correct_with(mech, state, kin, params, None)
}

/// [`correct`] with one row replaced by a temporary input.
pub fn correct_with(
    mech: &Mechanism,
    state: &mut State,
    kin: &mut Kinematics,
    params: &Params,
    temp: Option<TempInput>,
) -> Result<NewtonInfo, SolveError> {
    correct_from(mech, state, kin, params, temp, (Order::First, Order::First))
}

/// [`correct_with`], evaluating the starting point to `first` and every
/// corrected point to `then` (values only, when the caller expects the
/// point to pass and needs no D^c there): a point that does not pass is
/// evaluated again to first order. The converged position is left in `kin`
/// to the order it was evaluated to.
pub(crate) fn correct_from(
    mech: &Mechanism,
    state: &mut State,
    kin: &mut Kinematics,
    params: &Params,
    temp: Option<TempInput>,
    (first, then): (Order, Order),
) -> Result<NewtonInfo, SolveError> {
    let mut info = NewtonInfo::default();
    let mut order = first;
    let mut previous = f64::INFINITY;
    let mut growing = 0;
    // Whether the last correction used an earlier factorisation.
    let mut chord = false;
    loop {
        let (largest, ok) = deformations(mech, state, kin, params.tol, temp, order)?;
        if info.iterations == 0 {
            info.initial = largest;
        }
        info.residual = largest;
        if chord {
            kin.chord_rate = (largest / previous).max(1e-4);
        }
        if !largest.is_finite() {
            return Err(SolveError::NonFinite);
        }
        if ok {
            return Ok(info);
        }
        // Newton near a solution shrinks the deformations fast; three
        // growing iterations in a row mean it is heading elsewhere.
        growing = if largest > previous { growing + 1 } else { 0 };
        if info.iterations >= params.max_iter || growing >= 3 {
            return Err(SolveError::NoConvergence { iterations: info.iterations, residual: largest });
        }
        let reuse = temp.is_none()
            && kin.factored
            && largest * kin.chord_rate <= params.tol
            && (info.iterations == 0 || (chord && largest <= CHORD_CONTRACTION * previous));
        previous = largest;
        if !reuse && order < Order::First {
            // D^c is needed here after all.
            kin.evaluate(mech, state)?;
        }
        order = then;
        if !reuse {
            kin.assemble(mech);
            match temp {
                Some(t) => kin.factor_with_unit_row(t.row, t.col)?,
                None => kin.factor()?,
            }
            info.factorisations += 1;
        }
        chord = reuse;
        kin.lu.solve(&mut kin.rhs, &mut kin.work);
        for (c, &i) in mech.moving_coords().iter().enumerate() {
            state.x[i] -= kin.rhs[c];
        }
        info.iterations += 1;
    }
}

/// What the adjustment of the initial position did.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct AdjustInfo {
    /// Newton iterations in all.
    pub iterations: usize,
    /// Deformation of every prescribed row at the given co-ordinates
    /// (value there minus prescribed value).
    pub initial_deformations: Vec<f64>,
    /// Largest deformation at the end.
    pub residual: f64,
    /// Continuation stages used (1 when plain Newton converged).
    pub stages: usize,
}

/// Adjusts the moving co-ordinates to the prescribed values in
/// `state.target` (section 5.3.4, remark 2). Plain Newton is tried first;
/// when it fails, the prescribed values are moved from the values at the
/// given co-ordinates to the targets in stages, halving a stage that fails.
pub fn adjust(
    mech: &Mechanism,
    state: &mut State,
    kin: &mut Kinematics,
    params: &Params,
) -> Result<AdjustInfo, SolveError> {
    let target = state.target.clone();
    align_turns(mech, state)?;
    let start = state.clone();
    let mut from = vec![0.0; target.len()];
    for (r, v) in from.iter_mut().enumerate() {
        *v = state.clone().prescribed_value(mech, r)?;
    }
    let mut info = AdjustInfo {
        initial_deformations: from.iter().zip(&target).map(|(a, b)| a - b).collect(),
        ..AdjustInfo::default()
    };
    let first_error = match correct(mech, state, kin, params) {
        Ok(n) => {
            info.iterations = n.iterations;
            info.residual = n.residual;
            info.stages = 1;
            return Ok(info);
        }
        Err(e) => e,
    };
    // Continuation in lambda from 0 (given co-ordinates) to 1 (targets).
    *state = start;
    let (mut lambda, mut h) = (0.0f64, 0.25f64);
    let min_h = 0.5f64.powi(params.max_halvings as i32 + 2);
    while lambda < 1.0 {
        let next = (lambda + h).min(1.0);
        let saved = (state.x.clone(), state.branch.clone());
        for r in 0..target.len() {
            // Weighted, not from + next * (target - from): the difference of
            // two finite values may overflow.
            state.target[r] = (1.0 - next) * from[r] + next * target[r];
        }
        match correct(mech, state, kin, params) {
            Ok(n) => {
                info.iterations += n.iterations;
                info.residual = n.residual;
                info.stages += 1;
                lambda = next;
                h *= 2.0;
            }
            Err(_) => {
                state.x = saved.0;
                state.branch = saved.1;
                h *= 0.5;
                if h < min_h {
                    state.target = target;
                    return Err(first_error);
                }
            }
        }
    }
    Ok(info)
}

/// Puts every prescribed angle row on the turn of its prescribed value.
///
/// An angle found by `atan2` is known only up to whole turns: given
/// co-ordinates where, say, a plate angle beta2 - beta4 reads 1.108 while
/// -5.175 is prescribed describe the right position, a full turn away only
/// in how the angle is counted. Newton would otherwise try to turn the plate
/// once around to close that gap. So, row by row, where a row's value at
/// the given co-ordinates is whole turns from its prescribed value, the
/// angle memory of one of its elements is moved by those turns: an element
/// whose angle the row holds with a factor of +-1 and that no earlier row's
/// angle depends on (moving it would move that row too).
fn align_turns(mech: &Mechanism, state: &mut State) -> Result<(), SolveError> {
    use std::f64::consts::TAU;
    let mut used = vec![false; mech.elements().len()];
    for r in 0..mech.n_prescribed() {
        let terms = mech.prescribed_terms(r);
        let value = state.prescribed_value(mech, r)?;
        let turns = ((value - state.target[r]) / TAU).round();
        let tracked: Vec<bool> = terms.iter().map(|t| tracked(mech, state, t)).collect::<Result<_, _>>()?;
        if turns != 0.0 && turns.is_finite() {
            let free = terms.iter().zip(&tracked).find(|(t, &a)| a && t.factor.abs() == 1.0 && !used[t.element]);
            if let Some((t, _)) = free {
                state.branch[t.element] -= turns * TAU * t.factor;
            }
        }
        for (t, _) in terms.iter().zip(&tracked).filter(|(_, &a)| a) {
            used[t.element] = true;
        }
    }
    Ok(())
}

/// Whether term `t` is an angle that the element's memory tracks: one turn
/// more in the memory reads one turn more.
fn tracked(mech: &Mechanism, state: &State, t: &crate::model::Term) -> Result<bool, SolveError> {
    use std::f64::consts::TAU;
    let mut probe = crate::elements::FormEval::default();
    let mut branch = state.branch.clone();
    mech.eval_term(t, &state.x, &mut branch, Order::Value, &mut probe)?;
    let here = probe.value;
    branch[t.element] = here + TAU;
    mech.eval_term(t, &state.x, &mut branch, Order::Value, &mut probe)?;
    Ok((probe.value - here - TAU).abs() < 1e-6)
}
