//! A deck described without solving anything (`describe_deck_text`): what
//! it declares, as Python reads a deck into a `Mechanism` and a deck's
//! optimisation reads its OPTIMISE block. Typed objects owned by Rust with
//! getters; the elements, rows and co-ordinates are the echo's own classes
//! ([`crate::echo`]), the masses and loads [`crate::masses`]'. Numbers are
//! the deck's own, in its UNITS.

use std::path::PathBuf;

use mechfem_core::dynamics::Integrator;
use mechfem_core::InputMotion;
use mechfem_deck::ast::{LoadDefKind, MotionKind};
use mechfem_deck::Diagnostics;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};

use crate::echo::EchoCoordinate;
use crate::masses::EchoDynamics;
use crate::optimise_block::OptimiseBlock;
use crate::{convert, errors};

/// The motion of one input: `kind` `by` (MOV_RELE), `to` (MOV_ABSE),
/// `table` (MOV_FUNC), `free` (MOV_FREE) or `dynamic` (MOV_DYN), with its
/// `value` (delta, end, ds or the initial speed; None for a table), a
/// table's `rows` (`t value velocity acceleration`) and the `file` the deck
/// names.
#[pyclass(module = "mechfem._core", frozen, eq, get_all, from_py_object)]
#[derive(Debug, Clone, PartialEq)]
pub struct DeckInput {
    kind: &'static str,
    value: Option<f64>,
    rows: Option<Vec<[f64; 4]>>,
    file: Option<String>,
}

/// A deck's MOVEMENT block: `steps`, the time step `dt` and every input's
/// motion.
#[pyclass(module = "mechfem._core", frozen, eq, get_all, from_py_object)]
#[derive(Debug, Clone, PartialEq)]
pub struct DeckMotion {
    steps: usize,
    dt: f64,
    inputs: Vec<DeckInput>,
}

/// What a deck declares: its co-ordinates as given (`given`), elements,
/// prescribed and dependent rows with their FORM terms, NAMES, DOFs,
/// ACCURACY (`tol`) and MAXITER, motion (None without a MOVEMENT block),
/// storage requests, INTTOL (`inttol`), INTEGRATOR, STOPWHEN (`stop_when`:
/// buffer and value), mode, masses and loads (None for a KIN deck), units and
/// its OPTIMISE block ([`OptimiseBlock`]; None without one).
#[pyclass(module = "mechfem._core", frozen, get_all)]
pub struct DeckDescription {
    coordinates: Py<PyList>,
    elements: Py<PyList>,
    prescribed: Py<PyList>,
    dependent: Py<PyList>,
    names: Py<PyDict>,
    dofs: Vec<usize>,
    tol: f64,
    max_iter: usize,
    motion: Option<DeckMotion>,
    storage: Py<PyAny>,
    inttol: Option<(f64, f64)>,
    integrator: Option<&'static str>,
    stop_when: Option<(i64, f64)>,
    mode: &'static str,
    dynamics: Option<Py<EchoDynamics>>,
    optimise: Option<OptimiseBlock>,
    units: Py<PyDict>,
}

/// Reads and compiles the deck `text` without solving anything and returns
/// what it declares ([`DeckDescription`]).
#[pyfunction]
pub fn describe_deck_text(py: Python<'_>, text: &str, path: PathBuf, base_dir: PathBuf) -> PyResult<DeckDescription> {
    let parsed = py.detach(|| {
        let deck = mechfem_deck::parse_str(text, &path)?;
        let c = mechfem_deck::compile(&deck, &base_dir)?;
        Ok::<_, Diagnostics>((deck, c))
    });
    let (deck, c) = parsed.map_err(|d| errors::deck_error(py, &path, &d))?;
    let mech = &c.mechanism;
    // The deck's numbers as written, in its UNITS (crate::names).
    let (x, [prescribed, dependent]) = (c.coords_as_written(), c.rows_as_written());
    let (motion, dynamics) = (c.motion_as_written(), c.dynamics_as_written());
    let coordinates = (0..mech.n_coords()).map(|i| EchoCoordinate {
        number: i + 1,
        moving: mech.is_moving(i),
        given: x[i],
        adjusted: f64::NAN,
        name: None,
    });
    let motion = motion.as_ref().map(|m| {
        let file = |j: usize| {
            deck.movement.as_ref().and_then(|mv| {
                mv.motions.iter().find_map(|md| match &md.kind {
                    MotionKind::Function(f) if md.dof.value == j as i64 => Some(f.value.clone()),
                    _ => None,
                })
            })
        };
        let inputs = m
            .inputs
            .iter()
            .enumerate()
            .map(|(k, im)| {
                let (kind, value) = match im {
                    InputMotion::Relative { delta } => ("by", Some(*delta)),
                    InputMotion::Absolute { end } => ("to", Some(*end)),
                    InputMotion::Free { ds } => ("free", Some(*ds)),
                    InputMotion::Dynamic { v0 } => ("dynamic", Some(*v0)),
                    InputMotion::Table { .. } => ("table", None),
                };
                let rows = match im {
                    InputMotion::Table { rows } => Some(rows.clone()),
                    _ => None,
                };
                DeckInput { kind, value, rows, file: file(k + 1) }
            })
            .collect();
        DeckMotion { steps: m.steps, dt: m.dt, inputs }
    });
    // The LOADFUNC file of every load, in the order the loads were compiled (deck order).
    let files: Vec<Option<String>> = deck.dynamics.as_ref().map_or_else(Vec::new, |dy| {
        dy.loads
            .iter()
            .map(|l| match &l.kind {
                LoadDefKind::Function(f) => Some(f.value.clone()),
                _ => None,
            })
            .collect()
    });
    let movement = deck.movement.as_ref();
    Ok(DeckDescription {
        coordinates: PyList::new(py, coordinates)?.unbind(),
        elements: PyList::new(py, convert::echo_elements(&c, &[]))?.unbind(),
        prescribed: PyList::new(py, convert::echo_rows(&prescribed, &[]))?.unbind(),
        dependent: PyList::new(py, convert::echo_rows(&dependent, &[]))?.unbind(),
        names: crate::described_names::names(py, &c)?.unbind(),
        dofs: (0..mech.n_dof()).map(|j| mech.input_row(j) + 1).collect(),
        tol: c.units.as_written(mechfem_core::Dim::LENGTH, c.params.tol),
        max_iter: c.params.max_iter,
        motion,
        storage: convert::storage(py, &c)?.unbind(),
        // INTTOL as the deck gives it (None without: the tolerances are then ACCURACY's).
        inttol: movement.and_then(|m| m.inttol.as_ref()).map(|t| (t.rtol.value, t.atol.value)),
        integrator: movement.and_then(|m| m.integrator.as_ref()).map(|m| match m.value {
            Integrator::Auto => "auto",
            Integrator::Dop853 => "dop853",
            Integrator::Dopri5 => "dopri5",
            Integrator::Radau5 => "radau5",
        }),
        stop_when: movement.and_then(|m| m.stop_when.as_ref()).map(|s| (s.buffer.value, s.value.value)),
        mode: c.mode.name(),
        dynamics: dynamics.as_ref().map(|m| Py::new(py, EchoDynamics::of(m, &files))).transpose()?,
        optimise: c.optimise.as_ref().map(|o| OptimiseBlock::of(&c, o)),
        units: crate::names::units(py, &c)?.unbind(),
    })
}
