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
    /// Moved by the forces, starting with velocity `v0` (MOV_DYN): only a
    /// simulation ([`crate::dynamics::simulate`]) runs it.
    Dynamic {
        /// Initial velocity.
        v0: f64,
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

mod free;
mod history;
mod limits;
mod schedule;
mod step;

pub use limits::{LimitKind, LimitPosition};

use crate::error::SolveError;
use crate::model::{Mechanism, State};
use crate::solver::{adjust, AdjustInfo, Kinematics, Params, TransferOrder};
use free::FreeStepper;
use schedule::Schedule;
use step::Stepper;

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

    /// Asked after every position: `true` ends the run there (for example
    /// on Ctrl-C), with [`SolveError::Interrupted`] as the stop reason.
    fn stop_requested(&self) -> bool {
        false
    }

    /// The transfer functions this observer reads, asked once at the start
    /// of a run. A driven motion computes no more than that at every
    /// position after the first: `Some(First)` for det(D^c) and the
    /// first-order transfer functions, `None` for positions and the values
    /// of the dependent form parameters only (no det(D^c), so no limit
    /// positions are detected along the way). Transfer functions that were
    /// not computed read as NaN. The default is everything.
    fn transfer_order(&self) -> Option<TransferOrder> {
        Some(TransferOrder::Second)
    }

    /// Called by a simulation ([`crate::dynamics::simulate`]) after every
    /// step of its integrator, which has then reached `time` of `end`:
    /// before any position is observed, for progress reports. A run asked
    /// to stop ([`Self::stop_requested`]) stops integrating too.
    fn simulated(&mut self, time: f64, end: f64) {
        let _ = (time, end);
    }
}

impl Motion {
    /// How input j's value and velocity at position `index` (0-based)
    /// change per unit of its start value (its prescribed value at position
    /// 1): (1, 0) for steps of a fixed size (MOV_RELE); (1 - k/n, -1/(n dt))
    /// for steps to a fixed end (MOV_ABSE); (0, 0) where the start does not
    /// move the input (a motion table, free or dynamic motion).
    pub fn start_rates(&self, j: usize, index: usize) -> (f64, f64) {
        let n = self.steps as f64;
        match self.inputs.get(j) {
            Some(InputMotion::Relative { .. }) => (1.0, 0.0),
            Some(InputMotion::Absolute { .. }) if self.steps == 0 => (1.0, 0.0),
            Some(InputMotion::Absolute { .. }) => (1.0 - index as f64 / n, -1.0 / (n * self.dt)),
            _ => (0.0, 0.0),
        }
    }

    /// Sets the inputs that a motion table fixes at position 1 (its first
    /// row), overriding their prescribed values. [`run`] does this itself;
    /// call it to compute position 1 alone the way a run would.
    pub fn apply_initial_inputs(&self, mech: &Mechanism, state: &mut State) {
        for (j, im) in self.inputs.iter().enumerate() {
            if let InputMotion::Table { rows } = im {
                if let Some(r) = rows.first() {
                    state.target[mech.input_row(j)] = r[1];
                }
            }
        }
    }
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
    /// The limit position the input ran into, when one was located.
    pub limit: Option<LimitPosition>,
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
    /// Limit positions met on the way, in order.
    pub limits: Vec<LimitPosition>,
    /// Positions (0-based) where D^c was singular, so that no transfer
    /// functions exist there (free motion only).
    pub singular_positions: Vec<usize>,
    /// Set when the motion stopped early.
    pub stop: Option<Stop>,
}

/// Runs a motion: adjusts position 1, then steps the inputs through every
/// position, calling `observer` at each. Without a motion only position 1
/// is computed.
///
/// Driven motion predicts each position from the first- and second-order
/// transfer functions and corrects it by Newton. A step whose correction
/// fails, or moves the mechanism farther than the prediction did (a jump to
/// another assembly branch), is halved, up to `params.max_halvings` times.
/// When even the smallest step fails the run stops; the report says where
/// and why, and locates the limit position the input ran into. Every
/// position computed so far has been observed, and the state is left at the
/// last of them.
///
/// Free motion ([`InputMotion::Free`]) follows the mechanism through the
/// limit positions of its input instead.
///
/// An error is returned only when position 1 itself cannot be computed.
pub fn run(
    mech: &Mechanism,
    state: &mut State,
    motion: Option<&Motion>,
    params: &Params,
    observer: &mut dyn Observer,
) -> Result<RunReport, SolveError> {
    let nd = mech.n_dof();
    let free = motion.and_then(|m| {
        m.inputs
            .iter()
            .enumerate()
            .find_map(|(j, im)| if let InputMotion::Free { ds } = im { Some((j, *ds)) } else { None })
    });
    let mut kin = if free.is_some() { Kinematics::dense(mech) } else { Kinematics::new(mech) };
    if free.is_some() && nd != 1 {
        return Err(SolveError::Unsupported(
            "free motion (MOV_FREE) needs a mechanism with exactly one degree of freedom",
        ));
    }
    let schedule = match motion {
        Some(m) if free.is_none() => {
            m.apply_initial_inputs(mech, state);
            let start: Vec<f64> = (0..nd).map(|j| state.target[mech.input_row(j)]).collect();
            Some(Schedule::new(m, &start)?)
        }
        _ => None,
    };
    let adjust_info = adjust(mech, state, &mut kin, params)?;
    let mut report = RunReport {
        adjust: adjust_info,
        positions: 1,
        subdivided_steps: 0,
        limits: Vec::new(),
        singular_positions: Vec::new(),
        stop: None,
    };
    match kin.transfer(mech, state, TransferOrder::Second) {
        Ok(()) => {}
        // Free motion may start in a limit position of its input.
        Err(SolveError::Singular { .. }) if free.is_some() => report.singular_positions.push(0),
        Err(e) => return Err(e),
    }
    let zeros = vec![0.0; nd];
    let (time0, vel0, acc0) = match &schedule {
        Some(s) => (s.time(0), s.vel(0), s.acc(0)),
        None => (0.0, &zeros[..], &zeros[..]),
    };
    timed_finite(mech, &kin, vel0, acc0)?;
    observer.position(&PositionView {
        index: 0,
        time: time0,
        mech,
        state,
        kin: &kin,
        input_vel: vel0,
        input_acc: acc0,
    });
    if let (Some((dof, ds)), Some(m)) = (free, motion) {
        run_free(mech, state, &mut kin, m, dof, ds, params, observer, &mut report);
    } else if let (Some(mut s), Some(m)) = (schedule, motion) {
        run_driven(mech, state, &mut kin, m, &mut s, params, observer, &mut report);
    }
    Ok(report)
}

/// Checks that the velocities and accelerations of the moving co-ordinates
/// and the dependent form parameters (eqs. 5.29, 5.30) are finite at the
/// position in `kin`, for input velocities `qd` and accelerations `qdd`:
/// finite transfer functions times finite input rates can still overflow,
/// and an observer must never be handed an infinity as a result.
/// Accelerations are checked only where the second order was computed.
fn timed_finite(mech: &Mechanism, kin: &Kinematics, qd: &[f64], qdd: &[f64]) -> Result<(), SolveError> {
    let Some(order) = kin.order() else { return Ok(()) };
    let second = order == TransferOrder::Second;
    // A bound of every velocity and acceleration: when it lies well inside
    // the range of a double, so does each of them, and none needs computing.
    let largest = |v: &[f64]| v.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let (v, a) = (largest(qd), largest(qdd));
    let (s1, s2) = kin.transfer_sums();
    let bound = s1 * (v + a) + s2 * v * v;
    if bound < 0.5 * f64::MAX {
        return Ok(());
    }
    for &i in mech.moving_coords() {
        let v = kin.velocity(mech, i, qd);
        let a = if second { kin.acceleration(mech, i, qd, qdd) } else { 0.0 };
        if !(v.is_finite() && a.is_finite()) {
            return Err(SolveError::NonFinite);
        }
    }
    for d in 0..mech.n_dependent() {
        let v = kin.dep_velocity(d, qd);
        let a = if second { kin.dep_acceleration(d, qd, qdd) } else { 0.0 };
        if !(v.is_finite() && a.is_finite()) {
            return Err(SolveError::NonFinite);
        }
    }
    Ok(())
}

/// Driven motion through the schedule, with limit-position detection.
fn run_driven(
    mech: &Mechanism,
    state: &mut State,
    kin: &mut Kinematics,
    m: &Motion,
    s: &mut Schedule<'_>,
    params: &Params,
    observer: &mut dyn Observer,
    report: &mut RunReport,
) {
    let nd = mech.n_dof();
    let mut stepper = Stepper::new(mech, params, observer.transfer_order());
    stepper.start(mech, state);
    let mut previous = state.clone();
    let (mut det_prev2, mut det_prev, mut det_max) = (f64::NAN, kin.det(), kin.det().abs());
    for k in 1..=m.steps {
        s.reach(k);
        previous.clone_from(state);
        let stepped = stepper.step(mech, state, &previous, kin, s.values(k - 1), s.values(k));
        match stepped.and_then(|halved| timed_finite(mech, kin, s.vel(k), s.acc(k)).map(|()| halved)) {
            Ok(halved) => report.subdivided_steps += usize::from(halved),
            Err(error) => {
                // The stepper may have got part of the way: go back to the
                // last position observed, the one the report names.
                state.clone_from(&previous);
                // Length of the predicted step, a scale for locating a limit.
                let step_len = match kin.transfer(mech, state, TransferOrder::First) {
                    Ok(()) => (0..nd)
                        .map(|j| {
                            let d = s.values(k)[j] - s.values(k - 1)[j];
                            d * kin.x1(j).iter().map(|v| v * v).sum::<f64>().sqrt()
                        })
                        .fold(0.0f64, |a, v| a.max(v.abs())),
                    Err(_) => f64::NAN,
                };
                let towards = (0..nd).map(|j| s.values(k)[j] - s.values(k - 1)[j]).sum::<f64>().signum();
                let limit = limits::locate_input_limit(mech, state, 0, towards, step_len / 16.0, params, k - 1);
                report.stop = Some(Stop {
                    last_good: k - 1,
                    inputs: s.values(k).to_vec(),
                    last_inputs: s.values(k - 1).to_vec(),
                    error,
                    limit,
                });
                return;
            }
        }
        let det = kin.det();
        if det_prev * det < 0.0 {
            if let Some(l) =
                limits::locate_sign_change(mech, &previous, s.values(k - 1), s.values(k), det_prev, params, k - 1)
            {
                report.limits.push(l);
            }
        }
        det_max = det_max.max(det.abs());
        // A local minimum of |det| far below its scale: a near-limit position.
        if det_prev.abs() < det_prev2.abs() && det_prev.abs() <= det.abs() && det_prev.abs() < 1e-3 * det_max {
            let inputs = s.values(k - 1).to_vec();
            report.limits.push(LimitPosition {
                kind: LimitKind::NearZero,
                after: k - 1,
                inputs,
                coords: previous.x.clone(),
                det: det_prev,
            });
        }
        (det_prev2, det_prev) = (det_prev, det);
        observer.position(&PositionView {
            index: k,
            time: s.time(k),
            mech,
            state,
            kin,
            input_vel: s.vel(k),
            input_acc: s.acc(k),
        });
        report.positions += 1;
        if observer.stop_requested() && k < m.steps {
            report.stop = Some(Stop {
                last_good: k,
                inputs: s.values(k + 1).to_vec(),
                last_inputs: s.values(k).to_vec(),
                error: SolveError::Interrupted,
                limit: None,
            });
            return;
        }
    }
}

/// Free motion of the one DOF `dof` with step `ds` (its sign sets the
/// initial direction of the input).
fn run_free(
    mech: &Mechanism,
    state: &mut State,
    kin: &mut Kinematics,
    m: &Motion,
    dof: usize,
    ds: f64,
    params: &Params,
    observer: &mut dyn Observer,
    report: &mut RunReport,
) {
    let zeros = vec![0.0; mech.n_dof()];
    let mut free = FreeStepper::new(mech, dof, if ds < 0.0 { -1.0 } else { 1.0 }, params);
    let mut before = state.clone();
    let mut rate = match free.tangent(mech, state, kin) {
        Ok(()) => free.input_rate,
        Err(error) => {
            report.stop = Some(Stop {
                last_good: 0,
                inputs: Vec::new(),
                last_inputs: vec![state.target[mech.input_row(dof)]],
                error,
                limit: None,
            });
            return;
        }
    };
    let mut t_before = free.tangent.clone();
    for k in 1..=m.steps {
        before.clone_from(state);
        t_before.copy_from_slice(&free.tangent);
        let moved = free.step(mech, state, kin, ds.abs()).and_then(|_| free.tangent(mech, state, kin));
        if let Err(error) = moved {
            let last = vec![before.target[mech.input_row(dof)]];
            report.stop = Some(Stop { last_good: k - 1, inputs: Vec::new(), last_inputs: last, error, limit: None });
            return;
        }
        if free.input_rate * rate < 0.0 {
            // Passed an extreme of the input: locate it on a copy.
            let mut probe = FreeStepper::new(mech, dof, 1.0, params);
            let mut probe_kin = Kinematics::dense(mech);
            let (before_probe, t) = (before.clone(), t_before.clone());
            if let Some(l) = limits::bisect_extreme(
                mech,
                &mut probe,
                &mut probe_kin,
                &before_probe,
                &t,
                ds.abs(),
                rate,
                LimitKind::Passed,
                k - 1,
            ) {
                report.limits.push(l);
            }
        }
        rate = free.input_rate;
        match kin.transfer(mech, state, TransferOrder::Second) {
            Ok(()) => {}
            Err(SolveError::Singular { .. }) => report.singular_positions.push(k),
            Err(error) => {
                report.stop = Some(Stop {
                    last_good: k - 1,
                    inputs: Vec::new(),
                    last_inputs: vec![before.target[mech.input_row(dof)]],
                    error,
                    limit: None,
                });
                return;
            }
        }
        let time = k as f64 * m.dt;
        observer.position(&PositionView { index: k, time, mech, state, kin, input_vel: &zeros, input_acc: &zeros });
        report.positions += 1;
        if observer.stop_requested() && k < m.steps {
            let last = vec![state.target[mech.input_row(dof)]];
            report.stop = Some(Stop {
                last_good: k,
                inputs: Vec::new(),
                last_inputs: last,
                error: SolveError::Interrupted,
                limit: None,
            });
            return;
        }
    }
}
