//! What can be recorded at every position: the quantities of the deck's
//! buffer table, named with 0-based indices.

use super::inverse::InverseDynamics;
use super::observe::{Observer, PositionView};
use super::transmission::{transmission_angle, transmission_sensitivity};
use crate::dynamics::Component;
use crate::error::SolveError;
use crate::model::{FormRef, Mechanism};
use crate::solver::{DesignVar, Sensitivity, TransferOrder};

/// One recordable quantity (one buffer of the deck).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Quantity {
    /// Value of input j (BUFINP).
    Input(usize),
    /// Time (BUFTIME).
    Time,
    /// Co-ordinate i (BUFX0).
    X0(usize),
    /// d x_i / d input_j (BUFKX1).
    Kx1 {
        /// Co-ordinate.
        coord: usize,
        /// Input.
        j: usize,
    },
    /// d2 x_i / d input_j d input_m (BUFKX2).
    Kx2 {
        /// Co-ordinate.
        coord: usize,
        /// First input.
        j: usize,
        /// Second input.
        m: usize,
    },
    /// Velocity of co-ordinate i (BUFVX).
    Vx(usize),
    /// Acceleration of co-ordinate i (BUFAX).
    Ax(usize),
    /// Form parameter value (BUFE0).
    E0(FormRef),
    /// d eps / d input_j (BUFKE1).
    Ke1(FormRef, usize),
    /// d2 eps / d input_j d input_m (BUFKE2).
    Ke2(FormRef, usize, usize),
    /// Velocity of a form parameter (BUFVE).
    Ve(FormRef),
    /// Acceleration of a form parameter (BUFAE).
    Ae(FormRef),
    /// det(D^c) (BUFDET).
    Det,
    /// Generalised stress sigma_r of prescribed row r (BUFSIG).
    Sigma(usize),
    /// Drive force or torque of DOF j, the stress of its input row (BUFDRV).
    Drive(usize),
    /// Reaction on fixed co-ordinate i (BUFREA).
    Reaction(usize),
    /// Kinetic energy T (BUFEKIN).
    Ekin,
    /// Potential energy V of gravity and springs (BUFEPOT).
    Epot,
    /// Power delivered by the drives (BUFPOW).
    Power,
    /// Power of the loads that are neither gravity nor a spring's elastic
    /// force (point forces, loads, tables, motors, dampers): with the
    /// drives' power it makes d(T + V)/dt. No deck buffer records it.
    LoadPower,
    /// Entry (j, m) of the mass matrix in the degrees of freedom (BUFMRED).
    Mred(usize, usize),
    /// Transmission angle between the first sides of two elements with a
    /// frame, in [0, pi] (BUFTRA e1 e2).
    Transmission(usize, usize),
    /// One component of the force the body of an element exerts on the pin
    /// at co-ordinates `x`, `y` (BUFPIN e i j).
    Pin {
        /// The element (0-based).
        element: usize,
        /// The pin's x co-ordinate.
        x: usize,
        /// The pin's y co-ordinate.
        y: usize,
        /// Which component (x or y).
        component: Component,
    },
    /// One component of the shaking force and moment on the frame, inertia
    /// only (BUFSHAKE).
    Shaking(Component),
}

impl Quantity {
    /// Whether the quantity is one of the dynamics (it needs a mass and load
    /// model: [`Recorder::with_dynamics`]).
    pub fn is_dynamic(&self) -> bool {
        matches!(
            self,
            Quantity::Sigma(_)
                | Quantity::Drive(_)
                | Quantity::Reaction(_)
                | Quantity::Ekin
                | Quantity::Epot
                | Quantity::Power
                | Quantity::LoadPower
                | Quantity::Mred(..)
                | Quantity::Pin { .. }
                | Quantity::Shaking(_)
        )
    }

    /// Whether the quantity is made from transfer functions (and so does
    /// not exist at a limit position): everything that needs them but
    /// det(D^c) itself.
    pub fn needs_transfer(&self) -> bool {
        self.transfer_order().is_some() && *self != Quantity::Det
    }

    /// The transfer functions the quantity is made from: `None` for
    /// positions, values and the (identity) transfer functions of
    /// prescribed rows; `Some(First)` for first-order transfer functions,
    /// velocities and det(D^c); `Some(Second)` for second-order transfer
    /// functions and accelerations.
    pub fn transfer_order(&self) -> Option<TransferOrder> {
        match self {
            Quantity::Input(_)
            | Quantity::Time
            | Quantity::X0(_)
            | Quantity::E0(_)
            | Quantity::Ke1(FormRef::Prescribed(_), _)
            | Quantity::Ke2(FormRef::Prescribed(_), _, _)
            | Quantity::Ve(FormRef::Prescribed(_))
            | Quantity::Ae(FormRef::Prescribed(_))
            | Quantity::Transmission(..)
            | Quantity::Epot => None,
            Quantity::Kx1 { .. }
            | Quantity::Vx(_)
            | Quantity::Ke1(FormRef::Dependent(_), _)
            | Quantity::Ve(FormRef::Dependent(_))
            | Quantity::Det => Some(TransferOrder::First),
            Quantity::Kx2 { .. }
            | Quantity::Ax(_)
            | Quantity::Ke2(FormRef::Dependent(_), _, _)
            | Quantity::Ae(FormRef::Dependent(_))
            | Quantity::Sigma(_)
            | Quantity::Drive(_)
            | Quantity::Reaction(_)
            | Quantity::Ekin
            | Quantity::Power
            | Quantity::LoadPower
            | Quantity::Mred(..)
            | Quantity::Pin { .. }
            | Quantity::Shaking(_) => Some(TransferOrder::Second),
        }
    }

    /// The quantity's value at a position: NaN for a quantity that
    /// [needs transfer functions](Self::needs_transfer) at a position where
    /// D^c is singular (a limit position, reported as such by the run), and
    /// for a [dynamic](Self::is_dynamic) one (see [`Self::dynamic_value`]).
    pub fn value(&self, v: &PositionView<'_>) -> f64 {
        let (mech, kin) = (v.mech, v.kin);
        let (qd, qdd) = (v.input_vel, v.input_acc);
        // A prescribed row's derivatives are those of an identity: 1 for its
        // own input, 0 otherwise; constant rows do not move at all.
        // At a limit position D^c has no inverse: transfer functions, and
        // the velocities and accelerations made from them, do not exist.
        if kin.order().is_none() && self.needs_transfer() {
            return f64::NAN;
        }
        match *self {
            Quantity::Input(j) => v.input(j),
            Quantity::Time => v.time,
            Quantity::X0(i) => v.state.x[i],
            Quantity::Kx1 { coord, j } => kin.dx(mech, coord, j),
            Quantity::Kx2 { coord, j, m } => kin.d2x(mech, coord, j, m),
            Quantity::Vx(i) => kin.velocity(mech, i, qd),
            Quantity::Ax(i) => kin.acceleration(mech, i, qd, qdd),
            Quantity::E0(FormRef::Prescribed(r)) => kin.row_value(r),
            Quantity::E0(FormRef::Dependent(d)) => kin.dep(d),
            Quantity::Ke1(FormRef::Prescribed(r), j) => f64::from(u8::from(mech.input_of(r) == Some(j))),
            Quantity::Ke1(FormRef::Dependent(d), j) => kin.dep1(d, j),
            Quantity::Ke2(FormRef::Prescribed(_), _, _) => 0.0,
            Quantity::Ke2(FormRef::Dependent(d), j, m) => kin.dep2(d, j, m),
            Quantity::Ve(FormRef::Prescribed(r)) => mech.input_of(r).map_or(0.0, |j| qd[j]),
            Quantity::Ve(FormRef::Dependent(d)) => kin.dep_velocity(d, qd),
            Quantity::Ae(FormRef::Prescribed(r)) => mech.input_of(r).map_or(0.0, |j| qdd[j]),
            Quantity::Ae(FormRef::Dependent(d)) => kin.dep_acceleration(d, qd, qdd),
            Quantity::Det => kin.det(),
            Quantity::Transmission(a, b) => transmission_angle(mech, &v.state.x, a, b),
            _ => f64::NAN,
        }
    }

    /// The quantity's derivative with respect to design variable `var` of
    /// `s` (computed at this position, [`Sensitivity::compute`]): 0 for the
    /// time, which the motion fixes; NaN for det(D^c) and the dynamics,
    /// which have none, and for a quantity made from transfer functions
    /// that were not computed.
    pub fn sensitivity(&self, v: &PositionView<'_>, s: &Sensitivity, var: usize) -> f64 {
        let mech = v.mech;
        let (qd, qdd) = (v.input_vel, v.input_acc);
        let nd = mech.n_dof();
        let order = s.order();
        if order.is_none()
            || (self.transfer_order() == Some(TransferOrder::Second) && order != Some(TransferOrder::Second))
        {
            return f64::NAN;
        }
        // The variable's own row: an input's start moves the input by the
        // factor of `Sensitivity::scale_input`, which `dx` of the input's
        // co-ordinate direction already carries; a constant row is itself.
        let own_row = |r: usize| match s.vars()[var] {
            DesignVar::Row(rv) if rv == r => 1.0,
            _ => 0.0,
        };
        let input_scale = |j: usize| {
            let r = mech.input_row(j);
            // The input's value moves by the same factor as its co-ordinates.
            if own_row(r) == 0.0 {
                0.0
            } else {
                s.input_factor(var)
            }
        };
        let dvel = |j: usize| s.input_rate(j, var);
        match *self {
            // The times are the motion's (TSTEPE, a MOV_FUNC table's), whatever the design.
            Quantity::Time => 0.0,
            Quantity::Input(j) => input_scale(j),
            Quantity::X0(i) => s.dx(i, var),
            Quantity::Kx1 { coord, j } => s.dx1(coord, j, var),
            Quantity::Kx2 { coord, j, m } => s.dx2(coord, j, m, var),
            Quantity::Vx(i) => (0..nd).map(|j| s.dx1(i, j, var) * qd[j] + v.kin.dx(mech, i, j) * dvel(j)).sum(),
            Quantity::Ax(i) => {
                let mut a = 0.0;
                for j in 0..nd {
                    a += s.dx1(i, j, var) * qdd[j];
                    for m in 0..nd {
                        a += s.dx2(i, j, m, var) * qd[j] * qd[m] + 2.0 * v.kin.d2x(mech, i, j, m) * dvel(j) * qd[m];
                    }
                }
                a
            }
            Quantity::E0(FormRef::Prescribed(r)) => match mech.input_of(r) {
                Some(j) => input_scale(j),
                None => own_row(r),
            },
            Quantity::E0(FormRef::Dependent(d)) => s.dep(d, var),
            Quantity::Ke1(FormRef::Prescribed(_), _) | Quantity::Ke2(FormRef::Prescribed(_), _, _) => 0.0,
            Quantity::Ke1(FormRef::Dependent(d), j) => s.dep1(d, j, var),
            Quantity::Ke2(FormRef::Dependent(d), j, m) => s.dep2(d, j, m, var),
            Quantity::Ve(FormRef::Prescribed(r)) => mech.input_of(r).map_or(0.0, dvel),
            Quantity::Ae(FormRef::Prescribed(_)) => 0.0,
            Quantity::Ve(FormRef::Dependent(d)) => {
                (0..nd).map(|j| s.dep1(d, j, var) * qd[j] + v.kin.dep1(d, j) * dvel(j)).sum()
            }
            Quantity::Ae(FormRef::Dependent(d)) => {
                let mut a = 0.0;
                for j in 0..nd {
                    a += s.dep1(d, j, var) * qdd[j];
                    for m in 0..nd {
                        a += s.dep2(d, j, m, var) * qd[j] * qd[m] + 2.0 * v.kin.dep2(d, j, m) * dvel(j) * qd[m];
                    }
                }
                a
            }
            Quantity::Transmission(a, b) => transmission_sensitivity(mech, &v.state.x, s, var, a, b),
            _ => f64::NAN,
        }
    }

    /// The value of a [dynamic](Self::is_dynamic) quantity from inverse
    /// dynamics evaluated at the position (NaN for any other quantity).
    pub fn dynamic_value(&self, mech: &Mechanism, d: &InverseDynamics) -> f64 {
        match *self {
            Quantity::Sigma(r) => d.sigma(r),
            Quantity::Drive(j) => d.drive(mech, j),
            Quantity::Reaction(i) => d.reaction(mech, i),
            Quantity::Ekin => d.kinetic_energy(),
            Quantity::Epot => d.potential_energy(),
            Quantity::Power => d.drive_power(),
            Quantity::LoadPower => d.load_power(),
            Quantity::Mred(j, m) => d.mass_matrix_entry(mech, j, m),
            Quantity::Pin { element, x, y, component } => d.pin_force(element, x, y, component),
            Quantity::Shaking(c) => d.shaking(c),
            _ => f64::NAN,
        }
    }
}

/// Appends the values of `quantities` at the position `view` to `out`; the
/// dynamic ones from `dynamics`, evaluated here when any is asked for (NaN
/// without it).
pub fn record(
    quantities: &[Quantity],
    view: &PositionView<'_>,
    dynamics: Option<&mut InverseDynamics>,
    out: &mut Vec<f64>,
) {
    let dynamics = match dynamics {
        Some(d) if quantities.iter().any(Quantity::is_dynamic) => {
            d.evaluate(view);
            Some(&*d)
        }
        _ => None,
    };
    record_evaluated(quantities, view, dynamics, out);
}

/// Appends the values of `quantities` at the position `view` to `out`, as
/// [`record`] does, with inverse dynamics already evaluated at this
/// position ([`InverseDynamics::evaluate`]; the dynamic quantities are NaN
/// without it).
pub fn record_evaluated(
    quantities: &[Quantity],
    view: &PositionView<'_>,
    dynamics: Option<&InverseDynamics>,
    out: &mut Vec<f64>,
) {
    out.extend(quantities.iter().map(|&q| recorded_value(q, view, dynamics)));
}

/// The value [`record_evaluated`] records of quantity `q` at the position
/// `view`.
#[inline]
pub fn recorded_value(q: Quantity, view: &PositionView<'_>, dynamics: Option<&InverseDynamics>) -> f64 {
    let (mech, kin) = (view.mech, view.kin);
    let transfer = kin.order().is_some();
    // The quantities most recorded are read here without the generic path
    // of `Quantity::value` (which gives the same values): a short run
    // records a deck's few buffers at every position.
    match (q, dynamics) {
        (Quantity::X0(i), _) => view.state.x[i],
        (Quantity::Time, _) => view.time,
        (Quantity::Vx(i), _) if transfer => kin.velocity(mech, i, view.input_vel),
        (Quantity::Ax(i), _) if transfer => kin.acceleration(mech, i, view.input_vel, view.input_acc),
        (q, Some(d)) if q.is_dynamic() => q.dynamic_value(mech, d),
        (q, _) => q.value(view),
    }
}

/// An [`Observer`] that keeps chosen quantities, and optionally every
/// co-ordinate, for every position.
#[derive(Debug, Clone, Default)]
pub struct Recorder {
    quantities: Vec<Quantity>,
    keep_coords: bool,
    /// Row-major: one row of `quantities.len()` values per position.
    data: Vec<f64>,
    /// Row-major: one row of N co-ordinates per position (when kept).
    coords: Vec<f64>,
    positions: usize,
    /// Inverse dynamics, evaluated at every position when a dynamic
    /// quantity is recorded.
    dynamics: Option<Box<InverseDynamics>>,
    /// Whether inverse dynamics has been evaluated (and checked) at the
    /// position about to be recorded.
    checked: bool,
}

impl Recorder {
    /// Records `quantities`, and all co-ordinates when `keep_coords`.
    pub fn new(quantities: Vec<Quantity>, keep_coords: bool) -> Recorder {
        Recorder { quantities, keep_coords, ..Recorder::default() }
    }
    /// Records the dynamic quantities from the mass and load model of
    /// `dynamics` (without it they read NaN).
    pub fn with_dynamics(mut self, dynamics: InverseDynamics) -> Recorder {
        self.dynamics = Some(Box::new(dynamics));
        self
    }
    /// Makes room for `positions` more positions of a model of `n_coords`
    /// co-ordinates, so that recording them allocates nothing more (and
    /// never holds twice the memory while a growing table is moved).
    pub fn reserve(&mut self, positions: usize, n_coords: usize) {
        self.data.reserve_exact(positions.saturating_mul(self.quantities.len()));
        if self.keep_coords {
            self.coords.reserve_exact(positions.saturating_mul(n_coords));
        }
    }
    /// Numbers recorded per position for a model of `n_coords` co-ordinates.
    pub fn values_per_position(&self, n_coords: usize) -> usize {
        self.quantities.len() + if self.keep_coords { n_coords } else { 0 }
    }
    /// The recorded quantities, in column order.
    pub fn quantities(&self) -> &[Quantity] {
        &self.quantities
    }
    /// Number of positions recorded.
    pub fn positions(&self) -> usize {
        self.positions
    }
    /// Values, row-major (positions x quantities).
    pub fn data(&self) -> &[f64] {
        &self.data
    }
    /// One column: quantity `q` over all positions.
    pub fn column(&self, q: usize) -> Vec<f64> {
        let w = self.quantities.len();
        (0..self.positions).map(|k| self.data[k * w + q]).collect()
    }
    /// Co-ordinates, row-major (positions x N); empty unless kept.
    pub fn coords(&self) -> &[f64] {
        &self.coords
    }
    /// The values and the co-ordinates ([`Self::data`], [`Self::coords`]),
    /// handed over without a copy.
    pub fn into_parts(self) -> (Vec<f64>, Vec<f64>) {
        (self.data, self.coords)
    }
}

impl Observer for Recorder {
    /// As far as the recorded quantities need: a recorder of co-ordinates
    /// only makes a run compute positions only.
    fn transfer_order(&self) -> Option<TransferOrder> {
        self.quantities.iter().map(Quantity::transfer_order).max().flatten()
    }

    /// Inverse dynamics evaluated here, when a dynamic quantity is
    /// recorded: a position where it is not finite is refused.
    fn check(&mut self, view: &PositionView<'_>) -> Result<(), SolveError> {
        match self.dynamics.as_deref_mut() {
            Some(d) if self.quantities.iter().any(Quantity::is_dynamic) => {
                self.checked = true;
                d.evaluate_checked(view)
            }
            _ => Ok(()),
        }
    }

    fn moved_by_forces(&mut self, free: &[usize]) {
        if let Some(d) = self.dynamics.as_deref_mut() {
            d.set_moved_by_forces(free);
        }
    }

    fn position(&mut self, view: &PositionView<'_>) {
        if std::mem::take(&mut self.checked) {
            record_evaluated(&self.quantities, view, self.dynamics.as_deref(), &mut self.data);
        } else {
            record(&self.quantities, view, self.dynamics.as_deref_mut(), &mut self.data);
        }
        if self.keep_coords {
            self.coords.extend_from_slice(&view.state.x);
        }
        self.positions += 1;
    }
}
