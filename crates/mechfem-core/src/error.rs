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
    /// The corrector moved the mechanism farther than the predictor: it
    /// probably jumped to another assembly branch.
    #[error("the correction ({corrected:e}) went farther than the prediction ({predicted:e}): the step may jump to another branch")]
    BranchJump {
        /// Length of the predicted step in co-ordinate space.
        predicted: f64,
        /// Length of the Newton correction.
        corrected: f64,
    },
    /// A result was asked for before the transfer functions it needs were computed.
    #[error("the transfer functions were not computed at this position")]
    NotComputed,
    /// A motion mode this version cannot run.
    #[error("{0}")]
    Unsupported(&'static str),
    /// The observer asked the run to stop (for example on Ctrl-C).
    #[error("the run was interrupted")]
    Interrupted,
    /// A computed value became NaN or infinite.
    #[error("a computed value is not finite")]
    NonFinite,
    /// A simulation's integrator could not go on.
    #[error("the simulation stopped at time {time}: {reason}")]
    Simulation {
        /// The time it reached.
        time: f64,
        /// Why it could not go on.
        reason: &'static str,
    },
}
