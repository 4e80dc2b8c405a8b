//! Which run a model's motion makes, and the refusal of a run too large to
//! keep: what every front end (the deck reader's compiled model, the
//! Python binding, the batch runner) asks before and when it runs.

use std::borrow::Cow;
use std::fmt;

use crate::dynamics::{Dynamics, Integration};
use crate::run::{run, simulate, Observer, RunReport, SimReport};
use crate::{InputMotion, Mechanism, Motion, Params, SolveError, State, TransferOrder};

/// How a model moves through its motion.
#[derive(Debug, Clone, Copy)]
pub enum RunMode<'a> {
    /// Kinematically, the inputs prescribed (modes `KIN ANA` and `KIN OPT`).
    Kinematic,
    /// Kinematically, with the inverse dynamics of `dynamics` at every
    /// position (mode `DYN ANA`), which the run's observer evaluates.
    Inverse {
        /// The masses and loads.
        dynamics: &'a Dynamics,
    },
    /// Simulated: the degrees of freedom the motion leaves to the forces
    /// move under `dynamics`, integrated within `integration` (mode `DYN SIM`).
    Simulated {
        /// The masses and loads.
        dynamics: &'a Dynamics,
        /// The integrator's tolerances.
        integration: &'a Integration,
    },
}

impl<'a> RunMode<'a> {
    /// The masses and loads whose dynamic quantities the run records (None
    /// for a kinematic run).
    pub fn dynamics(&self) -> Option<&'a Dynamics> {
        match *self {
            RunMode::Kinematic => None,
            RunMode::Inverse { dynamics } | RunMode::Simulated { dynamics, .. } => Some(dynamics),
        }
    }

    /// The transfer functions a run computes: `asked` (None: `needed`, what
    /// the recorded quantities need, and at least the first order for
    /// det(D^c)); a run with dynamics always computes the second order, which
    /// its accelerations are made from.
    pub fn transfer_order(&self, asked: Option<TransferOrder>, needed: TransferOrder) -> TransferOrder {
        if self.dynamics().is_some() {
            return TransferOrder::Second;
        }
        asked.unwrap_or(needed.max(TransferOrder::First))
    }
}

/// The transfer functions of `degree`: 1 the first order, 2 also the
/// second; None for "what the recorded quantities need".
pub fn transfer_order_of(degree: Option<u8>) -> Result<Option<TransferOrder>, OrderError> {
    match degree {
        None => Ok(None),
        Some(1) => Ok(Some(TransferOrder::First)),
        Some(2) => Ok(Some(TransferOrder::Second)),
        Some(k) => Err(OrderError(k)),
    }
}

/// An order of transfer functions other than 1 and 2.
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
#[error("order must be 1, 2 or None, not {0}")]
pub struct OrderError(pub u8);

/// How far a run goes: through its whole motion, or to position 1 alone.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Extent {
    /// Every position of the motion.
    Motion,
    /// Position 1 alone, computed as a run of the motion computes it.
    PositionOne,
}

/// The motion a run of `extent` moves through, with `state` made ready for
/// it: `motion` itself for the whole motion; for position 1 alone the
/// inputs set to their start values and no motion, except a free motion
/// (none of its steps), which may start in a limit position of its input.
pub fn motion_of<'m>(
    mech: &Mechanism,
    state: &mut State,
    motion: Option<&'m Motion>,
    extent: Extent,
) -> Option<Cow<'m, Motion>> {
    let m = motion?;
    if extent == Extent::Motion {
        return Some(Cow::Borrowed(m));
    }
    m.apply_initial_inputs(mech, state);
    let free = m.inputs.iter().any(|im| matches!(im, InputMotion::Free { .. }));
    free.then(|| Cow::Owned(Motion { steps: 0, ..m.clone() }))
}

/// Moves the mechanism through `motion` (position 1 alone without one) as
/// `mode` says; a simulation also gives what its integrator did.
pub fn move_through(
    mech: &Mechanism,
    state: &mut State,
    motion: Option<&Motion>,
    params: &Params,
    mode: RunMode<'_>,
    observer: &mut dyn Observer,
) -> Result<(RunReport, Option<SimReport>), SolveError> {
    match (motion, mode) {
        (Some(m), RunMode::Simulated { dynamics, integration }) => {
            simulate(mech, state, m, params, integration, dynamics, observer).map(|s| (s.run.clone(), Some(s)))
        }
        _ => run(mech, state, motion, params, observer).map(|r| (r, None)),
    }
}

/// How many bytes a run holds per recorded value at its peak: the
/// recording itself, and the arrays a front end is handed while it is
/// converted.
const BYTES_PER_VALUE: u128 = 3 * 8;

/// A run refused before it started: its results would take more memory
/// than its limit allows. The message gives the facts and what to ask for
/// instead; how to raise the limit is the front end's to say (a command-line
/// option, an argument, an environment variable).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct MemoryRefusal {
    /// Positions the run would keep.
    pub positions: usize,
    /// Numbers recorded per position.
    pub values: usize,
    /// Bytes the results would take.
    pub need: u128,
    /// The limit, in bytes.
    pub limit: u64,
}

impl MemoryRefusal {
    /// The refusal of a run of `positions` positions that records `values`
    /// numbers per position, when its results would not fit in `limit`
    /// bytes; `Ok` when they fit. Checked before the run starts, so that a
    /// model asking for too much fails at once instead of after hours or by
    /// running the machine out of memory.
    pub fn check(positions: usize, values: usize, limit: u64) -> Result<(), MemoryRefusal> {
        let need = positions as u128 * values as u128 * BYTES_PER_VALUE;
        if need > u128::from(limit) {
            return Err(MemoryRefusal { positions, values, need, limit });
        }
        Ok(())
    }
}

impl fmt::Display for MemoryRefusal {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "the run would keep about {} of results in memory ({} positions x {} values), more than the memory limit \
             of {}. Ask for fewer steps (TSTEPE), fewer buffers or a smaller model, or raise the limit",
            bytes_text(self.need),
            self.positions,
            self.values,
            bytes_text(u128::from(self.limit))
        )
    }
}

impl std::error::Error for MemoryRefusal {}

/// Bytes in words: `512 MiB`, `5.4 GiB`.
fn bytes_text(bytes: u128) -> String {
    const UNITS: [&str; 5] = ["bytes", "KiB", "MiB", "GiB", "TiB"];
    let mut value = bytes as f64;
    let mut unit = 0;
    while value >= 1024.0 && unit + 1 < UNITS.len() {
        value /= 1024.0;
        unit += 1;
    }
    if unit == 0 || value >= 100.0 || value.fract() == 0.0 {
        format!("{value:.0} {}", UNITS[unit])
    } else {
        format!("{value:.1} {}", UNITS[unit])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn memory_refusal_counts_bytes_and_words_the_sizes() {
        assert!(MemoryRefusal::check(1000, 10, 1000 * 10 * 24).is_ok());
        let r = MemoryRefusal::check(1000, 10, 1000 * 10 * 24 - 1).unwrap_err();
        assert_eq!(r.need, 240_000);
        let text = r.to_string();
        assert!(text.contains("about 234 KiB of results in memory (1000 positions x 10 values)"), "{text}");
        assert!(text.ends_with("or raise the limit"), "{text}");
        let big = MemoryRefusal::check(10_000_001, 13, 2 << 30).unwrap_err().to_string();
        assert!(big.contains("about 2.9 GiB") && big.contains("memory limit of 2 GiB"), "{big}");
    }
}
