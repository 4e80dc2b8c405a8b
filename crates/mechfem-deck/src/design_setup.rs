//! What an optimiser of a compiled deck evaluates ([`DesignSetup`]): its
//! design variables, the quantities an objective reads and the extrema it
//! takes them at, all named by the deck's numbers, and why a choice of them
//! does not fit the deck ([`DesignSetupError`]).

use mechfem_core::design::{slopes, ExtremumSpec};
use mechfem_core::{DesignError, DesignVar, Quantity, Sensitivity};

use crate::compiled::Compiled;

/// The design variables, quantities and extrema of an optimisation of a
/// compiled deck.
#[derive(Debug, Clone)]
pub struct DesignSetup {
    /// The design variables.
    pub vars: Vec<DesignVar>,
    /// The quantity of each buffer an objective reads.
    pub quantities: Vec<Quantity>,
    /// Quantities wanted where a reference has an extremum.
    pub extrema: Vec<ExtremumSpec>,
}

/// Why design variables, buffers, extrema or design values do not fit a
/// compiled deck.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum DesignSetupError {
    /// The deck has no MOVEMENT block.
    #[error("an optimisation needs a motion: its positions are where it looks")]
    NoMotion,
    /// A design variable numbered 0.
    #[error("deck numbers start at 1")]
    NumberZero,
    /// A design variable of a kind other than 0 (fixed co-ordinate) and 1
    /// (prescribed row).
    #[error("a variable is of kind 0 or 1, not {0}")]
    VariableKind(u8),
    /// A buffer number the deck does not define.
    #[error("the deck defines no buffer {0}")]
    NoBuffer(u32),
    /// A buffer that cannot be the reference of an extremum.
    #[error(
        "buffer {0} cannot locate extrema: it must be a position (BUFX0 of a co-ordinate or BUFE0 of a dependent \
         form parameter) of a mechanism with one degree of freedom"
    )]
    NoReference(u32),
    /// Design variables that do not fit the model.
    #[error(transparent)]
    Variables(#[from] DesignError),
    /// As many design values as design variables are needed.
    #[error("{given} values for {vars} design variables")]
    ValueCount {
        /// Values given.
        given: usize,
        /// Design variables.
        vars: usize,
    },
    /// A design value that is not a finite number.
    #[error("design value {index} is {value}")]
    NotFinite {
        /// Which value (0-based).
        index: usize,
        /// The value.
        value: f64,
    },
}

impl DesignSetup {
    /// An error when `values` are not one finite number per design variable.
    pub fn check(&self, values: &[f64]) -> Result<(), DesignSetupError> {
        if values.len() != self.vars.len() {
            return Err(DesignSetupError::ValueCount { given: values.len(), vars: self.vars.len() });
        }
        match values.iter().position(|v| !v.is_finite()) {
            Some(index) => Err(DesignSetupError::NotFinite { index, value: values[index] }),
            None => Ok(()),
        }
    }
}

impl Compiled {
    /// The quantity of buffer `number` of the deck.
    fn buffer_quantity(&self, number: u32) -> Result<Quantity, DesignSetupError> {
        let buffer = self.buffers.iter().find(|b| b.number == number);
        buffer.map(|b| b.quantity).ok_or(DesignSetupError::NoBuffer(number))
    }

    /// The optimisation of the deck over `variables` (`(kind, number)` in
    /// the deck's numbering: kind 0 a fixed co-ordinate, 1 a prescribed
    /// row), reading buffers `buffers` and, for each pair `(b, bref)` of
    /// `extrema`, buffer b wherever buffer bref has an extremum.
    pub fn design_setup(
        &self,
        variables: &[(u8, usize)],
        buffers: &[u32],
        extrema: &[(u32, u32)],
    ) -> Result<DesignSetup, DesignSetupError> {
        let mech = &self.mechanism;
        if self.motion.is_none() {
            return Err(DesignSetupError::NoMotion);
        }
        let vars = variables
            .iter()
            .map(|&(kind, number)| {
                let k = number.checked_sub(1).ok_or(DesignSetupError::NumberZero)?;
                match kind {
                    0 => Ok(DesignVar::Fixed(k)),
                    1 => Ok(DesignVar::Row(k)),
                    _ => Err(DesignSetupError::VariableKind(kind)),
                }
            })
            .collect::<Result<Vec<_>, _>>()?;
        Sensitivity::new(mech, &vars)?;
        let quantities = buffers.iter().map(|&b| self.buffer_quantity(b)).collect::<Result<Vec<_>, _>>()?;
        let extrema = extrema
            .iter()
            .map(|&(b, r)| {
                let reference = self.buffer_quantity(r)?;
                if slopes(reference).is_none() || mech.n_dof() != 1 {
                    return Err(DesignSetupError::NoReference(r));
                }
                Ok(ExtremumSpec { quantity: self.buffer_quantity(b)?, reference })
            })
            .collect::<Result<Vec<_>, _>>()?;
        Ok(DesignSetup { vars, quantities, extrema })
    }
}
