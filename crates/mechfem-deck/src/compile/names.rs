//! The NAMES block to the model's [`Names`]: every number it names is
//! checked against the model (co-ordinates 1..N, elements 1..n_e, rows
//! 1..n_p, dependent form parameters 1..n_d, defined buffers).

use std::collections::BTreeSet;

use mechfem_core::Names;

use crate::ast::{Deck, NameKind};
use crate::compiled::Buffer;
use crate::diagnostic::{Diagnostic, DiagnosticKind, Hint};

/// The names of `deck`'s NAMES block, for a model of `n_coords`
/// co-ordinates, `n_elements` elements, `n_prescribed` rows and
/// `n_dependent` dependent form parameters, with `buffers`.
pub(crate) fn declared(deck: &Deck, sizes: [usize; 4], buffers: &[Buffer]) -> Result<Names, Box<Diagnostic>> {
    let [n_coords, n_elements, n_prescribed, n_dependent] = sizes;
    let mut names = Names::empty(n_coords, n_elements, n_prescribed, n_dependent);
    let Some(block) = &deck.names else { return Ok(names) };
    let defined: BTreeSet<i64> = buffers.iter().map(|x| i64::from(x.number)).collect();
    for def in &block.names {
        let k = def.kind.value;
        let (count, thing, hint) = match k {
            NameKind::Point | NameKind::Coord => (n_coords, "co-ordinate", "co-ordinates"),
            NameKind::Elem => (n_elements, "element", "elements"),
            NameKind::Row => (n_prescribed, "prescribed row", "prescribed rows"),
            NameKind::Dep => (n_dependent, "dependent form parameter", "dependent form parameters"),
            NameKind::Buf => (0, "buffer", "buffers"),
        };
        if k == NameKind::Buf {
            let b = &def.numbers[0];
            if !defined.contains(&b.value) {
                let mut defined: Vec<String> = buffers.iter().take(12).map(|x| x.number.to_string()).collect();
                if buffers.len() > 12 {
                    defined.push(format!("... ({} in all)", buffers.len()));
                }
                let hint = if defined.is_empty() {
                    "the deck defines no buffers: label a buffer that a BUF... line of STORAGE or OPTIMISE defines"
                        .to_string()
                } else {
                    format!("the deck defines the buffers {}", defined.join(", "))
                };
                return Err(deck
                    .error(DiagnosticKind::NameOutOfRange, b.span, format!("buffer {} is not defined", b.value))
                    .with_hint(hint));
            }
            names.buffers.insert(u32::try_from(b.value).unwrap_or(u32::MAX), def.name.value.clone());
            continue;
        }
        for n in &def.numbers {
            if usize::try_from(n.value).map_or(true, |v| v > count) {
                let has = match count {
                    0 => format!("the deck has no {hint}"),
                    1 => format!("the deck has {thing} 1 only"),
                    _ => format!("the deck has {hint} 1 to {count}"),
                };
                return Err(deck
                    .error(
                        DiagnosticKind::NameOutOfRange,
                        n.span,
                        format!("{} names {thing} {}, which the deck does not have", k.word(), n.value),
                    )
                    .with_hint(format!("{has}: {}", k.usage())));
            }
        }
        let at = |n: usize| usize::try_from(def.numbers[n].value - 1).unwrap_or(0);
        let name = def.name.value.clone();
        match k {
            NameKind::Point => {
                let (x, y) = (at(0), at(1));
                names.coordinates[x] = Some(format!("{name}.x"));
                names.coordinates[y] = Some(format!("{name}.y"));
                names.points.push((x, y, name));
            }
            NameKind::Coord => names.coordinates[at(0)] = Some(name),
            NameKind::Elem => names.elements[at(0)] = Some(name),
            NameKind::Row => names.prescribed[at(0)] = Some(name),
            NameKind::Dep => names.dependent[at(0)] = Some(name),
            NameKind::Buf => {}
        }
    }
    Ok(names)
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    use mechfem_core::Names;

    fn names(text: &str) -> Names {
        let deck = crate::parse_str(text, "names.mec").unwrap();
        crate::compile(&deck, Path::new(".")).unwrap().names
    }

    fn some(names: &[&str]) -> Vec<Option<String>> {
        names.iter().map(|n| (!n.is_empty()).then(|| n.to_string())).collect()
    }

    const CRANK: &str = "KIN ANA\nTOPOLOGY\nELEM 1 BIN 1 2 3 4 ; crank\nFORM 1 LENL 1 1\n 2 ANGB 1 2\nNRDOF 1\n\
                         GEOMETRY\nXFIX 1 0 ; O.x\n 2 0\nXMOV 3 1 ; A.x\n 4 0\n";

    #[test]
    fn the_names_block_names_points_coordinates_elements_and_rows() {
        let deck = format!(
            "{CRANK}NAMES\nPOINT 1 2 O\nCOORD 3 ax\nELEM 1 crank\nROW 2 phi\n 1 r\nBUF 7 the tip's x\n\
             STORAGE\nBUFX0 3 7\n"
        );
        let n = names(&deck);
        assert_eq!(n.coordinates, some(&["O.x", "O.y", "ax", ""]));
        assert_eq!(n.points, [(0, 1, "O".to_string())]);
        assert_eq!(n.elements, some(&["crank"]));
        assert_eq!(n.prescribed, some(&["r", "phi"]));
        assert_eq!(n.buffers.into_iter().collect::<Vec<_>>(), [(7, "the tip's x".to_string())]);
    }

    #[test]
    fn comments_name_nothing() {
        let n = names(CRANK);
        assert!(n.is_empty());
        assert_eq!(n.coordinates, some(&["", "", "", ""]));
        assert_eq!(n.elements, some(&[""]));
    }
}
