//! STORAGE to buffer definitions, output lists and pictures.

use std::collections::BTreeMap;

use mechfem_core::{FormRef, Quantity};

use crate::ast::{BufDef, BufList, Deck};
use crate::compiled::{Buffer, Picture, PlotItem};
use crate::diagnostic::{count, dof_hint, numbered, Diagnostic, DiagnosticKind, Hint, Spanned};
use crate::keywords::Keyword;

/// The sizes that buffer definitions are checked against.
pub(crate) struct Sizes {
    pub n_coords: usize,
    pub n_prescribed: usize,
    pub n_dependent: usize,
    pub n_dof: usize,
}

/// The compiled STORAGE block.
#[derive(Default)]
pub(crate) struct Outputs {
    pub buffers: Vec<Buffer>,
    pub printbuf: Option<Vec<u32>>,
    pub savedata: Vec<u32>,
    pub animate: Option<String>,
    pub pictures: Vec<Picture>,
}

pub(crate) fn outputs(deck: &Deck, sizes: &Sizes) -> Result<Outputs, Box<Diagnostic>> {
    let Some(st) = &deck.storage else { return Ok(Outputs::default()) };
    let mut defined: BTreeMap<u32, usize> = BTreeMap::new();
    let mut buffers = Vec::with_capacity(st.buffers.len());
    for def in &st.buffers {
        let quantity = quantity(deck, sizes, def)?;
        let number = buffer_number(&def.number);
        if let Some(first) = defined.get(&number) {
            return Err(deck
                .error(
                    DiagnosticKind::DuplicateBuffer,
                    def.number.span,
                    format!("buffer {number} is already defined at line {first}"),
                )
                .with_hint("give every BUF... keyword its own buffer number"));
        }
        defined.insert(number, def.line);
        buffers.push(Buffer { number, quantity, line: def.line });
    }
    let known = |b: &Spanned<i64>| -> Result<u32, Box<Diagnostic>> {
        let number = buffer_number(b);
        if defined.contains_key(&number) {
            return Ok(number);
        }
        let list: Vec<String> = defined.keys().take(12).map(u32::to_string).collect();
        let more = if defined.len() > 12 { ", ..." } else { "" };
        let hint = if list.is_empty() {
            "define it with a BUF... keyword; this deck defines no buffers".to_string()
        } else {
            format!("define it with a BUF... keyword; the defined buffers are {}{more}", list.join(", "))
        };
        Err(deck
            .error(DiagnosticKind::UnknownBuffer, b.span, format!("buffer {number} is not defined"))
            .with_hint(hint))
    };
    let list = |lines: &[BufList]| -> Result<Vec<u32>, Box<Diagnostic>> {
        let mut out: Vec<u32> = Vec::new();
        for b in lines.iter().flat_map(|l| &l.buffers) {
            let number = known(b)?;
            if !out.contains(&number) {
                out.push(number);
            }
        }
        Ok(out)
    };
    let printbuf = if st.printbuf.is_empty() {
        None
    } else if st.printbuf.iter().any(|l| l.buffers.is_empty()) {
        list(&st.printbuf)?;
        Some(Vec::new())
    } else {
        Some(list(&st.printbuf)?)
    };
    let savedata = list(&st.savedata)?;
    let mut pictures = Vec::with_capacity(st.pictures.len());
    for pic in &st.pictures {
        let mut items = Vec::with_capacity(pic.items.len());
        for item in &pic.items {
            items.push(match item.keyword.value {
                Keyword::PlotHodo => {
                    let x = coordinate(deck, sizes, Keyword::PlotHodo, &item.a)?;
                    let y = coordinate(deck, sizes, Keyword::PlotHodo, &item.b)?;
                    PlotItem::Hodograph { x, y }
                }
                Keyword::PlotCurv => PlotItem::Curve { x: known(&item.a)?, y: known(&item.b)? },
                _ => PlotItem::Function { x: known(&item.a)?, y: known(&item.b)? },
            });
        }
        pictures.push(Picture { title: pic.title.clone(), line: pic.line, items });
    }
    Ok(Outputs { buffers, printbuf, savedata, animate: st.animate.as_ref().map(|a| a.value.clone()), pictures })
}

/// A buffer number the parser has checked to lie in 1..=u32::MAX.
fn buffer_number(b: &Spanned<i64>) -> u32 {
    u32::try_from(b.value).unwrap_or(0)
}

fn quantity(deck: &Deck, sizes: &Sizes, def: &BufDef) -> Result<Quantity, Box<Diagnostic>> {
    let kw = def.keyword.value;
    let a = |k: usize| def.args.get(k);
    let coord = |k: usize| a(k).map_or(Ok(0), |i| coordinate(deck, sizes, kw, i));
    let input = |k: usize| a(k).map_or(Ok(0), |j| dof(deck, sizes, kw, j));
    let row = |k: usize| a(k).map_or(Ok(FormRef::Prescribed(0)), |r| form(deck, sizes, kw, r));
    // Second-order keywords: m defaults to j.
    let second = |k: usize| if a(k).is_some() { input(k) } else { input(k - 1) };
    Ok(match kw {
        Keyword::BufInp => Quantity::Input(input(0)?),
        Keyword::BufTime => Quantity::Time,
        Keyword::BufX0 => Quantity::X0(coord(0)?),
        Keyword::BufKx1 => Quantity::Kx1 { coord: coord(0)?, j: input(1)? },
        Keyword::BufKx2 => Quantity::Kx2 { coord: coord(0)?, j: input(1)?, m: second(2)? },
        Keyword::BufVx => Quantity::Vx(coord(0)?),
        Keyword::BufAx => Quantity::Ax(coord(0)?),
        Keyword::BufE0 => Quantity::E0(row(0)?),
        Keyword::BufKe1 => Quantity::Ke1(row(0)?, input(1)?),
        Keyword::BufKe2 => Quantity::Ke2(row(0)?, input(1)?, second(2)?),
        Keyword::BufVe => Quantity::Ve(row(0)?),
        Keyword::BufAe => Quantity::Ae(row(0)?),
        _ => Quantity::Det,
    })
}

/// A co-ordinate number 1..N as a 0-based index.
fn coordinate(deck: &Deck, sizes: &Sizes, kw: Keyword, i: &Spanned<i64>) -> Result<usize, Box<Diagnostic>> {
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
fn dof(deck: &Deck, sizes: &Sizes, kw: Keyword, j: &Spanned<i64>) -> Result<usize, Box<Diagnostic>> {
    let n = sizes.n_dof;
    match usize::try_from(j.value).ok().filter(|&v| (1..=n).contains(&v)) {
        Some(v) => Ok(v - 1),
        None => Err(deck
            .error(DiagnosticKind::UnknownDof, j.span, format!("{kw} names DOF {}, but NRDOF is {n}", j.value))
            .with_hint(dof_hint(n))),
    }
}

/// A destination: `r > 0` a prescribed row, `-k` a dependent form parameter.
fn form(deck: &Deck, sizes: &Sizes, kw: Keyword, r: &Spanned<i64>) -> Result<FormRef, Box<Diagnostic>> {
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
