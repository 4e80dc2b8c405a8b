//! TOPOLOGY and GEOMETRY to a core [`Mechanism`] and its initial [`State`].

use mechfem_core::{ElementError, Mechanism, MechanismBuilder, ModelError, State, Term};

use super::coordinates::coordinates;
use super::index;
use super::rows::{check_square, degrees_of_freedom, paras, resolve_forms, rows, Resolved};
use crate::ast::Deck;
use crate::compiled::{ElementInfo, RowInfo, TermInfo};
use crate::diagnostic::{Diagnostic, DiagnosticKind, Hint, Span, Subject};

/// The compiled model and its description for the print file.
pub(crate) struct Model {
    pub mechanism: Mechanism,
    pub state: State,
    pub elements: Vec<ElementInfo>,
    pub prescribed: Vec<RowInfo>,
    pub dependent: Vec<RowInfo>,
}

pub(crate) fn model(deck: &Deck) -> Result<Model, Box<Diagnostic>> {
    let coords = coordinates(deck)?;
    let forms = resolve_forms(deck)?;
    let prescribed = rows(deck, &forms, 1)?;
    let dependent = rows(deck, &forms, -1)?;
    let n_p = prescribed.len();
    let n_dof = degrees_of_freedom(deck, n_p)?;
    check_square(deck, &coords, &prescribed)?;
    let paras = paras(deck, n_p)?;
    check_lengths(deck, &prescribed[..n_p - n_dof])?;

    let mut b = MechanismBuilder::new();
    for c in coords.values() {
        b.coord(c.value.value, c.moving);
    }
    for e in &deck.topology.elements {
        let idx: Vec<usize> = e.coords.iter().map(|c| index(c.value)).collect();
        b.element(e.ty.value, &idx);
    }
    let terms = |row: &[&Resolved]| -> Vec<Term> {
        row.iter().map(|t| Term::scaled(t.element, t.form, t.def.factor())).collect()
    };
    for (r, row) in prescribed.iter().enumerate() {
        if r < n_p - n_dof {
            b.prescribe(&terms(row));
        } else {
            b.input(&terms(row));
        }
    }
    for row in &dependent {
        b.dependent(&terms(row));
    }
    let (mechanism, mut state) = b.build().map_err(|e| model_error(deck, e))?;
    state.set_given(&paras);

    let elements = deck
        .topology
        .elements
        .iter()
        .map(|e| ElementInfo {
            number: index(e.number.value) + 1,
            ty: e.ty.value,
            coords: e.coords.iter().map(|c| index(c.value) + 1).collect(),
            line: e.line,
        })
        .collect();
    let info = |rows: &[Vec<&Resolved>], sign: i64| -> Vec<RowInfo> {
        rows.iter()
            .enumerate()
            .map(|(k, row)| {
                let input = (sign > 0 && k >= n_p - n_dof).then(|| k + n_dof + 1 - n_p);
                RowInfo {
                    dest: sign * (k as i64 + 1),
                    terms: row
                        .iter()
                        .map(|t| TermInfo {
                            seq: t.def.seq.value,
                            element: t.element + 1,
                            name: t.ty.form_names().get(t.form).copied().unwrap_or("?"),
                            factor: t.def.factor(),
                            line: t.def.line,
                        })
                        .collect(),
                    para: if sign > 0 { paras.get(k).copied().flatten() } else { None },
                    input,
                }
            })
            .collect()
    };
    Ok(Model { mechanism, state, elements, prescribed: info(&prescribed, 1), dependent: info(&dependent, -1) })
}

/// A constant row that is one length alone (LENL, a distance between two
/// points) must be given a value above zero: at zero the points coincide
/// and the element's direction is undefined, below zero no position fits.
/// Newton iteration would only fail to converge, so say it here. Input rows
/// may pass through zero on purpose; the run then stops where they do.
fn check_lengths(deck: &Deck, constant: &[Vec<&Resolved>]) -> Result<(), Box<Diagnostic>> {
    for p in &deck.geometry.paras {
        let Some(row) = usize::try_from(p.row.value - 1).ok().and_then(|k| constant.get(k)) else { continue };
        let [t] = row.as_slice() else { continue };
        let form = t.ty.form_names().get(t.form).copied().unwrap_or("?");
        let length = p.value.value / t.def.factor();
        if form == "LENL" && (length.is_nan() || length <= 0.0) {
            return Err(deck
                .error(
                    DiagnosticKind::BadValue,
                    p.value.span,
                    format!(
                        "row {} prescribes the length LENL of element {} ({}) as {length}, but a length must be \
                         greater than zero",
                        p.row.value,
                        t.element + 1,
                        t.ty.name(),
                        length = deck.as_written(mechfem_core::Dim::LENGTH, length)
                    ),
                )
                .about_element(t.element)
                .with_hint("give the distance between the element's two points, a positive number; points that coincide have no direction"));
        }
    }
    Ok(())
}

/// `e` with its lengths as the deck writes them.
fn written_element_error(deck: &Deck, e: &ElementError) -> ElementError {
    match *e {
        ElementError::NoBeltSpan { l, d } => ElementError::NoBeltSpan {
            l: deck.as_written(mechfem_core::Dim::LENGTH, l),
            d: deck.as_written(mechfem_core::Dim::LENGTH, d),
        },
        other => other,
    }
}

/// Points a refusal of the core at the deck line that caused it.
fn model_error(deck: &Deck, e: ModelError) -> Box<Diagnostic> {
    if let ModelError::Element { element, source } = &e {
        if let Some(def) = deck.topology.elements.get(*element) {
            let span = match (def.coords.first(), def.coords.last()) {
                (Some(a), Some(b)) => a.span.to(b.span),
                _ => def.ty.span,
            };
            let list: Vec<String> = def.coords.iter().map(|c| c.value.to_string()).collect();
            let hint = match source {
                ElementError::CoincidentPoints => format!(
                    "change the initial values of its co-ordinates ({}) in GEOMETRY so that P and Q lie apart",
                    list.join(" ")
                ),
                ElementError::NoBeltSpan { .. } => "move the wheel centres further apart in GEOMETRY".to_string(),
                _ => format!("check the initial values of its co-ordinates ({}) in GEOMETRY", list.join(" ")),
            };
            return deck
                .error(
                    DiagnosticKind::Model,
                    span,
                    format!(
                        "element {} ({}) cannot be evaluated at the initial co-ordinates: {}",
                        element + 1,
                        def.ty.value.name(),
                        written_element_error(deck, source)
                    ),
                )
                .about_element(*element)
                .with_detail(*source)
                .with_hint(hint);
        }
    }
    let line = deck.topology.line;
    deck.error(
        DiagnosticKind::Model,
        Span::new(line, 0, deck.line_text(line).trim_end().chars().count()),
        format!("the model is refused: {e}"),
    )
}
