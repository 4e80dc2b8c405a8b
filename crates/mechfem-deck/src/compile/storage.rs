//! STORAGE to buffer definitions, output lists and pictures; the buffer
//! definitions of OPTIMISE join those of STORAGE.

use std::collections::BTreeMap;

use mechfem_core::{FormRef, Quantity};

use super::refs::{coordinate, dof, form, Sizes};
use crate::ast::{BufDef, BufList, Deck};
use crate::compiled::{Buffer, Picture, PlotItem};
use crate::diagnostic::{count, is_format, numbered, output_name_problem, Diagnostic, DiagnosticKind, Hint, Spanned};
use crate::keywords::Keyword;

/// The compiled STORAGE block.
#[derive(Default)]
pub(crate) struct Outputs {
    pub buffers: Vec<Buffer>,
    pub printbuf: Option<Vec<u32>>,
    pub savedata: Vec<u32>,
    pub animate: Option<String>,
    pub pictures: Vec<Picture>,
}

/// The outputs of `deck` with its `buffers` ([`buffers`] and the bands of
/// TOLERANCE, which PRINTBUF, SAVEDATA and the pictures may name).
pub(crate) fn outputs(deck: &Deck, sizes: &Sizes, buffers: Vec<Buffer>) -> Result<Outputs, Box<Diagnostic>> {
    let Some(st) = &deck.storage else { return Ok(Outputs { buffers, ..Outputs::default() }) };
    let defined = by_number(&buffers);
    let known = |b: &Spanned<i64>| defined_buffer(deck, &defined, b).map(|buffer| buffer.number);
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
    let animate = st.animate.as_ref().map(|a| animate_name(deck, a)).transpose()?;
    Ok(Outputs { buffers, printbuf, savedata, animate, pictures })
}

/// The ANIMATE name, a plain file name: the animation is written into the
/// output folder and nowhere else.
fn animate_name(deck: &Deck, name: &Spanned<String>) -> Result<String, Box<Diagnostic>> {
    let Some(problem) = output_name_problem(&name.value) else { return Ok(name.value.clone()) };
    Err(deck
        .error(DiagnosticKind::OutputName, name.span, format!("the ANIMATE name `{}` {problem}", shown(&name.value)))
        .with_hint(
            "give a plain file name such as `film`: the animation is written as film.gif (and film.mp4) into the \
             output folder, and nowhere else",
        ))
}

/// A name as a message shows it: control and format characters escaped
/// (`\0`, `\u{202e}`).
fn shown(name: &str) -> String {
    name.chars()
        .map(|c| match c {
            c if c.is_control() => c.escape_debug().to_string(),
            c if is_format(c) => c.escape_unicode().to_string(),
            c => c.to_string(),
        })
        .collect()
}

/// The buffers defined in OPTIMISE and STORAGE, in the order of their
/// lines; every number defined once.
pub(crate) fn buffers(deck: &Deck, sizes: &Sizes) -> Result<Vec<Buffer>, Box<Diagnostic>> {
    let optimise = deck.optimise.iter().flat_map(|o| &o.buffers);
    let mut defs: Vec<&BufDef> = optimise.chain(deck.storage.iter().flat_map(|s| &s.buffers)).collect();
    defs.sort_by_key(|d| d.line);
    let mut defined: BTreeMap<u32, usize> = BTreeMap::new();
    let mut buffers = Vec::with_capacity(defs.len());
    for def in defs {
        let parts = match super::designer::parts(deck, sizes, def)? {
            Some(parts) => parts,
            None => vec![quantity(deck, sizes, def)?],
        };
        for (k, quantity) in parts.into_iter().enumerate() {
            let number = super::designer::part_number(deck, def, k)?;
            if let Some(first) = defined.get(&number) {
                return Err(super::designer::taken(deck, def, k, number, *first));
            }
            defined.insert(number, def.line);
            buffers.push(Buffer { number, quantity, line: def.line });
        }
    }
    Ok(buffers)
}

/// The buffers by number.
pub(crate) fn by_number(buffers: &[Buffer]) -> BTreeMap<u32, Buffer> {
    buffers.iter().map(|b| (b.number, *b)).collect()
}

/// The buffer numbered `b`, or a diagnostic naming the buffers the deck
/// defines.
pub(crate) fn defined_buffer(
    deck: &Deck,
    defined: &BTreeMap<u32, Buffer>,
    b: &Spanned<i64>,
) -> Result<Buffer, Box<Diagnostic>> {
    let number = buffer_number(b);
    if let Some(buffer) = defined.get(&number) {
        return Ok(*buffer);
    }
    let list: Vec<String> = defined.keys().take(12).map(u32::to_string).collect();
    let more = if defined.len() > 12 { ", ..." } else { "" };
    let hint = if list.is_empty() {
        "define it with a BUF... keyword; this deck defines no buffers".to_string()
    } else {
        format!("define it with a BUF... keyword; the defined buffers are {}{more}", list.join(", "))
    };
    Err(deck.error(DiagnosticKind::UnknownBuffer, b.span, format!("buffer {number} is not defined")).with_hint(hint))
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
        Keyword::BufSig => Quantity::Sigma(a(0).map_or(Ok(0), |r| stressed_row(deck, sizes, kw, r))?),
        Keyword::BufDrv => Quantity::Drive(input(0)?),
        Keyword::BufRea => Quantity::Reaction(a(0).map_or(Ok(0), |i| fixed(deck, sizes, kw, i))?),
        Keyword::BufEkin => Quantity::Ekin,
        Keyword::BufEpot => Quantity::Epot,
        Keyword::BufPow => Quantity::Power,
        Keyword::BufMred => Quantity::Mred(input(0)?, input(1)?),
        _ => Quantity::Det,
    })
}

/// A prescribed row 1..n_p (the rows that carry a stress) as a 0-based index.
fn stressed_row(deck: &Deck, sizes: &Sizes, kw: Keyword, r: &Spanned<i64>) -> Result<usize, Box<Diagnostic>> {
    let n_p = sizes.n_prescribed;
    if let Some(k) = usize::try_from(r.value).ok().filter(|&k| (1..=n_p).contains(&k)) {
        return Ok(k - 1);
    }
    let message = match r.value {
        0 => format!("{kw} names destination 0, which is no form parameter"),
        v if v < 0 => format!("{kw} names dependent form parameter {v}, which carries no stress"),
        v => format!(
            "{kw} names prescribed row {v}, but the model has {}",
            count(n_p, "prescribed row", "prescribed rows")
        ),
    };
    Err(deck
        .error(DiagnosticKind::UnknownRow, r.span, message)
        .with_hint(format!("the stresses belong to the prescribed rows ({}), the rows of D^c", numbered(n_p, 1))))
}

/// A fixed co-ordinate (the ones that have a reaction) as a 0-based index.
fn fixed(deck: &Deck, sizes: &Sizes, kw: Keyword, i: &Spanned<i64>) -> Result<usize, Box<Diagnostic>> {
    let k = coordinate(deck, sizes, kw, i)?;
    if !sizes.moving.get(k).copied().unwrap_or(false) {
        return Ok(k);
    }
    let fixed: Vec<String> =
        (0..sizes.n_coords).filter(|&c| !sizes.moving[c]).take(12).map(|c| (c + 1).to_string()).collect();
    let more = if sizes.moving.iter().filter(|m| !**m).count() > 12 { ", ..." } else { "" };
    let hint = if fixed.is_empty() {
        "only a fixed co-ordinate (XFIX) has a reaction, and this model has none".to_string()
    } else {
        format!("name a fixed co-ordinate (XFIX): {}{more}", fixed.join(", "))
    };
    Err(deck
        .error(
            DiagnosticKind::NotFixed,
            i.span,
            format!("{kw} names co-ordinate {}, which moves (XMOV): only a fixed co-ordinate has a reaction", i.value),
        )
        .with_hint(hint))
}
