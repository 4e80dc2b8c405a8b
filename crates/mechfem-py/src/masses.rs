//! The masses and loads of a DYN deck as Python reads them
//! (`EchoModel.dynamics`, a deck's description): typed objects owned by
//! Rust, read through getters, in the deck's numbering (1-based,
//! destinations signed) and the numbers as the deck gives them, compared by
//! value and picklable (`__getnewargs__`).

use mechfem_core::dynamics::{Dynamics, LoadKind};
use pyo3::prelude::*;

use crate::convert::dest;

/// A MASS line: the body on element `element`.
#[pyclass(module = "mechfem._core", frozen, eq, get_all, from_py_object)]
#[derive(Debug, Clone, PartialEq)]
pub struct EchoBody {
    /// The element's number.
    pub element: usize,
    /// Its mass.
    pub mass: f64,
    /// Its centre of mass along the element, in the element's frame.
    pub u: f64,
    /// Its centre of mass across the element.
    pub v: f64,
    /// Its moment of inertia about its centre of mass.
    pub inertia: f64,
}

#[pymethods]
impl EchoBody {
    /// The body with these values.
    #[new]
    fn new(element: usize, mass: f64, u: f64, v: f64, inertia: f64) -> EchoBody {
        EchoBody { element, mass, u, v, inertia }
    }

    /// The arguments of [`EchoBody::new`] that make it again.
    fn __getnewargs__(&self) -> (usize, f64, f64, f64, f64) {
        (self.element, self.mass, self.u, self.v, self.inertia)
    }
}

/// A PMASS line: a point mass at the point of co-ordinates `x` and `y`.
#[pyclass(module = "mechfem._core", frozen, eq, get_all, from_py_object)]
#[derive(Debug, Clone, PartialEq)]
pub struct EchoPointMass {
    /// The co-ordinate of its x.
    pub x: usize,
    /// The co-ordinate of its y.
    pub y: usize,
    /// Its mass.
    pub mass: f64,
}

#[pymethods]
impl EchoPointMass {
    /// The point mass with these values.
    #[new]
    fn new(x: usize, y: usize, mass: f64) -> EchoPointMass {
        EchoPointMass { x, y, mass }
    }

    /// The arguments of [`EchoPointMass::new`] that make it again.
    fn __getnewargs__(&self) -> (usize, usize, f64) {
        (self.x, self.y, self.mass)
    }
}

/// An INERTIA line: an inertia on co-ordinate `coord`.
#[pyclass(module = "mechfem._core", frozen, eq, get_all, from_py_object)]
#[derive(Debug, Clone, PartialEq)]
pub struct EchoInertia {
    /// The co-ordinate's number.
    pub coord: usize,
    /// The inertia (a mass on a length, a moment of inertia on an angle).
    pub inertia: f64,
}

#[pymethods]
impl EchoInertia {
    /// The inertia with these values.
    #[new]
    fn new(coord: usize, inertia: f64) -> EchoInertia {
        EchoInertia { coord, inertia }
    }

    /// The arguments of [`EchoInertia::new`] that make it again.
    fn __getnewargs__(&self) -> (usize, f64) {
        (self.coord, self.inertia)
    }
}

/// A FORCE line: a constant force at the point of co-ordinates `x` and `y`.
#[pyclass(module = "mechfem._core", frozen, eq, get_all, from_py_object)]
#[derive(Debug, Clone, PartialEq)]
pub struct EchoForce {
    /// The co-ordinate of its point's x.
    pub x: usize,
    /// The co-ordinate of its point's y.
    pub y: usize,
    /// Its x component.
    pub fx: f64,
    /// Its y component.
    pub fy: f64,
}

#[pymethods]
impl EchoForce {
    /// The force with these values.
    #[new]
    fn new(x: usize, y: usize, fx: f64, fy: f64) -> EchoForce {
        EchoForce { x, y, fx, fy }
    }

    /// The arguments of [`EchoForce::new`] that make it again.
    fn __getnewargs__(&self) -> (usize, usize, f64, f64) {
        (self.x, self.y, self.fx, self.fy)
    }
}

/// A load on a row (`dest`: r > 0 prescribed, -k dependent): LOAD (its
/// `value`), LOADFUNC (its table's `rows` of time and value, and the `file`
/// the deck names where known), SPRING (`k`, `e0`, `c`) or MOTOR (`t0`,
/// `w0`); the numbers of the other kinds are None.
#[pyclass(module = "mechfem._core", frozen, eq, get_all, from_py_object)]
#[derive(Debug, Clone, PartialEq)]
pub struct EchoLoad {
    /// The row it acts on.
    pub dest: i64,
    /// `LOAD`, `LOADFUNC`, `SPRING` or `MOTOR`.
    pub kind: String,
    /// LOAD: the constant generalised force.
    pub value: Option<f64>,
    /// LOADFUNC: its table, `(time, value)` a row.
    pub rows: Vec<(f64, f64)>,
    /// LOADFUNC: the file as the deck names it (a deck's description;
    /// None in a run's echo).
    pub file: Option<String>,
    /// SPRING: the stiffness.
    pub k: Option<f64>,
    /// SPRING: the free value.
    pub e0: Option<f64>,
    /// SPRING: the damping.
    pub c: Option<f64>,
    /// MOTOR: the stall torque (or force).
    pub t0: Option<f64>,
    /// MOTOR: the no-load speed.
    pub w0: Option<f64>,
}

#[pymethods]
impl EchoLoad {
    /// The load with these values.
    #[new]
    #[pyo3(signature = (dest, kind, value=None, rows=Vec::new(), file=None, k=None, e0=None, c=None, t0=None, w0=None))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        dest: i64,
        kind: String,
        value: Option<f64>,
        rows: Vec<(f64, f64)>,
        file: Option<String>,
        k: Option<f64>,
        e0: Option<f64>,
        c: Option<f64>,
        t0: Option<f64>,
        w0: Option<f64>,
    ) -> EchoLoad {
        EchoLoad { dest, kind, value, rows, file, k, e0, c, t0, w0 }
    }

    /// The arguments of [`EchoLoad::new`] that make it again.
    #[allow(clippy::type_complexity)]
    fn __getnewargs__(
        &self,
    ) -> (
        i64,
        String,
        Option<f64>,
        Vec<(f64, f64)>,
        Option<String>,
        Option<f64>,
        Option<f64>,
        Option<f64>,
        Option<f64>,
        Option<f64>,
    ) {
        let l = self.clone();
        (l.dest, l.kind, l.value, l.rows, l.file, l.k, l.e0, l.c, l.t0, l.w0)
    }
}

/// The DYNAMICS block as compiled: gravity, bodies, point masses, inertias,
/// forces and loads.
#[pyclass(module = "mechfem._core", frozen, eq, get_all, from_py_object)]
#[derive(Debug, Clone, PartialEq)]
pub struct EchoDynamics {
    /// `(gx, gy)`, zero without GRAVITY.
    pub gravity: (f64, f64),
    /// The MASS lines.
    pub bodies: Vec<EchoBody>,
    /// The PMASS lines.
    pub point_masses: Vec<EchoPointMass>,
    /// The INERTIA lines.
    pub inertias: Vec<EchoInertia>,
    /// The FORCE lines.
    pub forces: Vec<EchoForce>,
    /// The loads, springs and motors.
    pub loads: Vec<EchoLoad>,
}

#[pymethods]
impl EchoDynamics {
    /// The masses and loads with these parts.
    #[new]
    fn new(
        gravity: (f64, f64),
        bodies: Vec<EchoBody>,
        point_masses: Vec<EchoPointMass>,
        inertias: Vec<EchoInertia>,
        forces: Vec<EchoForce>,
        loads: Vec<EchoLoad>,
    ) -> EchoDynamics {
        EchoDynamics { gravity, bodies, point_masses, inertias, forces, loads }
    }

    /// The arguments of [`EchoDynamics::new`] that make it again.
    #[allow(clippy::type_complexity)]
    fn __getnewargs__(
        &self,
    ) -> ((f64, f64), Vec<EchoBody>, Vec<EchoPointMass>, Vec<EchoInertia>, Vec<EchoForce>, Vec<EchoLoad>) {
        let d = self.clone();
        (d.gravity, d.bodies, d.point_masses, d.inertias, d.forces, d.loads)
    }
}

impl EchoDynamics {
    /// The mass and load model `m` in the deck's numbering; `files` names
    /// the LOADFUNC file of each load, where known.
    pub fn of(m: &Dynamics, files: &[Option<String>]) -> EchoDynamics {
        let n = |i: usize| i + 1;
        let loads = m
            .loads
            .iter()
            .enumerate()
            .map(|(k, l)| {
                let mut load = EchoLoad {
                    dest: dest(l.form),
                    kind: String::new(),
                    value: None,
                    rows: Vec::new(),
                    file: None,
                    k: None,
                    e0: None,
                    c: None,
                    t0: None,
                    w0: None,
                };
                match &l.kind {
                    LoadKind::Constant(q) => (load.kind, load.value) = ("LOAD".to_owned(), Some(*q)),
                    LoadKind::Table(rows) => {
                        load.kind = "LOADFUNC".to_owned();
                        load.rows = rows.iter().map(|r| (r[0], r[1])).collect();
                        load.file = files.get(k).cloned().flatten();
                    }
                    LoadKind::Spring { k, e0, c } => {
                        load.kind = "SPRING".to_owned();
                        (load.k, load.e0, load.c) = (Some(*k), Some(*e0), Some(*c));
                    }
                    LoadKind::Motor { t0, w0 } => {
                        load.kind = "MOTOR".to_owned();
                        (load.t0, load.w0) = (Some(*t0), Some(*w0));
                    }
                }
                load
            })
            .collect();
        EchoDynamics {
            gravity: (m.gravity[0], m.gravity[1]),
            bodies: m
                .bodies
                .iter()
                .map(|b| EchoBody { element: n(b.element), mass: b.mass, u: b.u, v: b.v, inertia: b.inertia })
                .collect(),
            point_masses: m.point_masses.iter().map(|p| EchoPointMass { x: n(p.x), y: n(p.y), mass: p.mass }).collect(),
            inertias: m.inertias.iter().map(|i| EchoInertia { coord: n(i.coord), inertia: i.inertia }).collect(),
            forces: m.forces.iter().map(|f| EchoForce { x: n(f.x), y: n(f.y), fx: f.f[0], fy: f.f[1] }).collect(),
            loads,
        }
    }
}
