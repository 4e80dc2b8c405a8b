//! Design sensitivities of inverse dynamics against central differences
//! of whole runs: every dynamic quantity (drive, stresses, reactions, pin
//! forces, shaking force and moment, energies, power, the reduced mass) at
//! every position,
//! with respect to prescribed values, fixed co-ordinates, an input's start
//! and every kind of mass variable, on a four-bar carrying every kind of
//! mass and load and on an offset slider-crank.

use crate::common_dynamics as models;

use mechfem_core::dynamic_design::evaluate;
use mechfem_core::dynamics::{Component, Dynamics, MassVar};
use mechfem_core::{
    design::DesignRun, DesignVar, ElementType, InputMotion, Mechanism, Motion, Params, Quantity, State,
};
use std::f64::consts::PI;

/// Every dynamic quantity of `mech`: the drive, every stress, the
/// reactions, the force of every element on each of its pins, shaking,
/// energies and power.
fn dynamic_quantities(mech: &Mechanism) -> Vec<Quantity> {
    let mut q = vec![Quantity::Drive(0), Quantity::Ekin, Quantity::Epot, Quantity::Power, Quantity::Mred(0, 0)];
    q.extend([Component::X, Component::Y, Component::Moment].map(Quantity::Shaking));
    q.extend((0..mech.n_prescribed()).map(Quantity::Sigma));
    q.extend((0..mech.n_coords()).filter(|&i| !mech.is_moving(i)).map(Quantity::Reaction));
    for (e, el) in mech.elements().iter().enumerate() {
        let c = el.coords();
        let pins: &[(usize, usize)] = match el.ty {
            ElementType::Bin => &[(0, 1), (2, 3)],
            ElementType::Tr1 => &[(0, 1), (3, 4)],
            ElementType::Tr2 => &[(0, 1), (2, 3), (4, 5)],
            _ => &[],
        };
        for &(a, b) in pins {
            for component in [Component::X, Component::Y] {
                q.push(Quantity::Pin { element: e, x: c[a], y: c[b], component });
            }
        }
    }
    q
}

struct Case<'a> {
    mech: &'a Mechanism,
    state: &'a State,
    dynamics: &'a Dynamics,
    motion: &'a Motion,
    vars: &'a [DesignVar],
    mass_vars: &'a [MassVar],
    quantities: &'a [Quantity],
}

impl Case<'_> {
    fn values(&self) -> Vec<f64> {
        let mut v: Vec<f64> = self
            .vars
            .iter()
            .map(|d| match *d {
                DesignVar::Row(r) => self.state.target[r],
                DesignVar::Fixed(i) => self.state.x[i],
            })
            .collect();
        v.extend(self.mass_vars.iter().map(|m| m.value(self.dynamics)));
        v
    }

    fn at(&self, values: &[f64]) -> DesignRun {
        let (mut state, mut dynamics) = (self.state.clone(), self.dynamics.clone());
        for (d, &x) in self.vars.iter().zip(values) {
            match *d {
                DesignVar::Row(r) => state.target[r] = x,
                DesignVar::Fixed(i) => state.x[i] = x,
            }
        }
        for (m, &x) in self.mass_vars.iter().zip(&values[self.vars.len()..]) {
            m.set(&mut dynamics, x);
        }
        let params = Params { tol: 1e-13, ..Params::default() };
        let run = evaluate(
            self.mech,
            &mut state,
            self.motion,
            &params,
            &dynamics,
            self.vars,
            self.mass_vars,
            self.quantities,
        )
        .unwrap();
        assert_eq!(run.positions, self.motion.steps + 1);
        run
    }

    /// Checks every gradient against central differences; returns the
    /// largest relative disagreement.
    fn check(&self) -> f64 {
        let x0 = self.values();
        let base = self.at(&x0);
        let (nq, nv) = (self.quantities.len(), x0.len());
        // Each quantity's scale: its largest size along the motion.
        let scale: Vec<f64> =
            (0..nq).map(|k| (0..base.positions).map(|p| base.values[p * nq + k].abs()).fold(1e-3, f64::max)).collect();
        let mut worst = 0.0f64;
        for v in 0..nv {
            let h = 1e-5 * x0[v].abs().max(0.1);
            let (mut plus, mut minus) = (x0.clone(), x0.clone());
            plus[v] += h;
            minus[v] -= h;
            let (p, m) = (self.at(&plus), self.at(&minus));
            let var_scale = x0[v].abs().max(0.1);
            for pos in 0..base.positions {
                for k in 0..nq {
                    let i = pos * nq + k;
                    let fd = (p.values[i] - m.values[i]) / (2.0 * h);
                    let g = base.gradient[i * nv + v];
                    // Relative to the quantity's size per relative change of the variable.
                    let err = (fd - g).abs() * var_scale / scale[k];
                    assert!(
                        err < 1e-6,
                        "variable {v} ({:?}), position {pos}, {:?}: sensitivity {g}, central difference {fd}",
                        if v < self.vars.len() {
                            format!("{:?}", self.vars[v])
                        } else {
                            format!("{:?}", self.mass_vars[v - self.vars.len()])
                        },
                        self.quantities[k]
                    );
                    worst = worst.max(err);
                }
            }
        }
        worst
    }
}

/// A table motion whose speed varies, so that accelerations are not zero.
fn varying_speed(start: f64, steps: usize) -> Motion {
    let dt = 0.02;
    let (w0, a) = (6.0, 0.8);
    let rows = (0..=steps)
        .map(|k| {
            let t = k as f64 * dt;
            let (s, c) = (5.0 * t).sin_cos();
            [t, start + w0 * t + a * s, w0 + 5.0 * a * c, -25.0 * a * s]
        })
        .collect();
    Motion { steps, dt, inputs: vec![InputMotion::Table { rows }] }
}

#[test]
fn fourbar_with_every_mass_and_load() {
    let model = models::fourbar(&models::Fourbar::default());
    let q = dynamic_quantities(&model.mech);
    let [_, _, xb0, _] = model.fixed;
    let r = model.rows;
    // The crank's u (its pin A), the coupler's length, the coupler point's u, the rocker's length, B0's x.
    let vars =
        [DesignVar::Row(r[0]), DesignVar::Row(r[2]), DesignVar::Row(r[3]), DesignVar::Row(r[5]), DesignVar::Fixed(xb0)];
    let mass_vars = [
        MassVar::Mass(0),
        MassVar::CentreU(1),
        MassVar::CentreV(2),
        MassVar::BodyInertia(1),
        MassVar::PointMass(0),
        MassVar::Inertia(0),
    ];
    let motion = varying_speed(model.state.target[r[6]], 30);
    let case = Case {
        mech: &model.mech,
        state: &model.state,
        dynamics: &model.dynamics,
        motion: &motion,
        vars: &vars,
        mass_vars: &mass_vars,
        quantities: &q,
    };
    let worst = case.check();
    eprintln!("four-bar: largest relative disagreement {worst:e}");
}

#[test]
fn fourbar_input_start_at_constant_speed() {
    let model = models::fourbar(&models::Fourbar::default());
    let q = dynamic_quantities(&model.mech);
    let vars = [DesignVar::Row(model.rows[6]), DesignVar::Row(model.rows[4])];
    let motion = Motion { steps: 24, dt: 0.01, inputs: vec![InputMotion::Absolute { end: 2.0 * PI }] };
    let case = Case {
        mech: &model.mech,
        state: &model.state,
        dynamics: &model.dynamics,
        motion: &motion,
        vars: &vars,
        mass_vars: &[MassVar::CentreU(0)],
        quantities: &q,
    };
    let worst = case.check();
    eprintln!("four-bar, input start: largest relative disagreement {worst:e}");
}

#[test]
fn slider_crank_with_gravity_and_gas_force() {
    let sc = models::SliderCrank::default();
    let (mech, state, dynamics) = models::slider_crank(&sc, 0.4);
    let q = dynamic_quantities(&mech);
    // Crank and rod lengths, the guide's height (the offset), the guide's angle.
    let vars = [DesignVar::Row(0), DesignVar::Row(1), DesignVar::Fixed(sc.yg), DesignVar::Row(2)];
    let mass_vars = [
        MassVar::Mass(0),
        MassVar::CentreU(0),
        MassVar::CentreV(0),
        MassVar::Mass(1),
        MassVar::BodyInertia(1),
        MassVar::PointMass(0),
    ];
    let motion = varying_speed(0.4, 30);
    let case = Case {
        mech: &mech,
        state: &state,
        dynamics: &dynamics,
        motion: &motion,
        vars: &vars,
        mass_vars: &mass_vars,
        quantities: &q,
    };
    let worst = case.check();
    eprintln!("slider-crank: largest relative disagreement {worst:e}");
}
