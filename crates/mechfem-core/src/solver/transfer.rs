//! Transfer functions at a position: first order (eq. 5.16a), second order
//! for every pair of inputs (eq. 5.22), the full second order on request
//! (eq. 5.28), dependent form parameters (eqs. 5.31, 5.32), det(D^c), and
//! timed velocities and accelerations (eqs. 5.29, 5.30).
//!
//! [`Kinematics`] is also the workspace of the Newton iteration: every
//! buffer is allocated once, in [`Kinematics::new`].

use super::assemble::{eval_rows, fill_dc, grad_dot, hess_product};
use super::lu::Lu;
use crate::elements::{FormEval, Order};
use crate::error::SolveError;
use crate::model::{Mechanism, State, FIXED};

/// How far [`Kinematics::transfer`] goes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum TransferOrder {
    /// det(D^c) and first-order transfer functions.
    First,
    /// Also second-order transfer functions of every pair of inputs.
    Second,
}

/// Workspace and results of the analysis at one position.
#[derive(Debug, Clone)]
pub struct Kinematics {
    n: usize,
    n_dof: usize,
    pub(crate) lu: Lu,
    pub(crate) work: Vec<f64>,
    pub(crate) rhs: Vec<f64>,
    pub(crate) cache: Vec<FormEval>,
    dep_cache: Vec<FormEval>,
    pub(crate) row_values: Vec<f64>,
    det: f64,
    /// d x^c / d input_j, column j at `x1[j*n..]`.
    x1: Vec<f64>,
    /// d2 x^c / d input_j d input_m, column of pair p at `x2[p*n..]`.
    x2: Vec<f64>,
    pair: Vec<usize>,
    dep: Vec<f64>,
    dep1: Vec<f64>,
    dep2: Vec<f64>,
    order: Option<TransferOrder>,
}

impl Kinematics {
    /// Allocates every buffer for `mech`.
    pub fn new(mech: &Mechanism) -> Kinematics {
        let n = mech.n_moving();
        let n_dof = mech.n_dof();
        let n_pairs = n_dof * (n_dof + 1) / 2;
        let mut pair = vec![0; n_dof * n_dof];
        let mut p = 0;
        for j in 0..n_dof {
            for m in j..n_dof {
                pair[j * n_dof + m] = p;
                pair[m * n_dof + j] = p;
                p += 1;
            }
        }
        let n_d = mech.n_dependent();
        Kinematics {
            n,
            n_dof,
            lu: Lu::new(n),
            work: vec![0.0; n],
            rhs: vec![0.0; n],
            cache: vec![FormEval::default(); mech.prescribed.terms().len()],
            dep_cache: vec![FormEval::default(); mech.dependent.terms().len()],
            row_values: vec![0.0; n],
            det: f64::NAN,
            x1: vec![0.0; n * n_dof],
            x2: vec![0.0; n * n_pairs],
            pair,
            dep: vec![0.0; n_d],
            dep1: vec![0.0; n_d * n_dof],
            dep2: vec![0.0; n_d * n_pairs],
            order: None,
        }
    }

    /// Computes det(D^c), the transfer functions of the moving co-ordinates
    /// and of the dependent form parameters at the state's co-ordinates,
    /// with one factorisation of D^c.
    pub fn transfer(&mut self, mech: &Mechanism, state: &mut State, order: TransferOrder) -> Result<(), SolveError> {
        self.order = None;
        let n = self.n;
        let eval_order = if order == TransferOrder::Second { Order::Second } else { Order::First };
        eval_rows(
            mech,
            &mech.prescribed,
            &state.x,
            &mut state.branch,
            eval_order,
            &mut self.cache,
            &mut self.row_values,
        )?;
        fill_dc(mech, &self.cache, &mut self.lu);
        if let Err(s) = self.lu.factor() {
            // A limit position: no transfer functions, but the values of the
            // dependent form parameters are still known.
            self.det = 0.0;
            eval_rows(
                mech,
                &mech.dependent,
                &state.x,
                &mut state.branch,
                Order::Value,
                &mut self.dep_cache,
                &mut self.dep,
            )?;
            return Err(SolveError::Singular { column: s.column, pivot: s.pivot });
        }
        self.det = self.lu.det();
        // eq. 5.16a: column j of F^cm is (D^c)^-1 e_{input row j}.
        for j in 0..self.n_dof {
            let col = &mut self.x1[j * n..(j + 1) * n];
            col.fill(0.0);
            col[mech.input_row(j)] = 1.0;
            self.lu.solve(col, &mut self.work);
        }
        if order == TransferOrder::Second {
            // eq. 5.22, for every pair (j, m): D^c x''_jm = -D_kl x'_j,k x'_m,l.
            for j in 0..self.n_dof {
                for m in j..self.n_dof {
                    let p = self.pair[j * self.n_dof + m];
                    let (a, b) = (&self.x1[j * n..(j + 1) * n], &self.x1[m * n..(m + 1) * n]);
                    for i in 0..n {
                        self.rhs[i] = -hess_product(mech, &mech.prescribed, &self.cache, i, a, b);
                    }
                    self.lu.solve(&mut self.rhs, &mut self.work);
                    self.x2[p * n..(p + 1) * n].copy_from_slice(&self.rhs);
                }
            }
        }
        self.dependents(mech, state, order)?;
        if self.x1.iter().chain(&self.x2).any(|v| !v.is_finite()) {
            return Err(SolveError::NonFinite);
        }
        self.order = Some(order);
        Ok(())
    }

    /// eqs. 5.31, 5.32: value, first and second order of every dependent
    /// form parameter.
    fn dependents(&mut self, mech: &Mechanism, state: &mut State, order: TransferOrder) -> Result<(), SolveError> {
        let (n, nd) = (self.n, self.n_dof);
        let rows = &mech.dependent;
        let eval_order = if order == TransferOrder::Second { Order::Second } else { Order::First };
        eval_rows(mech, rows, &state.x, &mut state.branch, eval_order, &mut self.dep_cache, &mut self.dep)?;
        for d in 0..rows.len() {
            for j in 0..nd {
                self.dep1[d * nd + j] = grad_dot(mech, rows, &self.dep_cache, d, &self.x1[j * n..(j + 1) * n]);
            }
            if order == TransferOrder::Second {
                let n_pairs = nd * (nd + 1) / 2;
                for j in 0..nd {
                    for m in j..nd {
                        let p = self.pair[j * nd + m];
                        let (a, b) = (&self.x1[j * n..(j + 1) * n], &self.x1[m * n..(m + 1) * n]);
                        self.dep2[d * n_pairs + p] =
                            grad_dot(mech, rows, &self.dep_cache, d, &self.x2[p * n..(p + 1) * n])
                                + hess_product(mech, rows, &self.dep_cache, d, a, b);
                    }
                }
            }
        }
        Ok(())
    }

    /// What the last successful [`Self::transfer`] computed, if anything.
    pub fn order(&self) -> Option<TransferOrder> {
        self.order
    }

    /// det(D^c) at the last transfer (0 when D^c was singular).
    pub fn det(&self) -> f64 {
        self.det
    }

    /// d x_i / d input_j for co-ordinate `coord` (0 for a fixed one).
    pub fn dx(&self, mech: &Mechanism, coord: usize, j: usize) -> f64 {
        match mech.column(coord) {
            FIXED => 0.0,
            c => self.x1[j * self.n + c],
        }
    }

    /// d2 x_i / d input_j d input_m for co-ordinate `coord`.
    pub fn d2x(&self, mech: &Mechanism, coord: usize, j: usize, m: usize) -> f64 {
        match mech.column(coord) {
            FIXED => 0.0,
            c => self.x2[self.pair[j * self.n_dof + m] * self.n + c],
        }
    }

    /// First-order transfer function of input j over the moving co-ordinates.
    pub fn x1(&self, j: usize) -> &[f64] {
        &self.x1[j * self.n..(j + 1) * self.n]
    }

    /// Second-order transfer function of inputs j, m over the moving co-ordinates.
    pub fn x2(&self, j: usize, m: usize) -> &[f64] {
        let p = self.pair[j * self.n_dof + m];
        &self.x2[p * self.n..(p + 1) * self.n]
    }

    /// Value of dependent form parameter d.
    pub fn dep(&self, d: usize) -> f64 {
        self.dep[d]
    }

    /// d eps_d / d input_j (eq. 5.31).
    pub fn dep1(&self, d: usize, j: usize) -> f64 {
        self.dep1[d * self.n_dof + j]
    }

    /// d2 eps_d / d input_j d input_m (eq. 5.32).
    pub fn dep2(&self, d: usize, j: usize, m: usize) -> f64 {
        let n_pairs = self.n_dof * (self.n_dof + 1) / 2;
        self.dep2[d * n_pairs + self.pair[j * self.n_dof + m]]
    }

    /// Value of prescribed row r at the last transfer.
    pub fn row_value(&self, r: usize) -> f64 {
        self.row_values[r]
    }

    /// Velocity of co-ordinate `coord` for input velocities `qd` (eq. 5.29).
    pub fn velocity(&self, mech: &Mechanism, coord: usize, qd: &[f64]) -> f64 {
        (0..self.n_dof).map(|j| self.dx(mech, coord, j) * qd[j]).sum()
    }

    /// Acceleration of co-ordinate `coord` for input velocities `qd` and
    /// accelerations `qdd` (eq. 5.30).
    pub fn acceleration(&self, mech: &Mechanism, coord: usize, qd: &[f64], qdd: &[f64]) -> f64 {
        let mut a = 0.0;
        for j in 0..self.n_dof {
            a += self.dx(mech, coord, j) * qdd[j];
            for m in 0..self.n_dof {
                a += self.d2x(mech, coord, j, m) * qd[j] * qd[m];
            }
        }
        a
    }

    /// Velocity of dependent form parameter d (fig. 5.3.9).
    pub fn dep_velocity(&self, d: usize, qd: &[f64]) -> f64 {
        (0..self.n_dof).map(|j| self.dep1(d, j) * qd[j]).sum()
    }

    /// Acceleration of dependent form parameter d (fig. 5.3.9).
    pub fn dep_acceleration(&self, d: usize, qd: &[f64], qdd: &[f64]) -> f64 {
        let mut a = 0.0;
        for j in 0..self.n_dof {
            a += self.dep1(d, j) * qdd[j];
            for m in 0..self.n_dof {
                a += self.dep2(d, j, m) * qd[j] * qd[m];
            }
        }
        a
    }

    /// The full inverse F^cp = (D^c)^-1 (eq. 5.16a): every first-order
    /// derivative of the moving co-ordinates with respect to every
    /// prescribed form parameter, written column-major into `out`
    /// (`out[k*n + c] = d x_c / d eps_k`). Uses the last factorisation.
    pub fn inverse(&mut self, out: &mut [f64]) -> Result<(), SolveError> {
        let n = self.n;
        self.require(TransferOrder::First)?;
        for k in 0..n {
            let col = &mut out[k * n..(k + 1) * n];
            col.fill(0.0);
            col[k] = 1.0;
            self.lu.solve(col, &mut self.work);
        }
        Ok(())
    }

    /// The full second order F_{c,kl} of eq. 5.28 for every pair of
    /// prescribed form parameters: `out[(k*n + l)*n + c] = d2 x_c / d eps_k d eps_l`.
    /// `f` must hold the inverse from [`Self::inverse`].
    pub fn second_order_all(&mut self, mech: &Mechanism, f: &[f64], out: &mut [f64]) -> Result<(), SolveError> {
        let n = self.n;
        self.require(TransferOrder::Second)?;
        for k in 0..n {
            for l in k..n {
                let (a, b) = (&f[k * n..(k + 1) * n], &f[l * n..(l + 1) * n]);
                for i in 0..n {
                    self.rhs[i] = -hess_product(mech, &mech.prescribed, &self.cache, i, a, b);
                }
                self.lu.solve(&mut self.rhs, &mut self.work);
                out[(k * n + l) * n..(k * n + l + 1) * n].copy_from_slice(&self.rhs);
                out[(l * n + k) * n..(l * n + k + 1) * n].copy_from_slice(&self.rhs);
            }
        }
        Ok(())
    }

    fn require(&self, order: TransferOrder) -> Result<(), SolveError> {
        match self.order {
            Some(o) if o >= order => Ok(()),
            _ => Err(SolveError::NotComputed),
        }
    }

    /// Number of moving co-ordinates.
    pub fn n_moving(&self) -> usize {
        self.n
    }
}
