//! The words of a failed run, in parts: what a [`SolveError`] says about a
//! model, with the things of the model it names (elements, co-ordinates,
//! rows, deck terms, the DYNAMICS line of a mass or load) kept as
//! structure, numbered as the deck numbers them (1-based).
//!
//! Joined, the parts are the message in the deck's words
//! ([`Worded`]'s `Display`); a front end that has its own names for the
//! things of the model (the Python API) words those parts itself and takes
//! the text parts as they are.

use std::fmt;

use crate::error::{DeckTerm, DynamicSource, DynamicsFault, ElementError, Piece, SolveError};
use crate::model::{FormRef, Mechanism, State};
use crate::run::design::DesignFailure;
use crate::solver::diagnose;

/// A piece of a message.
#[derive(Debug, Clone, PartialEq)]
pub enum Part {
    /// Words every front end says the same way.
    Text(String),
    /// Element `number` (deck numbering) of type `ty`.
    Element {
        /// Deck number.
        number: usize,
        /// Type name.
        ty: &'static str,
    },
    /// One co-ordinate.
    Coordinate(usize),
    /// Co-ordinates, always said in the plural.
    Coords(Vec<usize>),
    /// One prescribed row.
    Row(usize),
    /// Prescribed rows, always said in the plural.
    Rows(Vec<usize>),
    /// A term the deck spells its own way.
    Term(DeckTerm),
    /// The deck line of the statement just named (` given at line 23`); a front
    /// end whose model has no deck leaves it out.
    Line(usize),
    /// Why element `element` cannot be evaluated.
    Detail {
        /// Deck number.
        element: usize,
        /// The core's reason.
        error: ElementError,
    },
}

impl Part {
    /// A stable code of the part's kind, snake case.
    pub fn kind(&self) -> &'static str {
        match self {
            Part::Text(_) => "text",
            Part::Element { .. } => "element",
            Part::Coordinate(_) => "coordinate",
            Part::Coords(_) => "coords",
            Part::Row(_) => "row",
            Part::Rows(_) => "rows",
            Part::Term(_) => "term",
            Part::Line(_) => "line",
            Part::Detail { .. } => "detail",
        }
    }

    /// The part in the deck's words.
    pub fn deck(&self) -> String {
        match self {
            Part::Text(t) => t.clone(),
            Part::Element { number, ty } => format!("element {number} ({ty})"),
            Part::Coordinate(i) => format!("co-ordinate {i}"),
            Part::Coords(c) => format!("co-ordinates {}", list(c)),
            Part::Row(r) => format!("row {r}"),
            Part::Rows(r) => format!("rows {}", list(r)),
            Part::Term(t) => t.deck().to_string(),
            Part::Line(n) => format!(" given at line {n}"),
            Part::Detail { error, .. } => error.to_string(),
        }
    }
}

/// A message in parts; `Display` says it in the deck's words.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Worded(pub Vec<Part>);

impl fmt::Display for Worded {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.0.iter().try_for_each(|p| f.write_str(&p.deck()))
    }
}

fn text(t: impl Into<String>) -> Part {
    Part::Text(t.into())
}

fn list(numbers: &[usize]) -> String {
    numbers.iter().map(usize::to_string).collect::<Vec<_>>().join(", ")
}

/// The DYNAMICS line of each mass and load (deck line numbers), for a
/// fault of the dynamics to name its statement's line; empty for a model
/// built without a deck.
pub type Lines<'a> = &'a [(DynamicSource, usize)];

impl SolveError {
    /// A stable code of the failure, snake case (a run report's stop kind,
    /// an exception's `reason`).
    pub fn code(&self) -> &'static str {
        match self {
            SolveError::Element { .. } => "element",
            SolveError::Singular { .. } => "singular",
            SolveError::NoConvergence { .. } => "no_convergence",
            SolveError::BranchJump { .. } | SolveError::DetSignChange { .. } => "branch_jump",
            SolveError::NotComputed => "not_computed",
            SolveError::Unsupported(_) => "unsupported",
            SolveError::NonFinite => "non_finite",
            SolveError::Interrupted => "interrupted",
            SolveError::Simulation { .. } => "simulation",
            SolveError::Dynamics(_) => "non_finite_dynamics",
        }
    }

    /// The failure in parts, with the deck's numbering of `mech`; a fault of
    /// the dynamics names the line of its statement from `lines`.
    pub fn worded(&self, mech: &Mechanism, lines: Lines<'_>) -> Worded {
        Worded(match self {
            SolveError::Element { element, source } => {
                let ty = mech.elements().get(*element).map_or("?", |e| e.ty.name());
                let number = element + 1;
                vec![Part::Element { number, ty }, text(": "), Part::Detail { element: number, error: *source }]
            }
            SolveError::Singular { column, pivot } => {
                let coord = mech.moving_coords().get(*column).map_or(0, |i| i + 1);
                vec![
                    text(format!("D^c is singular (pivot {pivot:.2e} at the column of ")),
                    Part::Coordinate(coord),
                    text(")"),
                ]
            }
            SolveError::NoConvergence { iterations, residual } => vec![text(format!(
                "Newton iteration did not converge in {iterations} iterations (largest deformation {residual:.3e})"
            ))],
            SolveError::BranchJump { predicted, corrected } => vec![text(format!(
                "the correction ({corrected:.3e}) went too far from the prediction (a move of {predicted:.3e}): the \
                 step may jump to another assembly branch"
            ))],
            SolveError::DetSignChange { before, after } => vec![text(format!(
                "det(D^c) changed sign within the step (from {before:.3e} to {after:.3e}): the step crosses a limit \
                 position or a point where two assembly branches meet"
            ))],
            SolveError::Dynamics(fault) => dynamics_parts(mech, lines, fault),
            SolveError::Unsupported(u) => u
                .pieces()
                .iter()
                .map(|p| match p {
                    Piece::Text(t) => text(*t),
                    Piece::Term(t) => Part::Term(*t),
                })
                .collect(),
            other => vec![text(other.to_string())],
        })
    }
}

/// A result of the dynamics that is not finite, in parts with the deck's
/// numbering: what it is, the DYNAMICS line's keyword and what that line
/// names, and what to check.
fn dynamics_parts(mech: &Mechanism, lines: Lines<'_>, fault: &DynamicsFault) -> Vec<Part> {
    let element = |k: usize| Part::Element { number: k + 1, ty: mech.elements().get(k).map_or("?", |e| e.ty.name()) };
    let mut parts = vec![text(format!("{} ", fault.quantity.words()))];
    parts.extend(match fault.source {
        DynamicSource::Body { element: k } => vec![text("of the MASS on "), element(k)],
        DynamicSource::PointMass { x, y } => vec![text("of the PMASS at "), Part::Coords(vec![x + 1, y + 1])],
        DynamicSource::Inertia { coord } => vec![text("of the INERTIA on "), Part::Coordinate(coord + 1)],
        DynamicSource::Force { x, y } => vec![text("of the FORCE at "), Part::Coords(vec![x + 1, y + 1])],
        DynamicSource::Load { form: FormRef::Prescribed(r), keyword } => {
            vec![text(format!("of the {keyword} on ")), Part::Row(r + 1)]
        }
        DynamicSource::Load { form: FormRef::Dependent(d), keyword } => {
            vec![text(format!("of the {keyword} on dependent form parameter -{}", d + 1))]
        }
        DynamicSource::Row(r) => vec![text("of "), Part::Row(r + 1)],
        DynamicSource::Coordinate(i) => vec![text("on "), Part::Coordinate(i + 1)],
        DynamicSource::FreeDofs => {
            vec![text("of the degrees of freedom moved by the forces ("), Part::Term(DeckTerm::Dynamic), text(")")]
        }
        DynamicSource::Drives => vec![text("of the drives")],
    });
    if let Some(&(_, line)) = lines.iter().find(|(s, _)| *s == fault.source) {
        parts.push(Part::Line(line));
    }
    parts.push(text(
        " is not finite: a mass, a load or a speed of the motion is too large for the products the dynamics form of \
         them (a double holds about 1.8e308); check the units and the values of the DYNAMICS block and of the motion",
    ));
    parts
}

/// What the analysis of a singular D^c at position 1 found (deck numbers).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Dependence {
    /// Prescribed rows that depend on each other.
    pub rows: Vec<usize>,
    /// Co-ordinates that can move with every prescribed value held.
    pub coords: Vec<usize>,
    /// Rank of D^c.
    pub rank: usize,
    /// Order of D^c.
    pub size: usize,
}

/// A failure at position 1, worded: the error's parts, and for a singular
/// D^c the analysis at the co-ordinates `state` where it was met, which
/// names the rows and co-ordinates at fault (and is added to the words).
pub fn position_one(
    mech: &Mechanism,
    lines: Lines<'_>,
    state: &mut State,
    err: &SolveError,
) -> (Worded, Option<Dependence>) {
    let mut worded = err.worded(mech, lines);
    if !matches!(err, SolveError::Singular { .. }) {
        return (worded, None);
    }
    let m = match diagnose(mech, state) {
        Ok(m) if m.rank < m.n => m,
        _ => return (worded, None),
    };
    let rows: Vec<usize> = m.dependent_rows.iter().map(|r| r + 1).collect();
    let coords: Vec<usize> = m.free_coords.iter().map(|i| i + 1).collect();
    let parts = &mut worded.0;
    parts.push(text(format!("; D^c has rank {} of {}: prescribed ", m.rank, m.n)));
    match rows.as_slice() {
        [r] => parts.extend([Part::Row(*r), text(" is superfluous")]),
        _ => parts.extend([Part::Rows(rows.clone()), text(" are linearly dependent")]),
    }
    parts.extend([text(", and "), Part::Coords(coords.clone()), text(" can move with every prescribed value held")]);
    (worded, Some(Dependence { rows, coords, rank: m.rank, size: m.n }))
}

/// Why a design is infeasible, worded with the deck's numbering of `mech`:
/// a stable code (`position_one`, `other_branch`, `left_branch`) and the words.
pub fn design_failure(mech: &Mechanism, lines: Lines<'_>, e: &DesignFailure) -> (&'static str, String) {
    match e {
        DesignFailure::Solve(e) => {
            ("position_one", format!("position 1 cannot be computed: {}", e.worded(mech, lines)))
        }
        DesignFailure::OtherBranch { .. } => ("other_branch", e.to_string()),
        DesignFailure::LeftBranch(_) => ("left_branch", e.to_string()),
    }
}

/// Why a design's motion stopped before its end (`last_good`: the 0-based
/// position it last reached), worded with the deck's numbering of `mech`.
pub fn design_stopped(mech: &Mechanism, lines: Lines<'_>, last_good: usize, e: &SolveError) -> String {
    format!("the motion stopped before position {}: {}", last_good + 2, e.worded(mech, lines))
}

/// A start design that cannot be computed, in words (`why`: its failure).
pub fn infeasible_start(why: &str) -> String {
    format!("the start design is infeasible: {why}")
}
