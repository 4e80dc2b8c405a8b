//! The observer of a run: records the quantities of a deck's
//! [`Selection`] (its buffers, the hodographs, a DYN deck's dynamics, time
//! and det(D^c)) and every co-ordinate per position, keeps
//! the row values of position 1 for the model echo, and reports progress to
//! Python about every 1% of positions ([`Progress`], which the observer of
//! deck-text runs shares).

use std::time::{Duration, Instant};

use mechfem_core::dynamics::Dynamics;
use mechfem_core::run::{Columns, InverseDynamics, Selection};
use mechfem_core::{Mechanism, Observer, PositionView, SolveError, TransferOrder};
use pyo3::prelude::*;

/// Records a run for Python. Runs without the GIL; attaches only to report
/// progress and to notice Ctrl-C.
pub struct Recording {
    /// The named blocks of the table's columns.
    pub selection: Selection,
    /// The quantities of `selection` at every position, column by column.
    pub table: Columns,
    /// Every co-ordinate at every position, row-major (positions x N).
    pub coords: Vec<f64>,
    /// Values of the prescribed rows at position 1.
    pub prescribed_at_1: Vec<f64>,
    /// Values of the dependent form parameters at position 1.
    pub dependent_at_1: Vec<f64>,
    /// Progress reporting; its error stops the run.
    pub progress: Progress,
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

impl Recording {
    /// Records the quantities of `selection` and the `n_coords`
    /// co-ordinates over a run of `total` positions, into tables sized for
    /// them up front. With `det`, det(D^c) is computed at every position
    /// (and with it the first order, and the watch for limit positions by
    /// its sign); without, its column holds NaN unless a buffer asks for
    /// it, and a run whose quantities are all positions and values
    /// computes positions only.
    pub fn new(
        selection: Selection,
        n_coords: usize,
        total: usize,
        progress: Option<Py<PyAny>>,
        det: bool,
    ) -> Recording {
        let order = selection.transfer_order().max(det.then_some(TransferOrder::First));
        Recording {
            // Straight into columns: the table Python gets, with no
            // row-major copy to be transposed after the run.
            table: Columns::new(selection.width(), total),
            coords: Vec::with_capacity(total.saturating_mul(n_coords)),
            row: Vec::with_capacity(selection.width()),
            selection,
            prescribed_at_1: Vec::new(),
            dependent_at_1: Vec::new(),
            progress: Progress::new(progress, total),
            order,
            dynamics: None,
            checked: false,
        }
    }

    /// Records the dynamic quantities with the mass and load model of a
    /// DYN deck (checked when the deck was compiled).
    pub fn with_dynamics(&mut self, mech: &Mechanism, dynamics: Option<&Dynamics>) {
        self.dynamics = dynamics.map(|d| InverseDynamics::new(mech, d.clone()));
    }
}

impl Observer for Recording {
    fn position(&mut self, view: &PositionView<'_>) {
        if view.index == 0 {
            let (mech, kin) = (view.mech, view.kin);
            // The prescribed values themselves: the rows hold them to within ACCURACY.
            self.prescribed_at_1 = view.state.target.clone();
            self.dependent_at_1 = (0..mech.n_dependent()).map(|d| kin.dep(d)).collect();
        }
        self.row.clear();
        if std::mem::take(&mut self.checked) {
            self.selection.record_evaluated(view, self.dynamics.as_ref(), &mut self.row);
        } else {
            self.selection.record(view, self.dynamics.as_mut(), &mut self.row);
        }
        self.table.push(&self.row);
        self.coords.extend_from_slice(&view.state.x);
        self.progress.report(view.index + 1);
    }

    /// Inverse dynamics of a DYN deck, evaluated here: a position where
    /// it is not finite is refused.
    fn check(&mut self, view: &PositionView<'_>) -> Result<(), SolveError> {
        match self.dynamics.as_mut() {
            Some(d) if self.selection.is_dynamic() => {
                self.checked = true;
                d.evaluate_checked(view)
            }
            _ => Ok(()),
        }
    }

    fn simulated(&mut self, time: f64, end: f64) {
        let share = if end > 0.0 { (time / end).clamp(0.0, 1.0) } else { 1.0 };
        self.progress.report_share(share);
        self.progress.poll();
    }

    fn stop_requested(&self) -> bool {
        self.progress.error.is_some()
    }

    /// What the recorded quantities need, and det(D^c) when asked for (see
    /// [`Recording::new`]).
    fn transfer_order(&self) -> Option<TransferOrder> {
        self.order
    }
}
