//! Hostile input for the deck reader and the whole run: a generator of
//! plausible decks driven by a stream of choices (`generator.rs`), and the
//! checks every deck must pass whatever it holds.
//!
//! Shared by the property tests (`tests/hostile.rs`, choices from
//! proptest) and the fuzz targets (`fuzz/`, choices from libFuzzer's
//! bytes), which include this file by path.

#![allow(dead_code)]

mod generator;

use std::path::Path;

use mechfem_core::design::{evaluate, ExtremumSpec};
use mechfem_core::run::simulate_within;
use mechfem_core::{
    run, DesignVar, FormRef, InputMotion, InverseDynamics, Motion, Observer, PositionView, Quantity, Recorder,
    SolveError,
};
use mechfem_deck::{compile, parse_str, Compiled, Diagnostics, TargetKind};

// `Choose` is for the fuzz targets (`fuzz/src/lib.rs`), which re-export it.
#[allow(unused_imports)]
pub use generator::{deck, Bytes, Choose};

/// Longest motion a fuzz input runs; longer ones are cut to this.
pub const FUZZ_MAX_STEPS: usize = 2000;

/// Output positions of a simulation checked, at most (its motion is cut to
/// this), and the integrator steps it may take: every deck, however stiff,
/// is simulated in bounded time.
pub const SIM_MAX_OUTPUTS: usize = 20;
/// See [`SIM_MAX_OUTPUTS`].
pub const SIM_BUDGET: u32 = 2000;

/// Positions of a design evaluation checked, at most, and its design
/// variables used, at most.
pub const DESIGN_MAX_STEPS: usize = 50;
/// See [`DESIGN_MAX_STEPS`].
pub const DESIGN_MAX_VARS: usize = 2;

/// What became of a deck.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Outcome {
    /// Parsing or compiling gave diagnostics.
    Rejected,
    /// Position 1 could not be computed.
    Failed,
    /// The motion stopped before its last position.
    Stopped,
    /// Every position was computed.
    Completed,
    /// A `DYN SIM` deck with a DOF moved by the forces (MOV_DYN): the
    /// kinematic run refused its motion, as it must (running it is the
    /// simulation's, which the core checks), and position 1 was computed.
    Simulation,
}

/// Parses and compiles `text` (MOV_FUNC files are read from `dir`); the
/// diagnostics, if any, must render.
pub fn compile_text(text: &str, dir: &Path) -> Result<Compiled, Diagnostics> {
    let result = parse_str(text, "hostile.mec").and_then(|deck| compile(&deck, dir));
    if let Err(e) = &result {
        let rendered = e.to_string();
        assert!(rendered.starts_with("error: "), "a diagnostic that does not render:\n{rendered}");
        assert!(!e.0.is_empty(), "no diagnostic in an error");
    }
    result
}

/// Shortens a motion to at most `max_steps` steps, so that every deck runs
/// quickly (a MOV_FUNC table loses its surplus rows).
pub fn cap_steps(motion: &mut Motion, max_steps: usize) {
    if motion.steps > max_steps {
        motion.steps = max_steps;
        for im in &mut motion.inputs {
            if let InputMotion::Table { rows } = im {
                rows.truncate(max_steps + 1);
            }
        }
    }
}

/// Every quantity a buffer can record of this model (second-order terms
/// of the first three inputs only, to bound the work for large models).
pub fn every_quantity(c: &Compiled) -> Vec<Quantity> {
    let m = &c.mechanism;
    let (n, nd) = (m.n_coords(), m.n_dof());
    let pairs: Vec<(usize, usize)> = (0..nd.min(3)).flat_map(|j| (0..nd.min(3)).map(move |k| (j, k))).collect();
    let forms: Vec<FormRef> =
        (0..m.n_prescribed()).map(FormRef::Prescribed).chain((0..m.n_dependent()).map(FormRef::Dependent)).collect();
    let mut q = vec![Quantity::Time, Quantity::Det];
    q.extend((0..nd).map(Quantity::Input));
    for i in 0..n {
        q.extend([Quantity::X0(i), Quantity::Vx(i), Quantity::Ax(i)]);
        q.extend((0..nd).map(|j| Quantity::Kx1 { coord: i, j }));
        q.extend(pairs.iter().map(|&(j, k)| Quantity::Kx2 { coord: i, j, m: k }));
    }
    for &f in &forms {
        q.extend([Quantity::E0(f), Quantity::Ve(f), Quantity::Ae(f)]);
        q.extend((0..nd).map(|j| Quantity::Ke1(f, j)));
        q.extend(pairs.iter().map(|&(j, k)| Quantity::Ke2(f, j, k)));
    }
    q.truncate(20_000);
    // The results of inverse dynamics of a DYN deck: every stress, drive,
    // reaction on a fixed co-ordinate, the energies, the power and the mass
    // matrix.
    if c.dynamics.is_some() {
        q.extend((0..m.n_prescribed()).map(Quantity::Sigma));
        q.extend((0..nd).map(Quantity::Drive));
        q.extend((0..n).filter(|&i| m.column(i) == mechfem_core::model::FIXED).map(Quantity::Reaction));
        q.extend([Quantity::Ekin, Quantity::Epot, Quantity::Power]);
        q.extend((0..nd.min(3)).flat_map(|j| (0..nd.min(3)).map(move |k| Quantity::Mred(j, k))));
    }
    q
}

/// A recorder of `quantities` that evaluates the inverse dynamics of a DYN
/// deck when they hold any of its results.
pub fn recorder(c: &Compiled, quantities: Vec<Quantity>) -> Recorder {
    let rec = Recorder::new(quantities, false);
    match &c.dynamics {
        Some(d) => rec.with_dynamics(InverseDynamics::new(&c.mechanism, d.clone())),
        None => rec,
    }
}

/// A [`Recorder`] that also checks, at every position, that the state is
/// finite.
struct Checked {
    rec: Recorder,
    bad_state: Option<usize>,
}

impl Observer for Checked {
    fn check(&mut self, view: &PositionView<'_>) -> Result<(), SolveError> {
        self.rec.check(view)
    }
    fn position(&mut self, view: &PositionView<'_>) {
        if self.bad_state.is_none() && view.state.x.iter().any(|v| !v.is_finite()) {
            self.bad_state = Some(view.index);
        }
        self.rec.position(view);
    }
    fn transfer_order(&self) -> Option<mechfem_core::TransferOrder> {
        self.rec.transfer_order()
    }
}

/// Whether a DOF of the motion is moved by the forces (MOV_DYN).
pub fn is_simulated(motion: &Motion) -> bool {
    motion.inputs.iter().any(|im| matches!(im, InputMotion::Dynamic { .. }))
}

/// Runs a compiled deck with its motion cut to `max_steps` steps, recording
/// `quantities`, and checks what came out: the run's errors render, every
/// position reported is observed, and every recorded value is finite
/// except transfer functions at positions the run reports as singular.
/// A motion with a DOF moved by the forces must be refused as unsupported;
/// position 1 of its deck is checked instead.
pub fn run_checked(c: &Compiled, quantities: Vec<Quantity>, max_steps: usize) -> Outcome {
    if let Some(m) = c.motion.as_ref().filter(|m| is_simulated(m)) {
        let mut state = c.state.clone();
        let refused = run(&c.mechanism, &mut state, Some(m), &c.params, &mut Recorder::new(Vec::new(), false));
        assert!(
            matches!(refused, Err(SolveError::Unsupported(_))),
            "a kinematic run of a motion moved by the forces gave {refused:?}"
        );
        let position_1 = Compiled { motion: None, ..c.clone() };
        return match run_checked(&position_1, quantities, max_steps) {
            Outcome::Completed => Outcome::Simulation,
            other => other,
        };
    }
    let mut motion = c.motion.clone();
    if let Some(m) = motion.as_mut() {
        cap_steps(m, max_steps);
    }
    let mut state = c.state.clone();
    let mut obs = Checked { rec: recorder(c, quantities), bad_state: None };
    let report = match run(&c.mechanism, &mut state, motion.as_ref(), &c.params, &mut obs) {
        Ok(r) => r,
        Err(e) => {
            assert!(!e.to_string().is_empty());
            return Outcome::Failed;
        }
    };
    let rec = &obs.rec;
    assert_eq!(rec.positions(), report.positions, "positions observed and reported differ");
    assert_eq!(obs.bad_state, None, "a position with a non-finite co-ordinate was observed");
    assert!(state.x.iter().all(|v| v.is_finite()), "the run left a non-finite state: {:?}", state.x);
    let w = rec.quantities().len();
    for k in 0..rec.positions() {
        let singular = report.singular_positions.contains(&k);
        for (q, v) in rec.quantities().iter().zip(&rec.data()[k * w..(k + 1) * w]) {
            assert!(
                v.is_finite() || (singular && q.needs_transfer()),
                "{q:?} at position {k} is {v} without an error (report: {:?})",
                report.stop
            );
        }
    }
    for l in &report.limits {
        assert!(l.det.is_finite() && l.coords.iter().chain(&l.inputs).all(|v| v.is_finite()), "limit {l:?}");
    }
    match &report.stop {
        Some(stop) => {
            assert!(!stop.error.to_string().is_empty());
            assert_eq!(stop.last_good + 1, report.positions, "the stop names another position than the last one");
            Outcome::Stopped
        }
        None => {
            let expected = motion.as_ref().map_or(1, |m| m.steps + 1);
            assert_eq!(report.positions, expected, "the motion ended early without saying why");
            Outcome::Completed
        }
    }
}

/// Simulates a `DYN SIM` deck with its motion cut to [`SIM_MAX_OUTPUTS`]
/// output positions and an integrator budget of [`SIM_BUDGET`] steps,
/// recording every kinematic quantity: a simulation that cannot start says
/// why, one that ends early says why at its last output, and every output
/// is finite (transfer functions excepted at positions reported singular).
pub fn simulate_checked(c: &Compiled) {
    let (Some(motion), Some(dynamics)) = (c.motion.as_ref(), c.dynamics.as_ref()) else { return };
    let mut motion = motion.clone();
    cap_steps(&mut motion, SIM_MAX_OUTPUTS);
    let mut state = c.state.clone();
    let mut obs = Checked { rec: recorder(c, every_quantity(c)), bad_state: None };
    let result = simulate_within(
        &c.mechanism,
        &mut state,
        &motion,
        &c.params,
        &c.integration,
        dynamics,
        Some(SIM_BUDGET),
        &mut obs,
    );
    let report = match result {
        Ok(r) => r.run,
        Err(e) => {
            assert!(!e.to_string().is_empty());
            return;
        }
    };
    let rec = &obs.rec;
    assert_eq!(rec.positions(), report.positions, "simulation: positions observed and reported differ");
    assert_eq!(obs.bad_state, None, "simulation: a position with a non-finite co-ordinate was observed");
    let w = rec.quantities().len();
    for k in 0..rec.positions() {
        let singular = report.singular_positions.contains(&k);
        for (q, v) in rec.quantities().iter().zip(&rec.data()[k * w..(k + 1) * w]) {
            assert!(v.is_finite() || (singular && q.needs_transfer()), "simulation: {q:?} at output {k} is {v}");
        }
    }
    match &report.stop {
        Some(stop) => assert!(!stop.error.to_string().is_empty()),
        None => assert_eq!(report.positions, motion.steps + 1, "the simulation ended early without saying why"),
    }
}

/// Evaluates one design of a `KIN OPT` deck as an optimiser would: its
/// first [`DESIGN_MAX_VARS`] design variables set to the middle of their
/// ranges, the motion cut to [`DESIGN_MAX_STEPS`] steps, every kinematic
/// buffer and the TARGETEXT extrema with their design sensitivities. An
/// evaluation that fails says why; one that succeeds gives finite values
/// and gradients (transfer functions excepted at singular positions).
pub fn evaluate_checked(c: &Compiled) {
    let (Some(opt), Some(motion)) = (c.optimise.as_ref(), c.motion.as_ref()) else { return };
    let mut motion = motion.clone();
    cap_steps(&mut motion, DESIGN_MAX_STEPS);
    let vars: Vec<DesignVar> = opt.vary.iter().take(DESIGN_MAX_VARS).map(|v| v.var).collect();
    let mut state = c.state.clone();
    for v in opt.vary.iter().take(DESIGN_MAX_VARS) {
        let mid = 0.5 * v.lo + 0.5 * v.hi;
        match v.var {
            DesignVar::Row(r) => state.target[r] = mid,
            DesignVar::Fixed(i) => state.x[i] = mid,
        }
    }
    let quantity = |b: u32| c.buffers.iter().find(|x| x.number == b).map(|x| x.quantity);
    let quantities: Vec<Quantity> = c.buffers.iter().map(|b| b.quantity).filter(|q| !q.is_dynamic()).collect();
    let extrema: Vec<ExtremumSpec> = opt
        .targets
        .iter()
        .filter_map(|t| match t.kind {
            TargetKind::Extremum { reference, .. } => {
                Some(ExtremumSpec { quantity: quantity(t.buffer)?, reference: quantity(reference)? })
            }
            _ => None,
        })
        .collect();
    let design = match evaluate(&c.mechanism, &mut state, &motion, &c.params, &vars, &quantities, &extrema) {
        Ok(d) => d,
        Err(e) => {
            assert!(!e.to_string().is_empty());
            return;
        }
    };
    let (nq, nv) = (quantities.len(), vars.len());
    assert_eq!(design.positions, design.report.positions, "design: positions computed and reported differ");
    assert_eq!(design.values.len(), design.positions * nq);
    for k in 0..design.positions {
        let singular = design.report.singular_positions.contains(&k);
        for (i, q) in quantities.iter().enumerate() {
            let v = design.values[k * nq + i];
            let g = &design.gradient[(k * nq + i) * nv..(k * nq + i + 1) * nv];
            let exempt = singular && q.needs_transfer();
            assert!(v.is_finite() || exempt, "design: {q:?} at position {k} is {v}");
            // det(D^c) has no design sensitivity (NaN); the deck refuses it
            // in a target, a bound or an objective.
            let no_gradient = exempt || *q == Quantity::Det;
            assert!(g.iter().all(|d| d.is_finite()) || no_gradient, "design: d {q:?} / d p at position {k} is {g:?}");
        }
    }
    assert!(design.coords.iter().all(|v| v.is_finite()), "design: a non-finite co-ordinate");
    for e in &design.extrema {
        assert!(
            e.input.is_finite() && e.reference.is_finite() && e.value.is_finite(),
            "design: an extremum that is not finite: {e:?}"
        );
        assert!(e.gradient.iter().all(|d| d.is_finite()), "design: an extremum's gradient is not finite: {e:?}");
    }
}

/// The whole check of one deck: parse, compile, and if it compiles, run it
/// (at most `max_steps` steps) recording every quantity, then again
/// recording only the deck's buffers when they need less (a run computes no
/// more transfer functions than its observer reads); a `DYN SIM` deck is
/// also simulated ([`simulate_checked`]) and one design of a `KIN OPT` deck
/// evaluated ([`evaluate_checked`]).
pub fn check_deck(text: &str, dir: &Path, max_steps: usize) -> Outcome {
    let Ok(c) = compile_text(text, dir) else { return Outcome::Rejected };
    let outcome = run_checked(&c, every_quantity(&c), max_steps);
    if c.dynamics.is_some() && c.motion.as_ref().is_some_and(is_simulated) {
        simulate_checked(&c);
    }
    evaluate_checked(&c);
    let own: Vec<Quantity> = c.buffers.iter().map(|b| b.quantity).collect();
    let order = own.iter().map(Quantity::transfer_order).max().flatten();
    if order < Some(mechfem_core::TransferOrder::Second) {
        run_checked(&c, own, max_steps);
    }
    outcome
}
