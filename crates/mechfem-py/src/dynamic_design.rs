//! A compiled `DYN ANA` deck kept for an optimiser: [`DynamicDesignModel`]
//! evaluates one design after another with inverse dynamics at every
//! position ([`mechfem_core::dynamic_design::evaluate`]), the dynamic
//! buffers with their exact sensitivities to dimensions and to the mass
//! model. Kinematic variables are assembled on the start design's branch
//! as [`crate::design::DesignModel`] does; the mass model leaves the
//! kinematics alone. An infeasible design is returned with the reason,
//! never raised. The same [`Evaluation`] as `DesignModel`'s, so that the
//! optimiser takes either.

use std::path::PathBuf;

use mechfem_core::design::{Anchor, Design, DesignFailure, DesignRun};
use mechfem_core::dynamic_design::evaluate;
use mechfem_core::{worded, DesignVar, State};
use mechfem_deck::{Compiled, DesignUnits, DynamicSetup};
use pyo3::prelude::*;

use crate::design::reason;
use crate::errors;
use crate::evaluation::{self, Evaluation};
use crate::text::compile_text;

/// A DYN ANA deck, its design variables and the buffers an objective reads.
#[pyclass(module = "mechfem._core")]
pub struct DynamicDesignModel {
    compiled: Compiled,
    setup: DynamicSetup,
    /// The start design's branch, once evaluated (kinematic variables only).
    anchor: Option<Result<Anchor, String>>,
    runs: usize,
    /// The units its variables and results are in: the model's, or the
    /// core's.
    units: DesignUnits,
}

impl DynamicDesignModel {
    /// The model of the compiled deck `c` (see [`DynamicDesignModel::new`]).
    pub(crate) fn of_compiled(
        c: Compiled,
        variables: &[(u8, usize)],
        buffers: &[u32],
        in_model_units: bool,
    ) -> PyResult<Self> {
        let setup = c.dynamic_setup(variables, buffers).map_err(|e| errors::value_error(&e))?;
        let units = if in_model_units { c.dynamic_design_units(&setup) } else { DesignUnits::core() };
        Ok(DynamicDesignModel { compiled: c, setup, anchor: None, runs: 0, units })
    }
}

#[pymethods]
impl DynamicDesignModel {
    /// Compiles the DYN ANA deck `text` (named `path`, its files read from
    /// `base_dir`). `variables` are `(kind, number)` in the deck's
    /// numbering: kind 0 a fixed co-ordinate, 1 a prescribed row, 10..=15 the
    /// MASS, U, V or J of element `number`'s MASS line, the PMASS at
    /// co-ordinate `number`, the INERTIA on it; `buffers` the buffer
    /// numbers evaluated. `extrema` must be empty (a timed motion has none
    /// to locate).
    #[new]
    fn new(
        py: Python<'_>,
        text: &str,
        path: PathBuf,
        base_dir: PathBuf,
        variables: Vec<(u8, usize)>,
        buffers: Vec<u32>,
        extrema: Vec<(u32, u32)>,
    ) -> PyResult<Self> {
        if !extrema.is_empty() {
            return Err(pyo3::exceptions::PyValueError::new_err(
                "a dynamic design evaluation locates no extrema: pass an empty list",
            ));
        }
        let c = py.detach(|| compile_text(text, &path, &base_dir)).map_err(|d| errors::deck_error(py, &path, &d))?;
        DynamicDesignModel::of_compiled(c, &variables, &buffers, false)
    }

    /// The design's values as the deck gives them, in the order of the variables.
    fn start(&self) -> Vec<f64> {
        let (kin, mass) = self.deck_values();
        let values: Vec<f64> =
            self.setup.order.iter().map(|&k| if k < kin.len() { kin[k] } else { mass[k - kin.len()] }).collect();
        self.units.from_core(values)
    }

    /// How many designs have been evaluated (mechanism runs).
    #[getter]
    fn runs(&self) -> usize {
        self.runs
    }

    /// Evaluates `values` as the start design: the assembly branch of its
    /// position 1 is the branch of every later evaluation. An [`Evaluation`]
    /// as of [`Self::evaluate`].
    fn start_at(&mut self, py: Python<'_>, values: Vec<f64>) -> PyResult<Evaluation> {
        self.check(&values)?;
        let (kin, mass) = self.split(&self.units.to_core(values));
        let started = if self.setup.vars.is_empty() {
            None
        } else {
            let design = self.design();
            Some(py.detach(|| design.start(&kin)))
        };
        let result = match started {
            None => {
                self.anchor = None;
                py.detach(|| self.run(self.compiled.state.clone(), &kin, &mass))
            }
            Some(Ok((run, anchor))) => {
                let state = self.position_one(&run, &kin);
                self.anchor = Some(Ok(anchor));
                py.detach(|| self.run(state, &kin, &mass))
            }
            Some(Err(e)) => {
                self.anchor = Some(Err(reason(&self.compiled, &e).1));
                Err(e)
            }
        };
        self.runs += 1;
        self.evaluation(py, result)
    }

    /// Evaluates the design `values` on the start design's branch: its
    /// [`Evaluation`] (the gradient's variables in the order given, no
    /// extrema), as `DesignModel.evaluate` gives it.
    fn evaluate(&mut self, py: Python<'_>, values: Vec<f64>) -> PyResult<Evaluation> {
        self.check(&values)?;
        if self.setup.vars.is_empty() {
            return self.start_at(py, values);
        }
        if self.anchor.is_none() {
            let start = self.start();
            let d = self.start_at(py, start.clone())?;
            if start == values {
                return Ok(d);
            }
        }
        let anchor = match &self.anchor {
            Some(Ok(anchor)) => anchor,
            Some(Err(why)) => return self.failed(py, "start", worded::infeasible_start(why)),
            None => unreachable!("set by start_at"),
        };
        let (kin, mass) = self.split(&self.units.to_core(values));
        let design = self.design();
        let result = py.detach(|| {
            let run = design.evaluate(anchor, &kin)?;
            self.run(self.position_one(&run, &kin), &kin, &mass)
        });
        self.runs += 1;
        self.evaluation(py, result)
    }
}

impl DynamicDesignModel {
    fn check(&self, values: &[f64]) -> PyResult<()> {
        let err = if values.len() != self.setup.order.len() {
            Some(mechfem_deck::DesignSetupError::ValueCount { given: values.len(), vars: self.setup.order.len() })
        } else {
            values
                .iter()
                .position(|v| !v.is_finite())
                .map(|index| mechfem_deck::DesignSetupError::NotFinite { index, value: values[index] })
        };
        err.map_or(Ok(()), |e| Err(errors::value_error(&e)))
    }

    /// The deck's values of the kinematic and the mass variables.
    fn deck_values(&self) -> (Vec<f64>, Vec<f64>) {
        let s = &self.compiled.state;
        let kin = self
            .setup
            .vars
            .iter()
            .map(|v| match *v {
                DesignVar::Row(r) => s.target[r],
                DesignVar::Fixed(i) => s.x[i],
            })
            .collect();
        let model = self.compiled.dynamics.as_ref().expect("checked in new");
        (kin, self.setup.mass_vars.iter().map(|m| m.value(model)).collect())
    }

    /// The values as given, split into the kinematic and the mass ones.
    fn split(&self, values: &[f64]) -> (Vec<f64>, Vec<f64>) {
        let n_kin = self.setup.vars.len();
        let mut kin = vec![0.0; n_kin];
        let mut mass = vec![0.0; self.setup.mass_vars.len()];
        for (&k, &v) in self.setup.order.iter().zip(values) {
            if k < n_kin {
                kin[k] = v;
            } else {
                mass[k - n_kin] = v;
            }
        }
        (kin, mass)
    }

    fn design(&self) -> Design<'_> {
        let c = &self.compiled;
        Design {
            mech: &c.mechanism,
            base: &c.state,
            motion: c.motion.as_ref().expect("checked in new"),
            params: &c.params,
            vars: &self.setup.vars,
            quantities: &[],
            extrema: &[],
        }
    }

    /// The state of a kinematic design run: its values, and the
    /// co-ordinates of its position 1 on the start design's branch.
    fn position_one(&self, run: &DesignRun, kin: &[f64]) -> State {
        let mut state = self.compiled.state.clone();
        let nc = self.compiled.mechanism.n_coords();
        if let Some(x) = run.coords.get(..nc) {
            state.x.copy_from_slice(x);
        }
        for (v, &x) in self.setup.vars.iter().zip(kin) {
            match *v {
                DesignVar::Row(r) => state.target[r] = x,
                DesignVar::Fixed(i) => state.x[i] = x,
            }
        }
        state
    }

    /// The inverse dynamics of the design from `state`, the gradient in the
    /// order of the variables as given.
    fn run(&self, mut state: State, kin: &[f64], mass: &[f64]) -> Result<DesignRun, DesignFailure> {
        let c = &self.compiled;
        let mut model = c.dynamics.clone().expect("checked in new");
        for (m, &v) in self.setup.mass_vars.iter().zip(mass) {
            m.set(&mut model, v);
        }
        for (v, &x) in self.setup.vars.iter().zip(kin) {
            match *v {
                DesignVar::Row(r) => state.target[r] = x,
                DesignVar::Fixed(i) => state.x[i] = x,
            }
        }
        let motion = c.motion.as_ref().expect("checked in new");
        let s = &self.setup;
        let mut run =
            evaluate(&c.mechanism, &mut state, motion, &c.params, &model, &s.vars, &s.mass_vars, &s.quantities)
                .map_err(DesignFailure::Solve)?;
        let nv = s.order.len();
        let mut ordered = vec![0.0; run.gradient.len()];
        for (out, inner) in ordered.chunks_exact_mut(nv).zip(run.gradient.chunks_exact(nv)) {
            for (o, &k) in out.iter_mut().zip(&s.order) {
                *o = inner[k];
            }
        }
        run.gradient = ordered;
        Ok(run)
    }

    /// The [`Evaluation`] of [`DynamicDesignModel::evaluate`] for an evaluation.
    fn evaluation(&self, py: Python<'_>, result: Result<DesignRun, DesignFailure>) -> PyResult<Evaluation> {
        let (nq, nv) = (self.setup.quantities.len(), self.setup.order.len());
        evaluation::of_result(py, &self.compiled, &self.units, result, nq, nv)
    }

    /// An infeasible design without positions.
    fn failed(&self, py: Python<'_>, kind: &str, why: String) -> PyResult<Evaluation> {
        evaluation::infeasible(py, kind, why, self.setup.quantities.len(), self.setup.order.len())
    }
}

/// The DYN ANA deck `text` (named `path` in messages) with the numbers of
/// its mass model `masses` replaced: `(kind, number, value)`, kind 10..=15 as
/// for [`DynamicDesignModel::new`], values in the core's units; see
/// [`mechfem_deck::rewrite_masses::with_masses`]. A deck that does not
/// parse raises `DeckError`, a kind out of range `ValueError`.
#[pyfunction]
pub fn deck_with_masses(py: Python<'_>, text: &str, path: PathBuf, masses: Vec<(u8, usize, f64)>) -> PyResult<String> {
    let masses = masses
        .into_iter()
        .map(|(kind, number, value)| {
            let item = mechfem_deck::mass_item(kind).ok_or(mechfem_deck::DynamicSetupError::VariableKind(kind));
            item.map(|item| (item, number, value)).map_err(|e| errors::value_error(&e))
        })
        .collect::<PyResult<Vec<_>>>()?;
    mechfem_deck::rewrite_masses::with_masses(text, &path, &masses).map_err(|d| errors::deck_error(py, &path, &d))
}
