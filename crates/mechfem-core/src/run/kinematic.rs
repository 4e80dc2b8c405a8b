//! The kinematic run (mode `KIN ANA`): position 1 adjusted, then the
//! inputs stepped through every position of the motion program, driven or
//! free, with the limit positions met on the way. The other run modes move
//! the mechanism through it too: a simulation without a free DOF runs its
//! prescribed motion, an optimiser's evaluation records sensitivities along
//! it, and inverse dynamics is evaluated at its positions.

use super::observe::{Observer, PositionView, RunReport, Stop};
use crate::error::{SolveError, Unsupported};
use crate::model::{Mechanism, State};
use crate::motion::free::FreeStepper;
use crate::motion::limits::{self, LimitKind, LimitPosition};
use crate::motion::schedule::Schedule;
use crate::motion::step::Stepper;
use crate::motion::{InputMotion, Motion};
use crate::solver::{adjust, Kinematics, Params, TransferOrder};

/// Runs a motion: adjusts position 1, then steps the inputs through every
/// position, calling `observer` at each. Without a motion only position 1
/// is computed.
///
/// Driven motion predicts each position (from the transfer functions or
/// the last positions) and corrects it by Newton. A step whose correction
/// fails, moves the mechanism more than 1 % of the predicted move away from
/// the prediction, or changes the sign of det(D^c), may have crossed a
/// limit position or jumped to another assembly branch: it is halved, up
/// to `params.max_halvings` times. When even the smallest step fails the
/// run stops; the report says where and why, and locates the limit
/// position the input ran into. So a driven motion does not jump over a
/// limit position to another assembly branch (a run of positions only,
/// which has no det(D^c), may still pass a point where two branches meet,
/// such as a parallelogram's collinear position). Every
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
        return Err(SolveError::Unsupported(Unsupported::FreeNeedsOneDof));
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
    let view = PositionView { index: 0, time: time0, mech, state, kin: &kin, input_vel: vel0, input_acc: acc0 };
    observer.check(&view)?;
    observer.position(&view);
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
pub(super) fn timed_finite(mech: &Mechanism, kin: &Kinematics, qd: &[f64], qdd: &[f64]) -> Result<(), SolveError> {
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
        // (det(D^c) keeps its sign from position to position: the stepper
        // refuses a step that changes it.)
        let det = kin.det();
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
        let view =
            PositionView { index: k, time: s.time(k), mech, state, kin, input_vel: s.vel(k), input_acc: s.acc(k) };
        // The observer's own results (inverse dynamics) may not be finite
        // here: the motion stops at the position before.
        if let Err(error) = observer.check(&view) {
            state.clone_from(&previous);
            let (inputs, last_inputs) = (s.values(k).to_vec(), s.values(k - 1).to_vec());
            report.stop = Some(Stop { last_good: k - 1, inputs, last_inputs, error, limit: None });
            return;
        }
        observer.position(&view);
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
        let view = PositionView { index: k, time, mech, state, kin, input_vel: &zeros, input_acc: &zeros };
        if let Err(error) = observer.check(&view) {
            let last = vec![before.target[mech.input_row(dof)]];
            state.clone_from(&before);
            report.stop = Some(Stop { last_good: k - 1, inputs: Vec::new(), last_inputs: last, error, limit: None });
            return;
        }
        observer.position(&view);
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
