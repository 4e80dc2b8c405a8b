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
//! The integrator's dense output gives q and q' at the output times; q''
//! there comes from the equations of motion, and the outputs are then
//! replayed through the kinematic run as a motion table, so that every
//! buffer, limit-position check and observer works as in KIN ANA.

use nalgebra::{allocator::Allocator, Const, DefaultAllocator, Dim, Dyn, OVector, U1};
use ode_solvers::{Dopri5, OutputType, System};
use std::cell::RefCell;

use super::inverse::InverseDynamics;
use super::kinematic::run;
use super::observe::{Observer, PositionView, RunReport, Stop};
use crate::dynamics::{Dynamics, Integration};
use crate::error::{SolveError, Unsupported};
use crate::model::{Mechanism, State};
use crate::motion::{InputMotion, Motion};
use crate::solver::{adjust, correct, Kinematics, Params, TransferOrder};

/// What a simulation did: the integrator's work, and the run through the
/// output times.
#[derive(Debug, Clone, PartialEq)]
pub struct SimReport {
    /// The replay through the output times; its `stop` says why the
    /// simulation ended early, if it did.
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

/// How a driven DOF moves, at any time.
#[derive(Debug, Clone)]
enum Driver {
    /// Linear in time (MOV_RELE, MOV_ABSE).
    Linear { start: f64, rate: f64 },
    /// A table `t value velocity acceleration`: cubic between rows from
    /// the values and velocities, the acceleration linear between rows.
    Table(Vec<[f64; 4]>),
}

impl Driver {
    fn at(&self, t: f64) -> [f64; 3] {
        match self {
            Driver::Linear { start, rate } => [start + rate * t, *rate, 0.0],
            Driver::Table(rows) => {
                let k = rows.partition_point(|r| r[0] <= t).clamp(1, rows.len().max(2) - 1);
                let (a, b) = (rows[k - 1], rows[k.min(rows.len() - 1)]);
                let h = b[0] - a[0];
                if h <= 0.0 || h.is_nan() {
                    return [a[1], a[2], a[3]];
                }
                let s = ((t - a[0]) / h).clamp(0.0, 1.0);
                // Cubic Hermite basis and its derivative.
                let (s2, s3) = (s * s, s * s * s);
                let (h00, h10, h01, h11) = (2.0 * s3 - 3.0 * s2 + 1.0, s3 - 2.0 * s2 + s, 3.0 * s2 - 2.0 * s3, s3 - s2);
                let (d00, d10, d01, d11) =
                    (6.0 * s2 - 6.0 * s, 3.0 * s2 - 4.0 * s + 1.0, 6.0 * s - 6.0 * s2, 3.0 * s2 - 2.0 * s);
                let q = h00 * a[1] + h10 * h * a[2] + h01 * b[1] + h11 * h * b[2];
                let v = (d00 * a[1] + d01 * b[1]) / h + d10 * a[2] + d11 * b[2];
                [q, v, a[3] + s * (b[3] - a[3])]
            }
        }
    }
}

/// The equations of motion of a mechanism with its masses and loads.
struct Eom<'a> {
    mech: &'a Mechanism,
    params: Params,
    state: State,
    kin: Kinematics,
    inverse: InverseDynamics,
    /// The free DOFs, in order.
    free: Vec<usize>,
    /// The driven DOFs and how they move.
    driven: Vec<(usize, Driver)>,
    q: Vec<f64>,
    qd: Vec<f64>,
    qdd: Vec<f64>,
    drives: Vec<f64>,
    /// The inputs of the last position found, for the next prediction.
    q_last: Vec<f64>,
    /// M_ff and its right-hand side, for the free accelerations.
    m_ff: Vec<f64>,
    rhs: Vec<f64>,
    saved: State,
    evaluations: usize,
    /// Why the last evaluation failed, if it did.
    failure: Option<SolveError>,
    /// The largest |det(D^c)| met so far.
    det_max: f64,
    /// Whether a stage ran into a limit position of a free DOF.
    limit_met: bool,
}

/// |det(D^c)| below this share of the largest met so far is a limit position.
const LIMIT_DET: f64 = 1e-6;

const LIMIT_REASON: &str = "a limit position of a free degree of freedom (det(D^c) fell below 1e-6 of its largest \
                            value): the DOF cannot move the mechanism through it (let another DOF move freely)";

impl Eom<'_> {
    /// The free DOFs' accelerations at time `t`, free positions and speeds
    /// `y = [q_f, q_f']`, into `out`; the position found stays in `self.state`.
    fn accelerations(&mut self, t: f64, y: &[f64], out: &mut [f64]) -> Result<(), SolveError> {
        let (mech, nf) = (self.mech, self.free.len());
        for (k, &j) in self.free.iter().enumerate() {
            (self.q[j], self.qd[j], self.qdd[j]) = (y[k], y[nf + k], 0.0);
        }
        for (j, d) in &self.driven {
            [self.q[*j], self.qd[*j], self.qdd[*j]] = d.at(t);
        }
        self.saved.clone_from(&self.state);
        // Predict the position from the last one by the first-order transfer functions.
        if self.kin.order().is_some() {
            for j in 0..mech.n_dof() {
                let dq = self.q[j] - self.q_last[j];
                for (c, &i) in mech.moving_coords().iter().enumerate() {
                    self.state.x[i] += self.kin.x1(j)[c] * dq;
                }
            }
        }
        for j in 0..mech.n_dof() {
            self.state.target[mech.input_row(j)] = self.q[j];
        }
        let found = correct(mech, &mut self.state, &mut self.kin, &self.params)
            .and_then(|_| self.kin.finish(mech, &mut self.state, Some(TransferOrder::Second), None));
        if let Err(e) = found {
            self.state.clone_from(&self.saved);
            // The transfer functions are those of another position now: no prediction from them.
            let _ = self.kin.transfer(mech, &mut self.state, TransferOrder::Second);
            return Err(e);
        }
        // A free DOF cannot move the mechanism through a limit position of
        // its own: near one, D^c is nearly singular, the DOF's reduced mass
        // grows without bound and the motion would creep towards the limit
        // forever. Such a position counts as not found.
        let det = self.kin.det().abs();
        self.det_max = self.det_max.max(det);
        if det < LIMIT_DET * self.det_max {
            self.limit_met = true;
            self.state.clone_from(&self.saved);
            let _ = self.kin.transfer(mech, &mut self.state, TransferOrder::Second);
            return Err(SolveError::Simulation { time: t, reason: LIMIT_REASON });
        }
        self.q_last.copy_from_slice(&self.q);
        self.evaluations += 1;
        let view = PositionView {
            index: 0,
            time: t,
            mech,
            state: &self.state,
            kin: &self.kin,
            input_vel: &self.qd,
            input_acc: &self.qdd,
        };
        if !self.inverse.drives(&view, &mut self.drives) {
            return Err(SolveError::NotComputed);
        }
        // M_ff a = -b_f: the free DOFs' drives vanish.
        for (r, &j) in self.free.iter().enumerate() {
            for (c, &m) in self.free.iter().enumerate() {
                self.m_ff[r * nf + c] = self.inverse.mass_matrix_entry(mech, j, m);
            }
            self.rhs[r] = -self.drives[j];
        }
        // A mass or load too large for a double: named by inverse dynamics.
        let finite = |s: &[f64]| s.iter().all(|a| a.is_finite());
        if !(finite(&self.m_ff) && finite(&self.rhs)) {
            return Err(self.inverse.fault_at(&view));
        }
        solve_dense(nf, &mut self.m_ff, &mut self.rhs)
            .ok_or(SolveError::Unsupported(Unsupported::DynamicWithoutMass))?;
        if !finite(&self.rhs) {
            return Err(self.inverse.fault_at(&view));
        }
        out.copy_from_slice(&self.rhs);
        Ok(())
    }
}

impl Eom<'_> {
    /// Back at position 1 (`state`, inputs `q`), as before the integration.
    fn restart(&mut self, state: &State, q: &[f64]) {
        self.state.clone_from(state);
        self.q_last.copy_from_slice(q);
        let _ = self.kin.transfer(self.mech, &mut self.state, TransferOrder::Second);
    }

    /// [`Self::accelerations`] at `to = (t, y)`, coming from the output
    /// `from`: when the position there cannot be found from the last one,
    /// it is approached in shorter and shorter stages along the straight
    /// line between the two states.
    fn reach(&mut self, from: (f64, &[f64]), to: (f64, &[f64]), out: &mut [f64]) -> Result<(), SolveError> {
        let Err(mut error) = self.accelerations(to.0, to.1, out) else { return Ok(()) };
        let mut y = to.1.to_vec();
        for stages in [2, 4, 8, 16, 32] {
            let staged = (1..=stages).try_for_each(|i| {
                let s = i as f64 / stages as f64;
                for (yk, (a, b)) in y.iter_mut().zip(from.1.iter().zip(to.1)) {
                    *yk = a + s * (b - a);
                }
                self.accelerations(from.0 + s * (to.0 - from.0), &y, out)
            });
            match staged {
                Ok(()) => return Ok(()),
                Err(e) => error = e,
            }
        }
        Err(error)
    }
}

/// Solves the n x n system `a x = b` (row-major `a`, overwritten) in place
/// by Gaussian elimination with partial pivoting; None when `a` is singular.
fn solve_dense(n: usize, a: &mut [f64], b: &mut [f64]) -> Option<()> {
    let scale = a.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    for k in 0..n {
        let p = (k..n).max_by(|&i, &j| a[i * n + k].abs().total_cmp(&a[j * n + k].abs()))?;
        let pivot = a[p * n + k].abs();
        if pivot <= 1e-14 * scale || pivot.is_nan() {
            return None;
        }
        for c in 0..n {
            a.swap(k * n + c, p * n + c);
        }
        b.swap(k, p);
        for i in k + 1..n {
            let f = a[i * n + k] / a[k * n + k];
            for c in k..n {
                a[i * n + c] -= f * a[k * n + c];
            }
            b[i] -= f * b[k];
        }
    }
    for k in (0..n).rev() {
        let s: f64 = (k + 1..n).map(|c| a[k * n + c] * b[c]).sum();
        b[k] = (b[k] - s) / a[k * n + k];
    }
    Some(())
}

/// The integrator's view of the equations of motion; interior mutability
/// because it evaluates them through a shared reference.
struct Ode<'a, 'o> {
    eom: RefCell<Eom<'a>>,
    /// Scratch for one evaluation's accelerations.
    acc: RefCell<Vec<f64>>,
    observer: &'o mut dyn Observer,
    end: f64,
}

/// The integrator owns its system: it gets this borrow, so that the
/// equations and the observer are handed back afterwards.
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
                eom.failure = None;
                for k in 0..nf {
                    dy[nf + k] = acc[k];
                }
            }
            Err(e) => {
                // A derivative far too large makes the step fail its error
                // test: the integrator retries a shorter one, and gives up
                // when the step becomes too short.
                eom.failure = Some(e);
                for k in 0..2 * nf {
                    dy[k] = 1e150;
                }
            }
        }
    }

    fn solout(&mut self, t: f64, _y: &OVector<f64, D>, _dy: &OVector<f64, D>) -> bool {
        self.0.observer.simulated(t, self.0.end);
        self.0.observer.stop_requested()
    }
}

/// The observer of the replay of the outputs, which must not stop it.
struct Replay<'o>(&'o mut dyn Observer);

impl Observer for Replay<'_> {
    fn position(&mut self, view: &PositionView<'_>) {
        self.0.position(view);
    }
    fn check(&mut self, view: &PositionView<'_>) -> Result<(), SolveError> {
        self.0.check(view)
    }
    fn transfer_order(&self) -> Option<TransferOrder> {
        self.0.transfer_order()
    }
}

/// The integration's outcome: the output times and states reached, the
/// integrator's statistics, and why it ended early.
struct Integrated {
    times: Vec<f64>,
    states: Vec<Vec<f64>>,
    stats: (usize, usize, usize),
    error: Option<SolveError>,
}

fn integrate<D: Dim>(
    ode: &mut Ode<'_, '_>,
    dim: D,
    y0: &[f64],
    (end, dt): (f64, f64),
    tol: Integration,
    budget: Option<u32>,
) -> Integrated
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
        end,
        0.0,
        budget.unwrap_or_else(|| max_steps(end, dt)),
        1000,
        OutputType::Dense,
    );
    let result = solver.integrate();
    let (times, states) = (solver.x_out().clone(), solver.y_out().iter().map(|v| v.as_slice().to_vec()).collect());
    let error = match result {
        Ok(s) => return Integrated { times, states, stats: stats(&s), error: None },
        Err(e) => Some(match e {
            ode_solvers::dop_shared::IntegrationError::StiffnessDetected { x } => SolveError::Simulation {
                time: x,
                reason:
                    "the motion became stiff (a stiff spring or damper?): an explicit method would need very many steps",
            },
            ode_solvers::dop_shared::IntegrationError::StepSizeUnderflow { x } => SolveError::Simulation {
                time: x,
                reason: "the step size collapsed: no position could be found beyond this time (a limit position?)",
            },
            ode_solvers::dop_shared::IntegrationError::MaxNumStepReached { x, .. } if budget.is_some() => {
                SolveError::Simulation { time: x, reason: "the integrator used up the step budget it was given" }
            }
            ode_solvers::dop_shared::IntegrationError::MaxNumStepReached { x, .. } => SolveError::Simulation {
                time: x,
                reason: "the integrator needed more than 2000 steps per output interval on average: the motion \
                         has oscillations far faster than the outputs (a very stiff spring?)",
            },
        }),
    };
    Integrated { times, states, stats: (0, 0, 0), error }
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

fn stats(s: &ode_solvers::dop_shared::Stats) -> (usize, usize, usize) {
    (s.accepted_steps as usize, s.rejected_steps as usize, s.num_eval as usize)
}

/// Simulates the motion of `mech` under the masses and loads of
/// `dynamics`, from the position `state` (adjusted first, as in a run) and
/// the velocities of `motion`'s [`InputMotion::Dynamic`] inputs; the other
/// inputs follow their prescribed motion. The output times are those of
/// `motion` (`steps` steps of `dt`); `observer` sees every output position
/// with its velocities and accelerations, as in [`run`].
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
    let mut kin = Kinematics::new(mech);
    let adjusted = adjust(mech, state, &mut kin, params)?;
    kin.transfer(mech, state, TransferOrder::Second)?;
    let nf = free.len();
    let mut eom = Eom {
        mech,
        params: *params,
        state: state.clone(),
        kin,
        inverse: InverseDynamics::new(mech, dynamics.clone()),
        free: free.clone(),
        driven: driven.clone(),
        q: start.clone(),
        qd: vec![0.0; nd],
        qdd: vec![0.0; nd],
        drives: vec![0.0; nd],
        q_last: start.clone(),
        m_ff: vec![0.0; nf * nf],
        rhs: vec![0.0; nf],
        saved: state.clone(),
        evaluations: 0,
        failure: None,
        det_max: 0.0,
        limit_met: false,
    };
    let y0: Vec<f64> = free.iter().map(|&j| start[j]).chain(v0.iter().copied()).collect();
    // The free DOFs' accelerations at the start: a model they cannot move
    // in is refused here, before anything is integrated.
    let mut acc0 = vec![0.0; nf];
    eom.accelerations(0.0, &y0, &mut acc0)?;
    let mut ode = Ode { eom: RefCell::new(eom), acc: RefCell::new(vec![0.0; nf]), observer, end: span };
    // One output interval past the last output time: the integrator's
    // dense output at its very end is extrapolated from an earlier step
    // (ode_solvers 0.6), so the last output asked for must lie inside.
    let past = span + motion.dt;
    let out = match nf {
        0 => Integrated { times: vec![0.0], states: vec![vec![]], stats: (0, 0, 0), error: None },
        1 => integrate(&mut ode, Const::<2>, &y0, (past, motion.dt), *integration, budget),
        2 => integrate(&mut ode, Const::<4>, &y0, (past, motion.dt), *integration, budget),
        3 => integrate(&mut ode, Const::<6>, &y0, (past, motion.dt), *integration, budget),
        _ => integrate(&mut ode, Dyn(2 * nf), &y0, (past, motion.dt), *integration, budget),
    };
    let Ode { eom, observer, .. } = ode;
    let mut eom = eom.into_inner();
    let (steps, rejected, evaluations) = out.stats;
    // Without a free DOF the prescribed motion alone is replayed; position
    // 1 is always there, even when not one step succeeded.
    let (times, states) = if nf == 0 {
        ((0..=motion.steps).map(|k| k as f64 * motion.dt).collect(), vec![vec![]; motion.steps + 1])
    } else if out.times.is_empty() {
        (vec![0.0], vec![y0.clone()])
    } else {
        (out.times, out.states)
    };
    // The outputs with their accelerations, as a motion table per DOF; the
    // outputs the integrator gave at the right times only (its last one may
    // be the end of the interval when it stopped short).
    let mut tables: Vec<Vec<[f64; 4]>> = vec![Vec::with_capacity(times.len()); nd];
    let mut acc = vec![0.0; nf];
    // Steps cut down again and again at a limit position end as a collapse
    // or as apparent stiffness: the limit is the reason.
    let mut stop_error = match out.error {
        Some(SolveError::Simulation { time, .. }) if eom.limit_met => {
            Some(SolveError::Simulation { time, reason: LIMIT_REASON })
        }
        e => e,
    };
    // The outputs are visited from the start again, each position found
    // from the one before.
    eom.restart(state, &start);
    for (k, (t, y)) in times.iter().zip(&states).enumerate() {
        if k > motion.steps || (t - k as f64 * motion.dt).abs() > 1e-9 * motion.dt.max(span) {
            break;
        }
        if nf > 0 {
            let before = if k == 0 { (0.0, &y0[..]) } else { (times[k - 1], &states[k - 1][..]) };
            if let Err(e) = eom.reach(before, (*t, &y[..]), &mut acc) {
                stop_error.get_or_insert(e);
                break;
            }
        }
        for (f, &j) in free.iter().enumerate() {
            tables[j].push([*t, y[f], y[nf + f], acc[f]]);
        }
        for (j, d) in &driven {
            let [q, v, a] = d.at(*t);
            tables[*j].push([*t, q, v, a]);
        }
    }
    let reached = times.last().copied().unwrap_or(0.0).min(span);
    let n_out = tables.first().map_or(0, Vec::len);
    let replay = Motion {
        steps: n_out.saturating_sub(1),
        dt: motion.dt,
        inputs: tables.into_iter().map(|rows| InputMotion::Table { rows }).collect(),
    };
    // The positions reached are all kept, even after a request to stop
    // ended the integration.
    let mut run_report = run(mech, state, Some(&replay), params, &mut Replay(observer))?;
    run_report.adjust = adjusted;
    // A failure past the last output time asked for is no stop.
    if run_report.stop.is_none() && n_out < motion.steps + 1 {
        let last: Vec<f64> = (0..nd).map(|j| state.target[mech.input_row(j)]).collect();
        let error = stop_error.unwrap_or(SolveError::Interrupted);
        run_report.stop = Some(Stop {
            last_good: n_out.saturating_sub(1),
            inputs: Vec::new(),
            last_inputs: last,
            error,
            limit: None,
        });
    }
    Ok(SimReport {
        run: run_report,
        integration: *integration,
        steps,
        rejected,
        evaluations: evaluations.max(eom.evaluations),
        reached,
    })
}
