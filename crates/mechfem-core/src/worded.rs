//! The words of a failed run, in parts: what a [`SolveError`] says about a
//! model, with the things of the model it names (elements, co-ordinates,
//! rows, deck terms, the DYNAMICS line of a mass or load) kept as
//! structure, numbered as the deck numbers them (1-based).
//!
//! A thing the model names ([`Names`]: a NAMES block, the names of a model
//! built in Python) is said with its name beside its number
//! (`point K (co-ordinates 13, 14)`, `row 6 (phi)`, `element 3 (crank,
//! TR2)`); an unnamed one by its number alone. Joined, the parts are the
//! message in the deck's words ([`Worded`]'s `Display`); a front end that
//! has its own names for the things of the model (the Python API) words
//! those parts itself and takes the text parts as they are.

use std::fmt;

use crate::error::{DeckTerm, DynamicSource, DynamicsFault, ElementError, Piece, SolveError};
use crate::model::{FormRef, Mechanism, State};
use crate::names::Names;
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
        /// The element's name, if the model names it.
        name: Option<String>,
    },
    /// One co-ordinate.
    Coordinate {
        /// Deck number.
        number: usize,
        /// The co-ordinate's name (`C.x`, `s`), if the model names it.
        name: Option<String>,
    },
    /// Co-ordinates, always said in the plural.
    Coords {
        /// Deck numbers.
        numbers: Vec<usize>,
        /// Each one's name (`x5` for an unnamed one) when the model names
        /// any of them, else empty.
        names: Vec<String>,
    },
    /// The x and y co-ordinates (deck numbers) of a point the model names.
    Point {
        /// The point's name.
        name: String,
        /// Deck numbers of its x and y.
        coords: [usize; 2],
    },
    /// One prescribed row.
    Row {
        /// Deck number.
        number: usize,
        /// The row's name, if the model names it.
        name: Option<String>,
    },
    /// Prescribed rows, always said in the plural.
    Rows {
        /// Deck numbers.
        numbers: Vec<usize>,
        /// Each one's name (its formula for an unnamed one) when the model
        /// names any of them, else empty.
        names: Vec<String>,
    },
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
            Part::Coordinate { .. } => "coordinate",
            Part::Coords { .. } => "coords",
            Part::Point { .. } => "point",
            Part::Row { .. } => "row",
            Part::Rows { .. } => "rows",
            Part::Term(_) => "term",
            Part::Line(_) => "line",
            Part::Detail { .. } => "detail",
        }
    }

    /// The part in the deck's words, with the model's names beside the
    /// numbers.
    pub fn deck(&self) -> String {
        let named = |words: String, names: &[String]| {
            if names.is_empty() {
                words
            } else {
                format!("{words} ({})", names.join(", "))
            }
        };
        match self {
            Part::Text(t) => t.clone(),
            Part::Element { number, ty, name: None } => format!("element {number} ({ty})"),
            Part::Element { number, ty, name: Some(name) } => format!("element {number} ({name}, {ty})"),
            Part::Coordinate { number, name } => named(format!("co-ordinate {number}"), name.as_slice()),
            Part::Coords { numbers, names } => named(format!("co-ordinates {}", list(numbers)), names),
            Part::Point { name, coords } => format!("point {name} (co-ordinates {})", list(coords)),
            Part::Row { number, name } => named(format!("row {number}"), name.as_slice()),
            Part::Rows { numbers, names } => named(format!("rows {}", list(numbers)), names),
            Part::Term(t) => t.deck().to_string(),
            Part::Line(n) => format!(" given at line {n}"),
            Part::Detail { error, .. } => error.to_string(),
        }
    }
}

/// How a message names the things of a model: by deck number (1-based),
/// with the model's name beside it where it has one.
struct Namer<'a> {
    mech: &'a Mechanism,
    names: &'a Names,
}

fn name_of(names: &[Option<String>], k: usize) -> Option<String> {
    names.get(k).cloned().flatten()
}

impl Namer<'_> {
    /// Element `k` (0-based).
    fn element(&self, k: usize) -> Part {
        let ty = self.mech.elements().get(k).map_or("?", |e| e.ty.name());
        Part::Element { number: k + 1, ty, name: name_of(&self.names.elements, k) }
    }

    /// Co-ordinate `i` (0-based).
    fn coordinate(&self, i: usize) -> Part {
        Part::Coordinate { number: i + 1, name: name_of(&self.names.coordinates, i) }
    }

    /// Co-ordinates `coords` (0-based): a named point when they are its x
    /// and y.
    fn coords(&self, coords: &[usize]) -> Part {
        if let [x, y] = *coords {
            if let Some(p) = self.names.points.iter().find(|p| p.0 == x && p.1 == y) {
                return Part::Point { name: p.2.clone(), coords: [x + 1, y + 1] };
            }
        }
        let named = coords.iter().any(|&i| name_of(&self.names.coordinates, i).is_some());
        let names = if named { coords.iter().map(|&i| self.names.coordinate(i)).collect() } else { Vec::new() };
        Part::Coords { numbers: coords.iter().map(|i| i + 1).collect(), names }
    }

    /// Prescribed row `r` (0-based).
    fn row(&self, r: usize) -> Part {
        Part::Row { number: r + 1, name: name_of(&self.names.prescribed, r) }
    }

    /// Prescribed rows `rows` (0-based).
    fn rows(&self, rows: &[usize]) -> Part {
        let named = rows.iter().any(|&r| name_of(&self.names.prescribed, r).is_some());
        let names = if named {
            rows.iter().map(|&r| self.names.row(self.mech, FormRef::Prescribed(r))).collect()
        } else {
            Vec::new()
        };
        Part::Rows { numbers: rows.iter().map(|r| r + 1).collect(), names }
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

    /// The failure in parts, with the deck's numbering of `mech` and the
    /// model's `names` beside the numbers; a fault of the dynamics names the
    /// line of its statement from `lines`.
    pub fn worded(&self, mech: &Mechanism, names: &Names, lines: Lines<'_>) -> Worded {
        let namer = Namer { mech, names };
        Worded(match self {
            SolveError::Element { element, source } => {
                let number = element + 1;
                vec![namer.element(*element), text(": "), Part::Detail { element: number, error: *source }]
            }
            SolveError::Singular { column, pivot } => {
                let coord = match mech.moving_coords().get(*column) {
                    Some(&i) => namer.coordinate(i),
                    None => Part::Coordinate { number: 0, name: None },
                };
                vec![text(format!("D^c is singular (pivot {pivot:.2e} at the column of ")), coord, text(")")]
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
            SolveError::Dynamics(fault) => dynamics_parts(&namer, lines, fault),
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
/// numbering and the model's names: what it is, the DYNAMICS line's keyword
/// and what that line names, and what to check.
fn dynamics_parts(namer: &Namer<'_>, lines: Lines<'_>, fault: &DynamicsFault) -> Vec<Part> {
    let mut parts = vec![text(format!("{} ", fault.quantity.words()))];
    parts.extend(match fault.source {
        DynamicSource::Body { element: k } => vec![text("of the MASS on "), namer.element(k)],
        DynamicSource::PointMass { x, y } => vec![text("of the PMASS at "), namer.coords(&[x, y])],
        DynamicSource::Inertia { coord } => vec![text("of the INERTIA on "), namer.coordinate(coord)],
        DynamicSource::Force { x, y } => vec![text("of the FORCE at "), namer.coords(&[x, y])],
        DynamicSource::Load { form: FormRef::Prescribed(r), keyword } => {
            vec![text(format!("of the {keyword} on ")), namer.row(r)]
        }
        DynamicSource::Load { form: FormRef::Dependent(d), keyword } => {
            let words = format!("of the {keyword} on dependent form parameter -{}", d + 1);
            match name_of(&namer.names.dependent, d) {
                Some(name) => vec![text(format!("{words} ({name})"))],
                None => vec![text(words)],
            }
        }
        DynamicSource::Row(r) => vec![text("of "), namer.row(r)],
        DynamicSource::Coordinate(i) => vec![text("on "), namer.coordinate(i)],
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

/// A failure at position 1, worded with the model's `names`: the error's
/// parts, and for a singular D^c the analysis at the co-ordinates `state`
/// where it was met, which names the rows and co-ordinates at fault (and is
/// added to the words).
pub fn position_one(
    mech: &Mechanism,
    names: &Names,
    lines: Lines<'_>,
    state: &mut State,
    err: &SolveError,
) -> (Worded, Option<Dependence>) {
    let mut worded = err.worded(mech, names, lines);
    if !matches!(err, SolveError::Singular { .. }) {
        return (worded, None);
    }
    let m = match diagnose(mech, state) {
        Ok(m) if m.rank < m.n => m,
        _ => return (worded, None),
    };
    let namer = Namer { mech, names };
    let rows: Vec<usize> = m.dependent_rows.iter().map(|r| r + 1).collect();
    let coords: Vec<usize> = m.free_coords.iter().map(|i| i + 1).collect();
    let parts = &mut worded.0;
    parts.push(text(format!("; D^c has rank {} of {}: prescribed ", m.rank, m.n)));
    match m.dependent_rows.as_slice() {
        [r] => parts.extend([namer.row(*r), text(" is superfluous")]),
        all => parts.extend([namer.rows(all), text(" are linearly dependent")]),
    }
    let free = namer.coords(&m.free_coords);
    parts.extend([text(", and "), free, text(" can move with every prescribed value held")]);
    (worded, Some(Dependence { rows, coords, rank: m.rank, size: m.n }))
}

/// Why a design is infeasible, worded with the deck's numbering of `mech`
/// and the model's `names`: a stable code (`position_one`, `other_branch`,
/// `left_branch`) and the words.
pub fn design_failure(mech: &Mechanism, names: &Names, lines: Lines<'_>, e: &DesignFailure) -> (&'static str, String) {
    match e {
        DesignFailure::Solve(e) => {
            ("position_one", format!("position 1 cannot be computed: {}", e.worded(mech, names, lines)))
        }
        DesignFailure::OtherBranch { .. } => ("other_branch", e.to_string()),
        DesignFailure::LeftBranch(_) => ("left_branch", e.to_string()),
    }
}

/// Why a design's motion stopped before its end (`last_good`: the 0-based
/// position it last reached), worded with the deck's numbering of `mech`
/// and the model's `names`.
pub fn design_stopped(mech: &Mechanism, names: &Names, lines: Lines<'_>, last_good: usize, e: &SolveError) -> String {
    format!("the motion stopped before position {}: {}", last_good + 2, e.worded(mech, names, lines))
}

/// A start design that cannot be computed, in words (`why`: its failure).
pub fn infeasible_start(why: &str) -> String {
    format!("the start design is infeasible: {why}")
}
