//! One step of driven motion: prediction, Newton correction, and halving of
//! a step that fails or may have left its assembly branch.
//!
//! A step keeps the branch when its correction is small against its
//! predicted move ([`KAPPA`]) and det(D^c), where it is computed, keeps its
//! sign; otherwise it is halved (docs/analysis.md, *Keeping the branch*).
//!
//! Two predictors. The second-order Taylor expansion of eqs. 5.18 and 5.22
//! needs the transfer functions at the position the step starts from; the
//! polynomial through the last positions of a one-DOF mechanism
//! ([`History`], up to degree seven) needs nothing but those positions. A
//! run of positions only or of first order extrapolates; where it cannot
//! (the first steps, several inputs) it computes the transfer functions the
//! Taylor expansion needs. A run of second order has them anyway and uses
//! the Taylor expansion while it needs no correction (fine steps), the
//! history where it does (coarse steps: at one-degree steps of a four-bar
//! the history predicts to about 1e-10, the Taylor expansion to about 1e-6).
//!
//! A position that passes the convergence check without an iteration still
//! carries the deformations it was accepted with (up to the tolerance), and
//! extrapolation would amplify them from step to step. The copy kept for
//! extrapolation is therefore refined by one Newton correction with the
//! factorisation at hand (one solve, no evaluation); the position itself is
//! the one that was checked. A run of positions only has no factorisation
//! at every position: it keeps one for as long as it refines well enough
//! ([`Renewal`]). A position predicted so well that it needs no refining
//! is not kept at all: the extrapolation already passes through it (see
//! [`Stepper::remember`]). With transfer functions, the refinement is
//! solved in one pass with x' (`Lu::solve_two`).

use super::history::History;
use crate::elements::Order;
use crate::error::SolveError;
use crate::model::{Mechanism, State};
use crate::solver::newton::correct_from;
use crate::solver::{Kinematics, NewtonInfo, Params, TransferOrder};

/// Carries the mechanism from one set of input values to the next.
pub(crate) struct Stepper {
    saved_x: Vec<f64>,
    saved_branch: Vec<f64>,
    saved_target: Vec<f64>,
    delta: Vec<f64>,
    predicted_x: Vec<f64>,
    params: Params,
    /// The shortest fraction of a step it may be cut down to.
    min_h: f64,
    /// What is computed at every position reached.
    order: Option<TransferOrder>,
    /// Positions of a one-DOF mechanism for extrapolation, when used.
    history: Option<History>,
    /// Deformations at the position the last correction accepted.
    residual: Vec<f64>,
    /// That position refined for the history.
    refined: Vec<f64>,
    /// Newton iterations of the last correction.
    last_iterations: usize,
    /// Whether the history predicts (otherwise the Taylor expansion).
    use_history: bool,
    /// Whether the last prediction was the history's.
    extrapolated: bool,
    /// Positions only: when D^c is factorised afresh.
    renewal: Renewal,
    /// Positions only: whether D^c will probably be factorised at the next
    /// position (so evaluate it there with the values): one of the last two
    /// was refined (at coarse steps most are; at fine ones, where few are,
    /// evaluating D^c at every position after one refined would cost more
    /// than evaluating the few renewals twice), and the factorisation will
    /// be old enough.
    renewal_due: bool,
    /// Positions only: whether the last position was refined.
    last_refined: bool,
    /// Whether the last prediction was the first-order Taylor expansion.
    first_order_only: bool,
    /// Whether the step under way has been subdivided (its sub-steps are
    /// predicted by the Taylor expansion).
    subdividing: bool,
}

impl Stepper {
    /// A stepper that computes `order` at every position it reaches (`None`:
    /// positions and dependent values only). A mechanism with more than one
    /// input always gets at least the first-order transfer functions, which
    /// its predictor needs.
    pub(crate) fn new(mech: &Mechanism, params: &Params, order: Option<TransferOrder>) -> Stepper {
        let one_input = mech.n_dof() == 1;
        let order = if one_input { order } else { order.max(Some(TransferOrder::First)) };
        Stepper {
            saved_x: vec![0.0; mech.n_coords()],
            saved_branch: vec![0.0; mech.elements().len()],
            saved_target: vec![0.0; mech.n_prescribed()],
            delta: vec![0.0; mech.n_dof()],
            predicted_x: vec![0.0; mech.n_moving()],
            params: *params,
            min_h: 0.5f64.powi(params.max_halvings as i32),
            order,
            history: one_input.then(|| History::new(mech.n_moving(), 1e-4 * params.tol)),
            residual: vec![0.0; mech.n_moving()],
            refined: vec![0.0; mech.n_moving()],
            last_iterations: 1,
            use_history: order != Some(TransferOrder::Second),
            extrapolated: false,
            renewal: Renewal { age: 0, max_age: 1, clean: 0 },
            renewal_due: false,
            last_refined: false,
            subdividing: false,
            first_order_only: false,
        }
    }

    /// Remembers the current position as the latest one reached (for
    /// extrapolation); called at the start of a motion.
    pub(crate) fn start(&mut self, mech: &Mechanism, state: &State) {
        if let Some(h) = &mut self.history {
            h.clear();
            for (r, &i) in self.refined.iter_mut().zip(mech.moving_coords()) {
                *r = state.x[i];
            }
            h.push(state.target[mech.input_row(0)], &self.refined);
        }
    }

    /// Whether the position just reached may go into the history (`None`:
    /// not), and whether it must be refined by one correction
    /// D^c dx = -(deformations) first: deformations below a hundredth of
    /// the tolerance need none. A prediction that needs refining was
    /// short of a term, which the history keeps from now on.
    ///
    /// A run that computes the second order predicts by the Taylor
    /// expansion as long as that needs no correction (fine steps), and
    /// turns to the history when it does (coarse ones), back when the
    /// history needs no more than the quadratic.
    fn keeps(&mut self) -> Option<bool> {
        let hist = self.history.as_mut()?;
        if self.order == Some(TransferOrder::Second) {
            if !self.use_history && self.last_iterations > 0 {
                self.use_history = true;
                hist.clear();
            } else if self.use_history && self.extrapolated && self.last_iterations == 0 && hist.degree() <= 2 {
                self.use_history = false;
            }
            if !self.use_history {
                return None;
            }
        }
        let refine = self.residual.iter().any(|r| r.abs() > REFINE_ABOVE * self.params.tol);
        if refine && self.extrapolated {
            hist.deepen();
        }
        Some(refine)
    }

    /// Adds the position just reached to the history, refined as
    /// [`Self::keeps`] said. A run with transfer functions has had the
    /// correction solved with their factorisation (in `self.residual`, when
    /// `kin.factored`); a run of positions only solves it here.
    ///
    /// A position the extrapolation predicted so well that it passed
    /// unrefined is left out (up to [`MAX_SKIPPED`] in a row): the
    /// polynomial through the positions kept already gives it, and keeping
    /// the prediction with its small error would let the errors of several
    /// such positions add up through the extrapolation until predictions
    /// need refining at most steps (at 100 000 steps a turn: 59 000
    /// refinements a turn when kept, 6 000 when left out).
    fn remember(&mut self, mech: &Mechanism, state: &mut State, kin: &mut Kinematics, info: NewtonInfo, wanted: bool) {
        let Some(hist) = &mut self.history else { return };
        let mut refine = wanted;
        if self.order.is_none() {
            // A run of positions only computes D^c only where it must.
            let renew = self.renewal.renew(info, self.extrapolated, refine);
            if renew {
                refine &= kin.factor_here(mech, state).is_ok();
            }
            self.renewal_due = (wanted || self.last_refined) && self.renewal.due_next();
            self.last_refined = wanted;
        }
        if !wanted && self.extrapolated && info.iterations == 0 && hist.skipped() < MAX_SKIPPED {
            hist.skip();
            return;
        }
        refine &= kin.factored;
        if refine && self.order.is_none() {
            kin.solve(&mut self.residual);
        }
        for ((r, &i), &dx) in self.refined.iter_mut().zip(mech.moving_coords()).zip(&self.residual) {
            *r = if refine { state.x[i] - dx } else { state.x[i] };
        }
        hist.push(state.target[mech.input_row(0)], &self.refined);
    }

    /// Moves the inputs from `from` to `to`, starting at `start` (a copy of
    /// `state`); on success `kin` holds what the stepper computes at every
    /// position (see [`Stepper::new`]) at the new position. Returns whether
    /// the step had to be subdivided.
    pub(crate) fn step(
        &mut self,
        mech: &Mechanism,
        state: &mut State,
        start: &State,
        kin: &mut Kinematics,
        from: &[f64],
        to: &[f64],
    ) -> Result<bool, SolveError> {
        let (mut s, mut h) = (0.0f64, 1.0f64);
        let mut halved = false;
        self.subdividing = false;
        // det(D^c) where the sub-step starts, where it is known (NaN where not).
        let mut det_from = kin.det();
        while s < 1.0 {
            let s1 = if s + h >= 1.0 - 1e-12 { 1.0 } else { s + h };
            // Where to go back to if this sub-step fails: `start`, or a copy.
            if s > 0.0 {
                self.saved_x.copy_from_slice(&state.x);
                self.saved_branch.copy_from_slice(&state.branch);
                self.saved_target.copy_from_slice(&state.target);
            }
            let stepped = match self.try_step(mech, state, kin, from, to, s1) {
                Ok(info) => {
                    // What is needed at the new point, from the evaluation
                    // Newton converged with; it also drives the next prediction.
                    let keeps = self.keeps();
                    let refine = keeps == Some(true);
                    // With transfer functions, the refinement is solved with theirs.
                    let extra = (refine && self.order.is_some()).then_some(&mut self.residual[..]);
                    let t = kin.finish(mech, state, self.order, extra);
                    if let Err(e) = t {
                        if s1 >= 1.0 {
                            return Err(e);
                        }
                    }
                    // det(D^c) keeps its sign along a driven motion that
                    // stays on its branch: a sign change means the sub-step
                    // crossed a limit position (or jumped over a locked zone).
                    let det = if kin.order().is_some() { kin.det() } else { f64::NAN };
                    if det * det_from < 0.0 {
                        Err(SolveError::DetSignChange { before: det_from, after: det })
                    } else {
                        if !det.is_nan() {
                            det_from = det;
                        }
                        Ok((info, keeps, refine))
                    }
                }
                Err(e) => Err(e),
            };
            match stepped {
                Ok((info, keeps, refine)) => {
                    s = s1;
                    if keeps.is_some() {
                        self.remember(mech, state, kin, info, refine);
                    }
                    if halved {
                        h = (2.0 * h).min(1.0 - s).max(self.min_h);
                    }
                }
                Err(e) => {
                    if s > 0.0 {
                        state.x.copy_from_slice(&self.saved_x);
                        state.branch.copy_from_slice(&self.saved_branch);
                        state.target.copy_from_slice(&self.saved_target);
                    } else {
                        state.clone_from(start);
                    }
                    h *= 0.5;
                    halved = true;
                    // The polynomial through positions a whole step apart
                    // misses the slope at the last one by an amount that
                    // does not shrink with the sub-step: the rest of the
                    // step is predicted by the Taylor expansion, whose
                    // error does.
                    self.subdividing = true;
                    // Close to a limit position the path bends so sharply that
                    // only sub-steps short against the distance to it pass
                    // the test of the correction: those may be shorter than
                    // the shortest for a failed correction.
                    let floor =
                        if matches!(e, SolveError::BranchJump { .. }) { self.min_h * self.min_h } else { self.min_h };
                    if h < floor {
                        return Err(e);
                    }
                    // The full transfer functions at the saved point drive
                    // the shorter steps.
                    kin.transfer(mech, state, TransferOrder::Second)?;
                    det_from = kin.det();
                }
            }
        }
        Ok(halved)
    }

    /// Predicts and corrects to the inputs at fraction `s1` of the step.
    fn try_step(
        &mut self,
        mech: &Mechanism,
        state: &mut State,
        kin: &mut Kinematics,
        from: &[f64],
        to: &[f64],
        s1: f64,
    ) -> Result<NewtonInfo, SolveError> {
        let nd = mech.n_dof();
        for j in 0..nd {
            let r = mech.input_row(j);
            let goal = from[j] + s1 * (to[j] - from[j]);
            self.delta[j] = goal - state.target[r];
            state.target[r] = goal;
        }
        let predicted_sq = self.predict(mech, state, kin);
        // A run of positions only needs D^c at the predicted point only if
        // that point is not accepted as it is, as it usually was last time,
        // or if the factorisation is due for renewal there (evaluated now,
        // not once more after the check).
        let first = if self.order.is_none() && self.last_iterations == 0 && !self.renewal_due {
            Order::Value
        } else {
            Order::First
        };
        // Nor at a corrected point, which usually passes.
        let then = if self.order.is_none() { Order::Value } else { Order::First };
        let info = correct_from(mech, state, kin, &self.params, None, (first, then))?;
        self.last_iterations = info.iterations;
        if self.extrapolated && info.iterations > 0 {
            if let Some(h) = &mut self.history {
                h.deepen();
            }
        }
        // Newton leaves the deformations at the accepted position in
        // `kin.rhs`, which every later use overwrites first: take them.
        std::mem::swap(&mut self.residual, &mut kin.rhs);
        // The prediction is accurate to O(h^3) along a smooth path (eqs.
        // 5.18, 5.22; the polynomial through the last positions, better),
        // so the correction shrinks against the predicted move as h^2 when
        // the step is subdivided. A correction of more than [`KAPPA`] of the
        // predicted move therefore means the step was too long to trust:
        // it may have crossed a limit position or jumped over a locked zone
        // to another assembly branch. Halving it then either converges
        // (a smooth path) or closes in on the limit position (where the
        // path turns back and the prediction gets worse, not better).
        if info.iterations == 0 {
            return Ok(info);
        }
        // (Taken only here: computed with the prediction, the square root
        // would hold up the positions that need no correction, most of them.)
        let predicted = std::hint::black_box(predicted_sq).sqrt();
        let corrected: f64 = mech
            .moving_coords()
            .iter()
            .zip(&self.predicted_x)
            .map(|(&i, &p)| (state.x[i] - p) * (state.x[i] - p))
            .sum::<f64>()
            .sqrt();
        let kappa = if self.first_order_only { KAPPA_FIRST } else { KAPPA };
        // A converged position is known to about the tolerance times the
        // transfer ratio (|move| / |input change|), which grows without
        // bound towards a limit position.
        let dq = self.delta.iter().map(|d| d * d).sum::<f64>().sqrt();
        let ratio = if dq > 0.0 { predicted / dq } else { 0.0 };
        if corrected > kappa * predicted + 1e3 * self.params.tol * (1.0 + ratio) {
            return Err(SolveError::BranchJump { predicted, corrected });
        }
        Ok(info)
    }

    /// Moves the moving co-ordinates to the predicted position for the
    /// input change `self.delta` (the inputs in `state.target` are already
    /// the new ones); returns the square of the length of the predicted
    /// move (its root is wanted only after a correction: a square root's
    /// latency is a good part of a step that needs none).
    fn predict(&mut self, mech: &Mechanism, state: &mut State, kin: &mut Kinematics) -> f64 {
        let nd = mech.n_dof();
        let moving = mech.moving_coords();
        let extrapolated = self.use_history
            && !self.subdividing
            && self.delta.iter().any(|&d| d != 0.0)
            && self
                .history
                .as_mut()
                .is_some_and(|h| h.extrapolate(state.target[mech.input_row(0)], &mut self.predicted_x));
        self.extrapolated = extrapolated;
        self.first_order_only = false;
        if !extrapolated {
            // Nothing known at this point, or (one input) only the first
            // order, whose prediction is too coarse to check a step by:
            // get the transfer functions (a limit position leaves none, and
            // no prediction). Several inputs never extrapolate, and a run
            // of first order predicts them from the first order it has.
            let known = kin.order();
            let wanted = if self.history.is_some() {
                Some(TransferOrder::Second)
            } else {
                known.or(Some(TransferOrder::Second))
            };
            if known < wanted && self.delta.iter().any(|&d| d != 0.0) {
                let _ = kin.transfer(mech, state, TransferOrder::Second);
            }
            let order = kin.order();
            self.first_order_only = order == Some(TransferOrder::First);
            for (p, &i) in self.predicted_x.iter_mut().zip(moving) {
                *p = state.x[i];
            }
            if order.is_some() {
                // eqs. 5.18, 5.22: x += x' d + 1/2 x'' d d.
                for j in 0..nd {
                    let dj = self.delta[j];
                    for (p, v) in self.predicted_x.iter_mut().zip(kin.x1(j)) {
                        *p += v * dj;
                    }
                    if order == Some(TransferOrder::Second) {
                        for m in 0..nd {
                            let djm = 0.5 * dj * self.delta[m];
                            for (p, v) in self.predicted_x.iter_mut().zip(kin.x2(j, m)) {
                                *p += v * djm;
                            }
                        }
                    }
                }
            }
        }
        let mut moved = 0.0;
        for (c, &i) in moving.iter().enumerate() {
            let d = self.predicted_x[c] - state.x[i];
            moved += d * d;
            state.x[i] = self.predicted_x[c];
        }
        moved
    }
}

/// The largest correction of a step, as a fraction of the predicted move,
/// that is taken as a step along the same branch (see
/// [`Stepper::try_step`]).
const KAPPA: f64 = 0.01;

/// The same for a prediction of the first order only (several inputs in
/// a run of first order), whose error shrinks against the move as h, not
/// h^2. Such a run computes det(D^c) at every position, whose sign is
/// checked as well.
const KAPPA_FIRST: f64 = 0.1;

/// Deformations above this fraction of the tolerance are refined before a
/// position goes into the history: amplified by the extrapolation they
/// would soon matter.
const REFINE_ABOVE: f64 = 1e-2;

/// Most positions in a row left out of the history (see
/// [`Stepper::remember`]); after so many one is kept even when it
/// passed unrefined, so that the extrapolation never reaches far beyond
/// its last point.
const MAX_SKIPPED: usize = 32;

/// When a run of positions only factorises D^c afresh. It needs D^c for
/// nothing but correcting a prediction (rare) and refining the positions
/// kept for extrapolation. A factorisation from some steps back refines
/// well at fine steps; at coarse ones (a degree of a crank) it leaves
/// deformations that an extrapolation of high degree amplifies until
/// predictions need correcting. So the factorisation may grow older, up
/// to `max_age` positions, while predictions pass: each one that needs
/// correcting halves `max_age`, and 128 `max_age` positions in a row that
/// do not double it (up to 256).
struct Renewal {
    /// Positions since D^c was last factorised.
    age: usize,
    max_age: usize,
    /// Positions in a row whose prediction passed.
    clean: usize,
}

impl Renewal {
    /// Whether the next position renews the factorisation if it must refine.
    fn due_next(&self) -> bool {
        self.age + 1 >= self.max_age
    }

    /// Whether to factorise D^c at the position just accepted, after a
    /// correction `info` of a prediction that was `extrapolated`, to
    /// `refine` it for the history.
    fn renew(&mut self, info: NewtonInfo, extrapolated: bool, refine: bool) -> bool {
        if info.iterations > 0 && extrapolated {
            self.max_age = (self.max_age / 2).max(1);
            self.clean = 0;
        } else {
            self.clean += 1;
            if self.clean >= 128 * self.max_age {
                self.max_age = (2 * self.max_age).min(256);
                self.clean = 0;
            }
        }
        // The correction factorised D^c near here.
        let fresh = info.factorisations > 0;
        self.age = if fresh { 0 } else { self.age + 1 };
        // A correction with an old factorisation renews it as well, for the
        // chord steps of the next ones.
        let renew = !fresh && ((refine && self.age >= self.max_age) || info.iterations > 0);
        if renew {
            self.age = 0;
        }
        renew
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_factorisation_ages_while_predictions_pass() {
        let mut r = Renewal { age: 0, max_age: 1, clean: 0 };
        let passed = NewtonInfo::default();
        // Refining at every position: a new factorisation each time, until
        // 128 predictions in a row have passed.
        assert!((0..127).all(|_| r.renew(passed, true, true)));
        // Then every other position.
        assert!(!r.renew(passed, true, true));
        assert_eq!(r.max_age, 2);
        assert!(r.renew(passed, true, true) && !r.renew(passed, true, true) && r.renew(passed, true, true));
        // Which the stepper foresees, to evaluate D^c with the values.
        assert!(!r.due_next() && !r.renew(passed, true, true) && r.due_next() && r.renew(passed, true, true));
        // Nothing to refine: no factorisation, however old.
        assert!((0..10).all(|_| !r.renew(passed, true, false)));
        // A prediction that needed a correction with the old factorisation
        // renews it and halves the age allowed.
        let corrected = NewtonInfo { iterations: 1, ..NewtonInfo::default() };
        assert!(r.renew(corrected, true, false));
        assert_eq!(r.max_age, 1);
        // One that got a factorisation of its own does not.
        let factorised = NewtonInfo { iterations: 2, factorisations: 1, ..NewtonInfo::default() };
        assert!(!r.renew(factorised, true, true) && r.age == 0);
    }
}
