//! What the TOLERANCE block of a `KIN ANA` or `DYN ANA` deck compiles to:
//! the toleranced dimensions with their tolerances, and the buffers whose
//! bands are recorded.
//!
//! The deck reader only states the problem; the bands come from the design
//! sensitivities of [`mechfem_core::design::evaluate`]. Tolerances are in
//! the core's units, as every number of a [`crate::Compiled`].

use mechfem_core::DesignVar;

/// The compiled TOLERANCE block.
#[derive(Debug, Clone, PartialEq)]
pub struct Tolerance {
    /// The toleranced dimensions (TOL, TOLX), in deck order; at least one.
    pub dims: Vec<Toleranced>,
    /// The bands recorded (BUFTOL), in deck order; at least one.
    pub bands: Vec<BandDef>,
    /// Line of the TOLERANCE header.
    pub line: usize,
}

/// A dimension known to within +-t: `TOL r t` or `TOLX i t`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Toleranced {
    /// [`DesignVar::Row`] (0-based prescribed row) for TOL,
    /// [`DesignVar::Fixed`] (0-based fixed co-ordinate) for TOLX.
    pub var: DesignVar,
    /// The tolerance t (positive, in the core's units).
    pub t: f64,
    /// Line of the keyword.
    pub line: usize,
}

/// `BUFTOL bsrc b`: the band of buffer `source`, worst case into `buffer`
/// and root sum of squares into `buffer + 1`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BandDef {
    /// The buffer whose band is recorded (a number of
    /// [`crate::Compiled::buffers`]).
    pub source: u32,
    /// The worst-case band's number (the RSS band is `buffer + 1`).
    pub buffer: u32,
    /// Line of the keyword.
    pub line: usize,
}
