//! Which run a compiled deck makes: the one function every front end
//! calls to move a [`Compiled`] model through its motion.

use mechfem_core::run::{move_through, Observer, RunMode, RunReport, SimReport};
use mechfem_core::{Motion, SolveError, State};

use crate::ast::Mode;
use crate::compiled::Compiled;

impl Compiled {
    /// How the deck's motion is run: simulated for a `DYN SIM` deck (its
    /// MOV_DYN inputs moved by the forces), kinematically otherwise (a
    /// `DYN ANA` deck's inverse dynamics is its observer's to evaluate).
    pub fn run_mode(&self) -> RunMode<'_> {
        match (&self.dynamics, self.mode) {
            (Some(dynamics), Mode::DynSim) => RunMode::Simulated { dynamics, integration: &self.integration },
            _ => RunMode::Kinematic,
        }
    }

    /// Moves the model from `state` through `motion` (the deck's own, or
    /// one made of it; position 1 alone without one) as [`Compiled::run_mode`]
    /// says, with the deck's solver settings.
    pub fn move_through(
        &self,
        state: &mut State,
        motion: Option<&Motion>,
        observer: &mut dyn Observer,
    ) -> Result<(RunReport, Option<SimReport>), SolveError> {
        move_through(&self.mechanism, state, motion, &self.params, self.run_mode(), observer)
    }
}
