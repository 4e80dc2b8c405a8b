//! The synthesis statements of the OPTIMISE block: free timing
//! (`FREETIME r [ORDERED] [WITHIN w]`), a full turn of an input (`FULLROT r`) and the
//! frame angle (`VARYFRAME i lo hi`), referred to the model and the motion.

use mechfem_core::{DesignVar, InputMotion, Motion};

use super::model::Model;
use super::refs::{coordinate, Sizes};
use crate::ast::{Deck, Optimise as Block};
use crate::diagnostic::{count, Diagnostic, DiagnosticKind, Hint, Spanned};
use crate::keywords::Keyword;
use crate::optimise::{FrameAngle, FreeTime, FullRotation, Vary};

/// FREETIME, FULLROT and VARYFRAME, each if given.
pub(super) type Statements = (Option<FreeTime>, Option<FullRotation>, Option<FrameAngle>);

/// FREETIME, FULLROT and VARYFRAME of the block, each if given.
pub(super) fn statements(
    deck: &Deck,
    model: &Model,
    sizes: &Sizes,
    motion: &Motion,
    block: &Block,
    vary: &[Vary],
) -> Result<Statements, Box<Diagnostic>> {
    let free_time = match &block.free_time {
        Some(d) => {
            let row = input_row(deck, model, motion, d.keyword.value, &d.row)?;
            if let Some(v) = vary.iter().find(|v| v.var == DesignVar::Row(row)) {
                return Err(deck
                    .error(
                        DiagnosticKind::DesignVariable,
                        d.row.span,
                        format!("row {} is varied by VARY at line {} and by FREETIME", row + 1, v.line),
                    )
                    .with_hint(
                        "FREETIME makes the input's value at every position a design variable, its start among \
                         them: drop the VARY line of the input",
                    ));
            }
            if let Some(t) = block.targets.iter().find(|t| t.keyword.value == Keyword::TargetExt) {
                return Err(deck
                    .error(
                        DiagnosticKind::DesignVariable,
                        t.keyword.span,
                        "TARGETEXT looks for extrema along the motion, but with FREETIME the positions are separate \
                         target points with free inputs, not a motion",
                    )
                    .with_hint("compare values at the positions (TARGET, TARGETAT), or drop FREETIME"));
            }
            Some(FreeTime { row, ordered: d.ordered, within: d.within.map(|w| w.value), line: d.line })
        }
        None => None,
    };
    let full_rotation = match &block.full_rotation {
        Some((kw, r)) => {
            let row = input_row(deck, model, motion, kw.value, r)?;
            if motion.inputs.len() != 1 {
                return Err(deck
                    .error(
                        DiagnosticKind::DesignVariable,
                        kw.span,
                        format!(
                            "FULLROT turns one input a whole turn, but the mechanism has {}",
                            count(motion.inputs.len(), "degree of freedom", "degrees of freedom")
                        ),
                    )
                    .with_hint("FULLROT needs a mechanism of one degree of freedom driven by an angle (a crank)"));
            }
            Some(FullRotation { row, line: kw.span.line })
        }
        None => None,
    };
    let frame = match &block.frame {
        Some(d) => {
            let x = coordinate(deck, sizes, d.keyword.value, &d.index)?;
            if sizes.moving[x] || sizes.moving.get(x + 1).is_none_or(|&m| m) {
                return Err(deck
                    .error(
                        DiagnosticKind::NotFixed,
                        d.index.span,
                        format!(
                            "VARYFRAME turns the frame about the fixed point whose x is co-ordinate {}, but \
                             co-ordinates {} and {} are not both fixed (XFIX)",
                            x + 1,
                            x + 1,
                            x + 2
                        ),
                    )
                    .with_hint(
                        "name the x co-ordinate of a frame pivot: a point whose x and y (the next co-ordinate) are \
                         both fixed",
                    ));
            }
            Some(FrameAngle { x, lo: d.lo.value, hi: d.hi.value, line: d.line })
        }
        None => None,
    };
    Ok((free_time, full_rotation, frame))
}

/// The 0-based prescribed row `r` of an input moved by MOV_RELE or MOV_ABSE.
fn input_row(
    deck: &Deck,
    model: &Model,
    motion: &Motion,
    kw: Keyword,
    r: &Spanned<i64>,
) -> Result<usize, Box<Diagnostic>> {
    let inputs: Vec<String> = model
        .prescribed
        .iter()
        .enumerate()
        .filter(|(_, row)| row.input.is_some())
        .map(|(k, _)| (k + 1).to_string())
        .collect();
    let hint = format!("{kw} names the prescribed row of an input (the rows of the inputs: {})", inputs.join(", "));
    let Some((k, info)) = usize::try_from(r.value - 1).ok().and_then(|k| model.prescribed.get(k).map(|i| (k, i)))
    else {
        return Err(deck
            .error(
                DiagnosticKind::UnknownRow,
                r.span,
                format!(
                    "{kw} names row {}, but the model has {}",
                    r.value,
                    count(model.prescribed.len(), "prescribed row", "prescribed rows")
                ),
            )
            .with_hint(hint));
    };
    let Some(j) = info.input else {
        return Err(deck
            .error(DiagnosticKind::DesignVariable, r.span, format!("{kw} names row {}, which is not an input", k + 1))
            .with_hint(hint));
    };
    let stepped = motion
        .inputs
        .get(j.saturating_sub(1))
        .is_some_and(|i| matches!(i, InputMotion::Relative { .. } | InputMotion::Absolute { .. }));
    if !stepped {
        return Err(deck
            .error(
                DiagnosticKind::DesignVariable,
                r.span,
                format!("{kw} names row {}, the input of DOF {j}, which is not moved by MOV_RELE or MOV_ABSE", k + 1),
            )
            .with_hint(
                "free timing and a full turn move the input from its start value in steps: drive it with MOV_RELE or \
                 MOV_ABSE",
            ));
    }
    Ok(k)
}
