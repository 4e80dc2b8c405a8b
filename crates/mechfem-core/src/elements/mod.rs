//! The element catalogue.
//!
//! An element is a group of co-ordinates plus the form parameters that are
//! functions of them (theory, section 5.4). Elements hold no data of their own:
//! lengths, radii and transmission ratios are co-ordinates or prescribed form
//! parameters, so an element instance in a model is just its type and the
//! indices of its co-ordinates.
//!
//! Each type lives in its own file and implements [`Element`]; [`ElementType`]
//! gathers them for dispatch. Adding a type is one file plus one line in each
//! `match` of this module.

mod bin;
mod blt;
mod crd;
mod gr1;
mod gr2;
mod hlf;
mod local;
mod rk1;
mod rk2;
mod tr1;
mod tr2;

pub use bin::Bin;
pub use blt::Blt;
pub use crd::Crd;
pub use gr1::Gr1;
pub use gr2::Gr2;
pub use hlf::Hlf;
pub use rk1::Rk1;
pub use rk2::Rk2;
pub use tr1::Tr1;
pub use tr2::Tr2;

use crate::error::ElementError;

/// The largest number of co-ordinates any element type has.
pub const MAX_COORDS: usize = 8;

/// How far an evaluation goes: the value only, also the first derivatives
/// (a row of D), or also the second derivatives (a matrix D_kl).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum Order {
    /// Value only (order zero).
    Value = 0,
    /// Value and gradient.
    First = 1,
    /// Value, gradient and Hessian.
    Second = 2,
}

/// Number of intermediate results a [`FormEval`] keeps for [`Element::second`].
pub const AUX: usize = 6;

/// One form parameter evaluated at an element's co-ordinates, in the
/// element's own co-ordinate order.
///
/// Only the first `n` entries of `grad` and the leading `n x n` block of `hess`
/// are meaningful, `n` being the element's number of co-ordinates; an
/// evaluation writes every one of them up to the order it was asked for.
#[derive(Debug, Clone, Copy)]
pub struct FormEval {
    /// Value of the form parameter.
    pub value: f64,
    /// First derivatives with respect to the element's co-ordinates.
    pub grad: [f64; MAX_COORDS],
    /// Intermediate results of an evaluation to first order or more that the
    /// element type's [`Element::second`] reuses (their meaning is the
    /// element type's own: a direction's cosine and sine, a reciprocal
    /// length, ...).
    pub aux: [f64; AUX],
    /// Second derivatives (symmetric).
    pub hess: [[f64; MAX_COORDS]; MAX_COORDS],
}

impl Default for FormEval {
    fn default() -> Self {
        FormEval { value: 0.0, grad: [0.0; MAX_COORDS], aux: [0.0; AUX], hess: [[0.0; MAX_COORDS]; MAX_COORDS] }
    }
}

/// What a co-ordinate or a form parameter measures. Decks have no unit of
/// length, so this is the whole of a quantity's unit: the front ends name
/// units and convert degrees from it, and tell a point's pair of
/// co-ordinates from an angle.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Dimension {
    /// A length (a point's x or y, a radius, a distance).
    Length,
    /// An angle in radians.
    Angle,
    /// A pure number (a transmission ratio).
    Ratio,
    /// Whatever the co-ordinate is: the single co-ordinate element takes the
    /// dimension of the co-ordinate it is put on, which other elements set.
    Any,
}

impl Dimension {
    /// The word the binding and the documentation use: `length`, `angle`,
    /// `ratio`, `any`.
    pub fn name(self) -> &'static str {
        match self {
            Dimension::Length => "length",
            Dimension::Angle => "angle",
            Dimension::Ratio => "ratio",
            Dimension::Any => "any",
        }
    }
}

/// How a deck's ELEM line gives an element's co-ordinates: a point is two
/// co-ordinate numbers (x, y) that the named front end takes as one point,
/// an angle and a scalar one number each.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Slot {
    /// A point: the two co-ordinates `x<name>`, `y<name>` in a row.
    Point,
    /// An angle co-ordinate.
    Angle,
    /// Any other single co-ordinate (a ratio, a radius, a CRD's value).
    Scalar,
}

impl Slot {
    /// One letter per slot, as the Python front spells an element's slots:
    /// `P`, `a`, `s`.
    pub fn letter(self) -> char {
        match self {
            Slot::Point => 'P',
            Slot::Angle => 'a',
            Slot::Scalar => 's',
        }
    }
}

/// Behaviour shared by every element type.
///
/// `branch` is the element's angle memory: an element whose form parameters
/// depend on an `atan2` angle picks the value `2*pi*k` away from the principal
/// one that lies closest to `*branch`, and stores it back. A NaN branch means
/// "first evaluation": the principal value in (-pi, pi] is taken. This is how
/// a crank turned through many revolutions reports a continuous angle.
pub trait Element {
    /// Three-character name used in decks.
    const NAME: &'static str;
    /// Names of the co-ordinates, in deck order.
    const COORDS: &'static [&'static str];
    /// Four-character names of the form parameters.
    const FORMS: &'static [&'static str];
    /// What each co-ordinate measures, in the order of `COORDS`.
    const COORD_DIMENSIONS: &'static [Dimension];
    /// What each form parameter measures, in the order of `FORMS`.
    const FORM_DIMENSIONS: &'static [Dimension];

    /// Evaluates form parameter `form` (an index into `FORMS`) at the
    /// element's co-ordinates `x` up to `order`.
    fn eval(form: usize, x: &[f64], branch: &mut f64, order: Order, out: &mut FormEval) -> Result<(), ElementError>;

    /// The co-ordinates form parameter `form` can depend on, as a bit mask
    /// over the element's co-ordinates (bit k: co-ordinate k). Its
    /// derivatives with respect to the others are zero everywhere; D^c's
    /// sparsity, and the blocks it is factorised in, follow from this.
    fn depends(form: usize) -> u32 {
        let _ = form;
        (1 << Self::COORDS.len()) - 1
    }

    /// The second derivative of form parameter `form` at `x` along the
    /// directions `a` and `b` (both in the element's co-ordinate order):
    /// `sum_kl D_kl a_k b_l`, the element's share of the second-order
    /// products of eqs. 5.22 and 5.28. `first` is this form parameter's
    /// evaluation at `x` to first order or more, whose intermediate results
    /// it may reuse. NaN where the form parameter is not defined.
    ///
    /// The default contracts the Hessian of [`Element::eval`]; element types
    /// on the hot path of a motion write the product directly, without the
    /// Hessian.
    fn second(form: usize, x: &[f64], first: &FormEval, a: &[f64], b: &[f64]) -> f64 {
        let _ = first;
        let (mut out, mut branch) = (FormEval::default(), f64::NAN);
        if Self::eval(form, x, &mut branch, Order::Second, &mut out).is_err() {
            return f64::NAN;
        }
        hess_product(&out, x.len(), a, b)
    }
}

/// `sum_kl hess_kl a_k b_l` over the leading n x n block.
pub(crate) fn hess_product(e: &FormEval, n: usize, a: &[f64], b: &[f64]) -> f64 {
    let mut s = 0.0;
    for k in 0..n {
        let row: f64 = (0..n).map(|l| e.hess[k][l] * b[l]).sum();
        s += a[k] * row;
    }
    s
}

/// Every element type of the catalogue (`elements.md`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ElementType {
    /// Binary (truss) element `BIN`.
    Bin,
    /// Half beam `HLF`: a point and an angle co-ordinate.
    Hlf,
    /// Ternary-1 `TR1`: half beam plus point R in its local frame.
    Tr1,
    /// Ternary-2 `TR2`: binary plus point R in the frame along P->Q.
    Tr2,
    /// Gear pair `GR1`, transmission ratio as a co-ordinate.
    Gr1,
    /// Gear pair `GR2`, radii as co-ordinates.
    Gr2,
    /// Pinion and rack `RK1` on a ternary-1 frame.
    Rk1,
    /// Pinion and rack `RK2` on a ternary-2 frame.
    Rk2,
    /// Belt over two wheels `BLT`.
    Blt,
    /// Single co-ordinate `CRD`.
    Crd,
}

macro_rules! dispatch {
    ($ty:expr, $t:ident => $body:expr) => {
        match $ty {
            ElementType::Bin => {
                type $t = Bin;
                $body
            }
            ElementType::Hlf => {
                type $t = Hlf;
                $body
            }
            ElementType::Tr1 => {
                type $t = Tr1;
                $body
            }
            ElementType::Tr2 => {
                type $t = Tr2;
                $body
            }
            ElementType::Gr1 => {
                type $t = Gr1;
                $body
            }
            ElementType::Gr2 => {
                type $t = Gr2;
                $body
            }
            ElementType::Rk1 => {
                type $t = Rk1;
                $body
            }
            ElementType::Rk2 => {
                type $t = Rk2;
                $body
            }
            ElementType::Blt => {
                type $t = Blt;
                $body
            }
            ElementType::Crd => {
                type $t = Crd;
                $body
            }
        }
    };
}

impl ElementType {
    /// Every type, in catalogue order.
    pub const ALL: [ElementType; 10] = [
        ElementType::Bin,
        ElementType::Hlf,
        ElementType::Tr1,
        ElementType::Tr2,
        ElementType::Gr1,
        ElementType::Gr2,
        ElementType::Rk1,
        ElementType::Rk2,
        ElementType::Blt,
        ElementType::Crd,
    ];

    /// The type with this deck name (case-insensitive), if any.
    pub fn from_name(name: &str) -> Option<ElementType> {
        Self::ALL.into_iter().find(|t| t.name().eq_ignore_ascii_case(name))
    }

    /// Three-character deck name.
    pub fn name(self) -> &'static str {
        dispatch!(self, T => T::NAME)
    }

    /// Co-ordinate names in deck order.
    pub fn coord_names(self) -> &'static [&'static str] {
        dispatch!(self, T => T::COORDS)
    }

    /// Number of co-ordinates.
    pub fn n_coords(self) -> usize {
        self.coord_names().len()
    }

    /// Form-parameter names.
    pub fn form_names(self) -> &'static [&'static str] {
        dispatch!(self, T => T::FORMS)
    }

    /// What each co-ordinate measures, in deck order.
    pub fn coord_dimensions(self) -> &'static [Dimension] {
        dispatch!(self, T => T::COORD_DIMENSIONS)
    }

    /// What each form parameter measures, in the order of [`Self::form_names`].
    pub fn form_dimensions(self) -> &'static [Dimension] {
        dispatch!(self, T => T::FORM_DIMENSIONS)
    }

    /// The co-ordinates grouped as a deck's front end names them: a length
    /// co-ordinate `x<name>` followed by `y<name>` is a point, an angle is
    /// an angle, anything else a scalar.
    pub fn slots(self) -> Vec<Slot> {
        let (names, dims) = (self.coord_names(), self.coord_dimensions());
        let mut out = Vec::with_capacity(names.len());
        let mut k = 0;
        while k < names.len() {
            let pair = names.get(k + 1).is_some_and(|next| {
                dims[k] == Dimension::Length
                    && names[k].strip_prefix('x').is_some_and(|p| !p.is_empty() && next.strip_prefix('y') == Some(p))
            });
            out.push(if pair {
                Slot::Point
            } else if dims[k] == Dimension::Angle {
                Slot::Angle
            } else {
                Slot::Scalar
            });
            k += if pair { 2 } else { 1 };
        }
        out
    }

    /// Index of the form parameter with this name (case-insensitive).
    pub fn form_index(self, name: &str) -> Option<usize> {
        self.form_names().iter().position(|f| f.eq_ignore_ascii_case(name))
    }

    /// The co-ordinates form parameter `form` depends on; see [`Element::depends`].
    pub fn depends(self, form: usize) -> u32 {
        dispatch!(self, T => T::depends(form))
    }

    /// Evaluates form parameter `form` of this type; see [`Element::eval`].
    #[inline]
    pub fn eval(
        self,
        form: usize,
        x: &[f64],
        branch: &mut f64,
        order: Order,
        out: &mut FormEval,
    ) -> Result<(), ElementError> {
        dispatch!(self, T => T::eval(form, x, branch, order, out))
    }

    /// Second derivative of form parameter `form` of this type along `a`
    /// and `b`; see [`Element::second`].
    #[inline]
    pub fn second(self, form: usize, x: &[f64], first: &FormEval, a: &[f64], b: &[f64]) -> f64 {
        dispatch!(self, T => T::second(form, x, first, a, b))
    }

    /// [`Self::eval`] of an element whose co-ordinates are `x[coords[k]]`.
    /// Indices are checked when a model is built; one out of range reads NaN.
    #[inline(always)]
    pub(crate) fn eval_at(
        self,
        form: usize,
        coords: &[usize; MAX_COORDS],
        x: &[f64],
        branch: &mut f64,
        order: Order,
        out: &mut FormEval,
    ) -> Result<(), ElementError> {
        dispatch!(self, T => {
            let xe = gather::<{ MAX_COORDS }>(T::COORDS.len(), coords, x);
            T::eval(form, &xe[..T::COORDS.len()], branch, order, out)
        })
    }

    /// [`Self::second`] of an element whose co-ordinates are `x[coords[k]]`,
    /// along the vectors `a` and `b` over the columns of D^c (`cols[k]`, a
    /// fixed co-ordinate having no column and not moving).
    // Always: the second-order products call it for every term and pair of
    // vectors, and the compiler, seeing it called from the sensitivities as
    // well, would otherwise keep it a call (a fifth of a second-order run).
    #[inline(always)]
    pub(crate) fn second_at(
        self,
        form: usize,
        (coords, cols): (&[usize; MAX_COORDS], &[usize; MAX_COORDS]),
        x: &[f64],
        first: &FormEval,
        a: &[f64],
        b: &[f64],
    ) -> f64 {
        dispatch!(self, T => {
            let n = T::COORDS.len();
            let xe = gather::<{ MAX_COORDS }>(n, coords, x);
            let ae = gather::<{ MAX_COORDS }>(n, cols, a);
            let be = if std::ptr::eq(a, b) { ae } else { gather::<{ MAX_COORDS }>(n, cols, b) };
            T::second(form, &xe[..n], first, &ae[..n], &be[..n])
        })
    }
}

/// The first `n` entries `v[idx[k]]`, 0 where an index is out of range (a
/// fixed co-ordinate's missing column).
#[inline(always)]
fn gather<const M: usize>(n: usize, idx: &[usize; M], v: &[f64]) -> [f64; M] {
    let mut out = [0.0; M];
    for k in 0..n.min(M) {
        out[k] = v.get(idx[k]).copied().unwrap_or(0.0);
    }
    out
}

/// `atan2(dy, dx)` moved by a multiple of 2*pi to lie closest to `*branch`
/// (principal value when the branch is NaN); the branch is updated.
///
/// The principal value is fdlibm's `atan2` (the `libm` crate: within one
/// unit in the last place, like the platform's, and several times cheaper
/// than glibc's, whose exactly rounded result and errno handling cost most of
/// an element's evaluation).
#[inline]
pub(crate) fn tracked_atan2(dy: f64, dx: f64, branch: &mut f64) -> f64 {
    use std::f64::consts::{PI, TAU};
    let mut beta = libm::atan2(dy, dx);
    // Within pi of the remembered value the principal value is the closest.
    let gap = *branch - beta;
    if branch.is_finite() && gap.abs() >= PI {
        // One turn away, as a crank is at every step of its second half:
        // that many turns without `round` (a call, not an instruction, on
        // the baseline x86-64).
        let k = if gap.abs() < 2.5 * PI { gap.signum() } else { (gap / TAU).round() };
        beta += k * TAU;
    }
    *branch = beta;
    beta
}

#[cfg(test)]
pub(crate) mod fd;

#[cfg(test)]
mod catalogue_tests {
    use super::{Dimension, ElementType};

    /// The slots and dimensions of every type, as the deck specification's
    /// element table gives them (written out here, not computed).
    #[test]
    fn slots_and_dimensions_follow_the_specification() {
        let expected = [
            ("BIN", "PP", "LLLL", "LA"),
            ("HLF", "Pa", "LLA", "A"),
            ("TR1", "PaP", "LLALL", "ALL"),
            ("TR2", "PPP", "LLLLLL", "LALL"),
            ("GR1", "aaas", "AAAR", "A"),
            ("GR2", "aaass", "AAALL", "A"),
            ("RK1", "PaPsa", "LLALLLA", "L"),
            ("RK2", "PPPsa", "LLLLLLLA", "L"),
            ("BLT", "PaPass", "LLALLALL", "LAL"),
            ("CRD", "s", "*", "*"),
        ];
        let letter = |d: &Dimension| match d {
            Dimension::Length => 'L',
            Dimension::Angle => 'A',
            Dimension::Ratio => 'R',
            Dimension::Any => '*',
        };
        assert_eq!(ElementType::ALL.len(), expected.len());
        for (ty, (name, slots, coords, forms)) in ElementType::ALL.into_iter().zip(expected) {
            assert_eq!(ty.name(), name);
            assert_eq!(ty.slots().iter().map(|s| s.letter()).collect::<String>(), slots, "{name}");
            assert_eq!(ty.coord_dimensions().iter().map(letter).collect::<String>(), coords, "{name}");
            assert_eq!(ty.form_dimensions().iter().map(letter).collect::<String>(), forms, "{name}");
            assert_eq!(ty.coord_dimensions().len(), ty.n_coords(), "{name}");
            assert_eq!(ty.form_dimensions().len(), ty.form_names().len(), "{name}");
        }
    }
}
