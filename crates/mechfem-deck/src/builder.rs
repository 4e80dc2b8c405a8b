//! A typed deck built item by item, without text: what a program that holds
//! a model in its own objects (the Python `Mechanism`) hands the deck
//! reader instead of writing deck text for it to parse.
//!
//! A [`DeckBuilder`] fills the same typed [`Deck`] that [`crate::parse_str`]
//! makes of deck text, and [`DeckBuilder::build`] compiles it with the same
//! [`crate::compile`], so a model built here and the deck text that says the
//! same things compile to the same [`Compiled`] model, to the last bit.
//! (mujoco's `mjSpec`, which its own XML reader fills, is the pattern.)
//!
//! Names and units (`names.rs`) go where a deck states them: the UNITS
//! line right below the mode line, the NAMES block after the geometry.
//!
//! The builder checks each value as the parser checks the word it reads
//! (`checks.rs`): a number the parser would refuse is refused here, with a
//! message that names the item by the name the caller gave it. Items take
//! the line numbers the deck text of the same items would give them, in the
//! order the deck's blocks stand (mode, TOPOLOGY, GEOMETRY, DYNAMICS,
//! MOVEMENT, STORAGE), so that what the compiled model keeps of its lines
//! (buffers, pictures, elements, FORM terms) is the same as well.

mod checks;
mod dynamics;
mod names;
mod storage;
#[cfg(test)]
mod tests;

use std::path::{Path, PathBuf};

use mechfem_core::dynamics::Integrator;
use mechfem_core::ElementType;

use crate::ast::{
    CoordDef, Deck, ElemDef, FormDef, Geometry, IntTolDef, Mode, MotionDef, MotionKind, Movement, ParaDef, StopWhenDef,
    Topology, Tstepe,
};
use crate::compiled::Compiled;
use crate::diagnostic::{Diagnostic, DiagnosticKind, Diagnostics, Span, Spanned};
use crate::keywords::Keyword;

use checks::Tolerance;

/// What one builder call refuses: a diagnostic whose line is the item's
/// (as the deck text of the same items numbers it) and whose message
/// names the item by the caller's name for it.
pub type Refused = Box<Diagnostic>;

/// A deck built item by item (see the module's documentation). Items are
/// added block by block, in the order of a deck: elements, FORM terms and
/// [`DeckBuilder::nrdof`]; co-ordinates and PARA values; then
/// [`DeckBuilder::dynamics`] and its items, [`DeckBuilder::movement`] and
/// its items, [`DeckBuilder::storage`] and its items, each block at most
/// once and all optional.
#[derive(Debug, Clone)]
pub struct DeckBuilder {
    deck: Deck,
    /// The line the last item took.
    line: usize,
    /// Elements so far.
    elements: i64,
    /// FORM terms so far (their sequence numbers).
    forms: i64,
    /// The block being filled.
    block: Option<Keyword>,
    /// Whether names were given: the geometry is complete.
    named: bool,
}

/// A span covering line `line` as a whole.
fn whole_line(line: usize) -> Span {
    Span::new(line, 0, 0)
}

/// `value` at the start of line `line`.
fn at<T>(value: T, line: usize) -> Spanned<T> {
    Spanned::new(value, whole_line(line))
}

impl DeckBuilder {
    /// An empty deck of `mode` (`KIN ANA`, `DYN ANA` or `DYN SIM`; a
    /// `KIN OPT` deck is read from text), named `path` in messages.
    pub fn new(path: impl Into<PathBuf>, mode: Mode) -> Result<DeckBuilder, Refused> {
        let path = path.into();
        let mut b = DeckBuilder {
            deck: Deck {
                path,
                mode: at(mode, 2),
                topology: Topology { line: 3, ..Topology::default() },
                geometry: Geometry::default(),
                dynamics: None,
                movement: None,
                optimise: None,
                storage: None,
                names: None,
                units: None,
                tolerance: None,
                scale: None,
                source: vec![String::new(), mode.name().to_string(), "TOPOLOGY".to_string()],
            },
            line: 3,
            elements: 0,
            forms: 0,
            block: Some(Keyword::Elem),
            named: false,
        };
        if mode == Mode::KinOpt {
            return Err(b.refuse(
                DiagnosticKind::WrongMode,
                2,
                "a KIN OPT model is not built item by item: its OPTIMISE block is read from deck text",
            ));
        }
        b.line = 3;
        Ok(b)
    }

    /// The next line, which `text` (the item in the caller's words) stands for in messages.
    fn next_line(&mut self, text: impl Into<String>) -> usize {
        self.line += 1;
        self.deck.source.push(text.into());
        self.line
    }

    fn refuse(&self, kind: DiagnosticKind, line: usize, message: impl Into<String>) -> Refused {
        self.deck.error(kind, whole_line(line), message)
    }

    /// Refuses an item of `block` after a later block was begun.
    fn in_block(&self, kw: Keyword, block: Keyword, what: &str) -> Result<(), Refused> {
        if self.block == Some(block) {
            return Ok(());
        }
        Err(self.refuse(
            DiagnosticKind::WrongBlock,
            self.line + 1,
            format!("{what} ({kw}) comes after the items of a later block: add items in the order of a deck"),
        ))
    }

    /// Refuses a geometry item after the names.
    fn before_names(&self, what: &str) -> Result<(), Refused> {
        if !self.named {
            return Ok(());
        }
        let message = format!("{what} comes after the names: add items in the order of a deck");
        Err(self.refuse(DiagnosticKind::WrongBlock, self.line + 1, message))
    }

    /// Element `k` (the next number) of type `ty` on the co-ordinates
    /// `coords` (deck numbers), called `name`.
    pub fn element(&mut self, ty: &str, coords: &[i64], name: Option<&str>) -> Result<(), Refused> {
        self.in_block(Keyword::Elem, Keyword::Elem, "an element")?;
        let line = self.next_line(name.unwrap_or_default());
        let label = checks::label("the element", name);
        let Some(t) = ElementType::from_name(ty) else {
            return Err(self.refuse(
                DiagnosticKind::UnknownElementType,
                line,
                format!("{label} has the unknown element type `{ty}`"),
            ));
        };
        let names = t.coord_names();
        if coords.len() != names.len() {
            return Err(self.refuse(
                DiagnosticKind::ArgumentCount,
                line,
                format!(
                    "{label}, of type {}, has {} co-ordinates ({}), got {}",
                    t.name(),
                    names.len(),
                    names.join(" "),
                    coords.len()
                ),
            ));
        }
        let coords = coords.iter().map(|&i| checks::whole(self, line, i, &label).map(|v| at(v, line)));
        let coords = coords.collect::<Result<Vec<_>, _>>()?;
        self.elements += 1;
        let elem = ElemDef { line, number: at(self.elements, line), ty: at(t, line), coords };
        self.deck.topology.elements.push(elem);
        Ok(())
    }

    /// A FORM term: `factor` times form parameter `form` of element
    /// `element`, into destination `dest` (prescribed row `dest > 0`,
    /// dependent form parameter `-dest`), of the row called `name`.
    pub fn form(
        &mut self,
        form: &str,
        element: i64,
        dest: i64,
        factor: f64,
        name: Option<&str>,
    ) -> Result<(), Refused> {
        self.in_block(Keyword::Form, Keyword::Elem, "a row's term")?;
        let line = self.next_line(name.unwrap_or_default());
        let label = checks::label("the row", name);
        checks::whole(self, line, element, &label)?;
        checks::whole(self, line, dest, &label)?;
        if dest == 0 {
            return Err(self.refuse(DiagnosticKind::ZeroDestination, line, format!("{label} has destination 0")));
        }
        checks::finite(self, line, factor, &format!("the factor of a term of {label}"))?;
        self.forms += 1;
        self.deck.topology.forms.push(FormDef {
            line,
            seq: at(self.forms, line),
            name: at(form.to_ascii_uppercase(), line),
            element: at(element, line),
            dest: at(dest, line),
            factor: Some(at(factor, line)),
        });
        Ok(())
    }

    /// The number of inputs (NRDOF), which ends the topology; the
    /// co-ordinates follow.
    pub fn nrdof(&mut self, n: i64) -> Result<(), Refused> {
        self.in_block(Keyword::Nrdof, Keyword::Elem, "the number of inputs")?;
        let line = self.next_line("NRDOF");
        if n < 1 {
            return Err(self.refuse(
                DiagnosticKind::BadValue,
                line,
                format!("the model has {n} inputs: make at least one form parameter an input"),
            ));
        }
        checks::whole(self, line, n, "the number of inputs")?;
        self.deck.topology.nrdof = Some(at(n, line));
        let header = self.next_line("GEOMETRY");
        self.deck.geometry.line = header;
        self.block = Some(Keyword::Xmov);
        Ok(())
    }

    /// Co-ordinate `number` (a deck number), moving or fixed, at `value`, called `name`.
    pub fn coordinate(&mut self, number: i64, value: f64, moving: bool, name: Option<&str>) -> Result<(), Refused> {
        let kw = if moving { Keyword::Xmov } else { Keyword::Xfix };
        self.in_block(kw, Keyword::Xmov, "a co-ordinate")?;
        self.before_names("a co-ordinate")?;
        let line = self.next_line(name.unwrap_or_default());
        let label = checks::label("the co-ordinate", name);
        checks::whole(self, line, number, &label)?;
        checks::finite(self, line, value, &format!("the value of {label}"))?;
        let coord = CoordDef { line, moving, index: at(number, line), value: at(value, line) };
        self.deck.geometry.coords.push(coord);
        Ok(())
    }

    /// The prescribed value (PARA) of row `row`, called `name`.
    pub fn para(&mut self, row: i64, value: f64, name: Option<&str>) -> Result<(), Refused> {
        self.in_block(Keyword::Para, Keyword::Xmov, "a prescribed value")?;
        self.before_names("a prescribed value")?;
        let line = self.next_line(name.unwrap_or_default());
        let label = checks::label("the row", name);
        checks::whole(self, line, row, &label)?;
        checks::finite(self, line, value, &format!("the prescribed value of {label}"))?;
        self.deck.geometry.paras.push(ParaDef { line, row: at(row, line), value: at(value, line) });
        Ok(())
    }

    /// Begins the motion: `steps` steps of time `dt` each.
    pub fn movement(&mut self, steps: i64, dt: f64) -> Result<(), Refused> {
        if !matches!(self.block, Some(Keyword::Xmov | Keyword::Mass)) {
            return Err(self.refuse(DiagnosticKind::WrongBlock, self.line + 1, "the motion is given twice"));
        }
        let header = self.next_line("MOVEMENT");
        let line = self.next_line("the motion's steps");
        checks::steps(self, line, steps, dt)?;
        let tstepe = Tstepe { line, steps: at(steps, line), dt: Some(at(dt, line)) };
        self.deck.movement = Some(Movement {
            line: header,
            tstepe,
            motions: Vec::new(),
            accuracy: None,
            maxiter: None,
            inttol: None,
            integrator: None,
            stop_when: None,
        });
        self.block = Some(Keyword::Tstepe);
        Ok(())
    }

    /// The motion of input `dof` (1-based), named `what`: `kind` is `by`
    /// (a change), `to` (an end value), `free` (a step length of free
    /// motion) or `dynamic` (moved by the forces from the initial velocity
    /// `value`).
    pub fn motion(&mut self, dof: i64, kind: &str, value: f64, what: &str) -> Result<(), Refused> {
        let kw = match kind {
            "by" => Keyword::MovRele,
            "to" => Keyword::MovAbse,
            "free" => Keyword::MovFree,
            "dynamic" => Keyword::MovDyn,
            _ => {
                let message = format!("the motion of {what} is of kind `{kind}`: give by, to, free or dynamic");
                return Err(self.refuse(DiagnosticKind::UnknownKeyword, self.line + 1, message));
            }
        };
        self.in_block(kw, Keyword::Tstepe, what)?;
        let line = self.next_line(what);
        checks::motion_mode(self, line, kw, what)?;
        checks::whole(self, line, dof, what)?;
        let v = match kw {
            Keyword::MovDyn => checks::bounded(self, line, value, &format!("the initial velocity of {what}"))?,
            _ => at(checks::finite(self, line, value, &format!("the motion of {what}"))?, line),
        };
        if kw == Keyword::MovFree && value == 0.0 {
            return Err(self.refuse(DiagnosticKind::BadValue, line, format!("the free motion of {what} has ds 0")));
        }
        let kind = match kw {
            Keyword::MovRele => MotionKind::Relative(v),
            Keyword::MovAbse => MotionKind::Absolute(v),
            Keyword::MovFree => MotionKind::Free(v),
            _ => MotionKind::Dynamic(v),
        };
        let def = MotionDef { line, keyword: at(kw, line), dof: at(dof, line), kind };
        if let Some(m) = self.deck.movement.as_mut() {
            m.motions.push(def);
        }
        Ok(())
    }

    /// The motion of input `dof` read from the table file `file` (relative
    /// to the folder [`DeckBuilder::build`] is given), named `what`.
    pub fn motion_table(&mut self, dof: i64, file: &str, what: &str) -> Result<(), Refused> {
        self.in_block(Keyword::MovFunc, Keyword::Tstepe, what)?;
        let line = self.next_line(what);
        checks::whole(self, line, dof, what)?;
        let file = checks::file_name(self, line, file, what)?;
        let def = MotionDef {
            line,
            keyword: at(Keyword::MovFunc, line),
            dof: at(dof, line),
            kind: MotionKind::Function(at(file, line)),
        };
        if let Some(m) = self.deck.movement.as_mut() {
            m.motions.push(def);
        }
        Ok(())
    }

    /// Newton's tolerance (ACCURACY) and iteration limit (MAXITER), each if
    /// given, and the integrator's tolerances `(rtol, atol)` (INTTOL) of a
    /// simulation, if given.
    pub fn tolerances(
        &mut self,
        accuracy: Option<f64>,
        max_iter: Option<i64>,
        inttol: Option<(f64, f64)>,
    ) -> Result<(), Refused> {
        self.in_block(Keyword::Accuracy, Keyword::Tstepe, "the motion's tolerances")?;
        if let Some(tol) = accuracy {
            let line = self.next_line("accuracy");
            let tol = checks::finite(self, line, tol, "the accuracy")?;
            if tol <= 0.0 {
                return Err(self.refuse(
                    DiagnosticKind::BadValue,
                    line,
                    format!("the accuracy must be positive, got {tol}"),
                ));
            }
            if let Some(m) = self.deck.movement.as_mut() {
                m.accuracy = Some(at(tol, line));
            }
        }
        if let Some(m) = max_iter {
            let line = self.next_line("max_iter");
            checks::max_iter(self, line, m)?;
            if let Some(mv) = self.deck.movement.as_mut() {
                mv.maxiter = Some(at(m, line));
            }
        }
        if let Some((rtol, atol)) = inttol {
            let line = self.next_line("rtol and atol");
            checks::motion_mode(self, line, Keyword::Inttol, "the integrator's tolerances")?;
            let rtol = checks::tolerance(self, line, rtol, Tolerance::Relative)?;
            let atol = checks::tolerance(self, line, atol, Tolerance::Absolute)?;
            if let Some(m) = self.deck.movement.as_mut() {
                m.inttol = Some(IntTolDef { line, rtol, atol });
            }
        }
        self.block = Some(Keyword::Accuracy);
        Ok(())
    }

    /// The number of the last item added (its line in the deck text of the
    /// same items): the line a diagnostic of this builder or of the built
    /// model names is the number of the item it is about, which the caller
    /// maps back to its own object.
    pub fn item(&self) -> usize {
        self.line
    }

    /// How a simulation is integrated (INTEGRATOR: a word of
    /// [`Integrator::WORDS`]) and the buffer and value whose crossing ends
    /// it (STOPWHEN), each if given; after [`Self::tolerances`]. Whether
    /// the buffer exists is checked when the deck is compiled.
    pub fn simulation(&mut self, integrator: Option<&str>, stop_when: Option<(i64, f64)>) -> Result<(), Refused> {
        self.in_block(Keyword::Integrator, Keyword::Accuracy, "the simulation's integrator")?;
        if let Some(word) = integrator {
            let line = self.next_line("integrator");
            checks::motion_mode(self, line, Keyword::Integrator, "the integrator")?;
            let Some(method) = Integrator::from_word(word) else {
                let message =
                    format!("{word:?} is not an integration method: give one of {}", Integrator::WORDS.join(", "));
                return Err(self.refuse(DiagnosticKind::BadValue, line, message));
            };
            if let Some(m) = self.deck.movement.as_mut() {
                m.integrator = Some(at(method, line));
            }
        }
        if let Some((buffer, value)) = stop_when {
            let line = self.next_line("stop_when");
            checks::motion_mode(self, line, Keyword::StopWhen, "the stop condition")?;
            if !(1..=i64::from(u32::MAX)).contains(&buffer) {
                let message = format!("the stop condition's buffer is {buffer}: give a buffer number from 1 up");
                return Err(self.refuse(DiagnosticKind::BadValue, line, message));
            }
            let value = checks::finite(self, line, value, "the stop condition's value")?;
            if let Some(m) = self.deck.movement.as_mut() {
                m.stop_when = Some(StopWhenDef { line, buffer: at(buffer, line), value: at(value, line) });
            }
        }
        Ok(())
    }

    /// The typed deck built so far.
    pub fn deck(&self) -> &Deck {
        &self.deck
    }

    /// Compiles the deck (see [`crate::compile`]); table files are read
    /// from `dir`. A dynamics mode needs the masses and loads, a simulation
    /// a motion.
    pub fn build(&self, dir: &Path) -> Result<Compiled, Diagnostics> {
        let mode = self.deck.mode.value;
        let missing = if mode.has_dynamics() && self.deck.dynamics.is_none() {
            Some("masses or loads")
        } else if mode == Mode::DynSim && self.deck.movement.is_none() {
            Some("motion")
        } else {
            None
        };
        if let Some(what) = missing {
            let message = format!("a {} model needs its {what}", mode.name());
            return Err(Diagnostics(vec![*self.refuse(DiagnosticKind::MissingBlock, 2, message)]));
        }
        crate::compile(&self.deck, dir)
    }
}
