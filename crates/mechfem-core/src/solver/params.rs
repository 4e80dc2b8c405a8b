//! The tuning knobs of the position analysis.

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
