//! A compiled deck kept for an optimiser: [`DesignModel`] evaluates one
//! design after another ([`mechfem_core::design::Design`]), each on the
//! assembly branch of the start design, whatever was evaluated before, so
//! that a design's values never depend on the order of evaluation. A design
//! that cannot be assembled on that branch, whose motion leaves it, or whose
//! motion stops (a limit position) is returned as infeasible with the
//! reason, never raised.

use std::path::PathBuf;

use mechfem_core::design::{Anchor, Design, DesignFailure, DesignRun};
use mechfem_core::worded;
use mechfem_core::DesignVar;
use mechfem_deck::{Compiled, DesignSetup, DesignUnits};
use pyo3::prelude::*;

use crate::errors;
use crate::evaluation::{self, Evaluation};
use crate::text::compile_text;

/// A deck, its design variables, the buffers an objective reads and the
/// extrema it takes them at.
#[pyclass(module = "mechfem._core")]
pub struct DesignModel {
    compiled: Compiled,
    /// The design variables, the quantities read and the extrema.
    setup: DesignSetup,
    /// The start design: its branch and position 1, once evaluated, or why
    /// it could not be.
    anchor: Option<Result<Anchor, String>>,
    runs: usize,
    /// The units its variables and results are in: the model's, or the
    /// core's.
    units: DesignUnits,
}

impl DesignModel {
    /// The design model of the compiled model `c`: `variables`, `buffers`
    /// and `extrema` as for [`DesignModel::new`] (a model built item by item
    /// comes here from `ModelBuilder.design`, deck text through `new`); in
    /// the model's units when `in_model_units`.
    pub(crate) fn of_compiled(
        c: Compiled,
        variables: &[(u8, usize)],
        buffers: &[u32],
        extrema: &[(u32, u32)],
        in_model_units: bool,
    ) -> PyResult<DesignModel> {
        let setup = c.design_setup(variables, buffers, extrema).map_err(|e| errors::value_error(&e))?;
        let units = if in_model_units { c.design_units(&setup) } else { DesignUnits::core() };
        Ok(DesignModel { compiled: c, setup, anchor: None, runs: 0, units })
    }
}

#[pymethods]
impl DesignModel {
    /// Compiles the deck `text` (named `path`, its files read from
    /// `base_dir`). `variables` are `(kind, number)` in the deck's
    /// numbering: kind 0 a fixed co-ordinate, 1 a prescribed row;
    /// `buffers` the buffer numbers evaluated; `extrema` pairs of buffer
    /// numbers `(b, bref)`: b wherever bref has an extremum.
    #[new]
    fn new(
        py: Python<'_>,
        text: &str,
        path: PathBuf,
        base_dir: PathBuf,
        variables: Vec<(u8, usize)>,
        buffers: Vec<u32>,
        extrema: Vec<(u32, u32)>,
    ) -> PyResult<DesignModel> {
        let c = py.detach(|| compile_text(text, &path, &base_dir)).map_err(|d| errors::deck_error(py, &path, &d))?;
        DesignModel::of_compiled(c, &variables, &buffers, &extrema, false)
    }

    /// The design's values as the deck gives them.
    fn start(&self) -> Vec<f64> {
        let s = &self.compiled.state;
        let values: Vec<f64> = self
            .setup
            .vars
            .iter()
            .map(|v| match *v {
                DesignVar::Row(r) => s.target[r],
                DesignVar::Fixed(i) => s.x[i],
            })
            .collect();
        self.units.from_core(values)
    }

    /// How many designs have been evaluated (mechanism runs).
    #[getter]
    fn runs(&self) -> usize {
        self.runs
    }

    /// Evaluates `values` as the start design, from the deck's co-ordinates
    /// (its XMOV estimates): the assembly branch of its position 1 is the
    /// branch of every later evaluation. An [`Evaluation`] as of [`Self::evaluate`].
    fn start_at(&mut self, py: Python<'_>, values: Vec<f64>) -> PyResult<Evaluation> {
        self.check(&values)?;
        let values = self.units.to_core(values);
        let design = self.design();
        let result = py.detach(|| design.start(&values));
        self.runs += 1;
        let result = match result {
            Ok((run, anchor)) => {
                self.anchor = Some(Ok(anchor));
                Ok(run)
            }
            Err(e) => {
                self.anchor = Some(Err(reason(&self.compiled, &e).1));
                Err(e)
            }
        };
        self.evaluation(py, result)
    }

    /// Evaluates the design `values` on the start design's branch (the
    /// deck's own design unless [`Self::start_at`] chose another): its
    /// [`Evaluation`].
    fn evaluate(&mut self, py: Python<'_>, values: Vec<f64>) -> PyResult<Evaluation> {
        self.check(&values)?;
        if self.anchor.is_none() {
            let start = self.start();
            let d = self.start_at(py, start.clone())?;
            // The deck's own design evaluated again would be the same run.
            if start == values {
                return Ok(d);
            }
        }
        let Some(Ok(anchor)) = &self.anchor else {
            let why = match &self.anchor {
                Some(Err(why)) => why.clone(),
                _ => unreachable!("set by start_at"),
            };
            return self.failed(py, "start", worded::infeasible_start(&why));
        };
        let values = self.units.to_core(values);
        let design = self.design();
        let result = py.detach(|| design.evaluate(anchor, &values));
        self.runs += 1;
        self.evaluation(py, result)
    }
}

impl DesignModel {
    fn check(&self, values: &[f64]) -> PyResult<()> {
        self.setup.check(values).map_err(|e| errors::value_error(&e))
    }

    fn design(&self) -> Design<'_> {
        let c = &self.compiled;
        Design {
            mech: &c.mechanism,
            base: &c.state,
            motion: c.motion.as_ref().expect("checked in new"),
            params: &c.params,
            vars: &self.setup.vars,
            quantities: &self.setup.quantities,
            extrema: &self.setup.extrema,
        }
    }

    /// The [`Evaluation`] of [`DesignModel::evaluate`] for an evaluation.
    fn evaluation(&self, py: Python<'_>, result: Result<DesignRun, DesignFailure>) -> PyResult<Evaluation> {
        let (nq, nv) = (self.setup.quantities.len(), self.setup.vars.len());
        evaluation::of_result(py, &self.compiled, &self.units, result, nq, nv)
    }

    /// An infeasible design without positions.
    fn failed(&self, py: Python<'_>, kind: &str, why: String) -> PyResult<Evaluation> {
        evaluation::infeasible(py, kind, why, self.setup.quantities.len(), self.setup.vars.len())
    }
}

/// The kind of a failure (see [`DesignModel::evaluate`]) and its words.
pub(crate) fn reason(c: &Compiled, e: &DesignFailure) -> (&'static str, String) {
    worded::design_failure(&c.mechanism, &c.names, &c.dynamics_lines, e)
}

/// The deck `text` (named `path` in messages) of the design with the PARA
/// values of `rows` and the XFIX or XMOV values of `coords` replaced
/// (`(number, value)` in the deck's numbering), in mode `KIN ANA` without
/// its OPTIMISE block, its MOV_FUNC files named from `file_dir` when given:
/// see [`mechfem_deck::rewrite::design_deck`]. A deck
/// that does not parse raises `DeckError`.
#[pyfunction]
#[pyo3(signature = (text, path, rows, coords, file_dir=None))]
pub fn optimised_deck_text(
    py: Python<'_>,
    text: &str,
    path: PathBuf,
    rows: Vec<(usize, f64)>,
    coords: Vec<(usize, f64)>,
    file_dir: Option<PathBuf>,
) -> PyResult<String> {
    mechfem_deck::rewrite::design_deck(text, &path, &rows, &coords, file_dir.as_deref())
        .map_err(|d| errors::deck_error(py, &path, &d))
}
