//! What a deck compiles to: the core model and motion, plus what the
//! outputs and the print file's echo of the model need.
//!
//! Fields that feed the computation ([`Buffer::quantity`],
//! [`PlotItem::Hodograph`], [`Compiled::dynamics`]) use the core's 0-based indices; fields meant
//! for echoing the model ([`ElementInfo`], [`RowInfo`]) keep the deck's
//! 1-based numbers.

use mechfem_core::dynamics::{Dynamics, Integration};
use mechfem_core::{
    Dim, Dimension, DynamicSource, ElementType, FormRef, Mechanism, ModelDims, Motion, Names, Params, Quantity, State,
    Units,
};

use crate::ast::Mode;
use crate::diagnostic::Diagnostic;
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
    /// The names the NAMES block declares, beside the numbers they name.
    pub names: Names,
    /// The units the UNITS line declares ([`Units::NONE`] without one).
    /// Every number of this model (co-ordinates, PARA values, motion,
    /// masses, loads, design ranges, targets) is already in the core's
    /// units; outputs are converted back with [`Units::from_core`] and the
    /// kind of each quantity ([`Compiled::dims`]).
    pub units: Units,
    /// The kind of each co-ordinate and row of the model.
    pub dims: ModelDims,
    /// Numbers that look as if they were written in another unit (an
    /// angle of 720 in radians): warnings, the run goes on.
    pub warnings: Vec<Diagnostic>,
    /// The masses and loads (0-based indices): `Some` exactly for a
    /// [`Mode::DynAna`] or [`Mode::DynSim`] deck.
    pub dynamics: Option<Dynamics>,
    /// The DYNAMICS line each mass and load of [`Compiled::dynamics`]
    /// comes from, by what a [`mechfem_core::DynamicsFault`] calls it
    /// (the deck refuses a second line of one keyword on one thing, so a
    /// source has one line); empty without masses and loads.
    pub dynamics_lines: Vec<(DynamicSource, usize)>,
    /// The design variables, targets, bounds and objective of the OPTIMISE
    /// block: `Some` exactly for a [`Mode::KinOpt`] deck.
    pub optimise: Option<Optimise>,
    /// The toleranced dimensions and the bands of the TOLERANCE block:
    /// `Some` exactly when a `KIN ANA` or `DYN ANA` deck has one.
    pub tolerance: Option<crate::tolerance::Tolerance>,
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

impl Compiled {
    /// The label of buffer `b`: its NAMES label, else made from the names
    /// of what it records (`psi`, `dpsi/dphi`, `C.x`), else the deck's
    /// numbers (`x9`, `ANGB(8)`).
    pub fn label(&self, b: &Buffer) -> String {
        if let Some((band, rss)) = self.band_of(b.number) {
            let source = Buffer { number: band.source, ..*b };
            return format!("{} {}", self.label(&source), if rss { "rss" } else { "worst" });
        }
        self.names.label(&self.mechanism, b.number, b.quantity)
    }

    /// The unit buffer `b` is shown in (`mm`, `deg`, `mm/deg`, `-`, `N·mm`;
    /// "" without UNITS).
    pub fn unit(&self, b: &Buffer) -> String {
        self.dims.quantity(&self.mechanism, b.quantity).symbol(&self.units)
    }

    /// The prescribed and dependent rows with their PARA values and FORM
    /// factors as the deck writes them (in its UNITS), for an echo of the
    /// model; [`Compiled::prescribed`] and [`Compiled::dependent`] hold the
    /// core's.
    pub fn rows_as_written(&self) -> [Vec<RowInfo>; 2] {
        let [mut prescribed, mut dependent] = [self.prescribed.clone(), self.dependent.clone()];
        if self.units.is_identity() {
            return [prescribed, dependent];
        }
        let term_dim = |t: &TermInfo| {
            let Some(e) = t.element.checked_sub(1).and_then(|k| self.elements.get(k)) else { return Dim::NONE };
            match e.ty.form_index(t.name).and_then(|k| e.ty.form_dimensions().get(k)) {
                Some(Dimension::Any) => e.coords.first().map_or(Dim::LENGTH, |&c| self.dims.coord(c.saturating_sub(1))),
                Some(&d) => Dim::of(d),
                None => Dim::NONE,
            }
        };
        for (rows, prescribed) in [(&mut prescribed, true), (&mut dependent, false)] {
            for (k, r) in rows.iter_mut().enumerate() {
                let row = self.dims.form(if prescribed { FormRef::Prescribed(k) } else { FormRef::Dependent(k) });
                r.para = r.para.map(|p| self.units.as_written(row, p));
                for t in &mut r.terms {
                    // The core's factor turns the term's core number into the row's: f s_term / s_row.
                    let (a, b) = (row.out_scale(&self.units), term_dim(t).out_scale(&self.units));
                    if a != b {
                        t.factor = t.factor * a / b;
                    }
                }
            }
        }
        [prescribed, dependent]
    }

    /// How many of the deck's units one of the core's is, for what `q`
    /// records: multiply a column by it to give it in the deck's units.
    pub fn out_scale(&self, q: Quantity) -> f64 {
        self.dims.quantity(&self.mechanism, q).out_scale(&self.units)
    }
}
