//! Position analysis and transfer functions, split by verb:
//! [`lu`] factorises D^c (in diagonal blocks, dense, or banded for a large
//! mechanism), [`mobility`] explains a singular one, [`assemble`] builds
//! D^c, deformations and the second-order products element by element,
//! [`newton`] finds positions, [`transfer`] computes first- and
//! second-order transfer functions.

pub mod assemble;
pub mod lu;
pub mod mobility;
pub mod newton;
mod ordering;
pub mod sensitivity;
pub mod transfer;

pub use mobility::{diagnose, Mobility};
pub use newton::{adjust, correct, correct_with, AdjustInfo, NewtonInfo, TempInput};
pub use sensitivity::{DesignError, DesignVar, Sensitivity};
pub use transfer::{Kinematics, TransferOrder};

/// Tuning knobs of the position analysis.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Params {
    /// Newton stops when every kinematic deformation |eps(x) - eps^p| is
    /// below this (deck keyword ACCURACY). Where a row's value is so large
    /// that this is below what f64 can resolve, the bound is raised to 16 ulp
    /// of the value.
    pub tol: f64,
    /// Largest number of Newton iterations for one position (MAXITER).
    pub max_iter: usize,
    /// How many times a step of the inputs may be halved when Newton fails
    /// or jumps (2^max_halvings sub-steps at most).
    pub max_halvings: u32,
}

impl Default for Params {
    fn default() -> Self {
        Params { tol: 1e-10, max_iter: 25, max_halvings: 12 }
    }
}
