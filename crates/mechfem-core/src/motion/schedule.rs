//! The input values, velocities and accelerations at every position.

use super::{InputMotion, Motion};
use crate::error::SolveError;

/// Input values, velocities and accelerations at every position, and time.
pub(crate) struct Schedule {
    values: Vec<f64>,
    vel: Vec<f64>,
    acc: Vec<f64>,
    pub(crate) time: Vec<f64>,
    n_dof: usize,
}

impl Schedule {
    pub(crate) fn new(motion: &Motion, start: &[f64]) -> Result<Schedule, SolveError> {
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
                        let r = rows
                            .get(k)
                            .ok_or(SolveError::Unsupported("a motion table has fewer rows than positions"))?;
                        if !table_time {
                            s.time[k] = r[0];
                        }
                        (r[1], r[2], r[3])
                    }
                    InputMotion::Free { .. } => {
                        return Err(SolveError::Unsupported("free motion cannot be mixed with driven inputs"))
                    }
                };
                s.values[at] = v;
                s.vel[at] = vd;
                s.acc[at] = vdd;
            }
            table_time |= matches!(m, InputMotion::Table { .. });
        }
        // A motion that lasts longer than f64 can count, or whose inputs
        // move faster (a step time so short that delta / dt overflows).
        if s.time.iter().chain(&s.values).chain(&s.vel).chain(&s.acc).any(|v| !v.is_finite()) {
            return Err(SolveError::NonFinite);
        }
        Ok(s)
    }
    pub(crate) fn values(&self, k: usize) -> &[f64] {
        &self.values[k * self.n_dof..(k + 1) * self.n_dof]
    }
    pub(crate) fn vel(&self, k: usize) -> &[f64] {
        &self.vel[k * self.n_dof..(k + 1) * self.n_dof]
    }
    pub(crate) fn acc(&self, k: usize) -> &[f64] {
        &self.acc[k * self.n_dof..(k + 1) * self.n_dof]
    }
}
