//! Design sensitivities at a position: the derivatives of the co-ordinates,
//! the dependent form parameters and their transfer functions with respect
//! to a design variable (a prescribed value or a fixed co-ordinate), at
//! fixed inputs.
//!
//! All of them come from the factorisation of D^c the transfer functions
//! were computed with. With s = dx/dp over every co-ordinate (a fixed
//! co-ordinate that is the variable has s = 1, every other 0):
//!
//! * a prescribed value eps_r: D^c s = e_r (column r of F, eq. 5.16a);
//! * a fixed co-ordinate i: D^c s = -D[:, i];
//! * first order (eq. 5.28 with one index the input, one the design):
//!   D^c dx'_j = -D_kl x'_j s;
//! * second order, eq. 5.22 differentiated once more:
//!   D^c dx''_jm = -(D_kl s x''_jm + D_kl dx'_j x'_m + D_kl x'_j dx'_m
//!   + D_klq x'_j x'_m s).
//!
//! The third-order term is the derivative of each element's second
//! derivative along s, taken by a central difference of the element's own
//! closed form (no position is solved again): with a step of about 6e-6 of
//! the element's size its error is near 1e-10 of the term, far below what
//! the solve adds. Everything else is exact. Dependent form parameters
//! follow by the chain rule (eqs. 5.31, 5.32 differentiated).

use super::assemble::{grad_dot, second_products};
use super::transfer::{pairs, Kinematics, TransferOrder};
use crate::elements::{FormEval, Order};
use crate::error::SolveError;
use crate::model::{Mechanism, Over, Rows, State};

/// A design variable: a number of the model that a designer may change.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum DesignVar {
    /// The prescribed value of prescribed row r (0-based): a length, a local
    /// u or v, a fixed angle, a gear ratio, or an input's start value.
    Row(usize),
    /// The value of fixed co-ordinate i (0-based), e.g. a frame pivot.
    Fixed(usize),
}

/// Why a list of design variables (or a change of a model's numbers) does
/// not fit a model. The indices are 0-based; the words number them as the
/// deck does, 1-based (an index of `usize::MAX` is said as number 0).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum DesignError {
    /// A row index past the prescribed rows.
    #[error("the deck has no prescribed row {}", .0.wrapping_add(1))]
    NoRow(usize),
    /// A co-ordinate index past the co-ordinates.
    #[error("the deck has no co-ordinate {}", .0.wrapping_add(1))]
    NoCoordinate(usize),
    /// A co-ordinate that moves: its value is found, not chosen.
    #[error(
        "co-ordinate {} moves (XMOV): only a fixed co-ordinate is a design variable; vary the row that prescribes it \
         instead",
        .0 + 1
    )]
    Moving(usize),
}

/// Workspace and results of the design sensitivities at one position; every
/// buffer is allocated once, in [`Sensitivity::new`].
#[derive(Debug, Clone)]
pub struct Sensitivity {
    vars: Vec<DesignVar>,
    n_coords: usize,
    n_dof: usize,
    n_pairs: usize,
    n_dep: usize,
    pair: Vec<usize>,
    /// dx/dp over every co-ordinate, variable v at `s[v*N..]`.
    s: Vec<f64>,
    /// d x'_j / dp, at `s1[(v*n_dof + j)*N..]`.
    s1: Vec<f64>,
    /// d x''_jm / dp for pair p, at `s2[(v*n_pairs + p)*N..]`.
    s2: Vec<f64>,
    /// Dependent form parameters: d eps_d / dp at `e[v*n_dep + d]`, and
    /// their first- and second-order transfer functions likewise.
    e: Vec<f64>,
    e1: Vec<f64>,
    e2: Vec<f64>,
    /// The factor each variable's results were scaled with, and the change
    /// of each input's velocity per unit of the variable (see
    /// [`Sensitivity::scale_input`]).
    rate: Vec<f64>,
    factor: Vec<f64>,
    // Scratch.
    x1: Vec<f64>,
    x2: Vec<f64>,
    col: Vec<f64>,
    work: Vec<f64>,
    prod: Vec<f64>,
    dep_prod: Vec<f64>,
    probe: Vec<f64>,
    order: Option<TransferOrder>,
}

impl Sensitivity {
    /// A workspace for the variables `vars` of `mech`.
    pub fn new(mech: &Mechanism, vars: &[DesignVar]) -> Result<Sensitivity, DesignError> {
        for &v in vars {
            match v {
                DesignVar::Row(r) if r >= mech.n_prescribed() => return Err(DesignError::NoRow(r)),
                DesignVar::Fixed(i) if i >= mech.n_coords() => return Err(DesignError::NoCoordinate(i)),
                DesignVar::Fixed(i) if mech.is_moving(i) => return Err(DesignError::Moving(i)),
                _ => {}
            }
        }
        let (nv, n, nc, nd, ndep) = (vars.len(), mech.n_moving(), mech.n_coords(), mech.n_dof(), mech.n_dependent());
        let np = nd * (nd + 1) / 2;
        Ok(Sensitivity {
            vars: vars.to_vec(),
            n_coords: nc,
            n_dof: nd,
            n_pairs: np,
            n_dep: ndep,
            pair: pairs(nd),
            s: vec![f64::NAN; nv * nc],
            s1: vec![f64::NAN; nv * nd * nc],
            s2: vec![f64::NAN; nv * np * nc],
            e: vec![f64::NAN; nv * ndep],
            e1: vec![f64::NAN; nv * ndep * nd],
            e2: vec![f64::NAN; nv * ndep * np],
            rate: vec![0.0; nv * nd],
            factor: vec![1.0; nv],
            x1: vec![0.0; nd * nc],
            x2: vec![0.0; np * nc],
            col: vec![0.0; n],
            work: vec![0.0; 2 * n],
            prod: vec![0.0; n.max(1)],
            dep_prod: vec![0.0; ndep.max(1)],
            probe: vec![0.0; nc],
            order: None,
        })
    }

    /// The design variables.
    pub fn vars(&self) -> &[DesignVar] {
        &self.vars
    }

    /// Computes every sensitivity at the position of the last transfer of
    /// `kin` (which `state` must still hold), to the order of that transfer
    /// or `order`, whichever is lower.
    pub fn compute(
        &mut self,
        mech: &Mechanism,
        kin: &Kinematics,
        state: &State,
        order: TransferOrder,
    ) -> Result<(), SolveError> {
        self.order = None;
        let order = match kin.order() {
            Some(o) => o.min(order),
            None => return Err(SolveError::NotComputed),
        };
        let (nc, nd, np) = (self.n_coords, self.n_dof, self.n_pairs);
        self.rate.fill(0.0);
        self.factor.fill(1.0);
        // The transfer functions over every co-ordinate (fixed ones are 0).
        self.x1.fill(0.0);
        self.x2.fill(0.0);
        for (c, &i) in mech.moving_coords().iter().enumerate() {
            for j in 0..nd {
                self.x1[j * nc + i] = kin.x1(j)[c];
            }
            if order == TransferOrder::Second {
                for j in 0..nd {
                    for m in j..nd {
                        self.x2[self.pair[j * nd + m] * nc + i] = kin.x2(j, m)[c];
                    }
                }
            }
        }
        let x = &state.x;
        for v in 0..self.vars.len() {
            // s = dx/dp.
            self.col.fill(0.0);
            match self.vars[v] {
                DesignVar::Row(r) => self.col[r] = 1.0,
                DesignVar::Fixed(i) => {
                    column_of_fixed(&mech.prescribed, &kin.cache, i, &mut self.col);
                    self.col.iter_mut().for_each(|c| *c = -*c);
                }
            }
            kin.lu.solve(&mut self.col, &mut self.work);
            let s = &mut self.s[v * nc..(v + 1) * nc];
            scatter(mech, &self.col, s);
            if let DesignVar::Fixed(i) = self.vars[v] {
                s[i] = 1.0;
            }
            // d x'_j / dp.
            for j in 0..nd {
                let (s, a) = (&self.s[v * nc..(v + 1) * nc], &self.x1[j * nc..(j + 1) * nc]);
                second_products(&mech.prescribed, x, &kin.cache, (a, s), Over::Coordinates, &mut self.prod);
                self.col.iter_mut().zip(&self.prod).for_each(|(c, p)| *c = -p);
                kin.lu.solve(&mut self.col, &mut self.work);
                let k = (v * nd + j) * nc;
                scatter(mech, &self.col, &mut self.s1[k..k + nc]);
            }
            if order == TransferOrder::Second {
                for j in 0..nd {
                    for m in j..nd {
                        let p = self.pair[j * nd + m];
                        self.second(mech, kin, state, v, j, m);
                        let k = (v * np + p) * nc;
                        scatter(mech, &self.col, &mut self.s2[k..k + nc]);
                    }
                }
            }
            self.dependents(mech, kin, state, v, order);
        }
        let finite = |a: &[f64]| a.iter().all(|v| v.is_finite());
        let second_ok = order == TransferOrder::First || (finite(&self.s2) && finite(&self.e2));
        if !(finite(&self.s) && finite(&self.s1) && finite(&self.e) && finite(&self.e1) && second_ok) {
            return Err(SolveError::NonFinite);
        }
        self.order = Some(order);
        Ok(())
    }

    /// The right-hand side of d x''_jm / dp for variable v, solved into `col`.
    fn second(&mut self, mech: &Mechanism, kin: &Kinematics, state: &State, v: usize, j: usize, m: usize) {
        let (nc, nd) = (self.n_coords, self.n_dof);
        let x = &state.x;
        let p = self.pair[j * nd + m];
        let s = &self.s[v * nc..(v + 1) * nc];
        let (a, b) = (&self.x1[j * nc..(j + 1) * nc], &self.x1[m * nc..(m + 1) * nc]);
        let (da, db) = (&self.s1[(v * nd + j) * nc..][..nc], &self.s1[(v * nd + m) * nc..][..nc]);
        let x2 = &self.x2[p * nc..(p + 1) * nc];
        let rows = &mech.prescribed;
        let acc = |u: &[f64], w: &[f64], col: &mut [f64], prod: &mut [f64]| {
            second_products(rows, x, &kin.cache, (u, w), Over::Coordinates, prod);
            col.iter_mut().zip(prod.iter()).for_each(|(c, p)| *c -= p);
        };
        self.col.fill(0.0);
        acc(s, x2, &mut self.col, &mut self.prod);
        acc(da, b, &mut self.col, &mut self.prod);
        acc(a, db, &mut self.col, &mut self.prod);
        third_products(rows, x, &state.branch, &mut self.probe, s, a, b, &mut self.prod);
        self.col.iter_mut().zip(&self.prod).for_each(|(c, p)| *c -= p);
        kin.lu.solve(&mut self.col, &mut self.work);
    }

    /// The dependent form parameters' sensitivities for variable v.
    fn dependents(&mut self, mech: &Mechanism, kin: &Kinematics, state: &State, v: usize, order: TransferOrder) {
        let (nc, nd, np, ndep) = (self.n_coords, self.n_dof, self.n_pairs, self.n_dep);
        if ndep == 0 {
            return;
        }
        let rows = &mech.dependent;
        let (cache, x) = (&kin.dep_cache, &state.x);
        let s = &self.s[v * nc..(v + 1) * nc];
        for d in 0..ndep {
            self.e[v * ndep + d] = grad_dot(rows, cache, d, s, Over::Coordinates);
        }
        for j in 0..nd {
            let a = &self.x1[j * nc..(j + 1) * nc];
            let da = &self.s1[(v * nd + j) * nc..][..nc];
            second_products(rows, x, cache, (a, s), Over::Coordinates, &mut self.dep_prod);
            for d in 0..ndep {
                self.e1[(v * ndep + d) * nd + j] = grad_dot(rows, cache, d, da, Over::Coordinates) + self.dep_prod[d];
            }
        }
        if order < TransferOrder::Second {
            return;
        }
        for j in 0..nd {
            for m in j..nd {
                let p = self.pair[j * nd + m];
                let (a, b) = (&self.x1[j * nc..(j + 1) * nc], &self.x1[m * nc..(m + 1) * nc]);
                let (da, db) = (&self.s1[(v * nd + j) * nc..][..nc], &self.s1[(v * nd + m) * nc..][..nc]);
                let (x2, ds2) = (&self.x2[p * nc..(p + 1) * nc], &self.s2[(v * np + p) * nc..][..nc]);
                for d in 0..ndep {
                    self.e2[(v * ndep + d) * np + p] = grad_dot(rows, cache, d, ds2, Over::Coordinates);
                }
                for (u, w) in [(s, x2), (da, b), (a, db)] {
                    second_products(rows, x, cache, (u, w), Over::Coordinates, &mut self.dep_prod);
                    for d in 0..ndep {
                        self.e2[(v * ndep + d) * np + p] += self.dep_prod[d];
                    }
                }
                third_products(rows, x, &state.branch, &mut self.probe, s, a, b, &mut self.dep_prod);
                for d in 0..ndep {
                    self.e2[(v * ndep + d) * np + p] += self.dep_prod[d];
                }
            }
        }
    }

    /// Scales variable v's results by `factor` and records that input j's
    /// velocity changes by `velocity_rate` per unit of it: for an input's
    /// start value, whose change moves the input at a position by less than
    /// itself when the motion ends at a fixed value (MOV_ABSE), and not at
    /// all under a motion table.
    pub fn scale_input(&mut self, v: usize, j: usize, factor: f64, velocity_rate: f64) {
        let (nc, nd, np, ndep) = (self.n_coords, self.n_dof, self.n_pairs, self.n_dep);
        let scale = |a: &mut [f64]| a.iter_mut().for_each(|x| *x *= factor);
        scale(&mut self.s[v * nc..(v + 1) * nc]);
        scale(&mut self.s1[v * nd * nc..(v + 1) * nd * nc]);
        scale(&mut self.s2[v * np * nc..(v + 1) * np * nc]);
        scale(&mut self.e[v * ndep..(v + 1) * ndep]);
        scale(&mut self.e1[v * ndep * nd..(v + 1) * ndep * nd]);
        scale(&mut self.e2[v * ndep * np..(v + 1) * ndep * np]);
        self.rate[v * nd + j] = velocity_rate;
        self.factor[v] = factor;
    }

    /// The factor [`Self::scale_input`] gave variable v at this position (1
    /// otherwise): how far a unit of it moves its input here.
    pub fn input_factor(&self, v: usize) -> f64 {
        self.factor[v]
    }

    /// What the last successful [`Self::compute`] computed.
    pub fn order(&self) -> Option<TransferOrder> {
        self.order
    }

    /// d x_i / dp of co-ordinate i for variable v.
    pub fn dx(&self, i: usize, v: usize) -> f64 {
        self.s[v * self.n_coords + i]
    }

    /// d (d x_i / d input_j) / dp.
    pub fn dx1(&self, i: usize, j: usize, v: usize) -> f64 {
        self.s1[(v * self.n_dof + j) * self.n_coords + i]
    }

    /// d (d2 x_i / d input_j d input_m) / dp.
    pub fn dx2(&self, i: usize, j: usize, m: usize, v: usize) -> f64 {
        self.s2[(v * self.n_pairs + self.pair[j * self.n_dof + m]) * self.n_coords + i]
    }

    /// d eps_d / dp of dependent form parameter d.
    pub fn dep(&self, d: usize, v: usize) -> f64 {
        self.e[v * self.n_dep + d]
    }

    /// d (d eps_d / d input_j) / dp.
    pub fn dep1(&self, d: usize, j: usize, v: usize) -> f64 {
        self.e1[(v * self.n_dep + d) * self.n_dof + j]
    }

    /// d (d2 eps_d / d input_j d input_m) / dp.
    pub fn dep2(&self, d: usize, j: usize, m: usize, v: usize) -> f64 {
        self.e2[(v * self.n_dep + d) * self.n_pairs + self.pair[j * self.n_dof + m]]
    }

    /// d (velocity of input j) / dp (see [`Self::scale_input`]).
    pub fn input_rate(&self, j: usize, v: usize) -> f64 {
        self.rate[v * self.n_dof + j]
    }
}

/// A vector over the columns of D^c written over every co-ordinate (fixed
/// ones 0).
fn scatter(mech: &Mechanism, col: &[f64], out: &mut [f64]) {
    out.fill(0.0);
    for (c, &i) in mech.moving_coords().iter().enumerate() {
        out[i] = col[c];
    }
}

/// Column i of D (the prescribed rows' derivatives with respect to
/// co-ordinate i, fixed or not) from a cache evaluated to first order.
fn column_of_fixed(rows: &Rows, cache: &[FormEval], i: usize, out: &mut [f64]) {
    for ((t, s), (e, &row)) in rows.terms().iter().zip(rows.slots()).zip(cache.iter().zip(rows.row_of())) {
        for a in 0..s.n {
            if s.coords[a] == i {
                out[row] += t.factor * e.grad[a];
            }
        }
    }
}

/// `sum_klq D_{row,klq} a_k b_l s_q` for every row: each element's second
/// derivative along (a, b), differentiated along s by a central difference
/// of its closed form. Elements that s does not move contribute nothing.
#[allow(clippy::too_many_arguments)]
fn third_products(
    rows: &Rows,
    x: &[f64],
    branch: &[f64],
    probe: &mut [f64],
    s: &[f64],
    a: &[f64],
    b: &[f64],
    out: &mut [f64],
) {
    out[..rows.len()].fill(0.0);
    let mut first = FormEval::default();
    for ((t, slot), &row) in rows.terms().iter().zip(rows.slots()).zip(rows.row_of()) {
        let coords = &slot.coords[..slot.n];
        let s_max = coords.iter().fold(0.0f64, |m, &i| m.max(s[i].abs()));
        if s_max == 0.0 {
            continue;
        }
        let size = coords.iter().fold(1.0f64, |m, &i| m.max(x[i].abs()));
        let h = 6e-6 * size / s_max;
        let mut at = |sign: f64| -> f64 {
            for &i in coords {
                probe[i] = x[i] + sign * h * s[i];
            }
            let mut memory = branch[t.element];
            match slot.ty.eval_at(t.form, &slot.coords, probe, &mut memory, Order::First, &mut first) {
                Ok(()) => slot.ty.second_at(t.form, (&slot.coords, &slot.coords), probe, &first, a, b),
                Err(_) => f64::NAN,
            }
        };
        let d = (at(1.0) - at(-1.0)) / (2.0 * h);
        out[row] += t.factor * d;
    }
}
