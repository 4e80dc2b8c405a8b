//! Which mass or load made a result of inverse dynamics not finite.
//!
//! Only asked when [`InverseDynamics::check`] found a NaN or an infinity:
//! the contributions are formed again one by one, in the order
//! [`InverseDynamics::evaluate`] adds them up, and the first that is not
//! finite itself, or makes its sum overflow, is the one named. A result
//! made of finite contributions that overflows only in the balance (a
//! stress, a reaction, the drives' power) names the row or co-ordinate.

use super::inverse::InverseDynamics;
use super::observe::PositionView;
use crate::dynamics::LoadKind;
use crate::error::{DynamicQuantity as Q, DynamicSource as S, DynamicsFault, SolveError};
use crate::model::FIXED;

/// The deck keyword of a load.
fn keyword(kind: &LoadKind) -> &'static str {
    match kind {
        LoadKind::Constant(_) => "LOAD",
        LoadKind::Table(_) => "LOADFUNC",
        LoadKind::Spring { .. } => "SPRING",
        LoadKind::Motor { .. } => "MOTOR",
    }
}

fn finite(s: &[f64]) -> bool {
    s.iter().all(|x| x.is_finite())
}

impl InverseDynamics {
    /// The error for equations of motion that are not finite at the
    /// position `v` (a simulation's): the result of inverse dynamics and
    /// the mass or load it names, else the accelerations of the degrees of
    /// freedom moved by the forces themselves.
    pub(super) fn fault_at(&mut self, v: &PositionView<'_>) -> SolveError {
        match self.evaluate_checked(v) {
            Err(e) => e,
            Ok(()) => SolveError::Dynamics(DynamicsFault { quantity: Q::Acceleration, source: S::FreeDofs }),
        }
    }

    /// The first result at the position `v` that is not finite, and what
    /// it came from (see the module's documentation).
    pub(super) fn fault(&self, v: &PositionView<'_>) -> DynamicsFault {
        let fault = |quantity, source| DynamicsFault { quantity, source };
        let (mech, kin, x, qd) = (v.mech, v.kin, &v.state.x[..], v.input_vel);
        let m = &self.model;
        let g = m.gravity;
        let nc = mech.n_coords();
        let body = |k: usize| S::Body { element: m.bodies[k].element };
        let load = |k: usize| S::Load { form: m.loads[k].form, keyword: keyword(&m.loads[k].kind) };
        // V: gravity and springs.
        let mut epot = 0.0;
        for (k, (b, frame)) in m.bodies.iter().zip(&self.frames).enumerate() {
            let c = frame.centre(x, b.u, b.v);
            epot -= b.mass * (g[0] * c[0] + g[1] * c[1]);
            if !epot.is_finite() {
                return fault(Q::PotentialEnergy, body(k));
            }
        }
        for p in &m.point_masses {
            epot -= p.mass * (g[0] * x[p.x] + g[1] * x[p.y]);
            if !epot.is_finite() {
                return fault(Q::PotentialEnergy, S::PointMass { x: p.x, y: p.y });
            }
        }
        for (k, l) in m.loads.iter().enumerate() {
            let (eps, _) = Self::form_state(mech, kin, l.form, qd);
            epot += l.potential(eps);
            if !epot.is_finite() {
                return fault(Q::PotentialEnergy, load(k));
            }
        }
        // f: weights, point forces and loads, with their power.
        let mut f = vec![0.0; nc];
        for (k, (b, frame)) in m.bodies.iter().zip(&self.frames).enumerate() {
            frame.spread(x, b.u, b.v, [b.mass * g[0], b.mass * g[1]], 0.0, &mut f);
            if !finite(&f) {
                return fault(Q::Weight, body(k));
            }
        }
        for p in &m.point_masses {
            f[p.x] += p.mass * g[0];
            f[p.y] += p.mass * g[1];
            if !finite(&f) {
                return fault(Q::Weight, S::PointMass { x: p.x, y: p.y });
            }
        }
        let mut power = 0.0;
        for fc in &m.forces {
            f[fc.x] += fc.f[0];
            f[fc.y] += fc.f[1];
            power += fc.f[0] * self.xd[fc.x] + fc.f[1] * self.xd[fc.y];
            let source = S::Force { x: fc.x, y: fc.y };
            if !finite(&f) {
                return fault(Q::Force, source);
            }
            if !power.is_finite() {
                return fault(Q::Power, source);
            }
        }
        for (k, l) in m.loads.iter().enumerate() {
            let (eps, rate) = Self::form_state(mech, kin, l.form, qd);
            let q = l.value(v.time, eps, rate);
            Self::spread_load(mech, kin, l.form, q, &mut f);
            if !(q.is_finite() && finite(&f)) {
                return fault(Q::Force, load(k));
            }
            power += q * rate;
            if !power.is_finite() {
                return fault(Q::Power, load(k));
            }
        }
        // f_in - f: the inertia forces.
        let mut gi: Vec<f64> = f.iter().map(|v| -v).collect();
        for (k, (b, frame)) in m.bodies.iter().zip(&self.frames).enumerate() {
            let mo = frame.motion(x, &self.xd, &self.xdd, b.u, b.v);
            let f_in = [b.mass * mo.c_ddot[0], b.mass * mo.c_ddot[1]];
            frame.spread(x, b.u, b.v, f_in, b.inertia * mo.beta_ddot, &mut gi);
            if !finite(&gi) {
                return fault(Q::InertiaForce, body(k));
            }
        }
        for p in &m.point_masses {
            gi[p.x] += p.mass * self.xdd[p.x];
            gi[p.y] += p.mass * self.xdd[p.y];
            if !finite(&gi) {
                return fault(Q::InertiaForce, S::PointMass { x: p.x, y: p.y });
            }
        }
        for i in &m.inertias {
            gi[i.coord] += i.inertia * self.xdd[i.coord];
            if !finite(&gi) {
                return fault(Q::InertiaForce, S::Inertia { coord: i.coord });
            }
        }
        // T and the mass matrix, body by body.
        let nd = mech.n_dof();
        let mut ekin = 0.0;
        let mut mred = vec![0.0; nd * nd];
        for (k, (b, frame)) in m.bodies.iter().zip(&self.frames).enumerate() {
            let (cd, bd) = frame.velocity(x, &self.xd, b.u, b.v);
            ekin += 0.5 * (b.mass * (cd[0] * cd[0] + cd[1] * cd[1]) + b.inertia * bd * bd);
            if !ekin.is_finite() {
                return fault(Q::KineticEnergy, body(k));
            }
            for (jm, entry) in mred.iter_mut().enumerate() {
                let (aj, am) = (&self.x1[jm / nd * nc..][..nc], &self.x1[jm % nd * nc..][..nc]);
                let (cj, bj) = frame.velocity(x, aj, b.u, b.v);
                let (cm, bm) = frame.velocity(x, am, b.u, b.v);
                *entry += b.mass * (cj[0] * cm[0] + cj[1] * cm[1]) + b.inertia * bj * bm;
            }
            if !finite(&mred) {
                return fault(Q::MassMatrix, body(k));
            }
        }
        for p in &m.point_masses {
            let source = S::PointMass { x: p.x, y: p.y };
            ekin += 0.5 * p.mass * (self.xd[p.x] * self.xd[p.x] + self.xd[p.y] * self.xd[p.y]);
            if !ekin.is_finite() {
                return fault(Q::KineticEnergy, source);
            }
            for (jm, entry) in mred.iter_mut().enumerate() {
                let (aj, am) = (&self.x1[jm / nd * nc..][..nc], &self.x1[jm % nd * nc..][..nc]);
                *entry += p.mass * (aj[p.x] * am[p.x] + aj[p.y] * am[p.y]);
            }
            if !finite(&mred) {
                return fault(Q::MassMatrix, source);
            }
        }
        for i in &m.inertias {
            let source = S::Inertia { coord: i.coord };
            ekin += 0.5 * i.inertia * self.xd[i.coord] * self.xd[i.coord];
            if !ekin.is_finite() {
                return fault(Q::KineticEnergy, source);
            }
            for (jm, entry) in mred.iter_mut().enumerate() {
                *entry += i.inertia * self.x1[jm / nd * nc + i.coord] * self.x1[jm % nd * nc + i.coord];
            }
            if !finite(&mred) {
                return fault(Q::MassMatrix, source);
            }
        }
        // Every contribution is finite: the balance itself overflows.
        if let Some(r) = self.sigma[..mech.n_moving()].iter().position(|s| !s.is_finite()) {
            return fault(Q::Stress, S::Row(r));
        }
        if let Some(i) = (0..nc).find(|&i| mech.column(i) == FIXED && !(self.g[i] - self.dt_sigma[i]).is_finite()) {
            return fault(Q::Reaction, S::Coordinate(i));
        }
        fault(Q::Power, S::Drives)
    }
}
