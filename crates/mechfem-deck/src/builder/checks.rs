//! The values a [`DeckBuilder`] takes, checked as the parser checks the
//! words it reads (`args.rs`, `statements.rs`, `statements/dynamics.rs`):
//! every value the parser would refuse is refused, with the item named as
//! the caller names it.

use mechfem_core::units::Dim;

use crate::diagnostic::{real, DiagnosticKind, Spanned};
use crate::keywords::Keyword;
use crate::statements::dynamics::{out_of_bounds, LARGEST, SMALLEST};
use crate::statements::{MAX_ITER, MAX_STEPS};

use super::{at, DeckBuilder, Refused};

/// The largest whole number a deck reads exactly (2^53).
const MAX_WHOLE: i64 = 9_007_199_254_740_992;

/// `the element 'crank'`, or `the element` without a name.
pub(super) fn label(noun: &str, name: Option<&str>) -> String {
    match name {
        Some(n) => format!("{noun} {n:?}"),
        None => noun.to_string(),
    }
}

/// A finite number (the parser reads no NaN or infinity).
pub(super) fn finite(b: &DeckBuilder, line: usize, v: f64, what: &str) -> Result<f64, Refused> {
    if v.is_finite() {
        return Ok(v);
    }
    Err(b.refuse(DiagnosticKind::NumberOutOfRange, line, format!("{what} is {v}, not a finite number")))
}

/// A whole number the deck reads exactly.
pub(super) fn whole(b: &DeckBuilder, line: usize, v: i64, what: &str) -> Result<i64, Refused> {
    if v.unsigned_abs() < MAX_WHOLE.unsigned_abs() {
        return Ok(v);
    }
    Err(b.refuse(DiagnosticKind::NumberOutOfRange, line, format!("a number of {what}, {v}, is too large")))
}

/// A number of the dynamics: 0, or a magnitude from 1e-100 to 1e100.
pub(super) fn bounded(b: &DeckBuilder, line: usize, v: f64, what: &str) -> Result<Spanned<f64>, Refused> {
    let v = finite(b, line, v, what)?;
    match out_of_bounds(what, v) {
        None => Ok(at(v, line)),
        Some((message, _)) => Err(b.refuse(DiagnosticKind::NumberOutOfRange, line, message)),
    }
}

/// `v` as a message gives it: with its unit of kind `dim` in the model's
/// units (`-0.5 kg`), bare where the model gives none or the kind is not
/// known (`None`).
fn valued(b: &DeckBuilder, v: f64, dim: Option<Dim>) -> String {
    let units = b.deck.units.as_ref().map(|u| u.units);
    match dim.zip(units).map(|(d, u)| d.symbol(&u)) {
        Some(unit) if !unit.is_empty() && unit != "-" => format!("{} {unit}", real(v)),
        _ => real(v),
    }
}

/// A number of the dynamics ([`bounded`]) that is not negative, of kind
/// `dim` (for the message's unit; `None` where the kind is not known yet).
pub(super) fn not_negative(
    b: &DeckBuilder,
    line: usize,
    v: f64,
    what: &str,
    dim: Option<Dim>,
) -> Result<Spanned<f64>, Refused> {
    let v = bounded(b, line, v, what)?;
    if v.value < 0.0 {
        let message = format!("{what} must not be negative, got {}", valued(b, v.value, dim));
        return Err(b.refuse(DiagnosticKind::BadValue, line, message));
    }
    Ok(v)
}

/// The co-ordinates `x`, `y` of a point: two different ones.
pub(super) fn point(
    b: &DeckBuilder,
    line: usize,
    x: i64,
    y: i64,
    what: &str,
) -> Result<(Spanned<i64>, Spanned<i64>), Refused> {
    whole(b, line, x, what)?;
    whole(b, line, y, what)?;
    if x == y {
        let message = format!("{what} names co-ordinate {x} for both the x and the y of its point");
        return Err(b.refuse(DiagnosticKind::BadValue, line, message));
    }
    Ok((at(x, line), at(y, line)))
}

/// `steps` steps of time `dt`: 1 to [`MAX_STEPS`] steps of a positive
/// time, the whole time a finite number.
pub(super) fn steps(b: &DeckBuilder, line: usize, steps: i64, dt: f64) -> Result<(), Refused> {
    if !(1..=MAX_STEPS).contains(&steps) {
        let message = format!("the motion has {steps} steps: give 1 to {MAX_STEPS}");
        return Err(b.refuse(DiagnosticKind::BadValue, line, message));
    }
    let dt = finite(b, line, dt, "the time of a step (dt)")?;
    if dt <= 0.0 || !(steps as f64 * dt).is_finite() {
        let dt = valued(b, dt, Some(Dim::TIME));
        let message = format!("the time of a step (dt) is {dt}: give a positive time, n * dt finite");
        return Err(b.refuse(DiagnosticKind::BadValue, line, message));
    }
    Ok(())
}

/// A limit of Newton iterations: 1 to [`MAX_ITER`].
pub(super) fn max_iter(b: &DeckBuilder, line: usize, m: i64) -> Result<(), Refused> {
    if (1..=MAX_ITER).contains(&m) {
        return Ok(());
    }
    Err(b.refuse(DiagnosticKind::BadValue, line, format!("max_iter is {m}: give 1 to {MAX_ITER}")))
}

/// Which tolerance of the integrator.
#[derive(Debug, Clone, Copy)]
pub(super) enum Tolerance {
    /// rtol: from 1e-15 to below 1.
    Relative,
    /// atol: from 1e-100 to 1e100.
    Absolute,
}

/// A tolerance of the integrator, in the range of its kind.
pub(super) fn tolerance(b: &DeckBuilder, line: usize, v: f64, kind: Tolerance) -> Result<Spanned<f64>, Refused> {
    let (what, fits) = match kind {
        Tolerance::Relative => ("rtol", (1e-15..1.0).contains(&v)),
        Tolerance::Absolute => ("atol", (SMALLEST..=LARGEST).contains(&v)),
    };
    if fits {
        return Ok(at(v, line));
    }
    let message = format!(
        "{what} is {}: rtol lies from 1e-15 to below 1, atol from 1e-100 to 1e100 (in the units of the inputs)",
        real(v)
    );
    Err(b.refuse(DiagnosticKind::NumberOutOfRange, line, message))
}

/// A buffer number: 1 to 4294967295.
pub(super) fn buffer_number(b: &DeckBuilder, line: usize, n: i64) -> Result<Spanned<i64>, Refused> {
    if (1..=i64::from(u32::MAX)).contains(&n) {
        return Ok(at(n, line));
    }
    Err(b.refuse(DiagnosticKind::BadValue, line, format!("buffer number {n} is not allowed: give 1 to 4294967295")))
}

/// Whether the deck's lexer would keep `c` inside a word.
fn in_word(c: char) -> bool {
    !matches!(c, ' ' | '\t' | '\r' | '\x0c' | '\x0b' | ';') && !c.is_control()
}

/// A name the deck reads as one word (a table file, the animation).
pub(super) fn file_name(b: &DeckBuilder, line: usize, name: &str, what: &str) -> Result<String, Refused> {
    if !name.is_empty() && name.chars().all(in_word) {
        return Ok(name.to_string());
    }
    let message = format!("the file name {name:?} of {what} is empty or holds a blank, a ';' or a control character");
    Err(b.refuse(DiagnosticKind::BadValue, line, message))
}

/// A picture's title as the deck reads it from its BEGINPIC line: blanks
/// at either end dropped.
pub(super) fn title(b: &DeckBuilder, line: usize, title: &str) -> Result<String, Refused> {
    let t = title.trim_matches(|c| matches!(c, ' ' | '\t' | '\r' | '\x0c' | '\x0b'));
    if t.chars().any(|c| c == ';' || c.is_control()) {
        let message = format!("the picture title {title:?} holds a ';' or a control character");
        return Err(b.refuse(DiagnosticKind::BadValue, line, message));
    }
    Ok(t.to_string())
}

/// Refuses a motion keyword (or INTTOL) that the model's mode does not
/// have: free motion of a model with dynamics, a motion by the forces or
/// the integrator's tolerances without a simulation.
pub(super) fn motion_mode(b: &DeckBuilder, line: usize, kw: Keyword, what: &str) -> Result<(), Refused> {
    let mode = b.deck.mode.value;
    let refused = match kw {
        Keyword::MovFree => mode.has_dynamics(),
        Keyword::MovDyn | Keyword::Inttol | Keyword::Integrator | Keyword::StopWhen => mode != crate::ast::Mode::DynSim,
        _ => false,
    };
    if !refused {
        return Ok(());
    }
    let message = format!("{what} ({kw}) cannot move a {} model", mode.name());
    Err(b.refuse(DiagnosticKind::WrongMode, line, message))
}
