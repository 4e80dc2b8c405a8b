//! The TOLERANCE block as the deck writes it (modes `KIN ANA` and `DYN ANA`).

use crate::diagnostic::Spanned;
use crate::keywords::Keyword;

/// The TOLERANCE block, compiled to a [`crate::Tolerance`].
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ToleranceBlock {
    /// Line of the header.
    pub line: usize,
    /// `TOL` and `TOLX` lines, in order.
    pub dims: Vec<TolDef>,
    /// `BUFTOL` lines, in order.
    pub bands: Vec<BufTolDef>,
}

/// `TOL r t` or `TOLX i t`.
#[derive(Debug, Clone, PartialEq)]
pub struct TolDef {
    /// Line of the keyword.
    pub line: usize,
    /// TOL (a prescribed row) or TOLX (a fixed co-ordinate).
    pub keyword: Spanned<Keyword>,
    /// The row r or co-ordinate i.
    pub index: Spanned<i64>,
    /// The tolerance t (positive): the value is known to within +-t.
    pub t: Spanned<f64>,
}

/// `BUFTOL bsrc b`.
#[derive(Debug, Clone, PartialEq)]
pub struct BufTolDef {
    /// Line of the keyword.
    pub line: usize,
    /// The buffer whose band is recorded.
    pub source: Spanned<i64>,
    /// The worst-case band's number b (the RSS band is b + 1).
    pub buffer: Spanned<i64>,
}
