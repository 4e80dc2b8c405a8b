//! The typed deck: what a deck says, line by line, before any
//! cross-reference is checked.
//!
//! Every item keeps its line and the spans of its arguments, so that
//! [`crate::compile`] can point at the exact word when something does not
//! fit. Numbers that name things (co-ordinates, rows, DOFs, buffers) are kept
//! as the user wrote them, 1-based and signed.

use std::path::{Path, PathBuf};

use mechfem_core::ElementType;

use crate::diagnostic::{Diagnostic, DiagnosticKind, Hint, Span, Spanned};
use crate::keywords::Keyword;

mod names;
mod optimise;
mod tolerance;

pub(crate) use names::CoreScale;
pub use names::{NameDef, NameKind, NamesBlock, UnitsDef};
pub use optimise::{
    BoundDef, FrameDef, FreeTimeDef, MassVaryDef, ObjectiveDef, Optimise, TargetDef, TargetDefKind, VaryDef,
};
pub use tolerance::{BufTolDef, TolDef, ToleranceBlock};

/// A parsed deck.
#[derive(Debug, Clone, PartialEq)]
pub struct Deck {
    /// The file the deck was read from, as the caller named it.
    pub path: PathBuf,
    /// The mode of the first line.
    pub mode: Spanned<Mode>,
    /// The TOPOLOGY block.
    pub topology: Topology,
    /// The GEOMETRY block.
    pub geometry: Geometry,
    /// The DYNAMICS block: given exactly when the mode has dynamics
    /// ([`Mode::has_dynamics`]).
    pub dynamics: Option<Dynamics>,
    /// The MOVEMENT block, if given (always in a [`Mode::DynSim`] or
    /// [`Mode::KinOpt`] deck).
    pub movement: Option<Movement>,
    /// The OPTIMISE block: given exactly in a [`Mode::KinOpt`] deck.
    pub optimise: Option<Optimise>,
    /// The STORAGE block, if given.
    pub storage: Option<Storage>,
    /// The NAMES block, if given.
    pub names: Option<NamesBlock>,
    /// The UNITS line, if given.
    pub units: Option<UnitsDef>,
    /// The TOLERANCE block, if given (only in `KIN ANA` and `DYN ANA`).
    pub tolerance: Option<ToleranceBlock>,
    /// Set on the copy in the core's units that compiling works on.
    pub(crate) scale: Option<Box<CoreScale>>,
    /// The raw lines of the file, for diagnostics.
    pub(crate) source: Vec<String>,
}

impl Deck {
    /// The text of line `line` (1-based), or "" when there is no such line.
    pub fn line_text(&self, line: usize) -> &str {
        line.checked_sub(1).and_then(|k| self.source.get(k)).map_or("", String::as_str)
    }

    /// The files of tables the deck names (MOV_FUNC, LOADFUNC, TARGET), as
    /// written: relative to the deck's folder, in the order of the lines.
    pub fn table_files(&self) -> Vec<&Spanned<String>> {
        let motions = self.movement.iter().flat_map(|m| &m.motions).filter_map(|m| match &m.kind {
            MotionKind::Function(file) => Some(file),
            _ => None,
        });
        let loads = self.dynamics.iter().flat_map(|d| &d.loads).filter_map(|l| match &l.kind {
            LoadDefKind::Function(file) => Some(file),
            _ => None,
        });
        let targets = self.optimise.iter().flat_map(|o| &o.targets).filter_map(|t| match &t.kind {
            TargetDefKind::Values(file) => Some(file),
            _ => None,
        });
        let mut files: Vec<&Spanned<String>> = motions.chain(loads).chain(targets).collect();
        files.sort_by_key(|f| f.span.line);
        files
    }

    /// A diagnostic pointing at `span` of this deck.
    pub(crate) fn error(&self, kind: DiagnosticKind, span: Span, message: impl Into<String>) -> Box<Diagnostic> {
        diagnostic_at(&self.path, &self.source, kind, span, message)
    }
}

/// A diagnostic pointing at `span` of a file whose lines are `source`.
pub(crate) fn diagnostic_at(
    path: &Path,
    source: &[String],
    kind: DiagnosticKind,
    span: Span,
    message: impl Into<String>,
) -> Box<Diagnostic> {
    let text = span.line.checked_sub(1).and_then(|k| source.get(k)).cloned().unwrap_or_default();
    Box::new(Diagnostic {
        kind,
        path: path.to_path_buf(),
        line: span.line,
        columns: span.start..span.end.max(span.start),
        text,
        message: message.into(),
        hint: None,
        element: None,
        coordinate: None,
        detail: None,
        element_error: None,
    })
}

/// The diagnostic for a deck of dynamics (`DYN ANA`, `DYN SIM`) without a
/// DYNAMICS block, at the mode line's `span`.
pub(crate) fn missing_dynamics(path: &Path, source: &[String], mode: Mode, span: Span) -> Box<Diagnostic> {
    let message = format!("this {} deck has no DYNAMICS block", mode.name());
    diagnostic_at(path, source, DiagnosticKind::MissingBlock, span, message).with_hint(
        "add a DYNAMICS block after GEOMETRY with the masses and loads (MASS, PMASS, INERTIA, GRAVITY, FORCE, \
             LOAD, LOADFUNC, SPRING, MOTOR), or change the mode line to `KIN ANA` for kinematics only",
    )
}

/// The diagnostic for a deck whose mode needs a MOVEMENT block (`DYN SIM`,
/// `KIN OPT`) without one, at the mode line's `span`.
pub(crate) fn missing_movement(path: &Path, source: &[String], mode: Mode, span: Span) -> Box<Diagnostic> {
    let (message, hint) = if mode == Mode::KinOpt {
        (
            "this KIN OPT deck has no MOVEMENT block: the motion gives the positions at which the design is judged",
            "add a MOVEMENT block with `TSTEPE n [dt]` and, for every DOF j, a driven motion: `MOV_RELE j delta`, \
             `MOV_ABSE j end` or `MOV_FUNC j file`",
        )
    } else {
        (
            "this DYN SIM deck has no MOVEMENT block: a simulation needs its output times",
            "add a MOVEMENT block with `TSTEPE n dt` (positions at t = 0, dt, ..., n dt) and, for every DOF j, \
             `MOV_DYN j v0` to let the forces move it from the velocity v0, or MOV_RELE, MOV_ABSE or MOV_FUNC to \
             drive it",
        )
    };
    diagnostic_at(path, source, DiagnosticKind::MissingBlock, span, message).with_hint(hint)
}

/// The diagnostic for a `KIN OPT` deck without an OPTIMISE block, at the
/// mode line's `span`.
pub(crate) fn missing_optimise(path: &Path, source: &[String], span: Span) -> Box<Diagnostic> {
    let message = "this KIN OPT deck has no OPTIMISE block";
    diagnostic_at(path, source, DiagnosticKind::MissingBlock, span, message).with_hint(
        "add an OPTIMISE block with the design variables (`VARY r lo hi`, `VARYX i lo hi`) and what to achieve \
         (TARGET, TARGETAT, TARGETEXT, MINIMISE or MAXIMISE), or change the mode line to `KIN ANA` to analyse the \
         mechanism as it is",
    )
}

/// The modes of the classic program.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Mode {
    /// `KIN ANA`: kinematic analysis.
    KinAna,
    /// `KIN OPT`: kinematic optimisation (design variables changed until
    /// the motion meets targets or an objective; the OPTIMISE block).
    KinOpt,
    /// `DYN ANA`: dynamic analysis (inverse dynamics of a prescribed motion).
    DynAna,
    /// `DYN SIM`: dynamic simulation (forward dynamics: the forces move the
    /// DOFs given MOV_DYN).
    DynSim,
}

impl Mode {
    /// The mode line, e.g. `KIN ANA`.
    pub fn name(self) -> &'static str {
        match self {
            Mode::KinAna => "KIN ANA",
            Mode::KinOpt => "KIN OPT",
            Mode::DynAna => "DYN ANA",
            Mode::DynSim => "DYN SIM",
        }
    }

    /// Whether the mode computes dynamics (`DYN ANA`, `DYN SIM`): its deck
    /// needs a DYNAMICS block.
    pub fn has_dynamics(self) -> bool {
        matches!(self, Mode::DynAna | Mode::DynSim)
    }

    /// What the mode does, in words.
    pub fn description(self) -> &'static str {
        match self {
            Mode::KinAna => "kinematic analysis",
            Mode::KinOpt => "kinematic optimisation",
            Mode::DynAna => "dynamic analysis",
            Mode::DynSim => "dynamic simulation",
        }
    }
}

/// The TOPOLOGY block.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Topology {
    /// Line of the header.
    pub line: usize,
    /// `ELEM` lines, in order.
    pub elements: Vec<ElemDef>,
    /// `FORM` lines, in order.
    pub forms: Vec<FormDef>,
    /// `NRDOF n`, if given.
    pub nrdof: Option<Spanned<i64>>,
}

/// `ELEM k TYPE c1 c2 ...`
#[derive(Debug, Clone, PartialEq)]
pub struct ElemDef {
    /// Line of the definition.
    pub line: usize,
    /// Element number k (1, 2, ... in sequence).
    pub number: Spanned<i64>,
    /// Element type.
    pub ty: Spanned<ElementType>,
    /// Co-ordinate numbers in the type's order.
    pub coords: Vec<Spanned<i64>>,
}

/// `FORM s NAME k dest [f]`
#[derive(Debug, Clone, PartialEq)]
pub struct FormDef {
    /// Line of the definition.
    pub line: usize,
    /// Sequence number s (kept for reporting only).
    pub seq: Spanned<i64>,
    /// Form-parameter name, upper case.
    pub name: Spanned<String>,
    /// Element number k.
    pub element: Spanned<i64>,
    /// Destination: `r > 0` prescribed row, `-k` dependent form parameter (never 0).
    pub dest: Spanned<i64>,
    /// Factor f, if given (1.0 otherwise).
    pub factor: Option<Spanned<f64>>,
}

impl FormDef {
    /// The factor, 1.0 when none was given.
    pub fn factor(&self) -> f64 {
        self.factor.as_ref().map_or(1.0, |f| f.value)
    }
}

/// The GEOMETRY block.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Geometry {
    /// Line of the header.
    pub line: usize,
    /// `XFIX` and `XMOV` lines, in order.
    pub coords: Vec<CoordDef>,
    /// `PARA` lines, in order.
    pub paras: Vec<ParaDef>,
}

/// `XFIX i value` or `XMOV i value`.
#[derive(Debug, Clone, PartialEq)]
pub struct CoordDef {
    /// Line of the declaration.
    pub line: usize,
    /// True for XMOV.
    pub moving: bool,
    /// Co-ordinate number i.
    pub index: Spanned<i64>,
    /// Value (initial estimate for a moving co-ordinate).
    pub value: Spanned<f64>,
}

/// `PARA row value`
#[derive(Debug, Clone, PartialEq)]
pub struct ParaDef {
    /// Line of the definition.
    pub line: usize,
    /// Prescribed row.
    pub row: Spanned<i64>,
    /// Prescribed value.
    pub value: Spanned<f64>,
}

/// The DYNAMICS block (modes `DYN ANA` and `DYN SIM`), compiled to a
/// [`mechfem_core::dynamics::Dynamics`].
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Dynamics {
    /// Line of the header.
    pub line: usize,
    /// `MASS` lines, in order.
    pub masses: Vec<MassDef>,
    /// `PMASS` lines, in order.
    pub point_masses: Vec<PointMassDef>,
    /// `INERTIA` lines, in order.
    pub inertias: Vec<InertiaDef>,
    /// `GRAVITY gx gy`, if given (at most once).
    pub gravity: Option<GravityDef>,
    /// `FORCE` lines, in order.
    pub forces: Vec<ForceDef>,
    /// `LOAD`, `LOADFUNC`, `SPRING` and `MOTOR` lines, in order.
    pub loads: Vec<LoadDef>,
}

/// `MASS k m u v [J]`: element k is a rigid body.
#[derive(Debug, Clone, PartialEq)]
pub struct MassDef {
    /// Line of the definition.
    pub line: usize,
    /// Element number k.
    pub element: Spanned<i64>,
    /// Mass m (not negative).
    pub mass: Spanned<f64>,
    /// Centre of mass along the element's u-axis.
    pub u: Spanned<f64>,
    /// Centre of mass along the element's v-axis.
    pub v: Spanned<f64>,
    /// Moment of inertia about the centre of mass, if given (0 otherwise; not negative).
    pub inertia: Option<Spanned<f64>>,
}

/// `PMASS i j m`: a point mass.
#[derive(Debug, Clone, PartialEq)]
pub struct PointMassDef {
    /// Line of the definition.
    pub line: usize,
    /// Co-ordinate number of the point's x.
    pub x: Spanned<i64>,
    /// Co-ordinate number of the point's y.
    pub y: Spanned<i64>,
    /// Mass m (not negative).
    pub mass: Spanned<f64>,
}

/// `INERTIA i J`: a rotational inertia on an angle co-ordinate.
#[derive(Debug, Clone, PartialEq)]
pub struct InertiaDef {
    /// Line of the definition.
    pub line: usize,
    /// Co-ordinate number i.
    pub coord: Spanned<i64>,
    /// Moment of inertia J (not negative).
    pub inertia: Spanned<f64>,
}

/// `GRAVITY gx gy`
#[derive(Debug, Clone, PartialEq)]
pub struct GravityDef {
    /// Line of the definition.
    pub line: usize,
    /// Acceleration of gravity along x.
    pub gx: Spanned<f64>,
    /// Acceleration of gravity along y.
    pub gy: Spanned<f64>,
}

/// `FORCE i j fx fy`: a constant force at a point.
#[derive(Debug, Clone, PartialEq)]
pub struct ForceDef {
    /// Line of the definition.
    pub line: usize,
    /// Co-ordinate number of the point's x.
    pub x: Spanned<i64>,
    /// Co-ordinate number of the point's y.
    pub y: Spanned<i64>,
    /// Force along x.
    pub fx: Spanned<f64>,
    /// Force along y.
    pub fy: Spanned<f64>,
}

/// `LOAD`, `LOADFUNC`, `SPRING` or `MOTOR`: a generalised force on a form
/// parameter.
#[derive(Debug, Clone, PartialEq)]
pub struct LoadDef {
    /// Line of the keyword.
    pub line: usize,
    /// The keyword's own span (the line's first word, or where it is repeated).
    pub keyword: Spanned<Keyword>,
    /// Destination: `r > 0` prescribed row, `-k` dependent form parameter.
    pub form: Spanned<i64>,
    /// How the force depends on time and motion.
    pub kind: LoadDefKind,
}

/// The four kinds of generalised force.
#[derive(Debug, Clone, PartialEq)]
pub enum LoadDefKind {
    /// `LOAD r value`
    Constant(Spanned<f64>),
    /// `LOADFUNC r file` (file relative to the deck's folder).
    Function(Spanned<String>),
    /// `SPRING r k e0 [c]` (k and c not negative).
    Spring {
        /// Stiffness k.
        k: Spanned<f64>,
        /// Free value e0.
        e0: Spanned<f64>,
        /// Viscous damping c, if given (0 otherwise).
        c: Option<Spanned<f64>>,
    },
    /// `MOTOR r T0 w0` (w0 not zero).
    Motor {
        /// Stall torque T0.
        t0: Spanned<f64>,
        /// No-load speed w0.
        w0: Spanned<f64>,
    },
}

/// The MOVEMENT block.
#[derive(Debug, Clone, PartialEq)]
pub struct Movement {
    /// Line of the header.
    pub line: usize,
    /// `TSTEPE n [dt]` (the parser makes sure it is there and first).
    pub tstepe: Tstepe,
    /// `MOV_...` lines, in order.
    pub motions: Vec<MotionDef>,
    /// `ACCURACY tol`, if given (tol > 0).
    pub accuracy: Option<Spanned<f64>>,
    /// `MAXITER m`, if given (m >= 1).
    pub maxiter: Option<Spanned<i64>>,
    /// `INTTOL rtol atol`, if given (mode `DYN SIM` only).
    pub inttol: Option<IntTolDef>,
    /// `INTEGRATOR method`, if given (mode `DYN SIM` only).
    pub integrator: Option<Spanned<mechfem_core::dynamics::Integrator>>,
    /// `STOPWHEN b value`, if given (mode `DYN SIM` only).
    pub stop_when: Option<StopWhenDef>,
}

/// `STOPWHEN b value`: the simulation ends where buffer b crosses value.
#[derive(Debug, Clone, PartialEq)]
pub struct StopWhenDef {
    /// Line of the keyword.
    pub line: usize,
    /// The buffer watched (1..=u32::MAX).
    pub buffer: Spanned<i64>,
    /// The value.
    pub value: Spanned<f64>,
}

/// `INTTOL rtol atol`: the tolerances of the integrator of a simulation.
#[derive(Debug, Clone, PartialEq)]
pub struct IntTolDef {
    /// Line of the keyword.
    pub line: usize,
    /// Relative tolerance (finite, positive).
    pub rtol: Spanned<f64>,
    /// Absolute tolerance (finite, positive).
    pub atol: Spanned<f64>,
}

/// `TSTEPE n [dt]`
#[derive(Debug, Clone, PartialEq)]
pub struct Tstepe {
    /// Line of the keyword.
    pub line: usize,
    /// Number of steps n (at least 1).
    pub steps: Spanned<i64>,
    /// Time per step (positive), if given.
    pub dt: Option<Spanned<f64>>,
}

/// One `MOV_...` line.
#[derive(Debug, Clone, PartialEq)]
pub struct MotionDef {
    /// Line of the keyword.
    pub line: usize,
    /// The keyword's own span (the line's first word, or where it is repeated).
    pub keyword: Spanned<Keyword>,
    /// Degree of freedom j.
    pub dof: Spanned<i64>,
    /// What the input does.
    pub kind: MotionKind,
}

/// The five kinds of input motion.
#[derive(Debug, Clone, PartialEq)]
pub enum MotionKind {
    /// `MOV_RELE j delta`
    Relative(Spanned<f64>),
    /// `MOV_ABSE j end`
    Absolute(Spanned<f64>),
    /// `MOV_FUNC j file` (file relative to the deck's folder).
    Function(Spanned<String>),
    /// `MOV_FREE j ds`
    Free(Spanned<f64>),
    /// `MOV_DYN j v0`: moved by the forces from the initial velocity v0
    /// (mode `DYN SIM` only).
    Dynamic(Spanned<f64>),
}

/// The STORAGE block.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Storage {
    /// Line of the header.
    pub line: usize,
    /// `BUF...` lines, in order.
    pub buffers: Vec<BufDef>,
    /// `PRINTBUF` lines.
    pub printbuf: Vec<BufList>,
    /// `SAVEDATA` lines.
    pub savedata: Vec<BufList>,
    /// `ANIMATE name`, if given.
    pub animate: Option<Spanned<String>>,
    /// `BEGINPIC` ... `ENDPIC` pictures.
    pub pictures: Vec<PictureDef>,
}

/// One `BUF...` line.
#[derive(Debug, Clone, PartialEq)]
pub struct BufDef {
    /// Line of the keyword.
    pub line: usize,
    /// Which `BUF...` keyword.
    pub keyword: Spanned<Keyword>,
    /// The arguments before the buffer number (co-ordinate, row, DOFs).
    pub args: Vec<Spanned<i64>>,
    /// Buffer number (positive, at most `u32::MAX`).
    pub number: Spanned<i64>,
}

/// A list of buffer numbers (`PRINTBUF`, `SAVEDATA`).
#[derive(Debug, Clone, PartialEq)]
pub struct BufList {
    /// Line of the keyword.
    pub line: usize,
    /// Buffer numbers (may be empty for PRINTBUF: all buffers).
    pub buffers: Vec<Spanned<i64>>,
}

/// `BEGINPIC [title]` ... `ENDPIC`
#[derive(Debug, Clone, PartialEq)]
pub struct PictureDef {
    /// Line of BEGINPIC.
    pub line: usize,
    /// Title (the rest of the BEGINPIC line, may be empty).
    pub title: String,
    /// The plots, in order.
    pub items: Vec<PlotDef>,
}

/// `PLOTFUNC bx by`, `PLOTCURV bx by` or `PLOTHODO ix iy`.
#[derive(Debug, Clone, PartialEq)]
pub struct PlotDef {
    /// Line of the keyword.
    pub line: usize,
    /// Which keyword.
    pub keyword: Spanned<Keyword>,
    /// First argument (bx or ix).
    pub a: Spanned<i64>,
    /// Second argument (by or iy).
    pub b: Spanned<i64>,
}
