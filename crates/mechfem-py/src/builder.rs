//! The typed builder of a model (`ModelBuilder`): Python's `Mechanism`
//! hands the deck reader its items one call each, numbers and names, and
//! gets the same compiled model ([`Model`]) that deck text saying the same
//! things compiles to, without any text written or parsed
//! ([`mechfem_deck::DeckBuilder`]).

use std::path::{Path, PathBuf};

use mechfem_deck::{Compiled, DeckBuilder, Diagnostic, Diagnostics, Mode};
use pyo3::prelude::*;

use crate::design::DesignModel;
use crate::dynamic_design::DynamicDesignModel;
use crate::errors;
use crate::model::Model;
use crate::text::compile_text;

/// A model built item by item, in the order of a deck's blocks:
/// `ModelBuilder(path, mode)`, `units`, then `element`, `form`, `nrdof`;
/// `coordinate`, `para`; `name`; `dynamics` and its items; `movement` and its
/// items; `storage` and its items; then `build(base_dir)`. Each refusal is
/// a `DeckError` naming the item by the name it was given.
#[pyclass(module = "mechfem._core")]
pub struct ModelBuilder {
    builder: DeckBuilder,
    path: PathBuf,
    /// Whether the design models it makes take and give their numbers in
    /// the model's units (its UNITS) rather than the core's.
    #[pyo3(get, set)]
    design_in_model_units: bool,
}

/// The `DeckError` of one refused item.
fn refused(py: Python<'_>, path: &std::path::Path, d: Box<Diagnostic>) -> PyErr {
    errors::deck_error(py, path, &Diagnostics(vec![*d]))
}

#[pymethods]
impl ModelBuilder {
    /// An empty model of `mode` (`KIN ANA`, `DYN ANA` or `DYN SIM`), named `path` in messages.
    #[new]
    fn new(py: Python<'_>, path: PathBuf, mode: &str) -> PyResult<ModelBuilder> {
        let m = match mode {
            "KIN ANA" => Mode::KinAna,
            "DYN ANA" => Mode::DynAna,
            "DYN SIM" => Mode::DynSim,
            _ => Mode::KinOpt,
        };
        let builder = DeckBuilder::new(path.clone(), m).map_err(|d| refused(py, &path, d))?;
        Ok(ModelBuilder { builder, path, design_in_model_units: false })
    }

    /// The model's units by symbol (`mm`, `deg`, ...), each kind optional;
    /// before every other item.
    #[pyo3(signature = (length=None, angle=None, mass=None, force=None, time=None))]
    #[allow(clippy::too_many_arguments)]
    fn units(
        &mut self,
        py: Python<'_>,
        length: Option<&str>,
        angle: Option<&str>,
        mass: Option<&str>,
        force: Option<&str>,
        time: Option<&str>,
    ) -> PyResult<()> {
        self.builder.units(length, angle, mass, force, time).map_err(|d| refused(py, &self.path, d))
    }

    /// A name of the NAMES block (after the geometry): `kind` POINT, COORD,
    /// ELEM, ROW, DEP or BUF, its numbers and the name (a BUF's label).
    fn name(&mut self, py: Python<'_>, kind: &str, numbers: Vec<i64>, name: &str) -> PyResult<()> {
        self.builder.name(kind, &numbers, name).map_err(|d| refused(py, &self.path, d))
    }

    /// The next element: its type and co-ordinate numbers, and its name.
    #[pyo3(signature = (ty, coords, name=None))]
    fn element(&mut self, py: Python<'_>, ty: &str, coords: Vec<i64>, name: Option<&str>) -> PyResult<()> {
        self.builder.element(ty, &coords, name).map_err(|d| refused(py, &self.path, d))
    }

    /// A term `factor` x `form` of element `element` into row `dest`, of the row `name`.
    #[pyo3(signature = (form, element, dest, factor, name=None))]
    fn form(
        &mut self,
        py: Python<'_>,
        form: &str,
        element: i64,
        dest: i64,
        factor: f64,
        name: Option<&str>,
    ) -> PyResult<()> {
        self.builder.form(form, element, dest, factor, name).map_err(|d| refused(py, &self.path, d))
    }

    /// The number of inputs.
    fn nrdof(&mut self, py: Python<'_>, n: i64) -> PyResult<()> {
        self.builder.nrdof(n).map_err(|d| refused(py, &self.path, d))
    }

    /// Co-ordinate `number` at `value`, moving or fixed, and its name.
    #[pyo3(signature = (number, value, moving, name=None))]
    fn coordinate(
        &mut self,
        py: Python<'_>,
        number: i64,
        value: f64,
        moving: bool,
        name: Option<&str>,
    ) -> PyResult<()> {
        self.builder.coordinate(number, value, moving, name).map_err(|d| refused(py, &self.path, d))
    }

    /// The prescribed value of row `row`, and the row's name.
    #[pyo3(signature = (row, value, name=None))]
    fn para(&mut self, py: Python<'_>, row: i64, value: f64, name: Option<&str>) -> PyResult<()> {
        self.builder.para(row, value, name).map_err(|d| refused(py, &self.path, d))
    }

    /// Begins the masses and loads.
    fn dynamics(&mut self, py: Python<'_>) -> PyResult<()> {
        self.builder.dynamics().map_err(|d| refused(py, &self.path, d))
    }

    /// A body's mass on element `element`.
    #[allow(clippy::too_many_arguments)]
    fn mass(
        &mut self,
        py: Python<'_>,
        element: i64,
        mass: f64,
        u: f64,
        v: f64,
        inertia: f64,
        what: &str,
    ) -> PyResult<()> {
        self.builder.mass(element, mass, u, v, inertia, what).map_err(|d| refused(py, &self.path, d))
    }

    /// A point mass at the point of co-ordinates `x`, `y`.
    fn point_mass(&mut self, py: Python<'_>, x: i64, y: i64, mass: f64, what: &str) -> PyResult<()> {
        self.builder.point_mass(x, y, mass, what).map_err(|d| refused(py, &self.path, d))
    }

    /// A moment of inertia on co-ordinate `coord`.
    fn inertia(&mut self, py: Python<'_>, coord: i64, inertia: f64, what: &str) -> PyResult<()> {
        self.builder.inertia(coord, inertia, what).map_err(|d| refused(py, &self.path, d))
    }

    /// The acceleration of gravity.
    fn gravity(&mut self, py: Python<'_>, gx: f64, gy: f64) -> PyResult<()> {
        self.builder.gravity(gx, gy).map_err(|d| refused(py, &self.path, d))
    }

    /// A constant force at the point of co-ordinates `x`, `y`.
    fn force(&mut self, py: Python<'_>, x: i64, y: i64, fx: f64, fy: f64, what: &str) -> PyResult<()> {
        self.builder.force(x, y, fx, fy, what).map_err(|d| refused(py, &self.path, d))
    }

    /// A constant generalised force on row `row`.
    fn load(&mut self, py: Python<'_>, row: i64, value: f64, what: &str) -> PyResult<()> {
        self.builder.load(row, value, what).map_err(|d| refused(py, &self.path, d))
    }

    /// A generalised force on row `row` from the table file `file`.
    fn load_table(&mut self, py: Python<'_>, row: i64, file: &str, what: &str) -> PyResult<()> {
        self.builder.load_table(row, file, what).map_err(|d| refused(py, &self.path, d))
    }

    /// A spring with damper on row `row`.
    #[allow(clippy::too_many_arguments)]
    fn spring(&mut self, py: Python<'_>, row: i64, k: f64, e0: f64, c: f64, what: &str) -> PyResult<()> {
        self.builder.spring(row, k, e0, c, what).map_err(|d| refused(py, &self.path, d))
    }

    /// A motor on row `row`.
    fn motor(&mut self, py: Python<'_>, row: i64, t0: f64, w0: f64, what: &str) -> PyResult<()> {
        self.builder.motor(row, t0, w0, what).map_err(|d| refused(py, &self.path, d))
    }

    /// Begins the motion: `steps` steps of time `dt`.
    fn movement(&mut self, py: Python<'_>, steps: i64, dt: f64) -> PyResult<()> {
        self.builder.movement(steps, dt).map_err(|d| refused(py, &self.path, d))
    }

    /// The motion of input `dof`: `kind` by, to, free or dynamic.
    fn motion(&mut self, py: Python<'_>, dof: i64, kind: &str, value: f64, what: &str) -> PyResult<()> {
        self.builder.motion(dof, kind, value, what).map_err(|d| refused(py, &self.path, d))
    }

    /// The motion of input `dof` from the table file `file`.
    fn motion_table(&mut self, py: Python<'_>, dof: i64, file: &str, what: &str) -> PyResult<()> {
        self.builder.motion_table(dof, file, what).map_err(|d| refused(py, &self.path, d))
    }

    /// Newton's accuracy and iteration limit and the integrator's (rtol, atol), each if given.
    #[pyo3(signature = (accuracy=None, max_iter=None, inttol=None))]
    fn tolerances(
        &mut self,
        py: Python<'_>,
        accuracy: Option<f64>,
        max_iter: Option<i64>,
        inttol: Option<(f64, f64)>,
    ) -> PyResult<()> {
        self.builder.tolerances(accuracy, max_iter, inttol).map_err(|d| refused(py, &self.path, d))
    }

    /// The simulation's integrator (INTEGRATOR) and stop condition (buffer, value) (STOPWHEN), each if given.
    #[pyo3(signature = (integrator=None, stop_when=None))]
    fn simulation(&mut self, py: Python<'_>, integrator: Option<&str>, stop_when: Option<(i64, f64)>) -> PyResult<()> {
        self.builder.simulation(integrator, stop_when).map_err(|d| refused(py, &self.path, d))
    }

    /// Begins the storage.
    fn storage(&mut self, py: Python<'_>) -> PyResult<()> {
        self.builder.storage().map_err(|d| refused(py, &self.path, d))
    }

    /// Buffer `number`: `keyword` of the deck numbers `args`.
    fn buffer(&mut self, py: Python<'_>, keyword: &str, args: Vec<i64>, number: i64) -> PyResult<()> {
        self.builder.buffer(keyword, &args, number).map_err(|d| refused(py, &self.path, d))
    }

    /// The buffers the print file tabulates (all when empty).
    fn printbuf(&mut self, py: Python<'_>, buffers: Vec<i64>) -> PyResult<()> {
        self.builder.printbuf(&buffers).map_err(|d| refused(py, &self.path, d))
    }

    /// The buffers of the data set.
    fn savedata(&mut self, py: Python<'_>, buffers: Vec<i64>) -> PyResult<()> {
        self.builder.savedata(&buffers).map_err(|d| refused(py, &self.path, d))
    }

    /// The animation file's name.
    fn animate(&mut self, py: Python<'_>, name: &str) -> PyResult<()> {
        self.builder.animate(name).map_err(|d| refused(py, &self.path, d))
    }

    /// A picture of `plots` (keyword, first, second).
    fn picture(&mut self, py: Python<'_>, title: &str, plots: Vec<(String, i64, i64)>) -> PyResult<()> {
        self.builder.picture(title, &plots).map_err(|d| refused(py, &self.path, d))
    }

    /// The number of the last item added: a `DeckError` of this builder or
    /// of the built model names the item it is about by this number (its
    /// `line`).
    #[getter]
    fn item(&self) -> usize {
        self.builder.item()
    }

    /// The compiled model (table files read from `base_dir`); the builder
    /// can be built again.
    fn build(&self, py: Python<'_>, base_dir: PathBuf) -> PyResult<Model> {
        let compiled =
            py.detach(|| self.builder.build(&base_dir)).map_err(|d| errors::deck_error(py, &self.path, &d))?;
        Model::kept(py, compiled, self.path.clone())
    }

    /// The compiled model (table files read from `base_dir`) kept for an
    /// optimiser: a `DesignModel` of the design `variables`, `buffers` and
    /// `extrema`, as `DesignModel(text, ...)` takes them for deck text.
    fn design(
        &self,
        py: Python<'_>,
        base_dir: PathBuf,
        variables: Vec<(u8, usize)>,
        buffers: Vec<u32>,
        extrema: Vec<(u32, u32)>,
    ) -> PyResult<DesignModel> {
        let compiled =
            py.detach(|| self.builder.build(&base_dir)).map_err(|d| errors::deck_error(py, &self.path, &d))?;
        DesignModel::of_compiled(compiled, &variables, &buffers, &extrema, self.design_in_model_units)
    }

    /// The compiled DYN ANA model kept for an optimiser of its dynamics: a
    /// `DynamicDesignModel` of the design `variables` (mass variables
    /// included) and `buffers`, as `DynamicDesignModel(text, ...)` takes
    /// them for deck text; `extrema` must be empty.
    fn dynamic_design(
        &self,
        py: Python<'_>,
        base_dir: PathBuf,
        variables: Vec<(u8, usize)>,
        buffers: Vec<u32>,
        extrema: Vec<(u32, u32)>,
    ) -> PyResult<DynamicDesignModel> {
        if !extrema.is_empty() {
            return Err(pyo3::exceptions::PyValueError::new_err(
                "a dynamic design evaluation locates no extrema: pass an empty list",
            ));
        }
        let compiled =
            py.detach(|| self.builder.build(&base_dir)).map_err(|d| errors::deck_error(py, &self.path, &d))?;
        DynamicDesignModel::of_compiled(compiled, &variables, &buffers, self.design_in_model_units)
    }
}

/// What the variants of a study are made of: deck text, or a model built
/// item by item (a copy of its builder's items), compiled where the
/// variants run, without the GIL.
pub enum Source {
    Text(String),
    Built(Box<DeckBuilder>),
}

impl Source {
    /// Deck text (a `str`) or a `ModelBuilder`'s items.
    pub fn extract(ob: &Bound<'_, PyAny>) -> PyResult<Source> {
        if let Ok(text) = ob.extract::<String>() {
            return Ok(Source::Text(text));
        }
        let b = ob.extract::<PyRef<'_, ModelBuilder>>()?;
        Ok(Source::Built(Box::new(b.builder.clone())))
    }

    /// The compiled model: the text read as deck `path`, or the items
    /// built; table files read from `base_dir`.
    pub fn compile(&self, path: &Path, base_dir: &Path) -> Result<Compiled, Diagnostics> {
        match self {
            Source::Text(text) => compile_text(text, path, base_dir),
            Source::Built(b) => b.build(base_dir),
        }
    }
}
