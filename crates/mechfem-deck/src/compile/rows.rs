//! Form parameters: FORM lines resolved and grouped into prescribed rows and
//! dependent form parameters; NRDOF, the squareness of D^c, PARA.

use std::collections::BTreeMap;

use mechfem_core::{ElementType, FormEval, Order};

use super::index;
use crate::ast::{CoordDef, Deck, FormDef};
use crate::diagnostic::{count, Diagnostic, DiagnosticKind, Hint, Span};

/// A form parameter resolved to the core's indices.
pub(crate) struct Resolved<'a> {
    pub def: &'a FormDef,
    pub element: usize,
    pub ty: ElementType,
    pub form: usize,
}

/// Resolves every FORM line to an element index and form-parameter index.
pub(crate) fn resolve_forms(deck: &Deck) -> Result<Vec<Resolved<'_>>, Box<Diagnostic>> {
    let elements = &deck.topology.elements;
    let n_e = elements.len();
    deck.topology
        .forms
        .iter()
        .map(|def| {
            let k = def.element.value;
            let e = usize::try_from(k - 1).ok().and_then(|i| elements.get(i)).ok_or_else(|| {
                deck.error(
                    DiagnosticKind::UnknownElement,
                    def.element.span,
                    format!("FORM refers to element {k}, but the model has {}", count(n_e, "element", "elements")),
                )
                .with_hint(format!("elements are numbered {} by their ELEM lines", crate::diagnostic::numbered(n_e, 1)))
            })?;
            let ty = e.ty.value;
            let form = ty.form_index(&def.name.value).ok_or_else(|| {
                deck.error(
                    DiagnosticKind::UnknownFormName,
                    def.name.span,
                    format!("element {k} is of type {}, which has no form parameter `{}`", ty.name(), def.name.value),
                )
                .with_hint(format!(
                    "the form parameters of {} are {}",
                    ty.name(),
                    ty.form_names().join(", ")
                ))
            })?;
            Ok(Resolved { def, element: index(k), ty, form })
        })
        .collect()
}

/// Groups the form parameters with destinations of the given sign into rows
/// 1..n, checking that none is missing.
pub(crate) fn rows<'a, 'b>(
    deck: &Deck,
    forms: &'b [Resolved<'a>],
    sign: i64,
) -> Result<Vec<Vec<&'b Resolved<'a>>>, Box<Diagnostic>> {
    let mut by_dest: BTreeMap<i64, Vec<&Resolved>> = BTreeMap::new();
    for f in forms.iter().filter(|f| f.def.dest.value.signum() == sign) {
        by_dest.entry(f.def.dest.value * sign).or_default().push(f);
    }
    for (k, (&r, row)) in by_dest.iter().enumerate() {
        let expected = k as i64 + 1;
        if r != expected {
            let first = row.first().map_or(Span::default(), |f| f.def.dest.span);
            let (kind, message, hint) = if sign > 0 {
                (
                    DiagnosticKind::RowGap,
                    format!("prescribed row {expected} is missing: rows must be 1..n_p with none missing"),
                    format!("add a FORM with destination {expected}, or renumber the destinations from {r} on"),
                )
            } else {
                (
                    DiagnosticKind::DependentGap,
                    format!("dependent form parameter -{expected} is missing: they must be -1..-n_d with none missing"),
                    format!("add a FORM with destination -{expected}, or renumber the destinations from -{r} on"),
                )
            };
            return Err(deck.error(kind, first, message).with_hint(hint));
        }
    }
    Ok(by_dest.into_values().collect())
}

pub(crate) fn degrees_of_freedom(deck: &Deck, n_p: usize) -> Result<usize, Box<Diagnostic>> {
    let topo = &deck.topology;
    let Some(n) = &topo.nrdof else {
        let width = deck.line_text(topo.line).trim_end().chars().count();
        return Err(deck
            .error(DiagnosticKind::MissingNrdof, Span::new(topo.line, 0, width), "the TOPOLOGY block has no NRDOF")
            .with_hint(
                "add `NRDOF n` with the number of degrees of freedom; the last n prescribed rows are the inputs",
            ));
    };
    let n_dof = usize::try_from(n.value).unwrap_or(usize::MAX);
    if n_dof > n_p {
        return Err(deck
            .error(
                DiagnosticKind::NrdofTooLarge,
                n.span,
                format!("NRDOF {} is larger than the number of prescribed rows ({n_p})", n.value),
            )
            .with_hint(
                "the inputs are the last NRDOF prescribed rows: add FORM lines with destinations > 0, or lower NRDOF",
            ));
    }
    Ok(n_dof)
}

/// D^c must be square: as many prescribed rows as moving co-ordinates.
pub(crate) fn check_square(
    deck: &Deck,
    coords_by_number: &BTreeMap<i64, &CoordDef>,
    prescribed: &[Vec<&Resolved>],
) -> Result<(), Box<Diagnostic>> {
    let n_p = prescribed.len();
    let n_m = coords_by_number.values().filter(|c| c.moving).count();
    if n_p == n_m {
        return Ok(());
    }
    let (k, which) = if n_p > n_m { (n_p - n_m, "too many") } else { (n_m - n_p, "too few") };
    let message =
        format!("{} for {n_m} moving co-ordinates: {k} {which}", count(n_p, "prescribed row", "prescribed rows"));
    let rows = |k: usize| count(k, "prescribed form parameter", "prescribed form parameters");
    let coords = |k: usize| count(k, "co-ordinate", "co-ordinates");
    let hint = if n_p > n_m {
        let more = if k == 1 { "co-ordinate" } else { "co-ordinates" };
        format!("remove {}, or make {k} more {more} moving (XMOV)", rows(k))
    } else {
        let free = unconstrained(deck, coords_by_number, prescribed);
        let fix = format!("add {} (FORM with a destination > 0), or fix {} (XFIX)", rows(k), coords(k));
        if free.is_empty() {
            fix
        } else {
            let list: Vec<String> = free.iter().map(i64::to_string).collect();
            let which = if free.len() == 1 { "co-ordinate" } else { "co-ordinates" };
            format!(
                "no prescribed form parameter involves the moving {which} {}, which may be unconstrained; {fix}",
                list.join(", ")
            )
        }
    };
    let span = prescribed.last().and_then(|row| row.last()).map_or_else(
        || Span::new(deck.topology.line, 0, deck.line_text(deck.topology.line).trim_end().chars().count()),
        |f| f.def.dest.span,
    );
    Err(deck.error(DiagnosticKind::NotSquare, span, message).with_hint(hint))
}

/// The moving co-ordinates that no prescribed form parameter depends on.
/// Dependence is read from the first derivatives at the initial co-ordinates
/// and at a perturbed copy of them, so that a derivative that happens to be
/// zero in one configuration does not hide it.
fn unconstrained(deck: &Deck, coords: &BTreeMap<i64, &CoordDef>, prescribed: &[Vec<&Resolved>]) -> Vec<i64> {
    let x: Vec<f64> = coords.values().map(|c| c.value.value).collect();
    let shaken: Vec<f64> = x.iter().enumerate().map(|(i, v)| v + 0.37 * (1.7 * i as f64 + 0.3).sin()).collect();
    let mut involved = vec![false; x.len()];
    for t in prescribed.iter().flatten() {
        let Some(e) = deck.topology.elements.get(t.element) else { continue };
        let idx: Vec<usize> = e.coords.iter().map(|c| index(c.value)).collect();
        for config in [&x, &shaken] {
            let xe: Vec<f64> = idx.iter().map(|&i| config.get(i).copied().unwrap_or(0.0)).collect();
            let mut out = FormEval::default();
            let mut branch = f64::NAN;
            if t.ty.eval(t.form, &xe, &mut branch, Order::First, &mut out).is_err() {
                continue;
            }
            for (k, &i) in idx.iter().enumerate() {
                if out.grad.get(k).is_some_and(|g| *g != 0.0) {
                    if let Some(flag) = involved.get_mut(i) {
                        *flag = true;
                    }
                }
            }
        }
    }
    coords
        .iter()
        .filter(|(&i, c)| c.moving && !involved.get(index(i)).copied().unwrap_or(true))
        .map(|(&i, _)| i)
        .collect()
}

/// PARA values by prescribed row (0-based).
pub(crate) fn paras(deck: &Deck, n_p: usize) -> Result<Vec<Option<f64>>, Box<Diagnostic>> {
    let mut values: Vec<Option<f64>> = vec![None; n_p];
    let mut lines = vec![0; n_p];
    for p in &deck.geometry.paras {
        let r = p.row.value;
        let slot = usize::try_from(r - 1).ok().filter(|&k| k < n_p);
        let Some(k) = slot else {
            let message = if r < 1 {
                format!("PARA for row {r}: only prescribed rows (1..{n_p}) can be given a value")
            } else {
                format!("PARA for row {r}, but there are only {n_p} prescribed rows")
            };
            return Err(deck
                .error(DiagnosticKind::UnknownRow, p.row.span, message)
                .with_hint(format!("PARA takes a prescribed row 1..{n_p}, the destination of a FORM line")));
        };
        if values[k].is_some() {
            return Err(deck
                .error(
                    DiagnosticKind::DuplicatePara,
                    p.row.span,
                    format!("row {r} is given a value twice (first PARA at line {})", lines[k]),
                )
                .with_hint("keep one PARA line per row"));
        }
        values[k] = Some(p.value.value);
        lines[k] = p.line;
    }
    Ok(values)
}
