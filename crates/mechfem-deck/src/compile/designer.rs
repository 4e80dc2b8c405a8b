//! The designer's buffers of STORAGE: `BUFTRA e1 e2 b` (a transmission
//! angle), `BUFPIN e i j b` (the force an element exerts on a pin, x into b
//! and y into b+1) and `BUFSHAKE b` (shaking force x, y into b, b+1 and
//! moment into b+2). A keyword here may fill several consecutive buffers.

use mechfem_core::dynamics::{has_frame, Component};
use mechfem_core::{Quantity, Slot};

use super::refs::{coordinate, Sizes};
use crate::ast::{BufDef, Deck};
use crate::diagnostic::{count, numbered, Diagnostic, DiagnosticKind, Hint, Spanned, Subject};
use crate::keywords::Keyword;

/// The quantities of a designer's buffer keyword, one per buffer from its
/// number on; `None` for every other keyword.
pub(super) fn parts(deck: &Deck, sizes: &Sizes, def: &BufDef) -> Result<Option<Vec<Quantity>>, Box<Diagnostic>> {
    let kw = def.keyword.value;
    let arg = |k: usize| def.args.get(k);
    Ok(Some(match kw {
        Keyword::BufTra => {
            let (Some(a), Some(b)) = (arg(0), arg(1)) else { return Ok(None) };
            vec![Quantity::Transmission(framed(deck, kw, a)?, framed(deck, kw, b)?)]
        }
        Keyword::BufPin => {
            let (Some(e), Some(i), Some(j)) = (arg(0), arg(1), arg(2)) else { return Ok(None) };
            let element = element(deck, kw, e)?;
            let (x, y) = (coordinate(deck, sizes, kw, i)?, coordinate(deck, sizes, kw, j)?);
            pin_of(deck, kw, element, (i, x), (j, y))?;
            [Component::X, Component::Y].map(|component| Quantity::Pin { element, x, y, component }).to_vec()
        }
        Keyword::BufShake => [Component::X, Component::Y, Component::Moment].map(Quantity::Shaking).to_vec(),
        _ => return Ok(None),
    }))
}

/// An element number 1..n_e as a 0-based index.
fn element(deck: &Deck, kw: Keyword, e: &Spanned<i64>) -> Result<usize, Box<Diagnostic>> {
    let n_e = deck.topology.elements.len();
    match usize::try_from(e.value).ok().filter(|&k| (1..=n_e).contains(&k)) {
        Some(k) => Ok(k - 1),
        None => Err(deck
            .error(
                DiagnosticKind::UnknownElement,
                e.span,
                format!("{kw} names element {}, but the model has {}", e.value, count(n_e, "element", "elements")),
            )
            .with_hint(format!("elements are numbered {} by their ELEM lines", numbered(n_e, 1)))),
    }
}

/// An element with a first side (BIN, TR2: P->Q; HLF, TR1: the angle
/// co-ordinate's direction) as a 0-based index.
fn framed(deck: &Deck, kw: Keyword, e: &Spanned<i64>) -> Result<usize, Box<Diagnostic>> {
    let index = element(deck, kw, e)?;
    let ty = deck.topology.elements[index].ty.value;
    if has_frame(ty) {
        return Ok(index);
    }
    Err(deck
        .error(
            DiagnosticKind::NoFrame,
            e.span,
            format!(
                "{kw} names element {}, a {}, which has no side to measure a transmission angle on",
                e.value,
                ty.name()
            ),
        )
        .about_element(index)
        .with_hint(
            "a transmission angle is measured between the first sides of two BIN, TR2 (P->Q), HLF or TR1 (the \
             angle co-ordinate's direction) elements: name the coupler and the output link",
        ))
}

/// Checks that co-ordinates `x`, `y` (0-based, with the deck's numbers)
/// are the x and y of one point of element `element`.
fn pin_of(
    deck: &Deck,
    kw: Keyword,
    element: usize,
    (i, x): (&Spanned<i64>, usize),
    (_, y): (&Spanned<i64>, usize),
) -> Result<(), Box<Diagnostic>> {
    let e = &deck.topology.elements[element];
    let coords: Vec<usize> = e.coords.iter().map(|c| usize::try_from(c.value - 1).unwrap_or(usize::MAX)).collect();
    let mut points: Vec<(usize, usize)> = Vec::new();
    let mut at = 0;
    for slot in e.ty.value.slots() {
        if slot == Slot::Point {
            if let (Some(&a), Some(&b)) = (coords.get(at), coords.get(at + 1)) {
                points.push((a, b));
            }
            at += 2;
        } else {
            at += 1;
        }
    }
    if points.contains(&(x, y)) {
        return Ok(());
    }
    let listed: Vec<String> = points.iter().map(|(a, b)| format!("{} {}", a + 1, b + 1)).collect();
    Err(deck
        .error(
            DiagnosticKind::NotAPin,
            i.span,
            format!(
                "{kw} names co-ordinates {} {}, which are not a point of element {} ({})",
                x + 1,
                y + 1,
                element + 1,
                e.ty.value.name()
            ),
        )
        .about_element(element)
        .with_hint(format!(
            "a pin force acts where the element meets a pin: name one of its points by its x and y co-ordinates ({})",
            listed.join(" or ")
        )))
}

/// The number of part `k` of the buffer definition `def`: its number plus k.
pub(super) fn part_number(deck: &Deck, def: &BufDef, k: usize) -> Result<u32, Box<Diagnostic>> {
    let first = u32::try_from(def.number.value).unwrap_or(0);
    if let Some(n) = u32::try_from(k).ok().and_then(|k| first.checked_add(k)) {
        return Ok(n);
    }
    let kw = def.keyword.value;
    Err(deck
        .error(
            DiagnosticKind::BadValue,
            def.number.span,
            format!(
                "{kw} fills buffers {first} to {}, past the largest buffer number {}",
                u64::from(first) + k as u64,
                u32::MAX
            ),
        )
        .with_hint(format!("give {kw} a smaller buffer number")))
}

/// The error of a buffer number defined twice: by two lines, or by a
/// keyword that fills several buffers (part `k`) over one defined before.
pub(super) fn taken(deck: &Deck, def: &BufDef, k: usize, number: u32, first: usize) -> Box<Diagnostic> {
    let kw = def.keyword.value;
    let (message, hint) = if k == 0 {
        (
            format!("buffer {number} is already defined at line {first}"),
            "give every BUF... keyword its own buffer number".to_string(),
        )
    } else {
        let b = def.number.value;
        let last = match kw {
            Keyword::BufShake => "b, b+1 and b+2 (force x, y and moment)",
            _ => "b and b+1 (x and y)",
        };
        (
            format!("{kw} {b} also fills buffer {number}, which is already defined at line {first}"),
            format!("{kw} fills the buffers {last}: give it a number whose next ones are free"),
        )
    };
    deck.error(DiagnosticKind::DuplicateBuffer, def.number.span, message).with_hint(hint)
}
