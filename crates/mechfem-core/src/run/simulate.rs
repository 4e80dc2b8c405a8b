//! Forward dynamics (mode `DYN SIM`): the motion a mechanism makes under
//! its forces.
//!
//! The equations of motion live in the degrees of freedom only: every
//! co-ordinate follows from q by the kinematics, so `M(q) q'' = -b(q, q', t)`
//! with b the drive forces inverse dynamics finds for q'' = 0 (velocity
//! terms, gravity, springs, loads). A free DOF (MOV_DYN) has no drive: its
//! acceleration makes its drive force zero. A driven DOF follows its
//! prescribed motion and its drive force is what that motion needs. There is
//! no constraint drift to correct: positions are found by Newton at every
//! evaluation, from a prediction by the first-order transfer functions.
//!
//! The free DOFs and their speeds are integrated one step at a time
//! ([`advance`]) by the explicit Runge-Kutta methods of Dormand and Prince
//! of order 8 (DOP853, mechfem's own: [`dop853`]) and 5(4), and the
//! implicit Radau IIA of order 5 with a Jacobian of the reduced equations
//! by finite differences over the free states (both of the crate
//! `differential-equations`). The
//! default (`INTEGRATOR auto`) integrates with Dormand-Prince 5(4) and goes
//! over to Radau IIA where the motion is stiff (stiff springs and dampers,
//! a motion come to rest), and back where it is not, as LSODA does; the
//! report says which method ran where ([`SimReport::segments`]).
//!
//! The outputs come from the integrator's own solution: at each output time
//! its dense output gives q and q', the position there is found by Newton
//! from the last position the integrator found (within the step that
//! contains the output time, so on the branch the integration follows),
//! and q'' from the equations of motion. Each output is handed to the
//! observer as soon as the step that contains it is accepted, whatever the
//! spacing of the outputs against the steps; the integration then goes on
//! from the position it found itself, so that the outputs asked for do not
//! change the motion. The last step ends at the last output time exactly.
//! A STOPWHEN condition is watched at the end of every step and its
//! crossing located on the dense output ([`Event`]).

mod advance;
mod dop853;
mod eom;
mod free_state;
mod outputs;
mod stiffness;
mod system;

use differential_equations::methods::{DormandPrince, ExplicitRungeKutta, ImplicitRungeKutta, Ordinary, Radau};

use super::inverse::InverseDynamics;
use super::kinematic::{run, timed_finite};
use super::observe::{Observer, RunReport, Stop};
use crate::dynamics::{Dynamics, Integration, Integrator};
use crate::error::{SolveError, Unsupported};
use crate::model::{Mechanism, State};
use crate::motion::{InputMotion, Motion};
use crate::solver::{adjust, Kinematics, Params, TransferOrder};
use advance::{advance, Next, Run};
use dop853::Dop853;
use eom::{Driver, Eom, LIMIT_REASON};
use free_state::FreeState;
pub use outputs::Event;
use outputs::Outputs;
use system::System;

/// What a simulation did: the integrator's work, and the outputs it gave.
#[derive(Debug, Clone, PartialEq)]
pub struct SimReport {
    /// The outputs observed; its `stop` says why the simulation ended
    /// early, if it did.
    pub run: RunReport,
    /// The tolerances and the method asked for.
    pub integration: Integration,
    /// Steps the integrator accepted.
    pub steps: usize,
    /// Steps it rejected (too large an error estimate, or a position that
    /// could not be found).
    pub rejected: usize,
    /// Evaluations of the equations of motion, each one Newton position
    /// (found or not): the integrator's stages, those of its Jacobians,
    /// and the positions of the outputs and of a STOPWHEN crossing.
    pub evaluations: usize,
    /// Jacobians of the equations computed by the implicit method (each
    /// `2 nf + 1` evaluations).
    pub jacobians: usize,
    /// The time the integration reached.
    pub reached: f64,
    /// Which method integrated which stretch of time, in order.
    pub segments: Vec<Segment>,
    /// Where a STOPWHEN condition ended the simulation, if it did.
    pub event: Option<Event>,
    /// Why the Newton tolerance and the integrator's tolerances conflict,
    /// if they do ([`Integration::conflict`]).
    pub tolerance_warning: Option<String>,
}

/// A stretch of time one method integrated.
#[derive(Debug, Clone, PartialEq)]
pub struct Segment {
    /// The method ([`Integrator::Dop853`], [`Integrator::Dopri5`] or
    /// [`Integrator::Radau5`]).
    pub method: Integrator,
    /// Start and end time.
    pub from: f64,
    /// End time.
    pub to: f64,
    /// Steps accepted in it.
    pub steps: usize,
    /// Evaluations of the equations of motion in it.
    pub evaluations: usize,
}

/// The most steps a simulation to `end` with outputs every `dt` may take:
/// 2000 per output interval on average, and at least 200 000. A motion that
/// needs more has oscillations far faster than anything the outputs could
/// show (a very stiff spring resolved step by step), and would otherwise run
/// for hours.
fn max_steps(end: f64, dt: f64) -> usize {
    let outputs = (end / dt).ceil().clamp(1.0, 1e6);
    (200_000.0 + 2_000.0 * outputs) as usize
}

/// Simulates the motion of `mech` under the masses and loads of
/// `dynamics`, from the position `state` (adjusted first, as in a run) and
/// the velocities of `motion`'s [`InputMotion::Dynamic`] inputs; the other
/// inputs follow their prescribed motion. The output times are those of
/// `motion` (`steps` steps of `dt`); `observer` sees every output position
/// with its velocities and accelerations, as in [`run`], as soon as the
/// integration has passed it, and `state` is left at the last one.
///
/// An error is returned only when position 1 cannot be computed, or the
/// motion cannot be simulated at all (a free DOF without mass, free motion
/// MOV_FREE); a simulation that ends early (a limit position, a collapsing
/// step, a stiff problem, Ctrl-C) returns what it reached, with the reason
/// in `run.stop`.
pub fn simulate(
    mech: &Mechanism,
    state: &mut State,
    motion: &Motion,
    params: &Params,
    integration: &Integration,
    dynamics: &Dynamics,
    observer: &mut dyn Observer,
) -> Result<SimReport, SolveError> {
    simulate_within(mech, state, motion, params, integration, dynamics, None, observer)
}

/// As [`simulate`], with at most `budget` accepted and rejected integrator
/// steps instead of the default (2000 per output interval on average, at
/// least 200 000), for a caller that must bound the work any model can
/// cause (a fuzzer, a quick check). A simulation that uses the budget up
/// stops with that reason, like any other early end.
#[allow(clippy::too_many_arguments)]
pub fn simulate_within(
    mech: &Mechanism,
    state: &mut State,
    motion: &Motion,
    params: &Params,
    integration: &Integration,
    dynamics: &Dynamics,
    budget: Option<u32>,
    observer: &mut dyn Observer,
) -> Result<SimReport, SolveError> {
    let nd = mech.n_dof();
    let (mut free, mut v0, mut driven) = (Vec::new(), Vec::new(), Vec::new());
    motion.apply_initial_inputs(mech, state);
    let start: Vec<f64> = (0..nd).map(|j| state.target[mech.input_row(j)]).collect();
    let span = motion.steps as f64 * motion.dt;
    for (j, im) in motion.inputs.iter().enumerate() {
        match im {
            InputMotion::Dynamic { v0: v } => {
                free.push(j);
                v0.push(*v);
            }
            InputMotion::Relative { delta } => driven.push((j, Driver::Linear { start: start[j], rate: delta / span })),
            InputMotion::Absolute { end } => {
                driven.push((j, Driver::Linear { start: start[j], rate: (end - start[j]) / span }))
            }
            InputMotion::Table { rows } => driven.push((j, Driver::Table(rows.clone()))),
            InputMotion::Free { .. } => return Err(SolveError::Unsupported(Unsupported::FreeNotTimed)),
        }
    }
    if free.is_empty() {
        return prescribed(mech, state, motion, params, integration, &driven, observer);
    }
    observer.moved_by_forces(&free);
    let mut kin = Kinematics::new(mech);
    let adjusted = adjust(mech, state, &mut kin, params)?;
    kin.transfer(mech, state, TransferOrder::Second)?;
    let nf = free.len();
    let y0: Vec<f64> = free.iter().map(|&j| start[j]).chain(v0.iter().copied()).collect();
    let mut eom = Eom {
        mech,
        params: *params,
        state: state.clone(),
        kin,
        inverse: InverseDynamics::new(mech, dynamics.clone()),
        free,
        driven,
        q: start.clone(),
        qd: vec![0.0; nd],
        qdd: vec![0.0; nd],
        drives: vec![0.0; nd],
        q_last: start.clone(),
        m_ff: vec![0.0; nf * nf],
        rhs: vec![0.0; nf],
        saved: state.clone(),
        evaluations: 0,
        found_t: 0.0,
        found_y: y0.clone(),
        kept: state.clone(),
        kept_q: start.clone(),
        kept_y: y0.clone(),
        kept_t: 0.0,
        det_max: 0.0,
        limit_met: false,
        det_last: 0.0,
        kept_det: 0.0,
    };
    eom.inverse.set_moved_by_forces(&eom.free);
    // The free DOFs' accelerations at the start: a model they cannot move
    // in is refused here, before anything is integrated.
    let mut acc0 = vec![0.0; nf];
    eom.accelerations(0.0, &y0, &mut acc0)?;
    let g0 = integration.stop_when.map_or(f64::NAN, |sw| eom.watch(sw.quantity, &acc0) - sw.value);
    let view = eom.view(0, &acc0);
    timed_finite(mech, view.kin, view.input_vel, view.input_acc)?;
    observer.check(&view)?;
    observer.position(&view);
    let det = view.kin.det();
    let interrupted = motion.steps > 0 && observer.stop_requested();
    let mut run = Run {
        sys: System::new(eom),
        out: Outputs {
            observer,
            steps: motion.steps,
            dt: motion.dt,
            next: 1,
            previous: state.clone(),
            prev_inputs: start.clone(),
            inputs: start.clone(),
            det_prev2: f64::NAN,
            det_prev: det,
            det_max: det.abs(),
            report: RunReport {
                adjust: adjusted,
                positions: 1,
                subdivided_steps: 0,
                limits: Vec::new(),
                singular_positions: Vec::new(),
                stop: None,
            },
            stop: interrupted.then_some(SolveError::Interrupted),
            done: motion.steps == 0 || interrupted,
            stop_when: integration.stop_when,
            g_prev: g0,
            event: None,
        },
        span,
        tol: *integration,
        budget: budget.map_or_else(|| max_steps(span, motion.dt), |b| b as usize),
        budget_given: budget.is_some(),
        t: 0.0,
        y: y0,
        h: 0.0,
        steps: 0,
        rejected: 0,
        acc: vec![0.0; nf],
        a0: acc0,
        a1: vec![0.0; nf],
        yd: vec![0.0; 2 * nf],
        error: None,
    };
    let segments = integrate(&mut run, integration);
    let Run { sys, out, steps, rejected, error, t, .. } = run;
    let jacobians = sys.jacobians.get();
    let eom = sys.eom.into_inner();
    let mut report = out.report;
    state.clone_from(&out.previous);
    let reached = out.event.as_ref().map_or(t.min(span), |e| e.time);
    if report.positions < motion.steps + 1 && out.event.is_none() {
        let error = match out.stop.or(error) {
            // Steps cut down again and again at a limit position end as a
            // collapse or as apparent stiffness: the limit is the reason.
            Some(SolveError::Simulation { time, .. }) if eom.limit_met => {
                SolveError::Simulation { time, reason: LIMIT_REASON }
            }
            Some(e) => e,
            None => SolveError::Interrupted,
        };
        report.stop = Some(Stop {
            last_good: report.positions - 1,
            inputs: Vec::new(),
            last_inputs: out.prev_inputs,
            error,
            limit: None,
        });
    }
    Ok(SimReport {
        run: report,
        integration: *integration,
        steps,
        rejected,
        evaluations: eom.evaluations,
        jacobians,
        reached,
        segments,
        event: out.event,
        tolerance_warning: integration.conflict(params.tol),
    })
}

/// Integrates `run` to its end with the method of `integration`, the
/// automatic choice switching between Dormand-Prince 5(4) and Radau IIA;
/// the stretches each method integrated. The free state is an array for
/// up to three free DOFs, a `Vec` beyond ([`FreeState`] for the implicit
/// method).
fn integrate(run: &mut Run<'_, '_>, integration: &Integration) -> Vec<Segment> {
    match run.y.len() {
        2 => integrate_as::<[f64; 2], [f64; 2]>(run, integration),
        4 => integrate_as::<[f64; 4], [f64; 4]>(run, integration),
        6 => integrate_as::<[f64; 6], [f64; 6]>(run, integration),
        n => {
            free_state::set_dimension(n);
            integrate_as::<Vec<f64>, FreeState>(run, integration)
        }
    }
}

/// [`integrate`] with the free state `Y` for the explicit methods and `Z`
/// for the implicit one.
fn integrate_as<Y: system::Free + 'static, Z: system::Free + 'static>(
    run: &mut Run<'_, '_>,
    integration: &Integration,
) -> Vec<Segment> {
    let auto = integration.integrator == Integrator::Auto;
    let mut method = match integration.integrator {
        Integrator::Auto => Integrator::Dopri5,
        m => m,
    };
    let (rtol, atol, span, n) = (integration.rtol, integration.atol, run.span, run.y.len());
    let mut segments = Vec::new();
    while !run.out.done {
        let (from, calls, steps) = (run.t, run.sys.eom.borrow().evaluations, run.steps);
        let next = match method {
            Integrator::Radau5 => advance::<Z, _>(run, method, auto, |h| {
                // One tolerance per state: the library transforms its
                // tolerances (rtol' = 0.1 rtol^(2/3)) once per state, so a
                // single scalar would be transformed 2 nf times over.
                ImplicitRungeKutta::<Ordinary, Radau, f64, Z, 5, 3, 3>::radau5()
                    .rtol(vec![rtol; n])
                    .atol(vec![atol; n])
                    .h0(h)
                    .h_max(span)
                    .max_steps(usize::MAX)
            }),
            Integrator::Dop853 => advance::<Y, _>(run, method, auto, |h| Dop853::<Y>::new(rtol, atol, h, span)),
            _ => advance::<Y, _>(run, method, auto, |h| {
                ExplicitRungeKutta::<Ordinary, DormandPrince, f64, Y, 5, 7, 7>::dopri5()
                    .rtol(rtol)
                    .atol(atol)
                    .h0(h)
                    .h_max(span)
                    .max_steps(usize::MAX)
            }),
        };
        let to = run.out.event.as_ref().map_or(run.t, |e| e.time);
        if to > from || segments.is_empty() {
            segments.push(Segment {
                method,
                from,
                to,
                steps: run.steps - steps,
                evaluations: run.sys.eom.borrow().evaluations - calls,
            });
        }
        match next {
            Next::Switch(m) => method = m,
            Next::Done => break,
        }
    }
    segments
}

/// A simulation without a free DOF: the prescribed motion, run as a
/// kinematic run through the output times.
fn prescribed(
    mech: &Mechanism,
    state: &mut State,
    motion: &Motion,
    params: &Params,
    integration: &Integration,
    driven: &[(usize, Driver)],
    observer: &mut dyn Observer,
) -> Result<SimReport, SolveError> {
    let times = (0..=motion.steps).map(|k| k as f64 * motion.dt);
    let tables = driven.iter().map(|(_, d)| InputMotion::Table {
        rows: times
            .clone()
            .map(|t| {
                let [q, v, a] = d.at(t);
                [t, q, v, a]
            })
            .collect(),
    });
    let replay = Motion { steps: motion.steps, dt: motion.dt, inputs: tables.collect() };
    let report = run(mech, state, Some(&replay), params, observer)?;
    let reached = report.stop.as_ref().map_or(motion.steps, |s| s.last_good) as f64 * motion.dt;
    Ok(SimReport {
        run: report,
        integration: *integration,
        steps: 0,
        rejected: 0,
        evaluations: 0,
        jacobians: 0,
        reached,
        segments: Vec::new(),
        event: None,
        tolerance_warning: integration.conflict(params.tol),
    })
}
