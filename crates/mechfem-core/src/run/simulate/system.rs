//! The equations of motion as the integrator library sees them: a function
//! of time and the free state `y = [q_f, q_f']` that finds the position by
//! Newton at every evaluation, remembers the first evaluation of a step
//! that failed, and keeps the last evaluations for the stiffness test.

use differential_equations::ode::ODE;
use differential_equations::prelude::Matrix;
use differential_equations::traits::State;
use std::cell::{Cell, RefCell};

use super::eom::Eom;
use super::stiffness::Evaluation;
use crate::error::SolveError;

/// How many of the last evaluations are kept: a DOP853 step ends with its
/// twelfth stage and the first stage of the next step at the step's end,
/// then three stages of its dense output.
const KEPT: usize = 6;

pub(super) struct System<'a> {
    pub(super) eom: RefCell<Eom<'a>>,
    acc: RefCell<Vec<f64>>,
    /// The first evaluation that failed since [`Self::clear_failure`]: the
    /// step that made it is not taken, whatever the library made of it.
    failure: RefCell<Option<SolveError>>,
    /// The last evaluations, a ring, and where the next one goes.
    last: RefCell<Vec<Evaluation>>,
    next: Cell<usize>,
    /// Evaluations of the equations, failed ones included.
    pub(super) calls: Cell<usize>,
    /// Jacobians computed, and the last one (row-major, `2 nf` square).
    pub(super) jacobians: Cell<usize>,
    pub(super) jacobian: RefCell<Vec<f64>>,
}

impl<'a> System<'a> {
    pub(super) fn new(eom: Eom<'a>) -> System<'a> {
        let n = 2 * eom.free.len();
        let evaluation = || Evaluation { t: f64::NAN, y: vec![0.0; n], dy: vec![0.0; n] };
        System {
            acc: RefCell::new(vec![0.0; n / 2]),
            eom: RefCell::new(eom),
            failure: RefCell::new(None),
            last: RefCell::new((0..KEPT).map(|_| evaluation()).collect()),
            next: Cell::new(0),
            calls: Cell::new(0),
            jacobians: Cell::new(0),
            jacobian: RefCell::new(vec![0.0; n * n]),
        }
    }

    /// The failure of an evaluation since the last call, if any.
    pub(super) fn take_failure(&self) -> Option<SolveError> {
        self.failure.borrow_mut().take()
    }

    /// Whether an evaluation failed since the failure was last taken.
    pub(super) fn failed(&self) -> bool {
        self.failure.borrow().is_some()
    }

    /// The two kept evaluations at time `t` farthest apart in state, if
    /// two are kept there.
    pub(super) fn pair_at(&self, t: f64, f: impl FnOnce(&Evaluation, &Evaluation) -> bool) -> bool {
        let last = self.last.borrow();
        let distance =
            |a: &Evaluation, b: &Evaluation| a.y.iter().zip(&b.y).map(|(x, y)| (x - y) * (x - y)).sum::<f64>();
        let mut best: Option<(f64, usize, usize)> = None;
        for i in (0..KEPT).filter(|&i| last[i].t == t) {
            for j in (i + 1..KEPT).filter(|&j| last[j].t == t) {
                let d = distance(&last[i], &last[j]);
                if best.is_none_or(|b| d > b.0) {
                    best = Some((d, i, j));
                }
            }
        }
        match best {
            Some((d, i, j)) if d > 0.0 => f(&last[i], &last[j]),
            _ => false,
        }
    }
}

/// A free state as the library holds it: a fixed-size array for the few
/// free DOFs of most mechanisms, a `Vec` beyond for the explicit methods and
/// a [`super::free_state::FreeState`] for the implicit one (the library's
/// Radau IIA sizes its work from `State::zeros()`, which is empty for a
/// `Vec`).
pub(super) trait Free: State<f64> + AsRef<[f64]> + AsMut<[f64]> {
    fn from_slice(y: &[f64]) -> Self;
}

impl<const N: usize> Free for [f64; N] {
    fn from_slice(y: &[f64]) -> Self {
        let mut a = [0.0; N];
        a.copy_from_slice(y);
        a
    }
}

impl Free for Vec<f64> {
    fn from_slice(y: &[f64]) -> Self {
        y.to_vec()
    }
}

impl System<'_> {
    /// The free accelerations of the kept evaluation at exactly `(t, y)`,
    /// into `acc`, if one is kept.
    pub(super) fn acc_at(&self, t: f64, y: &[f64], acc: &mut [f64]) -> bool {
        let last = self.last.borrow();
        match last.iter().find(|e| e.t == t && e.y == y) {
            Some(e) => {
                acc.copy_from_slice(&e.dy[y.len() / 2..]);
                true
            }
            None => false,
        }
    }
}

impl<Y: Free> ODE<f64, Y> for System<'_> {
    fn diff(&self, t: f64, y: &Y, dydt: &mut Y) {
        let (y, dydt) = (y.as_ref(), dydt.as_mut());
        let nf = y.len() / 2;
        // Once a stage has failed the step is lost: the other stages are
        // not worth a Newton solve.
        if self.failed() {
            dydt.fill(0.0);
            return;
        }
        self.calls.set(self.calls.get() + 1);
        let (mut eom, mut acc) = (self.eom.borrow_mut(), self.acc.borrow_mut());
        dydt[..nf].copy_from_slice(&y[nf..]);
        match eom.accelerations(t, y, &mut acc) {
            Ok(()) => dydt[nf..].copy_from_slice(&acc),
            Err(e) => {
                *self.failure.borrow_mut() = Some(e);
                dydt.fill(0.0);
                return;
            }
        }
        let k = self.next.get();
        self.next.set((k + 1) % KEPT);
        let mut last = self.last.borrow_mut();
        last[k].t = t;
        last[k].y.copy_from_slice(y);
        last[k].dy.copy_from_slice(dydt);
    }

    /// By forward differences over the few free states, each a Newton
    /// position: `2 nf + 1` evaluations.
    fn jacobian(&self, t: f64, y: &Y, j: &mut Matrix<f64>) {
        let n = y.as_ref().len();
        self.jacobians.set(self.jacobians.get() + 1);
        let (mut f0, mut f1, mut yp) = (y.clone(), y.clone(), y.clone());
        self.diff(t, y, &mut f0);
        let mut stored = self.jacobian.borrow_mut();
        for c in 0..n {
            let yc = y.as_ref()[c];
            let h = f64::EPSILON.sqrt() * yc.abs().max(1.0);
            yp.as_mut()[c] = yc + h;
            self.diff(t, &yp, &mut f1);
            yp.as_mut()[c] = yc;
            for r in 0..n {
                let d = (f1.as_ref()[r] - f0.as_ref()[r]) / h;
                j[(r, c)] = d;
                stored[r * n + c] = d;
            }
        }
    }
}
