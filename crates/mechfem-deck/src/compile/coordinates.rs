//! Co-ordinates: XFIX/XMOV declarations checked against the elements.

use std::collections::BTreeMap;

use crate::ast::{CoordDef, Deck};
use crate::diagnostic::{Diagnostic, DiagnosticKind, Hint, Subject};

/// Checks XFIX/XMOV against the elements: every co-ordinate 1..N declared
/// once and used by an element. Returns the declarations by number.
pub(crate) fn coordinates(deck: &Deck) -> Result<BTreeMap<i64, &CoordDef>, Box<Diagnostic>> {
    let mut decl: BTreeMap<i64, &CoordDef> = BTreeMap::new();
    for c in &deck.geometry.coords {
        let i = c.index.value;
        if i < 1 {
            return Err(deck
                .error(
                    DiagnosticKind::CoordinateOutOfRange,
                    c.index.span,
                    format!("co-ordinate number {i} is out of range"),
                )
                .with_hint("co-ordinates are numbered 1, 2, 3, ..."));
        }
        if let Some(first) = decl.get(&i) {
            let kw = |m: bool| if m { "XMOV" } else { "XFIX" };
            return Err(deck
                .error(
                    DiagnosticKind::CoordinateDeclaredTwice,
                    c.index.span,
                    format!(
                        "co-ordinate {i} is declared twice: {} here, {} at line {}",
                        kw(c.moving),
                        kw(first.moving),
                        first.line
                    ),
                )
                .with_hint("declare each co-ordinate once: XFIX if it is fixed, XMOV if it moves"));
        }
        decl.insert(i, c);
    }
    let mut used: BTreeMap<i64, ()> = BTreeMap::new();
    for e in &deck.topology.elements {
        for c in &e.coords {
            let i = c.value;
            if i < 1 {
                return Err(deck
                    .error(
                        DiagnosticKind::CoordinateOutOfRange,
                        c.span,
                        format!("co-ordinate number {i} is out of range"),
                    )
                    .with_hint("co-ordinates are numbered 1, 2, 3, ..."));
            }
            if !decl.contains_key(&i) {
                return Err(deck
                    .error(
                        DiagnosticKind::CoordinateNotDeclared,
                        c.span,
                        format!("co-ordinate {i} of element {} is never declared", e.number.value),
                    )
                    .with_hint(format!(
                        "give it a value in the GEOMETRY block: `XFIX {i} value` or `XMOV {i} value`"
                    )));
            }
            used.insert(i, ());
        }
    }
    let n = decl.keys().next_back().copied().unwrap_or(0);
    for (k, (&i, c)) in decl.iter().enumerate() {
        let expected = k as i64 + 1;
        if i != expected {
            return Err(deck
                .error(
                    DiagnosticKind::CoordinateMissing,
                    c.index.span,
                    format!(
                        "co-ordinate {expected} is missing: co-ordinates must be numbered 1..{n} with none missing"
                    ),
                )
                .with_hint(format!(
                    "declare co-ordinate {expected} with XFIX or XMOV, or renumber the co-ordinates from {i} on"
                )));
        }
        if !used.contains_key(&i) {
            return Err(deck
                .error(DiagnosticKind::CoordinateUnused, c.index.span, format!("co-ordinate {i} is used by no element"))
                .about_coordinate(usize::try_from(i).unwrap_or_default())
                .with_hint(format!(
                    "connect it to an element, or remove its {} line and renumber the co-ordinates above it",
                    if c.moving { "XMOV" } else { "XFIX" }
                )));
        }
    }
    Ok(decl)
}
