//! Lines to a typed [`Deck`]: the mode line, block headers, keywords and the
//! repetition of a keyword by lines that start with a number.
//!
//! The parser checks everything that one line can tell on its own (argument
//! counts, numbers, element types, the element sequence, the place of
//! TSTEPE, the nesting of pictures). Cross-references between lines are left
//! to [`crate::compile`].

use std::path::{Path, PathBuf};

use crate::args::Source;
use crate::ast::{
    missing_dynamics, missing_movement, missing_optimise, Deck, Dynamics, Geometry, IntTolDef, Mode, MotionDef,
    Movement, NameKind, NamesBlock, Optimise, PictureDef, Storage, Topology, Tstepe, UnitsDef,
};
use crate::diagnostic::{Diagnostic, DiagnosticKind, Diagnostics, Hint, Span, Spanned};
use crate::files::read_deck;
use crate::keywords::{all_words, closest, Block, Keyword};
use crate::lexer::{lex, looks_numeric, source_lines, Line, Word};

/// The parser stops collecting after this many diagnostics.
const MAX_ERRORS: usize = 20;

/// Reads a deck from a file, up to its END line: a regular file of at most
/// [`MAX_DECK_BYTES`](crate::MAX_DECK_BYTES) before END ([`read_deck`]). The
/// path is kept as given and shown in diagnostics; MOV_FUNC files are later
/// looked up beside it.
pub fn parse_file(path: impl AsRef<Path>) -> Result<Deck, Diagnostics> {
    let path = path.as_ref();
    parse_str(&read_deck(path)?, path)
}

/// Reads a deck from text, up to its END line; `path` is only used in
/// diagnostics.
pub fn parse_str(text: &str, path: impl Into<PathBuf>) -> Result<Deck, Diagnostics> {
    let path = path.into();
    let raw = source_lines(text);
    let mut parser = Parser::new(Source { path: &path, lines: &raw });
    parser.run(lex(&raw));
    parser.finish().map(|mut deck| {
        deck.source = raw;
        deck
    })
}

/// The MOVEMENT block while it is being read.
#[derive(Default)]
pub(crate) struct MovementParts {
    pub line: usize,
    pub tstepe: Option<Tstepe>,
    pub motions: Vec<MotionDef>,
    pub accuracy: Option<Spanned<f64>>,
    pub maxiter: Option<Spanned<i64>>,
    pub inttol: Option<IntTolDef>,
    pub integrator: Option<Spanned<mechfem_core::dynamics::Integrator>>,
    pub stop_when: Option<crate::ast::StopWhenDef>,
    /// A missing or late TSTEPE has been reported.
    pub tstepe_reported: bool,
}

pub(crate) struct Parser<'a> {
    pub src: Source<'a>,
    pub errors: Vec<Diagnostic>,
    mode: Option<Spanned<Mode>>,
    block: Option<Block>,
    headers: [Option<usize>; Block::ALL.len()],
    /// The keyword a line starting with a number repeats.
    previous: Option<Keyword>,
    /// The previous keyword line was refused: its repetitions are skipped.
    poisoned: bool,
    /// A keyword alone on its line, waiting for repetition lines.
    pending: Option<(Keyword, Line)>,
    pub topology: Topology,
    pub geometry: Geometry,
    pub dynamics: Dynamics,
    pub movement: MovementParts,
    pub optimise: Optimise,
    pub tolerance: crate::ast::ToleranceBlock,
    pub storage: Storage,
    pub picture: Option<PictureDef>,
    /// ELEM lines seen so far, refused ones included.
    pub elem_lines: i64,
    /// Lines of NRDOF, ANIMATE, ... for "given twice" messages.
    pub once: Vec<(Keyword, usize)>,
    /// The NAMES block.
    pub names: NamesBlock,
    /// The kind a NAMES line starting with a number repeats.
    pub names_previous: Option<NameKind>,
    /// The names and numbers named so far.
    pub names_seen: crate::statements::names::NamesSeen,
    /// The UNITS line.
    pub units: Option<UnitsDef>,
}

impl<'a> Parser<'a> {
    fn new(src: Source<'a>) -> Self {
        Parser {
            src,
            errors: Vec::new(),
            mode: None,
            block: None,
            headers: [None; Block::ALL.len()],
            previous: None,
            poisoned: false,
            pending: None,
            topology: Topology::default(),
            geometry: Geometry::default(),
            dynamics: Dynamics::default(),
            movement: MovementParts::default(),
            optimise: Optimise::default(),
            tolerance: crate::ast::ToleranceBlock::default(),
            storage: Storage::default(),
            picture: None,
            elem_lines: 0,
            once: Vec::new(),
            names: NamesBlock::default(),
            names_previous: None,
            names_seen: Default::default(),
            units: None,
        }
    }

    fn error(&mut self, kind: DiagnosticKind, span: Span, message: impl Into<String>, hint: impl Into<String>) {
        let d = self.src.error(kind, span, message).with_hint(hint);
        self.errors.push(*d);
    }

    fn run(&mut self, mut lines: impl Iterator<Item = Line>) {
        let Some(first) = lines.next() else { return };
        if !self.mode_line(&first) {
            self.line(&first);
        }
        for line in lines {
            if self.errors.len() >= MAX_ERRORS || !self.line(&line) {
                break;
            }
        }
    }

    /// Reads the first line as the mode line; false when it is not one
    /// (it is then read as an ordinary line).
    fn mode_line(&mut self, line: &Line) -> bool {
        let first = &line.words[0];
        let upper = first.text.to_ascii_uppercase();
        let known = |w: &str| w == "END" || Block::from_name(w).is_some() || Keyword::from_name(w).is_some();
        if known(&upper) || looks_numeric(&upper) {
            self.error(
                DiagnosticKind::MissingMode,
                first.span,
                "the deck does not start with a mode line",
                "make `KIN ANA` the first line of the deck",
            );
            return false;
        }
        let last = line.words.last().map_or(first.span, |w| w.span);
        let span = first.span.to(line.words.get(1).map_or(first.span, |w| w.span));
        let second = line.words.get(1).map(|w| w.text.to_ascii_uppercase());
        let mode = match (upper.as_str(), second.as_deref()) {
            ("KIN", Some("ANA")) => Mode::KinAna,
            ("KIN", Some("OPT")) => Mode::KinOpt,
            ("DYN", Some("ANA")) => Mode::DynAna,
            ("DYN", Some("SIM")) => Mode::DynSim,
            _ => {
                let text: Vec<&str> = line.words.iter().map(|w| w.text.as_str()).collect();
                self.error(
                    DiagnosticKind::UnknownMode,
                    first.span.to(last),
                    format!("unknown mode `{}`", text.join(" ")),
                    "the first line gives the mode; mechfem runs `KIN ANA` (kinematic analysis), `KIN OPT` \
                     (design optimisation), `DYN ANA` (inverse dynamics) and `DYN SIM` (forward dynamics, a \
                     simulation)",
                );
                return true;
            }
        };
        if let Some(extra) = line.words.get(2) {
            self.error(
                DiagnosticKind::ArgumentCount,
                extra.span.to(last),
                format!("the mode line `{}` has extra words", mode.name()),
                "the mode line holds two words, such as `KIN ANA`",
            );
        }
        self.mode = Some(Spanned::new(mode, span));
        true
    }

    /// Reads one line; false after END.
    fn line(&mut self, line: &Line) -> bool {
        let first = &line.words[0];
        let upper = first.text.to_ascii_uppercase();
        if upper == "UNITS" {
            self.units_line(line);
            return true;
        }
        if self.block == Some(Block::Names) && upper != "END" && Block::from_name(&upper).is_none() {
            self.names_line(line);
            return true;
        }
        if looks_numeric(&first.text) {
            self.repetition(line);
            return true;
        }
        if upper == "END" {
            self.header_arguments("END", line);
            self.close_block();
            return false;
        }
        if let Some(block) = Block::from_name(&upper) {
            self.open_block(block, line);
        } else if let Some(kw) = Keyword::from_name(&upper) {
            self.keyword_line(kw, line, &line.words[1..], false);
        } else {
            self.unknown_keyword(first);
        }
        true
    }

    fn unknown_keyword(&mut self, word: &Word) {
        let hint = match closest(&word.text, all_words()) {
            Some(k) => format!("did you mean `{k}`?"),
            None => match self.block {
                Some(b) => {
                    let names: Vec<&str> = Keyword::of_block(b).map(Keyword::name).collect();
                    format!("the keywords of the {b} block are {}", names.join(", "))
                }
                None => {
                    let names: Vec<&str> = Block::ALL.iter().map(|b| b.name()).collect();
                    format!("the deck has the blocks {}", names.join(", "))
                }
            },
        };
        self.error(DiagnosticKind::UnknownKeyword, word.span, format!("unknown keyword `{}`", word.text), hint);
        self.previous = None;
        self.poisoned = true;
    }

    fn repetition(&mut self, line: &Line) {
        if let Some((kw, _)) = self.pending.take() {
            self.keyword_line(kw, line, &line.words, true);
        } else if self.poisoned {
            // The keyword to repeat was refused: so are its repetitions.
        } else if let Some(kw) = self.previous {
            self.keyword_line(kw, line, &line.words, true);
        } else if !self.errors.is_empty() {
            // Most likely a consequence of an earlier mistake (a keyword
            // refused or put in the wrong block): one message is enough.
            self.poisoned = true;
        } else {
            self.repeat_nothing(line);
        }
    }

    fn repeat_nothing(&mut self, line: &Line) {
        let hint = match self.block {
            Some(b) => {
                let names: Vec<&str> = Keyword::of_block(b).map(Keyword::name).collect();
                format!("start the line with a keyword of the {b} block: {}", names.join(", "))
            }
            None => "start the line with a keyword, after a block header such as TOPOLOGY".to_string(),
        };
        let place = self.block.map_or("before any block".to_string(), |b| format!("in the {b} block"));
        self.error(
            DiagnosticKind::NothingToRepeat,
            line.words[0].span,
            format!("this line starts with a number, so it repeats the previous keyword, but there is none {place}"),
            hint,
        );
        self.poisoned = true;
    }

    fn header_arguments(&mut self, name: &str, line: &Line) {
        if let (Some(first), Some(last)) = (line.words.get(1), line.words.last()) {
            self.error(
                DiagnosticKind::ArgumentCount,
                first.span.to(last.span),
                format!("{name} takes no arguments"),
                format!("put {name} alone on its line"),
            );
        }
    }

    fn open_block(&mut self, block: Block, line: &Line) {
        self.close_block();
        self.header_arguments(block.name(), line);
        let slot = &mut self.headers[block as usize];
        if let Some(first) = *slot {
            self.error(
                DiagnosticKind::DuplicateBlock,
                line.words[0].span,
                format!("the {block} block is given twice (first at line {first})"),
                format!("merge the two {block} blocks into one"),
            );
        } else {
            *slot = Some(line.number);
            match block {
                Block::Topology => self.topology.line = line.number,
                Block::Geometry => self.geometry.line = line.number,
                Block::Names => self.names.line = line.number,
                Block::Dynamics => self.dynamics.line = line.number,
                Block::Movement => self.movement.line = line.number,
                Block::Optimise => self.optimise.line = line.number,
                Block::Storage => self.storage.line = line.number,
                Block::Tolerance => self.tolerance.line = line.number,
            }
        }
        self.check_block_mode(block, line);
        if block == Block::Names {
            self.check_names_place(line);
            self.names_previous = None;
        }
        self.block = Some(block);
        self.previous = None;
        self.poisoned = false;
    }

    /// Refuses a block that the deck's mode does not have: DYNAMICS in a
    /// kinematic mode, OPTIMISE outside `KIN OPT`.
    fn check_block_mode(&mut self, block: Block, line: &Line) {
        let Some(mode) = self.mode() else { return };
        let span = line.words[0].span;
        let name = mode.name();
        if block == Block::Dynamics && !mode.has_dynamics() {
            let hint = if mode == Mode::KinOpt {
                "a KIN OPT deck optimises the kinematics only: remove the DYNAMICS block, or change the mode line to \
                 `DYN ANA` or `DYN SIM` to analyse the dynamics of one design"
            } else {
                "change the mode line to `DYN ANA` for inverse dynamics or `DYN SIM` for a simulation, or remove the \
                 DYNAMICS block"
            };
            let message = format!("a {name} deck has no DYNAMICS block: masses and loads belong to the dynamics modes");
            self.error(DiagnosticKind::WrongMode, span, message, hint);
        }
        if block == Block::Optimise && !matches!(mode, Mode::KinOpt | Mode::DynAna) {
            let message = format!(
                "a {name} deck has no OPTIMISE block: design variables and targets belong to the modes KIN OPT and \
                 DYN ANA"
            );
            let hint = format!(
                "change the mode line to `KIN OPT` to optimise the kinematics or `DYN ANA` to optimise the dynamics \
                 of a prescribed motion, or remove the OPTIMISE block to run {name} as it is"
            );
            self.error(DiagnosticKind::WrongMode, span, message, hint);
        }
        if block == Block::Tolerance && !matches!(mode, Mode::KinAna | Mode::DynAna) {
            let message = format!(
                "a {name} deck has no TOLERANCE block: tolerance bands belong to the analyses KIN ANA and DYN ANA"
            );
            let hint = format!(
                "run the design as `KIN ANA` (or `DYN ANA`) with the TOLERANCE block, or remove the block to run {name}"
            );
            self.error(DiagnosticKind::WrongMode, span, message, hint);
        }
    }

    /// Ends the current block: a bare keyword without repetition lines, an
    /// open picture, a MOVEMENT block without TSTEPE are reported.
    fn close_block(&mut self) {
        self.flush_pending();
        if let Some(pic) = self.picture.take() {
            let span =
                Span::new(pic.line, leading_blanks(self.src.lines, pic.line), line_width(self.src.lines, pic.line));
            self.error(
                DiagnosticKind::PictureStructure,
                span,
                "this picture has no ENDPIC",
                "add ENDPIC after the picture's last PLOT line",
            );
        }
        if self.block == Some(Block::Movement) && self.movement.tstepe.is_none() && !self.movement.tstepe_reported {
            let line = self.movement.line;
            self.movement.tstepe_reported = true;
            self.error(
                DiagnosticKind::MissingTstepe,
                Span::new(line, leading_blanks(self.src.lines, line), line_width(self.src.lines, line)),
                "the MOVEMENT block has no TSTEPE",
                "start the block with `TSTEPE n [dt]`: n steps of time dt; or remove the empty block",
            );
        }
        self.block = None;
    }

    fn flush_pending(&mut self) {
        if let Some((kw, line)) = self.pending.take() {
            let message = format!("{kw} expects {} arguments ({}), got 0", kw.arity_text(), kw.usage());
            let d = self.src.count_error(&line, &[], None, message).with_hint(format!(
                "give the arguments on this line, or on the lines below it that start with a number: {}",
                kw.synopsis()
            ));
            self.errors.push(*d);
        }
    }

    fn keyword_line(&mut self, kw: Keyword, line: &Line, args: &[Word], repeated: bool) {
        if !repeated {
            self.flush_pending();
            let right = kw.block();
            let wrong = match self.block {
                None => Some(format!("{kw} stands before any block header")),
                Some(b) if !kw.allowed_in(b) => Some(format!("{kw} belongs in the {right} block, not in {b}")),
                Some(_) => None,
            };
            if let Some(message) = wrong {
                let hint = format!("move it below the `{right}` header");
                self.error(DiagnosticKind::WrongBlock, line.words[0].span, message, hint);
                self.previous = Some(kw);
                self.poisoned = true;
                return;
            }
            self.previous = Some(kw);
            self.poisoned = false;
            if args.is_empty() && kw.arity().0 > 0 {
                self.pending = Some((kw, line.clone()));
                return;
            }
        }
        let keyword = Spanned::new(kw, line.words[0].span);
        if let Err(d) = self.statement(keyword, line, args, repeated) {
            self.errors.push(*d);
        }
    }

    /// The block being read.
    pub(crate) fn block(&self) -> Option<Block> {
        self.block
    }

    /// The deck's mode, once the mode line has been read.
    pub(crate) fn mode(&self) -> Option<Mode> {
        self.mode.map(|m| m.value)
    }

    /// Records the line of a keyword that may appear once; errs when it
    /// was there before.
    pub(crate) fn once(&mut self, kw: Spanned<Keyword>) -> Result<(), Box<Diagnostic>> {
        if let Some(&(_, first)) = self.once.iter().find(|(k, _)| *k == kw.value) {
            let k = kw.value;
            return Err(self
                .src
                .error(DiagnosticKind::DuplicateKeyword, kw.span, format!("{k} is given twice (first at line {first})"))
                .with_hint(format!("keep one {k} line")));
        }
        self.once.push((kw.value, kw.span.line));
        Ok(())
    }

    fn finish(mut self) -> Result<Deck, Diagnostics> {
        self.close_block();
        let path = self.src.path;
        if self.mode.is_none() && self.errors.is_empty() {
            let d = Diagnostic::file(DiagnosticKind::MissingMode, path, "the deck is empty")
                .with_hint("a deck starts with the mode line `KIN ANA`, followed by the TOPOLOGY and GEOMETRY blocks");
            self.errors.push(d);
        }
        for block in [Block::Topology, Block::Geometry] {
            if self.headers[block as usize].is_none() && self.mode.is_some() {
                let d = Diagnostic::file(DiagnosticKind::MissingBlock, path, format!("the deck has no {block} block"))
                    .with_hint(format!("add a line `{block}` followed by its keywords"));
                self.errors.push(d);
            }
        }
        if let Some(mode) = self.mode {
            let missing = |block: Block| self.headers[block as usize].is_none();
            let lines = self.src.lines;
            let mut found = Vec::new();
            if mode.value.has_dynamics() && missing(Block::Dynamics) {
                found.push(missing_dynamics(path, lines, mode.value, mode.span));
            }
            if matches!(mode.value, Mode::DynSim | Mode::KinOpt) && missing(Block::Movement) {
                found.push(missing_movement(path, lines, mode.value, mode.span));
            }
            if mode.value == Mode::KinOpt && missing(Block::Optimise) {
                found.push(missing_optimise(path, lines, mode.span));
            }
            self.errors.extend(found.into_iter().map(|d| *d));
        }
        self.errors.sort_by_key(|d| (d.line == 0, d.line));
        let (Some(mode), true) = (self.mode, self.errors.is_empty()) else {
            return Err(Diagnostics(self.errors));
        };
        let m = self.movement;
        let movement = match (self.headers[Block::Movement as usize], m.tstepe) {
            (Some(line), Some(tstepe)) => Some(Movement {
                line,
                tstepe,
                motions: m.motions,
                accuracy: m.accuracy,
                maxiter: m.maxiter,
                inttol: m.inttol,
                integrator: m.integrator,
                stop_when: m.stop_when,
            }),
            _ => None,
        };
        Ok(Deck {
            path: path.to_path_buf(),
            mode,
            topology: self.topology,
            geometry: self.geometry,
            dynamics: self.headers[Block::Dynamics as usize].map(|_| self.dynamics),
            movement,
            optimise: self.headers[Block::Optimise as usize].map(|_| self.optimise),
            storage: self.headers[Block::Storage as usize].map(|_| self.storage),
            names: self.headers[Block::Names as usize].map(|_| self.names),
            units: self.units,
            tolerance: self.headers[Block::Tolerance as usize].map(|_| self.tolerance),
            scale: None,
            source: Vec::new(),
        })
    }
}

/// Number of blank characters at the start of a line.
fn leading_blanks(lines: &[String], line: usize) -> usize {
    line.checked_sub(1).and_then(|k| lines.get(k)).map_or(0, |t| t.chars().take_while(|c| c.is_whitespace()).count())
}

/// Number of characters of a line without trailing blanks and comment.
fn line_width(lines: &[String], line: usize) -> usize {
    line.checked_sub(1)
        .and_then(|k| lines.get(k))
        .map_or(0, |t| t.split(';').next().unwrap_or("").trim_end().chars().count())
}

#[cfg(test)]
mod tests {
    use super::*;

    const HEAD: &str = "KIN ANA\nTOPOLOGY\nELEM 1 BIN 1 2 3 4\nFORM 1 LENL 1 1\nNRDOF 1\n";

    fn parse(text: &str) -> Result<Deck, Diagnostics> {
        parse_str(text, "t.mec")
    }

    #[test]
    fn a_number_line_repeats_the_previous_keyword() {
        let deck = parse(&format!("{HEAD}GEOMETRY\nXFIX 1 0\n 2 0\nXMOV 3 1\n\t4\t2\n")).unwrap();
        let moving: Vec<_> = deck.geometry.coords.iter().map(|c| (c.index.value, c.moving)).collect();
        assert_eq!(moving, [(1, false), (2, false), (3, true), (4, true)]);
    }

    #[test]
    fn a_keyword_alone_waits_for_number_lines() {
        let deck = parse(&format!("{HEAD}GEOMETRY\nXFIX\n 1 0\n 2 0\n")).unwrap();
        assert_eq!(deck.geometry.coords.len(), 2);
        assert_eq!(deck.geometry.coords[1].line, 9);
    }

    #[test]
    fn a_keyword_alone_without_number_lines_is_an_error() {
        let err = parse(&format!("{HEAD}GEOMETRY\nXFIX\nXMOV 1 0\n")).unwrap_err();
        assert_eq!(err.0.len(), 1);
        assert_eq!(err.0[0].kind, DiagnosticKind::ArgumentCount);
        assert_eq!(err.0[0].line, 7);
    }

    #[test]
    fn repetition_does_not_cross_a_block_header() {
        let err = parse(&format!("{HEAD}GEOMETRY\n 1 0\n")).unwrap_err();
        assert_eq!(err.0[0].kind, DiagnosticKind::NothingToRepeat);
    }

    #[test]
    fn repetitions_of_a_refused_keyword_are_skipped() {
        let err = parse(&format!("{HEAD}GEOMETRY\nXFX 1 0\n 2 0\n 3 0\n")).unwrap_err();
        assert_eq!(err.0.len(), 1);
        assert_eq!(err.0[0].kind, DiagnosticKind::UnknownKeyword);
        assert_eq!(err.0[0].hint.as_deref(), Some("did you mean `XFIX`?"));
    }

    #[test]
    fn independent_mistakes_are_all_reported() {
        let err = parse(&format!("{HEAD}GEOMETRY\nXFIX 1 zero\nXMOV 2 1 1\n")).unwrap_err();
        let kinds: Vec<_> = err.iter().map(|d| d.kind).collect();
        assert_eq!(kinds, [DiagnosticKind::NotANumber, DiagnosticKind::ArgumentCount]);
    }

    #[test]
    fn keywords_and_modes_are_case_insensitive() {
        let deck =
            parse("kin ana\ntopology\nelem 1 bin 1 2 3 4\nform 1 lenl 1 1\nnrdof 1\ngeometry\nxfix 1 0\n").unwrap();
        assert_eq!(deck.mode.value, Mode::KinAna);
        assert_eq!(deck.topology.forms[0].name.value, "LENL");
    }

    #[test]
    fn lines_after_end_are_ignored() {
        let deck = parse(&format!("{HEAD}GEOMETRY\nXFIX 1 0\nEND\nwhatever follows\n")).unwrap();
        assert_eq!(deck.geometry.coords.len(), 1);
    }
}
