//! OPTIMISE to an [`Optimise`]: design variables, targets, bounds and the
//! objective, referred to the model, the motion's positions and the deck's
//! buffers; TARGET files.

use std::collections::BTreeMap;
use std::path::Path;

use mechfem_core::dynamics::Dynamics;
use mechfem_core::{FormRef, Motion, Quantity};

use super::design::design_variables;
use super::model::Model;
use super::refs::Sizes;
use super::storage::{by_number, defined_buffer};
use super::table::read_column;
use crate::ast::{missing_movement, missing_optimise, Deck, Mode, TargetDef, TargetDefKind};
use crate::compiled::Buffer;
use crate::diagnostic::{count, Diagnostic, DiagnosticKind, Hint, Span};
use crate::keywords::Keyword;
use crate::optimise::{Bound, Objective, Optimise, Target, TargetKind};

/// The optimisation problem of a `KIN OPT` deck, or of a `DYN ANA` deck
/// with an OPTIMISE block (`None` otherwise).
#[allow(clippy::too_many_arguments)]
pub(crate) fn optimise(
    deck: &Deck,
    model: &Model,
    sizes: &Sizes,
    motion: Option<&Motion>,
    dynamics: Option<&Dynamics>,
    buffers: &[Buffer],
    deck_dir: &Path,
) -> Result<Option<Optimise>, Box<Diagnostic>> {
    let dynamic = deck.mode.value == Mode::DynAna && deck.optimise.is_some();
    if deck.mode.value != Mode::KinOpt && !dynamic {
        return Ok(None);
    }
    // The parser reports both already.
    let Some(block) = &deck.optimise else {
        return Err(missing_optimise(&deck.path, &deck.source, deck.mode.span));
    };
    let header = Span::new(block.line, 0, deck.line_text(block.line).trim_end().chars().count());
    let Some(motion) = motion else {
        if dynamic {
            return Err(deck
                .error(
                    DiagnosticKind::MissingBlock,
                    header,
                    "this DYN ANA deck optimises but has no MOVEMENT block: the motion gives the positions at which \
                     the design is judged",
                )
                .with_hint(
                    "add a MOVEMENT block with `TSTEPE n dt` and, for every DOF j, a driven motion: `MOV_RELE j \
                     delta`, `MOV_ABSE j end` or `MOV_FUNC j file`",
                ));
        }
        return Err(missing_movement(&deck.path, &deck.source, deck.mode.value, deck.mode.span));
    };
    let mass_vary = super::mass_vary::mass_variables(deck, dynamics, &block.mass_vary)?;
    if block.vary.is_empty() && mass_vary.is_empty() && dynamic {
        return Err(deck
            .error(DiagnosticKind::NothingToOptimise, header, "the OPTIMISE block has no design variable")
            .with_hint(
                "add `VARYM what n lo hi` to vary a number of the DYNAMICS block (a MASS line's MASS, U, V or J, \
                 a PMASS, an INERTIA), `VARY r lo hi` to vary the PARA value of prescribed row r or `VARYX i lo hi` \
                 to vary fixed co-ordinate i",
            ));
    }
    if block.vary.is_empty() && mass_vary.is_empty() {
        return Err(deck
            .error(DiagnosticKind::NothingToOptimise, header, "the OPTIMISE block has no design variable")
            .with_hint(
                "add `VARY r lo hi` to vary the PARA value of prescribed row r (a length, an angle, a local u or v, \
                 a gear ratio) or `VARYX i lo hi` to vary fixed co-ordinate i (a frame pivot)",
            ));
    }
    if block.targets.is_empty() && block.objective.is_none() {
        return Err(deck
            .error(
                DiagnosticKind::NothingToOptimise,
                header,
                "the OPTIMISE block has nothing to optimise: no TARGET, TARGETAT, TARGETEXT, MINIMISE or MAXIMISE",
            )
            .with_hint(
                "say what the design should achieve: values a buffer should take (`TARGET b file`, `TARGETAT b k \
                 value`, `TARGETEXT b bref value`) or a quantity to make small or large (`MINIMISE kind b`, \
                 `MAXIMISE kind b`); BOUND lines only constrain",
            ));
    }
    let vary = design_variables(deck, model, sizes, Some(motion), &block.vary)?;
    let defined = by_number(buffers);
    let judged = block.targets.iter().map(|t| (&t.buffer, t.keyword.value));
    let judged = judged.chain(block.bounds.iter().map(|b| (&b.buffer, Keyword::Bound)));
    let judged = judged.chain(block.objective.iter().map(|o| (&o.buffer, o.keyword.value)));
    let judged = judged.chain(block.objective.iter().filter_map(|o| o.with.as_ref().map(|b| (b, o.keyword.value))));
    for (b, kw) in judged {
        let buffer = defined_buffer(deck, &defined, b)?;
        if buffer.quantity == Quantity::Det {
            return Err(deck
                .error(
                    DiagnosticKind::NoSensitivity,
                    b.span,
                    format!(
                        "{kw} names buffer {}, det(D^c) (BUFDET at line {}), which has no design sensitivity",
                        buffer.number, buffer.line
                    ),
                )
                .with_hint(
                    "the optimiser follows the derivatives of what it judges with respect to the design variables, \
                     and mechfem does not compute those of det(D^c): keep BUFDET in STORAGE to watch it, and judge \
                     a transfer function or a position instead",
                ));
        }
    }
    if dynamic {
        kinematic_only(deck, block)?;
    }
    let (free_time, full_rotation, frame) = super::synthesis::statements(deck, model, sizes, motion, block, &vary)?;
    let positions = motion.steps + 1;
    let targets = block
        .targets
        .iter()
        .map(|t| {
            Ok(Target {
                buffer: defined_buffer(deck, &defined, &t.buffer)?.number,
                kind: target_kind(deck, t, &defined, positions, deck_dir)?,
                weight: t.weight.map_or(1.0, |w| w.value),
                line: t.line,
            })
        })
        .collect::<Result<Vec<_>, Box<Diagnostic>>>()?;
    let bounds = block
        .bounds
        .iter()
        .map(|b| {
            let buffer = defined_buffer(deck, &defined, &b.buffer)?.number;
            Ok(Bound { buffer, lo: b.lo.value, hi: b.hi.value, line: b.line })
        })
        .collect::<Result<Vec<_>, Box<Diagnostic>>>()?;
    let objective = match &block.objective {
        Some(o) => Some(Objective {
            sense: o.sense,
            reduce: o.reduce.value,
            buffer: defined_buffer(deck, &defined, &o.buffer)?.number,
            with: o.with.as_ref().map(|b| defined_buffer(deck, &defined, b).map(|b| b.number)).transpose()?,
            line: o.line,
        }),
        None => None,
    };
    Ok(Some(Optimise {
        vary,
        targets,
        bounds,
        objective,
        steps: block.steps.map_or(Optimise::DEFAULT_STEPS, |n| usize::try_from(n.value).unwrap_or(usize::MAX)),
        tol: block.tol.map(|t| t.value),
        ftol: block.ftol.map(|(_, rtol, atol)| (rtol, atol)),
        free_time,
        full_rotation,
        frame,
        mass_vary,
        line: block.line,
    }))
}

/// Refuses the statements of kinematic synthesis in a `DYN ANA` deck:
/// its motion is timed, every design is judged at the same instants.
fn kinematic_only(deck: &Deck, block: &crate::ast::Optimise) -> Result<(), Box<Diagnostic>> {
    let ext = block.targets.iter().find(|t| t.keyword.value == Keyword::TargetExt).map(|t| t.keyword);
    let found = [
        ext,
        block.free_time.as_ref().map(|f| f.keyword),
        block.full_rotation.as_ref().map(|f| f.0),
        block.frame.as_ref().map(|f| f.keyword),
    ];
    let Some(kw) = found.into_iter().flatten().next() else { return Ok(()) };
    Err(deck
        .error(
            DiagnosticKind::WrongMode,
            kw.span,
            format!("{} belongs to the kinematic synthesis of a KIN OPT deck, not to a DYN ANA deck", kw.value),
        )
        .with_hint(
            "a DYN ANA deck judges every design at the instants of its timed motion, by TARGET, TARGETAT, BOUND, \
             MINIMISE and MAXIMISE of its buffers: synthesise the kinematics in a KIN OPT deck first, then balance \
             the result here",
        ))
}

/// What a TARGET, TARGETAT or TARGETEXT line compares its buffer with.
fn target_kind(
    deck: &Deck,
    t: &TargetDef,
    defined: &BTreeMap<u32, Buffer>,
    positions: usize,
    deck_dir: &Path,
) -> Result<TargetKind, Box<Diagnostic>> {
    let kw = t.keyword.value;
    let steps = positions - 1;
    Ok(match &t.kind {
        TargetDefKind::Values(file) => {
            let values = read_column(deck, file, deck_dir, kw)?;
            let rows = values.len();
            if rows != positions {
                return Err(deck
                    .error(
                        DiagnosticKind::TargetFile,
                        file.span,
                        format!(
                            "the {kw} file `{}` has {}, expected {positions}",
                            file.value,
                            count(rows, "row", "rows")
                        ),
                    )
                    .with_hint(format!(
                        "TSTEPE {steps} makes {positions} positions: give one row for each, `*` or a blank row where \
                         the buffer is not compared (lines holding only a comment are not rows)"
                    )));
            }
            if values.iter().all(Option::is_none) {
                return Err(deck
                    .error(
                        DiagnosticKind::TargetFile,
                        file.span,
                        format!("the {kw} file `{}` has no value: every row is blank or `*`", file.value),
                    )
                    .with_hint("give the value the buffer should take in the rows of the positions that matter"));
            }
            TargetKind::Values { file: file.value.clone(), values }
        }
        TargetDefKind::At { position, value } => {
            let Some(k) = usize::try_from(position.value).ok().filter(|k| (1..=positions).contains(k)) else {
                return Err(deck
                    .error(
                        DiagnosticKind::BadValue,
                        position.span,
                        format!("{kw} names position {}, but the motion has {positions} positions", position.value),
                    )
                    .with_hint(format!(
                        "positions are numbered 1..{positions}: TSTEPE {steps} makes {positions}, position 1 the start"
                    )));
            };
            TargetKind::At { position: k - 1, value: value.value }
        }
        TargetDefKind::Extremum { reference, value } => {
            let r = defined_buffer(deck, defined, reference)?;
            if !matches!(r.quantity, Quantity::X0(_) | Quantity::E0(FormRef::Dependent(_))) {
                return Err(deck
                    .error(
                        DiagnosticKind::ExtremumReference,
                        reference.span,
                        format!(
                            "{kw} looks for the extrema of buffer {}, which is not a position quantity (defined at \
                             line {})",
                            r.number, r.line
                        ),
                    )
                    .with_hint(
                        "an extremum is located where the reference's first-order transfer function changes sign, \
                         and refined with its second-order one: name a buffer of BUFX0 (a co-ordinate) or of BUFE0 \
                         of a dependent form parameter (destination -k); a prescribed row is constant or, as an \
                         input, moves steadily, so it has no extremum inside the motion",
                    ));
            }
            TargetKind::Extremum { reference: r.number, value: value.value }
        }
    })
}
