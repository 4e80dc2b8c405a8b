//! Transfer functions at a position: first order (eq. 5.16a), second order
//! for every pair of inputs (eq. 5.22), the full second order on request
//! (eq. 5.28), dependent form parameters (eqs. 5.31, 5.32), det(D^c), and
//! timed velocities and accelerations (eqs. 5.29, 5.30).
//!
//! [`Kinematics`] is also the workspace of the Newton iteration: every
//! buffer is allocated once, in [`Kinematics::new`].

use super::assemble::{eval_rows, fill_dc, grad_dot, second_products};
use super::lu::Lu;
use super::plan::DcPlan;
use crate::elements::{FormEval, Order, MAX_COORDS};
use crate::error::SolveError;
use crate::model::{Mechanism, Over, State, FIXED};

/// How far [`Kinematics::transfer`] goes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum TransferOrder {
    /// det(D^c) and first-order transfer functions.
    First,
    /// Also second-order transfer functions of every pair of inputs.
    Second,
}

/// The number of every pair of inputs (j, m), j <= m, in order, at
/// `[j * n_dof + m]` and `[m * n_dof + j]`: where the second-order transfer
/// function of the pair is kept.
pub(crate) fn pairs(n_dof: usize) -> Vec<usize> {
    let mut pair = vec![0; n_dof * n_dof];
    let mut p = 0;
    for j in 0..n_dof {
        for m in j..n_dof {
            pair[j * n_dof + m] = p;
            pair[m * n_dof + j] = p;
            p += 1;
        }
    }
    pair
}

/// Workspace and results of the analysis at one position.
#[derive(Debug, Clone)]
pub struct Kinematics {
    n: usize,
    n_dof: usize,
    pub(crate) lu: Lu,
    /// Whether `lu` holds the factors of D^c (no row replaced) at the
    /// current or a recent position.
    pub(crate) factored: bool,
    /// How much the last chord step of a Newton correction shrank the
    /// largest deformation.
    pub(crate) chord_rate: f64,
    /// Where each prescribed term's gradient goes in `lu`.
    dc_pos: Vec<[usize; MAX_COORDS]>,
    /// Whether assembly writes every place of `lu` once (no clearing).
    overwrite: bool,
    pub(crate) work: Vec<f64>,
    pub(crate) rhs: Vec<f64>,
    pub(crate) cache: Vec<FormEval>,
    /// How far the last evaluation of the prescribed rows into `cache` went.
    evaluated: Order,
    pub(crate) dep_cache: Vec<FormEval>,
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
    /// The dependent rows' second-order products of one pair of inputs.
    dep_second: Vec<f64>,
    order: Option<TransferOrder>,
    /// See [`Kinematics::transfer_sums`].
    sums: (f64, f64),
    /// The co-ordinates of the last second-order transfer.
    x_second: Vec<f64>,
    /// Angle memory for evaluations away from the state.
    branch_scratch: Vec<f64>,
    /// Whether `x1, dep1` (`x2, dep2`) hold NaN rather than stale values.
    first_cleared: bool,
    second_cleared: bool,
}

impl Kinematics {
    /// Allocates every buffer for `mech`. D^c is stored as blocks when it
    /// splits into groups of co-ordinates that can be solved one after the
    /// other, a large block as a band when it can be ordered into a narrow
    /// one, anything else dense; that choice is made once for every
    /// structure of D^c on a thread, and the workspaces of mechanisms of
    /// that structure start from it.
    pub fn new(mech: &Mechanism) -> Kinematics {
        Self::with_plan(mech, DcPlan::of(mech))
    }

    /// As [`Self::new`], with D^c always stored dense: free motion replaces
    /// a row of D^c by a unit row anywhere, which a band may not hold.
    pub(crate) fn dense(mech: &Mechanism) -> Kinematics {
        Self::with_plan(mech, DcPlan::for_lu(mech, Lu::new(mech.n_moving())))
    }

    fn with_plan(mech: &Mechanism, plan: DcPlan) -> Kinematics {
        let DcPlan { lu, dc_pos, overwrite } = plan;
        let n = mech.n_moving();
        let n_dof = mech.n_dof();
        let n_pairs = n_dof * (n_dof + 1) / 2;
        let pair = pairs(n_dof);
        let n_d = mech.n_dependent();
        Kinematics {
            n,
            n_dof,
            dc_pos,
            overwrite,
            lu,
            factored: false,
            chord_rate: 0.05,
            // Two right-hand sides at once need twice n (`Lu::solve_two`).
            work: vec![0.0; 2 * n],
            rhs: vec![0.0; n],
            cache: vec![FormEval::default(); mech.prescribed.terms().len()],
            evaluated: Order::Value,
            dep_cache: vec![FormEval::default(); mech.dependent.terms().len()],
            row_values: vec![0.0; n],
            det: f64::NAN,
            x1: vec![f64::NAN; n * n_dof],
            x2: vec![f64::NAN; n * n_pairs],
            pair,
            dep: vec![0.0; n_d],
            dep1: vec![f64::NAN; n_d * n_dof],
            dep2: vec![f64::NAN; n_d * n_pairs],
            dep_second: vec![0.0; n_d],
            order: None,
            sums: (0.0, 0.0),
            x_second: vec![f64::NAN; mech.n_coords()],
            branch_scratch: vec![f64::NAN; mech.elements().len()],
            first_cleared: true,
            second_cleared: true,
        }
    }

    /// Whether D^c, or one of its diagonal blocks, is stored as a band
    /// (see [`Self::new`]).
    pub fn is_banded(&self) -> bool {
        self.lu.is_banded()
    }

    /// The sizes of the diagonal blocks D^c is factorised in, in the order
    /// they are solved (one block of every moving co-ordinate when it does
    /// not split; see [`Self::new`]).
    pub fn block_sizes(&self) -> Vec<usize> {
        self.lu.block_sizes()
    }

    /// Evaluates the prescribed rows to first order at the state's
    /// co-ordinates, into the cache and the row values.
    pub(crate) fn evaluate(&mut self, mech: &Mechanism, state: &mut State) -> Result<(), SolveError> {
        self.evaluate_to(mech, state, Order::First)
    }

    /// Evaluates the prescribed rows to `order` (values only: no D^c).
    pub(crate) fn evaluate_to(&mut self, mech: &Mechanism, state: &mut State, order: Order) -> Result<(), SolveError> {
        // Until it has succeeded, the cache holds nothing to build on.
        self.evaluated = Order::Value;
        eval_rows(&mech.prescribed, &state.x, &mut state.branch, order, &mut self.cache, &mut self.row_values)?;
        self.evaluated = order;
        Ok(())
    }

    /// Assembles and factorises D^c at the state's co-ordinates, which must
    /// be the point evaluated last (as a Newton correction leaves it): that
    /// evaluation is reused when it went to first order, and repeated to
    /// first order otherwise.
    pub(crate) fn factor_here(&mut self, mech: &Mechanism, state: &mut State) -> Result<(), SolveError> {
        if self.evaluated < Order::First {
            self.evaluate(mech, state)?;
        }
        self.assemble(mech);
        self.factor()
    }

    /// Writes D^c from the cache into the factorisation's storage.
    pub(crate) fn assemble(&mut self, mech: &Mechanism) {
        self.factored = false;
        fill_dc(mech, &self.cache, &self.dc_pos, self.overwrite, &mut self.lu);
    }

    /// Factorises the assembled D^c.
    pub(crate) fn factor(&mut self) -> Result<(), SolveError> {
        self.lu.factor().map_err(|s| SolveError::Singular { column: s.column, pivot: s.pivot })?;
        self.factored = true;
        Ok(())
    }

    /// Factorises the assembled D^c with row `row` replaced by the unit row
    /// e_col (a temporary input, section 5.5.3); `factored` stays false,
    /// as these are not the factors of D^c.
    pub(crate) fn factor_with_unit_row(&mut self, row: usize, col: usize) -> Result<(), SolveError> {
        self.lu.set_unit_row(row, col);
        self.lu.factor().map_err(|s| SolveError::Singular { column: s.column, pivot: s.pivot })
    }

    /// Solves `b` in place with the last factorisation: of D^c, or of D^c
    /// with a row replaced by a unit row.
    pub(crate) fn solve(&mut self, b: &mut [f64]) {
        self.lu.solve(b, &mut self.work);
    }

    /// The gradient of prescribed row `row`, as evaluated last, times `a`,
    /// a vector over the columns of D^c.
    pub(crate) fn row_dot(&self, mech: &Mechanism, row: usize, a: &[f64]) -> f64 {
        grad_dot(&mech.prescribed, &self.cache, row, a, Over::Columns)
    }

    /// Computes det(D^c), the transfer functions of the moving co-ordinates
    /// and of the dependent form parameters at the state's co-ordinates,
    /// with one factorisation of D^c.
    pub fn transfer(&mut self, mech: &Mechanism, state: &mut State, order: TransferOrder) -> Result<(), SolveError> {
        self.order = None;
        self.evaluate(mech, state)?;
        self.finish(mech, state, Some(order), None)
    }

    /// The analysis at a position whose prescribed rows are already in the
    /// cache (as a converged Newton correction leaves them): with `None`,
    /// only the values of the dependent form parameters (positions only:
    /// no det(D^c), no transfer functions); otherwise as [`Self::transfer`].
    ///
    /// With an order, `extra` (if any) is solved with D^c's new
    /// factorisation, together with the first column of x' (one pass for
    /// both); it is solved exactly when `self.factored` is true afterwards.
    pub(crate) fn finish(
        &mut self,
        mech: &Mechanism,
        state: &mut State,
        order: Option<TransferOrder>,
        mut extra: Option<&mut [f64]>,
    ) -> Result<(), SolveError> {
        self.order = None;
        let Some(order) = order else {
            self.det = f64::NAN;
            self.clear_from(TransferOrder::First);
            return self.dependents(mech, state, None);
        };
        let n = self.n;
        self.assemble(mech);
        if let Err(e) = self.factor() {
            // A limit position: no transfer functions, but the values of the
            // dependent form parameters are still known.
            self.det = 0.0;
            self.clear_from(TransferOrder::First);
            self.dependents(mech, state, None)?;
            return Err(e);
        }
        self.det = self.lu.det();
        // eq. 5.16a: column j of F^cm is (D^c)^-1 e_{input row j}.
        for j in 0..self.n_dof {
            let col = &mut self.x1[j * n..(j + 1) * n];
            col.fill(0.0);
            col[mech.input_row(j)] = 1.0;
            match extra.take() {
                Some(e) => self.lu.solve_two(col, e, &mut self.work),
                None => self.lu.solve(col, &mut self.work),
            }
        }
        if let Some(e) = extra {
            self.lu.solve(e, &mut self.work);
        }
        self.first_cleared = false;
        if order == TransferOrder::Second {
            // eq. 5.22, for every pair (j, m): D^c x''_jm = -D_kl x'_j,k x'_m,l.
            for j in 0..self.n_dof {
                for m in j..self.n_dof {
                    let p = self.pair[j * self.n_dof + m];
                    let (a, b) = (&self.x1[j * n..(j + 1) * n], &self.x1[m * n..(m + 1) * n]);
                    // Solved in its place in x2, not copied there.
                    let x2 = &mut self.x2[p * n..(p + 1) * n];
                    second_products(&mech.prescribed, &state.x, &self.cache, (a, b), Over::Columns, x2);
                    for r in x2.iter_mut() {
                        *r = -*r;
                    }
                    self.lu.solve(x2, &mut self.work);
                }
            }
            self.second_cleared = false;
            self.x_second.copy_from_slice(&state.x);
        } else {
            self.clear_from(TransferOrder::Second);
        }
        self.dependents(mech, state, Some(order))?;
        let (x2, dep2) =
            if order == TransferOrder::Second { (&self.x2[..], &self.dep2[..]) } else { (&[][..], &[][..]) };
        // det(D^c) overflows where D^c's entries are huge although its
        // inverse is not; the limit positions are found from it, so it must
        // be a number too.
        // The sums of magnitudes are infinite or NaN exactly when a transfer
        // function is not finite, and bound every velocity and acceleration
        // made from them (see `transfer_sums`).
        let abs_sum = |v: &[f64]| v.iter().map(|x| x.abs()).sum::<f64>();
        let (s1, s2) = (abs_sum(&self.x1) + abs_sum(&self.dep1), abs_sum(x2) + abs_sum(dep2));
        if !(self.det.is_finite() && s1.is_finite() && s2.is_finite()) {
            return Err(SolveError::NonFinite);
        }
        self.sums = (s1, s2);
        self.order = Some(order);
        Ok(())
    }

    /// Sets the transfer functions of `order` and above to NaN, so that
    /// none that was not computed at this position can be read as if it had.
    fn clear_from(&mut self, order: TransferOrder) {
        if order == TransferOrder::First && !self.first_cleared {
            self.x1.fill(f64::NAN);
            self.dep1.fill(f64::NAN);
            self.first_cleared = true;
        }
        if !self.second_cleared {
            self.x2.fill(f64::NAN);
            self.dep2.fill(f64::NAN);
            self.second_cleared = true;
        }
    }

    /// eqs. 5.31, 5.32: value, first and second order of every dependent
    /// form parameter, as far as `order` goes.
    fn dependents(
        &mut self,
        mech: &Mechanism,
        state: &mut State,
        order: Option<TransferOrder>,
    ) -> Result<(), SolveError> {
        let (n, nd) = (self.n, self.n_dof);
        let rows = &mech.dependent;
        if rows.len() == 0 {
            return Ok(());
        }
        let eval_order = if order.is_some() { Order::First } else { Order::Value };
        eval_rows(rows, &state.x, &mut state.branch, eval_order, &mut self.dep_cache, &mut self.dep)?;
        let Some(order) = order else { return Ok(()) };
        let n_pairs = nd * (nd + 1) / 2;
        for d in 0..rows.len() {
            for j in 0..nd {
                self.dep1[d * nd + j] = grad_dot(rows, &self.dep_cache, d, &self.x1[j * n..(j + 1) * n], Over::Columns);
            }
        }
        if order == TransferOrder::Second {
            for j in 0..nd {
                for m in j..nd {
                    let p = self.pair[j * nd + m];
                    let (a, b) = (&self.x1[j * n..(j + 1) * n], &self.x1[m * n..(m + 1) * n]);
                    second_products(rows, &state.x, &self.dep_cache, (a, b), Over::Columns, &mut self.dep_second);
                    for d in 0..rows.len() {
                        self.dep2[d * n_pairs + p] =
                            grad_dot(rows, &self.dep_cache, d, &self.x2[p * n..(p + 1) * n], Over::Columns)
                                + self.dep_second[d];
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

    /// The sums of the magnitudes of the first-order transfer functions (of
    /// the moving co-ordinates and the dependent form parameters) and of the
    /// second-order ones (0 when they were not computed), as of the last
    /// transfer: every velocity is at most s1 v and every acceleration at
    /// most s1 a + s2 v^2, v and a the largest input velocity and
    /// acceleration.
    pub fn transfer_sums(&self) -> (f64, f64) {
        self.sums
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

    /// The values of every prescribed row at the last transfer.
    pub fn row_values(&self) -> &[f64] {
        &self.row_values
    }

    /// The values of every dependent form parameter.
    pub fn dependent_values(&self) -> &[f64] {
        &self.dep
    }

    /// The first-order transfer functions of every input over the moving
    /// co-ordinates, input after input ([`Self::x1`] of each).
    pub fn first_order(&self) -> &[f64] {
        &self.x1
    }

    /// d eps_d / d input_j of every dependent row, at `d * n_dof + j`.
    pub fn dependent_first(&self) -> &[f64] {
        &self.dep1
    }

    /// d2 eps_d / d input_j d input_m of every dependent row, the pairs
    /// j <= m of each row after one another (with one input, one a row).
    pub fn dependent_second(&self) -> &[f64] {
        &self.dep2
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
        // The prescribed rows at the position of the last second-order
        // transfer, which need not be the state's.
        self.evaluated = Order::Value;
        self.branch_scratch.fill(f64::NAN);
        eval_rows(
            &mech.prescribed,
            &self.x_second,
            &mut self.branch_scratch,
            Order::First,
            &mut self.cache,
            &mut self.work,
        )?;
        for k in 0..n {
            for l in k..n {
                let (a, b) = (&f[k * n..(k + 1) * n], &f[l * n..(l + 1) * n]);
                second_products(&mech.prescribed, &self.x_second, &self.cache, (a, b), Over::Columns, &mut self.rhs);
                for r in self.rhs.iter_mut() {
                    *r = -*r;
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
