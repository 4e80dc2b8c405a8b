//! The outputs of a simulation as the integration produces them: each at
//! its time from the integrator's dense output, its position re-adjusted by
//! Newton; and the crossing of a STOPWHEN condition, located on the dense
//! output.

use super::super::kinematic::timed_finite;
use super::super::observe::{Observer, RunReport};
use super::eom::Eom;
use crate::dynamics::StopWhen;
use crate::error::SolveError;
use crate::model::State;
use crate::motion::limits::{LimitKind, LimitPosition};

/// Where a STOPWHEN condition ended a simulation.
#[derive(Debug, Clone, PartialEq)]
pub struct Event {
    /// The deck's number of the buffer watched.
    pub buffer: u32,
    /// The value it crossed.
    pub value: f64,
    /// The time of the crossing.
    pub time: f64,
    /// The value of every input there (0-based DOFs).
    pub inputs: Vec<f64>,
}

pub(super) struct Outputs<'o> {
    pub(super) observer: &'o mut dyn Observer,
    /// The last output index (TSTEPE's n) and the output interval.
    pub(super) steps: usize,
    pub(super) dt: f64,
    /// The index of the next output.
    pub(super) next: usize,
    /// The last output observed and its inputs, from which a sign change
    /// of det(D^c) before the next one is located.
    pub(super) previous: State,
    pub(super) prev_inputs: Vec<f64>,
    pub(super) inputs: Vec<f64>,
    /// det(D^c) at the two outputs before the last one, and its largest
    /// magnitude so far.
    pub(super) det_prev2: f64,
    pub(super) det_prev: f64,
    pub(super) det_max: f64,
    pub(super) report: RunReport,
    /// Why the outputs ended before the last one.
    pub(super) stop: Option<SolveError>,
    /// The outputs are over (the last one observed, an event, or a stop).
    pub(super) done: bool,
    /// The STOPWHEN condition, its quantity's value minus the value at
    /// the end of the last step accepted, and where it ended the run.
    pub(super) stop_when: Option<StopWhen>,
    pub(super) g_prev: f64,
    pub(super) event: Option<Event>,
}

impl Outputs<'_> {
    /// The time of output `k`.
    pub(super) fn time(&self, k: usize) -> f64 {
        k as f64 * self.dt
    }

    /// Observes the position `eom` found last, at output index `k` with
    /// the free accelerations `acc`. Whether the outputs are over.
    pub(super) fn observe(&mut self, eom: &mut Eom<'_>, k: usize, acc: &[f64]) -> bool {
        let view = eom.view(k, acc);
        if let Err(e) = timed_finite(view.mech, view.kin, view.input_vel, view.input_acc) {
            self.stop = Some(e);
            return true;
        }
        let mech = view.mech;
        self.inputs.clear();
        self.inputs.extend((0..mech.n_dof()).map(|j| view.input(j)));
        if let Err(e) = self.limits(view.kin.det(), k) {
            self.stop = Some(e);
            return true;
        }
        if let Err(e) = self.observer.check(&view) {
            self.stop = Some(e);
            return true;
        }
        self.observer.position(&view);
        self.report.positions += 1;
        self.previous.clone_from(view.state);
        std::mem::swap(&mut self.prev_inputs, &mut self.inputs);
        if k == self.steps {
            return true;
        }
        if self.observer.stop_requested() {
            self.stop = Some(SolveError::Interrupted);
            return true;
        }
        false
    }

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

/// The STOPWHEN quantity minus its value at time `t`, free state `y`
/// (NaN where the position cannot be found).
pub(super) fn watched(eom: &mut Eom<'_>, stop: &StopWhen, t: f64, y: &[f64], acc: &mut [f64]) -> f64 {
    match eom.reach(t, y, acc) {
        Ok(()) => eom.watch(stop.quantity, acc) - stop.value,
        Err(_) => f64::NAN,
    }
}

/// The root of `g` between `a` and `b` (times where `g` is `ga` and `gb`,
/// of opposite signs) by the Illinois variant of regula falsi, to `tol` in
/// time: superlinear, and never outside the bracket.
pub(super) fn locate(
    mut g: impl FnMut(f64) -> f64,
    (mut a, mut ga): (f64, f64),
    (mut b, mut gb): (f64, f64),
    tol: f64,
) -> f64 {
    for _ in 0..100 {
        if (b - a).abs() <= tol {
            break;
        }
        let t = b - gb * (b - a) / (gb - ga);
        let t = if t.is_finite() && t > a.min(b) && t < a.max(b) { t } else { 0.5 * (a + b) };
        let gt = g(t);
        if gt == 0.0 || gt.is_nan() {
            return t;
        }
        // The end kept from before has its value halved, so that it moves
        // too (Illinois).
        if gt * gb < 0.0 {
            (a, ga) = (b, gb);
        } else {
            ga *= 0.5;
        }
        (b, gb) = (t, gt);
    }
    if ga.abs() < gb.abs() {
        a
    } else {
        b
    }
}

/// The free state `[q, q']` at time `t` of a step from `t0` to `t1`, into
/// `out`: each free DOF's quintic Hermite interpolant through its value,
/// speed and acceleration at both ends of the step (`y0`, `a0`; `y1`, `a1`),
/// and its derivative. Its error is of the order of `h^6` in q and `h^5` in
/// q', as small as a fifth-order step's own.
pub(super) fn hermite(
    (t0, y0, a0): (f64, &[f64], &[f64]),
    (t1, y1, a1): (f64, &[f64], &[f64]),
    t: f64,
    out: &mut [f64],
) {
    let nf = a0.len();
    let h = t1 - t0;
    if h <= 0.0 {
        out.copy_from_slice(y1);
        return;
    }
    let s = ((t - t0) / h).clamp(0.0, 1.0);
    let (s2, s3, s4, s5) = (s * s, s * s * s, s * s * s * s, s * s * s * s * s);
    // The basis in the order p0, v0, a0, a1, v1, p1, and its derivative in s.
    let b = [
        1.0 - 10.0 * s3 + 15.0 * s4 - 6.0 * s5,
        s - 6.0 * s3 + 8.0 * s4 - 3.0 * s5,
        0.5 * s2 - 1.5 * s3 + 1.5 * s4 - 0.5 * s5,
        0.5 * s3 - s4 + 0.5 * s5,
        -4.0 * s3 + 7.0 * s4 - 3.0 * s5,
        10.0 * s3 - 15.0 * s4 + 6.0 * s5,
    ];
    let d = [
        -30.0 * s2 + 60.0 * s3 - 30.0 * s4,
        1.0 - 18.0 * s2 + 32.0 * s3 - 15.0 * s4,
        s - 4.5 * s2 + 6.0 * s3 - 2.5 * s4,
        1.5 * s2 - 4.0 * s3 + 2.5 * s4,
        -12.0 * s2 + 28.0 * s3 - 15.0 * s4,
        30.0 * s2 - 60.0 * s3 + 30.0 * s4,
    ];
    for k in 0..nf {
        let v = [y0[k], h * y0[nf + k], h * h * a0[k], h * h * a1[k], h * y1[nf + k], y1[k]];
        out[k] = (0..6).map(|i| b[i] * v[i]).sum();
        out[nf + k] = (0..6).map(|i| d[i] * v[i]).sum::<f64>() / h;
    }
}
