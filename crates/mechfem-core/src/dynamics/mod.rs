//! Masses and loads on a mechanism: the model that inverse dynamics
//! (mode `DYN ANA`, [`crate::run::InverseDynamics`]) and forward simulation
//! (mode `DYN SIM`, [`crate::run::simulate`]) evaluate.
//!
//! The dynamics need no constraint machinery of their own: the motion of
//! every co-ordinate follows from the degrees of freedom through the
//! transfer functions the kinematics already computes (x' and x''), so
//! velocities, accelerations, the mass matrix in the degrees of freedom and
//! the virtual work of every force are sums over the bodies, element by
//! element. The stresses of the prescribed rows come from one balance per
//! position, `(D^c)^T sigma = f_in - f`, solved with D^c's factorisation.
//!
//! * [`Dynamics`] is the mass and load model: rigid [`Body`]s on elements
//!   with a frame, [`PointMass`]es, rotational [`Inertia`]s on angle
//!   co-ordinates, gravity, constant point [`Force`]s, and generalised
//!   [`Load`]s on form parameters (constant, tabulated in time, springs
//!   with dampers, motors).
//! * [`crate::run::InverseDynamics`] evaluates it at a position of a run:
//!   stresses, drive forces, reactions, energies, drive power and the mass
//!   matrix.
//! * [`crate::run::simulate`] integrates the equations of motion of the
//!   degrees of freedom that move under the forces, with the tolerances of
//!   an [`Integration`].
//!
//! Units are the user's, consistent (SI recommended); angles in radians.

mod body;
mod variable;

pub use body::{BodyMotion, Frame, Variation};
pub use variable::MassVar;

use crate::elements::ElementType;
use crate::model::{FormRef, Mechanism};
use thiserror::Error;

/// A rigid body carried by an element (deck `MASS k m u v [J]`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Body {
    /// Element index (0-based); the element must have a frame ([`Frame::of`]).
    pub element: usize,
    /// Mass m.
    pub mass: f64,
    /// Centre of mass in the element's frame: along the u-axis.
    pub u: f64,
    /// Centre of mass in the element's frame: along the v-axis.
    pub v: f64,
    /// Moment of inertia about the centre of mass.
    pub inertia: f64,
}

/// A point mass at the point with co-ordinates `x`, `y` (deck `PMASS i j m`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PointMass {
    /// Co-ordinate index of the point's x.
    pub x: usize,
    /// Co-ordinate index of the point's y.
    pub y: usize,
    /// Mass.
    pub mass: f64,
}

/// A rotational inertia on an angle co-ordinate (deck `INERTIA i J`): a
/// wheel or flywheel without an element of its own.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Inertia {
    /// Co-ordinate index of the angle.
    pub coord: usize,
    /// Moment of inertia.
    pub inertia: f64,
}

/// A constant external force at a point (deck `FORCE i j fx fy`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Force {
    /// Co-ordinate index of the point's x.
    pub x: usize,
    /// Co-ordinate index of the point's y.
    pub y: usize,
    /// The force's components.
    pub f: [f64; 2],
}

/// How a generalised force on a form parameter depends on time and motion.
#[derive(Debug, Clone, PartialEq)]
pub enum LoadKind {
    /// A constant value (deck `LOAD r value`).
    Constant(f64),
    /// Rows `(t, value)` in increasing t, linear between rows and the end
    /// values outside the table (deck `LOADFUNC r file`).
    Table(Vec<[f64; 2]>),
    /// `-k (eps - e0) - c d(eps)/dt` (deck `SPRING r k e0 [c]`).
    Spring {
        /// Stiffness k.
        k: f64,
        /// Free value e0.
        e0: f64,
        /// Viscous damping c.
        c: f64,
    },
    /// `T0 (1 - d(eps)/dt / w0)` (deck `MOTOR r T0 w0`).
    Motor {
        /// Stall torque T0.
        t0: f64,
        /// No-load speed w0 (not zero).
        w0: f64,
    },
}

/// A generalised force on a form parameter: a torque on an angle, a force
/// along a length. It does work `Q d(eps)`.
#[derive(Debug, Clone, PartialEq)]
pub struct Load {
    /// The form parameter it acts on.
    pub form: FormRef,
    /// How it depends on time and motion.
    pub kind: LoadKind,
}

impl Load {
    /// The generalised force at time `t`, form-parameter value `eps` and
    /// rate `eps_dot`.
    pub fn value(&self, t: f64, eps: f64, eps_dot: f64) -> f64 {
        match &self.kind {
            LoadKind::Constant(q) => *q,
            LoadKind::Table(rows) => interpolate(rows, t),
            LoadKind::Spring { k, e0, c } => -k * (eps - e0) - c * eps_dot,
            LoadKind::Motor { t0, w0 } => t0 * (1.0 - eps_dot / w0),
        }
    }

    /// The potential energy it stores (springs only; dampers and the other
    /// loads are not conservative).
    pub fn potential(&self, eps: f64) -> f64 {
        match self.kind {
            LoadKind::Spring { k, e0, .. } => 0.5 * k * (eps - e0) * (eps - e0),
            _ => 0.0,
        }
    }
}

/// Linear interpolation in rows `(t, value)` of increasing t; the end
/// values outside the table.
pub fn interpolate(rows: &[[f64; 2]], t: f64) -> f64 {
    let (Some(first), Some(last)) = (rows.first(), rows.last()) else { return 0.0 };
    if t <= first[0] {
        return first[1];
    }
    if t >= last[0] {
        return last[1];
    }
    // The first row past t; t lies strictly inside the table here.
    let k = rows.partition_point(|r| r[0] <= t);
    let ([t0, v0], [t1, v1]) = (rows[k - 1], rows[k]);
    if t1 > t0 {
        v0 + (v1 - v0) * (t - t0) / (t1 - t0)
    } else {
        v1
    }
}

/// The mass and load model of a mechanism.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Dynamics {
    /// Rigid bodies on elements.
    pub bodies: Vec<Body>,
    /// Point masses.
    pub point_masses: Vec<PointMass>,
    /// Rotational inertias on angle co-ordinates.
    pub inertias: Vec<Inertia>,
    /// Acceleration of gravity (zero: none).
    pub gravity: [f64; 2],
    /// Constant point forces.
    pub forces: Vec<Force>,
    /// Generalised forces on form parameters.
    pub loads: Vec<Load>,
}

/// A mass or load that does not fit the mechanism it is put on.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum DynamicsError {
    /// A body on an element that does not exist.
    #[error("a mass is put on element {element}, but there are only {n_elements}")]
    UnknownElement {
        /// Element index (0-based).
        element: usize,
        /// Number of elements.
        n_elements: usize,
    },
    /// A body on an element type that has no frame.
    #[error("element {element} is a {ty}, which has no frame to carry a mass")]
    NoFrame {
        /// Element index (0-based).
        element: usize,
        /// Its type's name.
        ty: &'static str,
    },
    /// A co-ordinate index out of range.
    #[error("co-ordinate {coordinate} does not exist (there are {n_coords})")]
    UnknownCoordinate {
        /// Co-ordinate index (0-based).
        coordinate: usize,
        /// Number of co-ordinates.
        n_coords: usize,
    },
    /// A load on a form parameter that does not exist.
    #[error("a load acts on {form:?}, which does not exist")]
    UnknownForm {
        /// The form parameter named.
        form: FormRef,
    },
    /// A negative or non-finite mass or inertia, or another number that
    /// must be finite.
    #[error("{what} must be {must}, not {value}")]
    BadNumber {
        /// What the number is (`mass`, `moment of inertia`, ...).
        what: &'static str,
        /// What it must be.
        must: &'static str,
        /// The value given.
        value: f64,
    },
}

impl Dynamics {
    /// Whether there is no mass at all (every result then is that of the
    /// loads alone).
    pub fn is_massless(&self) -> bool {
        self.bodies.iter().all(|b| b.mass == 0.0 && b.inertia == 0.0)
            && self.point_masses.iter().all(|p| p.mass == 0.0)
            && self.inertias.iter().all(|i| i.inertia == 0.0)
    }

    /// Checks every item against the mechanism: indices in range, bodies on
    /// elements with a frame, masses and inertias finite and not negative,
    /// every other number finite, motors with a non-zero no-load speed,
    /// tables in increasing time.
    pub fn check(&self, mech: &Mechanism) -> Result<(), DynamicsError> {
        let n_coords = mech.n_coords();
        let coord = |c: usize| {
            if c < n_coords {
                Ok(())
            } else {
                Err(DynamicsError::UnknownCoordinate { coordinate: c, n_coords })
            }
        };
        let not_negative = |what, value: f64| {
            if value >= 0.0 && value.is_finite() {
                Ok(())
            } else {
                Err(DynamicsError::BadNumber { what, must: "finite and not negative", value })
            }
        };
        let finite = |what, value: f64| {
            if value.is_finite() {
                Ok(())
            } else {
                Err(DynamicsError::BadNumber { what, must: "finite", value })
            }
        };
        for b in &self.bodies {
            let e = mech
                .elements()
                .get(b.element)
                .ok_or(DynamicsError::UnknownElement { element: b.element, n_elements: mech.elements().len() })?;
            if Frame::of(e.ty, e.coords()).is_none() {
                return Err(DynamicsError::NoFrame { element: b.element, ty: e.ty.name() });
            }
            not_negative("mass", b.mass)?;
            not_negative("moment of inertia", b.inertia)?;
            finite("centre of mass u", b.u)?;
            finite("centre of mass v", b.v)?;
        }
        for p in &self.point_masses {
            coord(p.x)?;
            coord(p.y)?;
            not_negative("mass", p.mass)?;
        }
        for i in &self.inertias {
            coord(i.coord)?;
            not_negative("moment of inertia", i.inertia)?;
        }
        finite("gravity", self.gravity[0])?;
        finite("gravity", self.gravity[1])?;
        for f in &self.forces {
            coord(f.x)?;
            coord(f.y)?;
            finite("force", f.f[0])?;
            finite("force", f.f[1])?;
        }
        for l in &self.loads {
            let exists = match l.form {
                FormRef::Prescribed(r) => r < mech.n_prescribed(),
                FormRef::Dependent(d) => d < mech.n_dependent(),
            };
            if !exists {
                return Err(DynamicsError::UnknownForm { form: l.form });
            }
            match &l.kind {
                LoadKind::Constant(q) => finite("load", *q)?,
                LoadKind::Table(rows) => {
                    for r in rows {
                        finite("load table time", r[0])?;
                        finite("load table value", r[1])?;
                    }
                    if let Some(w) = rows.windows(2).find(|w| w[1][0] < w[0][0]) {
                        return Err(DynamicsError::BadNumber {
                            what: "load table time",
                            must: "increasing",
                            value: w[1][0],
                        });
                    }
                }
                LoadKind::Spring { k, e0, c } => {
                    finite("spring stiffness", *k)?;
                    finite("spring free value", *e0)?;
                    finite("damping", *c)?;
                }
                LoadKind::Motor { t0, w0 } => {
                    finite("motor stall torque", *t0)?;
                    if !(w0.is_finite() && *w0 != 0.0) {
                        return Err(DynamicsError::BadNumber {
                            what: "motor no-load speed",
                            must: "finite and not zero",
                            value: *w0,
                        });
                    }
                }
            }
        }
        Ok(())
    }
}

/// Settings of the integrator of a simulation (deck `INTTOL rtol atol`,
/// `INTEGRATOR`, `STOPWHEN`): each step's estimated local error in every
/// free degree of freedom and its speed stays below `atol + rtol * |value|`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Integration {
    /// Relative tolerance.
    pub rtol: f64,
    /// Absolute tolerance.
    pub atol: f64,
    /// The method, or how it is chosen (deck `INTEGRATOR`).
    pub integrator: Integrator,
    /// A condition that ends the simulation early (deck `STOPWHEN`).
    pub stop_when: Option<StopWhen>,
}

/// The integration method of a simulation (deck `INTEGRATOR`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Integrator {
    /// Dormand-Prince 5(4) while the motion is not stiff, Radau IIA 5
    /// while it is: the method switches on detected stiffness, as LSODA
    /// does (`auto`, the default).
    #[default]
    Auto,
    /// The explicit Runge-Kutta method of Dormand and Prince of order 8
    /// with its dense output of order 7 (`dop853`).
    Dop853,
    /// The explicit Runge-Kutta method of Dormand and Prince of order 5(4)
    /// (`explicit` or `dopri5`).
    Dopri5,
    /// The implicit Runge-Kutta method Radau IIA of order 5 (`implicit` or
    /// `radau5`).
    Radau5,
}

impl Integrator {
    /// The method's name as the print file and the run report say it.
    pub fn name(self) -> &'static str {
        match self {
            Integrator::Auto => "auto (Dormand-Prince 5(4), Radau IIA 5 while stiff)",
            Integrator::Dop853 => "DOP853 (explicit Runge-Kutta, order 8)",
            Integrator::Dopri5 => "Dormand-Prince 5(4) (explicit Runge-Kutta)",
            Integrator::Radau5 => "Radau IIA 5 (implicit Runge-Kutta, order 5)",
        }
    }

    /// The method a deck's `INTEGRATOR word` names (case-insensitive), if any.
    pub fn from_word(word: &str) -> Option<Integrator> {
        Some(match word.to_ascii_lowercase().as_str() {
            "auto" => Integrator::Auto,
            "dop853" => Integrator::Dop853,
            "explicit" | "dopri5" => Integrator::Dopri5,
            "implicit" | "radau5" => Integrator::Radau5,
            _ => return None,
        })
    }

    /// The words [`Self::from_word`] knows.
    pub const WORDS: [&'static str; 6] = ["auto", "explicit", "implicit", "dop853", "dopri5", "radau5"];
}

/// Ends a simulation where a recorded quantity crosses a value (deck
/// `STOPWHEN b value`): the crossing is located on the integrator's dense
/// output, and the simulation's last position is there.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StopWhen {
    /// The quantity watched.
    pub quantity: crate::run::Quantity,
    /// The deck's number of its buffer (for the report).
    pub buffer: u32,
    /// The value whose crossing ends the simulation.
    pub value: f64,
}

impl Integration {
    /// The smallest tolerance the integrator takes: below it a step's
    /// rounding dominates.
    pub const MIN_TOLERANCE: f64 = 1e-13;

    /// The tolerances `rtol`, `atol` with the default method and no stop
    /// condition.
    pub fn new(rtol: f64, atol: f64) -> Integration {
        Integration { rtol, atol, integrator: Integrator::Auto, stop_when: None }
    }

    /// Both tolerances at the Newton tolerance `tol` (deck ACCURACY), so
    /// that the integrator is as accurate as the positions it moves
    /// through; at least [`Self::MIN_TOLERANCE`].
    pub fn from_accuracy(tol: f64) -> Integration {
        let t = tol.max(Self::MIN_TOLERANCE);
        Integration::new(t, t)
    }

    /// The Newton tolerance (deck ACCURACY) that keeps the positions'
    /// error out of the integration error: a tenth of the tighter of the
    /// two tolerances (a thousandth for DOP853, whose error estimate of
    /// order 5 in long steps takes the positions' residual for error and
    /// rejects or shortens steps on it), never looser than the default
    /// Newton tolerance and not below 1e-14 (about 50 ulp of a co-ordinate
    /// of order 1, below which Newton meets rounding).
    pub fn newton_tolerance(&self) -> f64 {
        let share = if self.integrator == Integrator::Dop853 { 1e-3 } else { 0.1 };
        (share * self.rtol.min(self.atol)).clamp(Self::NEWTON_FLOOR, crate::solver::Params::default().tol)
    }

    /// The smallest Newton tolerance [`Self::newton_tolerance`] gives.
    pub const NEWTON_FLOOR: f64 = 1e-14;

    /// Why a Newton tolerance `tol` (ACCURACY) is too loose for these
    /// tolerances, if it is: more than ten times the tighter of the two,
    /// the positions' error, up to `tol`, bounds the simulation's error
    /// instead of the integrator's, and steps fail their error test on
    /// position noise.
    pub fn conflict(&self, tol: f64) -> Option<String> {
        let t = self.rtol.min(self.atol);
        (tol > 10.000_001 * t.max(Self::NEWTON_FLOOR)).then(|| {
            format!(
                "ACCURACY {tol:e} (the Newton tolerance of every position) is far looser than INTTOL's {t:e}: the \
                 positions' error, not the integrator's, bounds the simulation's accuracy, and steps may be rejected \
                 on it; leave ACCURACY out (it then follows from INTTOL) or give ACCURACY {:e} or less",
                (0.1 * t).max(Self::NEWTON_FLOOR)
            )
        })
    }
}

impl Default for Integration {
    fn default() -> Self {
        Integration::from_accuracy(crate::solver::Params::default().tol)
    }
}

/// One component of a planar force and moment: what each of the
/// consecutive buffers of a force records (`BUFPIN e i j b`: x into b, y
/// into b+1; `BUFSHAKE b`: x, y and the moment about the origin).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Component {
    /// The force's x.
    X,
    /// The force's y.
    Y,
    /// The moment about the origin (counter-clockwise positive).
    Moment,
}

impl Component {
    /// The component's suffix in a label (`.x`, `.y`, `.M`).
    pub fn suffix(self) -> &'static str {
        match self {
            Component::X => ".x",
            Component::Y => ".y",
            Component::Moment => ".M",
        }
    }
}

/// Whether an element type can carry a [`Body`] (it has a frame).
pub fn has_frame(ty: ElementType) -> bool {
    matches!(ty, ElementType::Bin | ElementType::Hlf | ElementType::Tr1 | ElementType::Tr2)
}

#[cfg(test)]
mod tests;
