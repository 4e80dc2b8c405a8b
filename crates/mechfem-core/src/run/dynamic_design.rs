//! One dynamic design evaluated for an optimiser or a tolerance analysis:
//! the motion run with inverse dynamics (mode `DYN ANA`) at every
//! position, chosen quantities recorded with their design sensitivities
//! with respect to kinematic variables ([`DesignVar`]: prescribed values,
//! fixed co-ordinates) and to the mass model's numbers ([`MassVar`]:
//! masses, centres of mass, inertias).
//!
//! The kinematic quantities do not depend on the mass model (their
//! sensitivity to a mass variable is 0); the dynamic ones take theirs from
//! [`DynamicSensitivity`].

use super::design::{scale_starts, DesignRun};
use super::inverse::{DynamicSensitivity, InverseDynamics};
use super::kinematic::run;
use super::observe::{Observer, PositionView};
use super::record::Quantity;
use crate::dynamics::{Dynamics, MassVar};
use crate::error::{SolveError, Unsupported};
use crate::model::{Mechanism, State};
use crate::motion::Motion;
use crate::solver::{DesignVar, Params, Sensitivity, TransferOrder};

struct Recording<'a> {
    sens: Sensitivity,
    inverse: InverseDynamics,
    dynamic: DynamicSensitivity,
    motion: &'a Motion,
    quantities: &'a [Quantity],
    dynamic_wanted: bool,
    values: Vec<f64>,
    gradient: Vec<f64>,
    coords: Vec<f64>,
    failed: Option<SolveError>,
}

impl Observer for Recording<'_> {
    fn position(&mut self, v: &PositionView<'_>) {
        let mech = v.mech;
        let computed = self.sens.compute(mech, v.kin, v.state, TransferOrder::Second);
        if let Err(e) = &computed {
            self.failed.get_or_insert(e.clone());
        }
        scale_starts(&mut self.sens, mech, self.motion, v.index, false);
        let n_kin = self.sens.vars().len();
        let nv = self.dynamic.n_vars();
        let mut dynamic_ok = false;
        if self.dynamic_wanted {
            if let Err(e) = self.inverse.evaluate_checked(v) {
                self.failed.get_or_insert(e);
            }
            dynamic_ok = computed.is_ok() && self.dynamic.compute(v, &self.inverse, &self.sens);
        }
        for &q in self.quantities {
            if q.is_dynamic() {
                self.values.push(q.dynamic_value(mech, &self.inverse));
                for var in 0..nv {
                    let g = if dynamic_ok { self.dynamic.quantity(mech, &self.inverse, q, var) } else { f64::NAN };
                    self.gradient.push(g);
                }
            } else {
                self.values.push(q.value(v));
                for var in 0..nv {
                    let g = match (var < n_kin, computed.is_ok()) {
                        (true, true) => q.sensitivity(v, &self.sens, var),
                        (true, false) => f64::NAN,
                        (false, _) => 0.0,
                    };
                    self.gradient.push(g);
                }
            }
        }
        self.coords.extend_from_slice(&v.state.x);
    }

    fn transfer_order(&self) -> Option<TransferOrder> {
        Some(TransferOrder::Second)
    }
}

/// Runs `motion` from `state` (the design's kinematic values already in
/// it) with the mass and load model `dynamics` (the design's mass values
/// already in it), and records `quantities` and their derivatives with
/// respect to `vars` followed by `mass_vars`: the gradient of position p,
/// quantity k, variable v at `(p * quantities + k) * (vars + mass_vars) + v`.
/// `dynamics` is a model that passed [`Dynamics::check`] on `mech` with
/// other values of the mass variables. Fails when position 1 cannot be
/// computed, a variable is not in the model, or a dynamic result is not
/// finite.
#[allow(clippy::too_many_arguments)]
pub fn evaluate(
    mech: &Mechanism,
    state: &mut State,
    motion: &Motion,
    params: &Params,
    dynamics: &Dynamics,
    vars: &[DesignVar],
    mass_vars: &[MassVar],
    quantities: &[Quantity],
) -> Result<DesignRun, SolveError> {
    let unknown = SolveError::Unsupported(Unsupported::UnknownDesignVariable);
    let sens = Sensitivity::new(mech, vars).map_err(|_| unknown.clone())?;
    // The model's structure is the caller's checked one (its numbers are
    // the design's, any sign: bounds keep an optimiser's masses positive).
    let on_frames = dynamics.bodies.iter().all(|b| {
        mech.elements().get(b.element).is_some_and(|e| crate::dynamics::Frame::of(e.ty, e.coords()).is_some())
    });
    if !on_frames || mass_vars.iter().any(|m| !m.exists(dynamics)) {
        return Err(unknown);
    }
    let n = motion.steps + 1;
    let (nq, nv, nc) = (quantities.len(), vars.len() + mass_vars.len(), mech.n_coords());
    let mut rec = Recording {
        sens,
        inverse: InverseDynamics::new(mech, dynamics.clone()),
        dynamic: DynamicSensitivity::new(mech, vars.len(), mass_vars),
        motion,
        quantities,
        dynamic_wanted: quantities.iter().any(Quantity::is_dynamic),
        values: Vec::with_capacity(n * nq),
        gradient: Vec::with_capacity(n * nq * nv),
        coords: Vec::with_capacity(n * nc),
        failed: None,
    };
    let report = run(mech, state, Some(motion), params, &mut rec)?;
    if let Some(e) = rec.failed {
        return Err(e);
    }
    Ok(DesignRun {
        positions: report.positions,
        report,
        values: rec.values,
        gradient: rec.gradient,
        coords: rec.coords,
        extrema: Vec::new(),
        left_branch: None,
        slope_one: Vec::new(),
    })
}
