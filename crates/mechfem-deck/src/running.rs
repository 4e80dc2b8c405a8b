//! Which run a compiled deck makes: the one place every front end asks how
//! a [`Compiled`] model moves through its motion ([`Compiled::run_mode`]),
//! which transfer functions it computes ([`Compiled::transfer_order`]) and
//! which motion a run of an [`Extent`] takes ([`Compiled::motion_for`]).

use std::borrow::Cow;

use mechfem_core::run::{
    motion_of, move_through, transfer_order_of, Extent, Observer, OrderError, RunMode, RunReport, SimReport,
};
use mechfem_core::{Motion, SolveError, State, TransferOrder};

use crate::ast::Mode;
use crate::compiled::Compiled;

impl Compiled {
    /// How the deck's motion is run: simulated for a `DYN SIM` deck (its
    /// MOV_DYN inputs moved by the forces), kinematically with inverse
    /// dynamics at every position for a deck with masses and loads
    /// (`DYN ANA`), kinematically otherwise.
    pub fn run_mode(&self) -> RunMode<'_> {
        match (&self.dynamics, self.mode) {
            (Some(dynamics), Mode::DynSim) => RunMode::Simulated { dynamics, integration: &self.integration },
            (Some(dynamics), _) => RunMode::Inverse { dynamics },
            (None, _) => RunMode::Kinematic,
        }
    }

    /// The transfer functions a run of the deck computes: `degree` 1 the
    /// first order, 2 also the second, None what the deck's own buffers
    /// need (and det(D^c), so at least the first order); a deck with
    /// dynamics always the second ([`RunMode::transfer_order`]).
    ///
    /// The solver predicts each position differently when it computes no
    /// second order (for one input), so only runs that compute the same
    /// orders give the same numbers to the last bit.
    pub fn transfer_order(&self, degree: Option<u8>) -> Result<TransferOrder, OrderError> {
        let asked = transfer_order_of(degree)?;
        let needed =
            self.buffers.iter().filter_map(|b| b.quantity.transfer_order()).fold(TransferOrder::First, Ord::max);
        Ok(self.run_mode().transfer_order(asked, needed))
    }

    /// The motion a run of `extent` moves through from `state` (made ready
    /// for it), see [`motion_of`].
    pub fn motion_for(&self, state: &mut State, extent: Extent) -> Option<Cow<'_, Motion>> {
        motion_of(&self.mechanism, state, self.motion.as_ref(), extent)
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
