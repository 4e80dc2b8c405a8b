//! One keyword line to one item of the typed deck.

pub(crate) mod dynamics;
pub(crate) mod names;
mod optimise;
mod simulation;
mod tolerance;

use mechfem_core::ElementType;

use crate::ast::{
    BufDef, BufList, CoordDef, ElemDef, FormDef, IntTolDef, Mode, MotionDef, MotionKind, ParaDef, PictureDef, PlotDef,
    Tstepe,
};
use crate::diagnostic::{real, Diagnostic, DiagnosticKind, Hint, Spanned};
use crate::keywords::{Block, Keyword};
use crate::lexer::{Line, Word};
use crate::parse::Parser;

/// The largest number of steps TSTEPE accepts: every position is stored.
pub const MAX_STEPS: i64 = 10_000_000;
/// The largest MAXITER: Newton iterations that neither converge nor diverge
/// would otherwise go on for as long as the deck says, at every subdivision
/// of a failing step.
pub const MAX_ITER: i64 = 1000;

impl Parser<'_> {
    /// Reads the arguments of one keyword line into the deck being built.
    pub(crate) fn statement(
        &mut self,
        kw: Spanned<Keyword>,
        line: &Line,
        args: &[Word],
        repeated: bool,
    ) -> Result<(), Box<Diagnostic>> {
        match kw.value.block() {
            Block::Movement => self.check_tstepe_first(kw)?,
            Block::Storage => self.check_picture(kw)?,
            _ => {}
        }
        self.check_mode(kw)?;
        if kw.value == Keyword::Elem {
            return self.elem(line, args, repeated);
        }
        self.src.check_count(kw.value, line, args, repeated)?;
        match kw.value.block() {
            Block::Dynamics => return self.dynamics_statement(kw, line, args),
            Block::Optimise => return self.optimise_statement(kw, line, args),
            Block::Tolerance => return self.tolerance_statement(kw, line, args),
            _ => {}
        }
        // `check_count` guarantees the required arguments; `arg` still
        // refuses to index out of range.
        let arg =
            |k: usize| args.get(k).ok_or_else(|| self.src.count_error(line, args, None, "missing argument".into()));
        let line_no = line.number;
        let src = &self.src;
        match kw.value {
            Keyword::Elem => {}
            Keyword::Form => {
                let seq = src.whole(arg(0)?, "the sequence number")?;
                let name = arg(1)?;
                let element = src.whole(arg(2)?, "the element number")?;
                let dest = src.whole(arg(3)?, "the destination")?;
                if dest.value == 0 {
                    return Err(src
                        .error(DiagnosticKind::ZeroDestination, dest.span, "destination 0 is not allowed")
                        .with_hint("use r > 0 for prescribed row r, or -k for dependent form parameter k"));
                }
                let factor = args.get(4).map(|w| src.real(w, "the factor")).transpose()?;
                let name = Spanned::new(name.text.to_ascii_uppercase(), name.span);
                self.topology.forms.push(FormDef { line: line_no, seq, name, element, dest, factor });
            }
            Keyword::Nrdof => {
                let n = src.whole(arg(0)?, "the number of degrees of freedom")?;
                if n.value < 1 {
                    return Err(src
                        .error(DiagnosticKind::BadValue, n.span, format!("NRDOF must be at least 1, got {}", n.value))
                        .with_hint("give the number of inputs that drive the mechanism"));
                }
                self.once(kw)?;
                self.topology.nrdof = Some(n);
            }
            Keyword::Xfix | Keyword::Xmov => {
                let index = src.whole(arg(0)?, "the co-ordinate number")?;
                let value = src.real(arg(1)?, "the co-ordinate's value")?;
                let moving = kw.value == Keyword::Xmov;
                self.geometry.coords.push(CoordDef { line: line_no, moving, index, value });
            }
            Keyword::Para => {
                let row = src.whole(arg(0)?, "the row number")?;
                let value = src.real(arg(1)?, "the prescribed value")?;
                self.geometry.paras.push(ParaDef { line: line_no, row, value });
            }
            Keyword::Tstepe => {
                let steps = src.whole(arg(0)?, "the number of steps")?;
                if steps.value < 1 {
                    return Err(src
                        .error(
                            DiagnosticKind::BadValue,
                            steps.span,
                            format!("TSTEPE needs at least 1 step, got {}", steps.value),
                        )
                        .with_hint("give the number of steps n; the motion has the positions 1..n+1"));
                }
                if steps.value > MAX_STEPS {
                    return Err(src
                        .error(
                            DiagnosticKind::BadValue,
                            steps.span,
                            format!("TSTEPE {} asks for more than {MAX_STEPS} steps", steps.value),
                        )
                        .with_hint("use fewer, longer steps"));
                }
                let dt = args.get(1).map(|w| src.real(w, "the time step")).transpose()?;
                if let Some(dt) = dt.as_ref().filter(|dt| dt.value <= 0.0) {
                    return Err(src
                        .error(
                            DiagnosticKind::BadValue,
                            dt.span,
                            format!("the time step must be positive, got {}", dt.value),
                        )
                        .with_hint("give the time of one step, or leave it out for 1"));
                }
                if let Some(dt) = dt.as_ref().filter(|dt| !(steps.value as f64 * dt.value).is_finite()) {
                    return Err(src
                        .error(
                            DiagnosticKind::BadValue,
                            dt.span,
                            format!(
                                "{} steps of {} last longer than the largest time a number can hold",
                                steps.value,
                                real(dt.value)
                            ),
                        )
                        .with_hint("give a shorter time step: n * dt must stay below about 1.8e308"));
                }
                self.once(kw)?;
                self.movement.tstepe = Some(Tstepe { line: line_no, steps, dt });
            }
            Keyword::MovRele | Keyword::MovAbse | Keyword::MovFunc | Keyword::MovFree | Keyword::MovDyn => {
                let dof = src.whole(arg(0)?, "the DOF number")?;
                let value = arg(1)?;
                let kind = match kw.value {
                    Keyword::MovRele => MotionKind::Relative(src.real(value, "the total change")?),
                    Keyword::MovAbse => MotionKind::Absolute(src.real(value, "the end value")?),
                    Keyword::MovFunc => MotionKind::Function(Spanned::new(value.text.clone(), value.span)),
                    Keyword::MovDyn => MotionKind::Dynamic(dynamics::bounded(src, value, "the initial velocity")?),
                    _ => {
                        let ds = src.real(value, "the step length")?;
                        if ds.value == 0.0 {
                            return Err(src
                                .error(
                                    DiagnosticKind::BadValue,
                                    ds.span,
                                    "the step length of free motion must not be 0",
                                )
                                .with_hint("give the distance the moving co-ordinates travel per step, e.g. 0.01"));
                        }
                        MotionKind::Free(ds)
                    }
                };
                self.movement.motions.push(MotionDef { line: line_no, keyword: kw, dof, kind });
            }
            Keyword::Accuracy => {
                let tol = src.real(arg(0)?, "the tolerance")?;
                if tol.value <= 0.0 {
                    return Err(src
                        .error(
                            DiagnosticKind::BadValue,
                            tol.span,
                            format!("ACCURACY must be positive, got {}", tol.value),
                        )
                        .with_hint("give the largest deformation Newton may leave, e.g. 1E-10"));
                }
                self.once(kw)?;
                self.movement.accuracy = Some(tol);
            }
            Keyword::Maxiter => {
                let m = src.whole(arg(0)?, "the number of iterations")?;
                if m.value < 1 {
                    return Err(src
                        .error(DiagnosticKind::BadValue, m.span, format!("MAXITER must be at least 1, got {}", m.value))
                        .with_hint("give the largest number of Newton iterations per position, e.g. 25"));
                }
                if m.value > MAX_ITER {
                    return Err(src
                        .error(
                            DiagnosticKind::BadValue,
                            m.span,
                            format!("MAXITER {} is more than {MAX_ITER} iterations", m.value),
                        )
                        .with_hint(
                            "Newton converges in a few iterations or not at all, and a step that fails is subdivided \
                             anyway; give at most 1000 (default 25)",
                        ));
                }
                self.once(kw)?;
                self.movement.maxiter = Some(m);
            }
            Keyword::Inttol => {
                let rtol = dynamics::tolerance(src, arg(0)?, dynamics::Tolerance::Relative)?;
                let atol = dynamics::tolerance(src, arg(1)?, dynamics::Tolerance::Absolute)?;
                self.once(kw)?;
                self.movement.inttol = Some(IntTolDef { line: line_no, rtol, atol });
            }
            Keyword::Integrator => {
                let method = simulation::integrator(src, arg(0)?)?;
                self.once(kw)?;
                self.movement.integrator = Some(method);
            }
            Keyword::StopWhen => {
                let def = simulation::stop_when(src, line_no, args)?;
                self.once(kw)?;
                self.movement.stop_when = Some(def);
            }
            Keyword::PrintBuf | Keyword::SaveData => {
                let buffers = args.iter().map(|w| src.buffer(w)).collect::<Result<Vec<_>, _>>()?;
                let list = BufList { line: line_no, buffers };
                if kw.value == Keyword::PrintBuf {
                    self.storage.printbuf.push(list);
                } else {
                    self.storage.savedata.push(list);
                }
            }
            Keyword::Animate => {
                let name = arg(0)?;
                let name = Spanned::new(name.text.clone(), name.span);
                self.once(kw)?;
                self.storage.animate = Some(name);
            }
            Keyword::BeginPic => {
                let title = match (args.first(), args.last()) {
                    (Some(a), Some(b)) => line_slice(src.lines, line_no, a.span.start, b.span.end),
                    _ => String::new(),
                };
                self.picture = Some(PictureDef { line: line_no, title, items: Vec::new() });
            }
            Keyword::EndPic => {
                if let Some(pic) = self.picture.take() {
                    if pic.items.is_empty() {
                        return Err(self
                            .src
                            .error(
                                DiagnosticKind::PictureStructure,
                                kw.span,
                                format!("the picture opened at line {} has nothing in it", pic.line),
                            )
                            .with_hint(
                                "put at least one PLOTFUNC, PLOTCURV or PLOTHODO line between BEGINPIC and ENDPIC, or \
                                 remove the empty picture",
                            ));
                    }
                    self.storage.pictures.push(pic);
                }
            }
            Keyword::PlotFunc | Keyword::PlotCurv | Keyword::PlotHodo => {
                let (a, b) = if kw.value == Keyword::PlotHodo {
                    (src.whole(arg(0)?, "the co-ordinate number")?, src.whole(arg(1)?, "the co-ordinate number")?)
                } else {
                    (src.buffer(arg(0)?)?, src.buffer(arg(1)?)?)
                };
                if let Some(pic) = self.picture.as_mut() {
                    pic.items.push(PlotDef { line: line_no, keyword: kw, a, b });
                }
            }
            _ => {
                let (last, indices) =
                    args.split_last().ok_or_else(|| src.count_error(line, args, None, "missing argument".into()))?;
                let names = buffer_argument_names(kw.value);
                let args = indices
                    .iter()
                    .enumerate()
                    .map(|(k, w)| src.whole(w, names.get(k).copied().unwrap_or("an index")))
                    .collect::<Result<Vec<_>, _>>()?;
                let number = src.buffer(last)?;
                let def = BufDef { line: line_no, keyword: kw, args, number };
                if self.block() == Some(Block::Optimise) {
                    self.optimise.buffers.push(def);
                } else {
                    self.storage.buffers.push(def);
                }
            }
        }
        Ok(())
    }

    /// `ELEM k TYPE c1 c2 ...`: the count of co-ordinates depends on the type.
    fn elem(&mut self, line: &Line, args: &[Word], repeated: bool) -> Result<(), Box<Diagnostic>> {
        self.elem_lines += 1;
        self.src.check_count(Keyword::Elem, line, args, repeated)?;
        let src = &self.src;
        let (Some(number), Some(ty_word)) = (args.first(), args.get(1)) else {
            return Err(src.count_error(line, args, None, "ELEM expects k TYPE c1 c2 ...".into()));
        };
        let number = src.whole(number, "the element number")?;
        if number.value != self.elem_lines {
            let expected = self.elem_lines;
            // Later elements are checked against this one's number, so one
            // slip gives one message.
            self.elem_lines = number.value;
            return Err(self
                .src
                .error(
                    DiagnosticKind::ElementSequence,
                    number.span,
                    format!("element number {} is out of sequence: expected {expected}", number.value),
                )
                .with_hint("number the elements 1, 2, 3, ... in the order of their ELEM lines"));
        }
        let ty = element_type(self, ty_word)?;
        let coords = &args[2..];
        let names = ty.coord_names();
        if coords.len() != names.len() {
            let message = format!(
                "an element of type {} has {} co-ordinates ({}), got {}",
                ty.name(),
                names.len(),
                names.join(" "),
                coords.len()
            );
            let surplus = (coords.len() > names.len()).then_some(2 + names.len());
            return Err(src.count_error(line, args, surplus, message).with_hint(format!(
                "usage: ELEM k {} {}",
                ty.name(),
                names.join(" ")
            )));
        }
        let coords = coords.iter().map(|w| src.whole(w, "a co-ordinate number")).collect::<Result<Vec<_>, _>>()?;
        let ty = Spanned::new(ty, ty_word.span);
        self.topology.elements.push(ElemDef { line: line.number, number, ty, coords });
        Ok(())
    }

    /// Refuses a keyword that the deck's mode does not have.
    fn check_mode(&self, kw: Spanned<Keyword>) -> Result<(), Box<Diagnostic>> {
        let k = kw.value;
        let err = |message: String, hint: &str| {
            Err(self.src.error(DiagnosticKind::WrongMode, kw.span, message).with_hint(hint))
        };
        let Some(mode) = self.mode() else { return Ok(()) };
        let name = mode.name();
        match mode {
            Mode::KinAna if k.is_dynamic_buffer() => err(
                format!("{k} records a result of the dynamics, which a KIN ANA deck does not compute"),
                "change the mode line to `DYN ANA` (or `DYN SIM`) and add a DYNAMICS block, or remove this line",
            ),
            Mode::KinOpt if k.is_dynamic_buffer() => err(
                format!("{k} records a result of the dynamics, which a KIN OPT deck does not compute"),
                "a KIN OPT deck judges a design by its kinematics (positions, transfer functions, velocities, \
                 accelerations): remove this line, or use BUFX0, BUFKX1, BUFKX2, BUFE0, BUFKE1, BUFKE2, BUFVX, BUFAX, \
                 BUFVE, BUFAE or BUFDET",
            ),
            Mode::KinOpt if matches!(k, Keyword::MovFree | Keyword::MovDyn) => err(
                format!("{k} cannot move a KIN OPT deck: the design is judged along a driven motion"),
                "drive every DOF with MOV_RELE, MOV_ABSE or MOV_FUNC: their positions are where the targets, bounds \
                 and objective of the OPTIMISE block are evaluated, the same for every design",
            ),
            _ if mode.has_dynamics() && k == Keyword::MovFree => err(
                format!(
                    "MOV_FREE cannot drive a {name} deck: free motion has no timing, so no velocities or accelerations"
                ),
                if mode == Mode::DynSim {
                    "let the forces move the DOF with `MOV_DYN j v0`, or prescribe it in time with MOV_RELE, \
                     MOV_ABSE or MOV_FUNC; each of the n steps of TSTEPE n dt takes the time dt"
                } else {
                    "prescribe the input in time with MOV_RELE, MOV_ABSE or MOV_FUNC; each of the n steps of \
                     TSTEPE n dt takes the time dt"
                },
            ),
            Mode::KinAna | Mode::DynAna if k == Keyword::MovDyn => err(
                format!("MOV_DYN lets the forces move a DOF, which only a simulation does, not a {name} deck"),
                if mode == Mode::KinAna {
                    "change the mode line to `DYN SIM` and add a DYNAMICS block to simulate, or prescribe the input \
                     with MOV_RELE, MOV_ABSE or MOV_FUNC"
                } else {
                    "change the mode line to `DYN SIM` to simulate, or prescribe the input with MOV_RELE, MOV_ABSE or \
                     MOV_FUNC"
                },
            ),
            Mode::KinAna | Mode::KinOpt | Mode::DynAna if k == Keyword::Inttol => err(
                format!("INTTOL sets the tolerances of a simulation's integrator, which a {name} deck does not run"),
                "remove this line (ACCURACY sets how closely Newton meets the prescribed values), or change the mode \
                 line to `DYN SIM`",
            ),
            Mode::KinAna | Mode::KinOpt | Mode::DynAna if matches!(k, Keyword::Integrator | Keyword::StopWhen) => err(
                format!("{k} sets how a simulation is integrated or ends, which a {name} deck does not run"),
                "remove this line, or change the mode line to `DYN SIM` and let an input move under the forces with \
                 MOV_DYN",
            ),
            _ => Ok(()),
        }
    }

    fn check_tstepe_first(&mut self, kw: Spanned<Keyword>) -> Result<(), Box<Diagnostic>> {
        if kw.value == Keyword::Tstepe {
            // Even a refused TSTEPE line is in its place.
            self.movement.tstepe_reported = true;
        }
        if self.movement.tstepe_reported {
            return Ok(());
        }
        self.movement.tstepe_reported = true;
        Err(self
            .src
            .error(DiagnosticKind::TstepeNotFirst, kw.span, format!("{} comes before TSTEPE", kw.value))
            .with_hint(
                "TSTEPE must be the first keyword of the MOVEMENT block: put `TSTEPE n [dt]` right below the header",
            ))
    }

    fn check_picture(&self, kw: Spanned<Keyword>) -> Result<(), Box<Diagnostic>> {
        let k = kw.value;
        let inside = matches!(k, Keyword::PlotFunc | Keyword::PlotCurv | Keyword::PlotHodo | Keyword::EndPic);
        let err = |message: String, hint: String| {
            Err(self.src.error(DiagnosticKind::PictureStructure, kw.span, message).with_hint(hint))
        };
        match (&self.picture, inside) {
            (None, true) if k == Keyword::EndPic => err(
                "ENDPIC without BEGINPIC".into(),
                "start the picture with `BEGINPIC [title]`, or remove this line".into(),
            ),
            (None, true) => err(format!("{k} outside a picture"), format!("put {k} between BEGINPIC and ENDPIC")),
            (Some(pic), false) => err(
                format!("{k} inside a picture: the picture opened at line {} has no ENDPIC yet", pic.line),
                format!("close the picture with ENDPIC before {k}"),
            ),
            _ => Ok(()),
        }
    }
}

/// The element type named by `word`, or a diagnostic listing the valid ones.
fn element_type(parser: &Parser<'_>, word: &Word) -> Result<ElementType, Box<Diagnostic>> {
    if let Some(ty) = ElementType::from_name(&word.text) {
        return Ok(ty);
    }
    let names: Vec<&str> = ElementType::ALL.iter().map(|t| t.name()).collect();
    let message = format!("unknown element type `{}`", word.text);
    Err(parser
        .src
        .error(DiagnosticKind::UnknownElementType, word.span, message)
        .with_hint(format!("element types are {}", names.join(", "))))
}

/// What the arguments before the buffer number of a `BUF...` keyword mean.
fn buffer_argument_names(kw: Keyword) -> &'static [&'static str] {
    const DOF: &str = "the DOF number";
    const COORD: &str = "the co-ordinate number";
    const FORM: &str = "the form parameter's destination";
    match kw {
        Keyword::BufInp => &[DOF],
        Keyword::BufX0 | Keyword::BufVx | Keyword::BufAx => &[COORD],
        Keyword::BufKx1 | Keyword::BufKx2 => &[COORD, DOF, DOF],
        Keyword::BufE0 | Keyword::BufVe | Keyword::BufAe => &[FORM],
        Keyword::BufKe1 | Keyword::BufKe2 => &[FORM, DOF, DOF],
        Keyword::BufSig => &["the prescribed row"],
        Keyword::BufDrv => &[DOF],
        Keyword::BufRea => &[COORD],
        Keyword::BufMred => &[DOF, DOF],
        Keyword::BufTra => &["the first element", "the second element"],
        Keyword::BufPin => &["the element", "the pin's x co-ordinate", "the pin's y co-ordinate"],
        _ => &[],
    }
}

/// Characters `start..end` of line `line` (1-based).
fn line_slice(lines: &[String], line: usize, start: usize, end: usize) -> String {
    let text = line.checked_sub(1).and_then(|k| lines.get(k)).map_or("", String::as_str);
    text.chars().skip(start).take(end.saturating_sub(start)).collect()
}
