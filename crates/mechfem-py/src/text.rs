//! Decks given as text instead of files, for the Python model API
//! (`mechfem.Mechanism`), which writes a deck and runs it through the same
//! reader and solver as `mechfem run`.
//!
//! * [`describe_deck_text`] reads and compiles a deck and returns what it
//!   declares (co-ordinates, elements, rows, motion, storage) without solving.
//! * [`run_deck_text`] runs a deck and returns its own buffers plus every
//!   quantity of the deck's buffer table for every co-ordinate, row and input,
//!   in the fixed layout of [`full_quantities`].
//!
//! The helpers [`run_variant`] (no GIL) and [`outcome_dict`] (GIL) are shared
//! with the batch runner ([`crate::batch`]).

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};

use mechfem_core::dynamics::{Dynamics, Integration};
use mechfem_core::run::{simulate, InverseDynamics, SimReport};
use mechfem_core::SolveError;
use mechfem_core::{
    record, run, FormRef, InputMotion, Mechanism, Motion, Observer, Params, PositionView, Quantity, RunReport, State,
    TransferOrder,
};
use mechfem_deck::ast::{LoadDefKind, MotionKind};
use mechfem_deck::{Compiled, Diagnostics, Mode};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::observe::Progress;
use crate::{convert, errors};

/// Parses and compiles deck text; `path` names it in diagnostics, MOV_FUNC
/// files are read from `base_dir`.
pub fn compile_text(text: &str, path: &Path, base_dir: &Path) -> Result<Compiled, Diagnostics> {
    let deck = mechfem_deck::parse_str(text, path)?;
    mechfem_deck::compile(&deck, base_dir)
}

/// Every recordable quantity of a model, in the layout the Python side
/// reshapes (N co-ordinates, D inputs, rows = prescribed then dependent):
///
/// * D input values;
/// * per co-ordinate: D first-order, D x D second-order transfer functions
///   (row-major in j, m), velocity, acceleration;
/// * per row: value, D first-order, D x D second-order, velocity, acceleration.
///
/// With a mass and load model (`dynamic`), then:
///
/// * per prescribed row: its stress; per input: the drive force;
/// * per co-ordinate: the reaction (NaN for a moving one);
/// * kinetic and potential energy, drive power;
/// * the D x D mass matrix, row-major.
///
/// Co-ordinate values are not in it: they are recorded separately.
pub fn full_quantities(mech: &Mechanism, dynamic: bool) -> Vec<Quantity> {
    let nd = mech.n_dof();
    let pairs = || (0..nd).flat_map(move |j| (0..nd).map(move |m| (j, m)));
    let mut q: Vec<Quantity> = (0..nd).map(Quantity::Input).collect();
    for coord in 0..mech.n_coords() {
        q.extend((0..nd).map(|j| Quantity::Kx1 { coord, j }));
        q.extend(pairs().map(|(j, m)| Quantity::Kx2 { coord, j, m }));
        q.extend([Quantity::Vx(coord), Quantity::Ax(coord)]);
    }
    let forms =
        (0..mech.n_prescribed()).map(FormRef::Prescribed).chain((0..mech.n_dependent()).map(FormRef::Dependent));
    for f in forms {
        q.push(Quantity::E0(f));
        q.extend((0..nd).map(|j| Quantity::Ke1(f, j)));
        q.extend(pairs().map(|(j, m)| Quantity::Ke2(f, j, m)));
        q.extend([Quantity::Ve(f), Quantity::Ae(f)]);
    }
    if dynamic {
        q.extend((0..mech.n_prescribed()).map(Quantity::Sigma));
        q.extend((0..nd).map(Quantity::Drive));
        q.extend((0..mech.n_coords()).map(Quantity::Reaction));
        q.extend([Quantity::Ekin, Quantity::Epot, Quantity::Power]);
        q.extend(pairs().map(|(j, m)| Quantity::Mred(j, m)));
    }
    q
}

/// The observer of [`execute`]: records `quantities` (the deck's buffers,
/// the full layout, time and det(D^c)) and every co-ordinate into tables
/// sized for the whole motion up front; stops when `cancel` is set or
/// progress reporting failed.
struct Watch<'a> {
    quantities: Vec<Quantity>,
    /// Row-major, positions x quantities.
    table: Vec<f64>,
    /// Row-major, positions x co-ordinates.
    coords: Vec<f64>,
    positions: usize,
    /// Inverse dynamics of a DYN deck.
    dynamics: Option<InverseDynamics>,
    /// The transfer functions to compute at every position.
    order: Option<TransferOrder>,
    cancel: &'a AtomicBool,
    progress: Option<Progress>,
}

impl Observer for Watch<'_> {
    fn position(&mut self, view: &PositionView<'_>) {
        record(&self.quantities, view, self.dynamics.as_mut(), &mut self.table);
        self.coords.extend_from_slice(&view.state.x);
        self.positions += 1;
        if let Some(p) = self.progress.as_mut() {
            p.report(view.index + 1);
        }
    }

    fn stop_requested(&self) -> bool {
        self.cancel.load(Ordering::Relaxed) || self.progress.as_ref().is_some_and(|p| p.error.is_some())
    }

    fn transfer_order(&self) -> Option<TransferOrder> {
        self.order
    }

    fn simulated(&mut self, time: f64, end: f64) {
        if let Some(p) = self.progress.as_mut() {
            p.report_share(if end > 0.0 { (time / end).clamp(0.0, 1.0) } else { 1.0 });
        }
    }
}

/// The transfer functions a run computes: `Some(1)` first order, `Some(2)`
/// first and second order, `None` what the deck's own buffers need (and
/// det(D^c), so at least the first order), as `run_deck` computes them.
///
/// The solver predicts each position differently when it computes no second
/// order (for one input), so only runs that compute the same orders give the
/// same numbers to the last bit.
pub fn transfer_order(c: &Compiled, order: Option<u8>) -> PyResult<TransferOrder> {
    // Inverse dynamics is made from the second order.
    if c.dynamics.is_some() && matches!(order, None | Some(1 | 2)) {
        return Ok(TransferOrder::Second);
    }
    match order {
        None => Ok(c
            .buffers
            .iter()
            .filter_map(|b| b.quantity.transfer_order())
            .fold(TransferOrder::First, TransferOrder::max)),
        Some(1) => Ok(TransferOrder::First),
        Some(2) => Ok(TransferOrder::Second),
        Some(k) => Err(PyValueError::new_err(format!("order must be 1, 2 or None, not {k}"))),
    }
}

/// The masses and loads and the tolerances of a DYN SIM deck, whose motion
/// is simulated; None for any other deck.
pub fn simulation<'a>(
    mode: Mode,
    dynamics: Option<&'a Dynamics>,
    integration: &'a Integration,
) -> Option<(&'a Dynamics, &'a Integration)> {
    Some((dynamics.filter(|_| mode == Mode::DynSim)?, integration))
}

/// Moves the mechanism through `motion` (position 1 alone without one):
/// simulated with `simulation` ([`simulation`]), run otherwise.
pub fn move_through(
    mech: &Mechanism,
    state: &mut State,
    motion: Option<&Motion>,
    params: &Params,
    simulation: Option<(&Dynamics, &Integration)>,
    observer: &mut dyn Observer,
) -> Result<(RunReport, Option<SimReport>), SolveError> {
    match (motion, simulation) {
        (Some(m), Some((d, tol))) => {
            simulate(mech, state, m, params, tol, d, observer).map(|s| (s.run.clone(), Some(s)))
        }
        _ => run(mech, state, motion, params, observer).map(|r| (r, None)),
    }
}

/// A finished run with everything recorded.
pub struct FullRun {
    /// The compiled deck, state at the last position.
    pub compiled: Compiled,
    /// Row-major, positions x `width`: the deck's buffers, [`full_quantities`], time, det(D^c).
    pub table: Vec<f64>,
    /// Row-major, positions x co-ordinates.
    pub coords: Vec<f64>,
    /// Positions computed.
    pub positions: usize,
    /// Columns of `table`.
    pub width: usize,
    /// Number of the deck's buffers at the front of `table`.
    pub n_buffers: usize,
    /// What the run did.
    pub report: RunReport,
    /// What the integrator of a simulation did.
    pub sim: Option<SimReport>,
    /// Steps the motion asked for.
    pub steps: usize,
    /// The co-ordinates as the deck gives them (before the adjustment of position 1).
    pub given: Vec<f64>,
}

/// What running one deck text gave.
pub enum Outcome {
    /// The deck has a mistake.
    Deck(Diagnostics),
    /// Position 1 could not be computed.
    Failed(Box<Compiled>, SolveError),
    /// The run (possibly stopped early; see the report).
    Ran(Box<FullRun>),
    /// The results would not fit in the memory limit: nothing was run.
    Refused(String),
    /// A change names a co-ordinate or row the deck does not have.
    BadChange(String),
}

/// Runs a compiled deck (its motion only when `with_motion`), recording
/// everything, unless the results would take more than `memory_limit`
/// bytes. Needs no GIL unless `progress` is given. Returns the error the
/// progress callback raised, if any, beside the outcome.
pub fn execute(
    mut c: Compiled,
    with_motion: bool,
    order: TransferOrder,
    cancel: &AtomicBool,
    progress: Option<Progress>,
    memory_limit: u64,
) -> (Outcome, Option<PyErr>) {
    if let (false, Some(m)) = (with_motion, c.motion.as_ref()) {
        // Position 1 alone, as a run would compute it.
        m.apply_initial_inputs(&c.mechanism, &mut c.state);
    }
    let mut quantities: Vec<Quantity> = c.buffers.iter().map(|b| b.quantity).collect();
    let n_buffers = quantities.len();
    quantities.extend(full_quantities(&c.mechanism, c.dynamics.is_some()));
    quantities.extend([Quantity::Time, Quantity::Det]);
    let given = c.state.x.clone();
    let motion = if with_motion { c.motion.as_ref() } else { None };
    let steps = motion.map_or(0, |m| m.steps);
    let (width, n) = (quantities.len(), c.mechanism.n_coords());
    if let Some(message) = errors::memory_refusal(steps + 1, width + n, memory_limit) {
        return (Outcome::Refused(message), None);
    }
    let mut watch = Watch {
        table: Vec::with_capacity((steps + 1) * width),
        coords: Vec::with_capacity((steps + 1) * n),
        quantities,
        positions: 0,
        dynamics: c.dynamics.as_ref().map(|d| InverseDynamics::new(&c.mechanism, d.clone())),
        order: Some(order),
        cancel,
        progress,
    };
    let sim = simulation(c.mode, c.dynamics.as_ref(), &c.integration);
    let result = move_through(&c.mechanism, &mut c.state, motion, &c.params, sim, &mut watch);
    let raised = watch.progress.and_then(|p| p.error);
    let outcome = match result {
        Ok((report, sim)) => Outcome::Ran(Box::new(FullRun {
            compiled: c,
            table: watch.table,
            coords: watch.coords,
            positions: watch.positions,
            width,
            n_buffers,
            report,
            sim,
            steps,
            given,
        })),
        Err(e) => Outcome::Failed(Box::new(c), e),
    };
    (outcome, raised)
}

/// Runs a variant of a compiled deck (a copy of `compiled` with `changes`
/// made) without the GIL, for worker threads.
pub fn run_variant(
    compiled: &Result<Compiled, Diagnostics>,
    changes: &[Change],
    order: Option<u8>,
    cancel: &AtomicBool,
    memory_limit: u64,
) -> Outcome {
    let c = match compiled {
        Ok(c) => c,
        Err(d) => return Outcome::Deck(d.clone()),
    };
    let mut c = c.clone();
    if let Err(message) = changes.iter().try_for_each(|ch| ch.apply(&mut c)) {
        return Outcome::BadChange(message);
    }
    // `order` has been checked by the caller.
    let order = transfer_order(&c, order).unwrap_or(TransferOrder::Second);
    execute(c, true, order, cancel, None, memory_limit).0
}

/// The run as a dict: `table` (positions x columns: the deck's buffers, in
/// the order of `buffer_numbers`, then [`full_quantities`], time and
/// det(D^c)), `coords`, the model's sizes, `report`, and the `model` echo
/// and `storage` requests as `run_deck` gives them.
fn run_dict(py: Python<'_>, r: FullRun) -> PyResult<Bound<'_, PyDict>> {
    let mech = &r.compiled.mechanism;
    let (nb, positions, n, nd) = (r.n_buffers, r.positions, mech.n_coords(), mech.n_dof());
    // The values of the rows at position 1, for the model echo.
    let rows_at = nb + nd + n * (nd + nd * nd + 2);
    let rw = 1 + nd + nd * nd + 2;
    let row_value = |k: usize| r.table.get(rows_at + k * rw).copied().unwrap_or(f64::NAN);
    let prescribed: Vec<f64> = (0..mech.n_prescribed()).map(row_value).collect();
    let dependent: Vec<f64> = (0..mech.n_dependent()).map(|k| row_value(mech.n_prescribed() + k)).collect();
    let at_1 = r.coords.get(..n).unwrap_or(&r.given);

    let d = PyDict::new(py);
    d.set_item("model", convert::model(py, &r.compiled, &r.given, at_1, &prescribed, &dependent)?)?;
    d.set_item("storage", convert::storage(py, &r.compiled)?)?;
    d.set_item("report", convert::report(py, mech, &r.report, r.steps)?)?;
    d.set_item("buffer_numbers", r.compiled.buffers.iter().map(|b| b.number).collect::<Vec<_>>())?;
    d.set_item("n_buffers", nb)?;
    d.set_item("n_coords", n)?;
    d.set_item("n_dof", nd)?;
    d.set_item("n_prescribed", mech.n_prescribed())?;
    d.set_item("n_dependent", mech.n_dependent())?;
    d.set_item("dynamic", r.compiled.dynamics.is_some())?;
    d.set_item("simulation", r.sim.as_ref().map(|s| convert::simulation(py, s)).transpose()?)?;
    d.set_item("table", convert::array2(py, r.table, positions, r.width)?)?;
    d.set_item("coords", convert::array2(py, r.coords, positions, n)?)?;
    Ok(d)
}

/// The outcome as a run dict, or as the exception it amounts to.
pub fn outcome_dict<'py>(py: Python<'py>, outcome: Outcome, path: &Path) -> PyResult<Bound<'py, PyDict>> {
    match outcome {
        Outcome::Ran(r) => run_dict(py, *r),
        Outcome::Deck(d) => Err(errors::deck_error(py, path, &d)),
        Outcome::Refused(message) => Err(errors::ResourceError::new_err(message)),
        Outcome::BadChange(message) => Err(PyValueError::new_err(message)),
        Outcome::Failed(mut c, e) => {
            let c = &mut *c;
            Err(errors::position_one_error(py, &c.mechanism, &mut c.state, &e))
        }
    }
}

/// A change of one number of a compiled deck, as a variant of a design
/// study makes it: the value of a co-ordinate (its XFIX or XMOV value) or of
/// a prescribed row (its PARA value), both numbered as in the deck.
#[derive(Debug, Clone, Copy)]
pub enum Change {
    /// Co-ordinate `number` gets `value`.
    Coord(usize, f64),
    /// Prescribed row `number` gets `value`.
    Row(usize, f64),
}

impl Change {
    /// From the Python triple (kind, number, value): kind 0 a co-ordinate, 1 a prescribed row.
    pub fn from_triple((kind, number, value): (u8, usize, f64)) -> PyResult<Change> {
        match kind {
            0 => Ok(Change::Coord(number, value)),
            1 => Ok(Change::Row(number, value)),
            _ => Err(PyValueError::new_err(format!("a change is of kind 0 (co-ordinate) or 1 (row), not {kind}"))),
        }
    }

    /// Makes the change in `c`, as if the deck had said so (the model echo
    /// included); an error when the deck has no such co-ordinate or row.
    pub fn apply(self, c: &mut Compiled) -> Result<(), String> {
        match self {
            Change::Coord(number, value) => {
                let x = number.checked_sub(1).and_then(|i| c.state.x.get_mut(i));
                *x.ok_or_else(|| format!("the deck has no co-ordinate {number}"))? = value;
            }
            Change::Row(number, value) => {
                let k = number.checked_sub(1).filter(|&k| k < c.prescribed.len() && k < c.state.target.len());
                let k = k.ok_or_else(|| format!("the deck has no prescribed row {number}"))?;
                c.state.target[k] = value;
                c.prescribed[k].para = Some(value);
            }
        }
        Ok(())
    }
}

/// Runs the deck `text` (named `path` in messages; MOV_FUNC files are read
/// from `base_dir`) and returns everything it computed.
///
/// With `motion=False` only position 1 is computed (as `check_deck` does).
/// `order` says which transfer functions to compute at every position (see
/// [`transfer_order`]); quantities made from ones not computed are NaN.
/// `progress(done, total)` is called about every 1% of the positions. A
/// motion that stops early returns every position computed so far and the
/// reason in `report["stop"]`; a deck mistake raises `DeckError`, a failure
/// at position 1 `AssemblyError`, `ConvergenceError` or `LimitPositionError`.
/// Ctrl-C returns the positions so far with `interrupted` set, as `run_deck`;
/// results that would take more than `memory_limit` bytes raise
/// `ResourceError` before the run starts.
#[pyfunction]
#[pyo3(signature = (text, path, base_dir, motion=true, progress=None, order=Some(2), memory_limit=u64::MAX))]
#[allow(clippy::too_many_arguments)]
pub fn run_deck_text<'py>(
    py: Python<'py>,
    text: &str,
    path: PathBuf,
    base_dir: PathBuf,
    motion: bool,
    progress: Option<Py<PyAny>>,
    order: Option<u8>,
    memory_limit: u64,
) -> PyResult<Bound<'py, PyDict>> {
    let c = py.detach(|| compile_text(text, &path, &base_dir)).map_err(|d| errors::deck_error(py, &path, &d))?;
    run_compiled(py, c, &path, motion, progress, order, memory_limit)
}

/// Runs a compiled deck (its motion when `motion`) and returns the run's
/// dict with `interrupted` set: what `run_deck_text` and a kept
/// `Model` return alike.
pub fn run_compiled<'py>(
    py: Python<'py>,
    c: Compiled,
    path: &Path,
    motion: bool,
    progress: Option<Py<PyAny>>,
    order: Option<u8>,
    memory_limit: u64,
) -> PyResult<Bound<'py, PyDict>> {
    let order = transfer_order(&c, order)?;
    let total = if motion { c.motion.as_ref().map_or(0, |m| m.steps) + 1 } else { 1 };
    let cancel = AtomicBool::new(false);
    let (outcome, raised) =
        py.detach(|| execute(c, motion, order, &cancel, Some(Progress::new(progress, total)), memory_limit));
    let interrupted = errors::interrupted(py, raised, matches!(outcome, Outcome::Ran(_)))?;
    let d = outcome_dict(py, outcome, path)?;
    d.set_item("interrupted", interrupted)?;
    Ok(d)
}

/// Reads and compiles the deck `text` without solving anything and returns
/// what it declares: `coordinates`, `elements`, `prescribed` and `dependent`
/// rows with their FORM terms, `dofs`, `motion` (None without a MOVEMENT
/// block), `tol`, `max_iter`, `storage`, `inttol` (INTTOL's rtol and atol,
/// None without it), the `mode` and the `dynamics`
/// (masses and loads, LOADFUNC tables with their file names; None for a
/// KIN ANA deck) and the `optimise` block of a KIN OPT deck
/// ([`convert::optimise`]; None otherwise). Numbers are the deck's own.
#[pyfunction]
pub fn describe_deck_text<'py>(
    py: Python<'py>,
    text: &str,
    path: PathBuf,
    base_dir: PathBuf,
) -> PyResult<Bound<'py, PyDict>> {
    let parsed = py.detach(|| {
        let deck = mechfem_deck::parse_str(text, &path)?;
        let c = mechfem_deck::compile(&deck, &base_dir)?;
        Ok::<_, Diagnostics>((deck, c))
    });
    let (deck, c) = parsed.map_err(|d| errors::deck_error(py, &path, &d))?;
    let mech = &c.mechanism;
    let d = PyDict::new(py);
    let coords = (0..mech.n_coords())
        .map(|i| {
            let cd = PyDict::new(py);
            cd.set_item("number", i + 1)?;
            cd.set_item("moving", mech.is_moving(i))?;
            cd.set_item("value", c.state.x[i])?;
            Ok(cd)
        })
        .collect::<PyResult<Vec<_>>>()?;
    d.set_item("coordinates", coords)?;
    d.set_item("elements", convert::elements(py, &c)?)?;
    d.set_item("prescribed", convert::rows(py, &c.prescribed, &[])?)?;
    d.set_item("dependent", convert::rows(py, &c.dependent, &[])?)?;
    d.set_item("dofs", (0..mech.n_dof()).map(|j| mech.input_row(j) + 1).collect::<Vec<_>>())?;
    d.set_item("tol", c.params.tol)?;
    d.set_item("max_iter", c.params.max_iter)?;
    let motion = match &c.motion {
        None => None,
        Some(m) => {
            let files: Vec<Option<String>> = (1..=m.inputs.len())
                .map(|j| {
                    deck.movement.as_ref().and_then(|mv| {
                        mv.motions.iter().find_map(|md| match &md.kind {
                            MotionKind::Function(f) if md.dof.value == j as i64 => Some(f.value.clone()),
                            _ => None,
                        })
                    })
                })
                .collect();
            let inputs = m
                .inputs
                .iter()
                .zip(files)
                .map(|(im, file)| {
                    let id = PyDict::new(py);
                    let (kind, value) = match im {
                        InputMotion::Relative { delta } => ("by", Some(*delta)),
                        InputMotion::Absolute { end } => ("to", Some(*end)),
                        InputMotion::Free { ds } => ("free", Some(*ds)),
                        InputMotion::Dynamic { v0 } => ("dynamic", Some(*v0)),
                        InputMotion::Table { .. } => ("table", None),
                    };
                    id.set_item("kind", kind)?;
                    id.set_item("value", value)?;
                    let table = match im {
                        InputMotion::Table { rows } => Some(rows.iter().map(|r| r.to_vec()).collect::<Vec<_>>()),
                        _ => None,
                    };
                    id.set_item("rows", table)?;
                    id.set_item("file", file)?;
                    Ok(id)
                })
                .collect::<PyResult<Vec<_>>>()?;
            let md = PyDict::new(py);
            md.set_item("steps", m.steps)?;
            md.set_item("dt", m.dt)?;
            md.set_item("inputs", inputs)?;
            Some(md)
        }
    };
    d.set_item("motion", motion)?;
    d.set_item("storage", convert::storage(py, &c)?)?;
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
    // INTTOL as the deck gives it (None without: the tolerances are then ACCURACY's).
    let inttol = deck.movement.as_ref().and_then(|m| m.inttol.as_ref()).map(|t| vec![t.rtol.value, t.atol.value]);
    d.set_item("inttol", inttol)?;
    d.set_item("mode", c.mode.name())?;
    d.set_item("dynamics", c.dynamics.as_ref().map(|m| convert::dynamics(py, m, &files)).transpose()?)?;
    d.set_item("optimise", c.optimise.as_ref().map(|o| convert::optimise(py, o)).transpose()?)?;
    Ok(d)
}
