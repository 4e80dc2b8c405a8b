//! MOVEMENT to a core [`Motion`], solver [`Params`] and the integrator's
//! [`Integration`]; MOV_FUNC files.

use std::path::Path;

use mechfem_core::dynamics::{Integration, StopWhen};

use crate::compiled::Buffer;
use mechfem_core::{InputMotion, Mechanism, Motion, Params, State};

use super::table::{self, Layout, Table};
use crate::ast::{missing_movement, Deck, Mode, MotionDef, MotionKind};
use crate::diagnostic::{dof_hint, real, Diagnostic, DiagnosticKind, Hint, Span, Spanned};
use crate::keywords::Keyword;

pub(crate) fn motion(deck: &Deck, n_dof: usize, deck_dir: &Path) -> Result<(Option<Motion>, Params), Box<Diagnostic>> {
    let mut params = Params::default();
    let Some(mv) = &deck.movement else {
        // The parser reports this already; a simulation has nothing to do
        // without output times, an optimisation no positions to judge.
        if matches!(deck.mode.value, Mode::DynSim | Mode::KinOpt) {
            return Err(missing_movement(&deck.path, &deck.source, deck.mode.value, deck.mode.span));
        }
        return Ok((None, params));
    };
    if let Some(tol) = &mv.accuracy {
        params.tol = tol.value;
    }
    if let Some(m) = &mv.maxiter {
        params.max_iter = usize::try_from(m.value).unwrap_or(usize::MAX);
    }
    let steps = usize::try_from(mv.tstepe.steps.value).unwrap_or(1);
    let dt = mv.tstepe.dt.as_ref().map_or(1.0, |dt| dt.value);

    let mut per_dof: Vec<Option<&MotionDef>> = vec![None; n_dof];
    for m in &mv.motions {
        let kw = m.keyword.value;
        let j = m.dof.value;
        let Some(slot) = usize::try_from(j - 1).ok().and_then(|k| per_dof.get_mut(k)) else {
            return Err(deck
                .error(DiagnosticKind::UnknownDof, m.dof.span, format!("{kw} for DOF {j}, but NRDOF is {n_dof}"))
                .with_hint(dof_hint(n_dof)));
        };
        if let Some(first) = slot {
            return Err(deck
                .error(
                    DiagnosticKind::DuplicateMotion,
                    m.dof.span,
                    format!("DOF {j} is given a second motion ({} at line {})", first.keyword.value, first.line),
                )
                .with_hint("give each DOF exactly one MOV_ keyword"));
        }
        if matches!(m.kind, MotionKind::Free(_)) && n_dof != 1 {
            return Err(deck
                .error(
                    DiagnosticKind::FreeMotionDof,
                    m.keyword.span,
                    format!("MOV_FREE needs a mechanism with one degree of freedom, this one has NRDOF {n_dof}"),
                )
                .with_hint("drive each DOF with MOV_RELE, MOV_ABSE or MOV_FUNC"));
        }
        *slot = Some(m);
    }
    let mut inputs = Vec::with_capacity(n_dof);
    for (k, m) in per_dof.iter().enumerate() {
        let j = k + 1;
        let Some(m) = m else {
            let width = deck.line_text(mv.line).trim_end().chars().count();
            // Free motion has no timing, so the dynamics cannot use it, nor
            // does it give the same positions for every design; only a
            // simulation lets the forces move a DOF.
            let (dynamic, free) = match deck.mode.value {
                Mode::DynSim => (format!("`MOV_DYN {j} v0`, "), String::new()),
                Mode::DynAna | Mode::KinOpt => (String::new(), String::new()),
                Mode::KinAna => (String::new(), format!(", `MOV_FREE {j} ds`")),
            };
            return Err(deck
                .error(DiagnosticKind::MissingMotion, Span::new(mv.line, 0, width), format!("DOF {j} has no motion"))
                .with_hint(format!(
                    "every DOF needs one motion: add one of {dynamic}`MOV_RELE {j} delta`, `MOV_ABSE {j} end`, \
                     `MOV_FUNC {j} file`{free}"
                )));
        };
        inputs.push(match &m.kind {
            MotionKind::Relative(d) => InputMotion::Relative { delta: d.value },
            MotionKind::Absolute(e) => InputMotion::Absolute { end: e.value },
            MotionKind::Free(ds) => InputMotion::Free { ds: ds.value },
            MotionKind::Dynamic(v0) => InputMotion::Dynamic { v0: v0.value },
            MotionKind::Function(file) => {
                InputMotion::Table { rows: table(deck, file, deck_dir, steps + 1, steps as f64 * dt)? }
            }
        });
    }
    Ok((Some(Motion { steps, dt, inputs }), params))
}

/// The integrator's tolerances: INTTOL's, else both from the Newton
/// tolerance `params.tol` (ACCURACY or its default); its method
/// (INTEGRATOR). With INTTOL and without ACCURACY, the Newton tolerance
/// follows from INTTOL ([`Integration::newton_tolerance`]).
pub(crate) fn integration(deck: &Deck, params: &mut Params) -> Integration {
    let mv = deck.movement.as_ref();
    let mut integration = match mv.and_then(|mv| mv.inttol.as_ref()) {
        Some(t) => {
            let mut i = Integration::new(t.rtol.value, t.atol.value);
            if let Some(m) = mv.and_then(|mv| mv.integrator) {
                i.integrator = m.value;
            }
            if mv.is_some_and(|mv| mv.accuracy.is_none()) {
                params.tol = i.newton_tolerance();
            }
            i
        }
        None => Integration::from_accuracy(params.tol),
    };
    if let Some(m) = mv.and_then(|mv| mv.integrator) {
        integration.integrator = m.value;
    }
    integration
}

/// The STOPWHEN condition, its buffer checked against those defined.
pub(crate) fn stop_when(deck: &Deck, buffers: &[Buffer]) -> Result<Option<StopWhen>, Box<Diagnostic>> {
    let Some(def) = deck.movement.as_ref().and_then(|mv| mv.stop_when.as_ref()) else { return Ok(None) };
    let buffer = super::storage::defined_buffer(deck, &super::storage::by_number(buffers), &def.buffer)?;
    Ok(Some(StopWhen { quantity: buffer.quantity, buffer: buffer.number, value: def.value.value }))
}

/// Checks the velocity change / (n dt) of every MOV_RELE and MOV_ABSE
/// input as the run computes it (from the input's value at position 1):
/// a step time so short, or a change so large, that it is not a finite
/// number leaves the run nothing to work with.
pub(crate) fn check_rates(
    deck: &Deck,
    motion: &Motion,
    mech: &Mechanism,
    state: &State,
) -> Result<(), Box<Diagnostic>> {
    let Some(mv) = &deck.movement else { return Ok(()) };
    let time = motion.steps as f64 * motion.dt;
    for m in &mv.motions {
        let j = usize::try_from(m.dof.value - 1).unwrap_or(0);
        let (word, change) = match &m.kind {
            MotionKind::Relative(delta) => (delta, delta.value),
            MotionKind::Absolute(end) => (end, end.value - state.target[mech.input_row(j)]),
            MotionKind::Function(_) | MotionKind::Free(_) | MotionKind::Dynamic(_) => continue,
        };
        if !(change / time).is_finite() {
            return Err(deck
                .error(
                    DiagnosticKind::BadValue,
                    word.span,
                    format!(
                        "{} asks DOF {} to change by {} in a time of {}, faster than a number can hold",
                        m.keyword.value,
                        j + 1,
                        real(deck.as_written(
                            deck.scale.as_ref().and_then(|s| s.inputs.get(j)).copied().unwrap_or_default(),
                            change
                        )),
                        real(deck.as_written(mechfem_core::Dim::TIME, time))
                    ),
                )
                .with_hint("give a longer time step (TSTEPE n dt) or a smaller change"));
        }
    }
    Ok(())
}

/// Reads a MOV_FUNC file: one row `t value [velocity [acceleration]]` per
/// position (missing velocity and acceleration: 0). In a simulation, whose
/// driven input is interpolated in time from `0` to `span`, the times must
/// increase from row to row and cover that span.
fn table(
    deck: &Deck,
    file: &Spanned<String>,
    deck_dir: &Path,
    expected: usize,
    span: f64,
) -> Result<Vec<[f64; 4]>, Box<Diagnostic>> {
    let layout = Layout {
        keyword: Keyword::MovFunc,
        kind: DiagnosticKind::MotionFile,
        columns: 2..=4,
        names: &["the time", "the input value", "the velocity", "the acceleration"],
        row: "write one row per position: t value [velocity [acceleration]]",
        max_bytes: None,
    };
    let table = table::read(deck, file, deck_dir, &layout)?;
    if table.rows.len() != expected {
        let steps = expected - 1;
        return Err(deck
            .error(
                DiagnosticKind::MotionFile,
                file.span,
                format!("the MOV_FUNC file `{}` has {} rows, expected {expected}", file.value, table.rows.len()),
            )
            .with_hint(format!(
                "TSTEPE {steps} makes {expected} positions: give one row `t value [velocity [acceleration]]` for each"
            )));
    }
    if deck.mode.value == Mode::DynSim {
        // The table's times are the deck's; `span` is in the core's units.
        let span = deck.scale.as_ref().map_or(span, |s| s.units.from_core(mechfem_core::Dim::TIME, span));
        check_times(&table, span)?;
    }
    Ok(table
        .rows
        .iter()
        .map(|(_, values)| {
            let mut row = [0.0; 4];
            for (slot, v) in row.iter_mut().zip(values) {
                *slot = v.value;
            }
            row
        })
        .collect())
}

/// The times of a MOV_FUNC table that drives a simulation from `0` to
/// `span`: increasing from row to row (the input is interpolated between
/// rows, which two rows at one time, or rows out of order, leave undefined)
/// and covering the span (outside it the input would stand still). The ends
/// are compared within 1e-9 of the span, the rounding of times written in
/// decimal.
fn check_times(table: &Table, span: f64) -> Result<(), Box<Diagnostic>> {
    let order_hint = "list the rows of a MOV_FUNC file in order of increasing time, one row per output time of the \
                      simulation: the input is interpolated between them";
    let mut previous: Option<(usize, f64)> = None;
    for (line, values) in &table.rows {
        let t = &values[0];
        if let Some((before, t0)) = previous.filter(|(_, t0)| t.value <= *t0) {
            let message = if t.value == t0 {
                format!("the time {} is the time of the row above (line {before}) too", t.value)
            } else {
                format!("the time {} comes before the time {t0} of the row above (line {before})", t.value)
            };
            return Err(table.error(DiagnosticKind::MotionFile, t.span, message).with_hint(order_hint));
        }
        previous = Some((*line, t.value));
    }
    let slack = 1e-9 * span.abs();
    let (Some((_, first)), Some((_, last))) = (table.rows.first(), table.rows.last()) else { return Ok(()) };
    let (t_first, t_last) = (&first[0], &last[0]);
    let cover = format!(
        "the simulation runs from t = 0 to t = {} (TSTEPE n dt: n * dt): give the input's rows from t = 0 to that \
         end",
        real(span)
    );
    if t_first.value > slack {
        let message =
            format!("the MOV_FUNC table starts at t = {}, after the simulation's start at t = 0", t_first.value);
        return Err(table.error(DiagnosticKind::MotionFile, t_first.span, message).with_hint(cover));
    }
    if t_last.value < span - slack {
        let message = format!(
            "the MOV_FUNC table ends at t = {}, before the simulation's end at t = {}",
            t_last.value,
            real(span)
        );
        return Err(table.error(DiagnosticKind::MotionFile, t_last.span, message).with_hint(cover));
    }
    Ok(())
}
