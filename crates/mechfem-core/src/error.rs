//! Errors of the core, typed and with the fields a caller needs to say
//! exactly what went wrong.

use thiserror::Error;

/// A form parameter that cannot be evaluated at the given co-ordinates.
#[derive(Debug, Clone, Copy, PartialEq, Error)]
pub enum ElementError {
    /// The two points that define a direction coincide (or are not finite).
    #[error("the points P and Q coincide, so the direction P->Q is undefined")]
    CoincidentPoints,
    /// A belt whose centre distance is not larger than |R_P - R_Q|.
    #[error("the belt has no free span: centre distance {l} <= |R_P - R_Q| = {d}")]
    NoBeltSpan {
        /// Centre distance.
        l: f64,
        /// |R_P - R_Q|.
        d: f64,
    },
    /// A gear radius of zero.
    #[error("the gear radius {name} is zero")]
    ZeroRadius {
        /// Which radius (its co-ordinate name, `R_a` or `R_c`).
        name: &'static str,
    },
}

/// Mistakes found while compiling a model.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum ModelError {
    /// An element refers to a co-ordinate that does not exist.
    #[error("element {element} refers to co-ordinate {coordinate}, but there are only {n_coords}")]
    UnknownCoordinate {
        /// Element index (0-based).
        element: usize,
        /// Co-ordinate index (0-based).
        coordinate: usize,
        /// Number of co-ordinates.
        n_coords: usize,
    },
    /// An element got the wrong number of co-ordinates.
    #[error("element {element} ({ty}) needs {expected} co-ordinates, got {got}")]
    WrongCoordinateCount {
        /// Element index.
        element: usize,
        /// Element type name.
        ty: &'static str,
        /// Required count.
        expected: usize,
        /// Given count.
        got: usize,
    },
    /// A form parameter index outside the element type's list.
    #[error("element {element} ({ty}) has no form parameter number {form}")]
    UnknownForm {
        /// Element index.
        element: usize,
        /// Element type name.
        ty: &'static str,
        /// Form index.
        form: usize,
    },
    /// A term names an element that does not exist.
    #[error("a form parameter refers to element {element}, but there are only {n_elements}")]
    UnknownElement {
        /// Element index.
        element: usize,
        /// Number of elements.
        n_elements: usize,
    },
    /// A prescribed or dependent row without terms.
    #[error("row {row} has no form parameters")]
    EmptyRow {
        /// Row index.
        row: usize,
    },
    /// D^c is not square.
    #[error("D^c is not square: {n_rows} prescribed form parameters for {n_moving} moving co-ordinates")]
    NotSquare {
        /// Prescribed rows.
        n_rows: usize,
        /// Moving co-ordinates.
        n_moving: usize,
    },
    /// More degrees of freedom than prescribed rows.
    #[error("{n_dof} degrees of freedom but only {n_rows} prescribed rows")]
    TooManyDof {
        /// Degrees of freedom.
        n_dof: usize,
        /// Prescribed rows.
        n_rows: usize,
    },
    /// A form parameter cannot be evaluated at the initial co-ordinates.
    #[error("element {element} cannot be evaluated at the initial co-ordinates: {source}")]
    Element {
        /// Element index.
        element: usize,
        /// What went wrong.
        #[source]
        source: ElementError,
    },
    /// A co-ordinate value that is NaN or infinite.
    #[error("co-ordinate {coordinate} is not a finite number")]
    NonFiniteCoordinate {
        /// Co-ordinate index.
        coordinate: usize,
    },
}

/// Failures of the position analysis.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum SolveError {
    /// A form parameter could not be evaluated.
    #[error("element {element}: {source}")]
    Element {
        /// Element index.
        element: usize,
        /// What went wrong.
        #[source]
        source: ElementError,
    },
    /// D^c is singular (a limit position, or a model that is not movable).
    #[error("D^c is singular (pivot {pivot:e} in column {column}): limit position or ill-posed model")]
    Singular {
        /// Column (moving co-ordinate index) where elimination broke down.
        column: usize,
        /// The pivot found there.
        pivot: f64,
    },
    /// Newton did not reach the tolerance.
    #[error("Newton iteration did not converge in {iterations} iterations (largest deformation {residual:e})")]
    NoConvergence {
        /// Iterations made.
        iterations: usize,
        /// Largest deformation at the end.
        residual: f64,
    },
    /// The corrector moved the mechanism too far from the prediction for a
    /// step along one branch: the step may cross a limit position or jump
    /// to another assembly branch.
    #[error("the correction ({corrected:e}) went too far from the prediction (a move of {predicted:e}): the step may jump to another branch")]
    BranchJump {
        /// Length of the predicted step in co-ordinate space.
        predicted: f64,
        /// Length of the Newton correction.
        corrected: f64,
    },
    /// det(D^c) changed sign within the smallest sub-step of a driven
    /// step: the step crosses a limit position of the input, or a point
    /// where two assembly branches meet.
    #[error("det(D^c) changed sign within the step (from {before:e} to {after:e}): the step crosses a limit position or a point where two assembly branches meet")]
    DetSignChange {
        /// det(D^c) where the sub-step started.
        before: f64,
        /// det(D^c) where it ended.
        after: f64,
    },
    /// A result was asked for before the transfer functions it needs were computed.
    #[error("the transfer functions were not computed at this position")]
    NotComputed,
    /// A motion or a request the model cannot run.
    #[error("{0}")]
    Unsupported(Unsupported),
    /// The observer asked the run to stop (for example on Ctrl-C).
    #[error("the run was interrupted")]
    Interrupted,
    /// A computed value became NaN or infinite.
    #[error("a computed value is not finite")]
    NonFinite,
    /// A result of the dynamics became NaN or infinite: a mass, a load or
    /// the motion is too large for the products the dynamics form of them.
    #[error("{0}")]
    Dynamics(DynamicsFault),
    /// A simulation's integrator could not go on.
    #[error("the simulation stopped at time {time}: {reason}")]
    Simulation {
        /// The time it reached.
        time: f64,
        /// Why it could not go on.
        reason: &'static str,
    },
}

/// Why a motion or a request cannot be run on a model.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Unsupported {
    /// A MOV_FUNC table has fewer rows than the motion has positions.
    TableTooShort,
    /// Free motion given for one input while another is driven.
    FreeWithDriven,
    /// An input that moves under the forces, in a kinematic run.
    DynamicNeedsSimulation,
    /// Free motion of a mechanism with more than one degree of freedom.
    FreeNeedsOneDof,
    /// Free motion found no tangent it can follow.
    FreeFoundNoDirection,
    /// An input that moves under the forces has no mass or inertia.
    DynamicWithoutMass,
    /// Free motion in a simulation.
    FreeNotTimed,
    /// A design variable that the model does not have.
    UnknownDesignVariable,
    /// An extremum asked of something other than a position quantity of a one-DOF mechanism.
    ExtremumNeedsOneDof,
}

/// A piece of a fixed message: plain words, or a term the deck spells its
/// own way, which a front end that does not speak the deck words in its
/// own terms.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Piece {
    /// Words that every front end says the same way.
    Text(&'static str),
    /// A term of the deck.
    Term(DeckTerm),
}

impl Piece {
    /// The piece as the deck says it.
    pub fn deck(self) -> &'static str {
        match self {
            Piece::Text(t) => t,
            Piece::Term(t) => t.deck(),
        }
    }
}

/// A term of the deck that a message may use.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DeckTerm {
    /// "a degree of freedom": an input.
    ADegreeOfFreedom,
    /// `MOV_FREE`: free motion.
    FreeMotion,
    /// `MOV_DYN`: an input that moves under the forces.
    Dynamic,
    /// `DYN SIM`: a simulation.
    Simulation,
}

impl DeckTerm {
    /// A stable code of the term, snake case.
    pub fn code(self) -> &'static str {
        match self {
            DeckTerm::ADegreeOfFreedom => "a_degree_of_freedom",
            DeckTerm::FreeMotion => "free_motion",
            DeckTerm::Dynamic => "dynamic",
            DeckTerm::Simulation => "simulation",
        }
    }

    /// The term as the deck says it.
    pub fn deck(self) -> &'static str {
        match self {
            DeckTerm::ADegreeOfFreedom => "a degree of freedom",
            DeckTerm::FreeMotion => "MOV_FREE",
            DeckTerm::Dynamic => "MOV_DYN",
            DeckTerm::Simulation => "DYN SIM",
        }
    }
}

impl std::fmt::Display for Unsupported {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        self.pieces().iter().try_for_each(|p| f.write_str(p.deck()))
    }
}

impl std::error::Error for Unsupported {}

impl Unsupported {
    /// The message in pieces; [`Display`](std::fmt::Display) joins them as the deck says them.
    pub fn pieces(self) -> &'static [Piece] {
        use DeckTerm::*;
        use Piece::{Term, Text};
        match self {
            Unsupported::TableTooShort => &[Text("a motion table has fewer rows than positions")],
            Unsupported::FreeWithDriven => &[Text("free motion cannot be mixed with driven inputs")],
            Unsupported::DynamicNeedsSimulation => &[
                Text("an input that moves under the forces ("),
                Term(Dynamic),
                Text(") needs a simulation ("),
                Term(Simulation),
                Text(")"),
            ],
            Unsupported::FreeNeedsOneDof => &[
                Text("free motion ("),
                Term(FreeMotion),
                Text(") needs a mechanism with exactly one degree of freedom"),
            ],
            Unsupported::FreeFoundNoDirection => &[Text(
                "free motion found no direction to move in: the mechanism has more than one degree of freedom here",
            )],
            Unsupported::DynamicWithoutMass => &[
                Term(ADegreeOfFreedom),
                Text(" that moves under the forces ("),
                Term(Dynamic),
                Text(") has no mass or inertia to move"),
            ],
            Unsupported::FreeNotTimed => {
                &[Text("free motion ("), Term(FreeMotion), Text(") has no timing: it cannot be simulated")]
            }
            Unsupported::UnknownDesignVariable => &[Text("a design variable is not in the model")],
            Unsupported::ExtremumNeedsOneDof => &[Text("an extremum needs a position quantity of a one-DOF mechanism")],
        }
    }
}

/// A result of the dynamics that is not finite at a position, and the mass
/// or load that made it so.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DynamicsFault {
    /// What is not finite.
    pub quantity: DynamicQuantity,
    /// What it belongs to.
    pub source: DynamicSource,
}

/// A result of the dynamics, in a [`DynamicsFault`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DynamicQuantity {
    /// A mass times gravity.
    Weight,
    /// A mass times its acceleration, or an inertia times its angular one.
    InertiaForce,
    /// The generalised force of a load, or a point force, on the co-ordinates.
    Force,
    /// A share of the kinetic energy.
    KineticEnergy,
    /// A share of the potential energy.
    PotentialEnergy,
    /// A share of the mass matrix in the degrees of freedom.
    MassMatrix,
    /// A share of the power of the loads or the drives.
    Power,
    /// The generalised stress of a prescribed row.
    Stress,
    /// The reaction on a fixed co-ordinate.
    Reaction,
    /// The accelerations of the degrees of freedom moved by the forces.
    Acceleration,
}

impl DynamicQuantity {
    /// The quantity in words.
    pub fn words(self) -> &'static str {
        match self {
            DynamicQuantity::Weight => "the weight",
            DynamicQuantity::InertiaForce => "the inertia force",
            DynamicQuantity::Force => "the force",
            DynamicQuantity::KineticEnergy => "the kinetic energy",
            DynamicQuantity::PotentialEnergy => "the potential energy",
            DynamicQuantity::MassMatrix => "the share of the mass matrix",
            DynamicQuantity::Power => "the power",
            DynamicQuantity::Stress => "the stress",
            DynamicQuantity::Reaction => "the reaction",
            DynamicQuantity::Acceleration => "the accelerations",
        }
    }
}

/// What a result of the dynamics belongs to (0-based indices).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum DynamicSource {
    /// The body on an element (deck `MASS`).
    Body {
        /// Element index.
        element: usize,
    },
    /// A point mass (deck `PMASS`).
    PointMass {
        /// Co-ordinate index of the point's x.
        x: usize,
        /// Co-ordinate index of the point's y.
        y: usize,
    },
    /// A rotational inertia (deck `INERTIA`).
    Inertia {
        /// Co-ordinate index.
        coord: usize,
    },
    /// A point force (deck `FORCE`).
    Force {
        /// Co-ordinate index of the point's x.
        x: usize,
        /// Co-ordinate index of the point's y.
        y: usize,
    },
    /// A load on a form parameter.
    Load {
        /// The form parameter it acts on.
        form: crate::model::FormRef,
        /// Its deck keyword: `LOAD`, `LOADFUNC`, `SPRING` or `MOTOR`.
        keyword: &'static str,
    },
    /// A prescribed row.
    Row(usize),
    /// A fixed co-ordinate.
    Coordinate(usize),
    /// The degrees of freedom that move under the forces (deck `MOV_DYN`).
    FreeDofs,
    /// The drives of the prescribed motion together.
    Drives,
}

impl std::fmt::Display for DynamicsFault {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        use crate::model::FormRef;
        let of = match self.source {
            DynamicSource::Body { element } => format!("of the MASS on element {element}"),
            DynamicSource::PointMass { x, y } => format!("of the PMASS at co-ordinates {x}, {y}"),
            DynamicSource::Inertia { coord } => format!("of the INERTIA on co-ordinate {coord}"),
            DynamicSource::Force { x, y } => format!("of the FORCE at co-ordinates {x}, {y}"),
            DynamicSource::Load { form: FormRef::Prescribed(r), keyword } => format!("of the {keyword} on row {r}"),
            DynamicSource::Load { form: FormRef::Dependent(d), keyword } => {
                format!("of the {keyword} on dependent form parameter {d}")
            }
            DynamicSource::Row(r) => format!("of row {r}"),
            DynamicSource::Coordinate(i) => format!("on co-ordinate {i}"),
            DynamicSource::FreeDofs => "of the degrees of freedom moved by the forces".to_string(),
            DynamicSource::Drives => "of the drives".to_string(),
        };
        write!(f, "{} {of} is not finite", self.quantity.words())
    }
}

/// A thing of a model asked for by a number it does not have (a label of
/// co-ordinate 12 of a model with 10).
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
#[error("no {kind} {number}")]
pub struct NoSuch {
    /// What was asked for: `co-ordinate`, `row`, `input`, `buffer`.
    pub kind: &'static str,
    /// Its number as asked (a dependent row is negative).
    pub number: i64,
}

/// A promise broken between the core and its caller: a run's answer that
/// should be there and is not. Never the user's mistake.
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
pub enum Lost {
    /// A run of a batch gave no result and no error.
    #[error("a batch run was lost")]
    BatchRun,
    /// A run's table was handed over once already.
    #[error("a run's table was taken twice")]
    TableTakenTwice,
    /// A run came back without the compiled deck that ran it.
    #[error("a run came back without its compiled deck")]
    CompiledDeck,
}
