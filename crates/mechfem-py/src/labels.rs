//! The names and units of a compiled model's things, as the core decides
//! them ([`mechfem_core::Names`], [`mechfem_core::ModelDims`],
//! [`mechfem_core::Units`]), for Python's labels (`mechfem.results.labels`): every
//! data-set header, axis, legend, title and sentence asks these getters.
//!
//! Numbers are the deck's: co-ordinates and inputs 1-based, a row by its
//! signed number (`r > 0` prescribed row r, `r < 0` dependent form
//! parameter -r). Each getter gives `(name, stated, shown, dim)`: the name,
//! the unit the model states (`mm/deg`; "" without UNITS), the unit an axis
//! shows (the stated one; without UNITS radians and seconds, nothing with a
//! length) and the exponents of length, angle, mass, force and time.

use mechfem_core::units::{Angle, Force, Length, Mass, Time};
use mechfem_core::{Dim, FormRef, Mechanism, ModelDims, Names, NoSuch, Quantity, Units};
use mechfem_deck::Compiled;
use pyo3::exceptions::PyIndexError;
use pyo3::prelude::*;
use pyo3::types::PyTuple;

/// What a getter gives: name, stated unit, shown unit, exponents.
type Named = (String, String, String, [i8; 5]);

/// What the input getter gives: name in a derivative, name as a quantity,
/// its deck row, stated unit, shown unit, exponents.
type Input = (String, String, usize, String, String, [i8; 5]);

/// The names and units of one compiled model.
///
/// A pickled `Labels` (a run's result sent to another process) travels as
/// the table of all its answers, and answers the same; only
/// `renamed` of it keeps the buffers' labels it was made with.
#[pyclass(module = "mechfem._core", name = "Labels", frozen)]
pub struct Labels {
    units: Units,
    source: Source,
}

enum Source {
    Model(Box<Model>),
    Table(Box<Table>),
}

struct Model {
    mechanism: Mechanism,
    names: Names,
    dims: ModelDims,
    buffers: Vec<(u32, Quantity)>,
    /// BUFTOL's band buffers: number, source buffer, "worst" or "rss"
    /// ([`Compiled::label`]).
    bands: Vec<(u32, u32, &'static str)>,
}

/// Every answer of a model's labels, by number.
#[derive(Clone, PartialEq)]
struct Table {
    coordinates: Vec<Named>,
    prescribed: Vec<Named>,
    dependent: Vec<Named>,
    inputs: Vec<Input>,
    buffers: Vec<(u32, Named)>,
    det: Named,
}

fn missing(kind: &'static str, n: impl TryInto<i64>) -> PyErr {
    PyIndexError::new_err(NoSuch { kind, number: n.try_into().unwrap_or(i64::MAX) }.to_string())
}

/// Entry `k` (1-based) of `list`.
fn nth<T: Clone>(list: &[T], k: usize, what: &'static str) -> PyResult<T> {
    k.checked_sub(1).and_then(|k| list.get(k)).cloned().ok_or_else(|| missing(what, k))
}

impl Labels {
    /// The labels of compiled deck `c`.
    pub fn of(c: &Compiled) -> Labels {
        let model = Model {
            mechanism: c.mechanism.clone(),
            names: c.names.clone(),
            dims: c.dims.clone(),
            buffers: c.buffers.iter().map(|b| (b.number, b.quantity)).collect(),
            bands: c
                .buffers
                .iter()
                .filter_map(|b| {
                    c.band_of(b.number).map(|(d, rss)| (b.number, d.source, if rss { "rss" } else { "worst" }))
                })
                .collect(),
        };
        Labels { units: c.units, source: Source::Model(Box::new(model)) }
    }

    fn named(&self, name: String, dim: Dim) -> Named {
        (name, dim.symbol(&self.units), dim.shown(&self.units), dim.0)
    }

    fn form(m: &Model, r: i64) -> PyResult<FormRef> {
        let k = usize::try_from(r.unsigned_abs()).unwrap_or(usize::MAX).wrapping_sub(1);
        match r {
            r if r > 0 && k < m.mechanism.n_prescribed() => Ok(FormRef::Prescribed(k)),
            r if r < 0 && k < m.mechanism.n_dependent() => Ok(FormRef::Dependent(k)),
            _ => Err(missing("row", r)),
        }
    }

    /// Every answer, for a pickle.
    fn table(&self) -> PyResult<Table> {
        let m = match &self.source {
            Source::Table(t) => return Ok((**t).clone()),
            Source::Model(m) => m,
        };
        let mech = &m.mechanism;
        let rows = |n: usize, sign: i64| (1..=n).map(|k| self.row(sign * k as i64)).collect::<PyResult<Vec<_>>>();
        Ok(Table {
            coordinates: (1..=mech.n_coords()).map(|i| self.coordinate(i)).collect::<PyResult<_>>()?,
            prescribed: rows(mech.n_prescribed(), 1)?,
            dependent: rows(mech.n_dependent(), -1)?,
            inputs: (1..=mech.n_dof()).map(|j| self.input(j)).collect::<PyResult<_>>()?,
            buffers: m.buffers.iter().map(|(n, _)| Ok((*n, self.buffer(*n)?))).collect::<PyResult<_>>()?,
            det: self.det(),
        })
    }

    /// The symbols of the units, for a pickle: "" where not declared, and
    /// whether any is.
    fn unit_symbols(&self) -> (bool, [String; 5]) {
        (self.units.declared, self.units.fields().map(|(_, s)| s.unwrap_or("").to_string()))
    }
}

#[pymethods]
impl Labels {
    /// Co-ordinate `i`: `C.x` (`x9` unnamed) and its unit.
    fn coordinate(&self, i: usize) -> PyResult<Named> {
        match &self.source {
            Source::Table(t) => nth(&t.coordinates, i, "co-ordinate"),
            Source::Model(m) => {
                let i = i
                    .checked_sub(1)
                    .filter(|&i| i < m.mechanism.n_coords())
                    .ok_or_else(|| missing("co-ordinate", i))?;
                Ok(self.named(m.names.coordinate(i), m.dims.coord(i)))
            }
        }
    }

    /// Row `r` (`r < 0`: dependent form parameter -r): `psi` (its formula
    /// `ANGB(8)` unnamed) and its unit.
    fn row(&self, r: i64) -> PyResult<Named> {
        match &self.source {
            Source::Table(t) if r < 0 => nth(&t.dependent, usize::try_from(-r).unwrap_or(0), "row"),
            Source::Table(t) => nth(&t.prescribed, usize::try_from(r).unwrap_or(0), "row"),
            Source::Model(m) => {
                let f = Labels::form(m, r)?;
                Ok(self.named(m.names.row(&m.mechanism, f), m.dims.form(f)))
            }
        }
    }

    /// Input `j` as a derivative says it (`phi`, `input1` unnamed), as a
    /// quantity (`phi`, its row's formula `ANGB(1)` unnamed), the deck row
    /// it is (1-based) and its unit.
    fn input(&self, j: usize) -> PyResult<Input> {
        match &self.source {
            Source::Table(t) => nth(&t.inputs, j, "input"),
            Source::Model(m) => {
                let mech = &m.mechanism;
                let j = j.checked_sub(1).filter(|&j| j < mech.n_dof()).ok_or_else(|| missing("input", j))?;
                let (value, stated, shown, dim) = self.named(m.names.input_value(mech, j), m.dims.input(mech, j));
                Ok((m.names.input(mech, j), value, mech.input_row(j) + 1, stated, shown, dim))
            }
        }
    }

    /// Buffer `number`: its label (the NAMES block's, else from the names
    /// of what it records, else the deck's numbers) and its unit.
    fn buffer(&self, number: u32) -> PyResult<Named> {
        match &self.source {
            Source::Table(t) => t
                .buffers
                .iter()
                .find(|(n, _)| *n == number)
                .map(|(_, b)| b.clone())
                .ok_or_else(|| missing("buffer", number)),
            Source::Model(m) => {
                let (_, q) = m.buffers.iter().find(|(n, _)| *n == number).ok_or_else(|| missing("buffer", number))?;
                let band = m.bands.iter().find(|(n, ..)| *n == number);
                let label = match band {
                    Some((_, source, kind)) => format!("{} {kind}", m.names.label(&m.mechanism, *source, *q)),
                    None => m.names.label(&m.mechanism, number, *q),
                };
                Ok(self.named(label, m.dims.quantity(&m.mechanism, *q)))
            }
        }
    }

    /// det(D^c) and its unit: the product of the rows' units over the
    /// moving co-ordinates' (each term of the determinant takes one entry
    /// d row_i / d x_j from every row and every column).
    fn det(&self) -> Named {
        match &self.source {
            Source::Table(t) => t.det.clone(),
            Source::Model(m) => self.named("det(D^c)".to_string(), m.dims.det(&m.mechanism)),
        }
    }

    /// The unit of a kind given by its exponents of length, angle, mass,
    /// force and time: `(stated, shown)`.
    fn unit(&self, dim: [i8; 5]) -> (String, String) {
        (Dim(dim, false).symbol(&self.units), Dim(dim, false).shown(&self.units))
    }

    /// What a number of the core of a kind given by its exponents is
    /// multiplied by to be given in the model's units (1 without UNITS).
    fn scale(&self, dim: [i8; 5]) -> f64 {
        Dim(dim, false).out_scale(&self.units)
    }

    /// These labels with a named model's own names for its co-ordinates,
    /// prescribed rows and dependent form parameters (a Python
    /// `Mechanism`'s, which may hold dots no deck name can); a list shorter
    /// than the model's leaves the rest as they are.
    fn renamed(&self, coordinates: Vec<String>, prescribed: Vec<String>, dependent: Vec<String>) -> PyResult<Labels> {
        let source = match &self.source {
            Source::Model(m) => {
                let mut names = m.names.clone();
                let put = |to: &mut Vec<Option<String>>, from: Vec<String>| {
                    to.iter_mut().zip(from).for_each(|(slot, name)| *slot = Some(name));
                };
                put(&mut names.coordinates, coordinates);
                put(&mut names.prescribed, prescribed);
                put(&mut names.dependent, dependent);
                let (mechanism, dims, buffers, bands) =
                    (m.mechanism.clone(), m.dims.clone(), m.buffers.clone(), m.bands.clone());
                let model = Model { mechanism, names, dims, buffers, bands };
                Source::Model(Box::new(model))
            }
            Source::Table(t) => {
                let mut t = (**t).clone();
                let put = |to: &mut Vec<Named>, from: Vec<String>| {
                    to.iter_mut().zip(from).for_each(|(slot, name)| slot.0 = name);
                };
                put(&mut t.coordinates, coordinates);
                for input in &mut t.inputs {
                    if let Some(name) = prescribed.get(input.2 - 1) {
                        input.0.clone_from(name);
                        input.1.clone_from(name);
                    }
                }
                put(&mut t.prescribed, prescribed);
                put(&mut t.dependent, dependent);
                Source::Table(Box::new(t))
            }
        };
        Ok(Labels { units: self.units, source })
    }

    /// Equal labels give the same answers in the same units (a pickled
    /// copy equals its original), so that two model echoes compare by what
    /// they say.
    fn __eq__(&self, other: &Bound<'_, PyAny>) -> PyResult<bool> {
        let Ok(other) = other.cast::<Labels>() else { return Ok(false) };
        let other = other.get();
        Ok(self.unit_symbols() == other.unit_symbols() && self.table()? == other.table()?)
    }

    /// A pickle: the table of every answer and the units' symbols.
    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyTuple>)> {
        let py = slf.py();
        let me = slf.get();
        let t = me.table()?;
        let args = (me.unit_symbols(), t.coordinates, t.prescribed, t.dependent, t.inputs, (t.buffers, t.det));
        Ok((slf.get_type().getattr("_tabulated")?, PyTuple::new(py, [args.into_pyobject(py)?])?))
    }

    /// Labels from the table of a pickle.
    #[staticmethod]
    #[allow(clippy::type_complexity)]
    fn _tabulated(
        table: ((bool, [String; 5]), Vec<Named>, Vec<Named>, Vec<Named>, Vec<Input>, (Vec<(u32, Named)>, Named)),
    ) -> Labels {
        let ((declared, s), coordinates, prescribed, dependent, inputs, (buffers, det)) = table;
        let units = Units {
            declared,
            length: Length::from_symbol(&s[0]),
            angle: Angle::from_symbol(&s[1]),
            mass: Mass::from_symbol(&s[2]),
            force: Force::from_symbol(&s[3]),
            time: Time::from_symbol(&s[4]),
        };
        let table = Table { coordinates, prescribed, dependent, inputs, buffers, det };
        Labels { units, source: Source::Table(Box::new(table)) }
    }
}
