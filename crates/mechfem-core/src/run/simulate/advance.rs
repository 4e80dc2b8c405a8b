//! One stretch of a simulation with one method of the integrator library:
//! step after step, each step's outputs and STOPWHEN crossing from its
//! dense output, until the end, a stop, or a change of method.
//!
//! The library's methods are driven one step at a time. A step in which an
//! evaluation of the equations failed (no position found, a limit
//! position) is not taken: the method is started again from the end of the
//! last step with a quarter of the step. Radau IIA is also started again
//! after every rejected step, before a step whose length mechfem sets
//! (the last one, which ends at the end time exactly) and before a step of
//! another length after one that kept its length, because the library's
//! Radau IIA keeps the factorisation of its Newton matrix for the old step
//! length there; a start costs one evaluation, and the Jacobian and
//! factorisation that a rejected step needs anyway.

use differential_equations::error::Error as StepError;
use differential_equations::interpolate::Interpolation;
use differential_equations::ode::OrdinaryNumericalMethod;
use differential_equations::status::Status;
use nalgebra::DMatrix;

use super::dop853::dense_output;
use super::outputs::{hermite, locate, watched, Event, Outputs};
use super::stiffness::{Stiffness, STIFF_REASON};
use super::system::{Free, System};
use crate::dynamics::{Integration, Integrator};
use crate::error::SolveError;

/// A simulation under way: the equations, the outputs, where the
/// integration is and what it did.
pub(super) struct Run<'a, 'o> {
    pub(super) sys: System<'a>,
    pub(super) out: Outputs<'o>,
    /// The end time and the tolerances.
    pub(super) span: f64,
    pub(super) tol: Integration,
    /// The most steps (accepted and rejected) allowed, and whether the
    /// caller gave that number.
    pub(super) budget: usize,
    pub(super) budget_given: bool,
    /// The end of the last step accepted, its free state, and the step
    /// the method would take next (0: the library chooses the first).
    pub(super) t: f64,
    pub(super) y: Vec<f64>,
    pub(super) h: f64,
    pub(super) steps: usize,
    pub(super) rejected: usize,
    pub(super) acc: Vec<f64>,
    /// The free accelerations at the end of the last step accepted and of
    /// the step just taken, and a free state of the dense output.
    pub(super) a0: Vec<f64>,
    pub(super) a1: Vec<f64>,
    pub(super) yd: Vec<f64>,
    /// Why the integration could not go on, when it is the integrator's
    /// own failure.
    pub(super) error: Option<SolveError>,
}

/// How a stretch ended.
pub(super) enum Next {
    /// The simulation is over (its end, a stop, or a failure).
    Done,
    /// Go on with another method from where the stretch ended.
    Switch(Integrator),
}

/// An explicit step whose `h rho` stays below this share of Dormand-Prince 5(4)'s
/// stability bound (3.25) ten steps running is one the explicit method could
/// take as well, at a lower cost per step: the automatic choice goes back
/// to it.
const CALM: f64 = 0.5 * 3.25;

/// Integrates with `method` (made by `make` for a first step `h`, 0 to let
/// the library choose) from where `run` is.
pub(super) fn advance<Y, M>(run: &mut Run<'_, '_>, method: Integrator, auto: bool, make: impl Fn(f64) -> M) -> Next
where
    Y: Free + 'static,
    M: OrdinaryNumericalMethod<f64, Y> + Interpolation<f64, Y> + 'static,
{
    let implicit = method == Integrator::Radau5;
    let Some(mut m) = start(run, &make, run.h) else { return Next::Done };
    let bound = if method == Integrator::Dopri5 { 3.25 } else { 6.1 };
    let mut stiffness = Stiffness::new(bound, !auto);
    let (mut calm, mut failures) = (0, 0);
    // The step length the implicit method's Newton matrices may be
    // factorised for: the library's Radau IIA keeps its factorisation
    // after a step that kept the step length and its Newton iteration
    // converged fast, and then uses it for later steps of other lengths
    // too, where its error estimate is wrong (Hairer's RADAU5 factorises
    // again). A step of another length starts the method again.
    let mut factorised: Option<f64> = None;
    loop {
        if run.out.done {
            return Next::Done;
        }
        if run.steps + run.rejected >= run.budget {
            run.error = Some(SolveError::Simulation { time: run.t, reason: budget_reason(run.budget_given) });
            return Next::Done;
        }
        // The step that reaches the end ends there exactly.
        let mut h = m.h();
        let last = run.t + 1.01 * h >= run.span;
        if last {
            h = run.span - run.t;
            if implicit && h != m.h() {
                let Some(fresh) = start(run, &make, h) else { return Next::Done };
                (m, factorised) = (fresh, None);
            } else {
                m.set_h(h);
            }
        }
        if implicit && factorised.is_some_and(|hf| hf != m.h()) {
            let Some(fresh) = start(run, &make, m.h()) else { return Next::Done };
            (m, factorised) = (fresh, None);
        }
        let taken = m.h();
        let stepped = m.step(&run.sys);
        if let Some(failure) = run.sys.take_failure() {
            // The step is not taken: again from its start, shorter.
            (run.rejected, failures) = (run.rejected + 1, failures + 1);
            let shorter = 0.25 * h;
            if failures > 40 || shorter <= 1e-14 * run.span {
                // A force or mass too large for a double is named as such;
                // anything else is a position that cannot be found.
                run.error = Some(match failure {
                    e @ SolveError::Dynamics(_) => e,
                    _ => SolveError::Simulation { time: run.t, reason: COLLAPSE_REASON },
                });
                return Next::Done;
            }
            let Some(fresh) = start(run, &make, shorter) else { return Next::Done };
            (m, factorised) = (fresh, None);
            continue;
        }
        match stepped {
            // The library's own stiffness test: `Stiffness` takes its place.
            Err(StepError::Stiffness { .. }) => {
                m.set_status(Status::Solving);
                continue;
            }
            Err(StepError::StepSize { t, .. }) => {
                run.error = Some(SolveError::Simulation { time: t, reason: COLLAPSE_REASON });
                return Next::Done;
            }
            Err(_) => {
                run.error = Some(SolveError::Simulation { time: run.t, reason: SINGULAR_REASON });
                return Next::Done;
            }
            Ok(_) => {}
        }
        if m.t() == run.t {
            run.rejected += 1;
            if implicit {
                let Some(fresh) = start(run, &make, m.h()) else { return Next::Done };
                (m, factorised) = (fresh, None);
            }
            continue;
        }
        failures = 0;
        run.steps += 1;
        let (t0, t1) = (run.t, m.t());
        if !run.sys.acc_at(t1, m.y().as_ref(), &mut run.a1) {
            let mut eom = run.sys.eom.borrow_mut();
            eom.keep();
            let found = eom.reach(t1, m.y().as_ref(), &mut run.a1);
            eom.back();
            if let Err(e) = found {
                run.error = Some(e);
                return Next::Done;
            }
        }
        let y1 = Y::from_slice(m.y().as_ref());
        let out = &run.out;
        let wanted = out.stop_when.is_some() || (!out.done && (out.time(out.next) <= t1 || last));
        let own = implicit || (wanted && dense_output::<M, Y>(&mut m, &run.sys));
        step_outputs(run, y1.as_ref(), t0, t1, last, own.then_some(&mut m));
        run.t = t1;
        run.y.copy_from_slice(m.y().as_ref());
        std::mem::swap(&mut run.a0, &mut run.a1);
        if implicit && (m.h() == taken || factorised.is_some()) {
            factorised = Some(taken);
        }
        run.h = m.h();
        if run.out.done {
            return Next::Done;
        }
        if !implicit {
            if stiffness.stiff(t1 - t0, t1, run.out.dt, &run.sys) {
                if auto {
                    return Next::Switch(Integrator::Radau5);
                }
                run.error = Some(SolveError::Simulation { time: t1, reason: STIFF_REASON });
                return Next::Done;
            }
        } else if auto {
            calm = if run.h * spectral_radius(&run.sys) < CALM { calm + 1 } else { 0 };
            if calm >= 10 {
                return Next::Switch(Integrator::Dopri5);
            }
        }
        run.out.observer.simulated(t1, run.span);
        if run.out.observer.stop_requested() {
            (run.out.stop, run.out.done) = (Some(SolveError::Interrupted), true);
            return Next::Done;
        }
    }
}

/// The method made by `make` for a first step `h`, started at the end of
/// the last step accepted; None when it cannot start (the reason in `run`).
fn start<Y, M>(run: &mut Run<'_, '_>, make: &impl Fn(f64) -> M, h: f64) -> Option<M>
where
    Y: Free,
    M: OrdinaryNumericalMethod<f64, Y>,
{
    let mut m = make(h.min(run.span - run.t));
    let started = m.init(&run.sys, run.t, run.span, &Y::from_slice(&run.y));
    if let Some(e) = run.sys.take_failure() {
        run.error = Some(e);
        return None;
    }
    if started.is_err() {
        run.error = Some(SolveError::Simulation { time: run.t, reason: COLLAPSE_REASON });
        return None;
    }
    Some(m)
}

/// The outputs inside the step from `t0` to `t1` (the end time when
/// `last`), whose end state is `y1`, and the STOPWHEN crossing in it: each
/// free state from a dense output and its position by Newton, from the
/// position the integration found last; the integration then goes on from
/// that position, so that the outputs do not change the motion. The dense
/// output is the method's own (`own`): the implicit method's collocation
/// polynomial, DOP853's of order 7; else the quintic Hermite interpolant
/// ([`hermite`]): the library's dense output of Dormand-Prince 5(4) is a
/// hundred times less accurate than its steps, while the Hermite
/// interpolant through the accelerations is as accurate (in a stiff motion
/// those accelerations hold the fast transient, which the collocation
/// polynomial does not); it is of order 5 only, too low for DOP853's long
/// steps.
fn step_outputs<Y, M>(run: &mut Run<'_, '_>, y1: &[f64], t0: f64, t1: f64, last: bool, mut own: Option<&mut M>)
where
    Y: Free,
    M: Interpolation<f64, Y>,
{
    let Run { out, acc, sys, y: y0, a0, a1, yd, tol, .. } = run;
    let (start, end) = ((t0, &y0[..], &a0[..]), (t1, y1, &a1[..]));
    let mut dense = |t: f64, yd: &mut [f64]| match own.as_deref_mut().map(|m| m.interpolate(t.clamp(t0, t1))) {
        Some(Ok(y)) => yd.copy_from_slice(y.as_ref()),
        _ => hermite(start, end, t, yd),
    };
    let mut eom = sys.eom.borrow_mut();
    let mut kept = false;
    let mut keep = |eom: &mut super::eom::Eom<'_>| {
        if !std::mem::replace(&mut kept, true) {
            eom.keep();
        }
    };
    // Where the watched quantity crosses its value in this step, if it does.
    let mut crossing = None;
    if let Some(sw) = out.stop_when {
        keep(&mut eom);
        let g1 = watched(&mut eom, &sw, t1, y1, acc);
        if out.g_prev * g1 < 0.0 {
            let tol = (tol.rtol * (t1 - t0)).max(4.0 * f64::EPSILON * t1);
            let g = |t: f64| {
                dense(t, yd);
                watched(&mut eom, &sw, t, yd, acc)
            };
            crossing = Some(locate(g, (t0, out.g_prev), (t1, g1), tol));
        } else if g1.is_finite() && g1 != 0.0 {
            out.g_prev = g1;
        }
    }
    while !out.done && out.next <= out.steps {
        let k = out.next;
        let at = out.time(k);
        let due = match crossing {
            Some(te) => at < te,
            None => at <= t1 || (last && k == out.steps),
        };
        if !due {
            break;
        }
        out.next += 1;
        // Position 1 is observed before the integration starts.
        if k == 0 {
            continue;
        }
        keep(&mut eom);
        dense(at, yd);
        if let Err(e) = eom.reach(at, yd, acc) {
            (out.stop, out.done) = (Some(e), true);
            break;
        }
        out.done = out.observe(&mut eom, k, acc);
    }
    if let (Some(te), false) = (crossing, out.done) {
        keep(&mut eom);
        dense(te, yd);
        match eom.reach(te, yd, acc) {
            Ok(()) => {
                let k = out.next;
                out.next += 1;
                out.observe(&mut eom, k, acc);
                let sw = out.stop_when.expect("a crossing of the STOPWHEN condition");
                out.event = Some(Event { buffer: sw.buffer, value: sw.value, time: te, inputs: eom.q.clone() });
            }
            Err(e) => out.stop = Some(e),
        }
        out.done = true;
    }
    if kept {
        eom.back();
    }
}

/// The largest |eigenvalue| of the last Jacobian of the implicit method.
fn spectral_radius(sys: &System<'_>) -> f64 {
    let j = sys.jacobian.borrow();
    let n = (j.len() as f64).sqrt() as usize;
    let m = DMatrix::from_row_slice(n, n, &j);
    match nalgebra::linalg::Schur::try_new(m, f64::EPSILON, 200) {
        Some(s) => s.complex_eigenvalues().iter().fold(0.0f64, |r, e| r.max(e.norm())),
        None => f64::INFINITY,
    }
}

const COLLAPSE_REASON: &str =
    "the step size collapsed: no position could be found beyond this time (a limit position?)";

const SINGULAR_REASON: &str = "the implicit integrator's Newton matrix stayed singular: the equations of motion have \
                               no unique solution beyond this time (a limit position?)";

fn budget_reason(given: bool) -> &'static str {
    if given {
        "the integrator used up the step budget it was given"
    } else {
        "the integrator needed more than 2000 steps per output interval on average: the motion has oscillations far \
         faster than the outputs (a very stiff spring?)"
    }
}
