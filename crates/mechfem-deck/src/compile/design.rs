//! VARY and VARYX to design variables: only a number the deck prescribes
//! (a row's PARA, a fixed co-ordinate's XFIX) can be one, each once, and it
//! starts inside its range.

use mechfem_core::{DesignVar, InputMotion, Motion};

use super::model::Model;
use super::refs::{coordinate, Sizes};
use crate::ast::{Deck, VaryDef};
use crate::compiled::TermInfo;
use crate::diagnostic::{count, real, Diagnostic, DiagnosticKind, Hint};
use crate::keywords::Keyword;
use crate::optimise::Vary;

/// The design variables of the OPTIMISE block, in deck order.
pub(crate) fn design_variables(
    deck: &Deck,
    model: &Model,
    sizes: &Sizes,
    motion: Option<&Motion>,
    defs: &[VaryDef],
) -> Result<Vec<Vary>, Box<Diagnostic>> {
    let mut out: Vec<Vary> = Vec::with_capacity(defs.len());
    for def in defs {
        let (var, start, what) = if def.keyword.value == Keyword::Vary {
            let (r, start) = row(deck, model, motion, def)?;
            (DesignVar::Row(r), start, format!("row {}", r + 1))
        } else {
            let i = fixed(deck, model, sizes, def)?;
            (DesignVar::Fixed(i), model.state.x[i], format!("co-ordinate {}", i + 1))
        };
        if let Some(first) = out.iter().find(|v| v.var == var) {
            return Err(deck
                .error(
                    DiagnosticKind::DesignVariable,
                    def.index.span,
                    format!("{what} is varied twice (first at line {})", first.line),
                )
                .with_hint(format!("keep one {} line per {}", def.keyword.value, what_kind(def.keyword.value))));
        }
        if !(def.lo.value..=def.hi.value).contains(&start) {
            let source = if def.keyword.value == Keyword::Vary { "PARA" } else { "XFIX" };
            // The numbers as the deck writes them, in its UNITS.
            let dim = match (var, &deck.scale) {
                (_, None) => mechfem_core::Dim::NONE,
                (DesignVar::Row(r), Some(s)) => s.dims.form(mechfem_core::FormRef::Prescribed(r)),
                (DesignVar::Fixed(i), Some(s)) => s.dims.coord(i),
            };
            let [start, lo, hi] = [start, def.lo.value, def.hi.value].map(|v| deck.as_written(dim, v));
            return Err(deck
                .error(
                    DiagnosticKind::DesignVariable,
                    def.lo.span.to(def.hi.span),
                    format!(
                        "{what} starts at {} (its {source}), outside its range [{}, {}]",
                        real(start),
                        real(lo),
                        real(hi)
                    ),
                )
                .with_hint(format!(
                    "the design starts as the deck gives it: widen the range to hold {}, or change the {source} value",
                    real(start)
                )));
        }
        out.push(Vary { var, lo: def.lo.value, hi: def.hi.value, line: def.line });
    }
    Ok(out)
}

fn what_kind(kw: Keyword) -> &'static str {
    if kw == Keyword::Vary {
        "row"
    } else {
        "co-ordinate"
    }
}

/// `VARY r`: a prescribed row with a PARA value, not fed by a MOV_FUNC
/// table; its 0-based index and start value.
fn row(deck: &Deck, model: &Model, motion: Option<&Motion>, def: &VaryDef) -> Result<(usize, f64), Box<Diagnostic>> {
    let r = def.index.value;
    let rows = &model.prescribed;
    let with_para: Vec<String> =
        rows.iter().enumerate().filter(|(_, row)| row.para.is_some()).map(|(k, _)| (k + 1).to_string()).collect();
    let choose = if with_para.is_empty() {
        "; no row of this deck has one: give a row its value with `PARA row value` in GEOMETRY".to_string()
    } else {
        format!(" (the rows with PARA: {})", list(&with_para))
    };
    let Some(info) = usize::try_from(r - 1).ok().and_then(|k| rows.get(k)) else {
        let message = match r {
            0 => "VARY names row 0, which is no form parameter".to_string(),
            r if r < 0 => format!(
                "VARY names dependent form parameter {r}, an output: only a prescribed row's value is a design \
                 variable"
            ),
            r => format!(
                "VARY names prescribed row {r}, but the model has {}",
                count(rows.len(), "prescribed row", "prescribed rows")
            ),
        };
        return Err(deck
            .error(DiagnosticKind::UnknownRow, def.index.span, message)
            .with_hint(format!("VARY takes a prescribed row that has a PARA value{choose}")));
    };
    let k = usize::try_from(r - 1).unwrap_or(0);
    if let Some(j) = info.input {
        let table = motion
            .and_then(|m| m.inputs.get(j.checked_sub(1)?))
            .is_some_and(|i| matches!(i, InputMotion::Table { .. }));
        if table {
            return Err(deck
                .error(
                    DiagnosticKind::DesignVariable,
                    def.index.span,
                    format!(
                        "row {r} is the input of DOF {j}, which MOV_FUNC reads from a table: the table fixes the \
                         input at every position"
                    ),
                )
                .with_hint(
                    "only the start of an input moved by MOV_RELE or MOV_ABSE is a design variable; to change where \
                     a MOV_FUNC input starts, change its table",
                ));
        }
    }
    let Some(start) = info.para else {
        let input = info.input.map_or(String::new(), |j| format!(" (the input of DOF {j})"));
        return Err(deck
            .error(
                DiagnosticKind::DesignVariable,
                def.index.span,
                format!("row {r}{input} has no PARA value, so it is not a design variable"),
            )
            .with_hint(format!(
                "a row without PARA takes whatever value the co-ordinates give it; add `PARA {r} value` to GEOMETRY to \
                 prescribe it and start the design there"
            )));
    };
    Ok((k, start))
}

/// `VARYX i`: a fixed co-ordinate; its 0-based index.
fn fixed(deck: &Deck, model: &Model, sizes: &Sizes, def: &VaryDef) -> Result<usize, Box<Diagnostic>> {
    let i = coordinate(deck, sizes, Keyword::VaryX, &def.index)?;
    if !sizes.moving[i] {
        return Ok(i);
    }
    // The rows whose elements hold the co-ordinate are the ones that place it.
    let involved: Vec<String> = model
        .prescribed
        .iter()
        .enumerate()
        .filter(|(_, row)| {
            let holds = |t: &TermInfo| t.element.checked_sub(1).and_then(|k| model.elements.get(k));
            row.terms.iter().any(|t| holds(t).is_some_and(|e| e.coords.contains(&(i + 1))))
        })
        .map(|(k, _)| (k + 1).to_string())
        .collect();
    let rows = if involved.is_empty() {
        String::new()
    } else {
        format!(" (the prescribed rows whose elements hold it: {})", list(&involved))
    };
    Err(deck
        .error(
            DiagnosticKind::NotFixed,
            def.index.span,
            format!("VARYX names co-ordinate {}, which moves (XMOV): the prescribed rows place it", i + 1),
        )
        .with_hint(format!(
            "VARYX takes a fixed co-ordinate (XFIX), such as a frame pivot; to move co-ordinate {}, VARY a row that \
             prescribes its place{rows}",
            i + 1
        )))
}

/// Up to 12 numbers, "1, 2, 3"; more end in ", ...".
fn list(numbers: &[String]) -> String {
    let more = if numbers.len() > 12 { ", ..." } else { "" };
    format!("{}{more}", numbers[..numbers.len().min(12)].join(", "))
}
