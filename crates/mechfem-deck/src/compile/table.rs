//! Tables of numbers in files named by the deck (MOV_FUNC, LOADFUNC,
//! TARGET).
//!
//! One row per line, numbers in Fortran's format separated by blanks, tabs
//! or commas; blank lines and comments (`;` or `#`) are skipped. A TARGET
//! file is a column with one row per position, where a blank row is a
//! position without a value. File names are relative to the deck's folder.
//!
//! A table file is read as data only: it must be a regular file (not a
//! folder, a device or a pipe), of at most [`MAX_TABLE_BYTES`] (or the
//! keyword's own smaller limit) and [`MAX_TABLE_LINES`] lines, without NUL
//! bytes (a binary file). The size is checked before reading, and the read
//! itself is capped, so no file is read without bound.

use std::ops::RangeInclusive;
use std::path::{Path, PathBuf};

use crate::args::Source;
use crate::ast::{diagnostic_at, Deck};
use crate::diagnostic::{Diagnostic, DiagnosticKind, Hint, Span, Spanned};
use crate::files::{bytes, Refused};
use crate::keywords::Keyword;
use crate::lexer::lex_line;
use crate::statements::dynamics::out_of_bounds;

/// The largest table file read when the keyword has no smaller limit.
pub(crate) const MAX_TABLE_BYTES: u64 = 64 << 20;

/// The most lines a table file may have: more than any motion or load
/// table needs, and few enough that a table never takes much memory.
pub(crate) const MAX_TABLE_LINES: usize = 2_000_000;

/// What a table file of a keyword must look like.
pub(crate) struct Layout {
    /// The keyword that names the file.
    pub keyword: Keyword,
    /// The diagnostic kind of a file that cannot be read or is too large
    /// (a bad row is `ArgumentCount` or `NotANumber`, at the line of the file).
    pub kind: DiagnosticKind,
    /// How many numbers a row holds.
    pub columns: RangeInclusive<usize>,
    /// What each column is, for messages (`the time`, ...).
    pub names: &'static [&'static str],
    /// How a row is written, for the hint of a bad row.
    pub row: &'static str,
    /// The largest file read, with the hint for a larger one (`None`:
    /// [`MAX_TABLE_BYTES`]).
    pub max_bytes: Option<(u64, &'static str)>,
}

/// A table read from a file.
pub(crate) struct Table {
    /// The file, as it was looked up (deck folder joined with the name).
    pub path: PathBuf,
    /// Its lines, for diagnostics.
    lines: Vec<String>,
    /// The rows, with the line (1-based) each one is on.
    pub rows: Vec<(usize, Vec<Spanned<f64>>)>,
}

impl Table {
    /// A diagnostic pointing at `span` of the table's file.
    pub fn error(&self, kind: DiagnosticKind, span: Span, message: impl Into<String>) -> Box<Diagnostic> {
        token_only(diagnostic_at(&self.path, &self.lines, kind, span, message))
    }
}

/// Reads the table file named by `file` (relative to `deck_dir`).
pub(crate) fn read(
    deck: &Deck,
    file: &Spanned<String>,
    deck_dir: &Path,
    layout: &Layout,
) -> Result<Table, Box<Diagnostic>> {
    let kw = layout.keyword;
    let (path, lines) = read_lines(deck, file, deck_dir, kw, layout.kind, layout.max_bytes)?;
    let src = Source { path: &path, lines: &lines };
    let (min, max) = (*layout.columns.start(), *layout.columns.end());
    let mut rows = Vec::new();
    for (k, line) in lines.iter().enumerate() {
        let cleaned: String =
            line.split('#').next().unwrap_or("").chars().map(|c| if c == ',' { ' ' } else { c }).collect();
        let Some(words) = lex_line(k + 1, &cleaned) else { continue };
        let n = words.words.len();
        if !layout.columns.contains(&n) {
            let surplus = (n > max).then_some(max);
            let holds = if min == max { min.to_string() } else { format!("{min} to {max}") };
            let message = format!("a row of a {kw} file holds {holds} numbers, this one has {n}");
            return Err(token_only(src.count_error(&words, &words.words, surplus, message).with_hint(layout.row)));
        }
        let row = words
            .words
            .iter()
            .zip(layout.names)
            .map(|(w, what)| src.real(w, what))
            .collect::<Result<Vec<_>, _>>()
            .map_err(token_only)?;
        rows.push((k + 1, row));
    }
    Ok(Table { path, lines, rows })
}

/// The lines of the file named by `file` (relative to `deck_dir`), with
/// the path it was looked up at; `kind` is the diagnostic kind of a file
/// that cannot be read or is larger than `max_bytes`.
fn read_lines(
    deck: &Deck,
    file: &Spanned<String>,
    deck_dir: &Path,
    kw: Keyword,
    kind: DiagnosticKind,
    max_bytes: Option<(u64, &'static str)>,
) -> Result<(PathBuf, Vec<String>), Box<Diagnostic>> {
    let path = deck_dir.join(&file.value);
    let at_deck = |message: String| deck.error(kind, file.span, message);
    let (max, hint) = max_bytes.unwrap_or((
        MAX_TABLE_BYTES,
        "a table file holds one short row of numbers per position or time: check that the deck names the right file",
    ));
    let name = &file.value;
    let bytes = bytes(&path, max).map_err(|e| match e {
        Refused::TooLarge => {
            at_deck(format!("the {kw} file `{name}` is larger than {} MiB", max >> 20)).with_hint(hint)
        }
        Refused::Io(why) => at_deck(format!("cannot read the {kw} file `{name}`: {why}"))
            .with_hint(format!("the file name is relative to the deck's folder; looked for {}", path.display())),
    })?;
    if let Some(at) = bytes.iter().position(|&b| b == 0) {
        return Err(at_deck(format!(
            "the {kw} file `{name}` is a binary file, not a table of numbers (a NUL byte at byte {})",
            at + 1
        ))
        .with_hint("a table file is text: one row of numbers per line, separated by blanks, tabs or commas"));
    }
    let n_lines = bytes.iter().filter(|&&b| b == b'\n').count() + usize::from(!bytes.ends_with(b"\n"));
    if n_lines > MAX_TABLE_LINES {
        return Err(
            at_deck(format!("the {kw} file `{name}` has {n_lines} lines, more than {MAX_TABLE_LINES}")).with_hint(hint)
        );
    }
    let text = String::from_utf8_lossy(&bytes);
    // A byte-order mark, as some editors write, is no part of the first row (a deck may have one too).
    let text = text.strip_prefix('\u{feff}').unwrap_or(&text);
    let lines = text.lines().map(|l| l.trim_end_matches('\r').to_string()).collect();
    Ok((path, lines))
}

/// Reads a TARGET file: one entry per row, a number, or `None` for a row
/// that is blank or `*` (a position that is not compared). Lines that hold only a
/// comment are not rows, nor are the blank lines at the end of the file,
/// which editors add unseen.
pub(crate) fn read_column(
    deck: &Deck,
    file: &Spanned<String>,
    deck_dir: &Path,
    kw: Keyword,
) -> Result<Vec<Option<f64>>, Box<Diagnostic>> {
    let (path, lines) = read_lines(deck, file, deck_dir, kw, DiagnosticKind::TargetFile, None)?;
    let src = Source { path: &path, lines: &lines };
    let mut values = Vec::new();
    let mut blank_tail = 0;
    for (k, line) in lines.iter().enumerate() {
        let trimmed = line.trim_start();
        if trimmed.starts_with(';') || trimmed.starts_with('#') {
            continue;
        }
        let useful = line.split('#').next().unwrap_or("");
        let Some(words) = lex_line(k + 1, useful) else {
            values.push(None);
            blank_tail += 1;
            continue;
        };
        blank_tail = 0;
        if words.words.len() > 1 {
            let message = format!("a row of a {kw} file holds one value, this one has {}", words.words.len());
            return Err(token_only(src.count_error(&words, &words.words, Some(1), message).with_hint(COLUMN_ROW)));
        }
        let word = &words.words[0];
        if word.text == "*" {
            values.push(None);
        } else {
            let v = src.real(word, "the target value").map_err(token_only).map_err(|d| match d.kind {
                DiagnosticKind::NotANumber => d.with_hint(
                    "write a number (like 12, -3.6, .5, 4E5 or 1.5D0) in each row, or `*` (or nothing) where the \
                     position is not compared",
                ),
                _ => d,
            })?;
            // The objective squares the difference from the value and
            // weighs it: a value within the numbers of the dynamics keeps
            // that finite.
            if let Some((message, hint)) = out_of_bounds("the target value", v.value) {
                return Err(token_only(
                    src.error(DiagnosticKind::NumberOutOfRange, word.span, message).with_hint(hint),
                ));
            }
            values.push(Some(v.value));
        }
    }
    values.truncate(values.len() - blank_tail);
    Ok(values)
}

/// How a row of a TARGET file is written.
const COLUMN_ROW: &str = "write one row per position: the value the buffer should take there, or `*` (or nothing) \
                          where it is not compared";

/// A diagnostic about a line of a table file, showing of that line only
/// the word at fault: the file is not the deck, and may be one the deck
/// should not have named (`MOV_FUNC 1 ~/.netrc`), so no more of it is
/// quoted than the mistake needs. Every other character but blanks shows
/// as `·`, so that the row keeps its shape and the columns stay true; a
/// wrong count of numbers needs none of them (the message gives the count).
fn token_only(mut d: Box<Diagnostic>) -> Box<Diagnostic> {
    let shown = if d.kind == DiagnosticKind::ArgumentCount { 0..0 } else { d.columns.clone() };
    d.text = d
        .text
        .chars()
        .enumerate()
        .map(|(k, c)| if shown.contains(&k) || c.is_whitespace() { c } else { '·' })
        .collect();
    d
}
