//! Diagnostics: what is wrong with a deck, where, and how to fix it.
//!
//! A [`Diagnostic`] renders like the messages of rustc and ruff: the message,
//! the file and position, the offending line with a caret under the word,
//! and a hint.

use std::fmt;
use std::ops::Range;
use std::path::PathBuf;

use mechfem_core::ElementError;
use thiserror::Error;

/// A position in a deck: a line and a range of characters on it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct Span {
    /// Line number, 1-based (0: the file as a whole).
    pub line: usize,
    /// First character, 0-based (characters, not bytes).
    pub start: usize,
    /// One past the last character.
    pub end: usize,
}

impl Span {
    /// A span covering characters `start..end` of `line`.
    pub fn new(line: usize, start: usize, end: usize) -> Span {
        Span { line, start, end }
    }

    /// A span that covers both `self` and `other` (same line assumed).
    pub fn to(self, other: Span) -> Span {
        Span { line: self.line, start: self.start.min(other.start), end: self.end.max(other.end) }
    }
}

/// A value read from the deck, with the place it was read from.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Spanned<T> {
    /// The value.
    pub value: T,
    /// Where it stands in the deck.
    pub span: Span,
}

impl<T> Spanned<T> {
    /// Wraps a value with its span.
    pub fn new(value: T, span: Span) -> Self {
        Spanned { value, span }
    }
}

/// What kind of mistake a [`Diagnostic`] reports.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum DiagnosticKind {
    /// The deck or a file it names cannot be read.
    Io,
    /// The first line is not a mode line.
    MissingMode,
    /// A mode line that names no known mode.
    UnknownMode,
    /// A word in keyword position that is no keyword.
    UnknownKeyword,
    /// A line starting with a number, with no earlier keyword in its block to repeat.
    NothingToRepeat,
    /// A keyword outside the block it belongs to.
    WrongBlock,
    /// A block header given twice.
    DuplicateBlock,
    /// A required block (TOPOLOGY, GEOMETRY; DYNAMICS in a DYN ANA or DYN SIM
    /// deck; MOVEMENT in a DYN SIM or KIN OPT deck; OPTIMISE in a KIN OPT
    /// deck) is missing.
    MissingBlock,
    /// A block or keyword that the deck's mode does not have (DYNAMICS or a
    /// dynamics buffer in KIN ANA and KIN OPT, OPTIMISE outside KIN OPT,
    /// MOV_FREE in DYN ANA, DYN SIM and KIN OPT, MOV_DYN and INTTOL outside
    /// DYN SIM).
    WrongMode,
    /// Too few or too many arguments.
    ArgumentCount,
    /// An argument that should be a number is not one (also NaN, inf).
    NotANumber,
    /// An argument that should be a whole number is not one.
    NotAWholeNumber,
    /// A number too large to represent.
    NumberOutOfRange,
    /// A value outside its allowed range (steps < 1, dt <= 0, INTTOL <= 0,
    /// a range whose lower end is not below its upper end, a weight <= 0, a
    /// position outside the motion, ...).
    BadValue,
    /// An element type name that is not in the catalogue.
    UnknownElementType,
    /// Elements not numbered 1, 2, 3, ... in sequence.
    ElementSequence,
    /// A keyword that may appear once is given again (NRDOF, TSTEPE, ...;
    /// also a second MINIMISE or MAXIMISE).
    DuplicateKeyword,
    /// TSTEPE is not the first keyword of the MOVEMENT block.
    TstepeNotFirst,
    /// The MOVEMENT block has no TSTEPE.
    MissingTstepe,
    /// BEGINPIC without ENDPIC, ENDPIC without BEGINPIC, PLOT* outside a
    /// picture, a picture with nothing in it, ...
    PictureStructure,
    /// A co-ordinate number outside 1..N.
    CoordinateOutOfRange,
    /// A co-ordinate declared twice (XFIX and XMOV, or twice the same).
    CoordinateDeclaredTwice,
    /// A co-ordinate used by an element but never declared.
    CoordinateNotDeclared,
    /// A gap in the co-ordinate numbers 1..N.
    CoordinateMissing,
    /// A declared co-ordinate that no element uses.
    CoordinateUnused,
    /// FORM or MASS refers to an element that does not exist.
    UnknownElement,
    /// MASS on an element that has no frame to carry a body (GR1, GR2, RK1, RK2, BLT, CRD).
    NoFrame,
    /// A form-parameter name that the element type does not have.
    UnknownFormName,
    /// A FORM destination of 0.
    ZeroDestination,
    /// Prescribed rows not 1..n_p without gaps.
    RowGap,
    /// Dependent form parameters not 1..n_d without gaps.
    DependentGap,
    /// NRDOF missing.
    MissingNrdof,
    /// NRDOF larger than the number of prescribed rows.
    NrdofTooLarge,
    /// The number of prescribed rows differs from the number of moving co-ordinates.
    NotSquare,
    /// PARA, BUF..., LOAD, LOADFUNC, SPRING, MOTOR or VARY for a row or
    /// dependent form parameter that does not exist (for VARY: that is no
    /// prescribed row).
    UnknownRow,
    /// PARA given twice for the same row.
    DuplicatePara,
    /// A DOF number outside 1..NRDOF.
    UnknownDof,
    /// A DOF given two motions.
    DuplicateMotion,
    /// A DOF without a motion.
    MissingMotion,
    /// MOV_FREE in a mechanism with more than one DOF.
    FreeMotionDof,
    /// A MOV_FUNC file with the wrong number of rows or a bad row.
    MotionFile,
    /// A LOADFUNC file that cannot be read, is too large or empty, or has
    /// a bad row or rows out of time order.
    LoadFile,
    /// BUFREA or VARYX on a co-ordinate that moves (only fixed ones have a
    /// reaction or are design variables of their own).
    NotFixed,
    /// A buffer number defined twice.
    DuplicateBuffer,
    /// PRINTBUF, SAVEDATA, PLOT*, TARGET..., BOUND, MINIMISE or MAXIMISE
    /// naming a buffer that is not defined.
    UnknownBuffer,
    /// VARY or VARYX of something that cannot be a design variable: a row
    /// without PARA, the input of a MOV_FUNC motion, a variable varied twice,
    /// a start value outside the range.
    DesignVariable,
    /// An OPTIMISE block without design variables, or with nothing to
    /// optimise (no TARGET..., MINIMISE or MAXIMISE).
    NothingToOptimise,
    /// A TARGET file that cannot be read, has a bad row, no value, or not
    /// one row per position.
    TargetFile,
    /// TARGETEXT whose reference buffer is not a position quantity (BUFX0,
    /// BUFE0, BUFINP), so it has no transfer functions to locate an extremum.
    ExtremumReference,
    /// TARGET..., BOUND, MINIMISE or MAXIMISE on a buffer that has no design
    /// sensitivity (BUFDET), so an optimiser cannot tell how to improve it.
    NoSensitivity,
    /// The core refused the model (for example coinciding points of a binary).
    Model,
    /// An output name (ANIMATE) that is not a plain file name: a folder
    /// part, `..`, an absolute path, a control character or more than
    /// [`MAX_OUTPUT_NAME`] bytes. A run writes into its output folder only.
    OutputName,
    /// A NAMES line that starts with no kind of name (POINT, COORD, ELEM,
    /// ROW, DEP, BUF).
    UnknownNameKind,
    /// A name that is not `[A-Za-z_][A-Za-z0-9_]*` or is longer than 40
    /// characters.
    BadName,
    /// A name given twice within its kind, or a thing named twice.
    DuplicateName,
    /// A NAMES line for a co-ordinate, element, row or buffer the deck does
    /// not have.
    NameOutOfRange,
    /// A buffer label (NAMES `BUF`) that does not print or is longer than
    /// 60 characters.
    BadLabel,
    /// A UNITS field or unit that does not exist.
    UnknownUnit,
    /// A number that looks as if it were written in another unit than the
    /// deck's (a warning, never an error).
    SuspiciousUnit,
    /// A TOLERANCE block without a toleranced dimension or a band, without
    /// a motion, or whose band numbers clash with other buffers.
    Tolerance,
    /// BUFPIN names co-ordinates that are not a point of its element.
    NotAPin,
}

impl DiagnosticKind {
    /// A stable name for the kind, in snake case (`coordinate_unused`): what
    /// front ends match on instead of the message, which may be reworded.
    pub fn code(self) -> &'static str {
        match self {
            DiagnosticKind::Io => "io",
            DiagnosticKind::MissingMode => "missing_mode",
            DiagnosticKind::UnknownMode => "unknown_mode",
            DiagnosticKind::UnknownKeyword => "unknown_keyword",
            DiagnosticKind::NothingToRepeat => "nothing_to_repeat",
            DiagnosticKind::WrongBlock => "wrong_block",
            DiagnosticKind::DuplicateBlock => "duplicate_block",
            DiagnosticKind::MissingBlock => "missing_block",
            DiagnosticKind::WrongMode => "wrong_mode",
            DiagnosticKind::ArgumentCount => "argument_count",
            DiagnosticKind::NotANumber => "not_a_number",
            DiagnosticKind::NotAWholeNumber => "not_a_whole_number",
            DiagnosticKind::NumberOutOfRange => "number_out_of_range",
            DiagnosticKind::BadValue => "bad_value",
            DiagnosticKind::UnknownElementType => "unknown_element_type",
            DiagnosticKind::ElementSequence => "element_sequence",
            DiagnosticKind::DuplicateKeyword => "duplicate_keyword",
            DiagnosticKind::TstepeNotFirst => "tstepe_not_first",
            DiagnosticKind::MissingTstepe => "missing_tstepe",
            DiagnosticKind::PictureStructure => "picture_structure",
            DiagnosticKind::CoordinateOutOfRange => "coordinate_out_of_range",
            DiagnosticKind::CoordinateDeclaredTwice => "coordinate_declared_twice",
            DiagnosticKind::CoordinateNotDeclared => "coordinate_not_declared",
            DiagnosticKind::CoordinateMissing => "coordinate_missing",
            DiagnosticKind::CoordinateUnused => "coordinate_unused",
            DiagnosticKind::UnknownElement => "unknown_element",
            DiagnosticKind::NoFrame => "no_frame",
            DiagnosticKind::UnknownFormName => "unknown_form_name",
            DiagnosticKind::ZeroDestination => "zero_destination",
            DiagnosticKind::RowGap => "row_gap",
            DiagnosticKind::DependentGap => "dependent_gap",
            DiagnosticKind::MissingNrdof => "missing_nrdof",
            DiagnosticKind::NrdofTooLarge => "nrdof_too_large",
            DiagnosticKind::NotSquare => "not_square",
            DiagnosticKind::UnknownRow => "unknown_row",
            DiagnosticKind::DuplicatePara => "duplicate_para",
            DiagnosticKind::UnknownDof => "unknown_dof",
            DiagnosticKind::DuplicateMotion => "duplicate_motion",
            DiagnosticKind::MissingMotion => "missing_motion",
            DiagnosticKind::FreeMotionDof => "free_motion_dof",
            DiagnosticKind::MotionFile => "motion_file",
            DiagnosticKind::LoadFile => "load_file",
            DiagnosticKind::NotFixed => "not_fixed",
            DiagnosticKind::DuplicateBuffer => "duplicate_buffer",
            DiagnosticKind::UnknownBuffer => "unknown_buffer",
            DiagnosticKind::DesignVariable => "design_variable",
            DiagnosticKind::NothingToOptimise => "nothing_to_optimise",
            DiagnosticKind::TargetFile => "target_file",
            DiagnosticKind::ExtremumReference => "extremum_reference",
            DiagnosticKind::NoSensitivity => "no_sensitivity",
            DiagnosticKind::Model => "model",
            DiagnosticKind::OutputName => "output_name",
            DiagnosticKind::UnknownNameKind => "unknown_name_kind",
            DiagnosticKind::BadName => "bad_name",
            DiagnosticKind::DuplicateName => "duplicate_name",
            DiagnosticKind::NameOutOfRange => "name_out_of_range",
            DiagnosticKind::BadLabel => "bad_label",
            DiagnosticKind::UnknownUnit => "unknown_unit",
            DiagnosticKind::SuspiciousUnit => "suspicious_unit",
            DiagnosticKind::Tolerance => "tolerance",
            DiagnosticKind::NotAPin => "not_a_pin",
        }
    }
}

/// The longest output name (in bytes) a deck may give, so that the name
/// with its extension stays well below the 255 bytes a file name may have.
pub const MAX_OUTPUT_NAME: usize = 200;

/// Why `name` is not a plain file name that stays inside the output folder,
/// or `None` when it is one.
pub fn output_name_problem(name: &str) -> Option<String> {
    let trimmed = name.trim();
    let drive = trimmed.len() >= 2 && trimmed.as_bytes()[1] == b':' && trimmed.as_bytes()[0].is_ascii_alphabetic();
    if trimmed.is_empty() {
        Some("is empty".into())
    } else if trimmed.starts_with('/') || trimmed.starts_with('\\') || drive {
        Some("is an absolute path".into())
    } else if trimmed.split(['/', '\\']).any(|part| part == "..") || trimmed == "." {
        Some("leads out of the output folder (`..`)".into())
    } else if trimmed.contains(['/', '\\']) {
        Some("has a folder part (`/` or `\\`)".into())
    } else if name.contains('\0') {
        Some("holds a NUL character".into())
    } else if name.chars().any(char::is_control) {
        Some("holds a control character".into())
    } else if let Some(c) = name.chars().find(|&c| is_format(c)) {
        Some(format!(
            "holds the character U+{:04X}, which does not show as itself (a format character or separator)",
            u32::from(c)
        ))
    } else if name.len() > MAX_OUTPUT_NAME {
        Some(format!("is {} bytes long, more than {MAX_OUTPUT_NAME}", name.len()))
    } else {
        None
    }
}

/// Whether `c` is a format character (Unicode category Cf: a direction
/// override such as U+202E, a zero-width space, a soft hyphen) or a line or
/// paragraph separator (U+2028, U+2029): invisible, or shown as a break,
/// so that a name holding one reads as another name.
pub(crate) fn is_format(c: char) -> bool {
    matches!(
        u32::from(c),
        0xAD | 0x600..=0x605
            | 0x61C
            | 0x6DD
            | 0x70F
            | 0x890..=0x891
            | 0x8E2
            | 0x180E
            | 0x200B..=0x200F
            | 0x2028..=0x202E
            | 0x2060..=0x2064
            | 0x2066..=0x206F
            | 0xFEFF
            | 0xFFF9..=0xFFFB
            | 0x110BD
            | 0x110CD
            | 0x13430..=0x1343F
            | 0x1BCA0..=0x1BCA3
            | 0x1D173..=0x1D17A
            | 0xE0001
            | 0xE0020..=0xE007F
    )
}

/// One mistake in a deck, with the place it was found and a hint.
#[derive(Debug, Clone, PartialEq, Error)]
pub struct Diagnostic {
    /// What kind of mistake.
    pub kind: DiagnosticKind,
    /// The file, as the caller named it.
    pub path: PathBuf,
    /// Line number, 1-based; 0 when the mistake concerns the file as a whole.
    pub line: usize,
    /// Characters of the line that are at fault (0-based, end exclusive).
    pub columns: Range<usize>,
    /// The text of the line (without its line break).
    pub text: String,
    /// What is wrong.
    pub message: String,
    /// How to fix it.
    pub hint: Option<String>,
    /// The element the mistake is about (1-based), when it is about one.
    pub element: Option<usize>,
    /// The co-ordinate the mistake is about (1-based), when it is about one.
    pub coordinate: Option<usize>,
    /// Why the core refused an element, in its own words (`its points P and Q
    /// coincide`), without the deck's numbering around it.
    pub detail: Option<String>,
    /// The core's reason itself, for a front end that words it with its own
    /// names for the element's points.
    pub element_error: Option<ElementError>,
}

impl Diagnostic {
    /// A diagnostic about the whole file (no line).
    pub fn file(kind: DiagnosticKind, path: impl Into<PathBuf>, message: impl Into<String>) -> Diagnostic {
        Diagnostic {
            kind,
            path: path.into(),
            line: 0,
            columns: 0..0,
            text: String::new(),
            message: message.into(),
            hint: None,
            element: None,
            coordinate: None,
            detail: None,
            element_error: None,
        }
    }

    /// Adds a hint.
    pub fn with_hint(mut self, hint: impl Into<String>) -> Diagnostic {
        self.hint = Some(hint.into());
        self
    }
}

/// Adds a hint to a boxed diagnostic (the form used inside this crate, to
/// keep `Result`s small).
pub(crate) trait Hint {
    /// Adds a hint.
    fn with_hint(self, hint: impl Into<String>) -> Self;
}

impl Hint for Box<Diagnostic> {
    fn with_hint(mut self, hint: impl Into<String>) -> Self {
        self.hint = Some(hint.into());
        self
    }
}

/// Names what a boxed diagnostic is about, so that a front end can name it
/// in its own words without reading the message.
pub(crate) trait Subject {
    /// The element (0-based index) the mistake is about.
    fn about_element(self, index: usize) -> Self;
    /// The co-ordinate (1-based, as the deck numbers it) the mistake is about.
    fn about_coordinate(self, number: usize) -> Self;
    /// The core's own reason why the element cannot be evaluated.
    fn with_detail(self, error: ElementError) -> Self;
}

impl Subject for Box<Diagnostic> {
    fn about_element(mut self, index: usize) -> Self {
        self.element = Some(index + 1);
        self
    }
    fn about_coordinate(mut self, number: usize) -> Self {
        self.coordinate = Some(number);
        self
    }
    fn with_detail(mut self, error: ElementError) -> Self {
        self.detail = Some(error.to_string());
        self.element_error = Some(error);
        self
    }
}

/// Width of a character on screen: tabs are shown as four blanks.
fn width(c: char) -> usize {
    if c == '\t' {
        4
    } else {
        1
    }
}

impl Diagnostic {
    /// The diagnostic rendered as a warning (`warning: ...`, the place, the
    /// line, a caret and the hint), for one that does not stop the deck
    /// ([`crate::Compiled::warnings`]).
    pub fn warning_text(&self) -> String {
        let text = self.to_string();
        match text.strip_prefix("error: ") {
            Some(rest) => format!("warning: {rest}"),
            None => text,
        }
    }
}

impl fmt::Display for Diagnostic {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(f, "error: {}", self.message)?;
        if self.line == 0 {
            write!(f, " --> {}", self.path.display())?;
            if let Some(hint) = &self.hint {
                write!(f, "\n  = hint: {hint}")?;
            }
            return Ok(());
        }
        let number = self.line.to_string();
        let pad = " ".repeat(number.len());
        writeln!(f, "{pad}--> {}:{}:{}", self.path.display(), self.line, self.columns.start + 1)?;
        writeln!(f, "{pad} |")?;
        // Tabs as four blanks; other control characters (a NUL) and format
        // characters (a direction override) as the replacement character,
        // so that the message stays plain text that reads as it is.
        let shown: String = self
            .text
            .chars()
            .map(|c| match c {
                '\t' => "    ".to_string(),
                c if c.is_control() || is_format(c) => '\u{fffd}'.to_string(),
                c => c.to_string(),
            })
            .collect();
        writeln!(f, "{number} | {}", shown.trim_end())?;
        let lead: usize = self.text.chars().take(self.columns.start).map(width).sum();
        let marked: usize = self.text.chars().skip(self.columns.start).take(self.columns.len()).map(width).sum();
        write!(f, "{pad} | {}{}", " ".repeat(lead), "^".repeat(marked.max(1)))?;
        if let Some(hint) = &self.hint {
            write!(f, "\n{pad} = hint: {hint}")?;
        }
        Ok(())
    }
}

/// One or more diagnostics; what the public functions of this crate return
/// on failure. Displays them one after another, separated by blank lines.
#[derive(Debug, Clone, PartialEq, Error)]
pub struct Diagnostics(pub Vec<Diagnostic>);

impl Diagnostics {
    /// The diagnostics, in the order of the deck.
    pub fn iter(&self) -> std::slice::Iter<'_, Diagnostic> {
        self.0.iter()
    }
}

impl From<Box<Diagnostic>> for Diagnostics {
    fn from(d: Box<Diagnostic>) -> Self {
        Diagnostics(vec![*d])
    }
}

impl From<Diagnostic> for Diagnostics {
    fn from(d: Diagnostic) -> Self {
        Diagnostics(vec![d])
    }
}

impl<'a> IntoIterator for &'a Diagnostics {
    type Item = &'a Diagnostic;
    type IntoIter = std::slice::Iter<'a, Diagnostic>;
    fn into_iter(self) -> Self::IntoIter {
        self.0.iter()
    }
}

impl fmt::Display for Diagnostics {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for (k, d) in self.0.iter().enumerate() {
            if k > 0 {
                write!(f, "\n\n")?;
            }
            write!(f, "{d}")?;
        }
        Ok(())
    }
}

/// "1 row", "2 rows", "no rows".
pub(crate) fn count(n: usize, singular: &str, plural: &str) -> String {
    match n {
        0 => format!("no {plural}"),
        1 => format!("1 {singular}"),
        _ => format!("{n} {plural}"),
    }
}

/// The numbers 1..n in words: "none", "1", "1..n"; `sign` -1 gives "-1..-n".
pub(crate) fn numbered(n: usize, sign: i64) -> String {
    let minus = if sign < 0 { "-" } else { "" };
    match n {
        0 => "none".to_string(),
        1 => format!("{minus}1"),
        _ => format!("{minus}1..{minus}{n}"),
    }
}

/// A number as a message shows it: in exponent form when very large or
/// very small, so that 1e307 does not take three hundred digits.
pub(crate) fn real(v: f64) -> String {
    if v != 0.0 && !(1e-4..1e15).contains(&v.abs()) {
        format!("{v:e}")
    } else {
        format!("{v}")
    }
}

/// Which degrees of freedom exist, as a hint.
pub(crate) fn dof_hint(n: usize) -> String {
    match n {
        1 => "the mechanism has one degree of freedom, DOF 1".to_string(),
        _ => format!("the degrees of freedom are numbered 1..{n}"),
    }
}
