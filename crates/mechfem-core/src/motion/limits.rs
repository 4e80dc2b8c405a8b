//! Limit positions found during a motion (theory section 5.5): where
//! det(D^c) comes close to zero, where a driven input cannot go on, and
//! where free motion passes an extreme of its input. Each is located
//! between the positions that enclose it.

use super::free::FreeStepper;
use crate::model::{Mechanism, State};
use crate::solver::{Kinematics, Params, TransferOrder};

/// What kind of limit position was found.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LimitKind {
    /// |det(D^c)| has a local minimum below 1e-3 of its largest value so far.
    NearZero,
    /// A driven input cannot go on: it reached its extreme value.
    InputLimit,
    /// Free motion passed an extreme value of the original input.
    Passed,
}

/// A limit position, located between positions `after` and `after + 1`
/// (at `after` itself for [`LimitKind::NearZero`]).
#[derive(Debug, Clone, PartialEq)]
pub struct LimitPosition {
    /// Kind.
    pub kind: LimitKind,
    /// Index of the position before it (0-based).
    pub after: usize,
    /// Values of the inputs there.
    pub inputs: Vec<f64>,
    /// All co-ordinates there.
    pub coords: Vec<f64>,
    /// det(D^c) there (close to zero, except for a near-zero minimum).
    pub det: f64,
}

fn inputs_of(mech: &Mechanism, state: &State) -> Vec<f64> {
    (0..mech.n_dof()).map(|j| state.target[mech.input_row(j)]).collect()
}

/// From the last good position of a driven motion that could not go on,
/// follows the free motion towards the wanted input values until the input
/// stops increasing (or decreasing), and bisects for its extreme value.
pub(crate) fn locate_input_limit(
    mech: &Mechanism,
    start: &State,
    dof: usize,
    towards: f64,
    ds: f64,
    params: &Params,
    after: usize,
) -> Option<LimitPosition> {
    if mech.n_dof() != 1 || !(ds > 0.0 && ds.is_finite()) {
        return None;
    }
    let mut kin = Kinematics::dense(mech);
    let mut state = start.clone();
    let mut free = FreeStepper::new(mech, dof, towards, params);
    free.tangent(mech, &mut state, &mut kin).ok()?;
    let mut rate = free.input_rate;
    // March until the rate of the input along the motion changes sign.
    for _ in 0..400 {
        let before = state.clone();
        let t_before = free.tangent.clone();
        free.step(mech, &mut state, &mut kin, ds).ok()?;
        free.tangent(mech, &mut state, &mut kin).ok()?;
        if free.input_rate * rate <= 0.0 {
            return bisect_extreme(
                mech,
                &mut free,
                &mut kin,
                &before,
                &t_before,
                ds,
                rate,
                LimitKind::InputLimit,
                after,
            );
        }
        rate = free.input_rate;
    }
    None
}

/// The input's rate along the free motion is `rate0` at `before` and has
/// the other sign one step `ds` further: bisects the arc length for the
/// extreme value of the input.
pub(crate) fn bisect_extreme(
    mech: &Mechanism,
    free: &mut FreeStepper,
    kin: &mut Kinematics,
    before: &State,
    t_before: &[f64],
    ds: f64,
    rate0: f64,
    kind: LimitKind,
    after: usize,
) -> Option<LimitPosition> {
    let (mut lo, mut hi) = (0.0, ds);
    let mut found: Option<State> = None;
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        let mut s = before.clone();
        free.set_previous(t_before);
        if free.step(mech, &mut s, kin, mid).is_err() {
            break;
        }
        free.tangent(mech, &mut s, kin).ok()?;
        if free.input_rate * rate0 > 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
        found = Some(s);
        if hi - lo < 1e-14 * ds.max(1.0) {
            break;
        }
    }
    let mut found = found?;
    let det = match kin.transfer(mech, &mut found, TransferOrder::First) {
        Ok(()) => kin.det(),
        Err(_) => 0.0,
    };
    Some(LimitPosition { kind, after, inputs: inputs_of(mech, &found), coords: found.x, det })
}
