//! Design sensitivities of inverse dynamics at a position: the derivatives
//! of the stresses, drives, reactions, pin forces, shaking force and
//! moment and energies with respect to the kinematic design variables of a
//! [`Sensitivity`] (prescribed values, fixed co-ordinates) and to the
//! numbers of the mass model ([`MassVar`]), at fixed inputs and input rates.
//!
//! Everything the balance is made of varies: the co-ordinates by s = dx/dp,
//! their velocities and accelerations by what the design sensitivities of
//! the transfer functions give,
//!
//! `dxd = sum_j (ds1_j qd_j + x'_j d(qd_j))`,
//! `dxdd = sum_j ds1_j qdd_j + sum_jm (ds2_jm qd_j qd_m + 2 x''_jm d(qd_j) qd_m)`,
//!
//! and the mass data by their own variation. The body terms vary by the
//! product rule ([`Frame::motion_variation`]); a load Q on a form parameter
//! spreads `Q grad(eps)`, which varies by `dQ grad(eps) + Q H(eps) s`, H the
//! element's second derivative (its closed form, along s, with a unit
//! vector for each of its co-ordinates).
//!
//! The stresses satisfy `(D^c)^T sigma = g^c` with g = f_in - f; its
//! variation is `(D^c)^T d(sigma) = dg^c - h^c`, with `h = (dD)^T sigma`,
//! `h_k = sum_rows sigma_r sum_l H_r,kl s_l` the stress-weighted second
//! derivatives along s; so `d(sigma_r) = F_{.r} . (dg - h)^c` with the
//! columns of `F = (D^c)^-1` the balance itself uses. A reaction
//! `R_i = g_i - (D^T sigma)_i` varies by `dg_i - (D^T d(sigma))_i - h_i`, a
//! pin force's row share `sigma grad` by `d(sigma) grad + sigma H s`.

use super::InverseDynamics;
use crate::dynamics::{Component, LoadKind, MassVar, Variation};
use crate::model::{FormRef, Mechanism, FIXED};
use crate::run::observe::PositionView;
use crate::run::record::Quantity;
use crate::solver::{DesignVar, Sensitivity, TransferOrder};

/// Workspace and results of the design sensitivities of inverse dynamics
/// at one position. The variables are the [`Sensitivity`]'s, in its order,
/// followed by the mass variables.
#[derive(Debug, Clone)]
pub struct DynamicSensitivity {
    mass_vars: Vec<MassVar>,
    n_kin: usize,
    n: usize,
    nc: usize,
    /// Columns of F = (D^c)^-1, column r at `f_cols[r * n..]`.
    f_cols: Vec<f64>,
    s: Vec<f64>,
    dxd: Vec<f64>,
    dxdd: Vec<f64>,
    dvel: Vec<f64>,
    dg: Vec<f64>,
    h: Vec<f64>,
    unit: Vec<f64>,
    /// `H s` of every prescribed term, each at `hs[t * LOCAL..]` (local order).
    hs: Vec<f64>,
    work: Vec<f64>,
    /// Results, variable v at `[v * n..]` etc.
    dsigma: Vec<f64>,
    dreaction: Vec<f64>,
    dekin: Vec<f64>,
    depot: Vec<f64>,
    dpower: Vec<f64>,
    dshake: Vec<f64>,
    /// The mass matrix's, variable v at `[v * nd * nd..]`.
    dmred: Vec<f64>,
    /// d x'_j / dp over every co-ordinate, DOF j at `[j * nc..]`, and zeros.
    ds1: Vec<f64>,
    zeros: Vec<f64>,
    delem: Vec<Vec<(usize, usize, f64)>>,
    computed: bool,
}

const LOCAL: usize = crate::elements::MAX_COORDS;

fn cross(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[1] - a[1] * b[0]
}

impl DynamicSensitivity {
    /// A workspace for `mech`, the kinematic variables of a [`Sensitivity`]
    /// with `n_kin` variables and the mass variables `mass_vars`.
    pub fn new(mech: &Mechanism, n_kin: usize, mass_vars: &[MassVar]) -> DynamicSensitivity {
        let (n, nc, nd) = (mech.n_moving(), mech.n_coords(), mech.n_dof());
        let nv = n_kin + mass_vars.len();
        let nan = |k| vec![f64::NAN; k];
        DynamicSensitivity {
            mass_vars: mass_vars.to_vec(),
            n_kin,
            n,
            nc,
            f_cols: nan(n * n),
            s: vec![0.0; nc],
            dxd: vec![0.0; nc],
            dxdd: vec![0.0; nc],
            dvel: vec![0.0; nd],
            dg: vec![0.0; nc],
            h: vec![0.0; nc],
            unit: vec![0.0; nc],
            hs: vec![0.0; mech.prescribed.terms().len() * LOCAL],
            work: vec![0.0; n],
            dsigma: nan(nv * n),
            dreaction: nan(nv * nc),
            dekin: nan(nv),
            depot: nan(nv),
            dpower: nan(nv),
            dshake: nan(nv * 3),
            dmred: nan(nv * nd * nd),
            ds1: vec![0.0; nd * nc],
            zeros: vec![0.0; nc],
            delem: vec![Vec::new(); nv],
            computed: false,
        }
    }

    /// The number of variables (kinematic and mass).
    pub fn n_vars(&self) -> usize {
        self.n_kin + self.mass_vars.len()
    }

    /// The mass variables.
    pub fn mass_vars(&self) -> &[MassVar] {
        &self.mass_vars
    }

    /// Computes every sensitivity at the position `v`, where `dynamics` was
    /// evaluated and `sens` computed to second order. Returns false (and
    /// every result reads NaN) where either is not known.
    pub fn compute(&mut self, v: &PositionView<'_>, dynamics: &InverseDynamics, sens: &Sensitivity) -> bool {
        self.computed = dynamics.balanced && sens.order() == Some(TransferOrder::Second);
        if !self.computed {
            return false;
        }
        let n = self.n;
        for r in 0..n {
            let col = &mut self.f_cols[r * n..(r + 1) * n];
            col.fill(0.0);
            col[r] = 1.0;
            v.kin.lu.solve(col, &mut self.work);
        }
        for var in 0..self.n_vars() {
            self.variable(v, dynamics, sens, var);
        }
        true
    }

    /// The variation of the co-ordinates, their rates and the input rates
    /// for variable `var` (zero for a mass variable).
    fn kinematic_variation(&mut self, v: &PositionView<'_>, sens: &Sensitivity, var: usize) {
        let (mech, kin, qd, qdd) = (v.mech, v.kin, v.input_vel, v.input_acc);
        let nd = mech.n_dof();
        if var >= self.n_kin {
            for b in [&mut self.s, &mut self.dxd, &mut self.dxdd, &mut self.dvel] {
                b.fill(0.0);
            }
            return;
        }
        for j in 0..nd {
            self.dvel[j] = sens.input_rate(j, var);
        }
        for i in 0..self.nc {
            self.s[i] = sens.dx(i, var);
            let (mut vel, mut acc) = (0.0, 0.0);
            for j in 0..nd {
                let ds1 = sens.dx1(i, j, var);
                vel += ds1 * qd[j] + kin.dx(mech, i, j) * self.dvel[j];
                acc += ds1 * qdd[j];
                for m in 0..nd {
                    acc += sens.dx2(i, j, m, var) * qd[j] * qd[m] + 2.0 * kin.d2x(mech, i, j, m) * self.dvel[j] * qd[m];
                }
            }
            self.dxd[i] = vel;
            self.dxdd[i] = acc;
        }
    }

    /// The variation of a load's form parameter and of its rate.
    fn form_variation(&self, v: &PositionView<'_>, sens: &Sensitivity, var: usize, form: FormRef) -> (f64, f64) {
        if var >= self.n_kin {
            return (0.0, 0.0);
        }
        let (mech, kin, qd) = (v.mech, v.kin, v.input_vel);
        match form {
            FormRef::Prescribed(r) => {
                let own = matches!(sens.vars()[var], DesignVar::Row(rv) if rv == r);
                match mech.input_of(r) {
                    Some(j) => (if own { sens.input_factor(var) } else { 0.0 }, self.dvel[j]),
                    None => (if own { 1.0 } else { 0.0 }, 0.0),
                }
            }
            FormRef::Dependent(d) => {
                let rate =
                    (0..mech.n_dof()).map(|j| sens.dep1(d, j, var) * qd[j] + kin.dep1(d, j) * self.dvel[j]).sum();
                (sens.dep(d, var), rate)
            }
        }
    }

    /// `(H s)_k` of every co-ordinate k of term t of `rows` (local order).
    fn second_along(&mut self, v: &PositionView<'_>, dependent: bool, t: usize, out: &mut [f64; LOCAL]) {
        let (mech, kin) = (v.mech, v.kin);
        let (rows, cache) = if dependent { (&mech.dependent, &kin.dep_cache) } else { (&mech.prescribed, &kin.cache) };
        let (slot, term) = (&rows.slots()[t], &rows.terms()[t]);
        out.fill(0.0);
        if slot.coords[..slot.n].iter().all(|&i| self.s[i] == 0.0) {
            return;
        }
        for k in 0..slot.n {
            self.unit[slot.coords[k]] = 1.0;
            out[k] =
                slot.ty.second_at(term.form, (&slot.coords, &slot.coords), &v.state.x, &cache[t], &self.unit, &self.s);
            self.unit[slot.coords[k]] = 0.0;
        }
    }

    fn variable(&mut self, v: &PositionView<'_>, d: &InverseDynamics, sens: &Sensitivity, var: usize) {
        let (mech, kin, x) = (v.mech, v.kin, &v.state.x[..]);
        let (n, nc, nd) = (self.n, self.nc, mech.n_dof());
        self.kinematic_variation(v, sens, var);
        let mass_var = var.checked_sub(self.n_kin).map(|k| self.mass_vars[k]);
        let grav = d.model.gravity;
        self.dg.fill(0.0);
        let mut delem = std::mem::take(&mut self.delem[var]);
        delem.clear();
        let (mut dekin, mut depot, mut dshake) = (0.0, 0.0, [0.0; 3]);
        for (b_idx, (b, frame)) in d.model.bodies.iter().zip(&d.frames).enumerate() {
            let own = |which: fn(usize) -> MassVar| if mass_var == Some(which(b_idx)) { 1.0 } else { 0.0 };
            let (dm, du, dv, dj) =
                (own(MassVar::Mass), own(MassVar::CentreU), own(MassVar::CentreV), own(MassVar::BodyInertia));
            let var_b = Variation { x: &self.s, xd: &self.dxd, xdd: &self.dxdd, u: du, v: dv };
            let mo = frame.motion(x, &d.xd, &d.xdd, b.u, b.v);
            let dmo = frame.motion_variation(x, &d.xd, &d.xdd, b.u, b.v, &var_b);
            let acc_g = [mo.c_ddot[0] - grav[0], mo.c_ddot[1] - grav[1]];
            let net = [b.mass * acc_g[0], b.mass * acc_g[1]];
            let dnet = [dm * acc_g[0] + b.mass * dmo.c_ddot[0], dm * acc_g[1] + b.mass * dmo.c_ddot[1]];
            let (torque, dtorque) = (b.inertia * mo.beta_ddot, dj * mo.beta_ddot + b.inertia * dmo.beta_ddot);
            for (i, value) in frame.spread_terms_variation(x, b.u, b.v, (net, torque), &var_b, (dnet, dtorque)) {
                if i != usize::MAX {
                    self.dg[i] += value;
                    delem.push((b.element, i, -value));
                }
            }
            let cd = mo.c_dot;
            dekin += 0.5 * dm * (cd[0] * cd[0] + cd[1] * cd[1])
                + b.mass * (cd[0] * dmo.c_dot[0] + cd[1] * dmo.c_dot[1])
                + 0.5 * dj * mo.beta_dot * mo.beta_dot
                + b.inertia * mo.beta_dot * dmo.beta_dot;
            depot -= dm * (grav[0] * mo.c[0] + grav[1] * mo.c[1]) + b.mass * (grav[0] * dmo.c[0] + grav[1] * dmo.c[1]);
            let ma = [b.mass * mo.c_ddot[0], b.mass * mo.c_ddot[1]];
            let dma = [dm * mo.c_ddot[0] + b.mass * dmo.c_ddot[0], dm * mo.c_ddot[1] + b.mass * dmo.c_ddot[1]];
            shake(&mut dshake, (mo.c, dmo.c), (ma, dma), dtorque);
        }
        for (k, p) in d.model.point_masses.iter().enumerate() {
            let dm = if mass_var == Some(MassVar::PointMass(k)) { 1.0 } else { 0.0 };
            let (c, dc) = ([x[p.x], x[p.y]], [self.s[p.x], self.s[p.y]]);
            let (a, da) = ([d.xdd[p.x], d.xdd[p.y]], [self.dxdd[p.x], self.dxdd[p.y]]);
            let (vel, dvel) = ([d.xd[p.x], d.xd[p.y]], [self.dxd[p.x], self.dxd[p.y]]);
            self.dg[p.x] += dm * (a[0] - grav[0]) + p.mass * da[0];
            self.dg[p.y] += dm * (a[1] - grav[1]) + p.mass * da[1];
            dekin += 0.5 * dm * (vel[0] * vel[0] + vel[1] * vel[1]) + p.mass * (vel[0] * dvel[0] + vel[1] * dvel[1]);
            depot -= dm * (grav[0] * c[0] + grav[1] * c[1]) + p.mass * (grav[0] * dc[0] + grav[1] * dc[1]);
            let ma = [p.mass * a[0], p.mass * a[1]];
            let dma = [dm * a[0] + p.mass * da[0], dm * a[1] + p.mass * da[1]];
            shake(&mut dshake, (c, dc), (ma, dma), 0.0);
        }
        for (k, i) in d.model.inertias.iter().enumerate() {
            let dj = if mass_var == Some(MassVar::Inertia(k)) { 1.0 } else { 0.0 };
            let c = i.coord;
            self.dg[c] += dj * d.xdd[c] + i.inertia * self.dxdd[c];
            dekin += 0.5 * dj * d.xd[c] * d.xd[c] + i.inertia * d.xd[c] * self.dxd[c];
            dshake[2] -= dj * d.xdd[c] + i.inertia * self.dxdd[c];
        }
        let mut local = [0.0; LOCAL];
        for l in &d.model.loads {
            let (eps, rate) = InverseDynamics::form_state(mech, kin, l.form, v.input_vel);
            let (deps, drate) = self.form_variation(v, sens, var, l.form);
            let q = l.value(v.time, eps, rate);
            let dq = match l.kind {
                LoadKind::Constant(_) | LoadKind::Table(_) => 0.0,
                LoadKind::Spring { k, c, .. } => -k * deps - c * drate,
                LoadKind::Motor { t0, w0 } => -t0 * drate / w0,
            };
            if let LoadKind::Spring { k, e0, .. } = l.kind {
                depot += k * (eps - e0) * deps;
            }
            let (dependent, row) = match l.form {
                FormRef::Prescribed(r) => (false, r),
                FormRef::Dependent(dd) => (true, dd),
            };
            let range = if dependent { mech.dependent.range(row) } else { mech.prescribed.range(row) };
            for t in range {
                self.second_along(v, dependent, t, &mut local);
                let (rows, cache) =
                    if dependent { (&mech.dependent, &kin.dep_cache) } else { (&mech.prescribed, &kin.cache) };
                let (slot, term) = (&rows.slots()[t], &rows.terms()[t]);
                for k in 0..slot.n {
                    let value = term.factor * (dq * cache[t].grad[k] + q * local[k]);
                    self.dg[slot.coords[k]] -= value;
                    delem.push((term.element, slot.coords[k], value));
                }
            }
        }
        // h = (dD)^T sigma over every co-ordinate.
        self.h.fill(0.0);
        let n_terms = mech.prescribed.terms().len();
        for t in 0..n_terms {
            self.second_along(v, false, t, &mut local);
            self.hs[t * LOCAL..(t + 1) * LOCAL].copy_from_slice(&local);
            let rows = &mech.prescribed;
            let (slot, term) = (&rows.slots()[t], &rows.terms()[t]);
            let sigma = d.sigma[rows.row_of()[t]];
            for k in 0..slot.n {
                self.h[slot.coords[k]] += term.factor * sigma * local[k];
            }
        }
        let moving = mech.moving_coords();
        for r in 0..n {
            let col = &self.f_cols[r * n..(r + 1) * n];
            self.dsigma[var * n + r] = col.iter().zip(moving).map(|(fc, &i)| fc * (self.dg[i] - self.h[i])).sum();
        }
        // Reactions: dg - D^T dsigma - h at the fixed co-ordinates; pins.
        let dreaction = &mut self.dreaction[var * nc..(var + 1) * nc];
        dreaction.copy_from_slice(&self.dg);
        let rows = &mech.prescribed;
        for t in 0..n_terms {
            let (slot, term, row) = (&rows.slots()[t], &rows.terms()[t], rows.row_of()[t]);
            let (sigma, dsigma) = (d.sigma[row], self.dsigma[var * n + row]);
            for k in 0..slot.n {
                let i = slot.coords[k];
                let grad = kin.cache[t].grad[k];
                let value = term.factor * (dsigma * grad + sigma * self.hs[t * LOCAL + k]);
                dreaction[i] -= value;
                delem.push((term.element, i, value));
            }
        }
        for (i, r) in dreaction.iter_mut().enumerate() {
            if mech.column(i) != FIXED {
                *r = f64::NAN;
            }
        }
        self.dpower[var] = (0..nd)
            .map(|j| {
                let row = mech.input_row(j);
                self.dsigma[var * n + row] * v.input_vel[j] + d.sigma[row] * self.dvel[j]
            })
            .sum();
        self.dekin[var] = dekin;
        self.depot[var] = depot;
        self.dshake[var * 3..var * 3 + 3].copy_from_slice(&dshake);
        self.mass_matrix(v, d, sens, var);
        delem.sort_by_key(|t| t.0);
        self.delem[var] = delem;
    }

    /// The variation of the mass matrix `M_jm = sum m c'_j . c'_m + J beta'_j
    /// beta'_m` (and point masses, inertias): each body's velocities along
    /// the transfer functions x'_j vary like velocities, by
    /// [`crate::dynamics::Frame::motion_variation`] with the transfer functions' variations
    /// as the rates'.
    fn mass_matrix(&mut self, v: &PositionView<'_>, d: &InverseDynamics, sens: &Sensitivity, var: usize) {
        let (mech, x) = (v.mech, &v.state.x[..]);
        let (nc, nd) = (self.nc, mech.n_dof());
        let mass_var = var.checked_sub(self.n_kin).map(|k| self.mass_vars[k]);
        for j in 0..nd {
            for i in 0..nc {
                self.ds1[j * nc + i] = if var < self.n_kin { sens.dx1(i, j, var) } else { 0.0 };
            }
        }
        let x1 = |j: usize| &d.x1[j * nc..(j + 1) * nc];
        for j in 0..nd {
            for m in j..nd {
                let mut dm_jm = 0.0;
                let (dj, dmv) = (&self.ds1[j * nc..(j + 1) * nc], &self.ds1[m * nc..(m + 1) * nc]);
                for (b_idx, (b, frame)) in d.model.bodies.iter().zip(&d.frames).enumerate() {
                    let own = |which: fn(usize) -> MassVar| if mass_var == Some(which(b_idx)) { 1.0 } else { 0.0 };
                    let (du, dv) = (own(MassVar::CentreU), own(MassVar::CentreV));
                    let along = |a: &[f64], da: &[f64]| {
                        let var_b = Variation { x: &self.s, xd: da, xdd: &self.zeros, u: du, v: dv };
                        let (c, beta) = frame.velocity(x, a, b.u, b.v);
                        let dmo = frame.motion_variation(x, a, &self.zeros, b.u, b.v, &var_b);
                        (c, beta, dmo.c_dot, dmo.beta_dot)
                    };
                    let (cj, bj, dcj, dbj) = along(x1(j), dj);
                    let (cm, bm, dcm, dbm) = along(x1(m), dmv);
                    let dot = |a: [f64; 2], b: [f64; 2]| a[0] * b[0] + a[1] * b[1];
                    dm_jm += own(MassVar::Mass) * dot(cj, cm)
                        + b.mass * (dot(dcj, cm) + dot(cj, dcm))
                        + own(MassVar::BodyInertia) * bj * bm
                        + b.inertia * (dbj * bm + bj * dbm);
                }
                for (k, p) in d.model.point_masses.iter().enumerate() {
                    let dmass = if mass_var == Some(MassVar::PointMass(k)) { 1.0 } else { 0.0 };
                    let (aj, am) = (x1(j), x1(m));
                    dm_jm += dmass * (aj[p.x] * am[p.x] + aj[p.y] * am[p.y])
                        + p.mass * (dj[p.x] * am[p.x] + aj[p.x] * dmv[p.x] + dj[p.y] * am[p.y] + aj[p.y] * dmv[p.y]);
                }
                for (k, i) in d.model.inertias.iter().enumerate() {
                    let dj_i = if mass_var == Some(MassVar::Inertia(k)) { 1.0 } else { 0.0 };
                    let (aj, am, c) = (x1(j), x1(m), i.coord);
                    dm_jm += dj_i * aj[c] * am[c] + i.inertia * (dj[c] * am[c] + aj[c] * dmv[c]);
                }
                self.dmred[(var * nd + j) * nd + m] = dm_jm;
                self.dmred[(var * nd + m) * nd + j] = dm_jm;
            }
        }
    }

    /// The derivative of a [dynamic](Quantity::is_dynamic) quantity with
    /// respect to variable `var` at the last computed position (NaN where
    /// not computed).
    pub fn quantity(&self, mech: &Mechanism, d: &InverseDynamics, q: Quantity, var: usize) -> f64 {
        if !self.computed || var >= self.n_vars() {
            return f64::NAN;
        }
        let n = self.n;
        match q {
            Quantity::Sigma(r) => self.dsigma[var * n + r],
            Quantity::Drive(j) => match d.motor_drive.get(j) {
                Some(t) if !t.is_nan() => f64::NAN,
                _ => self.dsigma[var * n + mech.input_row(j)],
            },
            Quantity::Reaction(i) => self.dreaction[var * self.nc + i],
            Quantity::Ekin => self.dekin[var],
            Quantity::Epot => self.depot[var],
            Quantity::Power => self.dpower[var],
            Quantity::Shaking(c) => self.dshake[var * 3 + component(c)],
            Quantity::Mred(j, m) => {
                let nd = mech.n_dof();
                self.dmred[(var * nd + j) * nd + m]
            }
            Quantity::Pin { element, x, y, component } => {
                let coord = match component {
                    Component::X => x,
                    Component::Y => y,
                    Component::Moment => return f64::NAN,
                };
                let terms = &self.delem[var];
                let (a, b) = (terms.partition_point(|t| t.0 < element), terms.partition_point(|t| t.0 <= element));
                terms[a..b].iter().filter(|t| t.1 == coord).map(|t| t.2).sum()
            }
            _ => f64::NAN,
        }
    }
}

fn component(c: Component) -> usize {
    match c {
        Component::X => 0,
        Component::Y => 1,
        Component::Moment => 2,
    }
}

/// Adds the variation of a body's share of the shaking force and moment:
/// `F = -m a`, `M = -(c x m a + J alpha)`, with `dtorque` the variation of
/// `J alpha`.
fn shake(out: &mut [f64; 3], (c, dc): ([f64; 2], [f64; 2]), (ma, dma): ([f64; 2], [f64; 2]), dtorque: f64) {
    out[0] -= dma[0];
    out[1] -= dma[1];
    out[2] -= cross(dc, ma) + cross(c, dma) + dtorque;
}
