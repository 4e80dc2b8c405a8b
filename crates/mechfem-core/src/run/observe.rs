//! What every run mode hands on: each position, as soon as it is computed,
//! to an [`Observer`] as a [`PositionView`], and at the end a [`RunReport`]
//! of how far the run got and what it met on the way.

use crate::error::SolveError;
use crate::model::{Mechanism, State};
use crate::motion::LimitPosition;
use crate::solver::{AdjustInfo, Kinematics, TransferOrder};

/// Everything known at one position, handed to an [`Observer`].
pub struct PositionView<'a> {
    /// Position index, 0-based (position 1 of the deck is index 0).
    pub index: usize,
    /// Time.
    pub time: f64,
    /// The model.
    pub mech: &'a Mechanism,
    /// Co-ordinates and prescribed values.
    pub state: &'a State,
    /// Transfer functions at this position.
    pub kin: &'a Kinematics,
    /// Input velocities.
    pub input_vel: &'a [f64],
    /// Input accelerations.
    pub input_acc: &'a [f64],
}

impl PositionView<'_> {
    /// Value of input j.
    pub fn input(&self, j: usize) -> f64 {
        self.state.target[self.mech.input_row(j)]
    }
}

/// Receives every position as soon as it is computed, so results can be
/// streamed rather than held.
pub trait Observer {
    /// Called once per position, in order.
    fn position(&mut self, view: &PositionView<'_>);

    /// Called with each position just before [`Self::position`]: an error
    /// refuses the position, which is then not observed. A run stops at the
    /// position before with this error as the reason, or returns it when
    /// position 1 is refused. An observer that computes results of its own
    /// (inverse dynamics) refuses a position where they are not finite.
    fn check(&mut self, view: &PositionView<'_>) -> Result<(), SolveError> {
        let _ = view;
        Ok(())
    }

    /// Asked after every position: `true` ends the run there (for example
    /// on Ctrl-C), with [`SolveError::Interrupted`] as the stop reason.
    fn stop_requested(&self) -> bool {
        false
    }

    /// The transfer functions this observer reads, asked once at the start
    /// of a run. A driven motion computes no more than that at every
    /// position after the first: `Some(First)` for det(D^c) and the
    /// first-order transfer functions, `None` for positions and the values
    /// of the dependent form parameters only (no det(D^c), so no limit
    /// positions are detected along the way). Transfer functions that were
    /// not computed read as NaN. The default is everything.
    fn transfer_order(&self) -> Option<TransferOrder> {
        Some(TransferOrder::Second)
    }

    /// Called by a simulation ([`simulate`](super::simulate)) after every
    /// step of its integrator, which has then reached `time` of `end`
    /// (after the outputs inside the step are observed), for progress
    /// reports and to look for Ctrl-C between outputs far apart. A run
    /// asked to stop ([`Self::stop_requested`]) stops integrating too.
    fn simulated(&mut self, time: f64, end: f64) {
        let _ = (time, end);
    }

    /// Called by a simulation before its first position with the DOFs
    /// that move under the forces (MOV_DYN, 0-based): an observer that
    /// evaluates inverse dynamics records a MOTOR's torque as the drive of
    /// such a DOF ([`InverseDynamics::set_moved_by_forces`](super::InverseDynamics::set_moved_by_forces)).
    fn moved_by_forces(&mut self, free: &[usize]) {
        let _ = free;
    }
}

/// Why a motion stopped before its last position.
#[derive(Debug, Clone, PartialEq)]
pub struct Stop {
    /// Index of the last position that was computed (0-based).
    pub last_good: usize,
    /// Input values that could not be reached.
    pub inputs: Vec<f64>,
    /// Input values at the last good position.
    pub last_inputs: Vec<f64>,
    /// The failure at the smallest step tried.
    pub error: SolveError,
    /// The limit position the input ran into, when one was located.
    pub limit: Option<LimitPosition>,
}

/// What a run did.
#[derive(Debug, Clone, PartialEq)]
pub struct RunReport {
    /// The adjustment of position 1.
    pub adjust: AdjustInfo,
    /// Number of positions computed and observed.
    pub positions: usize,
    /// Steps that had to be subdivided (their count).
    pub subdivided_steps: usize,
    /// Limit positions met on the way, in order.
    pub limits: Vec<LimitPosition>,
    /// Positions (0-based) where D^c was singular, so that no transfer
    /// functions exist there (free motion only).
    pub singular_positions: Vec<usize>,
    /// Set when the motion stopped early.
    pub stop: Option<Stop>,
}
