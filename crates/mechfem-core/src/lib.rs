//! Finite-element kinematics of planar mechanisms.
//!
//! A tour, in the order data flows:
//!
//! * [`elements`]: the element catalogue. Each element type gives its form
//!   parameters (lengths, angles, local u/v, ...) as functions of its
//!   co-ordinates, with first and second derivatives.
//! * [`model`]: a [`MechanismBuilder`] places elements on shared
//!   co-ordinates and declares which form parameters are prescribed (rows of
//!   D^c), which are inputs, and which are dependent outputs. It compiles to
//!   an immutable [`Mechanism`] and a mutable [`State`].
//! * [`solver`]: Newton-Raphson position analysis, including the adjustment
//!   of rough initial co-ordinates, and the transfer functions of first and
//!   second order (theory eqs. 5.16-5.32) at a position.
//! * [`motion`]: the input motion program and the loop over positions, with
//!   prediction, correction and automatic step subdivision.
//! * [`dynamics`]: masses and loads, and inverse dynamics at a position
//!   (stresses of the prescribed rows, drive forces, reactions, energies).
//! * [`record`]: the quantities that can be recorded per position.
//! * [`batch`]: many independent runs (the variants of a design study) on
//!   every core.
//!
//! Equation numbers refer to chapter 5 of the theory text that mechfem
//! implements (numerical kinematics with finite elements).

pub mod batch;
pub mod design;
pub mod dynamics;
pub mod elements;
pub mod error;
pub mod model;
pub mod motion;
pub mod record;
pub mod solver;

pub use elements::{Element, ElementType, FormEval, Order};
pub use error::{ElementError, ModelError, SolveError};
pub use model::{Mechanism, MechanismBuilder, State, Term};
pub use motion::{run, LimitKind, LimitPosition, Observer, PositionView, RunReport, Stop};
pub use motion::{InputMotion, Motion};
pub use record::{record, FormRef, Quantity, Recorder};
pub use solver::Params;
pub use solver::{
    adjust, diagnose, AdjustInfo, DesignError, DesignVar, Kinematics, Mobility, NewtonInfo, Sensitivity, TransferOrder,
};
