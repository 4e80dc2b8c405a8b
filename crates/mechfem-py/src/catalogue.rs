//! The facts the Python front would otherwise repeat: the element catalogue
//! (types, co-ordinates, slots, form parameters and what they measure) and
//! the solver's defaults and limits. Both are read from the core's and the
//! deck reader's own tables, so that a type or a default changes in one
//! place.

use mechfem_core::{ElementType, Params};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};

/// Every element type, in catalogue order, as a list of dicts: `type`
/// (`BIN`), `coordinates` (name and dimension per co-ordinate, deck order),
/// `slots` (`PP`: a point, `a`: an angle, `s`: a scalar) and `forms` (name
/// and dimension per form parameter), and `frame` (whether the element has
/// a frame that can carry a mass: MASS on it is allowed). Dimensions are `length`, `angle`,
/// `ratio` or `any` (the single co-ordinate element's, which is that of its
/// co-ordinate).
#[pyfunction]
pub fn catalogue(py: Python<'_>) -> PyResult<Bound<'_, PyList>> {
    let out = PyList::empty(py);
    for ty in ElementType::ALL {
        let d = PyDict::new(py);
        d.set_item("type", ty.name())?;
        let named = |names: &[&'static str], dims: &[mechfem_core::Dimension]| -> Vec<(&'static str, &'static str)> {
            names.iter().zip(dims).map(|(n, d)| (*n, d.name())).collect()
        };
        d.set_item("coordinates", named(ty.coord_names(), ty.coord_dimensions()))?;
        d.set_item("slots", ty.slots().iter().map(|s| s.letter()).collect::<String>())?;
        d.set_item("forms", named(ty.form_names(), ty.form_dimensions()))?;
        d.set_item("frame", mechfem_core::dynamics::has_frame(ty))?;
        out.append(d)?;
    }
    Ok(out)
}

/// The solver's defaults and the deck reader's limits, as `_core.DEFAULTS`:
/// `accuracy` (ACCURACY), `max_iter` (MAXITER), `max_halvings` (how often a
/// failing step is halved), `min_integration_tolerance` (the smallest
/// tolerance of a simulation's integrator), and the largest `max_iter_limit` (MAXITER) and
/// `max_steps` (TSTEPE) a deck may give.
pub fn defaults(py: Python<'_>) -> PyResult<Bound<'_, PyDict>> {
    let p = Params::default();
    let d = PyDict::new(py);
    d.set_item("accuracy", p.tol)?;
    d.set_item("max_iter", p.max_iter)?;
    d.set_item("max_halvings", p.max_halvings)?;
    d.set_item("min_integration_tolerance", mechfem_core::dynamics::Integration::MIN_TOLERANCE)?;
    d.set_item("max_iter_limit", mechfem_deck::MAX_ITER)?;
    d.set_item("max_steps", mechfem_deck::MAX_STEPS)?;
    Ok(d)
}
