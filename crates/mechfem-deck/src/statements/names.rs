//! The lines of the NAMES block and the UNITS line: what one line can tell
//! on its own (the kind, the numbers, the name's spelling and length, a
//! name given twice within its kind, a unit that does not exist). Whether
//! the numbers exist in the model is checked by [`crate::compile`].

use std::collections::HashMap;

use mechfem_core::units::{Angle, Force, Length, Mass, Time};
use mechfem_core::Units;

use crate::ast::{NameDef, NameKind, UnitsDef};
use crate::diagnostic::{is_format, Diagnostic, DiagnosticKind, Hint, Span, Spanned};
use crate::keywords::closest;
use crate::lexer::{looks_numeric, Line};
use crate::parse::Parser;

/// The longest name, in characters.
pub const MAX_NAME: usize = 40;
/// The longest buffer label, in characters.
pub const MAX_LABEL: usize = 60;

/// The names and numbers the NAMES block has given so far, with their lines.
#[derive(Default)]
pub(crate) struct NamesSeen {
    names: HashMap<(NameKind, String), usize>,
    numbers: HashMap<(NameKind, i64), usize>,
}

/// The fields of UNITS, in the order of [`UnitsDef::spans`].
const FIELDS: [&str; 5] = ["LENGTH", "ANGLE", "MASS", "FORCE", "TIME"];

impl Parser<'_> {
    /// Refuses a NAMES block before TOPOLOGY: its numbers name what
    /// TOPOLOGY declares.
    pub(crate) fn check_names_place(&mut self, line: &Line) {
        if self.topology.line == 0 {
            let d = self
                .src
                .error(DiagnosticKind::WrongBlock, line.words[0].span, "the NAMES block stands before TOPOLOGY")
                .with_hint(
                    "move the NAMES block below GEOMETRY: it names the points, elements and rows that TOPOLOGY and \
                     GEOMETRY declare",
                );
            self.errors.push(*d);
        }
    }

    /// One line of the NAMES block; a line starting with a number repeats
    /// the kind of the line above.
    pub(crate) fn names_line(&mut self, line: &Line) {
        let first = &line.words[0];
        let (kind, args) = if looks_numeric(&first.text) {
            match self.names_previous {
                Some(kind) => (Spanned::new(kind, first.span), &line.words[..]),
                None => {
                    self.push(self.unknown_kind(first.span, &first.text));
                    return;
                }
            }
        } else {
            match NameKind::from_word(&first.text) {
                Some(kind) => (Spanned::new(kind, first.span), &line.words[1..]),
                None => {
                    self.names_previous = None;
                    self.push(self.unknown_kind(first.span, &first.text));
                    return;
                }
            }
        };
        self.names_previous = Some(kind.value);
        if let Err(d) = self.name_def(line, kind, args) {
            self.push(d);
        }
    }

    fn push(&mut self, d: Box<Diagnostic>) {
        self.errors.push(*d);
    }

    fn unknown_kind(&self, span: Span, word: &str) -> Box<Diagnostic> {
        let words = NameKind::ALL.map(NameKind::word);
        let hint = match closest(word, words) {
            Some(k) => format!("did you mean `{k}`? A NAMES line is one of {}", usages()),
            None => format!("a NAMES line is one of {}", usages()),
        };
        self.src.error(DiagnosticKind::UnknownNameKind, span, format!("`{word}` is not a kind of name")).with_hint(hint)
    }

    fn name_def(
        &mut self,
        line: &Line,
        kind: Spanned<NameKind>,
        args: &[crate::lexer::Word],
    ) -> Result<(), Box<Diagnostic>> {
        let k = kind.value;
        let n = k.numbers();
        if args.len() < n + 1 || (k != NameKind::Buf && args.len() > n + 1) {
            let message =
                format!("{} expects {} numbers and a name ({}), got {} words", k.word(), n, k.usage(), args.len());
            let surplus = (args.len() > n + 1).then_some(n + 1);
            return Err(self.src.count_error(line, args, surplus, message).with_hint(format!("usage: {}", k.usage())));
        }
        let mut numbers = Vec::with_capacity(n);
        for w in &args[..n] {
            let v = self.src.whole(w, "the number")?;
            let v = if k == NameKind::Dep && v.value < 0 { Spanned::new(-v.value, v.span) } else { v };
            if v.value < 1 {
                return Err(self
                    .src
                    .error(DiagnosticKind::NameOutOfRange, v.span, format!("{} {} names nothing", k.word(), v.value))
                    .with_hint(format!("the numbers of {} start at 1: {}", k.word(), k.usage())));
            }
            numbers.push(v);
        }
        let name = if k == NameKind::Buf {
            let (a, b) = (&args[n], &args[args.len() - 1]);
            let text: String =
                self.src.lines[line.number - 1].chars().skip(a.span.start).take(b.span.end - a.span.start).collect();
            let label = Spanned::new(text, a.span.to(b.span));
            self.check_label(&label)?;
            label
        } else {
            let w = &args[n];
            let name = Spanned::new(w.text.clone(), w.span);
            self.check_name(k, &name)?;
            name
        };
        self.check_unique(k, line.number, &numbers, &name)?;
        self.names.names.push(NameDef { line: line.number, kind, numbers, name });
        Ok(())
    }

    fn check_name(&self, k: NameKind, name: &Spanned<String>) -> Result<(), Box<Diagnostic>> {
        let text = &name.value;
        let mut chars = text.chars();
        let starts = chars.next().is_some_and(|c| c.is_ascii_alphabetic() || c == '_');
        if !starts || !chars.all(|c| c.is_ascii_alphanumeric() || c == '_') {
            let suggestion: String =
                text.chars().map(|c| if c.is_ascii_alphanumeric() || c == '_' { c } else { '_' }).collect();
            let suggestion = if suggestion.starts_with(|c: char| c.is_ascii_digit()) {
                format!("_{suggestion}")
            } else {
                suggestion
            };
            return Err(self
                .src
                .error(DiagnosticKind::BadName, name.span, format!("`{text}` is not a name"))
                .with_hint(format!(
                    "a name starts with a letter or `_` and holds only letters, digits and `_` (no blanks, dots or \
                     hyphens), e.g. `{suggestion}`; {} names {}",
                    k.word(),
                    what(k)
                )));
        }
        let count = text.chars().count();
        if count > MAX_NAME {
            return Err(self
                .src
                .error(
                    DiagnosticKind::BadName,
                    name.span,
                    format!("the name `{text}` has {count} characters, more than {MAX_NAME}"),
                )
                .with_hint(format!("shorten the name to at most {MAX_NAME} characters")));
        }
        Ok(())
    }

    fn check_label(&self, label: &Spanned<String>) -> Result<(), Box<Diagnostic>> {
        let text = &label.value;
        if let Some(c) = text.chars().find(|&c| c.is_control() || is_format(c)) {
            return Err(self
                .src
                .error(
                    DiagnosticKind::BadLabel,
                    label.span,
                    format!("the label holds the character U+{:04X}, which does not print", u32::from(c)),
                )
                .with_hint("write the label in printable characters only (blanks are fine; no tabs)"));
        }
        let count = text.chars().count();
        if count > MAX_LABEL {
            return Err(self
                .src
                .error(
                    DiagnosticKind::BadLabel,
                    label.span,
                    format!("the label has {count} characters, more than {MAX_LABEL}"),
                )
                .with_hint(format!(
                    "shorten the label to at most {MAX_LABEL} characters: it heads a column and labels an axis"
                )));
        }
        Ok(())
    }

    /// A name given twice within its kind, or a thing named twice (looked
    /// up, so that a deck of many names is read in linear time).
    fn check_unique(
        &mut self,
        k: NameKind,
        line: usize,
        numbers: &[Spanned<i64>],
        name: &Spanned<String>,
    ) -> Result<(), Box<Diagnostic>> {
        if k != NameKind::Buf {
            if let Some(&first) = self.names_seen.names.get(&(k, name.value.clone())) {
                return Err(self
                    .src
                    .error(
                        DiagnosticKind::DuplicateName,
                        name.span,
                        format!("the name `{}` is given to two {} (first at line {first})", name.value, plural(k)),
                    )
                    .with_hint(format!("give every {} its own name", singular(k))));
            }
        }
        // Points and single co-ordinates name the same things.
        let group = match k {
            NameKind::Point | NameKind::Coord => NameKind::Coord,
            other => other,
        };
        for n in numbers {
            if let Some(&first) = self.names_seen.numbers.get(&(group, n.value)) {
                let thing = match group {
                    NameKind::Elem => "element",
                    NameKind::Row => "row",
                    NameKind::Dep => "dependent form parameter",
                    NameKind::Buf => "buffer",
                    NameKind::Point | NameKind::Coord => "co-ordinate",
                };
                return Err(self
                    .src
                    .error(
                        DiagnosticKind::DuplicateName,
                        n.span,
                        format!("{thing} {} is named twice (first at line {first})", n.value),
                    )
                    .with_hint(format!("keep one name for {thing} {}", n.value)));
            }
        }
        if k != NameKind::Buf {
            self.names_seen.names.insert((k, name.value.clone()), line);
        }
        for n in numbers {
            self.names_seen.numbers.insert((group, n.value), line);
        }
        Ok(())
    }

    /// `UNITS LENGTH mm ANGLE deg MASS kg FORCE N TIME s`, every field optional.
    pub(crate) fn units_line(&mut self, line: &Line) {
        if let Err(d) = self.units_def(line) {
            self.push(d);
        }
    }

    fn units_def(&mut self, line: &Line) -> Result<(), Box<Diagnostic>> {
        let word = &line.words[0];
        if let Some(first) = &self.units {
            return Err(self
                .src
                .error(
                    DiagnosticKind::DuplicateKeyword,
                    word.span,
                    format!("UNITS is given twice (first at line {})", first.line),
                )
                .with_hint("keep one UNITS line"));
        }
        let mut units = Units { declared: true, ..Units::NONE };
        let mut spans: [Option<Span>; 5] = [None; 5];
        let args = &line.words[1..];
        if args.is_empty() {
            return Err(self
                .src
                .error(DiagnosticKind::ArgumentCount, line.end(), "UNITS names no unit")
                .with_hint(units_usage()));
        }
        for pair in args.chunks(2) {
            let field = &pair[0];
            let Some(k) = FIELDS.iter().position(|f| f.eq_ignore_ascii_case(&field.text)) else {
                let hint = match closest(&field.text, FIELDS) {
                    Some(f) => format!("did you mean `{f}`? {}", units_usage()),
                    None => units_usage(),
                };
                return Err(self
                    .src
                    .error(DiagnosticKind::UnknownUnit, field.span, format!("`{}` is not a kind of unit", field.text))
                    .with_hint(hint));
            };
            let Some(value) = pair.get(1) else {
                return Err(self
                    .src
                    .error(DiagnosticKind::ArgumentCount, line.end(), format!("{} has no unit", FIELDS[k]))
                    .with_hint(format!("give the unit after {}: {}", FIELDS[k], allowed(k))));
            };
            if let Some(first) = spans[k] {
                return Err(self
                    .src
                    .error(
                        DiagnosticKind::DuplicateKeyword,
                        field.span,
                        format!("{} is given twice on the UNITS line (first at column {})", FIELDS[k], first.start + 1),
                    )
                    .with_hint(format!("keep one {}", FIELDS[k])));
            }
            let v = value.text.as_str();
            let ok = match k {
                0 => find(Length::ALL, Length::symbol, v).map(|x| units.length = Some(x)),
                1 => find(Angle::ALL, Angle::symbol, v).map(|x| units.angle = Some(x)),
                2 => find(Mass::ALL, Mass::symbol, v).map(|x| units.mass = Some(x)),
                3 => find(Force::ALL, Force::symbol, v).map(|x| units.force = Some(x)),
                _ => find(Time::ALL, Time::symbol, v).map(|x| units.time = Some(x)),
            };
            if ok.is_none() {
                return Err(self
                    .src
                    .error(
                        DiagnosticKind::UnknownUnit,
                        value.span,
                        format!("`{v}` is not a unit of {}", FIELDS[k].to_ascii_lowercase()),
                    )
                    .with_hint(format!("{} is one of {}", FIELDS[k], allowed(k))));
            }
            spans[k] = Some(value.span);
        }
        self.units = Some(UnitsDef { line: line.number, units, spans });
        Ok(())
    }
}

/// The unit of `all` written `v` (case-insensitive: `MM`, `KN`).
fn find<T: Copy>(all: &[T], symbol: fn(T) -> &'static str, v: &str) -> Option<T> {
    all.iter().copied().find(|&u| symbol(u).eq_ignore_ascii_case(v))
}

/// The units allowed for field k of UNITS.
fn allowed(k: usize) -> String {
    let symbols: Vec<&str> = match k {
        0 => Length::ALL.iter().map(|u| u.symbol()).collect(),
        1 => Angle::ALL.iter().map(|u| u.symbol()).collect(),
        2 => Mass::ALL.iter().map(|u| u.symbol()).collect(),
        3 => Force::ALL.iter().map(|u| u.symbol()).collect(),
        _ => Time::ALL.iter().map(|u| u.symbol()).collect(),
    };
    symbols.iter().map(|s| format!("`{s}`")).collect::<Vec<_>>().join(", ")
}

fn units_usage() -> String {
    "UNITS takes pairs of a kind and its unit, each optional, in any order: `UNITS LENGTH mm ANGLE deg MASS kg FORCE \
     N TIME s` (LENGTH m, mm, cm or in; ANGLE rad or deg; MASS kg or g; FORCE N or kN; TIME s or ms)"
        .to_string()
}

fn usages() -> String {
    NameKind::ALL.map(|k| format!("`{}`", k.usage())).join(", ")
}

fn plural(k: NameKind) -> &'static str {
    match k {
        NameKind::Point => "points",
        NameKind::Coord => "co-ordinates",
        NameKind::Elem => "elements",
        NameKind::Row => "rows",
        NameKind::Dep => "dependent form parameters",
        NameKind::Buf => "buffers",
    }
}

fn singular(k: NameKind) -> &'static str {
    match k {
        NameKind::Point => "point",
        NameKind::Coord => "co-ordinate",
        NameKind::Elem => "element",
        NameKind::Row => "row",
        NameKind::Dep => "dependent form parameter",
        NameKind::Buf => "buffer",
    }
}

fn what(k: NameKind) -> &'static str {
    match k {
        NameKind::Point => "the point of two co-ordinates",
        NameKind::Coord => "a single co-ordinate",
        NameKind::Elem => "an element",
        NameKind::Row => "a prescribed row",
        NameKind::Dep => "a dependent form parameter",
        NameKind::Buf => "a buffer",
    }
}
