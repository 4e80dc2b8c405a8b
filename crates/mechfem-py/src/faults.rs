//! The facts of an error as Python reads them: one mistake of a deck
//! ([`DeckDiagnostic`], Python's `_core.Diagnostic`: a `DeckError` carries
//! every one) and why an element cannot be evaluated ([`ElementFault`]), so
//! that a front end words them with its own names instead of reading the
//! message.

use mechfem_core::ElementError;
use mechfem_deck::Diagnostic;
use pyo3::prelude::*;

/// Why element `element` (deck number) cannot be evaluated: `kind`
/// (`coincident_points`, `no_belt_span`, `zero_radius`) and the numbers and
/// names of the reason as the core's message writes them: `distance` and
/// `difference` of a belt, `radius` (`R_a` or `R_c`) of a gear; None where
/// the kind has none.
#[pyclass(module = "mechfem._core", frozen, eq, get_all, from_py_object)]
#[derive(Debug, Clone, PartialEq)]
pub struct ElementFault {
    /// The element (deck number).
    pub element: usize,
    /// What is wrong with it.
    pub kind: String,
    /// A belt's distance between the wheel centres.
    pub distance: Option<String>,
    /// A belt's difference of the wheel radii.
    pub difference: Option<String>,
    /// A gear's radius that is zero.
    pub radius: Option<String>,
}

#[pymethods]
impl ElementFault {
    /// The fault with these values.
    #[new]
    #[pyo3(signature = (element, kind, distance = None, difference = None, radius = None))]
    fn new(
        element: usize,
        kind: String,
        distance: Option<String>,
        difference: Option<String>,
        radius: Option<String>,
    ) -> ElementFault {
        ElementFault { element, kind, distance, difference, radius }
    }

    /// The arguments of [`ElementFault::new`] that make it again.
    fn __getnewargs__(&self) -> (usize, String, Option<String>, Option<String>, Option<String>) {
        (self.element, self.kind.clone(), self.distance.clone(), self.difference.clone(), self.radius.clone())
    }

    fn __repr__(&self) -> String {
        format!("ElementFault(element={}, kind={:?})", self.element, self.kind)
    }
}

impl ElementFault {
    /// The fault of element `element` (deck number) the core's `error` describes.
    pub fn of(element: usize, error: &ElementError) -> ElementFault {
        let mut fault = ElementFault { element, kind: String::new(), distance: None, difference: None, radius: None };
        match error {
            ElementError::CoincidentPoints => fault.kind = "coincident_points".into(),
            ElementError::NoBeltSpan { l, d } => {
                fault.kind = "no_belt_span".into();
                fault.distance = Some(l.to_string());
                fault.difference = Some(d.to_string());
            }
            ElementError::ZeroRadius { name } => {
                fault.kind = "zero_radius".into();
                fault.radius = Some((*name).to_string());
            }
        }
        fault
    }
}

/// One mistake of a deck: `kind` (a stable code, snake case), `path`,
/// `line` and `column` (1-based; 0: the file as a whole), `text` (the
/// line), `message`, `hint`, and what it is about: `element`, `coordinate`
/// (deck numbers), `detail` (the core's reason in its words) and
/// `detail_fields` (the same as an [`ElementFault`]), None when it is about
/// none.
#[pyclass(module = "mechfem._core", name = "Diagnostic", frozen, eq, get_all, from_py_object)]
#[derive(Debug, Clone, PartialEq)]
pub struct DeckDiagnostic {
    pub kind: String,
    pub path: String,
    pub line: usize,
    pub column: usize,
    pub text: String,
    pub message: String,
    pub hint: Option<String>,
    pub element: Option<usize>,
    pub coordinate: Option<usize>,
    pub detail: Option<String>,
    pub detail_fields: Option<ElementFault>,
}

/// The arguments of [`DeckDiagnostic::new`] that make it again.
type DiagnosticArgs = (
    String,
    String,
    usize,
    usize,
    String,
    String,
    Option<String>,
    Option<usize>,
    Option<usize>,
    Option<String>,
    Option<ElementFault>,
);

#[pymethods]
impl DeckDiagnostic {
    /// The diagnostic with these values.
    #[new]
    #[allow(clippy::too_many_arguments)]
    fn new(
        kind: String,
        path: String,
        line: usize,
        column: usize,
        text: String,
        message: String,
        hint: Option<String>,
        element: Option<usize>,
        coordinate: Option<usize>,
        detail: Option<String>,
        detail_fields: Option<ElementFault>,
    ) -> DeckDiagnostic {
        DeckDiagnostic { kind, path, line, column, text, message, hint, element, coordinate, detail, detail_fields }
    }

    /// The arguments of [`DeckDiagnostic::new`] that make it again.
    fn __getnewargs__(&self) -> DiagnosticArgs {
        let d = self.clone();
        (
            d.kind,
            d.path,
            d.line,
            d.column,
            d.text,
            d.message,
            d.hint,
            d.element,
            d.coordinate,
            d.detail,
            d.detail_fields,
        )
    }

    fn __repr__(&self) -> String {
        format!("Diagnostic(kind={:?}, line={}, message={:?})", self.kind, self.line, self.message)
    }
}

impl DeckDiagnostic {
    /// The deck reader's diagnostic `d`.
    pub fn of(d: &Diagnostic) -> DeckDiagnostic {
        DeckDiagnostic {
            kind: d.kind.code().to_string(),
            path: d.path.to_string_lossy().into_owned(),
            line: d.line,
            column: if d.line == 0 { 0 } else { d.columns.start + 1 },
            text: d.text.clone(),
            message: d.message.clone(),
            hint: d.hint.clone(),
            element: d.element,
            coordinate: d.coordinate,
            detail: d.detail.clone(),
            detail_fields: match (d.element, &d.element_error) {
                (Some(element), Some(error)) => Some(ElementFault::of(element, error)),
                _ => None,
            },
        }
    }

    /// Its fields by name, as a `DeckError` carries the first diagnostic's.
    pub fn set_on(&self, py: Python<'_>, error: &Bound<'_, PyAny>) -> PyResult<()> {
        error.setattr("kind", &self.kind)?;
        error.setattr("path", &self.path)?;
        error.setattr("line", self.line)?;
        error.setattr("column", self.column)?;
        error.setattr("text", &self.text)?;
        error.setattr("message", &self.message)?;
        error.setattr("hint", self.hint.as_deref())?;
        error.setattr("element", self.element)?;
        error.setattr("coordinate", self.coordinate)?;
        error.setattr("detail", self.detail.as_deref())?;
        let fields = self.detail_fields.clone().map(|f| Py::new(py, f)).transpose()?;
        error.setattr("detail_fields", fields)
    }
}
