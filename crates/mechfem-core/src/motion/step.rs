//! One step of driven motion: second-order prediction, Newton correction,
//! and halving of a step that fails or jumps.

use crate::error::SolveError;
use crate::model::{Mechanism, State};
use crate::solver::{correct, Kinematics, Params, TransferOrder};

/// Carries the mechanism from one set of input values to the next.
pub(crate) struct Stepper {
    saved_x: Vec<f64>,
    saved_branch: Vec<f64>,
    saved_target: Vec<f64>,
    delta: Vec<f64>,
    predicted_x: Vec<f64>,
    params: Params,
}

impl Stepper {
    pub(crate) fn new(mech: &Mechanism, params: &Params) -> Stepper {
        Stepper {
            saved_x: vec![0.0; mech.n_coords()],
            saved_branch: vec![0.0; mech.elements().len()],
            saved_target: vec![0.0; mech.n_prescribed()],
            delta: vec![0.0; mech.n_dof()],
            predicted_x: vec![0.0; mech.n_moving()],
            params: *params,
        }
    }

    /// Moves the inputs from `from` to `to`; on success `kin` holds the
    /// second-order transfer functions at the new position. Returns whether
    /// the step had to be subdivided.
    pub(crate) fn step(
        &mut self,
        mech: &Mechanism,
        state: &mut State,
        kin: &mut Kinematics,
        from: &[f64],
        to: &[f64],
    ) -> Result<bool, SolveError> {
        let (mut s, mut h) = (0.0f64, 1.0f64);
        let min_h = 0.5f64.powi(self.params.max_halvings as i32);
        let mut halved = false;
        while s < 1.0 {
            let s1 = if s + h >= 1.0 - 1e-12 { 1.0 } else { s + h };
            self.saved_x.copy_from_slice(&state.x);
            self.saved_branch.copy_from_slice(&state.branch);
            self.saved_target.copy_from_slice(&state.target);
            match self.try_step(mech, state, kin, from, to, s1) {
                Ok(()) => {
                    s = s1;
                    // Transfer functions at the new point drive the next prediction.
                    let t = kin.transfer(mech, state, TransferOrder::Second);
                    if let Err(e) = t {
                        if s >= 1.0 {
                            return Err(e);
                        }
                    }
                    if halved {
                        h = (2.0 * h).min(1.0 - s).max(min_h);
                    }
                }
                Err(e) => {
                    state.x.copy_from_slice(&self.saved_x);
                    state.branch.copy_from_slice(&self.saved_branch);
                    state.target.copy_from_slice(&self.saved_target);
                    h *= 0.5;
                    halved = true;
                    if h < min_h {
                        return Err(e);
                    }
                    // Restore the transfer functions at the saved point.
                    kin.transfer(mech, state, TransferOrder::Second)?;
                }
            }
        }
        Ok(halved)
    }

    /// Predicts (second order, eqs. 5.18, 5.22) and corrects to the inputs at
    /// fraction `s1` of the step.
    fn try_step(
        &mut self,
        mech: &Mechanism,
        state: &mut State,
        kin: &mut Kinematics,
        from: &[f64],
        to: &[f64],
        s1: f64,
    ) -> Result<(), SolveError> {
        let nd = mech.n_dof();
        for j in 0..nd {
            let r = mech.input_row(j);
            let goal = from[j] + s1 * (to[j] - from[j]);
            self.delta[j] = goal - state.target[r];
            state.target[r] = goal;
        }
        let second = kin.order() == Some(TransferOrder::Second);
        let mut predicted = 0.0;
        if kin.order().is_some() {
            for (c, &i) in mech.moving_coords().iter().enumerate() {
                let mut dx = 0.0;
                for j in 0..nd {
                    dx += kin.x1(j)[c] * self.delta[j];
                    if second {
                        for m in 0..nd {
                            dx += 0.5 * kin.x2(j, m)[c] * self.delta[j] * self.delta[m];
                        }
                    }
                }
                state.x[i] += dx;
                self.predicted_x[c] = state.x[i];
                predicted += dx * dx;
            }
        } else {
            for (c, &i) in mech.moving_coords().iter().enumerate() {
                self.predicted_x[c] = state.x[i];
            }
        }
        correct(mech, state, kin, &self.params)?;
        // A corrector that goes farther than the predictor did has probably
        // jumped to another assembly branch.
        let corrected: f64 =
            mech.moving_coords().iter().enumerate().map(|(c, &i)| (state.x[i] - self.predicted_x[c]).powi(2)).sum();
        let (corrected, predicted) = (corrected.sqrt(), predicted.sqrt());
        if predicted > 0.0 && corrected > predicted + 1e3 * self.params.tol {
            return Err(SolveError::BranchJump { predicted, corrected });
        }
        Ok(())
    }
}
