//! A deck rewritten with new numbers: the final design of a `KIN OPT` run as
//! a `KIN ANA` deck that runs as any deck.
//!
//! [`design_deck`] works on the deck's own lines: it replaces the words that
//! hold the changed PARA and XFIX/XMOV values, the mode line and the
//! OPTIMISE block, and leaves every other line (comments, layout, blank
//! lines, whatever follows END) as the user wrote it.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use mechfem_core::{Dim, FormRef, Units};

use crate::ast::{Deck, LoadDefKind, MotionKind, NameKind};
use crate::diagnostic::{Diagnostic, DiagnosticKind, Diagnostics, Span, Spanned};
use crate::keywords::Block;
use crate::lexer::{lex_line, looks_numeric};
use crate::parse::parse_str;

/// The deck `text` (named `path` in diagnostics) with the PARA value of
/// every prescribed row `r` of `rows` and the XFIX or XMOV value of every
/// co-ordinate `i` of `coords` replaced (`(number, value)`, numbered as in
/// the deck, 1-based), and, for a `KIN OPT` deck, in mode `KIN ANA`: the
/// mode line says `KIN ANA`, and the OPTIMISE block is removed, except its
/// `BUF...` lines, which move to the top of the STORAGE block (where
/// PRINTBUF, SAVEDATA and pictures may name them; without a STORAGE block
/// nothing names them and they go too).
///
/// With `file_dir`, every MOV_FUNC and LOADFUNC file name that is not an
/// absolute path is written as `file_dir` joined with it: `file_dir` is the
/// old deck's folder as seen from where the new deck is written (relative
/// to the new deck's folder, or absolute), so that the new deck finds the
/// same files. Without it the names are kept.
///
/// The values are in the core's units, as the optimiser computes them: a
/// deck with UNITS gets them converted into its own units. Values are
/// written with Rust's shortest round-trip formatting, so the new deck
/// (without UNITS) reads back exactly these numbers. A row without a PARA line or
/// a co-ordinate not declared is reported as a diagnostic, as is a deck
/// that does not parse.
///
/// ```
/// let text = "KIN OPT\nTOPOLOGY\nELEM 1 BIN 1 2 3 4\nFORM 1 LENL 1 1\n 2 ANGB 1 2\nNRDOF 1\n\
///             GEOMETRY\nXFIX 1 0\n 2 0\nXMOV 3 1\n 4 .5\nPARA 1 1 ; crank\nMOVEMENT\nTSTEPE 4\n\
///             MOV_RELE 1 1.5\nOPTIMISE\nVARY 1 0.5 2\nBUFX0 4 1\nTARGETAT 1 5 0.5\n";
/// let out = mechfem_deck::rewrite::design_deck(text, "design.mec", &[(1, 0.75)], &[(3, 0.7)], None).unwrap();
/// assert!(out.starts_with("KIN ANA\n"));
/// assert!(out.contains("PARA 1 0.75 ; crank\n") && out.contains("XMOV 3 0.7\n"));
/// assert!(!out.contains("OPTIMISE") && !out.contains("TARGETAT"));
/// ```
pub fn design_deck(
    text: &str,
    path: impl Into<PathBuf>,
    rows: &[(usize, f64)],
    coords: &[(usize, f64)],
    file_dir: Option<&Path>,
) -> Result<String, Diagnostics> {
    let path = path.into();
    let deck = parse_str(text, path.clone())?;
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let lines: Vec<&str> = text.lines().map(|l| l.trim_end_matches('\r')).collect();

    // Word replacements per line: (span, new text).
    let mut edits: BTreeMap<usize, Vec<(Span, String)>> = BTreeMap::new();
    let mut edit = |span: Span, new: String| edits.entry(span.line).or_default().push((span, new));
    // The values are the core's; a deck with UNITS gets them in its own units.
    let units = deck.units.as_ref().map_or(Units::NONE, |u| u.units);
    let dims =
        if units.is_identity() { None } else { Some(crate::compile::dims(&deck).map_err(|d| Diagnostics(vec![*d]))?) };
    let written = |dim: Option<Dim>, value: f64| match dim {
        Some(dim) => units.from_core(dim, value),
        None => value,
    };
    for &(r, value) in rows {
        let value = written(dims.as_ref().map(|d| d.form(FormRef::Prescribed(r.saturating_sub(1)))), value);
        let para = deck.geometry.paras.iter().find(|p| usize::try_from(p.row.value) == Ok(r));
        let para = para.ok_or_else(|| {
            missing(&path, DiagnosticKind::UnknownRow, format!("prescribed row {r} has no PARA line"))
        })?;
        edit(para.value.span, format!("{value}"));
    }
    for &(i, value) in coords {
        let value = written(dims.as_ref().map(|d| d.coord(i.saturating_sub(1))), value);
        let coord = deck.geometry.coords.iter().find(|c| usize::try_from(c.index.value) == Ok(i));
        let message = || format!("co-ordinate {i} is not declared (XFIX or XMOV)");
        let coord = coord.ok_or_else(|| missing(&path, DiagnosticKind::CoordinateNotDeclared, message()))?;
        edit(coord.value.span, format!("{value}"));
    }
    if let Some(dir) = file_dir {
        for file in files(&deck) {
            if !Path::new(&file.value).is_absolute() {
                edit(file.span, dir.join(&file.value).display().to_string());
            }
        }
    }
    let optimise = deck.optimise.as_ref().map(|o| (o.line, block_end(&lines, o.line)));
    // A DYN ANA deck keeps its mode: without OPTIMISE it analyses the design.
    if optimise.is_some() && deck.mode.value == crate::ast::Mode::KinOpt {
        edit(deck.mode.span, "KIN ANA".to_string());
    }
    let moved = moved_buffers(&deck, &lines);
    // Without a STORAGE block the OPTIMISE block's buffers go, and so do their NAMES labels.
    let dropped: Vec<usize> = match (&deck.optimise, &deck.storage, &deck.names) {
        (Some(o), None, Some(names)) => names
            .names
            .iter()
            .filter(|n| n.kind.value == NameKind::Buf && o.buffers.iter().any(|b| b.number.value == n.numbers[0].value))
            .map(|n| n.line)
            .collect(),
        _ => Vec::new(),
    };
    let units_line = deck.units.as_ref().map(|u| u.line);

    let newline = if text.contains("\r\n") { "\r\n" } else { "\n" };
    let mut out: Vec<String> = Vec::with_capacity(lines.len() + moved.len());
    for (k, line) in lines.iter().enumerate() {
        let number = k + 1;
        let in_optimise = optimise.is_some_and(|(first, last)| (first..=last).contains(&number));
        if (in_optimise && units_line != Some(number)) || dropped.contains(&number) {
            continue;
        }
        out.push(match edits.get_mut(&number) {
            Some(e) => replaced(line, e),
            None => line.to_string(),
        });
        if deck.storage.as_ref().is_some_and(|s| s.line == number) {
            out.extend(moved.iter().cloned());
        }
    }
    let mut joined = out.join(newline);
    if text.ends_with('\n') {
        joined.push_str(newline);
    }
    Ok(joined)
}

fn missing(path: &Path, kind: DiagnosticKind, message: String) -> Diagnostics {
    Diagnostic::file(kind, path, message).into()
}

/// The MOV_FUNC and LOADFUNC file names of the deck.
fn files(deck: &Deck) -> Vec<&Spanned<String>> {
    let motions = deck.movement.iter().flat_map(|m| &m.motions).filter_map(|m| match &m.kind {
        MotionKind::Function(f) => Some(f),
        _ => None,
    });
    let loads = deck.dynamics.iter().flat_map(|d| &d.loads).filter_map(|l| match &l.kind {
        LoadDefKind::Function(f) => Some(f),
        _ => None,
    });
    motions.chain(loads).collect()
}

/// `line` with the character ranges of `edits` replaced.
pub(crate) fn replaced(line: &str, edits: &mut [(Span, String)]) -> String {
    edits.sort_by_key(|(s, _)| s.start);
    let chars: Vec<char> = line.chars().collect();
    let mut out = String::with_capacity(line.len() + 16);
    let mut at = 0;
    for (span, new) in edits.iter() {
        out.extend(&chars[at.min(chars.len())..span.start.min(chars.len())]);
        out.push_str(new);
        at = span.end.max(at);
    }
    out.extend(&chars[at.min(chars.len())..]);
    out
}

/// The last line of the block whose header is line `header`: the line before
/// the next block header or END, or the last line of the deck.
fn block_end(lines: &[&str], header: usize) -> usize {
    let next = (header + 1..=lines.len()).find(|&n| {
        lex_line(n, lines[n - 1]).is_some_and(|l| {
            let w = l.words[0].text.to_ascii_uppercase();
            w == "END" || Block::from_name(&w).is_some()
        })
    });
    next.map_or(lines.len(), |n| n - 1)
}

/// The OPTIMISE block's `BUF...` lines as STORAGE lines (a repetition line
/// gets its keyword written out), or none without a STORAGE block.
fn moved_buffers(deck: &Deck, lines: &[&str]) -> Vec<String> {
    let (Some(o), Some(_)) = (deck.optimise.as_ref(), deck.storage.as_ref()) else { return Vec::new() };
    o.buffers
        .iter()
        .map(|b| {
            let line = lines.get(b.line - 1).copied().unwrap_or("");
            let first = lex_line(b.line, line).map(|l| l.words[0].text.clone()).unwrap_or_default();
            if looks_numeric(&first) {
                format!("  {} {}", b.keyword.value.name(), line.trim_start())
            } else {
                line.to_string()
            }
        })
        .collect()
}
