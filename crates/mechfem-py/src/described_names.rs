//! The names of a deck's NAMES block as `describe_deck_text` hands them to
//! Python's deck reader (`Mechanism.from_deck`): named points with their
//! 1-based co-ordinates, and the names of co-ordinates, elements, prescribed
//! rows and dependent form parameters by number (None where unnamed).

use mechfem_deck::Compiled;
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// `{"points": [(x, y, name)], "coordinates": [...], "elements": [...],
/// "prescribed": [...], "dependent": [...]}`.
pub fn names<'py>(py: Python<'py>, c: &Compiled) -> PyResult<Bound<'py, PyDict>> {
    let n = &c.names;
    let d = PyDict::new(py);
    let points: Vec<(usize, usize, &str)> = n.points.iter().map(|(x, y, name)| (x + 1, y + 1, name.as_str())).collect();
    d.set_item("points", points)?;
    d.set_item("coordinates", &n.coordinates)?;
    d.set_item("elements", &n.elements)?;
    d.set_item("prescribed", &n.prescribed)?;
    d.set_item("dependent", &n.dependent)?;
    Ok(d)
}
