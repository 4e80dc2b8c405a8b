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
use mechfem_deck::{Compiled, DesignSetup};
use numpy::{PyArray1, PyArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::report::Report;
use crate::text::compile_text;
use crate::{convert, errors};

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
}

impl DesignModel {
    /// The design model of the compiled model `c`: `variables`, `buffers`
    /// and `extrema` as for [`DesignModel::new`] (a model built item by item
    /// comes here from `ModelBuilder.design`, deck text through `new`).
    pub(crate) fn of_compiled(
        c: Compiled,
        variables: &[(u8, usize)],
        buffers: &[u32],
        extrema: &[(u32, u32)],
    ) -> PyResult<DesignModel> {
        let setup = c.design_setup(variables, buffers, extrema).map_err(|e| errors::value_error(&e))?;
        Ok(DesignModel { compiled: c, setup, anchor: None, runs: 0 })
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
        DesignModel::of_compiled(c, &variables, &buffers, &extrema)
    }

    /// The design's values as the deck gives them.
    fn start(&self) -> Vec<f64> {
        let s = &self.compiled.state;
        self.setup
            .vars
            .iter()
            .map(|v| match *v {
                DesignVar::Row(r) => s.target[r],
                DesignVar::Fixed(i) => s.x[i],
            })
            .collect()
    }

    /// How many designs have been evaluated (mechanism runs).
    #[getter]
    fn runs(&self) -> usize {
        self.runs
    }

    /// Evaluates `values` as the start design, from the deck's co-ordinates
    /// (its XMOV estimates): the assembly branch of its position 1 is the
    /// branch of every later evaluation. A dict as of [`Self::evaluate`].
    fn start_at<'py>(&mut self, py: Python<'py>, values: Vec<f64>) -> PyResult<Bound<'py, PyDict>> {
        self.check(&values)?;
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
        self.dict(py, result)
    }

    /// Evaluates the design `values` on the start design's branch (the
    /// deck's own design unless [`Self::start_at`] chose another): a dict
    /// with `feasible`, `reason` (None when feasible) and `reason_kind`
    /// (None, `"position_one"`, `"other_branch"`, `"left_branch"` or
    /// `"stopped"`), `positions`, `position_one` (its co-ordinates at
    /// position 1, None when it has none), `values` (positions x buffers),
    /// `gradient` (positions x buffers x variables) and `extrema` (dicts
    /// with `spec`, `after`, `input`, `reference`, `value`, `gradient`).
    fn evaluate<'py>(&mut self, py: Python<'py>, values: Vec<f64>) -> PyResult<Bound<'py, PyDict>> {
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
        let design = self.design();
        let result = py.detach(|| design.evaluate(anchor, &values));
        self.runs += 1;
        self.dict(py, result)
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

    /// The dict of [`DesignModel::evaluate`] for an evaluation.
    fn dict<'py>(&self, py: Python<'py>, result: Result<DesignRun, DesignFailure>) -> PyResult<Bound<'py, PyDict>> {
        let c = &self.compiled;
        let motion = c.motion.as_ref().expect("checked in new");
        let (nq, nv) = (self.setup.quantities.len(), self.setup.vars.len());
        let d = PyDict::new(py);
        match result {
            Ok(run) => {
                let stop = run.report.stop.as_ref();
                let reason = stop
                    .map(|s| worded::design_stopped(&c.mechanism, &c.names, &c.dynamics_lines, s.last_good, &s.error));
                let at_1 = run.coords.get(..c.mechanism.n_coords()).map(<[f64]>::to_vec);
                d.set_item("position_one", at_1)?;
                d.set_item("feasible", reason.is_none())?;
                d.set_item("reason_kind", reason.as_ref().map(|_| "stopped"))?;
                d.set_item("reason", reason)?;
                d.set_item("positions", run.positions)?;
                d.set_item(
                    "report",
                    Report::of(py, &c.mechanism, &c.names, &c.dynamics_lines, &run.report, motion.steps)?,
                )?;
                d.set_item("values", convert::array2(py, run.values, run.positions, nq)?)?;
                let g = PyArray1::from_vec(py, run.gradient).reshape([run.positions, nq, nv])?;
                d.set_item("gradient", g)?;
                let found = run
                    .extrema
                    .iter()
                    .map(|e| {
                        let x = PyDict::new(py);
                        x.set_item("spec", e.spec)?;
                        x.set_item("after", e.after)?;
                        x.set_item("input", e.input)?;
                        x.set_item("reference", e.reference)?;
                        x.set_item("value", e.value)?;
                        x.set_item("gradient", e.gradient.clone())?;
                        Ok(x)
                    })
                    .collect::<PyResult<Vec<_>>>()?;
                d.set_item("extrema", found)?;
            }
            Err(e) => {
                let (kind, why) = reason(c, &e);
                return self.failed(py, kind, why);
            }
        }
        Ok(d)
    }

    /// The dict of an infeasible design without positions.
    fn failed<'py>(&self, py: Python<'py>, kind: &str, why: String) -> PyResult<Bound<'py, PyDict>> {
        infeasible(py, kind, why, self.setup.quantities.len(), self.setup.vars.len())
    }
}

/// The dict of an infeasible design without positions, `nq` quantities and
/// `nv` variables wide (a kinematic or a dynamic design alike).
pub(crate) fn infeasible<'py>(
    py: Python<'py>,
    kind: &str,
    why: String,
    nq: usize,
    nv: usize,
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("feasible", false)?;
    d.set_item("reason", why)?;
    d.set_item("reason_kind", kind)?;
    d.set_item("positions", 0)?;
    d.set_item("position_one", py.None())?;
    d.set_item("report", py.None())?;
    d.set_item("values", convert::array2(py, Vec::new(), 0, nq)?)?;
    d.set_item("gradient", PyArray1::<f64>::zeros(py, 0, false).reshape([0, nq, nv])?)?;
    d.set_item("extrema", Vec::<Bound<'py, PyDict>>::new())?;
    Ok(d)
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
