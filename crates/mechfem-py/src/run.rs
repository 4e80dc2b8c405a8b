//! What a run gives Python: one [`Run`], however it was started (a deck
//! file with `run_deck`, deck text with `run_deck_text`, a kept `Model`, a
//! variant of `run_deck_variants`).
//!
//! A [`Run`] owns the core's columns as the run left them and hands each
//! as a numpy array made on first access, which owns the column buffer
//! (no copy) and is handed again on every later access. What is the same
//! for every run of one compiled deck (the layout, the storage, the
//! buffer numbers, the model echo's fixed part) is converted once into
//! [`Shared`], whose Python objects every run holds.

use std::path::Path;
use std::sync::Mutex;

use mechfem_core::run::{Layout, MemoryRefusal, SimReport, TransferRecord};
use mechfem_core::{Lost, RunReport, SolveError, State};
use mechfem_deck::{Compiled, Diagnostics};
use numpy::ndarray::{Array2, ShapeBuilder};
use numpy::{PyArray1, PyArray2};
use pyo3::exceptions::{PyIndexError, PyValueError};
use pyo3::prelude::*;
use pyo3::sync::PyOnceLock;
use pyo3::types::{PyDict, PyList, PySlice, PyTuple};

use crate::echo::EchoModel;
use crate::report::Report;
use crate::simulated::Simulation;
use crate::{convert, errors};

/// A finished run of deck text with everything recorded, ready to be
/// wrapped for Python.
pub struct FullRun {
    /// The full layout ([`Layout`]): positions x its width, made when asked for.
    pub table: RecordedTable,
    /// The deck's buffers in the order of their definitions, column by column.
    pub buffers: Vec<f64>,
    /// Row-major, positions x co-ordinates.
    pub coords: Vec<f64>,
    /// Positions computed.
    pub positions: usize,
    /// Columns of `table`.
    pub width: usize,
    /// What the run did.
    pub report: RunReport,
    /// What the integrator of a simulation did.
    pub sim: Option<SimReport>,
    /// Steps the motion asked for.
    pub steps: usize,
    /// The co-ordinates as the deck gives them (before the adjustment of position 1).
    pub given: Vec<f64>,
    /// PARA value of each prescribed row.
    pub para: Vec<Option<f64>>,
    /// Value of every row, prescribed then dependent, at position 1.
    pub rows_at_1: Vec<f64>,
}

/// What running one deck text gave.
pub enum Outcome {
    /// The deck has a mistake.
    Deck(Diagnostics),
    /// Position 1 could not be computed (the state where it failed).
    Failed(Box<State>, SolveError),
    /// The run (possibly stopped early; see the report).
    Ran(Box<FullRun>),
    /// The results would not fit in the memory limit: nothing was run.
    Refused(MemoryRefusal),
    /// A change names a co-ordinate or row the deck does not have.
    BadChange(mechfem_core::DesignError),
}

/// The full layout's table of a run as the motion recorded it
/// ([`TransferRecord`]), made column by column ([`Layout::column_values`])
/// when Python first asks for it, each column then multiplied by its factor
/// from the core's units to the deck's.
pub struct RecordedTable {
    layout: Layout,
    record: TransferRecord,
    /// The factor of each column; empty when every factor is 1.
    scales: Vec<f64>,
}

impl RecordedTable {
    /// The table of `layout` of the positions of `record`, in the core's units.
    pub fn new(layout: Layout, record: TransferRecord) -> RecordedTable {
        RecordedTable { layout, record, scales: Vec::new() }
    }

    /// The table's columns in other units: column k multiplied by `scales[k]`.
    pub fn scale_columns(&mut self, scales: Vec<f64>) {
        self.scales = scales;
    }

    /// Column `c` alone at every position, as [`Self::values`] holds it:
    /// a study or a plot that reads a few quantities of a long run does not
    /// make the whole table.
    fn column(&self, c: usize) -> Vec<f64> {
        let mut out = Vec::with_capacity(self.record.positions());
        self.append_column(c, &mut out);
        out
    }

    /// The values, column after column.
    fn values(&self) -> Vec<f64> {
        let mut out = Vec::with_capacity(self.layout.width() * self.record.positions());
        for c in 0..self.layout.width() {
            self.append_column(c, &mut out);
        }
        out
    }

    /// Appends column `c` at every position to `out`, in the deck's units.
    fn append_column(&self, c: usize, out: &mut Vec<f64>) {
        let start = out.len();
        self.layout.column_values(&self.record, c, out);
        out.resize(start + self.record.positions(), f64::NAN);
        if let Some(&k) = self.scales.get(c).filter(|&&k| k != 1.0) {
            out[start..].iter_mut().for_each(|v| *v *= k);
        }
    }
}

/// The values of a [`Lazy`] table until they become a numpy array.
enum Values {
    /// Made, rows x cols.
    Made(Array2<f64>),
    /// Still to be made from a run's record (rows x cols, column after column).
    Recorded(Box<RecordedTable>, usize, usize),
}

/// A rows x cols table of the core, made a numpy array (owning its values)
/// when Python first asks for it.
struct Lazy {
    values: Mutex<Option<Values>>,
    array: PyOnceLock<Py<PyAny>>,
    /// Its columns.
    cols: usize,
}

impl Lazy {
    /// `data` column by column (`columns`) or row by row.
    fn new(data: Vec<f64>, rows: usize, cols: usize, columns: bool) -> PyResult<Lazy> {
        Ok(Lazy::of(Values::Made(array(data, rows, cols, columns)?), cols))
    }

    /// The `rows` x `cols` table of `table`, made when first asked for.
    fn recorded(table: RecordedTable, rows: usize, cols: usize) -> Lazy {
        Lazy::of(Values::Recorded(Box::new(table), rows, cols), cols)
    }

    fn of(values: Values, cols: usize) -> Lazy {
        Lazy { values: Mutex::new(Some(values)), array: PyOnceLock::new(), cols }
    }

    /// Column `c` at every position: a view of the table once it is made,
    /// else made alone from the run's record.
    fn column<'py>(&self, py: Python<'py>, c: usize) -> PyResult<Bound<'py, PyAny>> {
        if c >= self.cols {
            return Err(PyIndexError::new_err(c));
        }
        if self.array.get(py).is_none() {
            let values = self.values.lock().unwrap_or_else(|e| e.into_inner());
            if let Some(Values::Recorded(table, _, _)) = values.as_ref() {
                return Ok(PyArray1::from_vec(py, table.column(c)).into_any());
            }
        }
        self.get(py)?.get_item((PySlice::full(py), c))
    }

    fn get<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let array = self.array.get_or_try_init(py, || {
            let values = self.values.lock().unwrap_or_else(|e| e.into_inner()).take();
            let values = match values.ok_or_else(|| errors::lost(Lost::TableTakenTwice))? {
                Values::Made(values) => values,
                Values::Recorded(table, rows, cols) => array(table.values(), rows, cols, true)?,
            };
            Ok::<_, PyErr>(PyArray2::from_owned_array(py, values).into_any().unbind())
        })?;
        Ok(array.bind(py).clone())
    }
}

/// `data` as a rows x cols array, column by column (`columns`) or row by row.
fn array(data: Vec<f64>, rows: usize, cols: usize, columns: bool) -> PyResult<Array2<f64>> {
    let shape = (rows, cols).set_f(columns);
    Array2::from_shape_vec(shape, data).map_err(|e| PyValueError::new_err(e.to_string()))
}

/// Where a run's buffers are.
enum Buffers {
    /// Columns `start..start + width` of the table (a deck file's run).
    Block(usize, usize),
    /// A table of their own (a run of deck text, whose table is the full layout).
    Own(Lazy),
}

/// One run, as every run returns it: the core's columns (`table`, laid
/// out as `layout` names its blocks, `coords`, `buffers`) as numpy arrays,
/// the model's sizes, and the run report, model echo, storage requests and
/// simulation report.
#[pyclass(module = "mechfem._core", name = "Run", frozen)]
pub struct Run {
    positions: usize,
    n_coords: usize,
    n_dof: usize,
    n_prescribed: usize,
    n_dependent: usize,
    dynamic: bool,
    interrupted: bool,
    stopped: bool,
    table: Lazy,
    coords: Lazy,
    buffers: Buffers,
    layout: Py<PyDict>,
    buffer_numbers: Py<PyAny>,
    hodograph_coords: Py<PyAny>,
    report: Py<Report>,
    model: Py<EchoModel>,
    storage: Py<PyAny>,
    simulation: Option<Py<Simulation>>,
}

#[pymethods]
impl Run {
    /// Positions computed.
    #[getter]
    fn positions(&self) -> usize {
        self.positions
    }

    /// Number of co-ordinates.
    #[getter]
    fn n_coords(&self) -> usize {
        self.n_coords
    }

    /// Degrees of freedom.
    #[getter]
    fn n_dof(&self) -> usize {
        self.n_dof
    }

    /// Prescribed rows.
    #[getter]
    fn n_prescribed(&self) -> usize {
        self.n_prescribed
    }

    /// Dependent form parameters.
    #[getter]
    fn n_dependent(&self) -> usize {
        self.n_dependent
    }

    /// The deck has masses and loads (DYN ANA, DYN SIM).
    #[getter]
    fn dynamic(&self) -> bool {
        self.dynamic
    }

    /// Ctrl-C stopped the run; the positions before it are here.
    #[getter]
    fn interrupted(&self) -> bool {
        self.interrupted
    }

    /// The motion stopped before its end (the report's `stop` says why).
    #[getter]
    fn stopped(&self) -> bool {
        self.stopped
    }

    /// Positions x the columns of `layout`, each column contiguous.
    #[getter]
    fn table<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        self.table.get(py)
    }

    /// Column `c` of `table` at every position, without making the whole
    /// table when it is not made yet.
    fn column<'py>(&self, py: Python<'py>, c: usize) -> PyResult<Bound<'py, PyAny>> {
        self.table.column(py, c)
    }

    /// Positions x co-ordinates.
    #[getter]
    fn coords<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        self.coords.get(py)
    }

    /// Positions x the deck's buffers, in the order of `buffer_numbers`.
    #[getter]
    fn buffers<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        match &self.buffers {
            Buffers::Own(values) => values.get(py),
            Buffers::Block(start, width) => {
                let columns = PySlice::new(py, *start as isize, (start + width) as isize, 1);
                let all = PySlice::full(py);
                self.table.get(py)?.get_item(PyTuple::new(py, [all, columns])?)
            }
        }
    }

    /// Block name -> (first column, shape at one position).
    #[getter]
    fn layout<'py>(&self, py: Python<'py>) -> Bound<'py, PyDict> {
        self.layout.bind(py).clone()
    }

    /// The deck's buffer numbers, in the order of their definitions.
    #[getter]
    fn buffer_numbers<'py>(&self, py: Python<'py>) -> Bound<'py, PyAny> {
        self.buffer_numbers.bind(py).clone()
    }

    /// The co-ordinates (1-based) of the `hodograph` block's columns.
    #[getter]
    fn hodograph_coords<'py>(&self, py: Python<'py>) -> Bound<'py, PyAny> {
        self.hodograph_coords.bind(py).clone()
    }

    /// What the run did: the adjustment of position 1, limit positions, why it stopped.
    #[getter]
    fn report<'py>(&self, py: Python<'py>) -> Bound<'py, Report> {
        self.report.bind(py).clone()
    }

    /// The model as compiled, with its values at position 1.
    #[getter]
    fn model<'py>(&self, py: Python<'py>) -> Bound<'py, EchoModel> {
        self.model.bind(py).clone()
    }

    /// The storage requests.
    #[getter]
    fn storage<'py>(&self, py: Python<'py>) -> Bound<'py, PyAny> {
        self.storage.bind(py).clone()
    }

    /// What the integrator of a simulation did (None for a prescribed motion).
    #[getter]
    fn simulation(&self, py: Python<'_>) -> Option<Py<Simulation>> {
        self.simulation.as_ref().map(|s| s.clone_ref(py))
    }
}

/// The parts of a [`Run`] of a deck file (`run_deck`): its table holds the
/// buffers as one block.
pub struct DeckRun<'py> {
    /// The table, column by column, positions x `width`.
    pub table: Vec<f64>,
    /// Columns of `table`.
    pub width: usize,
    /// Row-major, positions x co-ordinates.
    pub coords: Vec<f64>,
    /// Positions computed.
    pub positions: usize,
    /// Number of co-ordinates.
    pub n_coords: usize,
    /// The buffers block: first column and width.
    pub buffers: (usize, usize),
    /// The layout, buffer numbers and hodograph co-ordinates every run of the deck shares.
    pub shape: [Bound<'py, PyAny>; 3],
    /// The run's report.
    pub report: Bound<'py, Report>,
    /// The model echo.
    pub model: Bound<'py, EchoModel>,
    /// The storage requests (`_core.Storage`).
    pub storage: Bound<'py, PyAny>,
    /// The simulation report.
    pub simulation: Option<Py<Simulation>>,
    /// Ctrl-C stopped it.
    pub interrupted: bool,
    /// The motion stopped early.
    pub stopped: bool,
}

impl Run {
    /// The run of a deck file of `c` (see [`DeckRun`]).
    pub fn of_deck(c: &Compiled, r: DeckRun<'_>) -> PyResult<Run> {
        let mech = &c.mechanism;
        let [layout, buffer_numbers, hodograph_coords] = r.shape;
        let (report, model) = (r.report, r.model);
        Ok(Run {
            positions: r.positions,
            n_coords: r.n_coords,
            n_dof: mech.n_dof(),
            n_prescribed: mech.n_prescribed(),
            n_dependent: mech.n_dependent(),
            dynamic: c.dynamics.is_some(),
            interrupted: r.interrupted,
            stopped: r.stopped,
            table: Lazy::new(r.table, r.positions, r.width, true)?,
            coords: Lazy::new(r.coords, r.positions, r.n_coords, false)?,
            buffers: Buffers::Block(r.buffers.0, r.buffers.1),
            layout: layout.cast_into::<PyDict>()?.unbind(),
            buffer_numbers: buffer_numbers.unbind(),
            hodograph_coords: hodograph_coords.unbind(),
            report: report.unbind(),
            model: model.unbind(),
            storage: r.storage.unbind(),
            simulation: r.simulation,
        })
    }
}

/// What every run of one compiled deck text has in common, converted for
/// Python once. Each run holds these very objects: they are not to be
/// changed.
pub struct Shared {
    /// Block name -> (first column, shape at one position), the core's full layout.
    layout: Py<PyDict>,
    storage: Py<PyAny>,
    buffer_numbers: Py<PyList>,
    hodograph_coords: Py<PyList>,
    echo: convert::Echo,
    /// The model echo and the report of the last run, with the numbers
    /// they were made from (bit patterns): a run with the same numbers
    /// hands Python the same dicts, which it converted once.
    last_echo: Mutex<Option<(Vec<u64>, Py<EchoModel>)>>,
    last_report: Mutex<Option<(Vec<u64>, Py<Report>)>>,
}

/// The object kept in `slot` for `key`, else the one `make` builds (then kept).
fn kept<'py, T>(
    py: Python<'py>,
    slot: &Mutex<Option<(Vec<u64>, Py<T>)>>,
    key: Vec<u64>,
    make: impl FnOnce() -> PyResult<Bound<'py, T>>,
) -> PyResult<Bound<'py, T>> {
    let lock = || slot.lock().unwrap_or_else(|e| e.into_inner());
    if let Some((_, d)) = lock().as_ref().filter(|(k, _)| *k == key) {
        return Ok(d.bind(py).clone());
    }
    // Made without the lock held: making it runs Python code.
    let d = make()?;
    *lock() = Some((key, d.clone().unbind()));
    Ok(d)
}

impl Shared {
    /// The Python objects of compiled deck `c` that every run of it shares.
    pub fn new(py: Python<'_>, c: &Compiled) -> PyResult<Shared> {
        let layout = Layout::full(&c.mechanism, c.dynamics.is_some());
        Ok(Shared {
            layout: convert::layout(py, layout.blocks())?.unbind(),
            storage: convert::storage(py, c)?.unbind(),
            buffer_numbers: PyList::new(py, c.buffers.iter().map(|b| b.number))?.unbind(),
            hodograph_coords: PyList::empty(py).unbind(),
            echo: convert::Echo::new(py, c)?,
            last_echo: Mutex::new(None),
            last_report: Mutex::new(None),
        })
    }

    /// The run `r` of deck text `c`, whose runs share these objects.
    fn run(&self, py: Python<'_>, c: &Compiled, mut r: FullRun) -> PyResult<Run> {
        crate::names::full_run(c, &mut r);
        let mech = &c.mechanism;
        let (positions, n, np) = (r.positions, mech.n_coords(), mech.n_prescribed());
        let at_1 = r.coords.get(..n).unwrap_or(&r.given);
        let (prescribed, dependent) = r.rows_at_1.split_at(np.min(r.rows_at_1.len()));
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        let mut key = bits(&r.given);
        key.extend(bits(at_1).into_iter().chain(bits(prescribed)).chain(bits(dependent)));
        key.extend(r.para.iter().map(|p| p.map_or(u64::MAX, f64::to_bits)));
        let echo = &self.echo;
        let model =
            kept(py, &self.last_echo, key, || echo.model(py, &r.given, at_1, prescribed, dependent, Some(&r.para)))?;
        let report = || Bound::new(py, Report::of(py, mech, &c.names, &c.dynamics_lines, &r.report, r.steps)?);
        let report = match Report::plain_key(&r.report, r.steps).filter(|_| r.sim.is_none()) {
            Some(key) => kept(py, &self.last_report, key, report)?,
            None => report()?,
        };
        Ok(Run {
            positions,
            n_coords: n,
            n_dof: mech.n_dof(),
            n_prescribed: np,
            n_dependent: mech.n_dependent(),
            dynamic: c.dynamics.is_some(),
            interrupted: false,
            stopped: r.report.stop.is_some(),
            table: Lazy::recorded(r.table, positions, r.width),
            coords: Lazy::new(r.coords, positions, n, false)?,
            buffers: Buffers::Own(Lazy::new(r.buffers, positions, c.buffers.len(), true)?),
            layout: self.layout.clone_ref(py),
            buffer_numbers: self.buffer_numbers.clone_ref(py).into_any(),
            hodograph_coords: self.hodograph_coords.clone_ref(py).into_any(),
            report: report.unbind(),
            model: model.unbind(),
            storage: self.storage.clone_ref(py),
            simulation: r.sim.as_ref().map(|sim| Py::new(py, Simulation::of(sim))).transpose()?,
        })
    }
}

/// The outcome as a [`Run`], or as the exception it amounts to; `text` is
/// the compiled deck that ran, with its shared objects (None for a deck
/// that did not compile); `interrupted` is set on the run.
pub fn outcome_run(
    py: Python<'_>,
    outcome: Outcome,
    text: Option<(&Compiled, &Shared)>,
    path: &Path,
    interrupted: bool,
) -> PyResult<Run> {
    let lost = || errors::lost(Lost::CompiledDeck);
    match outcome {
        Outcome::Ran(r) => {
            let (c, s) = text.ok_or_else(lost)?;
            let mut run = s.run(py, c, *r)?;
            run.interrupted = interrupted;
            Ok(run)
        }
        Outcome::Deck(d) => Err(errors::deck_error(py, path, &d)),
        Outcome::Refused(refusal) => Err(errors::resource_error(py, &refusal)),
        Outcome::BadChange(e) => Err(errors::change_error(&e)),
        Outcome::Failed(mut state, e) => {
            let (c, _) = text.ok_or_else(lost)?;
            Err(errors::position_one_error(
                py,
                &c.mechanism,
                &c.names,
                &c.dynamics_lines,
                &mut state,
                &c.error_as_written(&e),
            ))
        }
    }
}
