//! The OPTIMISE block as the deck writes it (mode `KIN OPT`).

use crate::diagnostic::Spanned;
use crate::keywords::Keyword;
use crate::optimise::{Reduce, Sense};

use super::BufDef;

/// The OPTIMISE block, compiled to a [`crate::Optimise`].
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Optimise {
    /// Line of the header.
    pub line: usize,
    /// `VARY` and `VARYX` lines, in order.
    pub vary: Vec<VaryDef>,
    /// `TARGET`, `TARGETAT` and `TARGETEXT` lines, in order.
    pub targets: Vec<TargetDef>,
    /// `BOUND` lines, in order.
    pub bounds: Vec<BoundDef>,
    /// `MINIMISE` or `MAXIMISE`, if given (at most one).
    pub objective: Option<ObjectiveDef>,
    /// `BUF...` lines, in order: buffers of the deck like those of STORAGE.
    pub buffers: Vec<BufDef>,
    /// `OPTSTEPS n`, if given (n >= 1).
    pub steps: Option<Spanned<i64>>,
    /// `OPTTOL tol`, if given (tol > 0).
    pub tol: Option<Spanned<f64>>,
    /// `OPTFTOL rtol atol`, if given (both >= 0, not both 0, rtol < 1),
    /// with the keyword (for the message when OPTTOL is given too).
    pub ftol: Option<(Spanned<Keyword>, f64, f64)>,
    /// `FREETIME r [ORDERED] [WITHIN w]`, if given.
    pub free_time: Option<FreeTimeDef>,
    /// `FULLROT r`, if given: the keyword and the row.
    pub full_rotation: Option<(Spanned<Keyword>, Spanned<i64>)>,
    /// `VARYFRAME i lo hi`, if given.
    pub frame: Option<FrameDef>,
    /// `VARYM what n lo hi` lines (mode `DYN ANA`), in order.
    pub mass_vary: Vec<MassVaryDef>,
}

/// `VARYM what n lo hi`: a number of the DYNAMICS block as a design
/// variable (mode `DYN ANA`).
#[derive(Debug, Clone, PartialEq)]
pub struct MassVaryDef {
    /// Line of the keyword.
    pub line: usize,
    /// The keyword.
    pub keyword: Spanned<Keyword>,
    /// Which number of which DYNAMICS line: the word `what`.
    pub what: Spanned<crate::optimise::MassItem>,
    /// The element k (MASS, U, V, J) or co-ordinate i (PMASS, INERTIA).
    pub index: Spanned<i64>,
    /// Lower end of the range.
    pub lo: Spanned<f64>,
    /// Upper end of the range (above `lo`).
    pub hi: Spanned<f64>,
}

/// `FREETIME r [ORDERED] [WITHIN w]`: the input of row r takes a value of
/// its own, a design variable, at every position.
#[derive(Debug, Clone, PartialEq)]
pub struct FreeTimeDef {
    /// Line of the keyword.
    pub line: usize,
    /// The keyword.
    pub keyword: Spanned<Keyword>,
    /// The input's row r.
    pub row: Spanned<i64>,
    /// Whether `ORDERED` follows: every value at or after the one before.
    pub ordered: bool,
    /// `WITHIN w` (after ORDERED): the last value at most w after the
    /// first, in the input's unit.
    pub within: Option<Spanned<f64>>,
}

/// `VARYFRAME i lo hi`: the frame turned about the fixed point whose x is
/// co-ordinate i, by an angle within [lo, hi].
#[derive(Debug, Clone, PartialEq)]
pub struct FrameDef {
    /// Line of the keyword.
    pub line: usize,
    /// The keyword.
    pub keyword: Spanned<Keyword>,
    /// The pivot's x co-ordinate i.
    pub index: Spanned<i64>,
    /// Lower end of the angle's range (at most 0).
    pub lo: Spanned<f64>,
    /// Upper end (at least 0).
    pub hi: Spanned<f64>,
}

/// `VARY r lo hi` or `VARYX i lo hi`.
#[derive(Debug, Clone, PartialEq)]
pub struct VaryDef {
    /// Line of the keyword.
    pub line: usize,
    /// VARY (a prescribed row) or VARYX (a fixed co-ordinate).
    pub keyword: Spanned<Keyword>,
    /// The row r or co-ordinate i.
    pub index: Spanned<i64>,
    /// Lower end of the range.
    pub lo: Spanned<f64>,
    /// Upper end of the range (above `lo`).
    pub hi: Spanned<f64>,
}

/// `TARGET`, `TARGETAT` or `TARGETEXT`.
#[derive(Debug, Clone, PartialEq)]
pub struct TargetDef {
    /// Line of the keyword.
    pub line: usize,
    /// Which of the three keywords.
    pub keyword: Spanned<Keyword>,
    /// The buffer compared.
    pub buffer: Spanned<i64>,
    /// What it is compared with.
    pub kind: TargetDefKind,
    /// The weight, if given (positive; 1 otherwise).
    pub weight: Option<Spanned<f64>>,
}

/// What a target compares its buffer with.
#[derive(Debug, Clone, PartialEq)]
pub enum TargetDefKind {
    /// `TARGET b file [w]` (file relative to the deck's folder).
    Values(Spanned<String>),
    /// `TARGETAT b k value [w]` (k 1-based).
    At {
        /// The position k.
        position: Spanned<i64>,
        /// The value.
        value: Spanned<f64>,
    },
    /// `TARGETEXT b bref value [w]`.
    Extremum {
        /// The buffer bref whose extrema are meant.
        reference: Spanned<i64>,
        /// The value.
        value: Spanned<f64>,
    },
}

/// `BOUND b lo hi`.
#[derive(Debug, Clone, PartialEq)]
pub struct BoundDef {
    /// Line of the keyword.
    pub line: usize,
    /// The buffer constrained.
    pub buffer: Spanned<i64>,
    /// Lower limit.
    pub lo: Spanned<f64>,
    /// Upper limit (above `lo`).
    pub hi: Spanned<f64>,
}

/// `MINIMISE kind b` or `MAXIMISE kind b`.
#[derive(Debug, Clone, PartialEq)]
pub struct ObjectiveDef {
    /// Line of the keyword.
    pub line: usize,
    /// MINIMISE or MAXIMISE.
    pub keyword: Spanned<Keyword>,
    /// Minimise or maximise.
    pub sense: Sense,
    /// MAX, MAXABS, RMS or END.
    pub reduce: Spanned<Reduce>,
    /// The buffer.
    pub buffer: Spanned<i64>,
    /// The second component b2, if given: the objective is then of the
    /// magnitude `sqrt(b^2 + b2^2)` (a force's x and y).
    pub with: Option<Spanned<i64>>,
}
