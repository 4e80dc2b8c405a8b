//! What a designer sizes bearings and balances a mechanism from: the force
//! each element's body exerts on each of its pins, and the shaking force and
//! moment the moving bodies' inertia puts on the frame.
//!
//! **Pin forces.** The rows of element e hold their stresses sigma (the
//! generalised force each row's constraint applies in the direction of
//! increasing eps) and the loads Q on its form parameters; its body, if it
//! has one, has the inertia force m a_G and the weight m g at its centre c
//! and the inertia torque J alpha on its angle beta. The force the element
//! exerts on the pin at co-ordinates (i, j) is the (i, j) part of
//!
//! `f_e = (d eps_e/dx)^T (sigma_e + Q_e) - (dc_e/dx)^T m_e (a_e - g) - (d beta_e/dx)^T J_e alpha_e`,
//!
//! each row's share taken term by term (a row made of form parameters of
//! several elements gives each element its own term). The pin is massless:
//! a point mass or a FORCE at the point belongs to the point, so at a
//! moving pin the elements' forces sum to `m_p (a - g) - F` of the point
//! (zero for a bare pin), and at a frame pivot they sum to minus the
//! reaction there (less a FORCE or a point mass on the pivot).
//!
//! **Shaking.** `F = -sum m a_G`, `M = -sum (r_G x m a_G + J alpha)` about
//! the origin, over bodies, point masses and rotational inertias: what
//! inertia alone does to the frame (gravity and loads are left out).

use super::inverse::InverseDynamics;
use super::observe::PositionView;
use crate::dynamics::{Component, LoadKind};
use crate::model::FormRef;

impl InverseDynamics {
    /// Splits the balance of the position `v` (evaluated: stresses known)
    /// by element, and sums the shaking force and moment.
    pub(super) fn designer_outputs(&mut self, v: &PositionView<'_>) {
        let (mech, kin, x) = (v.mech, v.kin, &v.state.x[..]);
        self.element_forces.clear();
        let rows = &mech.prescribed;
        for (t, (slot, term)) in rows.slots().iter().zip(rows.terms()).enumerate() {
            let s = term.factor * self.sigma[rows.row_of()[t]];
            for k in 0..slot.n {
                self.element_forces.push((term.element, slot.coords[k], s * kin.cache[t].grad[k]));
            }
        }
        for l in &self.model.loads {
            let (eps, rate) = Self::form_state(mech, kin, l.form, v.input_vel);
            let q = l.value(v.time, eps, rate);
            let (rows, cache, row) = match l.form {
                FormRef::Prescribed(r) => (&mech.prescribed, &kin.cache, r),
                FormRef::Dependent(d) => (&mech.dependent, &kin.dep_cache, d),
            };
            for t in rows.range(row) {
                let (slot, term) = (&rows.slots()[t], &rows.terms()[t]);
                for k in 0..slot.n {
                    self.element_forces.push((term.element, slot.coords[k], q * term.factor * cache[t].grad[k]));
                }
            }
        }
        let g = self.model.gravity;
        let mut shaking = [0.0; 3];
        for (b, frame) in self.model.bodies.iter().zip(&self.frames) {
            let m = frame.motion(x, &self.xd, &self.xdd, b.u, b.v);
            let ma = [b.mass * m.c_ddot[0], b.mass * m.c_ddot[1]];
            let alpha_j = b.inertia * m.beta_ddot;
            let net = [ma[0] - b.mass * g[0], ma[1] - b.mass * g[1]];
            for (i, value) in frame.spread_terms(x, b.u, b.v, net, alpha_j) {
                if i != usize::MAX {
                    self.element_forces.push((b.element, i, -value));
                }
            }
            shaking[0] -= ma[0];
            shaking[1] -= ma[1];
            shaking[2] -= m.c[0] * ma[1] - m.c[1] * ma[0] + alpha_j;
        }
        for p in &self.model.point_masses {
            let ma = [p.mass * self.xdd[p.x], p.mass * self.xdd[p.y]];
            shaking[0] -= ma[0];
            shaking[1] -= ma[1];
            shaking[2] -= x[p.x] * ma[1] - x[p.y] * ma[0];
        }
        for i in &self.model.inertias {
            shaking[2] -= i.inertia * self.xdd[i.coord];
        }
        self.shaking = shaking;
        // By element, each element's terms in the order they were added
        // (a stable sort): a pin force reads its element's terms only.
        self.element_forces.sort_by_key(|t| t.0);
    }

    /// One component of the force the body of element `element` exerts on
    /// the pin at co-ordinates `x`, `y` (see the module's text); NaN where
    /// the second-order transfer functions are not known, and for
    /// [`Component::Moment`], which a pin does not carry.
    pub fn pin_force(&self, element: usize, x: usize, y: usize, component: Component) -> f64 {
        let coord = match component {
            Component::X => x,
            Component::Y => y,
            Component::Moment => return f64::NAN,
        };
        if !self.balanced {
            return f64::NAN;
        }
        let terms = &self.element_forces;
        let (start, end) = (terms.partition_point(|t| t.0 < element), terms.partition_point(|t| t.0 <= element));
        terms[start..end].iter().filter(|t| t.1 == coord).map(|t| t.2).sum()
    }

    /// One component of the shaking force and moment (about the origin).
    pub fn shaking(&self, component: Component) -> f64 {
        match component {
            Component::X => self.shaking[0],
            Component::Y => self.shaking[1],
            Component::Moment => self.shaking[2],
        }
    }
}

impl InverseDynamics {
    /// Marks the DOFs `free` (0-based) as moving under the forces, as a
    /// simulation's MOV_DYN does: the drive of such a DOF is then the
    /// torque (or force) of the MOTORs on its input row, `T0 (1 - qdot /
    /// w0)`, where it has any; its stress is the integrator's residual.
    pub fn set_moved_by_forces(&mut self, free: &[usize]) {
        self.moved_by_forces.fill(false);
        for &j in free {
            if let Some(m) = self.moved_by_forces.get_mut(j) {
                *m = true;
            }
        }
    }

    /// The MOTOR torque of every DOF that moves under the forces, at the
    /// position `v` (NaN for the others and for DOFs without a motor).
    pub(super) fn motor_drives(&mut self, v: &PositionView<'_>) {
        let mech = v.mech;
        for (j, out) in self.motor_drive.iter_mut().enumerate() {
            *out = f64::NAN;
            if !self.moved_by_forces[j] {
                continue;
            }
            let row = FormRef::Prescribed(mech.input_row(j));
            for l in self.model.loads.iter().filter(|l| l.form == row && matches!(l.kind, LoadKind::Motor { .. })) {
                let t = l.value(v.time, v.input(j), v.input_vel[j]);
                *out = if out.is_nan() { t } else { *out + t };
            }
        }
    }
}
