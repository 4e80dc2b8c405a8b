//! Free motion (theory section 5.5.3): the mechanism moves "just as it can
//! be moved". The input's row is taken out of D^c and replaced by a
//! temporary input, a single moving co-ordinate chosen where the kernel of
//! the reduced D^c is largest; each step moves the co-ordinates a Euclidean
//! distance ds along that kernel (the tangent of the motion), keeping the
//! direction of the previous step, so limit positions of the original input
//! are passed.

use crate::error::{SolveError, Unsupported};
use crate::model::{Mechanism, State};
use crate::solver::{correct_with, Kinematics, Params, TempInput};

/// Steps along the free motion of a one-DOF mechanism.
pub(crate) struct FreeStepper {
    /// Row of the original input.
    row: usize,
    /// Column of the temporary input.
    col: usize,
    /// Unit tangent at the current position, oriented.
    pub(crate) tangent: Vec<f64>,
    /// d(original input)/ds along the oriented tangent.
    pub(crate) input_rate: f64,
    previous: Vec<f64>,
    has_previous: bool,
    /// Direction wanted for the original input before any step is made.
    initial_sign: f64,
    saved_x: Vec<f64>,
    saved_branch: Vec<f64>,
    params: Params,
}

impl FreeStepper {
    pub(crate) fn new(mech: &Mechanism, dof: usize, initial_sign: f64, params: &Params) -> FreeStepper {
        let n = mech.n_moving();
        FreeStepper {
            row: mech.input_row(dof),
            col: 0,
            tangent: vec![0.0; n],
            input_rate: 0.0,
            previous: vec![0.0; n],
            has_previous: false,
            initial_sign,
            saved_x: vec![0.0; mech.n_coords()],
            saved_branch: vec![0.0; mech.elements().len()],
            params: *params,
        }
    }

    /// Solves D_temp t = e_row with the current temporary input column:
    /// t is the kernel of the reduced D^c, scaled so t_col = 1.
    fn raw_tangent(&mut self, mech: &Mechanism, state: &mut State, kin: &mut Kinematics) -> Result<(), SolveError> {
        kin.evaluate(mech, state)?;
        kin.assemble(mech);
        kin.factor_with_unit_row(self.row, self.col)?;
        self.tangent.fill(0.0);
        self.tangent[self.row] = 1.0;
        kin.solve(&mut self.tangent);
        Ok(())
    }

    /// The oriented unit tangent at the current position. The temporary
    /// input moves to the co-ordinate with the largest share of the kernel
    /// whenever the current one has less than half of it.
    pub(crate) fn tangent(
        &mut self,
        mech: &Mechanism,
        state: &mut State,
        kin: &mut Kinematics,
    ) -> Result<(), SolveError> {
        let n = mech.n_moving();
        let mut ok = self.raw_tangent(mech, state, kin).is_ok();
        if ok {
            let big = argmax_abs(&self.tangent);
            if self.tangent[big].abs() > 2.0 * self.tangent[self.col].abs() {
                self.col = big;
                ok = self.raw_tangent(mech, state, kin).is_ok();
            }
        }
        if !ok {
            // Try every column, those the previous tangent favours first.
            let mut order: Vec<usize> = (0..n).collect();
            order.sort_by(|&a, &b| self.previous[b].abs().total_cmp(&self.previous[a].abs()));
            let mut found = false;
            for c in order {
                self.col = c;
                if self.raw_tangent(mech, state, kin).is_ok() {
                    let big = argmax_abs(&self.tangent);
                    if self.tangent[big].abs() <= 2.0 {
                        found = true;
                        break;
                    }
                }
            }
            if !found {
                return Err(SolveError::Unsupported(Unsupported::FreeFoundNoDirection));
            }
        }
        let norm = self.tangent.iter().map(|v| v * v).sum::<f64>().sqrt();
        let mut rate = kin.row_dot(mech, self.row, &self.tangent) / norm;
        let dot: f64 = self.tangent.iter().zip(&self.previous).map(|(a, b)| a * b).sum();
        let flip = if self.has_previous { dot < 0.0 } else { rate * self.initial_sign < 0.0 };
        let f = if flip { -1.0 / norm } else { 1.0 / norm };
        if flip {
            rate = -rate;
        }
        for t in self.tangent.iter_mut() {
            *t *= f;
        }
        self.input_rate = rate;
        Ok(())
    }

    /// Moves the co-ordinates a distance `ds` along the motion from the
    /// current position (halving a step that fails). On success the tangent
    /// of the step just made is remembered for orienting the next.
    pub(crate) fn step(
        &mut self,
        mech: &Mechanism,
        state: &mut State,
        kin: &mut Kinematics,
        ds: f64,
    ) -> Result<(), SolveError> {
        self.tangent(mech, state, kin)?;
        self.saved_x.copy_from_slice(&state.x);
        self.saved_branch.copy_from_slice(&state.branch);
        // The halvings are counted: an infinite or subnormal ds halved
        // never falls below ds / 2^max_halvings.
        let (mut h, mut halvings) = (ds, 0);
        loop {
            for (c, &i) in mech.moving_coords().iter().enumerate() {
                state.x[i] += h * self.tangent[c];
            }
            let temp = TempInput { row: self.row, col: self.col, value: state.x[mech.moving_coords()[self.col]] };
            let moved = correct_with(mech, state, kin, &self.params, Some(temp)).and_then(|_| {
                // The corrector works across the tangent and, along a
                // smooth path, moves the point by about (curvature) h^2 / 2:
                // a correction of more than a tenth of the step means the
                // step cut across to another part of the path (over a
                // locked zone, to another assembly branch) and is halved.
                let off: f64 = mech
                    .moving_coords()
                    .iter()
                    .zip(&self.tangent)
                    .map(|(&i, t)| (state.x[i] - self.saved_x[i] - h * t).powi(2))
                    .sum();
                if off.sqrt() > KAPPA_FREE * h + 1e3 * self.params.tol {
                    Err(SolveError::BranchJump { predicted: h, corrected: off.sqrt() })
                } else {
                    Ok(())
                }
            });
            match moved {
                Ok(()) => break,
                Err(e) => {
                    state.x.copy_from_slice(&self.saved_x);
                    state.branch.copy_from_slice(&self.saved_branch);
                    if halvings == self.params.max_halvings {
                        return Err(e);
                    }
                    h *= 0.5;
                    halvings += 1;
                }
            }
        }
        self.previous.copy_from_slice(&self.tangent);
        self.has_previous = true;
        // The original input is an output now: record where it went.
        state.target[self.row] = state.prescribed_value(mech, self.row)?;
        Ok(())
    }

    /// Forgets the direction of the previous step and sets it anew.
    pub(crate) fn set_previous(&mut self, t: &[f64]) {
        self.previous.copy_from_slice(t);
        self.has_previous = true;
    }
}

/// The largest correction of a free-motion step, as a fraction of the
/// step length, taken as a step along the same path.
const KAPPA_FREE: f64 = 0.1;

fn argmax_abs(v: &[f64]) -> usize {
    (0..v.len()).max_by(|&a, &b| v[a].abs().total_cmp(&v[b].abs())).unwrap_or(0)
}
