//! What the integrator of a `DYN SIM` run did, as Python reads it
//! (`Run.simulation`): the core's [`SimReport`], read through getters.

use mechfem_core::dynamics::{Integration, Integrator};
use mechfem_core::run::{Event, Segment};
use mechfem_core::{AdjustInfo, RunReport, SimReport};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

/// One stretch of a simulation integrated by one method: (method, from,
/// to, steps, evaluations).
type SegmentTuple = (String, f64, f64, usize, usize);

/// Where STOPWHEN ended a simulation: (buffer, value, time, inputs).
type EventTuple = (u32, f64, f64, Vec<f64>);

/// Everything a [`Simulation`] tells, in the order of its constructor.
type Fields =
    (String, f64, f64, usize, usize, usize, usize, f64, Vec<SegmentTuple>, Option<EventTuple>, Option<String>);

/// What the integrator of a simulation did: its method and tolerances,
/// its work, the time it reached, the stretches each method integrated,
/// where STOPWHEN ended it and why ACCURACY and INTTOL conflict, if they do.
#[pyclass(module = "mechfem._core", frozen)]
#[derive(Debug, Clone)]
pub struct Simulation(SimReport);

impl Simulation {
    /// What the core's integrator reported.
    pub fn of(s: &SimReport) -> Simulation {
        Simulation(s.clone())
    }

    fn fields(&self) -> Fields {
        let s = &self.0;
        (
            s.integration.integrator.name().to_owned(),
            s.integration.rtol,
            s.integration.atol,
            s.steps,
            s.rejected,
            s.evaluations,
            s.jacobians,
            s.reached,
            self.segments(),
            self.event(),
            s.tolerance_warning.clone(),
        )
    }
}

/// The method whose [`Integrator::name`] is `name`.
fn integrator_named(name: &str) -> PyResult<Integrator> {
    [Integrator::Auto, Integrator::Dop853, Integrator::Dopri5, Integrator::Radau5]
        .into_iter()
        .find(|i| i.name() == name)
        .ok_or_else(|| PyValueError::new_err(name.to_owned()))
}

#[pymethods]
impl Simulation {
    /// The record with these values (what a pickle of it is made again
    /// from; the run's own report is not part of it).
    #[new]
    #[allow(clippy::too_many_arguments)]
    fn new(
        method: &str,
        rtol: f64,
        atol: f64,
        steps: usize,
        rejected: usize,
        evaluations: usize,
        jacobians: usize,
        reached: f64,
        segments: Vec<SegmentTuple>,
        event: Option<EventTuple>,
        tolerance_warning: Option<String>,
    ) -> PyResult<Simulation> {
        let segments = segments
            .into_iter()
            .map(|(method, from, to, steps, evaluations)| {
                Ok(Segment { method: integrator_named(&method)?, from, to, steps, evaluations })
            })
            .collect::<PyResult<Vec<_>>>()?;
        Ok(Simulation(SimReport {
            run: RunReport {
                adjust: AdjustInfo::default(),
                positions: 0,
                subdivided_steps: 0,
                limits: Vec::new(),
                singular_positions: Vec::new(),
                stop: None,
            },
            integration: Integration { rtol, atol, integrator: integrator_named(method)?, stop_when: None },
            steps,
            rejected,
            evaluations,
            jacobians,
            reached,
            segments,
            event: event.map(|(buffer, value, time, inputs)| Event { buffer, value, time, inputs }),
            tolerance_warning,
        }))
    }

    /// The arguments of [`Simulation::new`] that make this record again.
    fn __getnewargs__(&self) -> Fields {
        self.fields()
    }

    /// Equal records tell the same.
    fn __eq__(&self, other: &Bound<'_, PyAny>) -> bool {
        other.cast::<Simulation>().is_ok_and(|o| o.get().fields() == self.fields())
    }

    /// The integrator's name.
    #[getter]
    fn method(&self) -> &'static str {
        self.0.integration.integrator.name()
    }

    /// Relative tolerance.
    #[getter]
    fn rtol(&self) -> f64 {
        self.0.integration.rtol
    }

    /// Absolute tolerance.
    #[getter]
    fn atol(&self) -> f64 {
        self.0.integration.atol
    }

    /// Steps accepted.
    #[getter]
    fn steps(&self) -> usize {
        self.0.steps
    }

    /// Steps rejected (error estimate too large, or no position found).
    #[getter]
    fn rejected(&self) -> usize {
        self.0.rejected
    }

    /// Evaluations of the equations of motion (one Newton position each).
    #[getter]
    fn evaluations(&self) -> usize {
        self.0.evaluations
    }

    /// Jacobians the implicit method computed.
    #[getter]
    fn jacobians(&self) -> usize {
        self.0.jacobians
    }

    /// The time the integration reached.
    #[getter]
    fn reached(&self) -> f64 {
        self.0.reached
    }

    /// Which method integrated which stretch, in order.
    #[getter]
    fn segments(&self) -> Vec<SegmentTuple> {
        self.0.segments.iter().map(|g| (g.method.name().to_owned(), g.from, g.to, g.steps, g.evaluations)).collect()
    }

    /// Where STOPWHEN ended the simulation; None when it did not.
    #[getter]
    fn event(&self) -> Option<EventTuple> {
        self.0.event.as_ref().map(|e| (e.buffer, e.value, e.time, e.inputs.clone()))
    }

    /// Why ACCURACY and INTTOL conflict, if they do.
    #[getter]
    fn tolerance_warning(&self) -> Option<String> {
        self.0.tolerance_warning.clone()
    }
}
