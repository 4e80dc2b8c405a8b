//! What a run did, as Python reads it (`Run.report`, `Check.adjust`): the
//! core's adjustment of position 1, the limit positions met and why a motion
//! stopped, read through getters, with positions in the deck's 1-based
//! numbering. Each is picklable (`__getnewargs__`) and compares by value.

use mechfem_core::{AdjustInfo, LimitKind, LimitPosition, Mechanism, Names, RunReport};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyList;

use crate::errors;

/// The Newton adjustment of the given co-ordinates that makes position 1.
#[pyclass(module = "mechfem._core", frozen, from_py_object)]
#[derive(Debug, Clone, PartialEq)]
pub struct Adjust(AdjustInfo);

impl Adjust {
    /// The core's adjustment.
    pub fn of(a: &AdjustInfo) -> Adjust {
        Adjust(a.clone())
    }
}

#[pymethods]
impl Adjust {
    /// The adjustment with these numbers.
    #[new]
    fn new(iterations: usize, stages: usize, initial_deformations: Vec<f64>, residual: f64) -> Adjust {
        Adjust(AdjustInfo { iterations, initial_deformations, residual, stages })
    }

    /// The arguments of [`Adjust::new`] that make it again.
    fn __getnewargs__(&self) -> (usize, usize, Vec<f64>, f64) {
        (self.0.iterations, self.0.stages, self.0.initial_deformations.clone(), self.0.residual)
    }

    /// Equal adjustments have equal numbers.
    fn __eq__(&self, other: &Bound<'_, PyAny>) -> bool {
        other.cast::<Adjust>().is_ok_and(|o| *o.get() == *self)
    }

    /// Every number, as Python writes a call.
    fn __repr__(&self) -> String {
        let a = &self.0;
        format!(
            "Adjust(iterations={}, stages={}, initial_deformations={:?}, residual={:?})",
            a.iterations, a.stages, a.initial_deformations, a.residual
        )
    }

    /// Newton iterations in all.
    #[getter]
    fn iterations(&self) -> usize {
        self.0.iterations
    }

    /// Continuation stages (1 when plain Newton converged).
    #[getter]
    fn stages(&self) -> usize {
        self.0.stages
    }

    /// Per prescribed row: its value at the given co-ordinates minus the
    /// prescribed value.
    #[getter]
    fn initial_deformations(&self) -> Vec<f64> {
        self.0.initial_deformations.clone()
    }

    /// The largest deformation after the adjustment.
    #[getter]
    fn residual(&self) -> f64 {
        self.0.residual
    }
}

/// Python's word for a kind of limit position.
fn kind_word(kind: LimitKind) -> &'static str {
    match kind {
        LimitKind::NearZero => "near_zero",
        LimitKind::InputLimit => "input_limit",
        LimitKind::Passed => "passed",
    }
}

/// A limit position met during the motion, located between two positions.
#[pyclass(module = "mechfem._core", frozen, from_py_object)]
#[derive(Debug, Clone, PartialEq)]
pub struct Limit(LimitPosition);

#[pymethods]
impl Limit {
    /// The limit position with these values (`after` 1-based).
    #[new]
    fn new(kind: &str, after: usize, inputs: Vec<f64>, coords: Vec<f64>, det: f64) -> PyResult<Limit> {
        let kind = [LimitKind::NearZero, LimitKind::InputLimit, LimitKind::Passed]
            .into_iter()
            .find(|k| kind_word(*k) == kind)
            .ok_or_else(|| PyValueError::new_err(kind.to_owned()))?;
        Ok(Limit(LimitPosition { kind, after: after.saturating_sub(1), inputs, coords, det }))
    }

    /// The arguments of [`Limit::new`] that make it again.
    fn __getnewargs__(&self) -> (&'static str, usize, Vec<f64>, Vec<f64>, f64) {
        (self.kind(), self.after(), self.inputs(), self.coords(), self.0.det)
    }

    /// Equal limit positions have equal values.
    fn __eq__(&self, other: &Bound<'_, PyAny>) -> bool {
        other.cast::<Limit>().is_ok_and(|o| *o.get() == *self)
    }

    /// Every value, as Python writes a call.
    fn __repr__(&self) -> String {
        let l = &self.0;
        format!(
            "Limit(kind={:?}, after={}, inputs={:?}, coords={:?}, det={:?})",
            self.kind(),
            self.after(),
            l.inputs,
            l.coords,
            l.det
        )
    }

    /// `near_zero`, `input_limit` or `passed`.
    #[getter]
    fn kind(&self) -> &'static str {
        kind_word(self.0.kind)
    }

    /// The position before it (1-based).
    #[getter]
    fn after(&self) -> usize {
        self.0.after + 1
    }

    /// The inputs' values there.
    #[getter]
    fn inputs(&self) -> Vec<f64> {
        self.0.inputs.clone()
    }

    /// Every co-ordinate there.
    #[getter]
    fn coords(&self) -> Vec<f64> {
        self.0.coords.clone()
    }

    /// det(D^c) there.
    #[getter]
    fn det(&self) -> f64 {
        self.0.det
    }
}

/// Why a motion stopped before its last position: the core's stop, its
/// failure worded by the core (`message`, and `parts` naming the things of
/// the model as structure).
#[pyclass(module = "mechfem._core", frozen, get_all)]
#[derive(Debug)]
pub struct Stop {
    /// The last position computed (1-based).
    last_good: usize,
    /// The input values that could not be reached.
    inputs: Vec<f64>,
    /// The input values at the last good position.
    last_inputs: Vec<f64>,
    /// What failed (the code of the core's error).
    kind: String,
    /// The core's words for the failure.
    message: String,
    /// The same words in parts.
    parts: Py<PyList>,
    /// The limit position the input ran into, when one was located.
    limit: Option<Limit>,
}

/// What [`Stop::new`] takes, in order.
type StopFields = (usize, Vec<f64>, Vec<f64>, String, String, Py<PyList>, Option<Limit>);

#[pymethods]
impl Stop {
    /// The stop with these values.
    #[new]
    fn new(
        last_good: usize,
        inputs: Vec<f64>,
        last_inputs: Vec<f64>,
        kind: String,
        message: String,
        parts: Py<PyList>,
        limit: Option<Limit>,
    ) -> Stop {
        Stop { last_good, inputs, last_inputs, kind, message, parts, limit }
    }

    /// The arguments of [`Stop::new`] that make it again.
    fn __getnewargs__(&self, py: Python<'_>) -> StopFields {
        let s = self;
        let parts = s.parts.clone_ref(py);
        (
            s.last_good,
            s.inputs.clone(),
            s.last_inputs.clone(),
            s.kind.clone(),
            s.message.clone(),
            parts,
            s.limit.clone(),
        )
    }

    /// Equal stops have equal values.
    fn __eq__(&self, other: &Bound<'_, PyAny>) -> PyResult<bool> {
        let Ok(o) = other.cast::<Stop>() else { return Ok(false) };
        let o = o.get();
        let same = (self.last_good, &self.inputs, &self.last_inputs, &self.kind, &self.message, &self.limit)
            == (o.last_good, &o.inputs, &o.last_inputs, &o.kind, &o.message, &o.limit);
        Ok(same && self.parts.bind(other.py()).eq(o.parts.bind(other.py()))?)
    }

    /// Every value but the parts, as Python writes a call.
    fn __repr__(&self) -> String {
        let limit = self.limit.as_ref().map_or("None".to_string(), Limit::__repr__);
        format!(
            "Stop(last_good={}, inputs={:?}, last_inputs={:?}, kind={:?}, message={:?}, limit={limit})",
            self.last_good, self.inputs, self.last_inputs, self.kind, self.message
        )
    }
}

/// What a run did: the adjustment of position 1, the positions computed,
/// the limit positions met and why the motion stopped, if it did.
#[pyclass(module = "mechfem._core", frozen, get_all)]
#[derive(Debug)]
pub struct Report {
    /// The adjustment of position 1.
    adjust: Adjust,
    /// Positions computed.
    positions: usize,
    /// Steps the motion asked for.
    steps: usize,
    /// Steps that had to be subdivided.
    subdivided_steps: usize,
    /// Limit positions met on the way, in order.
    limits: Vec<Limit>,
    /// Positions (1-based) where D^c was singular.
    singular_positions: Vec<usize>,
    /// Why the motion stopped early; None when it did not.
    stop: Option<Py<Stop>>,
}

/// What [`Report::new`] takes, in order.
type ReportFields = (Adjust, usize, usize, usize, Vec<Limit>, Vec<usize>, Option<Py<Stop>>);

impl Report {
    /// `r` for Python: `steps` is the number of steps the motion asked for,
    /// `names` the model's names and `lines` the DYNAMICS lines a stop's
    /// fault may name.
    pub fn of(
        py: Python<'_>,
        mech: &Mechanism,
        names: &Names,
        lines: errors::Lines<'_>,
        r: &RunReport,
        steps: usize,
    ) -> PyResult<Report> {
        let stop = r.stop.as_ref().map(|s| {
            let worded = s.error.worded(mech, names, lines);
            let stop = Stop {
                last_good: s.last_good + 1,
                inputs: s.inputs.clone(),
                last_inputs: s.last_inputs.clone(),
                kind: s.error.code().to_owned(),
                message: worded.to_string(),
                parts: errors::parts_object(py, &worded)?.unbind(),
                limit: s.limit.clone().map(Limit),
            };
            Py::new(py, stop)
        });
        Ok(Report {
            adjust: Adjust::of(&r.adjust),
            positions: r.positions,
            steps,
            subdivided_steps: r.subdivided_steps,
            limits: r.limits.iter().cloned().map(Limit).collect(),
            singular_positions: r.singular_positions.iter().map(|k| k + 1).collect(),
            stop: stop.transpose()?,
        })
    }

    /// Every number of a report of a run that met nothing to tell of (no
    /// stop, limit or singular position): two such runs with equal keys
    /// have equal reports, so one can serve both. `None` for a run that did
    /// meet something.
    pub fn plain_key(r: &RunReport, steps: usize) -> Option<Vec<u64>> {
        if r.stop.is_some() || !r.limits.is_empty() || !r.singular_positions.is_empty() {
            return None;
        }
        let a = &r.adjust;
        let mut numbers = vec![a.iterations as u64, a.stages as u64, a.residual.to_bits()];
        numbers.extend([r.positions, r.subdivided_steps, steps].map(|k| k as u64));
        numbers.extend(a.initial_deformations.iter().map(|v| v.to_bits()));
        Some(numbers)
    }
}

#[pymethods]
impl Report {
    /// The report with these values.
    #[new]
    fn new(
        adjust: Adjust,
        positions: usize,
        steps: usize,
        subdivided_steps: usize,
        limits: Vec<Limit>,
        singular_positions: Vec<usize>,
        stop: Option<Py<Stop>>,
    ) -> Report {
        Report { adjust, positions, steps, subdivided_steps, limits, singular_positions, stop }
    }

    /// The arguments of [`Report::new`] that make it again.
    fn __getnewargs__(&self, py: Python<'_>) -> ReportFields {
        let r = self;
        let stop = r.stop.as_ref().map(|s| s.clone_ref(py));
        (
            r.adjust.clone(),
            r.positions,
            r.steps,
            r.subdivided_steps,
            r.limits.clone(),
            r.singular_positions.clone(),
            stop,
        )
    }

    /// Equal reports tell the same.
    fn __eq__(&self, other: &Bound<'_, PyAny>) -> PyResult<bool> {
        let Ok(o) = other.cast::<Report>() else { return Ok(false) };
        let o = o.get();
        let numbers = |r: &Report| (r.adjust.clone(), r.positions, r.steps, r.subdivided_steps, r.limits.clone());
        if numbers(self) != numbers(o) || self.singular_positions != o.singular_positions {
            return Ok(false);
        }
        match (&self.stop, &o.stop) {
            (None, None) => Ok(true),
            (Some(a), Some(b)) => a.bind(other.py()).eq(b.bind(other.py())),
            _ => Ok(false),
        }
    }

    /// Every value, as Python writes a call.
    fn __repr__(&self) -> String {
        let limits = self.limits.iter().map(Limit::__repr__).collect::<Vec<_>>().join(", ");
        let stop = self.stop.as_ref().map_or("None".to_string(), |s| s.get().__repr__());
        format!(
            "Report(adjust={}, positions={}, steps={}, subdivided_steps={}, limits=[{limits}], \
             singular_positions={:?}, stop={stop})",
            self.adjust.__repr__(),
            self.positions,
            self.steps,
            self.subdivided_steps,
            self.singular_positions
        )
    }
}
