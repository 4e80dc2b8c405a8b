//! What an optimiser of a compiled `DYN ANA` deck evaluates
//! ([`DynamicSetup`]): kinematic design variables and variables of the
//! mass model, named by the deck's numbers, and the quantities an
//! objective reads; why a choice of them does not fit the deck
//! ([`DynamicSetupError`]).

use mechfem_core::dynamics::MassVar;
use mechfem_core::{DesignVar, Quantity};

use crate::compiled::Compiled;
use crate::design_setup::DesignSetupError;
use crate::optimise::MassItem;

/// The variables and quantities of a dynamic design evaluation. The
/// variables as given are split into the kinematic ones and those of the
/// mass model, each in the order given; `order` maps them back.
#[derive(Debug, Clone)]
pub struct DynamicSetup {
    /// The kinematic design variables (prescribed values, fixed co-ordinates).
    pub vars: Vec<DesignVar>,
    /// The variables of the mass model.
    pub mass_vars: Vec<MassVar>,
    /// The quantities recorded at every position.
    pub quantities: Vec<Quantity>,
    /// For each variable as given, its place in `vars` followed by `mass_vars`.
    pub order: Vec<usize>,
}

/// Why the variables or buffers asked of a dynamic design evaluation do not
/// fit the compiled deck.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum DynamicSetupError {
    /// What a kinematic design evaluation refuses too.
    #[error(transparent)]
    Design(#[from] DesignSetupError),
    /// The deck has no mass model (it is not a `DYN ANA` deck).
    #[error("the deck has no DYNAMICS block: a dynamic design evaluation needs a DYN ANA deck")]
    NoDynamics,
    /// A variable kind that is neither kinematic (0, 1) nor of the mass model (10..=15).
    #[error("a variable is of kind 0, 1 or 10 to 15, not {0}")]
    VariableKind(u8),
    /// A mass variable whose DYNAMICS line the deck does not have.
    #[error("the DYNAMICS block has no {item} line for number {number} to vary")]
    NoMassItem {
        /// The item's word, e.g. `PMASS`.
        item: &'static str,
        /// The element or co-ordinate named.
        number: usize,
    },
}

/// The mass item of a variable kind 10..=15: MASS, U, V, J, PMASS, INERTIA.
pub fn mass_item(kind: u8) -> Option<MassItem> {
    kind.checked_sub(10).and_then(|k| MassItem::ALL.get(usize::from(k)).copied())
}

impl Compiled {
    /// The setup of a dynamic design evaluation: `variables` are
    /// `(kind, number)` in the deck's numbering, kind 0 a fixed co-ordinate,
    /// 1 a prescribed row, 10..=15 the MASS, U, V or J of element `number`'s
    /// MASS line, the PMASS at co-ordinate `number`, the INERTIA on it;
    /// `buffers` the buffer numbers evaluated.
    pub fn dynamic_setup(&self, variables: &[(u8, usize)], buffers: &[u32]) -> Result<DynamicSetup, DynamicSetupError> {
        let Some(model) = &self.dynamics else { return Err(DynamicSetupError::NoDynamics) };
        let kinematic: Vec<(u8, usize)> = variables.iter().copied().filter(|&(k, _)| k <= 1).collect();
        let kin = self.design_setup(&kinematic, buffers, &[])?;
        let mut mass_vars = Vec::new();
        let mut order = Vec::with_capacity(variables.len());
        let mut next_kin = 0;
        for &(kind, number) in variables {
            if kind <= 1 {
                order.push(next_kin);
                next_kin += 1;
                continue;
            }
            let item = mass_item(kind).ok_or(DynamicSetupError::VariableKind(kind))?;
            let var = item.var(model, number).ok_or(DynamicSetupError::NoMassItem { item: item.name(), number })?;
            order.push(kinematic.len() + mass_vars.len());
            mass_vars.push(var);
        }
        Ok(DynamicSetup { vars: kin.vars, mass_vars, quantities: kin.quantities, order })
    }
}
