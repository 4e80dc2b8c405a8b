//! Inverse dynamics at a position: what the drives, the rows and the frame
//! must deliver so that the mechanism makes its prescribed motion.
//!
//! In the space of all co-ordinates, f holds the applied forces (gravity,
//! point forces, loads, springs, dampers, motors) and f_in the inertia
//! forces (mass times acceleration), both as generalised forces: the
//! coefficients of their virtual work. The prescribed rows hold the
//! mechanism together with their stresses sigma (the generalised force each
//! row's constraint applies in the direction of increasing eps_r), so
//! virtual work over the moving co-ordinates gives
//! `(D^c)^T sigma = f_in^c - f^c`: `sigma = F^T (f_in^c - f^c)` with
//! `F = (D^c)^-1`. Column r of F is `(D^c)^-1 e_r`, one solve with the
//! factorisation the position already has, so
//! `sigma_r = F_{.r} . (f_in^c - f^c)`.
//!
//! The frame holds each fixed co-ordinate i with the reaction
//! `R_i = f_in_i - f_i - (D^T sigma)_i`: the force the frame applies to the
//! mechanism there, balancing the rows' forces and the loads that act on it
//! directly.

mod sensitivity;

pub use sensitivity::DynamicSensitivity;

use super::observe::PositionView;
use crate::dynamics::{Dynamics, Frame, LoadKind};
use crate::error::SolveError;
use crate::model::{FormRef, Mechanism, FIXED};
use crate::solver::{Kinematics, TransferOrder};

/// The workspace and results of inverse dynamics at one position; every
/// buffer is allocated once, for one mechanism.
#[derive(Debug, Clone)]
pub struct InverseDynamics {
    pub(super) model: Dynamics,
    /// The frame of every body, in the model's order.
    pub(super) frames: Vec<Frame>,
    /// Co-ordinate velocities and accelerations (all N).
    pub(super) xd: Vec<f64>,
    pub(super) xdd: Vec<f64>,
    /// First-order transfer functions over all co-ordinates, DOF j at `x1[j*N..]`.
    pub(super) x1: Vec<f64>,
    /// Applied generalised forces f (all N).
    pub(super) f: Vec<f64>,
    /// f_in - f (all N).
    pub(super) g: Vec<f64>,
    /// (D^T sigma) over all co-ordinates.
    pub(super) dt_sigma: Vec<f64>,
    /// A column of F and the solver's scratch (n each).
    column: Vec<f64>,
    work: Vec<f64>,
    pub(super) sigma: Vec<f64>,
    ekin: f64,
    epot: f64,
    power: f64,
    load_power: f64,
    mred: Vec<f64>,
    /// Whether the last evaluation had the second-order transfer functions
    /// (without them only V is computed, the rest is NaN by design).
    pub(super) balanced: bool,
    /// The balance split by element: `(element, co-ordinate, generalised
    /// force)` terms of the forces each element exerts (`pins.rs`).
    pub(super) element_forces: Vec<(usize, usize, f64)>,
    /// Shaking force x, y and moment about the origin.
    pub(super) shaking: [f64; 3],
    /// Per DOF, whether it moves under the forces (a simulation's MOV_DYN).
    pub(super) moved_by_forces: Vec<bool>,
    /// Per DOF, the torque of the MOTORs on its input row when it moves
    /// under the forces (NaN otherwise): its drive.
    pub(super) motor_drive: Vec<f64>,
}

impl InverseDynamics {
    /// A workspace for `model` on `mech`; check the model first with
    /// [`Dynamics::check`].
    pub fn new(mech: &Mechanism, model: Dynamics) -> InverseDynamics {
        let frames = model
            .bodies
            .iter()
            .map(|b| {
                let e = &mech.elements()[b.element];
                Frame::of(e.ty, e.coords()).expect("Dynamics::check admits bodies on elements with a frame only")
            })
            .collect();
        let (nc, n, nd) = (mech.n_coords(), mech.n_moving(), mech.n_dof());
        let nan = |k| vec![f64::NAN; k];
        InverseDynamics {
            model,
            frames,
            xd: nan(nc),
            xdd: nan(nc),
            x1: nan(nc * nd),
            f: nan(nc),
            g: nan(nc),
            dt_sigma: nan(nc),
            column: nan(n),
            work: nan(n),
            sigma: nan(n),
            ekin: f64::NAN,
            epot: f64::NAN,
            power: f64::NAN,
            load_power: f64::NAN,
            mred: nan(nd * nd),
            balanced: false,
            element_forces: Vec::new(),
            shaking: [f64::NAN; 3],
            moved_by_forces: vec![false; nd],
            motor_drive: nan(nd),
        }
    }

    /// The mass and load model.
    pub fn model(&self) -> &Dynamics {
        &self.model
    }

    /// Evaluates everything at the position `v`. Where the second-order
    /// transfer functions were not computed (a limit position, where they
    /// do not exist) only the potential energy is known; the rest reads
    /// NaN.
    pub fn evaluate(&mut self, v: &PositionView<'_>) {
        self.epot = self.potential(v.kin, &v.state.x);
        self.balanced = self.balance(v);
        if !self.balanced {
            for b in [&mut self.sigma, &mut self.f, &mut self.g, &mut self.dt_sigma, &mut self.mred] {
                b.fill(f64::NAN);
            }
            (self.ekin, self.power, self.load_power) = (f64::NAN, f64::NAN, f64::NAN);
            self.shaking = [f64::NAN; 3];
            self.motor_drive.fill(f64::NAN);
            return;
        }
        let (mech, x, qd) = (v.mech, &v.state.x[..], v.input_vel);
        self.stresses(mech, v.kin);
        self.ekin = self.kinetic(x);
        self.power = (0..mech.n_dof()).map(|j| self.sigma[mech.input_row(j)] * qd[j]).sum();
        self.designer_outputs(v);
        self.motor_drives(v);
    }

    /// [`Self::evaluate`], then [`Self::check`].
    pub fn evaluate_checked(&mut self, v: &PositionView<'_>) -> Result<(), SolveError> {
        self.evaluate(v);
        self.check(v)
    }

    /// Checks that every result of the last [`Self::evaluate`] at the
    /// position `v` is finite (but those that are NaN by design where the
    /// second-order transfer functions are not known): finite masses and
    /// loads can still make products and sums that overflow, and no
    /// infinity may be handed on as a result. The error names the result
    /// and the mass or load it came from ([`SolveError::Dynamics`]).
    pub fn check(&self, v: &PositionView<'_>) -> Result<(), SolveError> {
        let finite = |s: &[f64]| s.iter().all(|x| x.is_finite());
        let mech = v.mech;
        let reactions = || (0..mech.n_coords()).all(|i| mech.column(i) != FIXED || self.reaction(mech, i).is_finite());
        let ok = self.epot.is_finite()
            && (!self.balanced
                || (finite(&self.sigma[..mech.n_moving()])
                    && finite(&self.mred)
                    && finite(&[self.ekin, self.power, self.load_power])
                    && reactions()));
        if ok {
            return Ok(());
        }
        Err(SolveError::Dynamics(self.fault(v)))
    }

    /// What the equations of motion need at the position `v`: the drive
    /// force of every DOF, written into `drives`, for the input
    /// accelerations of the view, and the mass matrix
    /// ([`Self::mass_matrix_entry`]); the stresses of the other rows are
    /// not computed. The drive of DOF j is `x'_j . (f_in - f)`, column j of
    /// F being x'_j. Returns false where the second-order transfer
    /// functions are not known.
    pub fn drives(&mut self, v: &PositionView<'_>, drives: &mut [f64]) -> bool {
        if !self.balance(v) {
            return false;
        }
        let nc = v.mech.n_coords();
        for (j, d) in drives.iter_mut().enumerate() {
            *d = self.x1[j * nc..(j + 1) * nc].iter().zip(&self.g).map(|(a, b)| a * b).sum();
        }
        true
    }

    /// Velocities, accelerations, f, f_in - f and the mass matrix at the
    /// position `v`; false where its second-order transfer functions are
    /// not known.
    fn balance(&mut self, v: &PositionView<'_>) -> bool {
        let (mech, kin, x) = (v.mech, v.kin, &v.state.x[..]);
        if kin.order() != Some(TransferOrder::Second) {
            return false;
        }
        let (nc, nd) = (mech.n_coords(), mech.n_dof());
        let (qd, qdd) = (v.input_vel, v.input_acc);
        for i in 0..nc {
            self.xd[i] = kin.velocity(mech, i, qd);
            self.xdd[i] = kin.acceleration(mech, i, qd, qdd);
            for j in 0..nd {
                self.x1[j * nc + i] = kin.dx(mech, i, j);
            }
        }
        self.applied(mech, kin, x, v.time, qd);
        self.inertia(x);
        self.mass_matrix(x, nc, nd);
        true
    }

    /// Value and rate of form parameter `form` at the position.
    pub(super) fn form_state(mech: &Mechanism, kin: &Kinematics, form: FormRef, qd: &[f64]) -> (f64, f64) {
        match form {
            FormRef::Prescribed(r) => {
                let rate = mech.input_of(r).map_or(0.0, |j| qd[j]);
                (kin.row_value(r), rate)
            }
            FormRef::Dependent(d) => (kin.dep(d), kin.dep_velocity(d, qd)),
        }
    }

    /// Adds `q` times the gradient of form parameter `form` over all
    /// co-ordinates to `out`: the generalised forces of a load `q` on it.
    pub(super) fn spread_load(mech: &Mechanism, kin: &Kinematics, form: FormRef, q: f64, out: &mut [f64]) {
        let (rows, cache, row) = match form {
            FormRef::Prescribed(r) => (&mech.prescribed, &kin.cache, r),
            FormRef::Dependent(d) => (&mech.dependent, &kin.dep_cache, d),
        };
        for t in rows.range(row) {
            let (slot, factor) = (&rows.slots()[t], rows.terms()[t].factor);
            for k in 0..slot.n {
                out[slot.coords[k]] += q * factor * cache[t].grad[k];
            }
        }
    }

    /// f: gravity, point forces and the loads on form parameters; also the
    /// power of the loads that are not springs' elastic part.
    fn applied(&mut self, mech: &Mechanism, kin: &Kinematics, x: &[f64], t: f64, qd: &[f64]) {
        self.f.fill(0.0);
        let g = self.model.gravity;
        for (b, frame) in self.model.bodies.iter().zip(&self.frames) {
            frame.spread(x, b.u, b.v, [b.mass * g[0], b.mass * g[1]], 0.0, &mut self.f);
        }
        for p in &self.model.point_masses {
            self.f[p.x] += p.mass * g[0];
            self.f[p.y] += p.mass * g[1];
        }
        let mut load_power = 0.0;
        for f in &self.model.forces {
            self.f[f.x] += f.f[0];
            self.f[f.y] += f.f[1];
            load_power += f.f[0] * self.xd[f.x] + f.f[1] * self.xd[f.y];
        }
        for l in &self.model.loads {
            let (eps, rate) = Self::form_state(mech, kin, l.form, qd);
            let q = l.value(t, eps, rate);
            Self::spread_load(mech, kin, l.form, q, &mut self.f);
            // A spring's elastic force is accounted for in V.
            let elastic = match l.kind {
                LoadKind::Spring { k, e0, .. } => -k * (eps - e0),
                _ => 0.0,
            };
            load_power += (q - elastic) * rate;
        }
        self.load_power = load_power;
    }

    /// g = f_in - f, f_in the inertia forces of bodies, point masses and
    /// rotational inertias.
    fn inertia(&mut self, x: &[f64]) {
        for (gi, fi) in self.g.iter_mut().zip(&self.f) {
            *gi = -fi;
        }
        for (b, frame) in self.model.bodies.iter().zip(&self.frames) {
            let m = frame.motion(x, &self.xd, &self.xdd, b.u, b.v);
            let f_in = [b.mass * m.c_ddot[0], b.mass * m.c_ddot[1]];
            frame.spread(x, b.u, b.v, f_in, b.inertia * m.beta_ddot, &mut self.g);
        }
        for p in &self.model.point_masses {
            self.g[p.x] += p.mass * self.xdd[p.x];
            self.g[p.y] += p.mass * self.xdd[p.y];
        }
        for i in &self.model.inertias {
            self.g[i.coord] += i.inertia * self.xdd[i.coord];
        }
    }

    /// sigma from the columns of F, and D^T sigma over all co-ordinates.
    fn stresses(&mut self, mech: &Mechanism, kin: &Kinematics) {
        let n = mech.n_moving();
        let moving = mech.moving_coords();
        for r in 0..n {
            self.column.fill(0.0);
            self.column[r] = 1.0;
            kin.lu.solve(&mut self.column, &mut self.work);
            self.sigma[r] = self.column.iter().zip(moving).map(|(fc, &i)| fc * self.g[i]).sum();
        }
        self.dt_sigma.fill(0.0);
        let rows = &mech.prescribed;
        for (t, (slot, term)) in rows.slots().iter().zip(rows.terms()).enumerate() {
            let s = term.factor * self.sigma[rows.row_of()[t]];
            for k in 0..slot.n {
                self.dt_sigma[slot.coords[k]] += s * kin.cache[t].grad[k];
            }
        }
    }

    fn kinetic(&self, x: &[f64]) -> f64 {
        let mut t = 0.0;
        for (b, frame) in self.model.bodies.iter().zip(&self.frames) {
            let (cd, bd) = frame.velocity(x, &self.xd, b.u, b.v);
            t += b.mass * (cd[0] * cd[0] + cd[1] * cd[1]) + b.inertia * bd * bd;
        }
        for p in &self.model.point_masses {
            t += p.mass * (self.xd[p.x] * self.xd[p.x] + self.xd[p.y] * self.xd[p.y]);
        }
        for i in &self.model.inertias {
            t += i.inertia * self.xd[i.coord] * self.xd[i.coord];
        }
        0.5 * t
    }

    /// V: gravity (`-m g . c`) and springs.
    fn potential(&self, kin: &Kinematics, x: &[f64]) -> f64 {
        let g = self.model.gravity;
        let mut v = 0.0;
        for (b, frame) in self.model.bodies.iter().zip(&self.frames) {
            let c = frame.centre(x, b.u, b.v);
            v -= b.mass * (g[0] * c[0] + g[1] * c[1]);
        }
        for p in &self.model.point_masses {
            v -= p.mass * (g[0] * x[p.x] + g[1] * x[p.y]);
        }
        for l in &self.model.loads {
            if let LoadKind::Spring { .. } = l.kind {
                let eps = match l.form {
                    FormRef::Prescribed(r) => kin.row_value(r),
                    FormRef::Dependent(d) => kin.dep(d),
                };
                v += l.potential(eps);
            }
        }
        v
    }

    /// M(q) = sum m c_j' . c_m' + J beta_j' beta_m' (+ point masses, inertias).
    fn mass_matrix(&mut self, x: &[f64], nc: usize, nd: usize) {
        self.mred.fill(0.0);
        for j in 0..nd {
            for m in j..nd {
                let (aj, am) = (&self.x1[j * nc..(j + 1) * nc], &self.x1[m * nc..(m + 1) * nc]);
                let mut s = 0.0;
                for (b, frame) in self.model.bodies.iter().zip(&self.frames) {
                    let (cj, bj) = frame.velocity(x, aj, b.u, b.v);
                    let (cm, bm) = frame.velocity(x, am, b.u, b.v);
                    s += b.mass * (cj[0] * cm[0] + cj[1] * cm[1]) + b.inertia * bj * bm;
                }
                for p in &self.model.point_masses {
                    s += p.mass * (aj[p.x] * am[p.x] + aj[p.y] * am[p.y]);
                }
                for i in &self.model.inertias {
                    s += i.inertia * aj[i.coord] * am[i.coord];
                }
                self.mred[j * nd + m] = s;
                self.mred[m * nd + j] = s;
            }
        }
    }

    /// Generalised stress of prescribed row r.
    pub fn sigma(&self, r: usize) -> f64 {
        self.sigma[r]
    }

    /// Drive force or torque of DOF j: the stress of its input row; for a
    /// DOF that moves under the forces and carries a MOTOR on its input row
    /// ([`Self::set_moved_by_forces`]), the motor's torque.
    pub fn drive(&self, mech: &Mechanism, j: usize) -> f64 {
        match self.motor_drive.get(j) {
            Some(&t) if !t.is_nan() => t,
            _ => self.sigma[mech.input_row(j)],
        }
    }

    /// Reaction on fixed co-ordinate i: the force the frame applies to the
    /// mechanism there (NaN for a moving co-ordinate).
    pub fn reaction(&self, mech: &Mechanism, i: usize) -> f64 {
        if mech.column(i) != FIXED {
            return f64::NAN;
        }
        self.g[i] - self.dt_sigma[i]
    }

    /// Kinetic energy T.
    pub fn kinetic_energy(&self) -> f64 {
        self.ekin
    }

    /// Potential energy V of gravity and springs.
    pub fn potential_energy(&self) -> f64 {
        self.epot
    }

    /// Power the drives deliver, `sum_j sigma_j qdot_j`.
    pub fn drive_power(&self) -> f64 {
        self.power
    }

    /// Power of the loads that are neither gravity nor a spring's elastic
    /// force (point forces, loads, tables, motors, dampers): with it,
    /// `drive_power + load_power = d(T + V)/dt`.
    pub fn load_power(&self) -> f64 {
        self.load_power
    }

    /// Entry (j, m) of the mass matrix in the degrees of freedom.
    pub fn mass_matrix_entry(&self, mech: &Mechanism, j: usize, m: usize) -> f64 {
        self.mred[j * mech.n_dof() + m]
    }
}
