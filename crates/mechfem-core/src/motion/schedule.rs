//! The input values, velocities and accelerations at every position.
//!
//! They are computed a window of positions at a time: a run of a million
//! positions holds no table of them all (for equidistant steps it would be
//! the largest thing a run allocates), and filling a window is a tight
//! loop away from the steps, whose time is a chain of dependent operations
//! that a computation at every step would lengthen.

use super::{InputMotion, Motion};
use crate::error::{SolveError, Unsupported};

/// Positions held at a time.
const WINDOW: usize = 256;

/// How the inputs move, checked once for the whole motion, and their
/// values at a window of positions.
pub(crate) struct Schedule<'a> {
    inputs: Vec<Input<'a>>,
    steps: usize,
    dt: f64,
    /// The input whose table gives the time of every position (the first
    /// table), if any.
    clock: Option<usize>,
    /// The first position of the window.
    base: usize,
    /// Values, velocities and accelerations of the positions in the window
    /// (`n_dof` each), and their times.
    values: Vec<f64>,
    vel: Vec<f64>,
    acc: Vec<f64>,
    time: Vec<f64>,
    n_dof: usize,
}

/// One input's motion.
enum Input<'a> {
    /// Equidistant steps from `start`, changing it by `delta` in all, at
    /// the constant velocity `vel`.
    Linear { start: f64, delta: f64, vel: f64 },
    /// One row per position: time, value, velocity, acceleration.
    Table(&'a [[f64; 4]]),
}

impl<'a> Schedule<'a> {
    /// The schedule of `motion` with the inputs at `start` at position 1,
    /// its window at the start. Fails when a table has fewer rows than
    /// positions, when an input moves freely, or when some input value,
    /// velocity, acceleration or time of the motion would not be finite.
    pub(crate) fn new(motion: &'a Motion, start: &[f64]) -> Result<Schedule<'a>, SolveError> {
        let (n, nd) = (motion.steps, start.len());
        let mut inputs = Vec::with_capacity(nd);
        let mut clock = None;
        for (j, m) in motion.inputs.iter().enumerate() {
            let delta = match m {
                InputMotion::Relative { delta } => *delta,
                InputMotion::Absolute { end } => end - start[j],
                InputMotion::Table { rows } => {
                    let rows = rows.get(..=n).ok_or(SolveError::Unsupported(Unsupported::TableTooShort))?;
                    clock = clock.or(Some(j));
                    inputs.push(Input::Table(rows));
                    continue;
                }
                InputMotion::Free { .. } => return Err(SolveError::Unsupported(Unsupported::FreeWithDriven)),
                InputMotion::Dynamic { .. } => {
                    return Err(SolveError::Unsupported(Unsupported::DynamicNeedsSimulation))
                }
            };
            inputs.push(Input::Linear { start: start[j], delta, vel: delta / (n as f64 * motion.dt) });
        }
        let len = WINDOW.min(n + 1);
        let mut s = Schedule {
            inputs,
            steps: n,
            dt: motion.dt,
            clock,
            base: 0,
            values: vec![0.0; len * nd],
            vel: vec![0.0; len * nd],
            acc: vec![0.0; len * nd],
            time: vec![0.0; len],
            n_dof: nd,
        };
        // A motion that lasts longer than f64 can count, or whose inputs
        // move faster (a step time so short that delta / dt overflows).
        // Equidistant values and times are monotonic in the position, so
        // the first and the last are their extremes; every row of a table
        // is looked at.
        let finite = |v: &[f64]| v.iter().all(|x| x.is_finite());
        for (j, input) in s.inputs.iter().enumerate() {
            if let Input::Table(rows) = input {
                let first = if s.clock == Some(j) { 0 } else { 1 };
                if !rows.iter().all(|r| finite(&r[first..])) {
                    return Err(SolveError::NonFinite);
                }
            }
        }
        // The window's first row after each fill: the last position, then
        // the first (a full window looked at costs a short run a per cent).
        for base in [n, 0] {
            s.fill(base);
            let row = 0..nd;
            if !(finite(&s.values[row.clone()])
                && finite(&s.vel[row.clone()])
                && finite(&s.acc[row])
                && s.time[0].is_finite())
            {
                return Err(SolveError::NonFinite);
            }
        }
        Ok(s)
    }

    /// Makes positions k - 1 to k + 1 (those of them in the motion)
    /// available.
    pub(crate) fn reach(&mut self, k: usize) {
        let last = (k + 1).min(self.steps);
        if k.saturating_sub(1) < self.base || last >= self.base + self.time.len() {
            self.fill(k.saturating_sub(1));
        }
    }

    /// Fills the window from position `base` (up to the last position).
    fn fill(&mut self, base: usize) {
        let (n, nd) = (self.steps as f64, self.n_dof);
        let len = self.time.len().min(self.steps + 1 - base);
        self.base = base;
        for (j, input) in self.inputs.iter().enumerate() {
            for i in 0..len {
                let k = base + i;
                let (v, vd, vdd) = match *input {
                    Input::Linear { start, delta, vel } => (start + delta * k as f64 / n, vel, 0.0),
                    Input::Table(rows) => (rows[k][1], rows[k][2], rows[k][3]),
                };
                self.values[i * nd + j] = v;
                self.vel[i * nd + j] = vd;
                self.acc[i * nd + j] = vdd;
            }
        }
        for (i, t) in self.time[..len].iter_mut().enumerate() {
            *t = match self.clock.map(|j| &self.inputs[j]) {
                Some(Input::Table(rows)) => rows[base + i][0],
                _ => (base + i) as f64 * self.dt,
            };
        }
    }

    /// The row of position k in the window.
    fn row(&self, k: usize) -> usize {
        k - self.base
    }

    pub(crate) fn values(&self, k: usize) -> &[f64] {
        let i = self.row(k);
        &self.values[i * self.n_dof..(i + 1) * self.n_dof]
    }

    pub(crate) fn vel(&self, k: usize) -> &[f64] {
        let i = self.row(k);
        &self.vel[i * self.n_dof..(i + 1) * self.n_dof]
    }

    pub(crate) fn acc(&self, k: usize) -> &[f64] {
        let i = self.row(k);
        &self.acc[i * self.n_dof..(i + 1) * self.n_dof]
    }

    pub(crate) fn time(&self, k: usize) -> f64 {
        self.time[self.row(k)]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn motion(steps: usize, dt: f64, inputs: Vec<InputMotion>) -> Motion {
        Motion { steps, dt, inputs }
    }

    #[test]
    fn equidistant_and_tabled_inputs() {
        let rows: Vec<[f64; 4]> = (0..=4).map(|k| [10.0 + k as f64, -(k as f64), 2.0, 3.0]).collect();
        let m = motion(
            4,
            0.5,
            vec![InputMotion::Relative { delta: 2.0 }, InputMotion::Absolute { end: 5.0 }, InputMotion::Table { rows }],
        );
        let mut s = Schedule::new(&m, &[1.0, 3.0, 0.0]).unwrap();
        s.reach(3);
        assert_eq!(s.values(3), [1.0 + 2.0 * 3.0 / 4.0, 3.0 + 2.0 * 3.0 / 4.0, -3.0]);
        assert_eq!(s.vel(3), [1.0, 1.0, 2.0]);
        assert_eq!(s.acc(3), [0.0, 0.0, 3.0]);
        // The table gives the time.
        assert_eq!(s.time(3), 13.0);
        assert_eq!(s.values(4)[1], 5.0);
        let plain = motion(4, 0.5, vec![InputMotion::Relative { delta: 2.0 }]);
        let s = Schedule::new(&plain, &[1.0]).unwrap();
        assert_eq!(s.time(3), 1.5);
    }

    #[test]
    fn the_window_moves_with_the_motion() {
        let n = 3 * WINDOW + 7;
        let m = motion(n, 0.25, vec![InputMotion::Relative { delta: -1.5 }]);
        let mut s = Schedule::new(&m, &[2.0]).unwrap();
        for k in 1..=n {
            s.reach(k);
            for i in [k - 1, k, (k + 1).min(n)] {
                assert_eq!(s.values(i), [2.0 + -1.5 * i as f64 / n as f64], "position {i} at step {k}");
                assert_eq!(s.time(i), i as f64 * 0.25);
            }
        }
        assert_eq!(s.values(n), [0.5]);
    }

    #[test]
    fn motions_that_cannot_run_are_refused() {
        let short = motion(4, 1.0, vec![InputMotion::Table { rows: vec![[0.0; 4]; 4] }]);
        assert!(matches!(Schedule::new(&short, &[0.0]), Err(SolveError::Unsupported(_))));
        let free = motion(4, 1.0, vec![InputMotion::Relative { delta: 1.0 }, InputMotion::Free { ds: 0.1 }]);
        assert!(matches!(Schedule::new(&free, &[0.0, 0.0]), Err(SolveError::Unsupported(_))));
        // Overflow at the last position only, in a value, a velocity, a
        // time, and in a table row.
        for m in [
            motion(4, 1.0, vec![InputMotion::Relative { delta: f64::MAX }]),
            motion(4, 1e-308, vec![InputMotion::Relative { delta: 1e10 }]),
            motion(4, f64::MAX, vec![InputMotion::Relative { delta: 1.0 }]),
            motion(2, 1.0, vec![InputMotion::Table { rows: vec![[0.0; 4], [0.0, f64::NAN, 0.0, 0.0], [0.0; 4]] }]),
        ] {
            assert_eq!(Schedule::new(&m, &[1e308]).err(), Some(SolveError::NonFinite), "{m:?}");
        }
        // A table's times are not read when another table gives them.
        let rows = vec![[f64::NAN, 0.0, 0.0, 0.0]; 3];
        let m = motion(2, 1.0, vec![InputMotion::Table { rows: vec![[0.0; 4]; 3] }, InputMotion::Table { rows }]);
        assert!(Schedule::new(&m, &[0.0, 0.0]).is_ok());
    }
}
