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
mod names;
#[cfg(test)]
mod tests;

use std::path::{Path, PathBuf};

use mechfem_core::ElementType;

use crate::ast::{
    BufDef, BufList, CoordDef, Deck, Dynamics, ElemDef, ForceDef, FormDef, Geometry, GravityDef, InertiaDef, IntTolDef,
    LoadDef, LoadDefKind, MassDef, Mode, MotionDef, MotionKind, Movement, ParaDef, PictureDef, PlotDef, PointMassDef,
    Storage, Topology, Tstepe,
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
    pub fn form(&mut self, form: &str, element: i64, dest: i64, factor: f64, name: Option<&str>) -> Result<(), Refused> {
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

    /// Begins the masses and loads (DYNAMICS), which a dynamics mode needs.
    pub fn dynamics(&mut self) -> Result<(), Refused> {
        self.in_block(Keyword::Mass, Keyword::Xmov, "the masses and loads")?;
        let line = self.next_line("DYNAMICS");
        let mode = self.deck.mode.value;
        if !mode.has_dynamics() {
            return Err(self.refuse(
                DiagnosticKind::WrongMode,
                line,
                format!("a {} model has no masses or loads", mode.name()),
            ));
        }
        self.deck.dynamics = Some(Dynamics { line, ..Dynamics::default() });
        self.block = Some(Keyword::Mass);
        Ok(())
    }

    fn dynamics_block(&mut self, kw: Keyword, what: &str) -> Result<(usize, String), Refused> {
        self.in_block(kw, Keyword::Mass, what)?;
        let line = self.next_line(what);
        Ok((line, what.to_string()))
    }

    fn dyn_mut(&mut self) -> &mut Dynamics {
        self.deck.dynamics.get_or_insert_with(Dynamics::default)
    }

    /// A body's mass `mass` with centre of mass (`u`, `v`) in the frame of
    /// element `element` and moment of inertia `inertia`, named `what`.
    pub fn mass(&mut self, element: i64, mass: f64, u: f64, v: f64, inertia: f64, what: &str) -> Result<(), Refused> {
        let (line, w) = self.dynamics_block(Keyword::Mass, what)?;
        checks::whole(self, line, element, &w)?;
        let mass = checks::not_negative(self, line, mass, &format!("the mass of {w}"))?;
        let u = checks::bounded(self, line, u, &format!("the centre of mass u of {w}"))?;
        let v = checks::bounded(self, line, v, &format!("the centre of mass v of {w}"))?;
        let inertia = checks::not_negative(self, line, inertia, &format!("the moment of inertia of {w}"))?;
        let def = MassDef { line, element: at(element, line), mass, u, v, inertia: Some(inertia) };
        self.dyn_mut().masses.push(def);
        Ok(())
    }

    /// A point mass `mass` at the point of co-ordinates `x`, `y`, named `what`.
    pub fn point_mass(&mut self, x: i64, y: i64, mass: f64, what: &str) -> Result<(), Refused> {
        let (line, w) = self.dynamics_block(Keyword::Pmass, what)?;
        let (x, y) = checks::point(self, line, x, y, &w)?;
        let mass = checks::not_negative(self, line, mass, &format!("the mass of {w}"))?;
        self.dyn_mut().point_masses.push(PointMassDef { line, x, y, mass });
        Ok(())
    }

    /// A moment of inertia `inertia` on the angle co-ordinate `coord`, named `what`.
    pub fn inertia(&mut self, coord: i64, inertia: f64, what: &str) -> Result<(), Refused> {
        let (line, w) = self.dynamics_block(Keyword::Inertia, what)?;
        checks::whole(self, line, coord, &w)?;
        let inertia = checks::not_negative(self, line, inertia, &format!("the moment of inertia of {w}"))?;
        self.dyn_mut().inertias.push(InertiaDef { line, coord: at(coord, line), inertia });
        Ok(())
    }

    /// The acceleration of gravity (`gx`, `gy`), given once.
    pub fn gravity(&mut self, gx: f64, gy: f64) -> Result<(), Refused> {
        let (line, w) = self.dynamics_block(Keyword::Gravity, "gravity")?;
        if self.deck.dynamics.as_ref().is_some_and(|d| d.gravity.is_some()) {
            return Err(self.refuse(DiagnosticKind::DuplicateKeyword, line, "gravity is given twice"));
        }
        let gx = checks::bounded(self, line, gx, &format!("the acceleration of {w}"))?;
        let gy = checks::bounded(self, line, gy, &format!("the acceleration of {w}"))?;
        self.dyn_mut().gravity = Some(GravityDef { line, gx, gy });
        Ok(())
    }

    /// A constant force (`fx`, `fy`) at the point of co-ordinates `x`, `y`, named `what`.
    pub fn force(&mut self, x: i64, y: i64, fx: f64, fy: f64, what: &str) -> Result<(), Refused> {
        let (line, w) = self.dynamics_block(Keyword::Force, what)?;
        let (x, y) = checks::point(self, line, x, y, &w)?;
        let fx = checks::bounded(self, line, fx, &format!("the force of {w}"))?;
        let fy = checks::bounded(self, line, fy, &format!("the force of {w}"))?;
        self.dyn_mut().forces.push(ForceDef { line, x, y, fx, fy });
        Ok(())
    }

    fn load_def(&mut self, kw: Keyword, row: i64, what: &str, kind: impl FnOnce(&Self, usize, &str) -> Result<LoadDefKind, Refused>) -> Result<(), Refused> {
        let (line, w) = self.dynamics_block(kw, what)?;
        checks::whole(self, line, row, &w)?;
        let kind = kind(self, line, &w)?;
        let def = LoadDef { line, keyword: at(kw, line), form: at(row, line), kind };
        self.dyn_mut().loads.push(def);
        Ok(())
    }

    /// A constant generalised force `value` on row `row`, named `what`.
    pub fn load(&mut self, row: i64, value: f64, what: &str) -> Result<(), Refused> {
        self.load_def(Keyword::Load, row, what, |b, line, w| {
            Ok(LoadDefKind::Constant(checks::bounded(b, line, value, &format!("the load on {w}"))?))
        })
    }

    /// A generalised force on row `row` read from the table file `file`
    /// (relative to the folder [`DeckBuilder::build`] is given), named `what`.
    pub fn load_table(&mut self, row: i64, file: &str, what: &str) -> Result<(), Refused> {
        self.load_def(Keyword::LoadFunc, row, what, |b, line, w| {
            Ok(LoadDefKind::Function(at(checks::file_name(b, line, file, w)?, line)))
        })
    }

    /// A spring of stiffness `k` and free value `e0` with damping `c` on row `row`, named `what`.
    pub fn spring(&mut self, row: i64, k: f64, e0: f64, c: f64, what: &str) -> Result<(), Refused> {
        self.load_def(Keyword::Spring, row, what, |b, line, w| {
            Ok(LoadDefKind::Spring {
                k: checks::not_negative(b, line, k, &format!("the stiffness of {w}"))?,
                e0: checks::bounded(b, line, e0, &format!("the free value of {w}"))?,
                c: Some(checks::not_negative(b, line, c, &format!("the damping of {w}"))?),
            })
        })
    }

    /// A motor of stall torque `t0` and no-load speed `w0` on row `row`, named `what`.
    pub fn motor(&mut self, row: i64, t0: f64, w0: f64, what: &str) -> Result<(), Refused> {
        self.load_def(Keyword::Motor, row, what, |b, line, w| {
            let t0 = checks::bounded(b, line, t0, &format!("the stall torque of {w}"))?;
            let w0 = checks::bounded(b, line, w0, &format!("the no-load speed of {w}"))?;
            if w0.value == 0.0 {
                return Err(b.refuse(DiagnosticKind::BadValue, line, format!("the no-load speed of {w} is 0")));
            }
            Ok(LoadDefKind::Motor { t0, w0 })
        })
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
        self.deck.movement =
            Some(Movement { line: header, tstepe, motions: Vec::new(), accuracy: None, maxiter: None, inttol: None });
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
        self.deck.movement.as_mut().map(|m| m.motions.push(def));
        Ok(())
    }

    /// The motion of input `dof` read from the table file `file` (relative
    /// to the folder [`DeckBuilder::build`] is given), named `what`.
    pub fn motion_table(&mut self, dof: i64, file: &str, what: &str) -> Result<(), Refused> {
        self.in_block(Keyword::MovFunc, Keyword::Tstepe, what)?;
        let line = self.next_line(what);
        checks::whole(self, line, dof, what)?;
        let file = checks::file_name(self, line, file, what)?;
        let def =
            MotionDef { line, keyword: at(Keyword::MovFunc, line), dof: at(dof, line), kind: MotionKind::Function(at(file, line)) };
        self.deck.movement.as_mut().map(|m| m.motions.push(def));
        Ok(())
    }

    /// Newton's tolerance (ACCURACY) and iteration limit (MAXITER), each if
    /// given, and the integrator's tolerances `(rtol, atol)` (INTTOL) of a
    /// simulation, if given.
    pub fn tolerances(&mut self, accuracy: Option<f64>, max_iter: Option<i64>, inttol: Option<(f64, f64)>) -> Result<(), Refused> {
        self.in_block(Keyword::Accuracy, Keyword::Tstepe, "the motion's tolerances")?;
        if let Some(tol) = accuracy {
            let line = self.next_line("accuracy");
            let tol = checks::finite(self, line, tol, "the accuracy")?;
            if tol <= 0.0 {
                return Err(self.refuse(DiagnosticKind::BadValue, line, format!("the accuracy must be positive, got {tol}")));
            }
            self.deck.movement.as_mut().map(|m| m.accuracy = Some(at(tol, line)));
        }
        if let Some(m) = max_iter {
            let line = self.next_line("max_iter");
            checks::max_iter(self, line, m)?;
            self.deck.movement.as_mut().map(|mv| mv.maxiter = Some(at(m, line)));
        }
        if let Some((rtol, atol)) = inttol {
            let line = self.next_line("rtol and atol");
            checks::motion_mode(self, line, Keyword::Inttol, "the integrator's tolerances")?;
            let rtol = checks::tolerance(self, line, rtol, Tolerance::Relative)?;
            let atol = checks::tolerance(self, line, atol, Tolerance::Absolute)?;
            self.deck.movement.as_mut().map(|m| m.inttol = Some(IntTolDef { line, rtol, atol }));
        }
        self.block = Some(Keyword::Accuracy);
        Ok(())
    }

    /// Begins the storage: buffers, lists and pictures.
    pub fn storage(&mut self) -> Result<(), Refused> {
        if matches!(self.block, Some(Keyword::Elem | Keyword::BufX0)) {
            return Err(self.refuse(DiagnosticKind::WrongBlock, self.line + 1, "the storage comes before the geometry or twice"));
        }
        let line = self.next_line("STORAGE");
        self.deck.storage = Some(Storage { line, ..Storage::default() });
        self.block = Some(Keyword::BufX0);
        Ok(())
    }

    /// Buffer `number`: `keyword` (`BUFX0`, ...) of the deck numbers `args`.
    pub fn buffer(&mut self, keyword: &str, args: &[i64], number: i64) -> Result<(), Refused> {
        self.in_block(Keyword::BufX0, Keyword::BufX0, "a buffer")?;
        let line = self.next_line(format!("buffer {number}"));
        let what = format!("buffer {number}");
        let kw = Keyword::from_name(keyword).filter(|k| k.is_buffer());
        let Some(kw) = kw else {
            return Err(self.refuse(DiagnosticKind::UnknownKeyword, line, format!("{what} records `{keyword}`, no quantity")));
        };
        if kw.is_dynamic_buffer() && !self.deck.mode.value.has_dynamics() {
            let message = format!("{what} records a result of the dynamics ({kw}), which a model without masses or loads does not compute");
            return Err(self.refuse(DiagnosticKind::WrongMode, line, message));
        }
        let (min, max) = kw.arity();
        let n = args.len() + 1;
        if n < min || max.is_some_and(|m| n > m) {
            return Err(self.refuse(DiagnosticKind::ArgumentCount, line, format!("{what} ({kw}) has {} arguments", args.len())));
        }
        let args = args.iter().map(|&a| checks::whole(self, line, a, &what).map(|v| at(v, line)));
        let args = args.collect::<Result<Vec<_>, _>>()?;
        let number = checks::buffer_number(self, line, number)?;
        self.deck.storage.as_mut().map(|s| s.buffers.push(BufDef { line, keyword: at(kw, line), args, number }));
        Ok(())
    }

    /// The buffers the print file tabulates (all of them when empty).
    pub fn printbuf(&mut self, buffers: &[i64]) -> Result<(), Refused> {
        self.buffer_list(buffers, "PRINTBUF", true)
    }

    /// The buffers the data set holds, in order.
    pub fn savedata(&mut self, buffers: &[i64]) -> Result<(), Refused> {
        self.buffer_list(buffers, "SAVEDATA", false)
    }

    fn buffer_list(&mut self, buffers: &[i64], what: &str, print: bool) -> Result<(), Refused> {
        self.in_block(Keyword::PrintBuf, Keyword::BufX0, what)?;
        let line = self.next_line(what);
        let buffers = buffers.iter().map(|&b| checks::buffer_number(self, line, b)).collect::<Result<Vec<_>, _>>()?;
        let list = BufList { line, buffers };
        if let Some(s) = self.deck.storage.as_mut() {
            if print { s.printbuf.push(list) } else { s.savedata.push(list) }
        }
        Ok(())
    }

    /// The name of the animation file (without extension).
    pub fn animate(&mut self, name: &str) -> Result<(), Refused> {
        self.in_block(Keyword::Animate, Keyword::BufX0, "the animation")?;
        let line = self.next_line("ANIMATE");
        let name = checks::file_name(self, line, name, "the animation")?;
        self.deck.storage.as_mut().map(|s| s.animate = Some(at(name, line)));
        Ok(())
    }

    /// A picture titled `title` of `plots`: (`PLOTFUNC`, `PLOTCURV` or
    /// `PLOTHODO`, first, second), buffer numbers or, for PLOTHODO, a point's
    /// co-ordinate numbers.
    pub fn picture(&mut self, title: &str, plots: &[(String, i64, i64)]) -> Result<(), Refused> {
        self.in_block(Keyword::BeginPic, Keyword::BufX0, "a picture")?;
        let line = self.next_line(title);
        let title = checks::title(self, line, title)?;
        if plots.is_empty() {
            let message = format!("the picture {title:?} has nothing in it: give it at least one plot");
            return Err(self.refuse(DiagnosticKind::PictureStructure, line, message));
        }
        let mut items = Vec::with_capacity(plots.len());
        for (kw, a, b) in plots {
            let l = self.next_line(format!("a plot of {title:?}"));
            let keyword = Keyword::from_name(kw).filter(|k| matches!(k, Keyword::PlotFunc | Keyword::PlotCurv | Keyword::PlotHodo));
            let Some(keyword) = keyword else {
                return Err(self.refuse(DiagnosticKind::UnknownKeyword, l, format!("the picture {title:?} has a plot of kind `{kw}`")));
            };
            let (a, b) = if keyword == Keyword::PlotHodo {
                (checks::whole(self, l, *a, "a co-ordinate")?, checks::whole(self, l, *b, "a co-ordinate")?)
            } else {
                (checks::buffer_number(self, l, *a)?.value, checks::buffer_number(self, l, *b)?.value)
            };
            items.push(PlotDef { line: l, keyword: at(keyword, l), a: at(a, l), b: at(b, l) });
        }
        self.next_line("ENDPIC");
        self.deck.storage.as_mut().map(|s| s.pictures.push(PictureDef { line, title, items }));
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
