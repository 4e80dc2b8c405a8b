//! The numbers of the mass model a designer may vary: what balancing and
//! the dynamic design sensitivities are taken with respect to.

use super::Dynamics;

/// A design variable of the mass model (indices 0-based into the lists of
/// [`Dynamics`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum MassVar {
    /// The mass of body b (deck `MASS`, its m).
    Mass(usize),
    /// The centre of mass of body b along its frame's u-axis.
    CentreU(usize),
    /// The centre of mass of body b along its frame's v-axis.
    CentreV(usize),
    /// The moment of inertia of body b about its centre of mass.
    BodyInertia(usize),
    /// The mass of point mass k (deck `PMASS`).
    PointMass(usize),
    /// The moment of inertia of rotational inertia k (deck `INERTIA`).
    Inertia(usize),
}

impl MassVar {
    /// Whether the item it names exists in `model`.
    pub fn exists(self, model: &Dynamics) -> bool {
        match self {
            MassVar::Mass(b) | MassVar::CentreU(b) | MassVar::CentreV(b) | MassVar::BodyInertia(b) => {
                b < model.bodies.len()
            }
            MassVar::PointMass(k) => k < model.point_masses.len(),
            MassVar::Inertia(k) => k < model.inertias.len(),
        }
    }

    /// Its value in `model` (NaN if the item does not exist).
    pub fn value(self, model: &Dynamics) -> f64 {
        let body = |b: usize| model.bodies.get(b);
        let v = match self {
            MassVar::Mass(b) => body(b).map(|b| b.mass),
            MassVar::CentreU(b) => body(b).map(|b| b.u),
            MassVar::CentreV(b) => body(b).map(|b| b.v),
            MassVar::BodyInertia(b) => body(b).map(|b| b.inertia),
            MassVar::PointMass(k) => model.point_masses.get(k).map(|p| p.mass),
            MassVar::Inertia(k) => model.inertias.get(k).map(|i| i.inertia),
        };
        v.unwrap_or(f64::NAN)
    }

    /// Sets its value in `model` (nothing if the item does not exist).
    pub fn set(self, model: &mut Dynamics, value: f64) {
        let slot = match self {
            MassVar::Mass(b) => model.bodies.get_mut(b).map(|b| &mut b.mass),
            MassVar::CentreU(b) => model.bodies.get_mut(b).map(|b| &mut b.u),
            MassVar::CentreV(b) => model.bodies.get_mut(b).map(|b| &mut b.v),
            MassVar::BodyInertia(b) => model.bodies.get_mut(b).map(|b| &mut b.inertia),
            MassVar::PointMass(k) => model.point_masses.get_mut(k).map(|p| &mut p.mass),
            MassVar::Inertia(k) => model.inertias.get_mut(k).map(|i| &mut i.inertia),
        };
        if let Some(s) = slot {
            *s = value;
        }
    }
}
