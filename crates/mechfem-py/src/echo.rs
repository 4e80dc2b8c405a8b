//! The echo of a run's model as Python reads it (`Run.model`, `Check.model`):
//! typed objects owned by Rust, read through getters, in the deck's
//! numbering and units, compared by value and picklable
//! (`__getnewargs__`). What every run of one compiled deck shares (the
//! elements, the rows' FORM terms, the DOFs, units, points and labels) is
//! made once ([`crate::convert::Echo`]); a run adds its numbers.

use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};

/// One FORM line: `factor * form` of element `element`.
#[pyclass(module = "mechfem._core", frozen, eq, get_all, from_py_object)]
#[derive(Debug, Clone, PartialEq)]
pub struct Term {
    /// The element's number.
    pub element: usize,
    /// The form parameter's name (`ANGB`, `LENL`).
    pub form: String,
    /// Its factor in the row.
    pub factor: f64,
    /// The FORM line's sequence number.
    pub seq: i64,
    /// The FORM line's line in the deck.
    pub line: usize,
}

#[pymethods]
impl Term {
    /// The term with these values.
    #[new]
    fn new(element: usize, form: String, factor: f64, seq: i64, line: usize) -> Term {
        Term { element, form, factor, seq, line }
    }

    /// The arguments of [`Term::new`] that make it again.
    fn __getnewargs__(&self) -> (usize, String, f64, i64, usize) {
        (self.element, self.form.clone(), self.factor, self.seq, self.line)
    }

    fn __repr__(&self) -> String {
        format!(
            "Term(element={}, form={}, factor={}, seq={}, line={})",
            self.element,
            text(&self.form),
            number(self.factor),
            self.seq,
            self.line
        )
    }
}

/// One ELEM line.
#[pyclass(module = "mechfem._core", frozen, eq, get_all, from_py_object)]
#[derive(Debug, Clone, PartialEq)]
pub struct EchoElement {
    /// The element's number.
    pub number: usize,
    /// Its type (`BIN`, `TR2`).
    #[pyo3(name = "type")]
    pub kind: String,
    /// Its co-ordinates, as the deck numbers them.
    pub coords: Vec<i64>,
    /// What each of its co-ordinates is (`x1`, `phi`).
    pub coord_names: Vec<String>,
    /// The ELEM line's line in the deck.
    pub line: usize,
    /// Its name in the deck's NAMES block (`ELEM 1 crank`), or None.
    pub name: Option<String>,
}

#[pymethods]
impl EchoElement {
    /// The element with these values.
    #[new]
    #[pyo3(signature = (number, kind, coords, coord_names, line, name = None))]
    fn new(
        number: usize,
        kind: String,
        coords: Vec<i64>,
        coord_names: Vec<String>,
        line: usize,
        name: Option<String>,
    ) -> EchoElement {
        EchoElement { number, kind, coords, coord_names, line, name }
    }

    /// The arguments of [`EchoElement::new`] that make it again.
    #[allow(clippy::type_complexity)]
    fn __getnewargs__(&self) -> (usize, String, Vec<i64>, Vec<String>, usize, Option<String>) {
        let e = self.clone();
        (e.number, e.kind, e.coords, e.coord_names, e.line, e.name)
    }

    fn __repr__(&self) -> String {
        format!(
            "EchoElement(number={}, type={}, coords={:?}, name={})",
            self.number,
            text(&self.kind),
            self.coords,
            maybe(&self.name)
        )
    }
}

/// A prescribed row of D^c (`dest > 0`) or a dependent form parameter
/// (`dest < 0`).
#[pyclass(module = "mechfem._core", frozen, eq, get_all, from_py_object)]
#[derive(Debug, Clone, PartialEq)]
pub struct EchoRow {
    /// The row's number: r > 0 prescribed, -k the k-th dependent one.
    pub dest: i64,
    /// Its FORM terms.
    pub terms: Vec<Term>,
    /// The value PARA prescribes, if any.
    pub para: Option<f64>,
    /// The DOF whose input this row is, if it is one.
    pub input: Option<usize>,
    /// Its value at position 1.
    pub value: f64,
    /// Its name in the deck's NAMES block (`ROW 6 phi`, `DEP 1 psi`), or None.
    pub name: Option<String>,
}

#[pymethods]
impl EchoRow {
    /// The row with these values.
    #[new]
    #[pyo3(signature = (dest, terms, para, input, value, name = None))]
    fn new(
        dest: i64,
        terms: Vec<Term>,
        para: Option<f64>,
        input: Option<usize>,
        value: f64,
        name: Option<String>,
    ) -> EchoRow {
        EchoRow { dest, terms, para, input, value, name }
    }

    /// The arguments of [`EchoRow::new`] that make it again.
    #[allow(clippy::type_complexity)]
    fn __getnewargs__(&self) -> (i64, Vec<Term>, Option<f64>, Option<usize>, f64, Option<String>) {
        let r = self.clone();
        (r.dest, r.terms, r.para, r.input, r.value, r.name)
    }

    fn __repr__(&self) -> String {
        format!(
            "EchoRow(dest={}, formula={}, value={}, name={})",
            self.dest,
            text(&self.formula()),
            number(self.value),
            maybe(&self.name)
        )
    }

    /// The combination, e.g. `ANGB(2) - ANGB(4)`, a factor other than one
    /// written before its term (`0.5*LENL(3)`).
    fn formula(&self) -> String {
        let mut out = String::new();
        for t in &self.terms {
            let magnitude = t.factor.abs();
            let text = if magnitude == 1.0 {
                format!("{}({})", t.form, t.element)
            } else {
                format!("{}*{}({})", general(magnitude), t.form, t.element)
            };
            if out.is_empty() {
                out = if t.factor < 0.0 { format!("-{text}") } else { text };
            } else {
                out += if t.factor < 0.0 { " - " } else { " + " };
                out += &text;
            }
        }
        out
    }
}

/// `s` as Python writes a text in a repr.
fn text(s: &str) -> String {
    format!("'{}'", s.replace('\\', "\\\\").replace('\'', "\\'"))
}

/// `s` as Python writes an optional text in a repr.
fn maybe(s: &Option<String>) -> String {
    s.as_deref().map_or_else(|| "None".to_owned(), text)
}

/// `v` as Python writes a float in a repr.
fn number(v: f64) -> String {
    if v.is_nan() {
        "nan".to_owned()
    } else if v.is_infinite() {
        (if v > 0.0 { "inf" } else { "-inf" }).to_owned()
    } else {
        format!("{v:?}")
    }
}

/// `v` as Python's `format(v, "g")` writes it: six significant digits,
/// trailing zeros dropped, an exponent below 1e-4 and from 1e6 on.
fn general(v: f64) -> String {
    if v == 0.0 || !v.is_finite() {
        return format!("{v}");
    }
    let exponent = format!("{v:.5e}");
    let (mantissa, power) = exponent.split_once('e').unwrap_or((exponent.as_str(), "0"));
    let power: i32 = power.parse().unwrap_or(0);
    let trimmed =
        |s: &str| if s.contains('.') { s.trim_end_matches('0').trim_end_matches('.').to_owned() } else { s.to_owned() };
    if (-4..6).contains(&power) {
        let decimals = usize::try_from(5 - power).unwrap_or(0);
        trimmed(&format!("{v:.decimals$}"))
    } else {
        let sign = if power < 0 { '-' } else { '+' };
        format!("{}e{sign}{:02}", trimmed(mantissa), power.abs())
    }
}

/// One co-ordinate: fixed or moving, its given value and its value at
/// position 1.
#[pyclass(module = "mechfem._core", frozen, eq, get_all, from_py_object)]
#[derive(Debug, Clone, PartialEq)]
pub struct EchoCoordinate {
    /// The co-ordinate's number.
    pub number: usize,
    /// Whether it moves.
    pub moving: bool,
    /// Its value as the deck gives it (XFIX, XMOV).
    pub given: f64,
    /// Its value at position 1.
    pub adjusted: f64,
    /// Its name from the deck's NAMES block (`C.x` for `POINT 9 10 C`,
    /// `s` for `COORD 11 s`), or None.
    pub name: Option<String>,
}

#[pymethods]
impl EchoCoordinate {
    /// The co-ordinate with these values.
    #[new]
    #[pyo3(signature = (number, moving, given, adjusted, name = None))]
    fn new(number: usize, moving: bool, given: f64, adjusted: f64, name: Option<String>) -> EchoCoordinate {
        EchoCoordinate { number, moving, given, adjusted, name }
    }

    /// The arguments of [`EchoCoordinate::new`] that make it again.
    fn __getnewargs__(&self) -> (usize, bool, f64, f64, Option<String>) {
        (self.number, self.moving, self.given, self.adjusted, self.name.clone())
    }

    fn __repr__(&self) -> String {
        format!(
            "EchoCoordinate(number={}, moving={}, given={}, adjusted={}, name={})",
            self.number,
            if self.moving { "True" } else { "False" },
            number(self.given),
            number(self.adjusted),
            maybe(&self.name)
        )
    }
}

/// A point the NAMES block names: co-ordinates `x` and `y` (1-based) are
/// `name.x` and `name.y`.
#[pyclass(module = "mechfem._core", frozen, eq, get_all, from_py_object)]
#[derive(Debug, Clone, PartialEq)]
pub struct EchoPoint {
    /// The co-ordinate of its x.
    pub x: usize,
    /// The co-ordinate of its y.
    pub y: usize,
    /// Its name.
    pub name: String,
}

#[pymethods]
impl EchoPoint {
    /// The point with these values.
    #[new]
    fn new(x: usize, y: usize, name: String) -> EchoPoint {
        EchoPoint { x, y, name }
    }

    /// The arguments of [`EchoPoint::new`] that make it again.
    fn __getnewargs__(&self) -> (usize, usize, String) {
        (self.x, self.y, self.name.clone())
    }

    fn __repr__(&self) -> String {
        format!("EchoPoint(x={}, y={}, name={})", self.x, self.y, text(&self.name))
    }
}

/// The model as compiled from the deck, for the echo in the print file: its
/// elements, rows, DOFs and co-ordinates, its mode, masses and loads, units,
/// named points, and the names and units of its things (`labels`). The
/// lists are shared by every run of one compiled deck where they do not
/// change (read them, do not change them).
#[pyclass(module = "mechfem._core", frozen)]
pub struct EchoModel {
    pub elements: Py<PyList>,
    pub prescribed: Py<PyList>,
    pub dependent: Py<PyList>,
    pub dofs: Py<PyList>,
    pub coordinates: Py<PyList>,
    pub mode: String,
    pub dynamics: Py<PyAny>,
    pub units: Py<PyDict>,
    pub points: Py<PyList>,
    pub labels: Py<PyAny>,
}

#[pymethods]
impl EchoModel {
    /// The model with these parts (what a pickle of it is made again from).
    #[new]
    #[pyo3(signature = (elements, prescribed, dependent, dofs, coordinates, mode, dynamics, units, points, labels))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        elements: Bound<'_, PyList>,
        prescribed: Bound<'_, PyList>,
        dependent: Bound<'_, PyList>,
        dofs: Bound<'_, PyList>,
        coordinates: Bound<'_, PyList>,
        mode: String,
        dynamics: Bound<'_, PyAny>,
        units: Bound<'_, PyDict>,
        points: Bound<'_, PyList>,
        labels: Bound<'_, PyAny>,
    ) -> EchoModel {
        EchoModel {
            elements: elements.unbind(),
            prescribed: prescribed.unbind(),
            dependent: dependent.unbind(),
            dofs: dofs.unbind(),
            coordinates: coordinates.unbind(),
            mode,
            dynamics: dynamics.unbind(),
            units: units.unbind(),
            points: points.unbind(),
            labels: labels.unbind(),
        }
    }

    /// The arguments of [`EchoModel::new`] that make it again.
    #[allow(clippy::type_complexity)]
    fn __getnewargs__<'py>(
        &self,
        py: Python<'py>,
    ) -> (
        Bound<'py, PyList>,
        Bound<'py, PyList>,
        Bound<'py, PyList>,
        Bound<'py, PyList>,
        Bound<'py, PyList>,
        String,
        Bound<'py, PyAny>,
        Bound<'py, PyDict>,
        Bound<'py, PyList>,
        Bound<'py, PyAny>,
    ) {
        (
            self.elements.bind(py).clone(),
            self.prescribed.bind(py).clone(),
            self.dependent.bind(py).clone(),
            self.dofs.bind(py).clone(),
            self.coordinates.bind(py).clone(),
            self.mode.clone(),
            self.dynamics.bind(py).clone(),
            self.units.bind(py).clone(),
            self.points.bind(py).clone(),
            self.labels.bind(py).clone(),
        )
    }

    /// Two echoes are equal when every part but the labels is (the labels
    /// follow from them).
    fn __eq__(&self, py: Python<'_>, other: &Bound<'_, PyAny>) -> PyResult<bool> {
        let Ok(o) = other.cast::<EchoModel>() else { return Ok(false) };
        let o = o.get();
        let same = |a: &Py<PyList>, b: &Py<PyList>| a.bind(py).eq(b.bind(py));
        Ok(self.mode == o.mode
            && same(&self.elements, &o.elements)?
            && same(&self.prescribed, &o.prescribed)?
            && same(&self.dependent, &o.dependent)?
            && same(&self.dofs, &o.dofs)?
            && same(&self.coordinates, &o.coordinates)?
            && same(&self.points, &o.points)?
            && self.dynamics.bind(py).eq(o.dynamics.bind(py))?
            && self.units.bind(py).eq(o.units.bind(py))?)
    }

    fn __repr__(&self, py: Python<'_>) -> String {
        format!(
            "EchoModel(mode={}, elements={}, prescribed={}, coordinates={})",
            text(&self.mode),
            self.elements.bind(py).len(),
            self.prescribed.bind(py).len(),
            self.coordinates.bind(py).len()
        )
    }

    /// Its ELEM lines ([`EchoElement`]).
    #[getter]
    fn elements<'py>(&self, py: Python<'py>) -> Bound<'py, PyList> {
        self.elements.bind(py).clone()
    }

    /// Its prescribed rows ([`EchoRow`], `dest` 1, 2, ...).
    #[getter]
    fn prescribed<'py>(&self, py: Python<'py>) -> Bound<'py, PyList> {
        self.prescribed.bind(py).clone()
    }

    /// Its dependent form parameters ([`EchoRow`], `dest` -1, -2, ...).
    #[getter]
    fn dependent<'py>(&self, py: Python<'py>) -> Bound<'py, PyList> {
        self.dependent.bind(py).clone()
    }

    /// For DOF j (1-based, list index j - 1): the prescribed row that is
    /// its input.
    #[getter]
    fn dofs<'py>(&self, py: Python<'py>) -> Bound<'py, PyList> {
        self.dofs.bind(py).clone()
    }

    /// Every co-ordinate ([`EchoCoordinate`]).
    #[getter]
    fn coordinates<'py>(&self, py: Python<'py>) -> Bound<'py, PyList> {
        self.coordinates.bind(py).clone()
    }

    /// The deck's mode line (`KIN ANA`, `DYN ANA`, `DYN SIM`).
    #[getter]
    fn mode(&self) -> String {
        self.mode.clone()
    }

    /// The masses and loads of a DYN deck, in the deck's numbering and
    /// units; None for a KIN deck.
    #[getter]
    fn dynamics<'py>(&self, py: Python<'py>) -> Bound<'py, PyAny> {
        self.dynamics.bind(py).clone()
    }

    /// The deck's UNITS: `length`, `angle`, `mass`, `force`, `time` to a
    /// symbol (`mm`, `deg`) or None where the deck declares none.
    #[getter]
    fn units<'py>(&self, py: Python<'py>) -> Bound<'py, PyDict> {
        self.units.bind(py).clone()
    }

    /// The points the NAMES block names ([`EchoPoint`]).
    #[getter]
    fn points<'py>(&self, py: Python<'py>) -> Bound<'py, PyList> {
        self.points.bind(py).clone()
    }

    /// The names and units of its co-ordinates, rows, inputs and buffers,
    /// as the core decides them (`Labels`); None where not known.
    #[getter]
    fn labels<'py>(&self, py: Python<'py>) -> Bound<'py, PyAny> {
        self.labels.bind(py).clone()
    }

    /// Its number of co-ordinates.
    #[getter]
    fn n_coords(&self, py: Python<'_>) -> usize {
        self.coordinates.bind(py).len()
    }

    /// Its number of moving co-ordinates.
    #[getter]
    fn n_moving(&self, py: Python<'_>) -> PyResult<usize> {
        let mut n = 0;
        for c in self.coordinates.bind(py).iter() {
            if c.cast::<EchoCoordinate>()?.get().moving {
                n += 1;
            }
        }
        Ok(n)
    }
}
