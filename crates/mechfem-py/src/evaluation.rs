//! What one evaluation of a design gives an optimiser ([`Evaluation`]): its
//! feasibility, the buffers' values and their exact gradients at every
//! position, and the extrema found ([`Extremum`]). `DesignModel` and
//! `DynamicDesignModel` return it; the Python models that wrap one (units,
//! a frame angle, free timing, a full turn) make a new one from it with
//! their own numbers, through the same constructor.

use mechfem_core::design::{DesignFailure, DesignRun, Extremum as FoundExtremum};
use mechfem_core::worded;
use mechfem_deck::{Compiled, DesignUnits};
use numpy::{PyArray1, PyArrayMethods};
use pyo3::prelude::*;

use crate::convert;
use crate::report::Report;

/// One evaluation of a design: `feasible`; `reason` (None when feasible)
/// and `reason_kind` (None, `"start"`, `"position_one"`, `"other_branch"`,
/// `"left_branch"` or `"stopped"`); `positions` computed; `position_one`
/// (the co-ordinates at position 1, None without); `report` (the run's,
/// None without positions); `values` (positions x buffers); `gradient`
/// (positions x buffers x variables); `extrema`.
#[pyclass(module = "mechfem._core", frozen, get_all)]
pub struct Evaluation {
    feasible: bool,
    reason: Option<String>,
    reason_kind: Option<String>,
    positions: usize,
    position_one: Option<Vec<f64>>,
    report: Option<Py<Report>>,
    values: Py<PyAny>,
    gradient: Py<PyAny>,
    extrema: Vec<Py<Extremum>>,
}

/// The arguments of [`Evaluation::new`] that make it again.
type EvaluationArgs = (
    bool,
    Option<String>,
    Option<String>,
    usize,
    Option<Vec<f64>>,
    Option<Py<Report>>,
    Py<PyAny>,
    Py<PyAny>,
    Vec<Py<Extremum>>,
);

#[pymethods]
impl Evaluation {
    /// An evaluation with these values (see the class).
    #[new]
    #[pyo3(signature = (feasible, reason, reason_kind, positions, position_one, report, values, gradient, extrema))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        feasible: bool,
        reason: Option<String>,
        reason_kind: Option<String>,
        positions: usize,
        position_one: Option<Vec<f64>>,
        report: Option<Py<Report>>,
        values: Py<PyAny>,
        gradient: Py<PyAny>,
        extrema: Vec<Py<Extremum>>,
    ) -> Evaluation {
        Evaluation { feasible, reason, reason_kind, positions, position_one, report, values, gradient, extrema }
    }

    /// The arguments of [`Evaluation::new`] that make it again.
    fn __getnewargs__(&self, py: Python<'_>) -> EvaluationArgs {
        (
            self.feasible,
            self.reason.clone(),
            self.reason_kind.clone(),
            self.positions,
            self.position_one.clone(),
            self.report.as_ref().map(|r| r.clone_ref(py)),
            self.values.clone_ref(py),
            self.gradient.clone_ref(py),
            self.extrema.iter().map(|x| x.clone_ref(py)).collect(),
        )
    }

    fn __repr__(&self) -> String {
        match &self.reason {
            None => format!("Evaluation(feasible, {} positions, {} extrema)", self.positions, self.extrema.len()),
            Some(why) => format!("Evaluation(infeasible: {why})"),
        }
    }
}

/// A buffer's value at an extremum of its reference: `spec` (which pair of
/// buffers), `after` (the position, 0-based, it lies after), `input`,
/// `reference` and `value` there, and `gradient` (by variable).
#[pyclass(module = "mechfem._core", frozen, get_all)]
#[derive(Debug, Clone)]
pub struct Extremum {
    spec: usize,
    after: usize,
    input: f64,
    reference: f64,
    value: f64,
    gradient: Vec<f64>,
}

#[pymethods]
impl Extremum {
    /// The extremum with these values (see the class).
    #[new]
    fn new(spec: usize, after: usize, input: f64, reference: f64, value: f64, gradient: Vec<f64>) -> Extremum {
        Extremum { spec, after, input, reference, value, gradient }
    }

    /// The arguments of [`Extremum::new`] that make it again.
    fn __getnewargs__(&self) -> (usize, usize, f64, f64, f64, Vec<f64>) {
        (self.spec, self.after, self.input, self.reference, self.value, self.gradient.clone())
    }

    fn __repr__(&self) -> String {
        format!("Extremum(spec={}, after={}, input={}, value={})", self.spec, self.after, self.input, self.value)
    }
}

impl From<&FoundExtremum> for Extremum {
    fn from(e: &FoundExtremum) -> Extremum {
        let FoundExtremum { spec, after, input, reference, value, ref gradient } = *e;
        Extremum { spec, after, input, reference, value, gradient: gradient.clone() }
    }
}

/// The evaluation of the compiled model `c` that gave `result`, in `units`,
/// its values `nq` buffers wide and its gradient `nv` variables wide: a
/// design that failed, or whose run stopped, is infeasible, said in the
/// model's words.
pub(crate) fn of_result(
    py: Python<'_>,
    c: &Compiled,
    units: &DesignUnits,
    result: Result<DesignRun, DesignFailure>,
    nq: usize,
    nv: usize,
) -> PyResult<Evaluation> {
    match result {
        Ok(mut run) => {
            units.in_model(&mut run);
            of_run(py, c, run, nq, nv)
        }
        Err(e) => {
            let (kind, why) = crate::design::reason(c, &e);
            infeasible(py, kind, why, nq, nv)
        }
    }
}

/// The evaluation of `run` (see [`of_result`]).
fn of_run(py: Python<'_>, c: &Compiled, run: DesignRun, nq: usize, nv: usize) -> PyResult<Evaluation> {
    let steps = c.motion.as_ref().map_or(0, |m| m.steps);
    let reason = run
        .report
        .stop
        .as_ref()
        .map(|s| worded::design_stopped(&c.mechanism, &c.names, &c.dynamics_lines, s.last_good, &s.error));
    let extrema = run.extrema.iter().map(|e| Py::new(py, Extremum::from(e))).collect::<PyResult<Vec<_>>>()?;
    Ok(Evaluation {
        feasible: reason.is_none(),
        reason_kind: reason.as_ref().map(|_| "stopped".to_string()),
        reason,
        positions: run.positions,
        position_one: run.coords.get(..c.mechanism.n_coords()).map(<[f64]>::to_vec),
        report: Some(Py::new(py, Report::of(py, &c.mechanism, &c.names, &c.dynamics_lines, &run.report, steps)?)?),
        values: convert::array2(py, run.values, run.positions, nq)?.unbind(),
        gradient: PyArray1::from_vec(py, run.gradient).reshape([run.positions, nq, nv])?.into_any().unbind(),
        extrema,
    })
}

/// An infeasible design without positions, of kind `kind` for the reason
/// `why`, `nq` buffers and `nv` variables wide.
pub(crate) fn infeasible(py: Python<'_>, kind: &str, why: String, nq: usize, nv: usize) -> PyResult<Evaluation> {
    Ok(Evaluation {
        feasible: false,
        reason: Some(why),
        reason_kind: Some(kind.to_string()),
        positions: 0,
        position_one: None,
        report: None,
        values: convert::array2(py, Vec::new(), 0, nq)?.unbind(),
        gradient: PyArray1::<f64>::zeros(py, 0, false).reshape([0, nq, nv])?.into_any().unbind(),
        extrema: Vec::new(),
    })
}
