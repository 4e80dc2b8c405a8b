//! Names and units for Python: the deck's units and named points as
//! dicts, and the numbers of a run converted from the core's units to the
//! deck's at the edge ([`mechfem_deck::Compiled::units`]). A deck without
//! UNITS passes every number unchanged.

use mechfem_core::{FormRef, Quantity};
use mechfem_deck::Compiled;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};

/// The deck's units: `length`, `angle`, `mass`, `force`, `time` to the
/// unit's symbol, or None where the deck declares none.
pub fn units<'py>(py: Python<'py>, c: &Compiled) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    for (kind, symbol) in c.units.fields() {
        d.set_item(kind, symbol)?;
    }
    Ok(d)
}

/// The named points: `x`, `y` (1-based co-ordinates) and `name`.
pub fn points<'py>(py: Python<'py>, c: &Compiled) -> PyResult<Bound<'py, PyList>> {
    let items = c
        .names
        .points
        .iter()
        .map(|(x, y, name)| {
            let d = PyDict::new(py);
            d.set_item("x", x + 1)?;
            d.set_item("y", y + 1)?;
            d.set_item("name", name)?;
            Ok(d)
        })
        .collect::<PyResult<Vec<_>>>()?;
    PyList::new(py, items)
}

/// Multiplies every `width`-long row of `values` by `scales` (nothing
/// when every scale is 1).
fn rows(values: &mut [f64], scales: &[f64]) {
    if scales.iter().all(|&s| s == 1.0) || scales.is_empty() {
        return;
    }
    for row in values.chunks_mut(scales.len()) {
        for (v, s) in row.iter_mut().zip(scales) {
            *v *= s;
        }
    }
}

/// The factor from the core's units to the deck's of each co-ordinate.
fn coord_scales(c: &Compiled) -> Vec<f64> {
    (0..c.mechanism.n_coords()).map(|i| 1.0 / c.dims.coord(i).scale(&c.units)).collect()
}

/// Co-ordinates (rows of N, one per position) in the deck's units.
pub fn coords(c: &Compiled, values: &mut [f64]) {
    if !c.units.is_identity() {
        rows(values, &coord_scales(c));
    }
}

/// Row values (prescribed, else dependent) in the deck's units.
pub fn row_values(c: &Compiled, values: &mut [f64], prescribed: bool) {
    if c.units.is_identity() {
        return;
    }
    let f = |k: usize| if prescribed { FormRef::Prescribed(k) } else { FormRef::Dependent(k) };
    let scales: Vec<f64> = (0..values.len()).map(|k| 1.0 / c.dims.form(f(k)).scale(&c.units)).collect();
    rows(values, &scales);
}

/// A run's table (column after column of `positions` values, each column
/// the quantity `quantities[k]`) and co-ordinates in the deck's units.
pub fn table(c: &Compiled, quantities: &[Quantity], table: &mut [f64], positions: usize, coords_: &mut [f64]) {
    if c.units.is_identity() {
        return;
    }
    for (q, column) in quantities.iter().zip(table.chunks_mut(positions.max(1))) {
        let k = c.out_scale(*q);
        if k != 1.0 {
            column.iter_mut().for_each(|v| *v *= k);
        }
    }
    coords(c, coords_);
}
