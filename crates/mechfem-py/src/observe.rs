//! The observer of every run ([`Recording`]): records what a run keeps
//! ([`Record`]: a deck's [`Selection`], or the full [`Layout`] with the
//! deck's buffers beside it) and every co-ordinate per position, keeps
//! the row values of position 1 for the model echo, stops on request, and
//! reports progress to Python about every 1% of positions ([`Progress`]).

use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

use mechfem_core::dynamics::Dynamics;
use mechfem_core::run::{Columns, InverseDynamics, Layout, Selection, TransferRecord};
use mechfem_core::{recorded_value, Mechanism, Observer, PositionView, Quantity, SolveError, TransferOrder};
use pyo3::prelude::*;

/// What a [`Recording`] keeps of each position, in its table's columns.
pub trait Record {
    /// Whether inverse dynamics is evaluated (and checked) at every
    /// position, before it is recorded.
    fn is_dynamic(&self) -> bool;

    /// Records the position `v` into `table` (`row`: room for one
    /// position); `checked` says inverse dynamics has been evaluated at it.
    fn record(
        &mut self,
        v: &PositionView<'_>,
        dynamics: Option<&mut InverseDynamics>,
        checked: bool,
        table: &mut Columns,
        row: &mut Vec<f64>,
    );
}

impl Record for Selection {
    fn is_dynamic(&self) -> bool {
        Selection::is_dynamic(self)
    }

    fn record(
        &mut self,
        v: &PositionView<'_>,
        dynamics: Option<&mut InverseDynamics>,
        checked: bool,
        table: &mut Columns,
        row: &mut Vec<f64>,
    ) {
        row.clear();
        if checked {
            self.record_evaluated(v, dynamics.as_deref(), row);
        } else {
            Selection::record(self, v, dynamics, row);
        }
        table.push(row);
    }
}

/// The full layout of a run of deck text, recorded as the motion computes
/// it ([`TransferRecord`]: the layout's table is made from it when Python
/// asks for it), and the deck's buffers, made as the run goes: a buffer the
/// layout has a column for from that column, a block of [`BLOCK`] positions
/// at a time while they are still in the cache (to the last bit the value
/// of the column), a co-ordinate and a quantity the layout does not have at
/// every position. It keeps its own record: the [`Recording`]'s table has
/// no column.
pub struct Full {
    /// The core's full layout: the columns of the table made from `record`.
    pub layout: Layout,
    /// Where each of the deck's buffers is found, in the order of their definitions.
    buffers: Vec<Source>,
    /// Every position, as the motion computed it.
    pub record: TransferRecord,
    /// Each buffer's values so far, column after column, room for `total` positions in each.
    made: Vec<f64>,
    /// The positions a column has room for.
    total: usize,
    /// One block of a column, on its way from the record into `made`.
    block: Vec<f64>,
    /// The buffers made at every position (a co-ordinate, a quantity the
    /// layout has no column for) with their place among the buffers.
    every_position: Vec<(usize, Source)>,
    /// The positions whose values of the layout's columns are in `made`.
    made_to: usize,
}

/// How many positions a buffer's column is made for at a time from the
/// record: some 70 kB of it for a four-bar, which the cache still holds.
const BLOCK: usize = 256;

impl Full {
    /// The full layout of `mech` (with inverse dynamics when `dynamic`) and
    /// the buffers recording `buffers`, for `total` positions.
    pub fn new(mech: &Mechanism, dynamic: bool, buffers: &[Quantity], total: usize) -> Full {
        let layout = Layout::full(mech, dynamic);
        let buffers: Vec<Source> = buffers.iter().map(|&q| Source::of(q, &layout)).collect();
        let record = TransferRecord::new(&layout, mech, total);
        // Zeros, for which the allocator asks the system, or fills memory it has.
        let made = vec![0.0; total.saturating_mul(buffers.len())];
        let every_position =
            buffers.iter().copied().enumerate().filter(|(_, b)| !matches!(b, Source::Column(_))).collect();
        let block = Vec::with_capacity(BLOCK);
        Full { made, total, block, every_position, made_to: 0, buffers, record, layout }
    }

    /// Columns of the layout and the buffers together.
    pub fn width(&self) -> usize {
        self.layout.width() + self.buffers.len()
    }

    /// Room for position `k` (0-based) in every column: a run that goes on
    /// past the positions its motion counts makes more.
    fn room_for(&mut self, k: usize) {
        if k < self.total {
            return;
        }
        let total = (k + 1).max(2 * self.total);
        let mut made = vec![0.0; total * self.buffers.len()];
        for (b, column) in self.made.chunks_exact(self.total.max(1)).enumerate() {
            made[b * total..b * total + self.total].copy_from_slice(column);
        }
        (self.made, self.total) = (made, total);
    }

    /// Makes the buffers read from the layout's columns up to the last position recorded.
    fn make_columns(&mut self) {
        let positions = self.made_to..self.record.positions();
        for (b, source) in self.buffers.iter().enumerate() {
            if let Source::Column(c) = *source {
                self.block.clear();
                self.layout.column_values_at(&self.record, c, positions.clone(), &mut self.block);
                let at = b * self.total + positions.start;
                self.made[at..at + self.block.len()].copy_from_slice(&self.block);
            }
        }
        self.made_to = positions.end;
    }

    /// The deck's buffers at every position recorded, column after column.
    pub fn buffer_table(&mut self) -> Vec<f64> {
        self.make_columns();
        let mut made = std::mem::take(&mut self.made);
        let positions = self.record.positions();
        if positions < self.total {
            // A run that stopped early: each column moves up to the end of the one before it.
            for b in 1..self.buffers.len() {
                made.copy_within(b * self.total..b * self.total + positions, b * positions);
            }
            made.truncate(positions * self.buffers.len());
        }
        made
    }
}

/// Where a buffer's value is found at each position.
#[derive(Debug, Clone, Copy)]
enum Source {
    /// In this column of the layout (the same value, to the last bit).
    Column(usize),
    /// Co-ordinate i.
    Coord(usize),
    /// A quantity the layout does not have, evaluated on its own.
    Own(Quantity),
}

impl Source {
    fn of(q: Quantity, layout: &Layout) -> Source {
        match (q, layout.column(q)) {
            (_, Some(c)) => Source::Column(c),
            (Quantity::X0(i), None) => Source::Coord(i),
            (q, None) => Source::Own(q),
        }
    }
}

impl Record for Full {
    /// Inverse dynamics once per position, for the layout and the buffers alike.
    fn is_dynamic(&self) -> bool {
        true
    }

    fn record(
        &mut self,
        v: &PositionView<'_>,
        dynamics: Option<&mut InverseDynamics>,
        _checked: bool,
        _table: &mut Columns,
        _row: &mut Vec<f64>,
    ) {
        let dynamics = dynamics.map(|d| &*d);
        self.record.push(&self.layout, v, dynamics);
        let k = self.record.positions() - 1;
        self.room_for(k);
        for &(b, source) in &self.every_position {
            self.made[b * self.total + k] = match source {
                Source::Coord(i) => v.state.x[i],
                Source::Own(q) => recorded_value(q, v, dynamics),
                // Not in `every_position`: made from the record, a block at a time.
                Source::Column(_) => continue,
            };
        }
        if self.record.positions() - self.made_to >= BLOCK {
            self.make_columns();
        }
    }
}

/// Records a run for Python. Runs without the GIL; attaches only to report
/// progress and to notice Ctrl-C.
pub struct Recording<'a, R> {
    /// What is recorded, in the columns of `table`.
    pub columns: R,
    /// The recorded values at every position, column by column.
    pub table: Columns,
    /// Every co-ordinate at every position, row-major (positions x N).
    pub coords: Vec<f64>,
    /// Values of the prescribed rows at position 1.
    pub prescribed_at_1: Vec<f64>,
    /// Values of the dependent form parameters at position 1.
    pub dependent_at_1: Vec<f64>,
    /// Progress reporting; its error stops the run.
    pub progress: Option<Progress>,
    /// Set by another thread to stop the run.
    cancel: Option<&'a AtomicBool>,
    /// The transfer functions the run computes at every position.
    order: Option<TransferOrder>,
    /// One position's values, before they go into their columns.
    row: Vec<f64>,
    /// Inverse dynamics, evaluated at every position when a dynamic
    /// quantity is recorded.
    dynamics: Option<InverseDynamics>,
    /// Whether inverse dynamics has been evaluated (and checked) at the
    /// position about to be recorded.
    checked: bool,
}

/// Progress reporting of a single run: attaches to Python about every 1%
/// of the positions to call the callback and to notice Ctrl-C.
pub struct Progress {
    callback: Option<Py<PyAny>>,
    total: usize,
    stride: usize,
    /// The most positions reported so far.
    reported: usize,
    /// The count of positions at which Python is next attached to: the
    /// next multiple of the stride with a callback; without one, at which
    /// the clock is looked at ([`Progress::interrupts`]). Kept as a count to
    /// compare with, not found by a division at every position.
    next: usize,
    /// The first error raised by the callback or a signal handler; it stops
    /// the run, and is raised (or, for Ctrl-C, reported) once the positions
    /// so far are kept.
    pub error: Option<PyErr>,
    /// When Python was last asked, for [`Progress::interrupts`].
    asked: Option<Instant>,
    /// When Python was last attached to, for [`Progress::poll`].
    attached: Instant,
}

/// How often [`Progress::interrupts`] asks Python for Ctrl-C.
const INTERRUPT_CHECK: Duration = Duration::from_millis(100);

impl Progress {
    /// Progress over `total` positions: reported to `callback` about every
    /// 1% of them; without a callback only Ctrl-C is looked for, as
    /// [`Progress::interrupts`] looks for it.
    pub fn new(callback: Option<Py<PyAny>>, total: usize) -> Progress {
        let (stride, asked) = match callback {
            Some(_) => ((total / 100).max(1), None),
            None => (64, Some(Instant::now())),
        };
        let mut p =
            Progress { callback, total, stride, next: 0, reported: 0, error: None, asked, attached: Instant::now() };
        p.next = p.after(0);
        p
    }

    /// No progress to report, only Ctrl-C to notice, for a run on the thread
    /// Python's signal handlers run on: Python is asked about every tenth of
    /// a second of the run (the clock read every 64 positions), so that a
    /// short run, or a study of many, pays next to nothing for it (a run of
    /// 360 positions attached to Python at every tenth of it would cost a
    /// few microseconds more), and at the last of `total` positions.
    pub fn interrupts() -> Progress {
        Progress::new(None, usize::MAX)
    }

    /// Looks for Ctrl-C when Python has not been attached to for a tenth of
    /// a second, whatever the progress: a simulation calls it after every
    /// step of its integrator, which may take many steps between two
    /// outputs (and a share of a percent of its time may take seconds). It
    /// reads the clock only, unless the tenth of a second is over.
    pub fn poll(&mut self) {
        if self.error.is_some() || self.attached.elapsed() < INTERRUPT_CHECK {
            return;
        }
        self.attached = Instant::now();
        self.error = Python::attach(|py| py.check_signals()).err();
    }

    /// Reports that the share `share` (0 to 1) of the work is done, in
    /// units of the positions.
    pub fn report_share(&mut self, share: f64) {
        let done = ((share * self.total as f64).floor() as usize).min(self.total);
        // On the stride, where `report` reports.
        let done = if done == self.total { done } else { done / self.stride * self.stride };
        self.report(done);
    }

    /// The count after `done` at which Python is attached to next (with
    /// [`Progress::interrupts`], at which the clock is looked at).
    fn after(&self, done: usize) -> usize {
        (done / self.stride).saturating_add(1).saturating_mul(self.stride).min(self.total)
    }

    /// Reports that `done` positions are computed, when that is a multiple
    /// of the stride or the last one, unless an error has stopped the run.
    #[inline]
    pub fn report(&mut self, done: usize) {
        // Never backwards: a simulation reports both the share of its time
        // integrated and the outputs found, which lag behind it.
        if done <= self.reported {
            return;
        }
        self.reported = done;
        if done < self.next || self.error.is_some() {
            return;
        }
        self.next = self.after(done);
        if let Some(asked) = self.asked.as_mut() {
            // And once at the end, so that a run shorter than the interval
            // still notices a Ctrl-C made during it.
            if done < self.total && asked.elapsed() < INTERRUPT_CHECK {
                return;
            }
            *asked = Instant::now();
        }
        self.attached = Instant::now();
        let result = Python::attach(|py| -> PyResult<()> {
            py.check_signals()?;
            if let Some(callback) = &self.callback {
                callback.call1(py, (done, self.total))?;
            }
            Ok(())
        });
        self.error = result.err();
    }
}

impl<'a, R: Record> Recording<'a, R> {
    /// Records `columns` (`width` of them) and the `n_coords` co-ordinates
    /// over a run of `total` positions, into tables sized for them up
    /// front, computing the transfer functions of `order`; stops when
    /// `cancel` is set or progress reporting failed.
    pub fn new(
        columns: R,
        width: usize,
        n_coords: usize,
        total: usize,
        order: Option<TransferOrder>,
        progress: Option<Progress>,
        cancel: Option<&'a AtomicBool>,
    ) -> Recording<'a, R> {
        Recording {
            // Straight into columns: the table Python gets, with no
            // row-major copy to be transposed after the run.
            table: Columns::new(width, total),
            coords: Vec::with_capacity(total.saturating_mul(n_coords)),
            row: Vec::with_capacity(width),
            columns,
            prescribed_at_1: Vec::new(),
            dependent_at_1: Vec::new(),
            progress,
            cancel,
            order,
            dynamics: None,
            checked: false,
        }
    }

    /// Records the dynamic quantities with the mass and load model of a
    /// DYN deck (checked when the deck was compiled).
    pub fn with_dynamics(mut self, mech: &Mechanism, dynamics: Option<&Dynamics>) -> Self {
        self.dynamics = dynamics.map(|d| InverseDynamics::new(mech, d.clone()));
        self
    }

    /// The error progress reporting met, if any.
    pub fn raised(&mut self) -> Option<PyErr> {
        self.progress.as_mut().and_then(|p| p.error.take())
    }
}

impl<R: Record> Observer for Recording<'_, R> {
    fn position(&mut self, view: &PositionView<'_>) {
        if view.index == 0 {
            let (mech, kin) = (view.mech, view.kin);
            // The prescribed values themselves: the rows hold them to within ACCURACY.
            self.prescribed_at_1 = view.state.target.clone();
            self.dependent_at_1 = (0..mech.n_dependent()).map(|d| kin.dep(d)).collect();
        }
        let checked = std::mem::take(&mut self.checked);
        self.columns.record(view, self.dynamics.as_mut(), checked, &mut self.table, &mut self.row);
        self.coords.extend_from_slice(&view.state.x);
        if let Some(p) = self.progress.as_mut() {
            p.report(view.index + 1);
        }
    }

    /// Inverse dynamics of a DYN deck, evaluated here: a position where
    /// it is not finite is refused.
    fn check(&mut self, view: &PositionView<'_>) -> Result<(), SolveError> {
        match self.dynamics.as_mut() {
            Some(d) if self.columns.is_dynamic() => {
                self.checked = true;
                d.evaluate_checked(view)
            }
            _ => Ok(()),
        }
    }

    fn moved_by_forces(&mut self, free: &[usize]) {
        if let Some(d) = self.dynamics.as_mut() {
            d.set_moved_by_forces(free);
        }
    }

    fn simulated(&mut self, time: f64, end: f64) {
        if let Some(p) = self.progress.as_mut() {
            p.report_share(if end > 0.0 { (time / end).clamp(0.0, 1.0) } else { 1.0 });
            p.poll();
        }
    }

    fn stop_requested(&self) -> bool {
        self.cancel.is_some_and(|c| c.load(Ordering::Relaxed))
            || self.progress.as_ref().is_some_and(|p| p.error.is_some())
    }

    /// What the recorded quantities need, and det(D^c) when asked for.
    fn transfer_order(&self) -> Option<TransferOrder> {
        self.order
    }
}
