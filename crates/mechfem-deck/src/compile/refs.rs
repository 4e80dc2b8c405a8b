//! References by number from deck lines to the model: co-ordinates, DOFs,
//! form parameters, each checked against the model's sizes.

use mechfem_core::{FormRef, Mechanism};

use crate::ast::Deck;
use crate::diagnostic::{count, dof_hint, numbered, Diagnostic, DiagnosticKind, Hint, Spanned};
use crate::keywords::Keyword;

/// The sizes of the model that references are checked against.
pub(crate) struct Sizes {
    pub n_coords: usize,
    pub n_prescribed: usize,
    pub n_dependent: usize,
    pub n_dof: usize,
    /// Per co-ordinate (0-based): whether it moves.
    pub moving: Vec<bool>,
}

impl Sizes {
    pub fn of(mech: &Mechanism) -> Sizes {
        Sizes {
            n_coords: mech.n_coords(),
            n_prescribed: mech.n_prescribed(),
            n_dependent: mech.n_dependent(),
            n_dof: mech.n_dof(),
            moving: (0..mech.n_coords()).map(|i| mech.is_moving(i)).collect(),
        }
    }
}

/// A co-ordinate number 1..N as a 0-based index.
pub(crate) fn coordinate(deck: &Deck, sizes: &Sizes, kw: Keyword, i: &Spanned<i64>) -> Result<usize, Box<Diagnostic>> {
    let n = sizes.n_coords;
    match usize::try_from(i.value).ok().filter(|&v| (1..=n).contains(&v)) {
        Some(v) => Ok(v - 1),
        None => Err(deck
            .error(
                DiagnosticKind::CoordinateOutOfRange,
                i.span,
                format!(
                    "{kw} names co-ordinate {}, but the model has {}",
                    i.value,
                    count(n, "co-ordinate", "co-ordinates")
                ),
            )
            .with_hint(format!("co-ordinates are numbered {}", numbered(n, 1)))),
    }
}

/// A DOF number 1..NRDOF as a 0-based index.
pub(crate) fn dof(deck: &Deck, sizes: &Sizes, kw: Keyword, j: &Spanned<i64>) -> Result<usize, Box<Diagnostic>> {
    let n = sizes.n_dof;
    match usize::try_from(j.value).ok().filter(|&v| (1..=n).contains(&v)) {
        Some(v) => Ok(v - 1),
        None => Err(deck
            .error(DiagnosticKind::UnknownDof, j.span, format!("{kw} names DOF {}, but NRDOF is {n}", j.value))
            .with_hint(dof_hint(n))),
    }
}

/// A destination: `r > 0` a prescribed row, `-k` a dependent form parameter.
pub(crate) fn form(deck: &Deck, sizes: &Sizes, kw: Keyword, r: &Spanned<i64>) -> Result<FormRef, Box<Diagnostic>> {
    let (n_p, n_d) = (sizes.n_prescribed, sizes.n_dependent);
    let k = usize::try_from(r.value.unsigned_abs()).unwrap_or(usize::MAX);
    let rows = count(n_p, "prescribed row", "prescribed rows");
    let dependents = count(n_d, "dependent form parameter", "dependent form parameters");
    let (ok, message) = if r.value > 0 {
        (k <= n_p, format!("{kw} names prescribed row {}, but the model has {rows}", r.value))
    } else if r.value < 0 {
        (k <= n_d, format!("{kw} names dependent form parameter {}, but the model has {dependents}", r.value))
    } else {
        (false, format!("{kw} names destination 0, which is no form parameter"))
    };
    if !ok {
        let hint = if n_d == 0 {
            format!("name a prescribed row ({})", numbered(n_p, 1))
        } else {
            format!(
                "name a prescribed row ({}) or a dependent form parameter ({})",
                numbered(n_p, 1),
                numbered(n_d, -1)
            )
        };
        return Err(deck.error(DiagnosticKind::UnknownRow, r.span, message).with_hint(hint));
    }
    Ok(if r.value > 0 { FormRef::Prescribed(k - 1) } else { FormRef::Dependent(k - 1) })
}
