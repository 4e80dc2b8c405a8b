//! TOLERANCE to a [`Tolerance`]: each toleranced dimension a number the deck
//! prescribes (a row's PARA, a fixed co-ordinate's XFIX), once; each band
//! of a buffer with exact design sensitivities, numbered clear of every
//! other buffer.

use mechfem_core::{DesignVar, Motion};

use super::model::Model;
use super::refs::{coordinate, Sizes};
use super::storage::{by_number, defined_buffer};
use crate::ast::{Deck, TolDef};
use crate::compiled::Buffer;
use crate::diagnostic::{count, Diagnostic, DiagnosticKind, Hint, Span};
use crate::keywords::Keyword;
use crate::tolerance::{without_sensitivity, BandDef, Tolerance, Toleranced};

/// The buffers whose bands can be recorded, in words.
const WITH_SENSITIVITY: &str = "BUFINP, BUFX0, BUFKX1, BUFKX2, BUFVX, BUFAX, BUFE0, BUFKE1, BUFKE2, BUFVE, BUFAE, BUFTRA or, \
                                 in DYN ANA, BUFDRV, BUFSIG, BUFREA, BUFPIN, BUFSHAKE, BUFEKIN, BUFEPOT, BUFPOW or BUFMRED";

/// The TOLERANCE block of `deck` (`None` without one).
pub(crate) fn tolerance(
    deck: &Deck,
    model: &Model,
    sizes: &Sizes,
    motion: Option<&Motion>,
    buffers: &[Buffer],
) -> Result<Option<Tolerance>, Box<Diagnostic>> {
    let Some(block) = &deck.tolerance else { return Ok(None) };
    let header = Span::new(block.line, 0, deck.line_text(block.line).trim_end().chars().count());
    if block.dims.is_empty() {
        return Err(deck
            .error(DiagnosticKind::Tolerance, header, "the TOLERANCE block has no toleranced dimension")
            .with_hint(
                "add `TOL r t` for the PARA value of prescribed row r (a length, an angle, a local u or v) known to \
                 +-t, or `TOLX i t` for fixed co-ordinate i (a frame pivot)",
            ));
    }
    if block.bands.is_empty() {
        return Err(deck
            .error(DiagnosticKind::Tolerance, header, "the TOLERANCE block records no band: it has no BUFTOL line")
            .with_hint(
                "add `BUFTOL bsrc b` to record the band of buffer bsrc: the worst case into buffer b and the root sum \
                 of squares into b + 1",
            ));
    }
    if motion.is_none() {
        return Err(deck
            .error(DiagnosticKind::Tolerance, header, "the TOLERANCE block needs a motion: this deck has no MOVEMENT")
            .with_hint(
                "add a MOVEMENT block (`TSTEPE n` and a motion of every DOF): the bands are computed at every \
                 position of the motion",
            ));
    }
    let mut dims: Vec<Toleranced> = Vec::with_capacity(block.dims.len());
    for def in &block.dims {
        let (var, what) = if def.keyword.value == Keyword::Tol {
            let r = row(deck, model, def)?;
            (DesignVar::Row(r), format!("row {}", r + 1))
        } else {
            let i = fixed(deck, sizes, def)?;
            (DesignVar::Fixed(i), format!("co-ordinate {}", i + 1))
        };
        if let Some(first) = dims.iter().find(|d| d.var == var) {
            return Err(deck
                .error(
                    DiagnosticKind::DesignVariable,
                    def.index.span,
                    format!("{what} is given a tolerance twice (first at line {})", first.line),
                )
                .with_hint(format!("keep one {} line for {what}", def.keyword.value)));
        }
        dims.push(Toleranced { var, t: def.t.value, line: def.line });
    }
    let defined = by_number(buffers);
    let mut bands: Vec<BandDef> = Vec::with_capacity(block.bands.len());
    for def in &block.bands {
        let source = defined_buffer(deck, &defined, &def.source)?;
        if let Some(what) = without_sensitivity(source.quantity) {
            return Err(deck
                .error(
                    DiagnosticKind::NoSensitivity,
                    def.source.span,
                    format!(
                        "BUFTOL names buffer {}, {what} (line {}), which has no design sensitivity",
                        source.number, source.line
                    ),
                )
                .with_hint(format!(
                    "a band is made of the exact first-order sensitivities of its buffer to the toleranced \
                     dimensions: give BUFTOL a buffer recorded by {WITH_SENSITIVITY}"
                )));
        }
        let b = u32::try_from(def.buffer.value).unwrap_or(0);
        let Some(b1) = b.checked_add(1) else {
            return Err(deck
                .error(DiagnosticKind::BadValue, def.buffer.span, format!("buffer number {b} leaves no room for b + 1"))
                .with_hint("BUFTOL records the RSS band into buffer b + 1: give a smaller b"));
        };
        for n in [b, b1] {
            let clash = match (defined.get(&n), bands.iter().find(|o| n == o.buffer || n == o.buffer + 1)) {
                (Some(other), _) => Some(format!("buffer {n} is already defined at line {}", other.line)),
                (None, Some(other)) => Some(format!("the BUFTOL at line {} records into buffer {n}", other.line)),
                (None, None) => None,
            };
            if let Some(clash) = clash {
                return Err(deck
                    .error(
                        DiagnosticKind::DuplicateBuffer,
                        def.buffer.span,
                        format!("BUFTOL records into buffers {b} and {b1}, but {clash}"),
                    )
                    .with_hint(format!(
                        "give BUFTOL a number b such that neither b nor b + 1 is used by another buffer (b = {} is \
                         free)",
                        free_pair(&defined, &bands)
                    )));
            }
        }
        bands.push(BandDef { source: source.number, buffer: b, line: def.line });
    }
    Ok(Some(Tolerance { dims, bands, line: block.line }))
}

/// BUFTOL's buffers b and b + 1 appended to `buffers`. Each records its
/// source's quantity during a run (so it has the source's unit and transfer
/// order); [`crate::Compiled::fill_bands`] then writes the band over it.
pub(crate) fn record_bands(tolerance: Option<&Tolerance>, buffers: &mut Vec<Buffer>) {
    for band in tolerance.iter().flat_map(|t| &t.bands) {
        let Some(source) = buffers.iter().find(|b| b.number == band.source).copied() else { continue };
        for number in [band.buffer, band.buffer + 1] {
            buffers.push(Buffer { number, quantity: source.quantity, line: band.line });
        }
    }
}

/// The smallest b with b and b + 1 free of buffers and bands.
fn free_pair(defined: &std::collections::BTreeMap<u32, Buffer>, bands: &[BandDef]) -> u32 {
    let used = |n: u32| defined.contains_key(&n) || bands.iter().any(|o| n == o.buffer || n == o.buffer + 1);
    (1..u32::MAX).find(|&b| !used(b) && !used(b + 1)).unwrap_or(1)
}

/// `TOL r`: a prescribed row with a PARA value that no motion drives; its
/// 0-based index.
fn row(deck: &Deck, model: &Model, def: &TolDef) -> Result<usize, Box<Diagnostic>> {
    let r = def.index.value;
    let rows = &model.prescribed;
    let Some(info) = usize::try_from(r - 1).ok().and_then(|k| rows.get(k)) else {
        let message = if r < 0 {
            format!("TOL names dependent form parameter {r}, an output: only a prescribed row's value has a tolerance")
        } else {
            format!(
                "TOL names prescribed row {r}, but the model has {}",
                count(rows.len(), "prescribed row", "prescribed rows")
            )
        };
        return Err(deck
            .error(DiagnosticKind::UnknownRow, def.index.span, message)
            .with_hint("TOL takes a prescribed row that has a PARA value: a length, an angle, a local u or v"));
    };
    if let Some(j) = info.input {
        return Err(deck
            .error(
                DiagnosticKind::DesignVariable,
                def.index.span,
                format!("row {r} is the input of DOF {j}: the motion gives its value at every position"),
            )
            .with_hint("TOL takes a dimension of the mechanism (a prescribed row with PARA), not an input"));
    }
    if info.para.is_none() {
        return Err(deck
            .error(
                DiagnosticKind::DesignVariable,
                def.index.span,
                format!("row {r} has no PARA value: its value is whatever the co-ordinates give it"),
            )
            .with_hint(format!(
                "add `PARA {r} value` to GEOMETRY to prescribe the dimension, then tolerance it; or tolerance the \
                 co-ordinates (TOLX) that give it"
            )));
    }
    Ok(usize::try_from(r - 1).unwrap_or(0))
}

/// `TOLX i`: a fixed co-ordinate; its 0-based index.
fn fixed(deck: &Deck, sizes: &Sizes, def: &TolDef) -> Result<usize, Box<Diagnostic>> {
    let i = coordinate(deck, sizes, Keyword::TolX, &def.index)?;
    if !sizes.moving[i] {
        return Ok(i);
    }
    Err(deck
        .error(
            DiagnosticKind::NotFixed,
            def.index.span,
            format!("TOLX names co-ordinate {}, which moves (XMOV): the prescribed rows place it", i + 1),
        )
        .with_hint(
            "TOLX takes a fixed co-ordinate (XFIX), such as a frame pivot; the tolerance of a moving point is that of \
             the rows that place it: give those rows TOL lines",
        ))
}
