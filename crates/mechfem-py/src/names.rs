//! Names and units for Python: the deck's units as a dict, the warnings of
//! numbers that look like another unit, and the numbers of a run converted
//! from the core's units to the deck's at the edge ([`mechfem_deck::Compiled::units`]). A deck without
//! UNITS passes every number unchanged.

use mechfem_core::{FormRef, Quantity};
use mechfem_deck::Compiled;
use std::ffi::CString;

use pyo3::exceptions::PyUserWarning;
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// The deck's units: `length`, `angle`, `mass`, `force`, `time` to the
/// unit's symbol, or None where the deck declares none.
pub fn units<'py>(py: Python<'py>, c: &Compiled) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    for (kind, symbol) in c.units.fields() {
        d.set_item(kind, symbol)?;
    }
    Ok(d)
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
    (0..c.mechanism.n_coords()).map(|i| c.dims.coord(i).out_scale(&c.units)).collect()
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
    let scales: Vec<f64> = (0..values.len()).map(|k| c.dims.form(f(k)).out_scale(&c.units)).collect();
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

pyo3::create_exception!(
    _core,
    UnitWarning,
    PyUserWarning,
    "A number of a deck that looks as if it were written in another unit than the deck's (an angle of 720 where \
     angles are radians); the run goes on with the number as written."
);

/// Warns (a [`UnitWarning`], a Python `UserWarning`) of every number of the deck that looks
/// like the wrong unit ([`Compiled::warnings`]).
pub fn warn(py: Python<'_>, c: &Compiled) -> PyResult<()> {
    for w in &c.warnings {
        let text = CString::new(w.warning_text().replace('\0', " "))?;
        PyErr::warn(py, &py.get_type::<UnitWarning>(), &text, 1)?;
    }
    Ok(())
}

/// A run of deck text ([`crate::run::FullRun`]) in the deck's units:
/// its full layout, its buffers, its co-ordinates and the numbers of its
/// echo (the co-ordinates as given, the rows at position 1, the PARA
/// values it ran with), its report and what its integrator did.
pub fn full_run(c: &Compiled, r: &mut crate::run::FullRun) {
    if c.units.is_identity() {
        return;
    }
    r.report = c.report_as_written(&r.report);
    r.sim = r.sim.as_ref().map(|s| c.sim_as_written(s));
    let positions = r.positions;
    let layout = mechfem_core::Layout::full(&c.mechanism, c.dynamics.is_some()).quantities();
    r.table.scale_columns(layout.iter().map(|q| c.out_scale(*q)).collect());
    coords(c, &mut r.coords);
    let buffers: Vec<Quantity> = c.buffers.iter().map(|b| b.quantity).collect();
    table(c, &buffers, &mut r.buffers, positions, &mut []);
    coords(c, &mut r.given);
    let np = c.mechanism.n_prescribed().min(r.rows_at_1.len());
    let (prescribed, dependent) = r.rows_at_1.split_at_mut(np);
    row_values(c, prescribed, true);
    row_values(c, dependent, false);
    for (k, p) in r.para.iter_mut().enumerate() {
        if let Some(p) = p {
            *p *= c.dims.form(FormRef::Prescribed(k)).out_scale(&c.units);
        }
    }
}
