//! What a deck compiles to: the core model and motion, plus what the
//! outputs and the print file's echo of the model need.
//!
//! Fields that feed the computation ([`Buffer::quantity`],
//! [`PlotItem::Hodograph`], [`Compiled::dynamics`]) use the core's 0-based indices; fields meant
//! for echoing the model ([`ElementInfo`], [`RowInfo`]) keep the deck's
//! 1-based numbers.

use mechfem_core::dynamics::{Dynamics, Integration};
use mechfem_core::{DynamicSource, ElementType, Mechanism, Motion, Params, Quantity, State};

use crate::ast::Mode;
use crate::optimise::Optimise;

/// A compiled deck, ready to run.
#[derive(Debug, Clone)]
pub struct Compiled {
    /// The mode of the deck.
    pub mode: Mode,
    /// The model (immutable).
    pub mechanism: Mechanism,
    /// The initial state: XFIX/XMOV values, and prescribed values from PARA
    /// (rows without PARA hold their value at the given co-ordinates).
    pub state: State,
    /// The input motion; `None` without a MOVEMENT block (position 1 only),
    /// which a [`Mode::DynSim`] or [`Mode::KinOpt`] deck always has. Its DOFs given MOV_DYN are
    /// [`mechfem_core::InputMotion::Dynamic`].
    pub motion: Option<Motion>,
    /// Solver settings (ACCURACY, MAXITER; defaults otherwise).
    pub params: Params,
    /// The tolerances of a simulation's integrator: INTTOL's, else
    /// [`Integration::from_accuracy`] of `params.tol` (ACCURACY or its
    /// default). Set for every deck; only [`Mode::DynSim`] uses it.
    pub integration: Integration,
    /// Buffer definitions of STORAGE and OPTIMISE, in deck order.
    pub buffers: Vec<Buffer>,
    /// Buffers to tabulate in the print file: `None` without PRINTBUF,
    /// `Some(empty)` for all buffers.
    pub printbuf: Option<Vec<u32>>,
    /// Buffers to write to the data set, in order (empty: no data set).
    pub savedata: Vec<u32>,
    /// Name of the animation file (without extension), if any.
    pub animate: Option<String>,
    /// Pictures, in deck order.
    pub pictures: Vec<Picture>,
    /// The elements as the deck declares them.
    pub elements: Vec<ElementInfo>,
    /// The prescribed rows 1..n_p (rows of D^c), as the deck builds them.
    pub prescribed: Vec<RowInfo>,
    /// The dependent form parameters 1..n_d.
    pub dependent: Vec<RowInfo>,
    /// The names the deck declares in its comments.
    pub names: Names,
    /// The masses and loads (0-based indices): `Some` exactly for a
    /// [`Mode::DynAna`] or [`Mode::DynSim`] deck.
    pub dynamics: Option<Dynamics>,
    /// The DYNAMICS line each mass and load of [`Compiled::dynamics`]
    /// comes from, by what a [`mechfem_core::DynamicsFault`] calls it
    /// (see [`Compiled::dynamics_line`]); empty without masses and loads.
    pub dynamics_lines: Vec<(DynamicSource, usize)>,
    /// The design variables, targets, bounds and objective of the OPTIMISE
    /// block: `Some` exactly for a [`Mode::KinOpt`] deck.
    pub optimise: Option<Optimise>,
}

impl Compiled {
    /// The line of the DYNAMICS statement a fault found during the run
    /// names: `None` for what no single line gives (a row's stress, the
    /// drives, the free degrees of freedom) and for a model built without
    /// a deck. The deck refuses a second line of one keyword on one thing,
    /// so the source names one line.
    pub fn dynamics_line(&self, source: &DynamicSource) -> Option<usize> {
        self.dynamics_lines.iter().find(|(s, _)| s == source).map(|&(_, line)| line)
    }
}

/// One output buffer: one value per position.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Buffer {
    /// The buffer number chosen in the deck.
    pub number: u32,
    /// What it records (0-based indices).
    pub quantity: Quantity,
    /// Line of the `BUF...` keyword.
    pub line: usize,
}

/// One picture (`BEGINPIC` ... `ENDPIC`).
#[derive(Debug, Clone, PartialEq)]
pub struct Picture {
    /// Title (may be empty).
    pub title: String,
    /// Line of BEGINPIC.
    pub line: usize,
    /// What is drawn, in deck order.
    pub items: Vec<PlotItem>,
}

/// One item of a picture.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PlotItem {
    /// `PLOTFUNC bx by`: buffer `y` against buffer `x`.
    Function {
        /// Buffer on the horizontal axis.
        x: u32,
        /// Buffer on the vertical axis.
        y: u32,
    },
    /// `PLOTCURV bx by`: a curve with equal axis scales.
    Curve {
        /// Buffer on the horizontal axis.
        x: u32,
        /// Buffer on the vertical axis.
        y: u32,
    },
    /// `PLOTHODO ix iy`: path and velocity hodograph of the point with
    /// co-ordinates `x`, `y` (0-based co-ordinate indices), mechanism drawn in.
    Hodograph {
        /// Co-ordinate index of the point's x.
        x: usize,
        /// Co-ordinate index of the point's y.
        y: usize,
    },
}

/// An element as the deck declares it (deck numbering).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ElementInfo {
    /// Element number k (1-based).
    pub number: usize,
    /// Element type.
    pub ty: ElementType,
    /// Co-ordinate numbers (1-based) in the type's order.
    pub coords: Vec<usize>,
    /// Line of the ELEM keyword.
    pub line: usize,
}

/// A prescribed row or dependent form parameter and the FORM lines that
/// make it (deck numbering).
#[derive(Debug, Clone, PartialEq)]
pub struct RowInfo {
    /// Destination: `r > 0` for prescribed row r, `-k` for dependent form parameter k.
    pub dest: i64,
    /// The single form parameters combined into it (eq. 5.33).
    pub terms: Vec<TermInfo>,
    /// The value PARA prescribes, if any.
    pub para: Option<f64>,
    /// The DOF (1-based) whose input this row is, if it is one.
    pub input: Option<usize>,
}

/// One single form parameter of a row.
#[derive(Debug, Clone, PartialEq)]
pub struct TermInfo {
    /// The FORM line's sequence number s.
    pub seq: i64,
    /// Element number (1-based).
    pub element: usize,
    /// Form-parameter name, e.g. `LENL`.
    pub name: &'static str,
    /// Factor f.
    pub factor: f64,
    /// Line of the FORM keyword.
    pub line: usize,
}

/// The names a deck declares in the `;` comments of its lines, by deck
/// number (index i - 1 for number i); `None` where no name is declared.
///
/// mechfem's rule, made for the decks its Python writer produces
/// (`ELEM 1 BIN 1 2 5 6 ; crank: A0 A`, `FORM 3 LENL 2 2 1 ; coupler.length`,
/// `XMOV 5 0.95 ; A.x`, `PARA 2 3.5 ; phi`) while free-text comments of
/// hand-written decks (`; crank A0-A`) name nothing:
///
/// * a co-ordinate takes the comment of its XFIX or XMOV line (a line that
///   repeats the keyword has its own), an element that of its ELEM line, a
///   prescribed row or dependent form parameter that of the first FORM line
///   with its destination, and a prescribed row whose first FORM line has no
///   comment that of its PARA line;
/// * the comment is trimmed; of an ELEM or FORM comment only the part before
///   the first `:` counts (what follows is the element's slots or the row's
///   formula), trimmed again;
/// * that text is a name when it is one word of the form
///   `[A-Za-z_][A-Za-z0-9_.]*` (`A.x`, `crank_angle`, `coupler.length`):
///   anything with a blank, a comma or a hyphen in it is a note, not a name;
/// * names are compared as written, case and all. A name declared for two
///   co-ordinates, two elements or two rows, or for a co-ordinate and an
///   element or row, would not say which is meant: it is dropped for all of
///   them. An element and a row may share a name.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct Names {
    /// Co-ordinates 1..N.
    pub coordinates: Vec<Option<String>>,
    /// Elements 1..n_e.
    pub elements: Vec<Option<String>>,
    /// Prescribed rows 1..n_p.
    pub prescribed: Vec<Option<String>>,
    /// Dependent form parameters 1..n_d.
    pub dependent: Vec<Option<String>>,
}
