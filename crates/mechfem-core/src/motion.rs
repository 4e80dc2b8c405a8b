//! Input motion: how the inputs move from position to position, and the
//! loop that carries the mechanism through all positions.

/// How one input (degree of freedom) moves.
#[derive(Debug, Clone, PartialEq)]
pub enum InputMotion {
    /// Equidistant steps changing the input by `delta` in total (MOV_RELE).
    Relative {
        /// Total change.
        delta: f64,
    },
    /// Equidistant steps from the initial value to `end` (MOV_ABSE).
    Absolute {
        /// Final value.
        end: f64,
    },
    /// One row per position: time, value, velocity, acceleration (MOV_FUNC).
    Table {
        /// `[t, value, velocity, acceleration]`, one per position.
        rows: Vec<[f64; 4]>,
    },
    /// Free motion with step `ds` in co-ordinate space (MOV_FREE).
    Free {
        /// Euclidean step length of the moving co-ordinates.
        ds: f64,
    },
}

/// A motion program: `steps` steps (positions 1..=steps+1), each `dt` long,
/// and one [`InputMotion`] per degree of freedom.
#[derive(Debug, Clone, PartialEq)]
pub struct Motion {
    /// Number of steps n.
    pub steps: usize,
    /// Time per step.
    pub dt: f64,
    /// One entry per DOF, in DOF order.
    pub inputs: Vec<InputMotion>,
}

use crate::error::SolveError;
use crate::model::{Mechanism, State};
use crate::solver::{adjust, correct, AdjustInfo, Kinematics, Params, TransferOrder};

/// Everything known at one position, handed to an [`Observer`].
pub struct PositionView<'a> {
    /// Position index, 0-based (position 1 of the deck is index 0).
    pub index: usize,
    /// Time.
    pub time: f64,
    /// The model.
    pub mech: &'a Mechanism,
    /// Co-ordinates and prescribed values.
    pub state: &'a State,
    /// Transfer functions at this position.
    pub kin: &'a Kinematics,
    /// Input velocities.
    pub input_vel: &'a [f64],
    /// Input accelerations.
    pub input_acc: &'a [f64],
}

impl PositionView<'_> {
    /// Value of input j.
    pub fn input(&self, j: usize) -> f64 {
        self.state.target[self.mech.input_row(j)]
    }
}

/// Receives every position as soon as it is computed, so results can be
/// streamed rather than held.
pub trait Observer {
    /// Called once per position, in order.
    fn position(&mut self, view: &PositionView<'_>);
}

/// Why a motion stopped before its last position.
#[derive(Debug, Clone, PartialEq)]
pub struct Stop {
    /// Index of the last position that was computed (0-based).
    pub last_good: usize,
    /// Input values that could not be reached.
    pub inputs: Vec<f64>,
    /// Input values at the last good position.
    pub last_inputs: Vec<f64>,
    /// The failure at the smallest step tried.
    pub error: SolveError,
}

/// What a run did.
#[derive(Debug, Clone, PartialEq)]
pub struct RunReport {
    /// The adjustment of position 1.
    pub adjust: AdjustInfo,
    /// Number of positions computed and observed.
    pub positions: usize,
    /// Steps that had to be subdivided (their count).
    pub subdivided_steps: usize,
    /// Set when the motion stopped early.
    pub stop: Option<Stop>,
}

/// Input values, velocities and accelerations at every position, and time.
struct Schedule {
    values: Vec<f64>,
    vel: Vec<f64>,
    acc: Vec<f64>,
    time: Vec<f64>,
    n_dof: usize,
}

impl Schedule {
    fn new(motion: &Motion, start: &[f64]) -> Result<Schedule, SolveError> {
        let (n, nd) = (motion.steps, start.len());
        let mut s = Schedule {
            values: vec![0.0; (n + 1) * nd],
            vel: vec![0.0; (n + 1) * nd],
            acc: vec![0.0; (n + 1) * nd],
            time: (0..=n).map(|k| k as f64 * motion.dt).collect(),
            n_dof: nd,
        };
        let mut table_time = false;
        for (j, m) in motion.inputs.iter().enumerate() {
            for k in 0..=n {
                let at = k * nd + j;
                let lin = |delta: f64| (start[j] + delta * k as f64 / n as f64, delta / (n as f64 * motion.dt));
                let (v, vd, vdd) = match m {
                    InputMotion::Relative { delta } => {
                        let (v, vd) = lin(*delta);
                        (v, vd, 0.0)
                    }
                    InputMotion::Absolute { end } => {
                        let (v, vd) = lin(end - start[j]);
                        (v, vd, 0.0)
                    }
                    InputMotion::Table { rows } => {
                        let r = rows.get(k).ok_or(SolveError::Unsupported("a motion table has fewer rows than positions"))?;
                        if !table_time {
                            s.time[k] = r[0];
                        }
                        (r[1], r[2], r[3])
                    }
                    InputMotion::Free { .. } => {
                        return Err(SolveError::Unsupported(
                            "free motion (MOV_FREE) is not available in this version; drive the mechanism with MOV_RELE, MOV_ABSE or MOV_FUNC",
                        ))
                    }
                };
                s.values[at] = v;
                s.vel[at] = vd;
                s.acc[at] = vdd;
            }
            table_time |= matches!(m, InputMotion::Table { .. });
        }
        Ok(s)
    }
    fn values(&self, k: usize) -> &[f64] {
        &self.values[k * self.n_dof..(k + 1) * self.n_dof]
    }
    fn vel(&self, k: usize) -> &[f64] {
        &self.vel[k * self.n_dof..(k + 1) * self.n_dof]
    }
    fn acc(&self, k: usize) -> &[f64] {
        &self.acc[k * self.n_dof..(k + 1) * self.n_dof]
    }
}

/// Runs a motion: adjusts position 1, then steps the inputs through every
/// position, calling `observer` at each. Without a motion only position 1
/// is computed.
///
/// Each step predicts the new co-ordinates from the first- and second-order
/// transfer functions and corrects them by Newton. A step whose correction
/// fails, or moves the mechanism farther than the prediction did (a jump to
/// another assembly branch), is halved, up to `params.max_halvings` times.
/// When even the smallest step fails the run stops, and the report says
/// where and why; every position computed so far has been observed.
///
/// An error is returned only when position 1 itself cannot be computed.
pub fn run(mech: &Mechanism, state: &mut State, motion: Option<&Motion>, params: &Params, observer: &mut dyn Observer) -> Result<RunReport, SolveError> {
    let nd = mech.n_dof();
    let mut kin = Kinematics::new(mech);
    let schedule = match motion {
        Some(m) => {
            // A motion table fixes the inputs at position 1 too.
            for (j, im) in m.inputs.iter().enumerate() {
                if let InputMotion::Table { rows } = im {
                    if let Some(r) = rows.first() {
                        state.target[mech.input_row(j)] = r[1];
                    }
                }
            }
            let start: Vec<f64> = (0..nd).map(|j| state.target[mech.input_row(j)]).collect();
            Some(Schedule::new(m, &start)?)
        }
        None => None,
    };
    let adjust_info = adjust(mech, state, &mut kin, params)?;
    kin.transfer(mech, state, TransferOrder::Second)?;
    let zeros = vec![0.0; nd];
    let (time0, vel0, acc0) = match &schedule {
        Some(s) => (s.time[0], s.vel(0), s.acc(0)),
        None => (0.0, &zeros[..], &zeros[..]),
    };
    observer.position(&PositionView { index: 0, time: time0, mech, state, kin: &kin, input_vel: vel0, input_acc: acc0 });
    let mut report = RunReport { adjust: adjust_info, positions: 1, subdivided_steps: 0, stop: None };
    let Some(s) = schedule else { return Ok(report) };
    let mut stepper = Stepper::new(mech, params);
    for k in 1..=motion.map_or(0, |m| m.steps) {
        match stepper.step(mech, state, &mut kin, s.values(k - 1), s.values(k)) {
            Ok(halved) => report.subdivided_steps += usize::from(halved),
            Err(error) => {
                report.stop = Some(Stop { last_good: k - 1, inputs: s.values(k).to_vec(), last_inputs: s.values(k - 1).to_vec(), error });
                return Ok(report);
            }
        }
        observer.position(&PositionView { index: k, time: s.time[k], mech, state, kin: &kin, input_vel: s.vel(k), input_acc: s.acc(k) });
        report.positions += 1;
    }
    Ok(report)
}

/// Carries the mechanism from one set of input values to the next.
struct Stepper {
    saved_x: Vec<f64>,
    saved_branch: Vec<f64>,
    saved_target: Vec<f64>,
    delta: Vec<f64>,
    predicted_x: Vec<f64>,
    params: Params,
}

impl Stepper {
    fn new(mech: &Mechanism, params: &Params) -> Stepper {
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
    fn step(&mut self, mech: &Mechanism, state: &mut State, kin: &mut Kinematics, from: &[f64], to: &[f64]) -> Result<bool, SolveError> {
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
    fn try_step(&mut self, mech: &Mechanism, state: &mut State, kin: &mut Kinematics, from: &[f64], to: &[f64], s1: f64) -> Result<(), SolveError> {
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
