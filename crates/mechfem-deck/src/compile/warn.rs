//! Numbers that look as if they were written in another unit than the
//! deck's: an angle of 720 where angles are radians (two turns are 12.6
//! rad), or 6.2832 where angles are degrees. Every angle a designer
//! writes is looked at: prescribed values, angular co-ordinates, motion
//! steps and ends, VARY ranges of angles, the values of targets and
//! bounds on angle buffers and STOPWHEN's value on one. They are
//! warnings: the run goes on with the number as written.

use std::f64::consts::PI;

use mechfem_core::units::Angle;
use mechfem_core::{Dim, Mechanism, ModelDims, Units};

use crate::ast::{Deck, MotionKind, TargetDefKind};
use crate::compiled::Buffer;
use crate::diagnostic::{Diagnostic, DiagnosticKind, Hint, Spanned};
use crate::keywords::Keyword;

/// Whether `v`, an angle in radians, looks like degrees: a whole number of
/// at least 90 that is a multiple of 15 (90, 180, 360, 720).
fn degrees_in_radians(v: f64) -> bool {
    v.abs() >= 90.0 && v.fract() == 0.0 && v % 15.0 == 0.0
}

/// Whether `v`, an angle in degrees, looks like radians: pi/2, pi or 2 pi
/// (or their multiples up to 4) written to at least three decimals.
fn radians_in_degrees(v: f64) -> bool {
    v != 0.0 && (1..=8).any(|k| (v.abs() - f64::from(k) * PI / 2.0).abs() < 5e-4)
}

/// The warnings of `deck` (as written), whose model has the kinds `dims`
/// and whose buffers are `buffers`.
pub(crate) fn suspicious(
    deck: &Deck,
    units: &Units,
    dims: &ModelDims,
    mech: &Mechanism,
    buffers: &[Buffer],
) -> Vec<Diagnostic> {
    let degrees = units.angle == Some(Angle::Deg);
    let mut out = Vec::new();
    let mut check = |dim: Dim, v: &Spanned<f64>, what: &str| {
        if dim != Dim::ANGLE {
            return;
        }
        let (looks, unit, other) = if degrees {
            (radians_in_degrees(v.value), "degrees", "radians")
        } else {
            (degrees_in_radians(v.value), "radians", "degrees")
        };
        if !looks {
            return;
        }
        let hint = if degrees {
            format!(
                "the deck's UNITS says ANGLE deg: write the angle in degrees ({:.6} rad is {:.4} deg)",
                v.value,
                v.value.to_degrees()
            )
        } else {
            format!(
                "angles of this deck are radians ({} deg is {:.6} rad): write it in radians, or add `UNITS ANGLE deg` \
                 to give every angle of the deck in degrees",
                v.value,
                v.value.to_radians()
            )
        };
        let message = format!("{what} {} is an angle in {unit}, but looks like {other}", v.value);
        out.push(*deck.error(DiagnosticKind::SuspiciousUnit, v.span, message).with_hint(hint));
    };
    let row = |r: i64| usize::try_from(r - 1).ok().and_then(|k| dims.prescribed.get(k)).copied();
    let coord = |i: i64| usize::try_from(i - 1).ok().and_then(|k| dims.coords.get(k)).copied();
    let buffer = |b: i64| buffers.iter().find(|x| i64::from(x.number) == b).map(|x| dims.quantity(mech, x.quantity));
    for c in &deck.geometry.coords {
        if let Some(d) = coord(c.index.value) {
            check(d, &c.value, "the co-ordinate");
        }
    }
    for p in &deck.geometry.paras {
        if let Some(d) = row(p.row.value) {
            check(d, &p.value, "the prescribed value");
        }
    }
    if let Some(o) = &deck.optimise {
        for v in &o.vary {
            let d = if v.keyword.value == Keyword::VaryX { coord(v.index.value) } else { row(v.index.value) };
            if let Some(d) = d {
                check(d, &v.lo, "the lower end of the range");
                check(d, &v.hi, "the upper end of the range");
            }
        }
        for t in &o.targets {
            let Some(d) = buffer(t.buffer.value) else { continue };
            match &t.kind {
                TargetDefKind::At { value, .. } | TargetDefKind::Extremum { value, .. } => {
                    check(d, value, "the target");
                }
                TargetDefKind::Values(_) => {}
            }
        }
        for b in &o.bounds {
            if let Some(d) = buffer(b.buffer.value) {
                check(d, &b.lo, "the lower bound");
                check(d, &b.hi, "the upper bound");
            }
        }
    }
    if let Some(mv) = &deck.movement {
        for m in &mv.motions {
            let Some(j) = usize::try_from(m.dof.value - 1).ok().filter(|&j| j < mech.n_dof()) else { continue };
            let d = dims.input(mech, j);
            match &m.kind {
                MotionKind::Relative(v) => check(d, v, "the motion's step"),
                MotionKind::Absolute(v) => check(d, v, "the motion's end"),
                _ => {}
            }
        }
        if let Some(stop) = &mv.stop_when {
            if let Some(d) = buffer(stop.buffer.value) {
                check(d, &stop.value, "STOPWHEN's value");
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    // The approximations of pi are the point: they are what a deck writes.
    #[allow(clippy::approx_constant)]
    #[test]
    fn an_angle_of_whole_turns_in_degrees_is_suspicious_in_radians() {
        assert!(degrees_in_radians(720.0) && degrees_in_radians(-360.0) && degrees_in_radians(90.0));
        assert!(!degrees_in_radians(6.28) && !degrees_in_radians(100.0) && !degrees_in_radians(12.0));
        assert!(radians_in_degrees(6.2832) && radians_in_degrees(-3.14159) && radians_in_degrees(1.5708));
        assert!(!radians_in_degrees(360.0) && !radians_in_degrees(6.0) && !radians_in_degrees(3.0));
    }
}
