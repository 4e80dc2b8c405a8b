//! Finite-element kinematics of planar mechanisms.
//!
//! A tour, from the ground up, in the order data flows:
//!
//! * [`elements`]: the element catalogue. Each element type gives its form
//!   parameters (lengths, angles, local u/v, ...) as functions of its
//!   co-ordinates, with first and second derivatives.
//! * [`model`]: a [`MechanismBuilder`] places elements on shared
//!   co-ordinates and declares which form parameters are prescribed (rows of
//!   D^c), which are inputs, and which are dependent outputs. It compiles to
//!   an immutable [`Mechanism`] and a mutable [`State`], plain data both.
//! * [`solver`]: Newton-Raphson position analysis, including the adjustment
//!   of rough initial co-ordinates, the transfer functions of first and
//!   second order (theory eqs. 5.16-5.32) at a position, and their design
//!   sensitivities, in a workspace ([`Kinematics`]) allocated once per run.
//! * [`dynamics`]: the mass and load model.
//! * [`motion`]: the input motion program and the stepping core: prediction,
//!   correction and automatic step subdivision, free motion, and the
//!   location of limit positions.
//! * [`run`](mod@run): the run modes, a file each: the kinematic run
//!   ([`run()`]), inverse dynamics ([`InverseDynamics`]), simulation
//!   ([`simulate`]) and one design of an optimiser ([`design`]), with what
//!   they hand on at every position ([`Observer`], [`Recorder`]).
//! * [`names`] and [`units`]: what a designer calls the model's numbers,
//!   and the scale of each kind of quantity between the model's units and
//!   the core's (SI, or the numbers as they are), applied at the edges.
//! * [`batch`]: many independent runs (the variants of a design study) on
//!   every core.
//!
//! Equation numbers refer to chapter 5 of the theory text that mechfem
//! implements (numerical kinematics with finite elements).

pub mod batch;
pub mod dynamics;
pub mod elements;
pub mod error;
pub mod model;
pub mod motion;
pub mod names;
pub mod run;
mod sizes;
pub mod solver;
pub mod units;
pub mod worded;

pub use elements::{Dimension, Element, ElementType, FormEval, Order, Slot};
pub use error::{
    DeckTerm, DynamicQuantity, DynamicSource, DynamicsFault, ElementError, Lost, ModelError, NoSuch, Piece, SolveError,
    Unsupported,
};
pub use model::{FormRef, Mechanism, MechanismBuilder, State, Term};
pub use motion::{InputMotion, LimitKind, LimitPosition, Motion};
pub use names::Names;
pub use run::dynamic_design;
pub use run::{design, run, simulate, InverseDynamics, Observer, PositionView, RunReport, SimReport, Stop};
pub use run::{record, record_evaluated, recorded_value, Layout, Quantity, Recorder};
pub use solver::Params;
pub use solver::{
    adjust, diagnose, AdjustInfo, DesignError, DesignVar, Kinematics, Mobility, NewtonInfo, Sensitivity, TransferOrder,
};
pub use units::{Dim, ModelDims, Units};
