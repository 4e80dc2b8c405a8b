//! The names a deck declares in its comments ([`Names`] gives the rule).

use std::collections::{BTreeMap, BTreeSet};

use super::rows::Resolved;
use crate::ast::{CoordDef, Deck};
use crate::compiled::Names;

/// The declared names of the co-ordinates (by number), elements and rows
/// of `deck`, ambiguous ones dropped.
pub(crate) fn declared(
    deck: &Deck,
    coords: &BTreeMap<i64, &CoordDef>,
    prescribed: &[Vec<&Resolved>],
    dependent: &[Vec<&Resolved>],
) -> Names {
    // A FORM line's comment, even a note, speaks for its row: PARA's is
    // read only when that line has none, so a note is never passed over.
    let row_name = |row: &Vec<&Resolved>, para: Option<&str>| {
        let form = row.first().and_then(|t| t.def.comment.as_deref());
        match form {
            Some(comment) => name_in(comment, true),
            None => para.and_then(|comment| name_in(comment, false)),
        }
    };
    let para_comment = |k: usize| {
        let para = deck.geometry.paras.iter().find(|p| p.row.value == k as i64 + 1);
        para.and_then(|p| p.comment.as_deref())
    };
    let mut names = Names {
        coordinates: coords.values().map(|c| c.comment.as_deref().and_then(|t| name_in(t, false))).collect(),
        elements: deck.topology.elements.iter().map(|e| e.comment.as_deref().and_then(|t| name_in(t, true))).collect(),
        prescribed: prescribed.iter().enumerate().map(|(k, row)| row_name(row, para_comment(k))).collect(),
        dependent: dependent.iter().map(|row| row_name(row, None)).collect(),
    };
    drop_ambiguous(&mut names);
    names
}

/// The name a comment declares: the trimmed text, before its first `:`
/// when `before_colon`, if it is one word `[A-Za-z_][A-Za-z0-9_.]*`.
fn name_in(comment: &str, before_colon: bool) -> Option<String> {
    let text = comment.trim();
    let text = if before_colon { text.split(':').next().unwrap_or(text).trim() } else { text };
    let mut chars = text.chars();
    let starts = chars.next().is_some_and(|c| c.is_ascii_alphabetic() || c == '_');
    let rest = chars.all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '.');
    (starts && rest).then(|| text.to_string())
}

/// Drops every name that two co-ordinates, two elements or two rows share,
/// or a co-ordinate and an element or row.
fn drop_ambiguous(names: &mut Names) {
    // How often each name is declared: for co-ordinates, elements, rows.
    let mut uses: BTreeMap<&str, [usize; 3]> = BTreeMap::new();
    let lists = [(&names.coordinates, 0), (&names.elements, 1), (&names.prescribed, 2), (&names.dependent, 2)];
    for (list, kind) in lists {
        for name in list.iter().flatten() {
            uses.entry(name).or_default()[kind] += 1;
        }
    }
    let ambiguous: BTreeSet<String> = uses
        .into_iter()
        .filter(|(_, [coords, elements, rows])| {
            *coords > 1 || *elements > 1 || *rows > 1 || (*coords > 0 && elements + rows > 0)
        })
        .map(|(name, _)| name.to_string())
        .collect();
    let all = [&mut names.coordinates, &mut names.elements, &mut names.prescribed, &mut names.dependent];
    for name in all.into_iter().flatten() {
        if name.as_ref().is_some_and(|n| ambiguous.contains(n)) {
            *name = None;
        }
    }
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    use crate::compiled::Names;

    fn names(text: &str) -> Names {
        let deck = crate::parse_str(text, "names.mec").unwrap();
        crate::compile(&deck, Path::new(".")).unwrap().names
    }

    fn some(names: &[&str]) -> Vec<Option<String>> {
        names.iter().map(|n| (!n.is_empty()).then(|| n.to_string())).collect()
    }

    /// A four-bar as `mechfem.Mechanism.to_deck` writes it.
    const WRITTEN: &str = "; written by mechfem from the Python model 'fourbar'
KIN ANA
TOPOLOGY
ELEM 1 BIN 1 2 5 6 ; crank: A0 A
ELEM 2 TR2 5 6 7 8 9 10 ; coupler: A B C
ELEM 3 BIN 3 4 7 8 ; rocker: B0 B
FORM 1 LENL 1 1 1.0 ; crank.length
FORM 2 LENL 2 2 1.0 ; coupler.length
FORM 3 LENU 2 3 1.0 ; coupler.u
FORM 4 LENV 2 4 1.0 ; coupler.v
FORM 5 LENL 3 5 1.0 ; rocker.length
FORM 6 ANGB 1 6 1.0 ; phi: crank.angle
FORM 7 ANGB 3 -1 1.0 ; psi: rocker.angle
NRDOF 1
GEOMETRY
XFIX 1 0.0 ; A0.x
XFIX 2 0.0 ; A0.y
XFIX 3 4.0 ; B0.x
XFIX 4 0.0 ; B0.y
XMOV 5 1.0 ; A.x
XMOV 6 0.0 ; A.y
XMOV 7 3.5 ; B.x
XMOV 8 2.5 ; B.y
XMOV 9 1.5 ; C.x
XMOV 10 2.0 ; C.y
PARA 1 1.0 ; crank.length
PARA 6 0.0 ; phi
";

    #[test]
    fn a_written_deck_declares_every_name() {
        let n = names(WRITTEN);
        assert_eq!(n.coordinates, some(&["A0.x", "A0.y", "B0.x", "B0.y", "A.x", "A.y", "B.x", "B.y", "C.x", "C.y"]));
        assert_eq!(n.elements, some(&["crank", "coupler", "rocker"]));
        let rows = ["crank.length", "coupler.length", "coupler.u", "coupler.v", "rocker.length", "phi"];
        assert_eq!(n.prescribed, some(&rows));
        assert_eq!(n.dependent, some(&["psi"]));
    }

    #[test]
    fn free_text_is_not_a_name() {
        // The example's comments are notes, except the single words naming
        // the first co-ordinate of each point.
        let n = names(include_str!("../../../../examples/fourbar/fourbar.mec"));
        assert_eq!(n.coordinates, some(&["A0", "", "B0", "", "", "", "B", "", "C", ""]));
        assert_eq!(n.elements, some(&["", "", ""]));
        assert_eq!(n.prescribed, some(&["", "", "", "", "", ""]));
        assert_eq!(n.dependent, some(&[""]));
    }

    #[test]
    fn a_comment_that_is_not_one_word_names_nothing() {
        let deck = "KIN ANA\nTOPOLOGY\nELEM 1 BIN 1 2 3 4 ; crank A0-A: the input\nFORM 1 LENL 1 1 ; 1st: length\n\
                    2 ANGB 1 2 ; a-b\nNRDOF 1\nGEOMETRY\nXFIX 1 0 ; the x of A0\n 2 0 ; A0.y, fixed\n\
                    XMOV 3 1 ; x:\n 4 .5 ; _y.\n";
        let n = names(deck);
        assert_eq!(n.coordinates, some(&["", "", "", "_y."]));
        assert_eq!(n.elements, some(&[""]));
        assert_eq!(n.prescribed, some(&["", ""]));
    }

    #[test]
    fn an_ambiguous_name_is_dropped_for_all_that_declare_it() {
        // `A` names two co-ordinates, `tip` a co-ordinate and an element,
        // `len` a prescribed row and a dependent one; `bar` an element and a
        // row, which is allowed.
        let deck = "KIN ANA\nTOPOLOGY\nELEM 1 BIN 1 2 3 4 ; bar: P Q\n 2 BIN 3 4 5 6 ; tip\n\
                    FORM 1 LENL 1 1 ; bar\n 2 ANGB 1 2 ; len\n 3 LENL 2 3\n 4 ANGB 2 4 ; drive\n 5 LENL 2 -1 ; len\n\
                    NRDOF 1\nGEOMETRY\nXFIX 1 0 ; A\n 2 0 ; A\nXMOV 3 1 ; tip\n 4 0 ; Q.y\n 5 2 ; R.x\n 6 0 ; R.y\n";
        let n = names(deck);
        assert_eq!(n.coordinates, some(&["", "", "", "Q.y", "R.x", "R.y"]));
        assert_eq!(n.elements, some(&["bar", ""]));
        assert_eq!(n.prescribed, some(&["bar", "", "", "drive"]));
        assert_eq!(n.dependent, some(&[""]));
    }

    #[test]
    fn continuation_lines_and_para_comments_declare_names() {
        // FORM stands alone and its lines repeat it; the first FORM line of a
        // row names it, PARA only when that line has no comment.
        let deck = "KIN ANA\nTOPOLOGY\nELEM 1 BIN 1 2 3 4 ; crank\n 2 BIN 3 4 5 6\nFORM ; the rows\n\
                    1 LENL 1 1\n 2 LENL 2 2 1 ; link: LENL(2) + LENL(1)\n 3 LENL 1 2 1 ; not.this\n\
                    4 ANGB 2 3 ; row 3: free text\n 5 ANGB 1 4\nNRDOF 1\nGEOMETRY\n\
                    XFIX 1 0 ; O.x\n 2 0 ; O.y\nXMOV 3 1 ; A.x\n 4 0 ; A.y\n 5 2 ; B.x\n 6 0 ; B.y\n\
                    PARA 1 1 ; crank_length\n 2 2 ; ignored\n 3 0 ; ignored.too\n 4 0 ; phi\n";
        let n = names(deck);
        assert_eq!(n.coordinates, some(&["O.x", "O.y", "A.x", "A.y", "B.x", "B.y"]));
        assert_eq!(n.elements, some(&["crank", ""]));
        assert_eq!(n.prescribed, some(&["crank_length", "link", "", "phi"]));
    }
}
