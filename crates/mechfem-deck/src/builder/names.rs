//! The names and units of a built deck: the UNITS line and the NAMES block,
//! checked as the parser checks them (`statements/names.rs`).

use mechfem_core::units::{Angle, Force, Length, Mass, Time};
use mechfem_core::Units;

use crate::ast::{NameDef, NameKind, NamesBlock, UnitsDef};
use crate::diagnostic::{is_format, DiagnosticKind};
use crate::keywords::Keyword;
use crate::statements::names::{MAX_LABEL, MAX_NAME};

use super::{at, whole_line, DeckBuilder, Refused};

/// The unit spelled `v` (case-insensitive, as the UNITS line reads it).
fn unit<T: Copy>(all: &[T], symbol: fn(T) -> &'static str, v: &str) -> Option<T> {
    all.iter().copied().find(|&u| symbol(u).eq_ignore_ascii_case(v))
}

impl DeckBuilder {
    /// The model's units, each kind given by its symbol (`mm`, `deg`, `kg`,
    /// `kN`, `ms`) or not at all: the UNITS line, which stands right below
    /// the mode line, so this comes before every other item.
    pub fn units(
        &mut self,
        length: Option<&str>,
        angle: Option<&str>,
        mass: Option<&str>,
        force: Option<&str>,
        time: Option<&str>,
    ) -> Result<(), Refused> {
        if self.line != 3 || self.deck.units.is_some() || self.elements > 0 {
            let message = "the units come before every other item, once";
            return Err(self.refuse(DiagnosticKind::DuplicateKeyword, self.line + 1, message));
        }
        let mut units = Units { declared: true, ..Units::NONE };
        let mut spans = [None; 5];
        let given = [length, angle, mass, force, time];
        for (k, v) in given.into_iter().enumerate() {
            let Some(v) = v else { continue };
            let ok = match k {
                0 => unit(Length::ALL, Length::symbol, v).map(|u| units.length = Some(u)),
                1 => unit(Angle::ALL, Angle::symbol, v).map(|u| units.angle = Some(u)),
                2 => unit(Mass::ALL, Mass::symbol, v).map(|u| units.mass = Some(u)),
                3 => unit(Force::ALL, Force::symbol, v).map(|u| units.force = Some(u)),
                _ => unit(Time::ALL, Time::symbol, v).map(|u| units.time = Some(u)),
            };
            if ok.is_none() {
                let kind = ["length", "angle", "mass", "force", "time"][k];
                return Err(self.refuse(DiagnosticKind::UnknownUnit, 3, format!("`{v}` is not a unit of {kind}")));
            }
            spans[k] = Some(whole_line(3));
        }
        if given.iter().all(Option::is_none) {
            return Err(self.refuse(DiagnosticKind::ArgumentCount, 3, "the units name no unit"));
        }
        // The UNITS line takes line 3; TOPOLOGY moves below it.
        self.deck.source.insert(2, "UNITS".to_string());
        self.deck.units = Some(UnitsDef { line: 3, units, spans });
        self.deck.topology.line = 4;
        self.line = 4;
        Ok(())
    }

    /// A name of the NAMES block, after the geometry: `kind` `POINT` (the
    /// co-ordinates x, y), `COORD`, `ELEM`, `ROW` or `DEP` (one number), or
    /// `BUF` (a buffer's label, free text).
    pub fn name(&mut self, kind: &str, numbers: &[i64], name: &str) -> Result<(), Refused> {
        self.in_block(Keyword::Xmov, Keyword::Xmov, "a name")?;
        if !self.named {
            let header = self.next_line("NAMES");
            self.deck.names = Some(NamesBlock { line: header, names: Vec::new() });
            self.named = true;
        }
        let line = self.next_line(name);
        let Some(k) = NameKind::from_word(kind) else {
            return Err(self.refuse(DiagnosticKind::UnknownNameKind, line, format!("`{kind}` is not a kind of name")));
        };
        if numbers.len() != k.numbers() {
            let message = format!("{} {name:?} has {} numbers: {}", k.word(), numbers.len(), k.usage());
            return Err(self.refuse(DiagnosticKind::ArgumentCount, line, message));
        }
        let mut nums = Vec::with_capacity(numbers.len());
        for &n in numbers {
            let n = if k == NameKind::Dep { n.checked_abs().unwrap_or(0) } else { n };
            if n < 1 {
                return Err(self.refuse(
                    DiagnosticKind::NameOutOfRange,
                    line,
                    format!("{} {n} names nothing", k.word()),
                ));
            }
            nums.push(at(super::checks::whole(self, line, n, name)?, line));
        }
        let text = if k == NameKind::Buf { label(self, line, name)? } else { deck_name(self, line, name)? };
        self.unique(k, &nums, &text, line)?;
        let def = NameDef { line, kind: at(k, line), numbers: nums, name: at(text, line) };
        if let Some(block) = self.deck.names.as_mut() {
            block.names.push(def);
        }
        Ok(())
    }

    /// A name given twice within its kind, or a thing named twice.
    fn unique(&self, k: NameKind, numbers: &[crate::Spanned<i64>], name: &str, line: usize) -> Result<(), Refused> {
        let coordinates = |k: NameKind| matches!(k, NameKind::Point | NameKind::Coord);
        for d in self.deck.names.iter().flat_map(|b| &b.names) {
            let same = d.kind.value == k;
            if same && k != NameKind::Buf && d.name.value == name {
                let message = format!("the name `{name}` is given twice (first at line {})", d.line);
                return Err(self.refuse(DiagnosticKind::DuplicateName, line, message));
            }
            if !(same || (coordinates(d.kind.value) && coordinates(k))) {
                continue;
            }
            if let Some(n) = numbers.iter().find(|n| d.numbers.iter().any(|m| m.value == n.value)) {
                let message = format!("{} {} is named twice (first at line {})", k.word(), n.value, d.line);
                return Err(self.refuse(DiagnosticKind::DuplicateName, line, message));
            }
        }
        Ok(())
    }
}

/// A name as a deck writes one: a letter or `_`, then letters, digits and
/// `_`, at most [`MAX_NAME`] characters.
fn deck_name(b: &DeckBuilder, line: usize, name: &str) -> Result<String, Refused> {
    let mut chars = name.chars();
    let starts = chars.next().is_some_and(|c| c.is_ascii_alphabetic() || c == '_');
    if starts && chars.all(|c| c.is_ascii_alphanumeric() || c == '_') && name.chars().count() <= MAX_NAME {
        return Ok(name.to_string());
    }
    let message = format!(
        "`{name}` is not a name: a name starts with a letter or `_` and holds only letters, digits and `_`, at most \
         {MAX_NAME} characters"
    );
    Err(b.refuse(DiagnosticKind::BadName, line, message))
}

/// A buffer's label as the deck reads it from its line: printable, blanks
/// at either end dropped, at most [`MAX_LABEL`] characters.
fn label(b: &DeckBuilder, line: usize, text: &str) -> Result<String, Refused> {
    let t = text.trim_matches(|c| matches!(c, ' ' | '\t' | '\r' | '\x0c' | '\x0b'));
    let bad = t.chars().find(|&c| c.is_control() || is_format(c) || c == ';');
    if t.is_empty() || bad.is_some() || t.chars().count() > MAX_LABEL {
        let message = format!(
            "the label {text:?} is empty, holds a ';' or a character that does not print, or is \
                               longer than {MAX_LABEL} characters"
        );
        return Err(b.refuse(DiagnosticKind::BadLabel, line, message));
    }
    Ok(t.to_string())
}
