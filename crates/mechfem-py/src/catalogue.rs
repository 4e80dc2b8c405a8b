//! The facts the Python front would otherwise repeat: the element catalogue
//! (types, co-ordinates, slots, form parameters and what they measure) and
//! the solver's defaults and limits. Both are read from the core's and the
//! deck reader's own tables, so that a type or a default changes in one
//! place; Python reads them as typed objects with getters.

use mechfem_core::{ElementType, Params};
use pyo3::prelude::*;

/// One element type of the catalogue. Dimensions are `length`, `angle`,
/// `ratio` or `any` (the single co-ordinate element's, which is that of
/// its co-ordinate).
#[pyclass(module = "mechfem._core", name = "ElementKind", frozen, eq, get_all, from_py_object)]
#[derive(Debug, Clone, PartialEq)]
pub struct ElementKind {
    /// The deck's three-letter name (`BIN`).
    #[pyo3(name = "type")]
    kind: &'static str,
    /// Each co-ordinate's name and dimension, in deck order.
    coordinates: Vec<(&'static str, &'static str)>,
    /// The co-ordinates as a named model gives them: `P` a point (x, y),
    /// `a` an angle, `s` a scalar.
    slots: String,
    /// Each form parameter's deck name and dimension.
    forms: Vec<(&'static str, &'static str)>,
    /// Whether the element has a frame that can carry a mass.
    frame: bool,
}

/// Every element type, in catalogue order.
#[pyfunction]
pub fn catalogue() -> Vec<ElementKind> {
    let named = |names: &[&'static str], dims: &[mechfem_core::Dimension]| -> Vec<(&'static str, &'static str)> {
        names.iter().zip(dims).map(|(n, d)| (*n, d.name())).collect()
    };
    ElementType::ALL
        .iter()
        .map(|ty| ElementKind {
            kind: ty.name(),
            coordinates: named(ty.coord_names(), ty.coord_dimensions()),
            slots: ty.slots().iter().map(|s| s.letter()).collect(),
            forms: named(ty.form_names(), ty.form_dimensions()),
            frame: mechfem_core::dynamics::has_frame(*ty),
        })
        .collect()
}

/// The solver's defaults and the deck reader's limits (`_core.DEFAULTS`).
#[pyclass(module = "mechfem._core", frozen, get_all)]
pub struct Defaults {
    /// How closely Newton meets the prescribed values (ACCURACY).
    accuracy: f64,
    /// Newton iterations per position (MAXITER).
    max_iter: usize,
    /// How often a failing step is halved.
    max_halvings: u32,
    /// The smallest tolerance of a simulation's integrator.
    min_integration_tolerance: f64,
    /// The largest MAXITER a deck may give.
    max_iter_limit: i64,
    /// The largest TSTEPE a deck may give.
    max_steps: i64,
}

/// The solver's defaults and the deck reader's limits.
pub fn defaults() -> Defaults {
    let p = Params::default();
    Defaults {
        accuracy: p.tol,
        max_iter: p.max_iter,
        max_halvings: p.max_halvings,
        min_integration_tolerance: mechfem_core::dynamics::Integration::MIN_TOLERANCE,
        max_iter_limit: mechfem_deck::MAX_ITER,
        max_steps: mechfem_deck::MAX_STEPS,
    }
}
