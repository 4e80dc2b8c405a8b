//! What the OPTIMISE block of a `KIN OPT` deck compiles to: the design
//! variables with their ranges, the least-squares targets, the bounds and
//! the objective, all referring to buffers of [`crate::Compiled::buffers`].
//!
//! The deck reader only states the problem; it neither evaluates nor
//! optimises anything. Positions are 0-based, as everywhere in the
//! compiled deck.

use mechfem_core::dynamics::MassVar;
use mechfem_core::DesignVar;

/// The compiled OPTIMISE block.
#[derive(Debug, Clone, PartialEq)]
pub struct Optimise {
    /// The design variables (VARY, VARYX), in deck order; at least one.
    pub vary: Vec<Vary>,
    /// The least-squares terms (TARGET, TARGETAT, TARGETEXT), in deck order.
    pub targets: Vec<Target>,
    /// The constraints (BOUND), in deck order.
    pub bounds: Vec<Bound>,
    /// The MINIMISE or MAXIMISE term, if any (at most one). There is at
    /// least one target or an objective.
    pub objective: Option<Objective>,
    /// The iteration limit (OPTSTEPS; 200 without it).
    pub steps: usize,
    /// Stop when the objective's relative change is below this (OPTTOL),
    /// if given.
    pub tol: Option<f64>,
    /// Stop when an iteration changes the objective f by less than
    /// `atol + rtol |f|` (OPTFTOL rtol atol), if given: `(rtol, atol)`.
    pub ftol: Option<(f64, f64)>,
    /// Free timing (FREETIME), if given.
    pub free_time: Option<FreeTime>,
    /// The input that must turn fully (FULLROT), if given.
    pub full_rotation: Option<FullRotation>,
    /// The frame angle (VARYFRAME), if given.
    pub frame: Option<FrameAngle>,
    /// The variables of the mass model (VARYM, mode `DYN ANA`), in deck
    /// order; they follow the `vary` ones.
    pub mass_vary: Vec<MassVary>,
    /// Line of the OPTIMISE header.
    pub line: usize,
}

impl Optimise {
    /// The iteration limit without OPTSTEPS.
    pub const DEFAULT_STEPS: usize = 200;
}

/// A design variable (`VARY r lo hi` or `VARYX i lo hi`) and its range.
/// Its start value is the deck's: the row's PARA, or the XFIX value.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Vary {
    /// The variable: [`DesignVar::Row`] (0-based prescribed row) for VARY,
    /// [`DesignVar::Fixed`] (0-based fixed co-ordinate) for VARYX.
    pub var: DesignVar,
    /// Lower end of the range (below `hi`).
    pub lo: f64,
    /// Upper end of the range.
    pub hi: f64,
    /// Line of the keyword.
    pub line: usize,
}

/// A least-squares term: `weight * (buffer - value)^2`, summed over the
/// values the kind gives.
#[derive(Debug, Clone, PartialEq)]
pub struct Target {
    /// The buffer compared (a number of [`crate::Compiled::buffers`]).
    pub buffer: u32,
    /// What it is compared with, and where.
    pub kind: TargetKind,
    /// The weight w (positive; 1 without it).
    pub weight: f64,
    /// Line of the keyword.
    pub line: usize,
}

/// What a [`Target`] compares its buffer with.
#[derive(Debug, Clone, PartialEq)]
pub enum TargetKind {
    /// `TARGET b file [w]`: one value per position from the file (`None`
    /// where the row is blank or `*`: that position is not compared).
    Values {
        /// The file name as the deck gives it (relative to the deck's folder).
        file: String,
        /// One entry per position, in order.
        values: Vec<Option<f64>>,
    },
    /// `TARGETAT b k value [w]`: the buffer at one position.
    At {
        /// The position, 0-based (the deck's k is 1-based).
        position: usize,
        /// The value the buffer should take there.
        value: f64,
    },
    /// `TARGETEXT b bref value [w]`: the buffer at every extremum of buffer
    /// `reference` along the motion.
    Extremum {
        /// The buffer whose extrema are meant: a position quantity,
        /// [`mechfem_core::Quantity::X0`] of a co-ordinate or
        /// [`mechfem_core::Quantity::E0`] of a dependent form parameter.
        reference: u32,
        /// The value the buffer should take there.
        value: f64,
    },
}

/// A constraint (`BOUND b lo hi`): the buffer stays within [lo, hi] at
/// every position.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Bound {
    /// The buffer constrained.
    pub buffer: u32,
    /// Lower limit (below `hi`).
    pub lo: f64,
    /// Upper limit.
    pub hi: f64,
    /// Line of the keyword.
    pub line: usize,
}

/// Whether the objective term is made small or large.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Sense {
    /// `MINIMISE`.
    Minimise,
    /// `MAXIMISE`.
    Maximise,
}

/// How the values of a buffer over the positions make one number.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Reduce {
    /// `MAX`: the largest value.
    Max,
    /// `MAXABS`: the largest absolute value.
    MaxAbs,
    /// `RMS`: the root mean square over the positions.
    Rms,
    /// `END`: the value at the last position.
    End,
}

impl Reduce {
    /// Every kind, in the order of the deck reference.
    pub const ALL: [Reduce; 4] = [Reduce::Max, Reduce::MaxAbs, Reduce::Rms, Reduce::End];

    /// The word of the deck, e.g. `MAXABS`.
    pub fn name(self) -> &'static str {
        match self {
            Reduce::Max => "MAX",
            Reduce::MaxAbs => "MAXABS",
            Reduce::Rms => "RMS",
            Reduce::End => "END",
        }
    }

    /// The kind spelled `word` (case-insensitive).
    pub fn from_name(word: &str) -> Option<Reduce> {
        Reduce::ALL.into_iter().find(|r| r.name().eq_ignore_ascii_case(word))
    }
}

/// The objective term (`MINIMISE kind b` or `MAXIMISE kind b`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Objective {
    /// Minimise or maximise.
    pub sense: Sense,
    /// How the buffer's values over the positions make one number.
    pub reduce: Reduce,
    /// The buffer.
    pub buffer: u32,
    /// The second component, if given: the objective is of the magnitude
    /// `sqrt(b^2 + b2^2)` at every position (a force's x and y).
    pub with: Option<u32>,
    /// Line of the keyword.
    pub line: usize,
}

/// What a `VARYM` line varies: one number of a DYNAMICS line.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum MassItem {
    /// `MASS`: the mass m of element k's MASS line.
    Mass,
    /// `U`: its centre of mass along the element's u-axis.
    U,
    /// `V`: its centre of mass along the element's v-axis.
    V,
    /// `J`: its moment of inertia about the centre of mass.
    J,
    /// `PMASS`: the mass of the PMASS at the point whose x is co-ordinate i.
    PointMass,
    /// `INERTIA`: the moment of inertia of the INERTIA on co-ordinate i.
    Inertia,
}

impl MassItem {
    /// Every item, in the order of the deck reference.
    pub const ALL: [MassItem; 6] =
        [MassItem::Mass, MassItem::U, MassItem::V, MassItem::J, MassItem::PointMass, MassItem::Inertia];

    /// The word of the deck, e.g. `PMASS`.
    pub fn name(self) -> &'static str {
        match self {
            MassItem::Mass => "MASS",
            MassItem::U => "U",
            MassItem::V => "V",
            MassItem::J => "J",
            MassItem::PointMass => "PMASS",
            MassItem::Inertia => "INERTIA",
        }
    }

    /// The item spelled `word` (case-insensitive).
    pub fn from_name(word: &str) -> Option<MassItem> {
        MassItem::ALL.into_iter().find(|r| r.name().eq_ignore_ascii_case(word))
    }

    /// The variable of `model` it names for the deck's element or
    /// co-ordinate `number` (1-based), if the DYNAMICS block has that line.
    pub fn var(self, model: &mechfem_core::dynamics::Dynamics, number: usize) -> Option<MassVar> {
        let k = number.checked_sub(1)?;
        match self {
            MassItem::Mass | MassItem::U | MassItem::V | MassItem::J => {
                model.bodies.iter().position(|b| b.element == k).map(|b| match self {
                    MassItem::Mass => MassVar::Mass(b),
                    MassItem::U => MassVar::CentreU(b),
                    MassItem::V => MassVar::CentreV(b),
                    _ => MassVar::BodyInertia(b),
                })
            }
            MassItem::PointMass => model.point_masses.iter().position(|p| p.x == k).map(MassVar::PointMass),
            MassItem::Inertia => model.inertias.iter().position(|i| i.coord == k).map(MassVar::Inertia),
        }
    }

    /// Its kind of quantity; `coord` is the kind of the co-ordinate an
    /// INERTIA sits on (a moment of inertia on an angle, a mass on a length).
    pub fn dim(self, coord: mechfem_core::Dim) -> mechfem_core::Dim {
        use mechfem_core::Dim;
        match self {
            MassItem::Mass | MassItem::PointMass => Dim::MASS,
            MassItem::U | MassItem::V => Dim::LENGTH,
            MassItem::J => Dim::INERTIA,
            MassItem::Inertia => crate::compile::inertia_on(coord),
        }
    }

    /// Whether it names an element's MASS line (else a co-ordinate).
    pub fn of_element(self) -> bool {
        matches!(self, MassItem::Mass | MassItem::U | MassItem::V | MassItem::J)
    }

    /// Whether it is a mass or a moment of inertia (a centre is not).
    pub fn is_mass(self) -> bool {
        !matches!(self, MassItem::U | MassItem::V)
    }
}

/// `VARYM what n lo hi`: a number of the mass model as a design variable.
/// Its start value is the DYNAMICS line's.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MassVary {
    /// Which number.
    pub item: MassItem,
    /// The deck's element k or co-ordinate i, 1-based as written.
    pub number: usize,
    /// The variable of the compiled mass model.
    pub var: MassVar,
    /// Lower end of the range (below `hi`).
    pub lo: f64,
    /// Upper end of the range.
    pub hi: f64,
    /// Line of the keyword.
    pub line: usize,
}

/// `FREETIME r [ORDERED] [WITHIN w]`: the input of prescribed row r takes a
/// value of its own at every position of the motion, a design variable that
/// starts at the motion's value there.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FreeTime {
    /// The input's prescribed row, 0-based.
    pub row: usize,
    /// Each value at or after the one before (`ORDERED`).
    pub ordered: bool,
    /// `WITHIN w` (with `ordered`): the last value at most w after the
    /// first, in the core's units (radians for an angle input).
    pub within: Option<f64>,
    /// Line of the keyword.
    pub line: usize,
}

/// `FULLROT r`: a design is feasible only if the input of row r turns
/// through a whole turn from its start without a limit position.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FullRotation {
    /// The input's prescribed row, 0-based.
    pub row: usize,
    /// Line of the keyword.
    pub line: usize,
}

/// `VARYFRAME i lo hi`: the frame (every fixed point, fixed angle and
/// angle input) turned about the fixed point whose x is co-ordinate i by a
/// design variable within [lo, hi], 0 being the deck's frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FrameAngle {
    /// The pivot's x co-ordinate, 0-based (its y is the next one).
    pub x: usize,
    /// Lower end of the range.
    pub lo: f64,
    /// Upper end of the range.
    pub hi: f64,
    /// Line of the keyword.
    pub line: usize,
}
