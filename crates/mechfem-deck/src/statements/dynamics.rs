//! One line of the DYNAMICS block, and the numbers of the MOVEMENT block that
//! only a simulation reads (MOV_DYN's initial velocity, INTTOL): what the
//! line alone can tell. Whether the elements, co-ordinates and form
//! parameters it names exist, and whether a point or an element already has
//! the same kind of mass or load, is checked by [`crate::compile`].
//!
//! Every number of the dynamics is 0 or has a magnitude from
//! [`SMALLEST`] to [`LARGEST`]: the products inverse dynamics and a
//! simulation form of a few of them (a mass times gravity, a stiffness
//! times a stretch, a mass times a speed squared) then stay far inside the
//! range of a double, and a subnormal number, which no model means, is
//! refused instead of dividing into an infinity.

use crate::args::Source;
use crate::ast::{ForceDef, GravityDef, InertiaDef, LoadDef, LoadDefKind, MassDef, PointMassDef};
use crate::diagnostic::{real, Diagnostic, DiagnosticKind, Hint, Spanned};
use crate::keywords::Keyword;
use crate::lexer::{Line, Word};
use crate::parse::Parser;

/// The largest magnitude of a number of the dynamics (and of a value an
/// optimisation compares a buffer with).
pub(crate) const LARGEST: f64 = 1e100;
/// The smallest magnitude, other than 0, of a number of the dynamics.
pub(crate) const SMALLEST: f64 = 1e-100;

impl Parser<'_> {
    /// Reads one line of the DYNAMICS block (its argument count is checked).
    pub(crate) fn dynamics_statement(
        &mut self,
        kw: Spanned<Keyword>,
        line: &Line,
        args: &[Word],
    ) -> Result<(), Box<Diagnostic>> {
        let arg =
            |k: usize| args.get(k).ok_or_else(|| self.src.count_error(line, args, None, "missing argument".into()));
        let line_no = line.number;
        let src = &self.src;
        const COORD: &str = "the co-ordinate number";
        const INERTIA: &str = "the moment of inertia";
        match kw.value {
            Keyword::Mass => {
                let element = src.whole(arg(0)?, "the element number")?;
                let mass = not_negative(src, arg(1)?, "the mass", "give the body's mass, 0 or more")?;
                let u = bounded(src, arg(2)?, "the centre of mass u")?;
                let v = bounded(src, arg(3)?, "the centre of mass v")?;
                let inertia = args.get(4).map(|w| not_negative(src, w, INERTIA, HINT_BODY_INERTIA)).transpose()?;
                self.dynamics.masses.push(MassDef { line: line_no, element, mass, u, v, inertia });
            }
            Keyword::Pmass => {
                let (x, y) = point(src, kw.value, arg(0)?, arg(1)?)?;
                let mass = not_negative(src, arg(2)?, "the mass", "give the point's mass, 0 or more")?;
                self.dynamics.point_masses.push(PointMassDef { line: line_no, x, y, mass });
            }
            Keyword::Inertia => {
                let coord = src.whole(arg(0)?, COORD)?;
                let inertia = not_negative(src, arg(1)?, INERTIA, HINT_WHEEL_INERTIA)?;
                self.dynamics.inertias.push(InertiaDef { line: line_no, coord, inertia });
            }
            Keyword::Gravity => {
                let gx = bounded(src, arg(0)?, "the acceleration of gravity")?;
                let gy = bounded(src, arg(1)?, "the acceleration of gravity")?;
                self.once(kw)?;
                self.dynamics.gravity = Some(GravityDef { line: line_no, gx, gy });
            }
            Keyword::Force => {
                let (x, y) = point(src, kw.value, arg(0)?, arg(1)?)?;
                let fx = bounded(src, arg(2)?, "the force")?;
                let fy = bounded(src, arg(3)?, "the force")?;
                self.dynamics.forces.push(ForceDef { line: line_no, x, y, fx, fy });
            }
            _ => {
                let form = src.whole(arg(0)?, "the form parameter's destination")?;
                let kind = match kw.value {
                    Keyword::Load => LoadDefKind::Constant(bounded(src, arg(1)?, "the load")?),
                    Keyword::LoadFunc => {
                        let file = arg(1)?;
                        LoadDefKind::Function(Spanned::new(file.text.clone(), file.span))
                    }
                    // A negative stiffness or damping is refused: it is far more
                    // often a slip of the sign than a model, and it makes the
                    // equilibrium unstable (a negative damper feeds energy in).
                    Keyword::Spring => LoadDefKind::Spring {
                        k: not_negative(src, arg(1)?, "the spring's stiffness", HINT_STIFFNESS)?,
                        e0: bounded(src, arg(2)?, "the free value")?,
                        c: args.get(3).map(|w| not_negative(src, w, "the damping", HINT_DAMPING)).transpose()?,
                    },
                    _ => {
                        let t0 = bounded(src, arg(1)?, "the stall torque")?;
                        let w0 = bounded(src, arg(2)?, "the no-load speed")?;
                        if w0.value == 0.0 {
                            let message = "the no-load speed w0 of a motor must not be 0";
                            return Err(src.error(DiagnosticKind::BadValue, w0.span, message).with_hint(HINT_MOTOR));
                        }
                        LoadDefKind::Motor { t0, w0 }
                    }
                };
                self.dynamics.loads.push(LoadDef { line: line_no, keyword: kw, form, kind });
            }
        }
        Ok(())
    }
}

const HINT_BODY_INERTIA: &str = "give the moment of inertia about the centre of mass, 0 or more (default 0)";
const HINT_WHEEL_INERTIA: &str = "give the moment of inertia about the angle's axis, 0 or more";
const HINT_STIFFNESS: &str =
    "give k, 0 or more: the spring's force -k (eps_r - e0) pulls eps_r back towards its free value e0";
const HINT_DAMPING: &str = "give c, 0 or more: the damper's force -c d(eps_r)/dt works against the motion";
const HINT_MOTOR: &str = "the motor's force T0 (1 - d(eps_r)/dt / w0) falls to zero at the speed w0: give that speed \
                          (negative for a motor that runs backwards)";

/// The co-ordinate numbers `i j` of a point (PMASS, FORCE): two different
/// co-ordinates, its x and its y.
fn point(src: &Source<'_>, kw: Keyword, i: &Word, j: &Word) -> Result<(Spanned<i64>, Spanned<i64>), Box<Diagnostic>> {
    let x = src.whole(i, "the co-ordinate number")?;
    let y = src.whole(j, "the co-ordinate number")?;
    if x.value != y.value {
        return Ok((x, y));
    }
    Err(src
        .error(
            DiagnosticKind::BadValue,
            x.span.to(y.span),
            format!("{kw} names co-ordinate {} for both the x and the y of its point", x.value),
        )
        .with_hint(format!(
            "a point has two co-ordinates: give `{kw} i j ...` with i its x co-ordinate and j its y co-ordinate, as \
             the element's points are numbered"
        )))
}

/// The word read as a number of the dynamics: 0, or a magnitude from
/// [`SMALLEST`] to [`LARGEST`].
pub(crate) fn bounded(src: &Source<'_>, w: &Word, what: &str) -> Result<Spanned<f64>, Box<Diagnostic>> {
    let v = src.real(w, what)?;
    match out_of_bounds(what, v.value) {
        None => Ok(v),
        Some((message, hint)) => Err(src.error(DiagnosticKind::NumberOutOfRange, w.span, message).with_hint(hint)),
    }
}

/// The message and hint for `value`, read as `what`, when it is neither 0
/// nor of a magnitude from [`SMALLEST`] to [`LARGEST`]; `None` when it is.
pub(crate) fn out_of_bounds(what: &str, value: f64) -> Option<(String, String)> {
    let size = value.abs();
    if size == 0.0 || (SMALLEST..=LARGEST).contains(&size) {
        return None;
    }
    Some(if size > LARGEST {
        (
            format!(
                "{what} {} is too large: mechfem multiplies it by masses, speeds, lengths or weights, and a \
                 magnitude above 1e100 could overflow them",
                real(value)
            ),
            format!(
                "give {what} in consistent units, at most 1e100 in magnitude: in SI units (m, kg, s, N) a \
                 mechanism's numbers lie far below that"
            ),
        )
    } else {
        (
            format!("{what} {} is too small to be meant: its magnitude is below 1e-100", real(value)),
            format!("give {what} as 0, or at least 1e-100 in magnitude, in consistent units"),
        )
    })
}

/// The word read as a number of the dynamics ([`bounded`]) that must not
/// be negative (a mass, an inertia, a stiffness).
fn not_negative(src: &Source<'_>, w: &Word, what: &str, hint: &str) -> Result<Spanned<f64>, Box<Diagnostic>> {
    let v = src.real(w, what)?;
    if v.value < 0.0 {
        return Err(src
            .error(DiagnosticKind::BadValue, w.span, format!("{what} must not be negative, got {}", real(v.value)))
            .with_hint(hint));
    }
    bounded(src, w, what)
}

/// Which tolerance of INTTOL.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Tolerance {
    /// rtol: a share of the value, below 1 and not below the precision of a
    /// double (about 2.2e-16), which no step can meet.
    Relative,
    /// atol: in the DOFs' units, within the numbers of the dynamics.
    Absolute,
}

/// The word read as a tolerance of the integrator: a positive number in
/// the range of its kind.
pub(crate) fn tolerance(src: &Source<'_>, w: &Word, kind: Tolerance) -> Result<Spanned<f64>, Box<Diagnostic>> {
    let what = match kind {
        Tolerance::Relative => "the relative tolerance rtol",
        Tolerance::Absolute => "the absolute tolerance atol",
    };
    let v = src.real(w, what)?;
    let usage = "give `INTTOL rtol atol`, both positive: each step's estimated error in a DOF and its velocity stays \
                 below atol + rtol * |value|, e.g. `INTTOL 1e-8 1e-10`";
    if v.value <= 0.0 {
        return Err(src
            .error(
                DiagnosticKind::BadValue,
                w.span,
                format!("{what} of INTTOL must be positive, got {}", real(v.value)),
            )
            .with_hint(usage));
    }
    let fits = match kind {
        Tolerance::Relative => (1e-15..1.0).contains(&v.value),
        Tolerance::Absolute => (SMALLEST..=LARGEST).contains(&v.value),
    };
    if fits {
        return Ok(v);
    }
    let message = match kind {
        Tolerance::Relative if v.value >= 1.0 => {
            format!("{what} of INTTOL is {}: a relative error of 1 or more lets a step go anywhere", real(v.value))
        }
        Tolerance::Relative => format!(
            "{what} of INTTOL is {}, finer than a double can hold (about 2.2e-16): no step can meet it",
            real(v.value)
        ),
        Tolerance::Absolute => {
            format!("{what} of INTTOL is {}: it must lie from 1e-100 to 1e100", real(v.value))
        }
    };
    Err(src.error(DiagnosticKind::NumberOutOfRange, w.span, message).with_hint(format!(
        "{usage}; rtol lies from 1e-15 to below 1, atol from 1e-100 to 1e100 (in the units of the DOFs)"
    )))
}
