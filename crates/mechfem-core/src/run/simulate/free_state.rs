//! The free state of a mechanism with more free DOFs than the fixed-size
//! arrays cover, as the implicit method of the integrator library needs it.
//!
//! The library's Radau IIA sizes its error scale and the first Newton
//! iterate with `State::zeros()`, which has no length to go by: for a `Vec`
//! it is empty, and the method indexes past its end. [`FreeState`] is a
//! `Vec` whose `zeros()` has the length of the simulation under way on this
//! thread ([`set_dimension`]); everything else is `Vec`'s own arithmetic.

use differential_equations::tolerance::Tolerance;
use differential_equations::traits::State;
use std::cell::Cell;

thread_local! {
    /// The length of the free state of the simulation this thread runs.
    static DIMENSION: Cell<usize> = const { Cell::new(0) };
}

/// Sets the length of [`FreeState::zeros`] for the simulation this thread
/// is about to integrate.
pub(super) fn set_dimension(n: usize) {
    DIMENSION.with(|d| d.set(n));
}

#[derive(Clone, Debug)]
pub(super) struct FreeState(Vec<f64>);

impl AsRef<[f64]> for FreeState {
    fn as_ref(&self) -> &[f64] {
        &self.0
    }
}

impl AsMut<[f64]> for FreeState {
    fn as_mut(&mut self) -> &mut [f64] {
        &mut self.0
    }
}

impl super::system::Free for FreeState {
    fn from_slice(y: &[f64]) -> Self {
        FreeState(y.to_vec())
    }
}

impl State<f64> for FreeState {
    fn len(&self) -> usize {
        self.0.len()
    }

    fn get_component(&self, index: usize) -> f64 {
        self.0[index]
    }

    fn set_component(&mut self, index: usize, value: f64) {
        self.0[index] = value;
    }

    fn dot(&self, other: &Self) -> f64 {
        State::dot(&self.0, &other.0)
    }

    fn map_components_mut<F>(&mut self, f: F)
    where
        F: FnMut(usize, &mut f64),
    {
        State::map_components_mut(&mut self.0, f);
    }

    fn zeros_like(&self) -> Self {
        FreeState(vec![0.0; self.0.len()])
    }

    fn zeros() -> Self {
        FreeState(vec![0.0; DIMENSION.with(Cell::get)])
    }

    fn mul_add_assign(&mut self, alpha: f64, other: &Self) {
        State::mul_add_assign(&mut self.0, alpha, &other.0);
    }

    fn scale_mut(&mut self, alpha: f64) {
        State::scale_mut(&mut self.0, alpha);
    }

    fn fill(&mut self, value: f64) {
        self.0.fill(value);
    }

    fn copy_from_state(&mut self, other: &Self) {
        self.0.clone_from(&other.0);
    }

    fn norm_squared(&self) -> f64 {
        State::norm_squared(&self.0)
    }

    fn diff_norm_squared(&self, other: &Self) -> f64 {
        State::diff_norm_squared(&self.0, &other.0)
    }

    fn error_norm(&self, y_new: &Self, err: &Self, atol: &Tolerance<f64>, rtol: &Tolerance<f64>) -> f64 {
        State::error_norm(&self.0, &y_new.0, &err.0, atol, rtol)
    }

    fn error_norm_inf(&self, y_new: &Self, err: &Self, atol: &Tolerance<f64>, rtol: &Tolerance<f64>) -> f64 {
        State::error_norm_inf(&self.0, &y_new.0, &err.0, atol, rtol)
    }
}
