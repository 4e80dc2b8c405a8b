//! A design model's numbers in the model's own units (its UNITS: lengths in
//! mm, angles in degrees, masses in g, ...) instead of the core's.
//!
//! The core evaluates a design in metres, radians, kilograms and newtons.
//! A design model made for a model with other units ([`DesignUnits`]) takes
//! each variable in the model's unit and hands the core the variable times
//! its unit's size in the core's (pi/180 for a degree, 1/1000 for a mm);
//! it gives each buffer's value, the co-ordinates and the value at an
//! extremum divided by their unit's size, and each derivative with both:
//! d(buffer)/d(variable) in the model's units is the core's times the
//! variable's size over the buffer's (a transfer function in mm/deg, a
//! drive torque in N·mm per degree). A deck's own optimisation keeps the
//! core's units (its print file converts); `mechfem.optimize` and
//! `RunResult.sensitivity` work in the model's.

use mechfem_core::design::{DesignRun, ExtremumSpec};
use mechfem_core::dynamics::MassVar;
use mechfem_core::{DesignVar, Dim, FormRef, Quantity};

use crate::compile::inertia_on;
use crate::compiled::Compiled;
use crate::design_setup::DesignSetup;
use crate::dynamic_setup::DynamicSetup;

/// A design model's units: how many of the core's units one of the model's
/// is, for each variable (in the order given), buffer, co-ordinate and
/// extremum spec; or the core's units themselves, where nothing is
/// converted ([`DesignUnits::core`]).
#[derive(Debug, Clone, PartialEq)]
pub struct DesignUnits(Option<Sizes>);

#[derive(Debug, Clone, PartialEq)]
struct Sizes {
    vars: Vec<f64>,
    quantities: Vec<f64>,
    coords: Vec<f64>,
    extrema: Vec<f64>,
}

impl Compiled {
    /// The units of the design model `setup` of this model ([`DesignUnits::core`]
    /// for a model in the core's units, whose numbers need no conversion).
    pub fn design_units(&self, setup: &DesignSetup) -> DesignUnits {
        let vars = setup.vars.iter().map(|&v| self.var_size(v)).collect();
        self.units_of(vars, &setup.quantities, &setup.extrema)
    }

    /// The units of the dynamic design model `setup` (its mass variables
    /// among its variables, in the order given).
    pub fn dynamic_design_units(&self, setup: &DynamicSetup) -> DesignUnits {
        let n_kin = setup.vars.len();
        let vars = setup
            .order
            .iter()
            .map(|&k| match setup.vars.get(k) {
                Some(&v) => self.var_size(v),
                None => self.mass_size(setup.mass_vars[k - n_kin]),
            })
            .collect();
        self.units_of(vars, &setup.quantities, &[])
    }

    fn units_of(&self, vars: Vec<f64>, quantities: &[Quantity], extrema: &[ExtremumSpec]) -> DesignUnits {
        if self.units.is_identity() {
            return DesignUnits::core();
        }
        let size = |q: Quantity| self.dims.quantity(&self.mechanism, q).scale(&self.units);
        DesignUnits(Some(Sizes {
            vars,
            quantities: quantities.iter().map(|&q| size(q)).collect(),
            coords: (0..self.mechanism.n_coords()).map(|i| self.dims.coord(i).scale(&self.units)).collect(),
            extrema: extrema.iter().map(|e| size(e.quantity)).collect(),
        }))
    }

    fn var_size(&self, v: DesignVar) -> f64 {
        let dim = match v {
            DesignVar::Row(r) => self.dims.form(FormRef::Prescribed(r)),
            DesignVar::Fixed(i) => self.dims.coord(i),
        };
        dim.scale(&self.units)
    }

    fn mass_size(&self, m: MassVar) -> f64 {
        let dim = match m {
            MassVar::Mass(_) | MassVar::PointMass(_) => Dim::MASS,
            MassVar::CentreU(_) | MassVar::CentreV(_) => Dim::LENGTH,
            MassVar::BodyInertia(_) => Dim::INERTIA,
            MassVar::Inertia(k) => {
                let on = self.dynamics.as_ref().and_then(|d| d.inertias.get(k));
                inertia_on(on.map_or(Dim::NONE, |i| self.dims.coord(i.coord)))
            }
        };
        dim.scale(&self.units)
    }
}

impl DesignUnits {
    /// The core's own units: a design model that takes and gives the core's
    /// numbers.
    pub fn core() -> DesignUnits {
        DesignUnits(None)
    }

    /// The variables `values`, given in the model's units, in the core's.
    pub fn to_core(&self, values: Vec<f64>) -> Vec<f64> {
        match &self.0 {
            Some(u) => values.iter().zip(&u.vars).map(|(v, s)| v * s).collect(),
            None => values,
        }
    }

    /// The variables `values`, in the core's units, in the model's.
    pub fn from_core(&self, values: Vec<f64>) -> Vec<f64> {
        match &self.0 {
            Some(u) => values.iter().zip(&u.vars).map(|(v, s)| v / s).collect(),
            None => values,
        }
    }

    /// The evaluation `run` (of the variables and buffers these units were
    /// made for) in the model's units: values, derivatives, co-ordinates
    /// and extrema. Its report, and the slopes at position 1 that the
    /// design's next evaluation starts from, stay in the core's.
    pub fn in_model(&self, run: &mut DesignRun) {
        let Some(u) = &self.0 else { return };
        let (nq, nv) = (u.quantities.len(), u.vars.len());
        for row in run.values.chunks_exact_mut(nq.max(1)) {
            for (v, s) in row.iter_mut().zip(&u.quantities) {
                *v /= s;
            }
        }
        for block in run.gradient.chunks_exact_mut((nq * nv).max(1)) {
            for (row, s) in block.chunks_exact_mut(nv.max(1)).zip(&u.quantities) {
                derivatives(row, &u.vars, *s);
            }
        }
        for row in run.coords.chunks_exact_mut(u.coords.len().max(1)) {
            for (x, s) in row.iter_mut().zip(&u.coords) {
                *x /= s;
            }
        }
        for e in &mut run.extrema {
            let s = u.extrema.get(e.spec).copied().unwrap_or(1.0);
            e.value /= s;
            derivatives(&mut e.gradient, &u.vars, s);
        }
    }
}

/// One quantity's derivatives with respect to the variables of sizes `vars`
/// (`row`, in the core's units) in the model's: times the variable's size,
/// over the quantity's (`size`).
fn derivatives(row: &mut [f64], vars: &[f64], size: f64) {
    for (g, v) in row.iter_mut().zip(vars) {
        *g = *g * v / size;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_derivative_takes_the_variables_size_over_the_quantitys() {
        // d(x in mm)/d(phi in deg) = dx/dphi (m/rad) * (pi/180) / 1e-3; a length variable's, times 1e-3 / 1e-3.
        let degree = std::f64::consts::PI / 180.0;
        let mut row = [2.0, 3.0];
        derivatives(&mut row, &[degree, 1e-3], 1e-3);
        assert_eq!(row, [2.0 * degree / 1e-3, 3.0 * 1e-3 / 1e-3]);
        let sizes = Sizes { vars: vec![degree, 1e-3], quantities: vec![], coords: vec![], extrema: vec![] };
        let units = DesignUnits(Some(sizes));
        assert_eq!(units.to_core(vec![90.0, 250.0]), vec![90.0 * degree, 250.0 * 1e-3]);
        assert_eq!(units.from_core(vec![90.0 * degree, 0.25]), vec![90.0 * degree / degree, 0.25 / 1e-3]);
    }
}
