//! The equations of motion of a simulation in its free degrees of freedom,
//! and how its driven degrees of freedom move.

use super::super::inverse::InverseDynamics;
use super::super::observe::PositionView;
use super::super::record::{record, Quantity};
use crate::error::{SolveError, Unsupported};
use crate::model::{Mechanism, State};
use crate::solver::{correct, Kinematics, Params, TransferOrder};

/// How a driven DOF moves, at any time.
#[derive(Debug, Clone)]
pub(super) enum Driver {
    /// Linear in time (MOV_RELE, MOV_ABSE).
    Linear { start: f64, rate: f64 },
    /// A table `t value velocity acceleration`: cubic between rows from
    /// the values and velocities, the acceleration linear between rows.
    Table(Vec<[f64; 4]>),
}

impl Driver {
    pub(super) fn at(&self, t: f64) -> [f64; 3] {
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
pub(super) struct Eom<'a> {
    pub(super) mech: &'a Mechanism,
    pub(super) params: Params,
    pub(super) state: State,
    pub(super) kin: Kinematics,
    pub(super) inverse: InverseDynamics,
    /// The free DOFs, in order.
    pub(super) free: Vec<usize>,
    /// The driven DOFs and how they move.
    pub(super) driven: Vec<(usize, Driver)>,
    pub(super) q: Vec<f64>,
    pub(super) qd: Vec<f64>,
    pub(super) qdd: Vec<f64>,
    pub(super) drives: Vec<f64>,
    /// The inputs of the last position found, for the next prediction.
    pub(super) q_last: Vec<f64>,
    /// M_ff and its right-hand side, for the free accelerations.
    pub(super) m_ff: Vec<f64>,
    pub(super) rhs: Vec<f64>,
    pub(super) saved: State,
    /// Evaluations of the equations, one Newton position each, whether
    /// the position was found or not: the integrator's stages, its
    /// Jacobians, the outputs and the STOPWHEN location.
    pub(super) evaluations: usize,
    /// The time and free state `[q_f, q_f']` of the last position found.
    pub(super) found_t: f64,
    pub(super) found_y: Vec<f64>,
    /// The position at the end of the integrator's last accepted step, and
    /// its inputs, kept while the outputs inside the step are found.
    pub(super) kept: State,
    pub(super) kept_q: Vec<f64>,
    pub(super) kept_y: Vec<f64>,
    pub(super) kept_t: f64,
    pub(super) kept_det: f64,
    /// The largest |det(D^c)| met so far.
    pub(super) det_max: f64,
    /// Whether a stage ran into a limit position of a free DOF.
    pub(super) limit_met: bool,
    /// det(D^c) at the last position found (0 before the first).
    pub(super) det_last: f64,
}

/// |det(D^c)| below this share of the largest met so far is a limit position.
pub(super) const LIMIT_DET: f64 = 1e-6;

pub(super) const LIMIT_REASON: &str =
    "a limit position of a free degree of freedom (det(D^c) fell below 1e-6 of its largest \
                            value): the DOF cannot move the mechanism through it (let another DOF move freely)";

impl Eom<'_> {
    /// The free DOFs' accelerations at time `t`, free positions and speeds
    /// `y = [q_f, q_f']`, into `out`; the position found stays in `self.state`.
    pub(super) fn accelerations(&mut self, t: f64, y: &[f64], out: &mut [f64]) -> Result<(), SolveError> {
        let (mech, nf) = (self.mech, self.free.len());
        self.evaluations += 1;
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
        // Newton from a far prediction (a long step's stage) can close the
        // mechanism on its other assembly branch, where det(D^c) has the
        // other sign: such a position counts as not found either.
        let (before, after) = (self.det_last, self.kin.det());
        if before * after < 0.0 {
            self.state.clone_from(&self.saved);
            let _ = self.kin.transfer(mech, &mut self.state, TransferOrder::Second);
            return Err(SolveError::DetSignChange { before, after });
        }
        self.det_last = after;
        if det < LIMIT_DET * self.det_max {
            self.limit_met = true;
            self.state.clone_from(&self.saved);
            let _ = self.kin.transfer(mech, &mut self.state, TransferOrder::Second);
            return Err(SolveError::Simulation { time: t, reason: LIMIT_REASON });
        }
        self.q_last.copy_from_slice(&self.q);
        self.found_t = t;
        self.found_y.copy_from_slice(y);
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
    /// [`Self::accelerations`] at `(t, y)`: when the position there cannot
    /// be found from the last one found, it is approached in shorter and
    /// shorter stages along the straight line between the two states.
    pub(super) fn reach(&mut self, t: f64, y: &[f64], out: &mut [f64]) -> Result<(), SolveError> {
        let Err(mut error) = self.accelerations(t, y, out) else { return Ok(()) };
        let (from_t, from_y) = (self.found_t, self.found_y.clone());
        let mut at = y.to_vec();
        for stages in [2, 4, 8, 16, 32] {
            let staged = (1..=stages).try_for_each(|i| {
                let s = i as f64 / stages as f64;
                for (yk, (a, b)) in at.iter_mut().zip(from_y.iter().zip(y)) {
                    *yk = a + s * (b - a);
                }
                self.accelerations(from_t + s * (t - from_t), &at, out)
            });
            match staged {
                Ok(()) => return Ok(()),
                Err(e) => error = e,
            }
        }
        Err(error)
    }

    /// Keeps the position last found (the end of an accepted step) while
    /// the outputs inside the step are found from it.
    pub(super) fn keep(&mut self) {
        self.kept.clone_from(&self.state);
        self.kept_q.copy_from_slice(&self.q_last);
        self.kept_y.copy_from_slice(&self.found_y);
        self.kept_t = self.found_t;
        self.kept_det = self.det_last;
    }

    /// Back at the position [`Self::keep`] kept, so that the integration
    /// goes on from the position it found itself, whatever outputs were
    /// found in between.
    pub(super) fn back(&mut self) {
        self.state.clone_from(&self.kept);
        self.q_last.copy_from_slice(&self.kept_q);
        self.found_y.copy_from_slice(&self.kept_y);
        self.found_t = self.kept_t;
        self.det_last = self.kept_det;
        let _ = self.kin.transfer(self.mech, &mut self.state, TransferOrder::Second);
    }

    /// The position last found as an observer sees it, at output `index`,
    /// with the free DOFs' accelerations `acc` found there.
    pub(super) fn view(&mut self, index: usize, acc: &[f64]) -> PositionView<'_> {
        for (&j, &a) in self.free.iter().zip(acc) {
            self.qdd[j] = a;
        }
        PositionView {
            index,
            time: self.found_t,
            mech: self.mech,
            state: &self.state,
            kin: &self.kin,
            input_vel: &self.qd,
            input_acc: &self.qdd,
        }
    }
}

impl Eom<'_> {
    /// The value of `quantity` at the position last found, with the free
    /// DOFs' accelerations `acc` found there (inverse dynamics evaluated
    /// for a quantity of the dynamics).
    pub(super) fn watch(&mut self, quantity: Quantity, acc: &[f64]) -> f64 {
        for (&j, &a) in self.free.iter().zip(acc) {
            self.qdd[j] = a;
        }
        let view = PositionView {
            index: 0,
            time: self.found_t,
            mech: self.mech,
            state: &self.state,
            kin: &self.kin,
            input_vel: &self.qd,
            input_acc: &self.qdd,
        };
        let mut out = Vec::with_capacity(1);
        record(&[quantity], &view, Some(&mut self.inverse), &mut out);
        out[0]
    }
}

/// Solves the n x n system `a x = b` (row-major `a`, overwritten) in place
/// by Gaussian elimination with partial pivoting; None when `a` is singular.
pub(super) fn solve_dense(n: usize, a: &mut [f64], b: &mut [f64]) -> Option<()> {
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
