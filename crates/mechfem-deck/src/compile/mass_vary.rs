//! VARYM to design variables of the mass model: only a number a DYNAMICS
//! line gives (a MASS line's m, u, v or J, a PMASS's m, an INERTIA's J)
//! can be one, in a `DYN ANA` deck, each once, starting inside its range;
//! a mass or moment of inertia stays 0 or positive over its range.

use mechfem_core::dynamics::{Dynamics, MassVar};
use mechfem_core::Dim;

use crate::ast::{Deck, MassVaryDef};
use crate::diagnostic::{real, Diagnostic, DiagnosticKind, Hint};
use crate::optimise::{MassItem, MassVary};

/// The mass variables of the OPTIMISE block, in deck order.
pub(crate) fn mass_variables(
    deck: &Deck,
    dynamics: Option<&Dynamics>,
    defs: &[MassVaryDef],
) -> Result<Vec<MassVary>, Box<Diagnostic>> {
    let (Some(_), Some(model)) = (defs.first(), dynamics) else {
        return match defs.first() {
            Some(first) => Err(deck
                .error(
                    DiagnosticKind::WrongMode,
                    first.keyword.span,
                    format!("VARYM varies the mass model, which a {} deck does not have", deck.mode.value.name()),
                )
                .with_hint(
                    "VARYM belongs to a DYN ANA deck, whose DYNAMICS block gives the masses it varies: change the \
                     mode line to `DYN ANA` and add the DYNAMICS block, or vary dimensions with VARY and VARYX",
                )),
            None => Ok(Vec::new()),
        };
    };
    let mut out: Vec<MassVary> = Vec::with_capacity(defs.len());
    for def in defs {
        let item = def.what.value;
        let var = variable(deck, model, def)?;
        let what = described(item, def.index.value);
        if let Some(first) = out.iter().find(|v| v.var == var) {
            return Err(deck
                .error(
                    DiagnosticKind::DesignVariable,
                    def.index.span,
                    format!("{what} is varied twice (first at line {})", first.line),
                )
                .with_hint("keep one VARYM line for each number of the DYNAMICS block"));
        }
        let coord =
            deck.scale.as_ref().map_or(Dim::NONE, |s| s.dims.coord(usize::try_from(def.index.value - 1).unwrap_or(0)));
        let dim = item.dim(coord);
        let written = |v: f64| real(deck.as_written(dim, v));
        if item.is_mass() && def.lo.value < 0.0 {
            return Err(deck
                .error(
                    DiagnosticKind::DesignVariable,
                    def.lo.span,
                    format!("{what} may become negative: its range starts at {}", written(def.lo.value)),
                )
                .with_hint(
                    "a mass or moment of inertia is 0 or positive: give the range's lower end lo at 0 or above \
                     (0 lets the optimiser remove the counterweight)",
                ));
        }
        let start = var.value(model);
        if !(def.lo.value..=def.hi.value).contains(&start) {
            return Err(deck
                .error(
                    DiagnosticKind::DesignVariable,
                    def.lo.span.to(def.hi.span),
                    format!(
                        "{what} starts at {} (its DYNAMICS line), outside its range [{}, {}]",
                        written(start),
                        written(def.lo.value),
                        written(def.hi.value)
                    ),
                )
                .with_hint(
                    "the design the deck describes is where the optimisation starts: widen the range to hold the \
                     value of the DYNAMICS line, or change that value",
                ));
        }
        let number = usize::try_from(def.index.value).unwrap_or(0);
        out.push(MassVary { item, number, var, lo: def.lo.value, hi: def.hi.value, line: def.line });
    }
    Ok(out)
}

/// The variable a VARYM line names, or why there is none.
fn variable(deck: &Deck, model: &Dynamics, def: &MassVaryDef) -> Result<MassVar, Box<Diagnostic>> {
    let item = def.what.value;
    let n = def.index.value;
    let found = usize::try_from(n).ok().and_then(|k| item.var(model, k));
    if let Some(var) = found {
        return Ok(var);
    }
    let (line, given) = match item {
        MassItem::PointMass => ("PMASS", model.point_masses.iter().map(|p| p.x + 1).collect::<Vec<_>>()),
        MassItem::Inertia => ("INERTIA", model.inertias.iter().map(|i| i.coord + 1).collect()),
        _ => ("MASS", model.bodies.iter().map(|b| b.element + 1).collect()),
    };
    let on = if item.of_element() { "element" } else { "co-ordinate" };
    let list = if given.is_empty() {
        format!("the DYNAMICS block has no {line} line")
    } else {
        let names: Vec<String> = given.iter().map(usize::to_string).collect();
        format!("the DYNAMICS block has {line} lines on {on} {}", names.join(", "))
    };
    let what = match item {
        MassItem::PointMass => format!("a PMASS at the point whose x is co-ordinate {n}"),
        MassItem::Inertia => format!("an INERTIA on co-ordinate {n}"),
        _ => format!("a MASS line on element {n}"),
    };
    Err(deck
        .error(
            DiagnosticKind::DesignVariable,
            def.index.span,
            format!("VARYM {} needs {what}: there is none", item.name()),
        )
        .with_hint(format!(
            "{list}: name one of them, or add the {line} line to the DYNAMICS block with the start value (a \
             counterweight that may vanish starts at a mass of 0 or more)"
        )))
}

/// The number a VARYM line varies, in words.
fn described(item: MassItem, n: i64) -> String {
    match item {
        MassItem::Mass => format!("the mass of element {n}"),
        MassItem::U => format!("the centre of mass (u) of element {n}"),
        MassItem::V => format!("the centre of mass (v) of element {n}"),
        MassItem::J => format!("the moment of inertia of element {n}"),
        MassItem::PointMass => format!("the point mass at co-ordinate {n}"),
        MassItem::Inertia => format!("the INERTIA on co-ordinate {n}"),
    }
}
