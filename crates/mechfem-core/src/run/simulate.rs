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
//! The free DOFs and their speeds are integrated by the explicit
//! Runge-Kutta method of Dormand and Prince of order 5(4) with step-size
//! control, dense output and stiffness detection (`ode_solvers::Dopri5`):
//! a mechanism without stiff springs is not stiff, an explicit method needs
//! one evaluation of the equations (one Newton position) per stage and no
//! Jacobian of them, and a stiff problem is detected and stops the run with
//! that reason instead of creeping on. (The crate's eighth-order `Dop853`
//! would take fewer steps at tight tolerances, but version 0.6 evaluates its
//! twelfth stage at the start of the step instead of its end, which is wrong
//! for forces that depend on time.)
//!
//! The outputs come from the integrator's own solution: at each output time
//! its dense output gives q and q', the position there is found by Newton
//! from the last position the integrator found (within the step that
//! contains the output time, so on the branch the integration follows),
//! and q'' from the equations of motion. Each output is handed to the
//! observer as soon as the step that contains it is accepted, whatever the
//! spacing of the outputs against the steps; the integration then goes on
//! from the position it found itself, so that the outputs asked for do not
//! change the motion.

mod eom;
mod stiffness;

use nalgebra::{allocator::Allocator, Const, DefaultAllocator, Dim, Dyn, OVector, U1};
use ode_solvers::{Dopri5, OutputType, System};
use std::cell::RefCell;

use super::inverse::InverseDynamics;
use super::kinematic::{run, timed_finite};
use super::observe::{Observer, RunReport, Stop};
use crate::dynamics::{Dynamics, Integration};
use crate::error::{SolveError, Unsupported};
use crate::model::{Mechanism, State};
use crate::motion::limits::{LimitKind, LimitPosition};
use crate::motion::{InputMotion, Motion};
use crate::solver::{adjust, Kinematics, Params, TransferOrder};
use eom::{Driver, Eom, LIMIT_REASON};
use stiffness::{Evaluation, Stiffness, STIFF_REASON};

/// What a simulation did: the integrator's work, and the outputs it gave.
#[derive(Debug, Clone, PartialEq)]
pub struct SimReport {
    /// The outputs observed; its `stop` says why the simulation ended
    /// early, if it did.
    pub run: RunReport,
    /// The tolerances used.
    pub integration: Integration,
    /// Steps the integrator accepted.
    pub steps: usize,
    /// Steps it rejected (too large an error estimate, or a position that
    /// could not be found).
    pub rejected: usize,
    /// Evaluations of the equations of motion.
    pub evaluations: usize,
    /// The time the integration reached.
    pub reached: f64,
}

/// The outputs of a simulation as the integration produces them.
struct Outputs<'o> {
    observer: &'o mut dyn Observer,
    /// The last output index (TSTEPE's n), the output interval and the
    /// time of the last output.
    steps: usize,
    dt: f64,
    span: f64,
    /// The time of the next output as the integrator's dense output counts
    /// it (the same sum of intervals, so the same number to the last bit),
    /// and its index.
    xd: f64,
    next: usize,
    /// The last output observed and its inputs, from which a sign change
    /// of det(D^c) before the next one is located.
    previous: State,
    prev_inputs: Vec<f64>,
    inputs: Vec<f64>,
    /// det(D^c) at the two outputs before the last one, and its largest
    /// magnitude so far.
    det_prev2: f64,
    det_prev: f64,
    det_max: f64,
    report: RunReport,
    /// Why the outputs ended before the last one, when it is not the
    /// integrator's own failure.
    stop: Option<SolveError>,
    /// The outputs are over (the last one observed, or a stop).
    done: bool,
    /// Outputs were found inside the step last accepted.
    inside: bool,
    /// The time the integration reached.
    reached: f64,
    stiffness: Stiffness,
}

/// The integrator's view of the equations of motion; interior mutability
/// because it evaluates them through a shared reference.
struct Ode<'a, 'o> {
    eom: RefCell<Eom<'a>>,
    /// Scratch for one evaluation's accelerations.
    acc: RefCell<Vec<f64>>,
    /// The integrator's last two evaluations, the latest at index 1: after
    /// an accepted step, the latest is at its end.
    evals: RefCell<[Evaluation; 2]>,
    out: Outputs<'o>,
}

/// The integrator owns its system: it gets this borrow, so that the
/// equations and the outputs are handed back afterwards.
struct OdeRef<'r, 'a, 'o>(&'r mut Ode<'a, 'o>);

impl<D: Dim> System<f64, OVector<f64, D>> for OdeRef<'_, '_, '_>
where
    DefaultAllocator: Allocator<D>,
{
    fn system(&self, t: f64, y: &OVector<f64, D>, dy: &mut OVector<f64, D>) {
        let (mut eom, mut acc) = (self.0.eom.borrow_mut(), self.0.acc.borrow_mut());
        let nf = eom.free.len();
        for k in 0..nf {
            dy[k] = y[nf + k];
        }
        match eom.accelerations(t, y.as_slice(), &mut acc) {
            Ok(()) => {
                for k in 0..nf {
                    dy[nf + k] = acc[k];
                }
            }
            // A derivative far too large makes the step fail its error
            // test: the integrator retries a shorter one, and gives up
            // when the step becomes too short.
            Err(_) => dy.fill(1e150),
        }
        let mut evals = self.0.evals.borrow_mut();
        evals.swap(0, 1);
        evals[1].t = t;
        evals[1].y.copy_from_slice(y.as_slice());
        evals[1].dy.copy_from_slice(dy.as_slice());
    }

    /// Called by `Dopri5` (dense output) once for every output time inside
    /// an accepted step, as it adds it (`y` that output), and then once for
    /// the step itself (`t` its end).
    fn solout(&mut self, t: f64, y: &OVector<f64, D>, _dy: &OVector<f64, D>) -> bool {
        let ode = &mut *self.0;
        if ode.out.done {
            return true;
        }
        let step_end = ode.evals.get_mut()[1].t;
        // The integrator adds the outputs up to the step's end, counting
        // their times as `xd` is counted here.
        let done = if ode.out.xd <= step_end {
            let at = ode.out.xd;
            ode.out.xd += ode.out.dt;
            let done = ode.output(at, y.as_slice());
            // The integration ends with this step, accepted.
            if done {
                ode.out.reached = step_end;
            }
            done
        } else {
            ode.stepped(t)
        };
        ode.out.done |= done;
        done
    }
}

impl Ode<'_, '_> {
    /// The next output, at time `t` with the dense output's free state `y`:
    /// its position found from the last one the integration found, its
    /// accelerations, and the observer told. Whether the outputs are over.
    fn output(&mut self, t: f64, y: &[f64]) -> bool {
        let k = self.out.next;
        self.out.next += 1;
        // Position 1 is observed before the integration starts.
        if k == 0 {
            return false;
        }
        let (eom, acc) = (self.eom.get_mut(), self.acc.get_mut());
        if !self.out.inside {
            eom.keep();
            self.out.inside = true;
        }
        if let Err(e) = eom.reach(t, y, acc) {
            self.out.stop = Some(e);
            return true;
        }
        let view = eom.view(k, acc);
        if let Err(e) = timed_finite(view.mech, view.kin, view.input_vel, view.input_acc) {
            self.out.stop = Some(e);
            return true;
        }
        let out = &mut self.out;
        let mech = view.mech;
        out.inputs.clear();
        out.inputs.extend((0..mech.n_dof()).map(|j| view.input(j)));
        if let Err(e) = out.limits(view.kin.det(), k) {
            out.stop = Some(e);
            return true;
        }
        if let Err(e) = out.observer.check(&view) {
            out.stop = Some(e);
            return true;
        }
        out.observer.position(&view);
        out.report.positions += 1;
        out.previous.clone_from(view.state);
        std::mem::swap(&mut out.prev_inputs, &mut out.inputs);
        if k == out.steps {
            return true;
        }
        if out.observer.stop_requested() {
            out.stop = Some(SolveError::Interrupted);
            return true;
        }
        false
    }

    /// An accepted step ending at `t`: progress, and a request to stop.
    fn stepped(&mut self, t: f64) -> bool {
        let out = &mut self.out;
        if out.inside {
            self.eom.get_mut().back();
            out.inside = false;
        }
        let h = t - out.reached;
        out.reached = t;
        if out.stiffness.stiff(h, out.dt, self.evals.get_mut()) {
            out.stop = Some(SolveError::Simulation { time: t, reason: STIFF_REASON });
            return true;
        }
        out.observer.simulated(t, out.span);
        if out.observer.stop_requested() {
            out.stop = Some(SolveError::Interrupted);
            return true;
        }
        false
    }
}

impl Outputs<'_> {
    /// The limit positions between the last output and output `k`, where
    /// det(D^c) is `det`, found as a kinematic run finds them: a local
    /// minimum of |det| far below its largest value. A sign change of
    /// det(D^c) between two outputs means the integration passed a limit
    /// position or a point where two assembly branches meet without
    /// meeting the limit test of its evaluations: output `k` would be on
    /// another branch, so it is refused.
    fn limits(&mut self, det: f64, k: usize) -> Result<(), SolveError> {
        if self.det_prev * det < 0.0 {
            return Err(SolveError::DetSignChange { before: self.det_prev, after: det });
        }
        self.det_max = self.det_max.max(det.abs());
        let prev = self.det_prev.abs();
        if prev < self.det_prev2.abs() && prev <= det.abs() && prev < 1e-3 * self.det_max {
            self.report.limits.push(LimitPosition {
                kind: LimitKind::NearZero,
                after: k - 1,
                inputs: self.prev_inputs.clone(),
                coords: self.previous.x.clone(),
                det: self.det_prev,
            });
        }
        (self.det_prev2, self.det_prev) = (self.det_prev, det);
        Ok(())
    }
}

/// The integrator's statistics, or why it gave up.
fn integrate<D: Dim>(
    ode: &mut Ode<'_, '_>,
    dim: D,
    y0: &[f64],
    (end, dt, span): (f64, f64, f64),
    tol: Integration,
    budget: Option<u32>,
) -> Result<(usize, usize, usize), SolveError>
where
    DefaultAllocator: Allocator<D>,
{
    let y = OVector::<f64, D>::from_iterator_generic(dim, U1, y0.iter().copied());
    let mut solver = Dopri5::from_param(
        OdeRef(ode),
        0.0,
        end,
        dt,
        y,
        tol.rtol,
        tol.atol,
        0.9,
        0.04,
        0.2,
        10.0,
        span,
        0.0,
        budget.unwrap_or_else(|| max_steps(span, dt)),
        // Its own stiffness test never: `Stiffness` takes its place.
        u32::MAX,
        OutputType::Dense,
    );
    use ode_solvers::dop_shared::IntegrationError as E;
    match solver.integrate() {
        Ok(s) => Ok((s.accepted_steps as usize, s.rejected_steps as usize, s.num_eval as usize)),
        Err(E::StiffnessDetected { x }) => Err(SolveError::Simulation { time: x, reason: STIFF_REASON }),
        Err(E::StepSizeUnderflow { x }) => Err(SolveError::Simulation {
            time: x,
            reason: "the step size collapsed: no position could be found beyond this time (a limit position?)",
        }),
        Err(E::MaxNumStepReached { x, .. }) if budget.is_some() => {
            Err(SolveError::Simulation { time: x, reason: "the integrator used up the step budget it was given" })
        }
        Err(E::MaxNumStepReached { x, .. }) => Err(SolveError::Simulation {
            time: x,
            reason: "the integrator needed more than 2000 steps per output interval on average: the motion has \
                     oscillations far faster than the outputs (a very stiff spring?)",
        }),
    }
}

/// The most steps a simulation to `end` with outputs every `dt` may take:
/// 2000 per output interval on average, and at least 200 000. A motion that
/// needs more has oscillations far faster than anything the outputs could
/// show (a very stiff spring resolved step by step), and would otherwise run
/// for hours.
fn max_steps(end: f64, dt: f64) -> u32 {
    let outputs = (end / dt).ceil().clamp(1.0, 1e6);
    (200_000.0 + 2_000.0 * outputs) as u32
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
    };
    // The free DOFs' accelerations at the start: a model they cannot move
    // in is refused here, before anything is integrated.
    let mut acc0 = vec![0.0; nf];
    eom.accelerations(0.0, &y0, &mut acc0)?;
    let view = eom.view(0, &acc0);
    timed_finite(mech, view.kin, view.input_vel, view.input_acc)?;
    observer.check(&view)?;
    observer.position(&view);
    let det = view.kin.det();
    let evaluation = || Evaluation { t: f64::NAN, y: vec![0.0; 2 * nf], dy: vec![0.0; 2 * nf] };
    let mut ode = Ode {
        eom: RefCell::new(eom),
        acc: RefCell::new(vec![0.0; nf]),
        evals: RefCell::new([evaluation(), evaluation()]),
        out: Outputs {
            observer,
            steps: motion.steps,
            dt: motion.dt,
            span,
            xd: 0.0,
            next: 0,
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
            stop: None,
            done: motion.steps == 0,
            inside: false,
            reached: 0.0,
            stiffness: Stiffness::default(),
        },
    };
    if !ode.out.done && ode.out.observer.stop_requested() {
        (ode.out.stop, ode.out.done) = (Some(SolveError::Interrupted), true);
    }
    // The integration is asked to go on to twice the last output time,
    // which it never reaches: it ends with the step that holds the last
    // output. So that output lies inside a step (the dense output of
    // ode_solvers 0.6 at the very end of an integration is extrapolated
    // from an earlier step), and neither the longest step (the span) nor
    // any other choice of the integrator depends on the output interval:
    // the same motion is integrated whatever the outputs.
    let past = (2.0 * span).min(f64::MAX);
    let integrated = if ode.out.done {
        Ok((0, 0, 0))
    } else {
        match nf {
            1 => integrate(&mut ode, Const::<2>, &y0, (past, motion.dt, span), *integration, budget),
            2 => integrate(&mut ode, Const::<4>, &y0, (past, motion.dt, span), *integration, budget),
            3 => integrate(&mut ode, Const::<6>, &y0, (past, motion.dt, span), *integration, budget),
            _ => integrate(&mut ode, Dyn(2 * nf), &y0, (past, motion.dt, span), *integration, budget),
        }
    };
    let Ode { eom, out, .. } = ode;
    let eom = eom.into_inner();
    let mut report = out.report;
    state.clone_from(&out.previous);
    let (stats, failed) = match integrated {
        Ok(stats) => (stats, None),
        Err(e) => ((0, 0, 0), Some(e)),
    };
    if report.positions < motion.steps + 1 {
        let error = match out.stop.or(failed) {
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
        steps: stats.0,
        rejected: stats.1,
        evaluations: stats.2.max(eom.evaluations),
        reached: out.reached.min(span),
    })
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
    Ok(SimReport { run: report, integration: *integration, steps: 0, rejected: 0, evaluations: 0, reached })
}
