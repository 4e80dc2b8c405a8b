//! The explicit Runge-Kutta method of order 8 of Dormand and Prince, with
//! the error estimator of order 5 and 3 and the dense output of order 7 of
//! Hairer's DOP853 (Hairer, Nørsett and Wanner, Solving ODEs I, II.5 and
//! II.6; the coefficients are those of Hairer's dop853.f).
//!
//! mechfem has its own DOP853 stepper because the integrator library's
//! (`differential-equations` 0.7) cannot be used for mechanisms: its dense
//! output alternates `s` and `1 - s` the wrong way round in the terms of
//! order 4 to 7 (its local error between steps falls as h^5, not h^8:
//! 2.3e-6 against 4e-10 in one step of 0.2 on the equation of this file's
//! tests, whose steps' ends it matches bit for bit), it evaluates the three stages of that dense output at
//! every step whether an output falls in it or not, and it keeps them
//! private. Here the dense output's three stages are evaluated only for a
//! step that holds an output or a STOPWHEN crossing ([`Dop853::dense`]),
//! and the step-size control is Hairer's (the step grows at most sixfold,
//! shrinks at most threefold, and does not grow right after a rejected
//! step). Each step evaluates the equations 12 times: the 11 stages after
//! the first, and the derivative at the new end, which is the next step's
//! first stage.

use std::any::Any;

use differential_equations::error::Error as StepError;
use differential_equations::interpolate::Interpolation;
use differential_equations::ode::{OrdinaryNumericalMethod, ODE};
use differential_equations::stats::Evals;
use differential_equations::status::Status;

use super::system::{Free, System};
use tableau::{A, B, C, D, E3, E5};

mod tableau;

/// Stages of a step, the derivative at its end, and the three stages of
/// the dense output.
const STAGES: usize = 12;
const EXTENDED: usize = 16;

/// One DOP853 integration: where it is, the step just taken and the next.
pub(super) struct Dop853<Y: Free> {
    rtol: f64,
    atol: f64,
    h: f64,
    h_max: f64,
    t: f64,
    y: Y,
    /// The derivative at `(t, y)`, the next step's first stage.
    f: Y,
    /// The last step accepted: its start, length and stages (`k[12]` is
    /// the derivative at its end, `k[13..16]` the dense output's stages).
    t_prev: f64,
    y_prev: Y,
    h_prev: f64,
    k: Vec<Y>,
    /// The dense output's coefficients for the last step accepted, once
    /// [`Self::dense`] has made them.
    cont: Vec<Y>,
    dense_ready: bool,
    stage: Y,
    /// Whether the last step tried was rejected.
    reject: bool,
    status: Status<f64, Y>,
}

impl<Y: Free> Dop853<Y> {
    /// A DOP853 with tolerances `rtol` and `atol`, first step `h0` (0: a
    /// step chosen as Hairer's HINIT and SciPy choose it) and longest step `h_max`.
    pub(super) fn new(rtol: f64, atol: f64, h0: f64, h_max: f64) -> Self {
        let empty = Y::zeros();
        Dop853 {
            rtol,
            atol,
            h: h0,
            h_max,
            t: 0.0,
            y: empty.clone(),
            f: empty.clone(),
            t_prev: 0.0,
            y_prev: empty.clone(),
            h_prev: 0.0,
            k: Vec::new(),
            cont: Vec::new(),
            dense_ready: false,
            stage: empty,
            reject: false,
            status: Status::Uninitialized,
        }
    }

    fn scale(&self, a: f64, b: f64) -> f64 {
        self.atol + self.rtol * a.abs().max(b.abs())
    }

    /// Hairer's first step: one Euler step of a length from the size of
    /// the state and its derivative, and the second derivative from it.
    fn first_step<F: ODE<f64, Y> + ?Sized>(&mut self, ode: &F, tf: f64) -> f64 {
        let (y0, f0) = (self.y.as_ref(), self.f.as_ref());
        let n = y0.len() as f64;
        let sk: Vec<f64> = y0.iter().map(|&v| self.scale(v, v)).collect();
        let norm = |v: &[f64]| (v.iter().zip(&sk).map(|(x, s)| (x / s) * (x / s)).sum::<f64>() / n).sqrt();
        let (dnf, dny) = (norm(f0), norm(y0));
        let h_max = self.h_max.min((tf - self.t).abs());
        let mut h = if dnf <= 1e-5 || dny <= 1e-5 { 1e-6 } else { 0.01 * dny / dnf };
        h = h.min(h_max);
        let y1: Vec<f64> = y0.iter().zip(f0).map(|(y, f)| y + h * f).collect();
        let mut f1 = self.f.clone();
        ode.diff(self.t + h, &Y::from_slice(&y1), &mut f1);
        let d2: Vec<f64> = f1.as_ref().iter().zip(f0).map(|(a, b)| (a - b) / h).collect();
        let der12 = norm(&d2).max(dnf);
        let h1 = if der12 <= 1e-15 { (h * 1e-3).max(1e-6) } else { (0.01 / der12).powf(1.0 / 8.0) };
        (100.0 * h).min(h1).min(h_max)
    }

    /// The stage state `y + h sum_j a[i][j] k[j]` into `self.stage`.
    fn stage_state(&mut self, i: usize, y: &[f64], h: f64) {
        let out = self.stage.as_mut();
        out.copy_from_slice(y);
        for (j, &a) in A[i].iter().enumerate().take(i) {
            if a != 0.0 {
                for (o, k) in out.iter_mut().zip(self.k[j].as_ref()) {
                    *o += h * a * k;
                }
            }
        }
    }

    /// Evaluates the three stages of the dense output of the last step
    /// accepted and makes its coefficients, once per step; whether the
    /// dense output is ready (not when an evaluation failed: `ode` knows).
    pub(super) fn dense<F: ODE<f64, Y> + ?Sized>(&mut self, ode: &F, failed: impl Fn() -> bool) -> bool {
        if self.dense_ready || self.h_prev == 0.0 {
            return self.dense_ready;
        }
        let (t0, h) = (self.t_prev, self.h_prev);
        let y0 = self.y_prev.clone();
        for i in STAGES + 1..EXTENDED {
            self.stage_state(i, y0.as_ref(), h);
            let mut k = self.k[i].clone();
            ode.diff(t0 + C[i] * h, &self.stage, &mut k);
            self.k[i] = k;
            if failed() {
                return false;
            }
        }
        let n = y0.as_ref().len();
        for c in 0..7 {
            for m in 0..n {
                let (y0m, y1m) = (y0.as_ref()[m], self.y.as_ref()[m]);
                let (f0, f1) = (self.k[0].as_ref()[m], self.k[STAGES].as_ref()[m]);
                let dy = y1m - y0m;
                self.cont[c].as_mut()[m] = match c {
                    0 => dy,
                    1 => h * f0 - dy,
                    2 => 2.0 * dy - h * (f0 + f1),
                    _ => h * (0..EXTENDED).map(|j| D[c - 3][j] * self.k[j].as_ref()[m]).sum::<f64>(),
                };
            }
        }
        self.dense_ready = true;
        true
    }
}

impl<Y: Free> OrdinaryNumericalMethod<f64, Y> for Dop853<Y> {
    fn init<F>(&mut self, ode: &F, t0: f64, tf: f64, y0: &Y) -> Result<Evals, StepError<f64, Y>>
    where
        F: ODE<f64, Y> + ?Sized,
    {
        let mut evals = Evals::new();
        (self.t, self.y, self.f) = (t0, y0.clone(), y0.clone());
        ode.diff(t0, y0, &mut self.f);
        evals.function += 1;
        if self.h == 0.0 {
            self.h = self.first_step(ode, tf);
            evals.function += 1;
        }
        self.h = self.h.min(self.h_max);
        (self.t_prev, self.y_prev, self.h_prev) = (t0, y0.clone(), 0.0);
        self.k = vec![y0.clone(); EXTENDED];
        self.cont = vec![y0.clone(); 7];
        self.stage = y0.clone();
        (self.dense_ready, self.reject) = (false, false);
        self.status = Status::Initialized;
        Ok(evals)
    }

    fn step<F>(&mut self, ode: &F) -> Result<Evals, StepError<f64, Y>>
    where
        F: ODE<f64, Y> + ?Sized,
    {
        let mut evals = Evals::new();
        let h = self.h;
        if 0.1 * h.abs() <= self.t.abs() * f64::EPSILON || h.is_nan() {
            return Err(StepError::StepSize { t: self.t, y: self.y.clone() });
        }
        let y = self.y.clone();
        self.k[0].clone_from(&self.f);
        for i in 1..STAGES {
            self.stage_state(i, y.as_ref(), h);
            let mut k = self.k[i].clone();
            ode.diff(self.t + C[i] * h, &self.stage, &mut k);
            self.k[i] = k;
        }
        evals.function += STAGES - 1;
        let n = y.as_ref().len();
        let mut y_new = y.clone();
        let (mut err5, mut err3) = (0.0, 0.0);
        for m in 0..n {
            let k = |j: usize| self.k[j].as_ref()[m];
            let step: f64 = (0..STAGES).map(|j| B[j] * k(j)).sum();
            let y1 = y.as_ref()[m] + h * step;
            y_new.as_mut()[m] = y1;
            let sk = self.scale(y.as_ref()[m], y1);
            let e3: f64 = (0..STAGES).map(|j| E3[j] * k(j)).sum::<f64>() / sk;
            let e5: f64 = (0..STAGES).map(|j| E5[j] * k(j)).sum::<f64>() / sk;
            (err3, err5) = (err3 + e3 * e3, err5 + e5 * e5);
        }
        let deno = if err5 + 0.01 * err3 > 0.0 { err5 + 0.01 * err3 } else { 1.0 };
        let err = h.abs() * err5 * (1.0 / (n as f64 * deno)).sqrt();
        let fac11 = err.powf(1.0 / 8.0);
        if err <= 1.0 && err.is_finite() {
            let t_new = self.t + h;
            let mut f_new = self.f.clone();
            ode.diff(t_new, &y_new, &mut f_new);
            evals.function += 1;
            self.k[STAGES].clone_from(&f_new);
            let grow = (fac11 / SAFE).clamp(1.0 / GROW, 1.0 / SHRINK);
            let mut h_new = (h / grow).min(self.h_max);
            if self.reject {
                h_new = h_new.min(h);
            }
            (self.t_prev, self.h_prev) = (self.t, h);
            self.y_prev = std::mem::replace(&mut self.y, y_new);
            (self.t, self.f, self.h) = (t_new, f_new, h_new);
            (self.dense_ready, self.reject) = (false, false);
            self.status = Status::Solving;
        } else {
            let shrink = if err.is_finite() { (fac11 / SAFE).min(1.0 / SHRINK) } else { 1.0 / SHRINK };
            self.h = h / shrink;
            self.reject = true;
            self.status = Status::RejectedStep;
        }
        Ok(evals)
    }

    fn t(&self) -> f64 {
        self.t
    }
    fn y(&self) -> &Y {
        &self.y
    }
    fn t_prev(&self) -> f64 {
        self.t_prev
    }
    fn y_prev(&self) -> &Y {
        &self.y_prev
    }
    fn h(&self) -> f64 {
        self.h
    }
    fn set_h(&mut self, h: f64) {
        self.h = h;
    }
    fn status(&self) -> &Status<f64, Y> {
        &self.status
    }
    fn set_status(&mut self, status: Status<f64, Y>) {
        self.status = status;
    }
}

impl<Y: Free> Interpolation<f64, Y> for Dop853<Y> {
    /// The dense output of order 7 of the last step accepted (Hairer's
    /// CONTD8), once [`Dop853::dense`] has made it.
    fn interpolate(&mut self, t: f64) -> Result<Y, StepError<f64, Y>> {
        if !self.dense_ready || t < self.t_prev || t > self.t {
            return Err(StepError::OutOfBounds { t_interp: t, t_prev: self.t_prev, t_curr: self.t });
        }
        let s = (t - self.t_prev) / self.h_prev;
        let s1 = 1.0 - s;
        let mut out = self.y_prev.clone();
        for (m, o) in out.as_mut().iter_mut().enumerate() {
            let c = |i: usize| self.cont[i].as_ref()[m];
            let conpar = c(3) + s * (c(4) + s1 * (c(5) + s * c(6)));
            *o += s * (c(0) + s1 * (c(1) + s * (c(2) + s1 * conpar)));
        }
        Ok(out)
    }
}

/// Makes the dense output of order 7 of the step `method` accepted last,
/// when `method` is DOP853: its three stages are evaluated only for a step
/// that holds an output or may hold a STOPWHEN crossing. Whether that dense
/// output is there to use (not for another method, nor when an evaluation
/// for it failed: the outputs of the step then come from the quintic
/// Hermite interpolant).
pub(super) fn dense_output<M: Any, Y: Free + 'static>(method: &mut M, sys: &System<'_>) -> bool {
    let Some(dop853) = (method as &mut dyn Any).downcast_mut::<Dop853<Y>>() else { return false };
    let ready = dop853.dense(sys, || sys.failed());
    if !ready {
        sys.take_failure();
    }
    ready
}

/// Hairer's step-size control: safety factor, and the most a step may
/// shrink (to a third) and grow (sixfold) at once.
const SAFE: f64 = 0.9;
const SHRINK: f64 = 0.333;
const GROW: f64 = 6.0;

#[cfg(test)]
mod tests {
    use super::*;

    /// y1' = 1 + y1^2, y2' = -y1 y2: y = (tan t, cos t), nonlinear.
    struct Tangent;

    impl ODE<f64, [f64; 2]> for Tangent {
        fn diff(&self, _t: f64, y: &[f64; 2], dy: &mut [f64; 2]) {
            *dy = [1.0 + y[0] * y[0], -y[0] * y[1]];
        }
    }

    fn exact(t: f64) -> [f64; 2] {
        [t.tan(), t.cos()]
    }

    fn error(y: &[f64; 2], t: f64) -> f64 {
        let e = exact(t);
        (y[0] - e[0]).abs().max((y[1] - e[1]).abs())
    }

    /// One step of length `h` from the exact state at `t0`, accepted (the
    /// tolerances are loose): its error at the end and, from the dense
    /// output, the largest at 7 points inside.
    fn one_step(t0: f64, h: f64) -> (f64, f64) {
        let mut m = Dop853::<[f64; 2]>::new(1.0, 1.0, h, 1.0);
        m.init(&Tangent, t0, t0 + 1.0, &exact(t0)).unwrap();
        m.step(&Tangent).unwrap();
        assert_eq!(m.t(), t0 + h, "the step is accepted");
        assert!(m.dense(&Tangent, || false));
        let inside = (1..8).map(|i| t0 + h * i as f64 / 8.0);
        let dense = inside.map(|t| error(&m.interpolate(t).unwrap(), t)).fold(0.0, f64::max);
        (error(m.y(), t0 + h), dense)
    }

    /// The step's local error falls as h^9 (order 8), the dense output's
    /// as h^8 (order 7).
    #[test]
    fn the_step_is_of_order_8_and_its_dense_output_of_order_7() {
        let (e1, d1) = one_step(0.3, 0.2);
        let (e2, d2) = one_step(0.3, 0.1);
        let (step, dense) = ((e1 / e2).log2(), (d1 / d2).log2());
        assert!((8.5..9.8).contains(&step), "step: order {step} - 1 ({e1:e}, {e2:e})");
        assert!((7.5..8.8).contains(&dense), "dense output: order {dense} - 1 ({d1:e}, {d2:e})");
    }

    /// Integrated adaptively, the steps' ends follow the tolerance, and the
    /// dense output between them stays within a small multiple of their
    /// error (its local error is of order h^8 where the step's is h^9).
    #[test]
    fn the_dense_output_is_as_accurate_as_the_steps() {
        for tol in [1e-6, 1e-9, 1e-12] {
            let mut m = Dop853::<[f64; 2]>::new(tol, tol, 0.0, 1.3);
            m.init(&Tangent, 0.0, 1.3, &exact(0.0)).unwrap();
            let (mut ends, mut inside, mut steps) = (0.0f64, 0.0f64, 0);
            while m.t() < 1.3 {
                let h = m.h().min(1.3 - m.t());
                m.set_h(h);
                let t0 = m.t();
                m.step(&Tangent).unwrap();
                if m.t() == t0 {
                    continue;
                }
                steps += 1;
                ends = ends.max(error(m.y(), m.t()));
                assert!(m.dense(&Tangent, || false));
                for i in 1..10 {
                    let t = t0 + (m.t() - t0) * i as f64 / 10.0;
                    inside = inside.max(error(&m.interpolate(t).unwrap(), t));
                }
            }
            assert!(steps >= 5, "{steps} steps");
            assert!(ends < 10.0 * tol && inside < 30.0 * ends, "{tol:e}: {ends:e} at ends, {inside:e} inside");
        }
    }
}
