//! One line of the OPTIMISE block: what the line alone can tell (numbers,
//! ranges, weights, the kind of an objective). Whether the rows,
//! co-ordinates, buffers and positions it names exist is checked by
//! [`crate::compile`].

use crate::args::Source;
use crate::ast::{BoundDef, FrameDef, FreeTimeDef, MassVaryDef, ObjectiveDef, TargetDef, TargetDefKind, VaryDef};
use crate::diagnostic::{real, Diagnostic, DiagnosticKind, Hint, Spanned};
use crate::keywords::{closest, Keyword};
use crate::lexer::{Line, Word};
use crate::optimise::{MassItem, Reduce, Sense};
use crate::parse::Parser;
use crate::statements::dynamics::bounded;

/// The largest OPTSTEPS: SciPy's SLSQP counts its iterations in a 32-bit
/// integer, which a larger limit wraps round to a negative one.
pub(crate) const MAX_OPTSTEPS: i64 = i32::MAX as i64;

impl Parser<'_> {
    /// Reads one line of the OPTIMISE block (its argument count is checked).
    pub(crate) fn optimise_statement(
        &mut self,
        kw: Spanned<Keyword>,
        line: &Line,
        args: &[Word],
    ) -> Result<(), Box<Diagnostic>> {
        let arg =
            |k: usize| args.get(k).ok_or_else(|| self.src.count_error(line, args, None, "missing argument".into()));
        let line_no = line.number;
        let src = &self.src;
        match kw.value {
            Keyword::Vary | Keyword::VaryX => {
                let what = if kw.value == Keyword::Vary { "the row number" } else { "the co-ordinate number" };
                let index = src.whole(arg(0)?, what)?;
                let (lo, hi) = range(src, kw.value, arg(1)?, arg(2)?)?;
                self.optimise.vary.push(VaryDef { line: line_no, keyword: kw, index, lo, hi });
            }
            Keyword::Target | Keyword::TargetAt | Keyword::TargetExt => {
                let buffer = src.buffer(arg(0)?)?;
                let (kind, weight) = match kw.value {
                    Keyword::Target => {
                        let file = arg(1)?;
                        (TargetDefKind::Values(Spanned::new(file.text.clone(), file.span)), args.get(2))
                    }
                    Keyword::TargetAt => {
                        let position = src.whole(arg(1)?, "the position k")?;
                        let value = bounded(src, arg(2)?, "the target value")?;
                        (TargetDefKind::At { position, value }, args.get(3))
                    }
                    _ => {
                        let reference = src.buffer(arg(1)?)?;
                        let value = bounded(src, arg(2)?, "the target value")?;
                        (TargetDefKind::Extremum { reference, value }, args.get(3))
                    }
                };
                let weight = weight.map(|w| positive_weight(src, kw.value, w)).transpose()?;
                self.optimise.targets.push(TargetDef { line: line_no, keyword: kw, buffer, kind, weight });
            }
            Keyword::Bound => {
                let buffer = src.buffer(arg(0)?)?;
                let (lo, hi) = range(src, kw.value, arg(1)?, arg(2)?)?;
                self.optimise.bounds.push(BoundDef { line: line_no, buffer, lo, hi });
            }
            Keyword::Minimise | Keyword::Maximise => {
                let reduce = reduce(src, kw.value, arg(0)?)?;
                let buffer = src.buffer(arg(1)?)?;
                let with = args.get(2).map(|w| src.buffer(w)).transpose()?;
                if let Some(b2) = &with {
                    if !matches!(reduce.value, Reduce::Rms | Reduce::MaxAbs) {
                        return Err(src
                            .error(
                                DiagnosticKind::BadValue,
                                b2.span,
                                format!(
                                    "{} {} takes one buffer: only RMS and MAXABS judge the magnitude of two",
                                    kw.value,
                                    reduce.value.name()
                                ),
                            )
                            .with_hint(format!(
                                "`{kw} RMS b b2` and `{kw} MAXABS b b2` judge sqrt(b^2 + b2^2) at every position (a \
                                 force's x and y, e.g. the shaking force of BUFSHAKE); {} of one buffer takes only b",
                                reduce.value.name(),
                                kw = kw.value
                            )));
                    }
                }
                if let Some(first) = &self.optimise.objective {
                    return Err(src
                        .error(
                            DiagnosticKind::DuplicateKeyword,
                            kw.span,
                            format!("a second objective: {} is given at line {}", first.keyword.value, first.line),
                        )
                        .with_hint(
                            "give at most one MINIMISE or MAXIMISE line; state further wishes as TARGET, TARGETAT, \
                             TARGETEXT or BOUND lines",
                        ));
                }
                let sense = if kw.value == Keyword::Minimise { Sense::Minimise } else { Sense::Maximise };
                self.optimise.objective =
                    Some(ObjectiveDef { line: line_no, keyword: kw, sense, reduce, buffer, with });
            }
            Keyword::OptSteps => {
                let n = src.whole(arg(0)?, "the iteration limit")?;
                if n.value < 1 {
                    return Err(src
                        .error(
                            DiagnosticKind::BadValue,
                            n.span,
                            format!("OPTSTEPS must be at least 1, got {}", n.value),
                        )
                        .with_hint("give the largest number of iterations of the optimiser (default 200)"));
                }
                if n.value > MAX_OPTSTEPS {
                    return Err(src
                        .error(
                            DiagnosticKind::NumberOutOfRange,
                            n.span,
                            format!("OPTSTEPS {} is more iterations than the optimiser can count", n.value),
                        )
                        .with_hint(
                            "the optimiser counts its iterations in 32 bits: give at most 2147483647 (default 200); \
                             a design that has not converged in a few hundred iterations rarely does later",
                        ));
                }
                self.once(kw)?;
                self.optimise.steps = Some(n);
            }
            Keyword::FreeTime => {
                let row = src.whole(arg(0)?, "the input's row number")?;
                let (ordered, within) = free_time_words(src, line, args)?;
                self.once(kw)?;
                self.optimise.free_time = Some(FreeTimeDef { line: line_no, keyword: kw, row, ordered, within });
            }
            Keyword::FullRot => {
                let row = src.whole(arg(0)?, "the input's row number")?;
                self.once(kw)?;
                self.optimise.full_rotation = Some((kw, row));
            }
            Keyword::VaryM => {
                let what = mass_item(src, arg(0)?)?;
                let number = if what.value.of_element() { "the element number" } else { "the co-ordinate number" };
                let index = src.whole(arg(1)?, number)?;
                let (lo, hi) = range(src, kw.value, arg(2)?, arg(3)?)?;
                self.optimise.mass_vary.push(MassVaryDef { line: line_no, keyword: kw, what, index, lo, hi });
            }
            Keyword::VaryFrame => {
                let index = src.whole(arg(0)?, "the pivot's x co-ordinate number")?;
                let (lo, hi) = range(src, kw.value, arg(1)?, arg(2)?)?;
                if lo.value > 0.0 || hi.value < 0.0 {
                    return Err(src
                        .error(
                            DiagnosticKind::BadValue,
                            lo.span.to(hi.span),
                            format!(
                                "VARYFRAME's range [{}, {}] does not hold 0, the frame as the deck gives it",
                                real(lo.value),
                                real(hi.value)
                            ),
                        )
                        .with_hint(
                            "the angle turns the deck's frame, so the design starts at 0: give a range from at most 0 \
                             to at least 0, e.g. `VARYFRAME 1 -3.141592653589793 3.141592653589793` (a whole turn: \
                             the angle wraps)",
                        ));
                }
                self.once(kw)?;
                self.optimise.frame = Some(FrameDef { line: line_no, keyword: kw, index, lo, hi });
            }
            Keyword::OptFTol => {
                let rtol = src.real(arg(0)?, "the relative tolerance rtol")?;
                let atol = src.real(arg(1)?, "the absolute tolerance atol")?;
                ftol_values(src, &rtol, &atol)?;
                self.once(kw)?;
                self.both_tolerances(kw, self.optimise.tol.map(|t| t.span.line))?;
                self.optimise.ftol = Some((kw, rtol.value, atol.value));
            }
            _ => {
                let tol = src.real(arg(0)?, "the tolerance")?;
                if tol.value >= 1.0 {
                    return Err(src
                        .error(
                            DiagnosticKind::BadValue,
                            tol.span,
                            format!(
                                "OPTTOL must be below 1, got {}: the optimiser would stop before its first step",
                                real(tol.value)
                            ),
                        )
                        .with_hint(
                            "give the relative change of the objective below which the optimiser stops, e.g. 1E-8",
                        ));
                }
                if tol.value <= 0.0 {
                    return Err(src
                        .error(
                            DiagnosticKind::BadValue,
                            tol.span,
                            format!("OPTTOL must be positive, got {}", real(tol.value)),
                        )
                        .with_hint(
                            "give the relative change of the objective below which the optimiser stops, e.g. 1E-8",
                        ));
                }
                self.once(kw)?;
                self.both_tolerances(kw, self.optimise.ftol.map(|(k, _, _)| k.span.line))?;
                self.optimise.tol = Some(tol);
            }
        }
        Ok(())
    }
}

impl Parser<'_> {
    /// OPTTOL and OPTFTOL say the same thing in two ways: one of them.
    fn both_tolerances(&self, kw: Spanned<Keyword>, other: Option<usize>) -> Result<(), Box<Diagnostic>> {
        let Some(first) = other else { return Ok(()) };
        let other = if kw.value == Keyword::OptTol { Keyword::OptFTol } else { Keyword::OptTol };
        Err(self
            .src
            .error(
                DiagnosticKind::DuplicateKeyword,
                kw.span,
                format!("{} and {other} (line {first}) are both given", kw.value),
            )
            .with_hint(
                "give one: OPTFTOL rtol atol stops when an iteration changes the objective f by less than \
                 atol + rtol |f|; OPTTOL tol is the classic relative tolerance (for SLSQP scaled by the start \
                 objective)",
            ))
    }
}

/// The numbers of `OPTFTOL rtol atol`: both zero or positive and finite,
/// rtol below 1, not both zero.
fn ftol_values(src: &Source<'_>, rtol: &Spanned<f64>, atol: &Spanned<f64>) -> Result<(), Box<Diagnostic>> {
    let hint = "OPTFTOL rtol atol stops the optimiser when an iteration changes the objective f by less than \
                atol + rtol |f|: give e.g. `OPTFTOL 1E-10 1E-14`";
    for (v, name) in [(rtol, "rtol"), (atol, "atol")] {
        if !(v.value >= 0.0 && v.value.is_finite()) {
            return Err(src
                .error(
                    DiagnosticKind::BadValue,
                    v.span,
                    format!("OPTFTOL's {name} must be zero or positive and finite, got {}", real(v.value)),
                )
                .with_hint(hint));
        }
    }
    if rtol.value >= 1.0 {
        return Err(src
            .error(
                DiagnosticKind::BadValue,
                rtol.span,
                format!(
                    "OPTFTOL's rtol must be below 1, got {}: the optimiser would stop before its first step",
                    real(rtol.value)
                ),
            )
            .with_hint(hint));
    }
    if rtol.value == 0.0 && atol.value == 0.0 {
        return Err(src
            .error(
                DiagnosticKind::BadValue,
                rtol.span.to(atol.span),
                "OPTFTOL's rtol and atol are both 0: the optimiser would never stop on the objective".to_string(),
            )
            .with_hint(hint));
    }
    Ok(())
}

/// `lo hi` of VARY, VARYX or BOUND: two numbers, lo below hi; for a design
/// variable also hi - lo finite (the optimiser scales its steps by it).
fn range(src: &Source<'_>, kw: Keyword, lo: &Word, hi: &Word) -> Result<(Spanned<f64>, Spanned<f64>), Box<Diagnostic>> {
    // A bound is compared with the buffer's values: within the numbers of
    // the dynamics, the difference stays finite.
    let read = |w: &Word, what: &str| if kw == Keyword::Bound { bounded(src, w, what) } else { src.real(w, what) };
    let lo = read(lo, "the lower end lo")?;
    let hi = read(hi, "the upper end hi")?;
    if lo.value < hi.value && (kw == Keyword::Bound || (hi.value - lo.value).is_finite()) {
        return Ok((lo, hi));
    }
    if lo.value < hi.value {
        return Err(src
            .error(
                DiagnosticKind::BadValue,
                lo.span.to(hi.span),
                format!(
                    "{kw}'s range [{}, {}] is wider than a number can hold: hi - lo overflows",
                    real(lo.value),
                    real(hi.value)
                ),
            )
            .with_hint(
                "the optimiser measures a variable's steps against its range: give the range the variable can \
                 sensibly take (its width below about 1.8e308)",
            ));
    }
    let hint = if kw == Keyword::Bound {
        "give `BOUND b lo hi` with lo below hi: the buffer must stay within [lo, hi] at every position"
    } else {
        "give the range with its lower end first and below the upper end: the variable may take any value in [lo, hi]"
    };
    Err(src
        .error(
            DiagnosticKind::BadValue,
            lo.span.to(hi.span),
            format!("{kw}'s range is empty: lo {} is not below hi {}", real(lo.value), real(hi.value)),
        )
        .with_hint(hint))
}

/// What follows the row of `FREETIME r [ORDERED] [WITHIN w]`: whether the
/// points are ordered, and the sweep w that bounds them (only with ORDERED:
/// the sweep of unordered points has no first and last).
fn free_time_words(
    src: &Source<'_>,
    line: &Line,
    args: &[Word],
) -> Result<(bool, Option<Spanned<f64>>), Box<Diagnostic>> {
    const FORMS: &str = "`FREETIME r` makes the input's value at every position a design variable; `FREETIME r \
                         ORDERED` keeps each value at or after the one before; `FREETIME r ORDERED WITHIN w` also \
                         keeps the last at most w after the first";
    let is = |w: &Word, word: &str| w.text.eq_ignore_ascii_case(word);
    let Some(first) = args.get(1) else { return Ok((false, None)) };
    if is(first, "WITHIN") {
        return Err(src
            .error(
                DiagnosticKind::BadValue,
                first.span,
                "FREETIME's WITHIN bounds ordered points, but ORDERED is not given",
            )
            .with_hint(
                "WITHIN w keeps the last point at most w after the first, which needs the points in order: write \
                 `FREETIME r ORDERED WITHIN w`",
            ));
    }
    // Another word where FREETIME takes `word` after `place`.
    let instead = |w: &Word, word: &str, place: &str| {
        src.error(
            DiagnosticKind::BadValue,
            w.span,
            format!("FREETIME takes the word {word} after {place}, not `{}`", w.text),
        )
        .with_hint(FORMS)
    };
    if !is(first, "ORDERED") {
        return Err(instead(first, "ORDERED", "the row"));
    }
    let Some(second) = args.get(2) else { return Ok((true, None)) };
    if !is(second, "WITHIN") {
        return Err(instead(second, "WITHIN", "ORDERED"));
    }
    let Some(word) = args.get(3) else {
        return Err(src
            .count_error(line, args, None, "FREETIME's WITHIN is not followed by the sweep w".into())
            .with_hint(
                "give the largest input from the first point to the last, in the input's unit (the deck's angle \
                 unit for a crank), e.g. `FREETIME 6 ORDERED WITHIN 6.2831853` for points passed in one turn",
            ));
    };
    let w = bounded(src, word, "the sweep w")?;
    if w.value > 0.0 {
        return Ok((true, Some(w)));
    }
    Err(src
        .error(
            DiagnosticKind::BadValue,
            w.span,
            format!("FREETIME's sweep w after WITHIN must be positive, got {}", real(w.value)),
        )
        .with_hint(
            "w is the largest input from the first point to the last (ordered points advance, so the sweep is at \
             least 0): give a positive number in the input's unit, e.g. 6.2831853 rad or 360 deg for one turn",
        ))
}

/// The weight of a target: a positive number.
fn positive_weight(src: &Source<'_>, kw: Keyword, w: &Word) -> Result<Spanned<f64>, Box<Diagnostic>> {
    let v = bounded(src, w, "the weight")?;
    if v.value > 0.0 {
        return Ok(v);
    }
    Err(src
        .error(DiagnosticKind::BadValue, w.span, format!("the weight of {kw} must be positive, got {}", real(v.value)))
        .with_hint(
            "the weight w multiplies the target's squared error in the objective: give a positive number, or leave \
             it out for 1",
        ))
}

/// The kind of MINIMISE or MAXIMISE: MAX, MAXABS, RMS or END.
/// The word `what` of a VARYM line.
fn mass_item(src: &Source<'_>, w: &Word) -> Result<Spanned<MassItem>, Box<Diagnostic>> {
    if let Some(m) = MassItem::from_name(&w.text) {
        return Ok(Spanned::new(m, w.span));
    }
    let names = MassItem::ALL.map(MassItem::name);
    let guess = closest(&w.text, names).map_or(String::new(), |n| format!("; did you mean `{n}`?"));
    Err(src.error(DiagnosticKind::BadValue, w.span, format!("unknown item `{}` of VARYM", w.text)).with_hint(format!(
        "VARYM names the number of the DYNAMICS block it varies: MASS, U, V or J of element k's MASS line (`VARYM U \
         k lo hi`), PMASS of the point mass at co-ordinate i (`VARYM PMASS i lo hi`) or INERTIA on co-ordinate i{guess}"
    )))
}

fn reduce(src: &Source<'_>, kw: Keyword, w: &Word) -> Result<Spanned<Reduce>, Box<Diagnostic>> {
    if let Some(r) = Reduce::from_name(&w.text) {
        return Ok(Spanned::new(r, w.span));
    }
    let names = Reduce::ALL.map(Reduce::name);
    let guess = closest(&w.text, names).map_or(String::new(), |n| format!("; did you mean `{n}`?"));
    Err(src.error(DiagnosticKind::BadValue, w.span, format!("unknown kind `{}` of {kw}", w.text)).with_hint(format!(
        "the kind says what is made {}: MAX (the largest value of the buffer over the positions), MAXABS \
             (the largest absolute value), RMS (the root mean square) or END (the value at the last position){guess}",
        if kw == Keyword::Minimise { "small" } else { "large" }
    )))
}
