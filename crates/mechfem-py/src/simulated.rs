//! What the integrator of a `DYN SIM` run did, as Python reads it
//! (`Run.simulation`): a typed object with getters, made from the core's
//! [`SimReport`].

use mechfem_core::SimReport;
use pyo3::prelude::*;

/// One stretch of a simulation integrated by one method: (method, from,
/// to, steps, evaluations).
type Segment = (String, f64, f64, usize, usize);

/// Where STOPWHEN ended a simulation: (buffer, value, time, inputs).
type Event = (u32, f64, f64, Vec<f64>);

/// What the integrator of a simulation did: its method and tolerances,
/// its work, the time it reached, the stretches each method integrated,
/// where STOPWHEN ended it and why ACCURACY and INTTOL conflict, if they do.
#[pyclass(module = "mechfem._core", frozen, get_all, eq)]
#[derive(Debug, Clone, PartialEq)]
pub struct Simulation {
    /// The integrator's name.
    pub method: String,
    /// Relative tolerance.
    pub rtol: f64,
    /// Absolute tolerance.
    pub atol: f64,
    /// Steps accepted.
    pub steps: usize,
    /// Steps rejected (error estimate too large, or no position found).
    pub rejected: usize,
    /// Evaluations of the equations of motion (one Newton position each).
    pub evaluations: usize,
    /// Jacobians the implicit method computed.
    pub jacobians: usize,
    /// The time the integration reached.
    pub reached: f64,
    /// Which method integrated which stretch, in order.
    pub segments: Vec<Segment>,
    /// Where STOPWHEN ended the simulation; None when it did not.
    pub event: Option<Event>,
    /// Why ACCURACY and INTTOL conflict, if they do.
    pub tolerance_warning: Option<String>,
}

impl Simulation {
    /// What the core's integrator reported.
    pub fn of(s: &SimReport) -> Simulation {
        Simulation {
            method: s.integration.integrator.name().to_owned(),
            rtol: s.integration.rtol,
            atol: s.integration.atol,
            steps: s.steps,
            rejected: s.rejected,
            evaluations: s.evaluations,
            jacobians: s.jacobians,
            reached: s.reached,
            segments: s
                .segments
                .iter()
                .map(|g| (g.method.name().to_owned(), g.from, g.to, g.steps, g.evaluations))
                .collect(),
            event: s.event.as_ref().map(|e| (e.buffer, e.value, e.time, e.inputs.clone())),
            tolerance_warning: s.tolerance_warning.clone(),
        }
    }
}

#[pymethods]
impl Simulation {
    /// The record with these values (what a pickle of it is made again from).
    #[new]
    #[allow(clippy::too_many_arguments)]
    fn new(
        method: String,
        rtol: f64,
        atol: f64,
        steps: usize,
        rejected: usize,
        evaluations: usize,
        jacobians: usize,
        reached: f64,
        segments: Vec<Segment>,
        event: Option<Event>,
        tolerance_warning: Option<String>,
    ) -> Simulation {
        Simulation {
            method,
            rtol,
            atol,
            steps,
            rejected,
            evaluations,
            jacobians,
            reached,
            segments,
            event,
            tolerance_warning,
        }
    }

    /// The arguments of [`Simulation::new`] that make this record again.
    #[allow(clippy::type_complexity)]
    fn __getnewargs__(
        &self,
    ) -> (String, f64, f64, usize, usize, usize, usize, f64, Vec<Segment>, Option<Event>, Option<String>) {
        let s = self.clone();
        (
            s.method,
            s.rtol,
            s.atol,
            s.steps,
            s.rejected,
            s.evaluations,
            s.jacobians,
            s.reached,
            s.segments,
            s.event,
            s.tolerance_warning,
        )
    }
}
