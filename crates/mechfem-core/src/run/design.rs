//! One design evaluated for an optimiser: the motion run with chosen
//! quantities and their design sensitivities at every position, and the
//! quantities taken where a reference has an extremum (its dead positions),
//! located to full precision with their sensitivities too.
//!
//! An extremum of a position quantity r (a co-ordinate or a dependent form
//! parameter) along a one-DOF motion lies where its first-order transfer
//! function r' changes sign; Newton on r' with r'' as its slope finds it,
//! kept inside the bracket of the two positions by bisection. A quantity b
//! there depends on the design p both directly and through the input q* of
//! the extremum: d b(q*, p)/dp = b_p + b_q dq*/dp with dq*/dp = -r'_p / r''.
//! b_q is b's sensitivity to the input row's prescribed value, at fixed
//! everything else, which [`Sensitivity`] computes like any other.
//!
//! A driven motion that changes the orientation of a group of co-ordinates
//! (see [`Orientation`]) has left the branch of its position 1: the run
//! stops there and says so ([`DesignRun::left_branch`]). [`Design`]
//! evaluates an optimiser's designs on the branch of its start design.

use super::branch::block_coords;
pub use super::branch::{Anchor, BranchChange, Design, DesignFailure, Orientation};
use super::kinematic::run;
use super::observe::{Observer, PositionView, RunReport};
use super::record::Quantity;
use crate::error::{SolveError, Unsupported};
use crate::model::{FormRef, Mechanism, State};
use crate::motion::{InputMotion, Motion};
use crate::solver::{correct, DesignVar, Kinematics, Params, Sensitivity, TransferOrder};

/// A quantity wanted where a reference quantity has its extrema.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ExtremumSpec {
    /// What is wanted there.
    pub quantity: Quantity,
    /// The reference: a co-ordinate ([`Quantity::X0`]) or a dependent form
    /// parameter ([`Quantity::E0`]).
    pub reference: Quantity,
}

/// A quantity at one extremum of its reference.
#[derive(Debug, Clone, PartialEq)]
pub struct Extremum {
    /// Which [`ExtremumSpec`].
    pub spec: usize,
    /// The position (0-based) after which it lies.
    pub after: usize,
    /// The input's value there.
    pub input: f64,
    /// The reference's value there.
    pub reference: f64,
    /// The quantity's value there.
    pub value: f64,
    /// Its derivative with respect to every design variable.
    pub gradient: Vec<f64>,
}

/// Everything one evaluation computed.
#[derive(Debug, Clone)]
pub struct DesignRun {
    /// The run (how far it got, limit positions, why it stopped).
    pub report: RunReport,
    /// Positions computed.
    pub positions: usize,
    /// Row-major, positions x quantities.
    pub values: Vec<f64>,
    /// Row-major, positions x quantities x variables.
    pub gradient: Vec<f64>,
    /// Row-major, positions x co-ordinates.
    pub coords: Vec<f64>,
    /// Every extremum of every spec, in order of spec and position.
    pub extrema: Vec<Extremum>,
    /// Where a driven motion left the branch of its position 1 (the run
    /// stopped at the last position on it).
    pub left_branch: Option<BranchChange>,
    /// dx/dp of every co-ordinate at position 1: variable v's column at
    /// `slope_one[v * N..]`, N the number of co-ordinates.
    pub slope_one: Vec<f64>,
}

/// The first- and second-order transfer functions of a reference quantity
/// with respect to input 0, or None when it cannot have an extremum that
/// they locate.
pub fn slopes(reference: Quantity) -> Option<(Quantity, Quantity)> {
    match reference {
        Quantity::X0(coord) => Some((Quantity::Kx1 { coord, j: 0 }, Quantity::Kx2 { coord, j: 0, m: 0 })),
        Quantity::E0(f @ FormRef::Dependent(_)) => Some((Quantity::Ke1(f, 0), Quantity::Ke2(f, 0, 0))),
        _ => None,
    }
}

/// Records the quantities, their sensitivities, the co-ordinates and the
/// references' slopes at every position.
struct Recording<'a> {
    sens: Sensitivity,
    motion: &'a Motion,
    quantities: &'a [Quantity],
    slope_of: Vec<Quantity>,
    values: Vec<f64>,
    gradient: Vec<f64>,
    coords: Vec<f64>,
    /// Every element's angle memory at every position, so that a point
    /// between positions is computed on the same branch of each angle.
    branches: Vec<f64>,
    inputs: Vec<f64>,
    vel: Vec<f64>,
    acc: Vec<f64>,
    slopes: Vec<f64>,
    failed: Option<SolveError>,
    /// Position 1's orientation, when the motion is to keep it (driven).
    orientation: Option<Orientation>,
    dets: Vec<f64>,
    left_branch: Option<BranchChange>,
    slope_one: Vec<f64>,
}

impl Observer for Recording<'_> {
    fn position(&mut self, v: &PositionView<'_>) {
        let mech = v.mech;
        let nv = self.sens.vars().len();
        let computed = self.sens.compute(mech, v.kin, v.state, TransferOrder::Second);
        if let Err(e) = &computed {
            self.failed.get_or_insert(e.clone());
        }
        scale_starts(&mut self.sens, mech, self.motion, v.index, false);
        if v.index == 0 && computed.is_ok() {
            for var in 0..nv {
                self.slope_one.extend((0..mech.n_coords()).map(|i| self.sens.dx(i, var)));
            }
        }
        self.keeps_branch(v);
        for q in self.quantities {
            self.values.push(q.value(v));
            for var in 0..nv {
                self.gradient.push(if computed.is_ok() { q.sensitivity(v, &self.sens, var) } else { f64::NAN });
            }
        }
        self.coords.extend_from_slice(&v.state.x);
        self.branches.extend_from_slice(&v.state.branch);
        self.inputs.push(v.input(0));
        self.vel.push(v.input_vel.first().copied().unwrap_or(0.0));
        self.acc.push(v.input_acc.first().copied().unwrap_or(0.0));
        self.slopes.extend(self.slope_of.iter().map(|q| q.value(v)));
    }

    fn transfer_order(&self) -> Option<TransferOrder> {
        Some(TransferOrder::Second)
    }

    fn stop_requested(&self) -> bool {
        self.left_branch.is_some()
    }
}

impl Recording<'_> {
    /// Takes position 1's orientation, or checks a later position's against
    /// it. Free motion passes the limit positions of its input, where the
    /// orientation changes, so it is not checked.
    fn keeps_branch(&mut self, v: &PositionView<'_>) {
        let free = self.motion.inputs.iter().any(|m| matches!(m, InputMotion::Free { .. }));
        if free || self.left_branch.is_some() || v.kin.order().is_none() {
            return;
        }
        match &self.orientation {
            None => self.orientation = Some(Orientation::of(v.kin, &mut self.dets)),
            Some(one) => {
                v.kin.lu.block_dets(&mut self.dets);
                if let Some(b) = one.reversed_in(&self.dets) {
                    let coords = block_coords(v.mech, v.kin, b);
                    self.left_branch = Some(BranchChange { after: v.index - 1, coords });
                }
            }
        }
    }
}

/// Scales the sensitivities to an input's start value by how far it moves
/// the input at position `index` of `motion`; `extremum`: at an extremum,
/// which is a property of the mechanism wherever the motion samples it, so
/// the start moves nothing there but the input's velocity.
pub(super) fn scale_starts(sens: &mut Sensitivity, mech: &Mechanism, motion: &Motion, index: usize, extremum: bool) {
    // At an extremum the last variable is the input itself, unscaled.
    let n = sens.vars().len() - usize::from(extremum);
    for k in 0..n {
        if let DesignVar::Row(r) = sens.vars()[k] {
            if let Some(j) = mech.input_of(r) {
                let (factor, rate) = motion.start_rates(j, index);
                sens.scale_input(k, j, if extremum { 0.0 } else { factor }, rate);
            }
        }
    }
}

/// Runs `motion` from `state` (the design's values already in it) and
/// records `quantities` and their derivatives with respect to `vars`, and
/// every extremum of each spec's reference. Fails when position 1 cannot be
/// computed; a motion that stops early returns the positions it reached.
pub fn evaluate(
    mech: &Mechanism,
    state: &mut State,
    motion: &Motion,
    params: &Params,
    vars: &[DesignVar],
    quantities: &[Quantity],
    extrema: &[ExtremumSpec],
) -> Result<DesignRun, SolveError> {
    let sens = Sensitivity::new(mech, vars).map_err(|_| SolveError::Unsupported(Unsupported::UnknownDesignVariable))?;
    let mut slope_of = Vec::with_capacity(extrema.len());
    for e in extrema {
        match slopes(e.reference) {
            Some((s, _)) if mech.n_dof() == 1 => slope_of.push(s),
            _ => return Err(SolveError::Unsupported(Unsupported::ExtremumNeedsOneDof)),
        }
    }
    let n = motion.steps + 1;
    let (nq, nv, nc) = (quantities.len(), vars.len(), mech.n_coords());
    let mut rec = Recording {
        sens,
        motion,
        quantities,
        slope_of,
        values: Vec::with_capacity(n * nq),
        gradient: Vec::with_capacity(n * nq * nv),
        coords: Vec::with_capacity(n * nc),
        branches: Vec::with_capacity(n * mech.elements().len()),
        inputs: Vec::with_capacity(n),
        vel: Vec::with_capacity(n),
        acc: Vec::with_capacity(n),
        slopes: Vec::with_capacity(n * extrema.len()),
        failed: None,
        orientation: None,
        dets: Vec::new(),
        left_branch: None,
        slope_one: Vec::with_capacity(nv * nc),
    };
    let base = state.clone();
    let mut report = run(mech, state, Some(motion), params, &mut rec)?;
    if let Some(e) = rec.failed {
        return Err(e);
    }
    if rec.left_branch.is_some() {
        // Stopped by the recording itself, not interrupted.
        report.stop = None;
    }
    let positions = report.positions;
    let mut found = Vec::new();
    let mut kin = Kinematics::new(mech);
    let mut all_vars = vars.to_vec();
    all_vars.push(DesignVar::Row(mech.input_row(0)));
    let mut sens = Sensitivity::new(mech, &all_vars).expect("checked above");
    let ne = extrema.len();
    for (k, spec) in extrema.iter().enumerate() {
        let (slope, curvature) = slopes(spec.reference).expect("checked above");
        for p in 0..positions.saturating_sub(1) {
            let (f0, f1) = (rec.slopes[p * ne + k], rec.slopes[(p + 1) * ne + k]);
            // A sign change between p and p + 1, or a zero at p + 1 (found
            // from the left only, so that it counts once).
            if !(f0 * f1 < 0.0 || (f1 == 0.0 && f0 != 0.0)) {
                continue;
            }
            let mut at = base.clone();
            at.x.copy_from_slice(&rec.coords[p * nc..(p + 1) * nc]);
            let n_el = at.branch.len();
            at.branch.copy_from_slice(&rec.branches[p * n_el..(p + 1) * n_el]);
            at.target[mech.input_row(0)] = rec.inputs[p];
            let bracket = (rec.inputs[p], rec.inputs[p + 1], f0, f1);
            let q = locate(mech, &mut at, &mut kin, params, slope, curvature, bracket)?;
            // Input rates between the positions, linear in the input.
            let w = if bracket.1 != bracket.0 { (q - bracket.0) / (bracket.1 - bracket.0) } else { 0.0 };
            let vel = [rec.vel[p] + w * (rec.vel[p + 1] - rec.vel[p])];
            let acc = [rec.acc[p] + w * (rec.acc[p + 1] - rec.acc[p])];
            sens.compute(mech, &kin, &at, TransferOrder::Second)?;
            scale_starts(&mut sens, mech, motion, p, true);
            let view = PositionView {
                index: p,
                time: f64::NAN,
                mech,
                state: &at,
                kin: &kin,
                input_vel: &vel,
                input_acc: &acc,
            };
            let b_q = spec.quantity.sensitivity(&view, &sens, nv);
            let r2 = curvature.value(&view);
            let gradient = (0..nv)
                .map(|v| spec.quantity.sensitivity(&view, &sens, v) - b_q * slope.sensitivity(&view, &sens, v) / r2)
                .collect();
            found.push(Extremum {
                spec: k,
                after: p,
                input: q,
                reference: spec.reference.value(&view),
                value: spec.quantity.value(&view),
                gradient,
            });
        }
    }
    Ok(DesignRun {
        report,
        positions,
        values: rec.values,
        gradient: rec.gradient,
        coords: rec.coords,
        extrema: found,
        left_branch: rec.left_branch,
        slope_one: rec.slope_one,
    })
}

/// Newton on the reference's slope between two positions (inputs q0, q1,
/// slopes f0, f1 of opposite signs), bisecting whenever a step would leave
/// the bracket. Leaves `state` and `kin` at the extremum with the transfer
/// functions computed there; returns the input's value.
fn locate(
    mech: &Mechanism,
    state: &mut State,
    kin: &mut Kinematics,
    params: &Params,
    slope: Quantity,
    curvature: Quantity,
    (q0, q1, f0, f1): (f64, f64, f64, f64),
) -> Result<f64, SolveError> {
    let row = mech.input_row(0);
    let (mut lo, mut hi) = if f0 < 0.0 { (q0, q1) } else { (q1, q0) };
    // The zero of the straight line through both slopes: a good start.
    let mut q = if f1 == 0.0 { q1 } else { q0 + (q1 - q0) * f0 / (f0 - f1) };
    let zeros = [0.0];
    for _ in 0..60 {
        // Predict the co-ordinates from the last converged point.
        if let Some(TransferOrder::First | TransferOrder::Second) = kin.order() {
            let dq = q - state.target[row];
            for (c, &i) in mech.moving_coords().iter().enumerate() {
                state.x[i] += kin.x1(0)[c] * dq;
            }
        }
        state.target[row] = q;
        correct(mech, state, kin, params)?;
        kin.transfer(mech, state, TransferOrder::Second)?;
        let view = PositionView { index: 0, time: f64::NAN, mech, state, kin, input_vel: &zeros, input_acc: &zeros };
        let (f, df) = (slope.value(&view), curvature.value(&view));
        if f == 0.0 {
            return Ok(q);
        }
        if f < 0.0 {
            lo = q;
        } else {
            hi = q;
        }
        let newton = q - f / df;
        let inside = (newton - lo) * (newton - hi) < 0.0;
        let next = if inside && df.is_finite() && df != 0.0 { newton } else { 0.5 * (lo + hi) };
        let done = (next - q).abs() <= 4.0 * f64::EPSILON * q.abs().max(1.0);
        if done {
            return Ok(q);
        }
        if !(next - q).is_finite() {
            break;
        }
        q = next;
    }
    // The last point computed, which `state` and `kin` hold.
    Ok(state.target[row])
}
