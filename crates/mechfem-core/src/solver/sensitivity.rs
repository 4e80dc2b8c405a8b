//! Design sensitivities at a position: the derivatives of the co-ordinates,
//! the dependent form parameters and their transfer functions with respect
//! to a design variable.

/// A design variable: a number of the model that a designer may change.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum DesignVar {
    /// The prescribed value of prescribed row r (0-based): a length, a local
    /// u or v, a fixed angle, a gear ratio, or an input's start value.
    Row(usize),
    /// The value of fixed co-ordinate i (0-based), e.g. a frame pivot.
    Fixed(usize),
}
