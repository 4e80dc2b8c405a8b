//! The TOLERANCE block of a deck evaluated: the design sensitivities of
//! every BUFTOL's buffer to every toleranced dimension at every position,
//! from one run of [`mechfem_core::design::evaluate`], in the deck's units.
//! The bands themselves (worst case, root sum of squares, shares) are
//! Python's arithmetic on these (`mechfem.bands`).

use std::path::PathBuf;

use mechfem_core::design::evaluate;
use mechfem_core::{dynamic_design, DesignVar, Dim, FormRef, Quantity};
use mechfem_deck::Compiled;
use numpy::PyArray1;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::errors;
use crate::text::compile_text;

/// The kind of a toleranced dimension.
fn dim_of(c: &Compiled, var: DesignVar) -> Dim {
    match var {
        DesignVar::Row(r) => c.dims.form(FormRef::Prescribed(r)),
        DesignVar::Fixed(i) => c.dims.coord(i),
    }
}

/// The TOLERANCE block of the deck `text` (named `path`, its files read
/// from `base_dir`) evaluated, or None when the deck has none. A dict:
/// `dims` `(kind, number, t, line)` (kind 0 a fixed co-ordinate, 1 a
/// prescribed row; deck numbering; t in the deck's units), `bands`
/// `(source, b, line)`, `positions`, `inputs` (positions x DOFs),
/// `values` (positions x bands) and `gradient` (positions x bands x dims),
/// flat and row-major, in the deck's units; `labels` `(label, unit)` of
/// each band's buffer, `dim_units` and `input_units` the units of the
/// dimensions and inputs ("" without UNITS).
#[pyfunction]
pub fn deck_tolerance<'py>(
    py: Python<'py>,
    text: &str,
    path: PathBuf,
    base_dir: PathBuf,
) -> PyResult<Option<Bound<'py, PyDict>>> {
    let c = py.detach(|| compile_text(text, &path, &base_dir)).map_err(|d| errors::deck_error(py, &path, &d))?;
    let (Some(tol), Some(motion)) = (&c.tolerance, &c.motion) else { return Ok(None) };
    let vars: Vec<DesignVar> = tol.dims.iter().map(|d| d.var).collect();
    let source = |number: u32| c.buffers.iter().find(|b| b.number == number).map(|b| b.quantity);
    let mut quantities: Vec<Quantity> = tol.bands.iter().filter_map(|b| source(b.source)).collect();
    let nb = quantities.len();
    let nj = c.mechanism.n_dof();
    quantities.extend((0..nj).map(Quantity::Input));
    let mut state = c.state.clone();
    // A band of a result of the dynamics takes the sensitivities of inverse dynamics.
    let dynamic = c.dynamics.as_ref().filter(|_| quantities.iter().any(Quantity::is_dynamic));
    let run = py
        .detach(|| match dynamic {
            Some(d) => {
                dynamic_design::evaluate(&c.mechanism, &mut state, motion, &c.params, d, &vars, &[], &quantities)
            }
            None => evaluate(&c.mechanism, &mut state, motion, &c.params, &vars, &quantities, &[]),
        })
        .map_err(|e| {
            let mut at = c.state.clone();
            errors::position_one_error(py, &c.mechanism, &c.dynamics_lines, &mut at, &c.error_as_written(&e))
        })?;
    let (nq, nv) = (quantities.len(), vars.len());
    let q_scale: Vec<f64> = quantities.iter().map(|&q| c.out_scale(q)).collect();
    let v_scale: Vec<f64> = vars.iter().map(|&v| dim_of(&c, v).out_scale(&c.units)).collect();
    let mut values = Vec::with_capacity(run.positions * nb);
    let mut inputs = Vec::with_capacity(run.positions * nj);
    let mut gradient = Vec::with_capacity(run.positions * nb * nv);
    for p in 0..run.positions {
        for k in 0..nq {
            let value = run.values[p * nq + k] * q_scale[k];
            if k >= nb {
                inputs.push(value);
                continue;
            }
            values.push(value);
            for v in 0..nv {
                gradient.push(run.gradient[(p * nq + k) * nv + v] * q_scale[k] / v_scale[v]);
            }
        }
    }
    let dims: Vec<(u8, usize, f64, usize)> = tol
        .dims
        .iter()
        .zip(&v_scale)
        .map(|(d, s)| match d.var {
            DesignVar::Fixed(i) => (0, i + 1, d.t * s, d.line),
            DesignVar::Row(r) => (1, r + 1, d.t * s, d.line),
        })
        .collect();
    let bands: Vec<(u32, u32, usize)> = tol.bands.iter().map(|b| (b.source, b.buffer, b.line)).collect();
    let labels: Vec<(String, String)> = tol
        .bands
        .iter()
        .filter_map(|b| c.buffers.iter().find(|x| x.number == b.source))
        .map(|b| (c.label(b), c.unit(b)))
        .collect();
    let dim_units: Vec<String> = vars.iter().map(|&v| dim_of(&c, v).symbol(&c.units)).collect();
    let input_units: Vec<String> = (0..nj).map(|j| c.dims.input(&c.mechanism, j).symbol(&c.units)).collect();
    let d = PyDict::new(py);
    d.set_item("labels", labels)?;
    d.set_item("dim_units", dim_units)?;
    d.set_item("input_units", input_units)?;
    d.set_item("dims", dims)?;
    d.set_item("bands", bands)?;
    d.set_item("positions", run.positions)?;
    d.set_item("dofs", nj)?;
    d.set_item("inputs", PyArray1::from_vec(py, inputs))?;
    d.set_item("values", PyArray1::from_vec(py, values))?;
    d.set_item("gradient", PyArray1::from_vec(py, gradient))?;
    Ok(Some(d))
}
