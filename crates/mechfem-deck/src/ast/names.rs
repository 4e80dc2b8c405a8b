//! The NAMES block and the UNITS line, as written.

use mechfem_core::Units;

use crate::diagnostic::{Span, Spanned};

/// What a line of the NAMES block names.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum NameKind {
    /// `POINT i j name`: co-ordinates i (x) and j (y).
    Point,
    /// `COORD i name`: a single co-ordinate.
    Coord,
    /// `ELEM k name`: an element.
    Elem,
    /// `ROW r name`: a prescribed row.
    Row,
    /// `DEP d name`: a dependent form parameter.
    Dep,
    /// `BUF b label`: a buffer's label (free text).
    Buf,
}

impl NameKind {
    /// Every kind, in the order of the deck reference.
    pub const ALL: [NameKind; 6] =
        [NameKind::Point, NameKind::Coord, NameKind::Elem, NameKind::Row, NameKind::Dep, NameKind::Buf];

    /// The word that starts its line.
    pub fn word(self) -> &'static str {
        match self {
            NameKind::Point => "POINT",
            NameKind::Coord => "COORD",
            NameKind::Elem => "ELEM",
            NameKind::Row => "ROW",
            NameKind::Dep => "DEP",
            NameKind::Buf => "BUF",
        }
    }

    /// Its arguments, as in the deck reference.
    pub fn usage(self) -> &'static str {
        match self {
            NameKind::Point => "POINT i j name",
            NameKind::Coord => "COORD i name",
            NameKind::Elem => "ELEM k name",
            NameKind::Row => "ROW r name",
            NameKind::Dep => "DEP d name",
            NameKind::Buf => "BUF b label",
        }
    }

    /// How many numbers stand before the name.
    pub(crate) fn numbers(self) -> usize {
        if self == NameKind::Point {
            2
        } else {
            1
        }
    }

    /// The kind spelled `word` (case-insensitive).
    pub fn from_word(word: &str) -> Option<NameKind> {
        NameKind::ALL.into_iter().find(|k| k.word().eq_ignore_ascii_case(word))
    }
}

/// One line of the NAMES block.
#[derive(Debug, Clone, PartialEq)]
pub struct NameDef {
    /// Line of the definition.
    pub line: usize,
    /// What it names.
    pub kind: Spanned<NameKind>,
    /// The numbers: `[i, j]` of a POINT, one number otherwise (for DEP the
    /// dependent form parameter d, given as `d` or `-d`, kept positive).
    pub numbers: Vec<Spanned<i64>>,
    /// The name (a BUF's label: the text to the end of the line).
    pub name: Spanned<String>,
}

/// The NAMES block.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct NamesBlock {
    /// Line of the header.
    pub line: usize,
    /// Its lines, in order.
    pub names: Vec<NameDef>,
}

/// `UNITS LENGTH mm ANGLE deg ...`
#[derive(Debug, Clone, PartialEq)]
pub struct UnitsDef {
    /// Line of the keyword.
    pub line: usize,
    /// The units it declares (`declared` set).
    pub units: Units,
    /// The span of each value given, by kind: length, angle, mass, force, time.
    pub spans: [Option<Span>; 5],
}

/// How a deck's numbers were scaled to the core's units: set on the copy
/// of a deck with UNITS that [`crate::compile`] works on, for the numbers
/// it reads from tables (MOV_FUNC, LOADFUNC, TARGET files).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct CoreScale {
    /// The deck's units.
    pub units: Units,
    /// The kinds of the model's co-ordinates and rows.
    pub dims: mechfem_core::ModelDims,
    /// The kind of each DOF's input.
    pub inputs: Vec<mechfem_core::Dim>,
}

impl crate::ast::Deck {
    /// `value`, a number of kind `dim` of the deck [`crate::compile`] works
    /// on (in the core's units for a deck with UNITS), as the deck's units
    /// say it: what a message about the deck quotes.
    pub(crate) fn as_written(&self, dim: mechfem_core::Dim, value: f64) -> f64 {
        self.scale.as_ref().map_or(value, |s| s.units.from_core(dim, value))
    }
}
