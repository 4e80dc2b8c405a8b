//! A `DYN ANA` deck rewritten with new numbers of its mass model: the
//! final design of its OPTIMISE block's mass variables (VARYM), written
//! into the DYNAMICS lines they came from. The words that hold the values
//! are replaced; every other character of the deck stays as written.

use std::collections::BTreeMap;
use std::path::PathBuf;

use mechfem_core::{Dim, Units};

use crate::diagnostic::{Diagnostic, DiagnosticKind, Diagnostics, Span};
use crate::optimise::MassItem;
use crate::parse::parse_str;

/// The deck `text` (named `path` in diagnostics) with the number of every
/// `(item, number, value)` of `masses` replaced: MASS, U, V or J of element
/// `number`'s MASS line (a J the line leaves out is appended), the PMASS at
/// co-ordinate `number`, the INERTIA on it. The values are in the core's
/// units; a deck with UNITS gets them in its own. A deck that does not
/// parse, or a DYNAMICS line that does not exist, is a diagnostic.
///
/// ```
/// use mechfem_deck::MassItem;
/// let text = "DYN ANA\nTOPOLOGY\nELEM 1 BIN 1 2 3 4\nFORM 1 LENL 1 1\n 2 ANGB 1 2\nNRDOF 1\n\
///             GEOMETRY\nXFIX 1 0\n 2 0\nXMOV 3 1\n 4 0\nPARA 1 1\nDYNAMICS\nMASS 1 2 0.5 0 ; crank\n";
/// let masses = [(MassItem::U, 1, -0.25), (MassItem::J, 1, 0.125)];
/// let out = mechfem_deck::rewrite_masses::with_masses(text, "d.mec", &masses).unwrap();
/// assert!(out.contains("MASS 1 2 -0.25 0 0.125 ; crank\n"), "{out}");
/// ```
pub fn with_masses(
    text: &str,
    path: impl Into<PathBuf>,
    masses: &[(MassItem, usize, f64)],
) -> Result<String, Diagnostics> {
    let path = path.into();
    let deck = parse_str(text, path.clone())?;
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let lines: Vec<&str> = text.lines().map(|l| l.trim_end_matches('\r')).collect();
    let units = deck.units.as_ref().map_or(Units::NONE, |u| u.units);
    let dims =
        if units.is_identity() { None } else { Some(crate::compile::dims(&deck).map_err(|d| Diagnostics(vec![*d]))?) };
    let missing = |item: MassItem, n: usize| -> Diagnostics {
        let message = format!("the DYNAMICS block has no {} line for number {n}", item.name());
        Diagnostic::file(DiagnosticKind::BadValue, &path, message).into()
    };
    let dy = deck.dynamics.as_ref();
    let mut edits: BTreeMap<usize, Vec<(Span, String)>> = BTreeMap::new();
    for &(item, n, value) in masses {
        let is = |k: i64| usize::try_from(k) == Ok(n);
        let (span, dim, append) = match item {
            MassItem::PointMass => {
                let p =
                    dy.and_then(|d| d.point_masses.iter().find(|p| is(p.x.value))).ok_or_else(|| missing(item, n))?;
                (p.mass.span, Dim::MASS, false)
            }
            MassItem::Inertia => {
                let i =
                    dy.and_then(|d| d.inertias.iter().find(|i| is(i.coord.value))).ok_or_else(|| missing(item, n))?;
                let on = dims.as_ref().map_or(Dim::NONE, |d| d.coord(n.saturating_sub(1)));
                (i.inertia.span, crate::compile::inertia_on(on), false)
            }
            _ => {
                let m =
                    dy.and_then(|d| d.masses.iter().find(|m| is(m.element.value))).ok_or_else(|| missing(item, n))?;
                match item {
                    MassItem::Mass => (m.mass.span, Dim::MASS, false),
                    MassItem::U => (m.u.span, Dim::LENGTH, false),
                    MassItem::V => (m.v.span, Dim::LENGTH, false),
                    _ => m.inertia.as_ref().map_or((m.v.span, Dim::INERTIA, true), |j| (j.span, Dim::INERTIA, false)),
                }
            }
        };
        let value = if dims.is_some() { units.from_core(dim, value) } else { value };
        let new = if append {
            let written = lines.get(span.line - 1).map_or("", |l| word(l, span));
            format!("{written} {value}")
        } else {
            format!("{value}")
        };
        edits.entry(span.line).or_default().push((span, new));
    }
    let newline = if text.contains("\r\n") { "\r\n" } else { "\n" };
    let out: Vec<String> = lines
        .iter()
        .enumerate()
        .map(|(k, line)| match edits.get_mut(&(k + 1)) {
            Some(e) => crate::rewrite::replaced(line, e),
            None => (*line).to_string(),
        })
        .collect();
    let mut joined = out.join(newline);
    if text.ends_with('\n') {
        joined.push_str(newline);
    }
    Ok(joined)
}

/// The text of the word at `span` of `line`.
fn word(line: &str, span: Span) -> &str {
    let chars: Vec<(usize, char)> = line.char_indices().collect();
    let at = |c: usize| chars.get(c).map_or(line.len(), |&(b, _)| b);
    &line[at(span.start)..at(span.end)]
}
