//! A compiled model kept by Python ([`Model`]): deck text or a deck file is
//! read and compiled once, and run again with other prescribed values,
//! fixed co-ordinates or start values without any text written or parsed.

use std::path::PathBuf;
use std::sync::Arc;

use mechfem_deck::{Change, Compiled};
use pyo3::prelude::*;

use crate::run::{Run, Shared};
use crate::text::{compile_text, run_compiled};
use crate::{cache, errors};

/// A deck compiled once, to be run many times: `Model(text, path, base_dir)`
/// compiles deck text (named `path` in messages; MOV_FUNC files are read
/// from `base_dir`), `Model.from_path(path)` a deck file.
#[pyclass(module = "mechfem._core", frozen)]
pub struct Model {
    compiled: Compiled,
    path: PathBuf,
    /// What every run holds alike, converted for Python once.
    shared: Shared,
}

#[pymethods]
impl Model {
    #[new]
    fn new(py: Python<'_>, text: &str, path: PathBuf, base_dir: PathBuf) -> PyResult<Model> {
        let compiled =
            py.detach(|| compile_text(text, &path, &base_dir)).map_err(|d| errors::deck_error(py, &path, &d))?;
        Model::kept(py, compiled, path)
    }

    /// The deck file at `path`, compiled (or taken from the decks kept by `run_deck`).
    #[staticmethod]
    fn from_path(py: Python<'_>, path: PathBuf) -> PyResult<Model> {
        let (compiled, _) = py.detach(|| cache::load(&path)).map_err(|d| errors::deck_error(py, &path, &d))?;
        Model::kept(py, Arc::unwrap_or_clone(compiled), path)
    }

    /// Number of co-ordinates.
    #[getter]
    fn n_coords(&self) -> usize {
        self.compiled.mechanism.n_coords()
    }

    /// The compiled model in full (Rust's `Debug` text): two models with
    /// the same text compute the same numbers, for comparing a model built
    /// item by item with the one its deck text compiles to.
    fn fingerprint(&self) -> String {
        format!("{:?}", self.compiled)
    }

    /// Number of prescribed rows.
    #[getter]
    fn n_prescribed(&self) -> usize {
        self.compiled.mechanism.n_prescribed()
    }

    /// Runs a copy of the model with `changes` made, each `(kind, number,
    /// value)` as for `run_deck_variants` (kind 0: co-ordinate `number`
    /// gets `value`, its XFIX or XMOV value; kind 1: prescribed row
    /// `number`, its PARA value), and returns what `run_deck_text` returns
    /// for deck text that says so. `motion`, `progress`, `order` and
    /// `memory_limit` are `run_deck_text`'s.
    #[pyo3(signature = (changes=Vec::new(), motion=true, progress=None, order=Some(2), memory_limit=u64::MAX))]
    fn run(
        &self,
        py: Python<'_>,
        changes: Vec<(u8, usize, f64)>,
        motion: bool,
        progress: Option<Py<PyAny>>,
        order: Option<u8>,
        memory_limit: u64,
    ) -> PyResult<Run> {
        let changes = changes.into_iter().map(|(kind, number, value)| Change::of_kind(kind, number, value));
        let changes = changes.collect::<Result<Vec<_>, _>>().map_err(|e| errors::value_error(&e))?;
        let numbers = self.compiled.numbers(&changes).map_err(|e| errors::change_error(&e))?;
        let text = (&self.compiled, &self.shared);
        run_compiled(py, text, numbers, &self.path, motion, progress, order, memory_limit)
    }
}

impl Model {
    /// A model kept for Python: its runs share what every run holds alike.
    pub fn kept(py: Python<'_>, compiled: Compiled, path: PathBuf) -> PyResult<Model> {
        let shared = Shared::new(py, &compiled)?;
        Ok(Model { compiled, path, shared })
    }
}
