//! Position analysis and transfer functions, split by verb:
//! [`newton`] finds positions, [`transfer`] computes first- and
//! second-order transfer functions, [`sensitivity`] their derivatives with
//! respect to the design, and [`mobility`] explains a singular D^c.
//!
//! Inside, `assemble` builds D^c, the deformations and the second-order
//! products element by element, `lu` factorises D^c (in diagonal blocks,
//! dense, or banded for a large mechanism, as `ordering` arranges it), and
//! `plan` chooses D^c's storage once for every mechanism structure.

pub(crate) mod assemble;
pub(crate) mod lu;
pub mod mobility;
pub mod newton;
mod ordering;
mod params;
mod plan;
pub mod sensitivity;
pub mod transfer;

pub use mobility::{diagnose, Mobility};
pub use newton::{adjust, correct, correct_with, AdjustInfo, NewtonInfo, TempInput};
pub use params::Params;
pub use sensitivity::{DesignError, DesignVar, Sensitivity};
pub use transfer::{Kinematics, TransferOrder};
