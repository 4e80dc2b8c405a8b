//! The Python exceptions and the mapping of deck and solver errors onto them.
//!
//! Messages name things as the deck does: elements, rows and co-ordinates
//! 1-based, never the core's 0-based indices. Beside its message, a solver
//! error carries its [`Part`]s, which a front end words in its own terms.

use std::path::Path;

use mechfem_core::run::MemoryRefusal;
use mechfem_core::{
    diagnose, DeckTerm, DynamicSource, DynamicsFault, ElementError, FormRef, Mechanism, Piece, SolveError, State,
};
use mechfem_deck::{Diagnostic, Diagnostics};
use pyo3::exceptions::{PyException, PyKeyboardInterrupt};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList, PyString, PyTuple};
use pyo3::{create_exception, PyErr};

create_exception!(mechfem.errors, MechfemError, PyException, "Base class of every error mechfem raises.");
create_exception!(
    mechfem.errors,
    DeckError,
    MechfemError,
    "The deck has a mistake: str() is the rendered diagnostic; `kind`, `path`, `line`, `column`, `text`, `message`, \
     `hint`, `element`, `coordinate` and `detail` are the first one's fields, `diagnostics` every one's."
);
create_exception!(
    mechfem.errors,
    AssemblyError,
    MechfemError,
    "The model cannot be evaluated at position 1: `element` (deck number), `element_type`, the core's `detail` and \
     its `detail_fields`, and the message's `parts`."
);
create_exception!(
    mechfem.errors,
    ConvergenceError,
    MechfemError,
    "Newton iteration cannot reach position 1: `reason` (a stable code), `iterations` and `residual` when it ran out, \
     and the message's `parts`."
);
create_exception!(
    mechfem.errors,
    LimitPositionError,
    MechfemError,
    "D^c is singular at position 1: `rows` that depend on each other, `coords` that can still move (deck numbers), \
     `rank` and `size` of D^c, `coordinate` at whose column the pivot vanished, and the message's `parts`."
);

create_exception!(
    mechfem.errors,
    ResourceError,
    MechfemError,
    "The run would keep more results in memory than its limit allows; it was refused before it started."
);

/// The `ResourceError` of a run refused before it started, worded by the
/// core, with its facts as fields: `positions`, `values`, `need` and
/// `limit` (bytes).
pub fn resource_error(py: Python<'_>, refusal: &MemoryRefusal) -> PyErr {
    let e = ResourceError::new_err(refusal.to_string());
    let value = e.value(py);
    let _ = value.setattr("positions", refusal.positions);
    let _ = value.setattr("values", refusal.values);
    let _ = value.setattr("need", refusal.need);
    let _ = value.setattr("limit", refusal.limit);
    e
}

/// The fields of one diagnostic, as a dict: `kind` (a stable code,
/// [`DiagnosticKind::code`](mechfem_deck::DiagnosticKind::code)), `path`,
/// `line` and `column` (1-based; 0: the file as a whole), `text` (the
/// line), `message`, `hint`, and what it is about: `element`, `coordinate`
/// (deck numbers), `detail` (the core's reason) and `detail_fields` (see
/// [`detail_fields`]), None when it is about none.
fn diagnostic_fields<'py>(py: Python<'py>, d: &Diagnostic) -> PyResult<Bound<'py, PyDict>> {
    let out = PyDict::new(py);
    out.set_item("kind", d.kind.code())?;
    out.set_item("path", d.path.to_string_lossy().into_owned())?;
    out.set_item("line", d.line)?;
    out.set_item("column", if d.line == 0 { 0 } else { d.columns.start + 1 })?;
    out.set_item("text", &d.text)?;
    out.set_item("message", &d.message)?;
    out.set_item("hint", d.hint.as_deref())?;
    out.set_item("element", d.element)?;
    out.set_item("coordinate", d.coordinate)?;
    out.set_item("detail", d.detail.as_deref())?;
    let fields = match (d.element, &d.element_error) {
        (Some(element), Some(error)) => Some(detail_fields(py, element, error)?),
        _ => None,
    };
    out.set_item("detail_fields", fields)?;
    Ok(out)
}

/// A `DeckError` carrying every diagnostic: str() renders them all, the
/// attributes are the first one's fields (see [`diagnostic_fields`]) and
/// `diagnostics` holds every one's, so that a front end names things from
/// the fields instead of reading the message.
pub fn deck_error(py: Python<'_>, path: &Path, diagnostics: &Diagnostics) -> PyErr {
    let err = DeckError::new_err(diagnostics.to_string());
    let value = err.value(py);
    // Setting attributes on a fresh exception instance cannot fail; building
    // the dicts only fails when Python is out of memory, and then the
    // message alone still says what is wrong.
    let _ = value.setattr("path", path.to_string_lossy().into_owned());
    let _ = value.setattr("line", 0);
    let all: Vec<Bound<'_, PyDict>> = diagnostics.iter().filter_map(|d| diagnostic_fields(py, d).ok()).collect();
    if let Some(first) = all.first() {
        for (key, item) in first.iter() {
            let _ = value.setattr(key.extract::<String>().unwrap_or_default(), item);
        }
    }
    let _ = value.setattr("diagnostics", all);
    err
}

/// What to do with the error `raised` by progress reporting during a run
/// that `kept` its positions (or not): Ctrl-C after which they were kept is
/// `Ok(true)`, the run was interrupted and its positions are returned (the
/// report says so); no error is `Ok(false)`; any other error is raised.
///
/// A Ctrl-C made after the run last looked for one is taken here too,
/// before anything is handed to Python: left pending, it would be raised
/// inside the first call into numpy, which cannot report it.
pub fn interrupted(py: Python<'_>, raised: Option<PyErr>, kept: bool) -> PyResult<bool> {
    let raised = raised.or_else(|| py.check_signals().err());
    match raised {
        None => Ok(false),
        Some(err) if kept && err.is_instance_of::<PyKeyboardInterrupt>(py) => Ok(true),
        Some(err) => Err(err),
    }
}

/// A short name for what failed, used by the run report (`Stop.kind`).
pub fn kind(err: &SolveError) -> &'static str {
    match err {
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

/// A piece of a message. The things of the model it names (elements,
/// co-ordinates, rows, deck terms, why an element failed) cross to Python
/// as structure, so that a front end names them in its own words (the
/// Python API with the model's names) without reading the message.
#[derive(Debug, Clone)]
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
    fn kind(&self) -> &'static str {
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

    /// A plain string for [`Part::Text`]; otherwise the tuple `(kind, value,
    /// deck words)`, the value being a number, a list of numbers, a term's
    /// code or the fields of [`detail_fields`].
    fn object<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let value = match self {
            Part::Text(t) => return Ok(PyString::new(py, t).into_any()),
            Part::Element { number: n, .. } | Part::Coordinate(n) | Part::Row(n) | Part::Line(n) => {
                n.into_pyobject(py)?.into_any()
            }
            Part::Coords(n) | Part::Rows(n) => PyList::new(py, n)?.into_any(),
            Part::Term(t) => PyString::new(py, t.code()).into_any(),
            Part::Detail { element, error } => detail_fields(py, *element, error)?.into_any(),
        };
        let items = [PyString::new(py, self.kind()).into_any(), value, PyString::new(py, &self.deck()).into_any()];
        Ok(PyTuple::new(py, items)?.into_any())
    }
}

fn text(t: impl Into<String>) -> Part {
    Part::Text(t.into())
}

/// The message the parts make, in the deck's words.
pub fn message(parts: &[Part]) -> String {
    parts.iter().map(Part::deck).collect()
}

/// The parts as the Python list of `parts` (see [`Part`]).
pub fn parts_object<'py>(py: Python<'py>, parts: &[Part]) -> PyResult<Bound<'py, PyList>> {
    let items = parts.iter().map(|p| p.object(py)).collect::<PyResult<Vec<_>>>()?;
    PyList::new(py, items)
}

/// Why element `element` (deck number) cannot be evaluated, as a dict:
/// `element`, `kind` (`coincident_points`, `no_belt_span`, `zero_radius`)
/// and the numbers and names of the reason, as the core's message writes
/// them: `distance` and `difference` of a belt, `radius` (`R_a` or `R_c`).
pub fn detail_fields<'py>(py: Python<'py>, element: usize, error: &ElementError) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("element", element)?;
    match error {
        ElementError::CoincidentPoints => d.set_item("kind", "coincident_points")?,
        ElementError::NoBeltSpan { l, d: diff } => {
            d.set_item("kind", "no_belt_span")?;
            d.set_item("distance", l.to_string())?;
            d.set_item("difference", diff.to_string())?;
        }
        ElementError::ZeroRadius { name } => {
            d.set_item("kind", "zero_radius")?;
            d.set_item("radius", *name)?;
        }
    }
    Ok(d)
}

/// The DYNAMICS line of each mass and load, as the compiled deck gives
/// them ([`mechfem_deck::Compiled::dynamics_lines`]).
pub type Lines<'a> = &'a [(DynamicSource, usize)];

/// The error in parts, with the deck's numbering; a fault of the dynamics
/// names the line of its statement from `lines`.
pub fn parts(mech: &Mechanism, lines: Lines<'_>, err: &SolveError) -> Vec<Part> {
    match err {
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
            "the correction ({corrected:.3e}) went too far from the prediction (a move of {predicted:.3e}): the step \
             may jump to another assembly branch"
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

/// The error in words, with the deck's numbering.
pub fn describe(mech: &Mechanism, lines: Lines<'_>, err: &SolveError) -> String {
    message(&parts(mech, lines, err))
}

/// The exception for a failure at position 1. A singular D^c is analysed
/// at the co-ordinates where it was met, to name the rows and co-ordinates
/// at fault.
pub fn position_one_error(
    py: Python<'_>,
    mech: &Mechanism,
    lines: Lines<'_>,
    state: &mut State,
    err: &SolveError,
) -> PyErr {
    let (e, parts) = position_one_exception(py, mech, lines, state, err);
    let value = e.value(py);
    // Every failure here is at position 1; a front end words it from this
    // and the fields below instead of from the message.
    let _ = value.setattr("position", 1);
    let _ = value.setattr("reason", kind(err));
    if let Ok(parts) = parts_object(py, &parts) {
        let _ = value.setattr("parts", parts);
    }
    match err {
        SolveError::Element { element, source } => {
            let _ = value.setattr("element", element + 1);
            let _ = value.setattr("element_type", mech.elements().get(*element).map(|e| e.ty.name()));
            let _ = value.setattr("detail", source.to_string());
            if let Ok(fields) = detail_fields(py, element + 1, source) {
                let _ = value.setattr("detail_fields", fields);
            }
        }
        SolveError::Singular { column, .. } => {
            let _ = value.setattr("coordinate", mech.moving_coords().get(*column).map(|i| i + 1));
        }
        SolveError::NoConvergence { iterations, residual } => {
            let _ = value.setattr("iterations", *iterations);
            let _ = value.setattr("residual", *residual);
        }
        _ => {}
    }
    e
}

/// The exception of [`position_one_error`] and the parts of its message,
/// with the fields only its analysis finds (the rows and co-ordinates of a
/// singular D^c).
fn position_one_exception(
    py: Python<'_>,
    mech: &Mechanism,
    lines: Lines<'_>,
    state: &mut State,
    err: &SolveError,
) -> (PyErr, Vec<Part>) {
    let mut parts = parts(mech, lines, err);
    let e = match err {
        SolveError::Element { .. } => AssemblyError::new_err(message(&parts)),
        SolveError::Singular { .. } => {
            let (rows, coords, rank) = match diagnose(mech, state) {
                Ok(m) if m.rank < m.n => {
                    let rows: Vec<usize> = m.dependent_rows.iter().map(|r| r + 1).collect();
                    let coords: Vec<usize> = m.free_coords.iter().map(|i| i + 1).collect();
                    parts.push(text(format!("; D^c has rank {} of {}: prescribed ", m.rank, m.n)));
                    match rows.as_slice() {
                        [r] => parts.extend([Part::Row(*r), text(" is superfluous")]),
                        _ => parts.extend([Part::Rows(rows.clone()), text(" are linearly dependent")]),
                    }
                    parts.extend([
                        text(", and "),
                        Part::Coords(coords.clone()),
                        text(" can move with every prescribed value held"),
                    ]);
                    (rows, coords, Some((m.rank, m.n)))
                }
                _ => (Vec::new(), Vec::new(), None),
            };
            let e = LimitPositionError::new_err(message(&parts));
            let value = e.value(py);
            let _ = value.setattr("rows", rows);
            let _ = value.setattr("coords", coords);
            let _ = value.setattr("rank", rank.map(|r| r.0));
            let _ = value.setattr("size", rank.map(|r| r.1));
            e
        }
        SolveError::NoConvergence { .. }
        | SolveError::BranchJump { .. }
        | SolveError::DetSignChange { .. }
        | SolveError::NonFinite
        | SolveError::Simulation { .. } => ConvergenceError::new_err(message(&parts)),
        SolveError::NotComputed | SolveError::Unsupported(_) | SolveError::Interrupted | SolveError::Dynamics(_) => {
            MechfemError::new_err(message(&parts))
        }
    };
    (e, parts)
}

fn list(numbers: &[usize]) -> String {
    numbers.iter().map(usize::to_string).collect::<Vec<_>>().join(", ")
}
