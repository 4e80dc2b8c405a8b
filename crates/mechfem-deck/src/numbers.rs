//! The numbers of one run of a compiled deck ([`Numbers`]), and the changes
//! a variant of a design study, or a model kept by Python and run again,
//! makes to them ([`Change`]): what is run anew on one compiled model.

use mechfem_core::{DesignError, FormRef, State};

use crate::compiled::Compiled;

/// The numbers of one run of a compiled deck: its state (co-ordinates and
/// prescribed values) and the PARA value of each prescribed row, as the
/// deck gives them with a variant's changes made. Everything else of the
/// compiled deck is the same for every run of it, and shared.
#[derive(Debug, Clone)]
pub struct Numbers {
    /// Co-ordinates and prescribed values to start from.
    pub state: State,
    /// PARA value of each prescribed row (None for an input without one).
    pub para: Vec<Option<f64>>,
}

/// A change of one number of a compiled deck: the value of a co-ordinate
/// (its XFIX or XMOV value) or of a prescribed row (its PARA value), both
/// numbered as in the deck and given in the deck's own units.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Change {
    /// Co-ordinate `number` gets `value`.
    Coord(usize, f64),
    /// Prescribed row `number` gets `value`.
    Row(usize, f64),
}

/// A change of a kind other than 0 (co-ordinate) and 1 (prescribed row).
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
#[error("a change is of kind 0 (co-ordinate) or 1 (row), not {0}")]
pub struct ChangeKindError(pub u8);

impl Change {
    /// The change of `kind` 0 (co-ordinate `number`) or 1 (prescribed row
    /// `number`) to `value`.
    pub fn of_kind(kind: u8, number: usize, value: f64) -> Result<Change, ChangeKindError> {
        match kind {
            0 => Ok(Change::Coord(number, value)),
            1 => Ok(Change::Row(number, value)),
            _ => Err(ChangeKindError(kind)),
        }
    }

    /// Makes the change (its value in the core's units) in `n`, as if the
    /// deck had said so; an error when the deck has no such co-ordinate or
    /// row.
    fn apply(self, n: &mut Numbers) -> Result<(), DesignError> {
        // Number 0 is said as such (index usize::MAX, see DesignError).
        let index = |number: usize| number.wrapping_sub(1);
        match self {
            Change::Coord(number, value) => {
                let x = n.state.x.get_mut(index(number));
                *x.ok_or(DesignError::NoCoordinate(index(number)))? = value;
            }
            Change::Row(number, value) => {
                let k = Some(index(number)).filter(|&k| k < n.para.len() && k < n.state.target.len());
                let k = k.ok_or(DesignError::NoRow(index(number)))?;
                n.state.target[k] = value;
                n.para[k] = Some(value);
            }
        }
        Ok(())
    }
}

impl Compiled {
    /// `change` with its value in the core's SI units: a change gives a
    /// number in the deck's own UNITS, as the deck does.
    pub fn in_core_units(&self, change: Change) -> Change {
        if self.units.is_identity() {
            return change;
        }
        match change {
            Change::Coord(number, v) => {
                Change::Coord(number, self.units.to_core(self.dims.coord(number.wrapping_sub(1)), v))
            }
            Change::Row(number, v) => {
                let row = self.dims.form(FormRef::Prescribed(number.wrapping_sub(1)));
                Change::Row(number, self.units.to_core(row, v))
            }
        }
    }

    /// The deck's own numbers with `changes` made; an error names a
    /// co-ordinate or row the deck does not have.
    pub fn numbers(&self, changes: &[Change]) -> Result<Numbers, DesignError> {
        let mut n = Numbers { state: self.state.clone(), para: self.prescribed.iter().map(|r| r.para).collect() };
        changes.iter().try_for_each(|&ch| self.in_core_units(ch).apply(&mut n))?;
        // What the deck reader derives from the co-ordinates, derived from
        // the new ones: the angles each element tracks from its directions,
        // and the value of every row the deck gives none. Co-ordinates at
        // which an element cannot be evaluated are left for the run, which
        // says so at position 1. Co-ordinates equal to the deck's own (a
        // named model run again with its points unmoved) keep what the
        // reader derived from them.
        let moved = n.state.x.iter().zip(&self.state.x).any(|(a, b)| a.to_bits() != b.to_bits());
        if moved {
            if let Ok(mut start) = self.mechanism.start_state(n.state.x.clone()) {
                start.set_given(&n.para);
                n.state = start;
            }
        }
        Ok(n)
    }
}
