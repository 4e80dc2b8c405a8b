//! Input motion: how the inputs move from position to position, and the
//! stepping core that every run mode ([`crate::run`](mod@crate::run))
//! carries the mechanism with: the schedule of input values, one driven
//! step (prediction, correction, halving), one step of free motion, and the
//! location of the limit positions met on the way.

/// How one input (degree of freedom) moves.
#[derive(Debug, Clone, PartialEq)]
pub enum InputMotion {
    /// Equidistant steps changing the input by `delta` in total (MOV_RELE).
    Relative {
        /// Total change.
        delta: f64,
    },
    /// Equidistant steps from the initial value to `end` (MOV_ABSE).
    Absolute {
        /// Final value.
        end: f64,
    },
    /// One row per position: time, value, velocity, acceleration (MOV_FUNC).
    Table {
        /// `[t, value, velocity, acceleration]`, one per position.
        rows: Vec<[f64; 4]>,
    },
    /// Free motion with step `ds` in co-ordinate space (MOV_FREE).
    Free {
        /// Euclidean step length of the moving co-ordinates.
        ds: f64,
    },
    /// Moved by the forces, starting with velocity `v0` (MOV_DYN): only a
    /// simulation ([`crate::run::simulate`]) runs it.
    Dynamic {
        /// Initial velocity.
        v0: f64,
    },
}

/// A motion program: `steps` steps (positions 1..=steps+1), each `dt` long,
/// and one [`InputMotion`] per degree of freedom.
#[derive(Debug, Clone, PartialEq)]
pub struct Motion {
    /// Number of steps n.
    pub steps: usize,
    /// Time per step.
    pub dt: f64,
    /// One entry per DOF, in DOF order.
    pub inputs: Vec<InputMotion>,
}

pub(crate) mod free;
mod history;
pub(crate) mod limits;
pub(crate) mod schedule;
pub(crate) mod step;

pub use limits::{LimitKind, LimitPosition};

use crate::model::{Mechanism, State};

impl Motion {
    /// How input j's value and velocity at position `index` (0-based)
    /// change per unit of its start value (its prescribed value at position
    /// 1): (1, 0) for steps of a fixed size (MOV_RELE); (1 - k/n, -1/(n dt))
    /// for steps to a fixed end (MOV_ABSE); (0, 0) where the start does not
    /// move the input (a motion table, free or dynamic motion).
    pub fn start_rates(&self, j: usize, index: usize) -> (f64, f64) {
        let n = self.steps as f64;
        match self.inputs.get(j) {
            Some(InputMotion::Relative { .. }) => (1.0, 0.0),
            Some(InputMotion::Absolute { .. }) if self.steps == 0 => (1.0, 0.0),
            Some(InputMotion::Absolute { .. }) => (1.0 - index as f64 / n, -1.0 / (n * self.dt)),
            _ => (0.0, 0.0),
        }
    }

    /// Sets the inputs that a motion table fixes at position 1 (its first
    /// row), overriding their prescribed values. A run
    /// ([`crate::run::run`]) does this itself; call it to compute position 1
    /// alone the way a run would.
    pub fn apply_initial_inputs(&self, mech: &Mechanism, state: &mut State) {
        for (j, im) in self.inputs.iter().enumerate() {
            if let InputMotion::Table { rows } = im {
                if let Some(r) = rows.first() {
                    state.target[mech.input_row(j)] = r[1];
                }
            }
        }
    }
}
