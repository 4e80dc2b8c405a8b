//! A run recorded as the motion computes it ([`TransferRecord`]): at every
//! position the inputs with their velocities and accelerations, the time,
//! det(D^c), the row values and the transfer functions of the moving
//! co-ordinates and the dependent rows, and with a mass and load model the
//! values of inverse dynamics. The full [`Layout`]'s table is made from it
//! when it is asked for ([`Layout::table`]), column by column over all
//! positions, with the formulas of [`Layout::record`]: every value to the
//! last bit the one that records a position at a time.
//!
//! A run that records everything so costs little more than one that records
//! nothing: a position is a few slices copied one after the other into one
//! row-major buffer, about half the numbers of the layout's width (the
//! velocities and accelerations, the fixed co-ordinates' zeros, the
//! prescribed rows' identities are not kept but made), and nothing is
//! written that is overwritten later.
//!
//! ```
//! use mechfem_core::run::{Layout, TransferRecord};
//! # let deck = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/fourbar/fourbar.mec");
//! # let model = mechfem_deck::load(deck).unwrap();
//! let layout = Layout::full(&model.mechanism, false);
//! let record = TransferRecord::new(&layout, &model.mechanism, 0);
//! // No position yet: every column is empty.
//! assert!(layout.table(&record).is_empty());
//! ```

use super::inverse::InverseDynamics;
use super::layout::{acceleration, velocity, Layout};
use super::observe::PositionView;
use crate::dynamics::Component;
use crate::model::{Mechanism, FIXED};
use std::ops::Range;

/// Where each part of a position starts in a [`TransferRecord`]'s row.
#[derive(Debug, Clone, Default)]
struct Offsets {
    /// Input values (D).
    inputs: usize,
    /// Input velocities (D).
    qd: usize,
    /// Input accelerations (D).
    qdd: usize,
    time: usize,
    det: usize,
    /// Prescribed row values, then the dependent ones (R).
    rows: usize,
    /// d x / d input_j over the moving co-ordinates, input after input (D x moving).
    x1: usize,
    /// d2 x / d input_j d input_m over the moving co-ordinates, row-major in (j, m) (D x D x moving).
    x2: usize,
    /// d eps_d / d input_j (dependent rows x D).
    dep1: usize,
    /// d2 eps_d / d input_j d input_m (dependent rows x D x D).
    dep2: usize,
    /// The blocks of inverse dynamics, as the layout orders them (`sigma` to `loadpow`).
    dynamic: usize,
    /// Numbers a position.
    stride: usize,
}

/// What a run computed at every position, row-major, from which the full
/// [`Layout`]'s table is made ([`Layout::table`]); see the module's docs.
#[derive(Debug, Clone, Default)]
pub struct TransferRecord {
    n_dof: usize,
    n_moving: usize,
    at: Offsets,
    /// One row of `at.stride` numbers per position.
    data: Vec<f64>,
    /// Whether the transfer functions exist at each position (not at a limit position).
    transfer: Vec<bool>,
}

impl TransferRecord {
    /// An empty record of the positions of `mech` laid out as `layout`
    /// (of that mechanism), with room for `positions` of them.
    pub fn new(layout: &Layout, mech: &Mechanism, positions: usize) -> TransferRecord {
        let (nd, nm) = (layout.n_dof, mech.n_moving());
        let (np, ndep) = (layout.n_prescribed, layout.n_dependent);
        let mut at = Offsets::default();
        let mut end = 0;
        let mut part = |width: usize| {
            end += width;
            end - width
        };
        at.inputs = part(nd);
        at.qd = part(nd);
        at.qdd = part(nd);
        at.time = part(1);
        at.det = part(1);
        at.rows = part(np + ndep);
        at.x1 = part(nd * nm);
        at.x2 = part(nd * nd * nm);
        at.dep1 = part(ndep * nd);
        at.dep2 = part(ndep * nd * nd);
        at.dynamic = part(if layout.dynamic { layout.at.time - layout.at.sigma } else { 0 });
        at.stride = end;
        TransferRecord {
            n_dof: nd,
            n_moving: nm,
            data: Vec::with_capacity(positions.saturating_mul(at.stride)),
            transfer: Vec::with_capacity(positions),
            at,
        }
    }

    /// Number of positions recorded.
    pub fn positions(&self) -> usize {
        self.transfer.len()
    }

    /// Numbers kept a position.
    pub fn stride(&self) -> usize {
        self.at.stride
    }

    /// The values of the prescribed rows, then of the dependent ones, at
    /// position `k` (0-based): the `e0` block of the layout there.
    pub fn row_values(&self, k: usize) -> &[f64] {
        let row = &self.data[k * self.at.stride..];
        &row[self.at.rows..self.at.x1]
    }

    /// Appends the position `v`, laid out as `layout` (the one the record
    /// was made for); the values of inverse dynamics from `dynamics`,
    /// evaluated at this position ([`InverseDynamics::evaluate`]; NaN without it).
    pub fn push(&mut self, layout: &Layout, v: &PositionView<'_>, dynamics: Option<&InverseDynamics>) {
        let (kin, nd, at) = (v.kin, self.n_dof, &self.at);
        let data = &mut self.data;
        let start = data.len();
        // Appended part after part in the row's order, each as one slice
        // where the motion holds it as one: a position is recorded at every
        // step, so it is written once, with no NaN written first.
        data.reserve(at.stride);
        data.extend((0..nd).map(|j| v.input(j)));
        data.extend_from_slice(&v.input_vel[..nd]);
        data.extend_from_slice(&v.input_acc[..nd]);
        data.extend_from_slice(&[v.time, kin.det()]);
        data.extend_from_slice(kin.row_values());
        data.extend_from_slice(kin.dependent_values());
        let transfer = kin.order().is_some();
        if !transfer {
            // A limit position (D^c has no inverse): no transfer functions.
            data.resize(start + at.dynamic, f64::NAN);
        } else if nd == 1 {
            // One input, the common case: every block is one slice as the motion holds it.
            data.extend_from_slice(kin.first_order());
            data.extend_from_slice(kin.x2(0, 0));
            data.extend_from_slice(kin.dependent_first());
            data.extend_from_slice(kin.dependent_second());
        } else {
            // The second-order blocks hold every pair (j, m), both orders of it.
            data.extend_from_slice(kin.first_order());
            for j in 0..nd {
                for m in 0..nd {
                    data.extend_from_slice(kin.x2(j, m));
                }
            }
            data.extend_from_slice(kin.dependent_first());
            let ndep = layout.n_dependent;
            data.extend((0..ndep).flat_map(|d| (0..nd).flat_map(move |j| (0..nd).map(move |m| kin.dep2(d, j, m)))));
        }
        debug_assert_eq!(data.len() - start, at.dynamic, "the kinematic part of a recorded position");
        data.resize(start + at.stride, f64::NAN);
        if let (true, Some(d)) = (layout.dynamic, dynamics) {
            dynamic_values(layout, v.mech, d, &mut data[start + at.dynamic..]);
        }
        self.transfer.push(transfer);
    }

    /// The rows of the positions `positions` with whether each has transfer functions.
    fn rows(&self, positions: Range<usize>) -> impl Iterator<Item = (&[f64], bool)> {
        let stride = self.at.stride.max(1);
        let data = &self.data[positions.start * stride..positions.end * stride];
        data.chunks_exact(stride).zip(self.transfer[positions].iter().copied())
    }
}

/// Writes the values of the layout's blocks of inverse dynamics (`sigma`
/// to `loadpow`, in its order) from `d`, evaluated at the position, into `out`.
fn dynamic_values(layout: &Layout, mech: &Mechanism, d: &InverseDynamics, out: &mut [f64]) {
    let (nd, n) = (layout.n_dof, layout.n_coords);
    let values = (0..layout.n_prescribed)
        .map(|r| d.sigma(r))
        .chain((0..nd).map(|j| d.drive(mech, j)))
        .chain((0..n).map(|i| d.reaction(mech, i)))
        .chain([d.kinetic_energy(), d.potential_energy(), d.drive_power()])
        .chain((0..nd).flat_map(|j| (0..nd).map(move |m| d.mass_matrix_entry(mech, j, m))))
        .chain(
            layout
                .pins
                .iter()
                .flat_map(|&(e, x, y)| [d.pin_force(e, x, y, Component::X), d.pin_force(e, x, y, Component::Y)]),
        )
        .chain([Component::X, Component::Y, Component::Moment].map(|c| d.shaking(c)))
        .chain([d.load_power()]);
    let mut written = 0;
    for (x, value) in out.iter_mut().zip(values) {
        *x = value;
        written += 1;
    }
    debug_assert_eq!(written, out.len(), "the blocks of inverse dynamics");
}

impl Layout {
    /// The table of the positions of `record` (made for this layout):
    /// column after column, each `record.positions()` long, every value the
    /// one [`Self::record`] records at that position.
    pub fn table(&self, record: &TransferRecord) -> Vec<f64> {
        let mut out = Vec::with_capacity(self.width * record.positions());
        for c in 0..self.width {
            self.column_values(record, c, &mut out);
        }
        out
    }

    /// Appends the values of column `c` at every position of `record`
    /// (made for this layout), as [`Self::table`] holds them.
    pub fn column_values(&self, record: &TransferRecord, c: usize, out: &mut Vec<f64>) {
        self.column_values_at(record, c, 0..record.positions(), out);
    }

    /// As [`Self::column_values`], at the positions `positions` (0-based,
    /// recorded ones) only: a column made a block of positions at a time,
    /// while they are still in the cache, as a run records them.
    pub fn column_values_at(&self, record: &TransferRecord, c: usize, positions: Range<usize>, out: &mut Vec<f64>) {
        let Some(block) = self.blocks.iter().find(|b| b.columns().contains(&c)) else {
            return;
        };
        let (at, o) = (&self.at, &record.at);
        let (nd, nm, np) = (self.n_dof, record.n_moving, self.n_prescribed);
        let sq = nd * nd;
        let t = c - block.start;
        let nan = f64::NAN;
        let rows = record.rows(positions);
        // The transfer functions of the co-ordinate in column `col` of D^c
        // (0 for a fixed one), as the layout holds them.
        let (mut d1, mut d2) = (vec![0.0; nd], vec![0.0; sq]);
        let coord = |row: &[f64], col: usize, d1: &mut [f64], d2: &mut [f64]| {
            for (j, d) in d1.iter_mut().enumerate() {
                *d = if col == FIXED { 0.0 } else { row[o.x1 + j * nm + col] };
            }
            for (p, d) in d2.iter_mut().enumerate() {
                *d = if col == FIXED { 0.0 } else { row[o.x2 + p * nm + col] };
            }
        };
        match block.name {
            "inputs" => out.extend(rows.map(|(r, _)| r[o.inputs + t])),
            "kx1" => {
                let (col, j) = (self.columns[t / nd], t % nd);
                out.extend(rows.map(|(r, tr)| match (tr, col) {
                    (false, _) => nan,
                    (true, FIXED) => 0.0,
                    (true, col) => r[o.x1 + j * nm + col],
                }));
            }
            "kx2" => {
                let (col, p) = (self.columns[t / sq], t % sq);
                out.extend(rows.map(|(r, tr)| match (tr, col) {
                    (false, _) => nan,
                    (true, FIXED) => 0.0,
                    (true, col) => r[o.x2 + p * nm + col],
                }));
            }
            "vx" | "ax" if nd == 1 => {
                // One input, the common case: the same sums, without the loops over the inputs.
                let (col, acc) = (self.columns[t], block.name == "ax");
                out.extend(rows.map(|(r, tr)| {
                    if !tr {
                        return nan;
                    }
                    let (d1, d2) = if col == FIXED { (0.0, 0.0) } else { (r[o.x1 + col], r[o.x2 + col]) };
                    let (qd, qdd) = (r[o.qd], r[o.qdd]);
                    if acc {
                        acceleration(&[d1], &[d2], &[qd], &[qdd])
                    } else {
                        velocity(&[d1], &[qd])
                    }
                }));
            }
            "vx" | "ax" => {
                let (col, acc) = (self.columns[t], block.name == "ax");
                for (r, tr) in rows {
                    out.push(if tr {
                        coord(r, col, &mut d1, &mut d2);
                        let (qd, qdd) = (&r[o.qd..][..nd], &r[o.qdd..][..nd]);
                        if acc {
                            acceleration(&d1, &d2, qd, qdd)
                        } else {
                            velocity(&d1, qd)
                        }
                    } else {
                        nan
                    });
                }
            }
            "e0" => out.extend(rows.map(|(r, _)| r[o.rows + t])),
            "ke1" if t / nd < np => out.extend(rows.map(|_| self.prescribed_ke1[t])),
            "ke1" => {
                let d = t / nd - np;
                out.extend(rows.map(|(r, tr)| if tr { r[o.dep1 + d * nd + t % nd] } else { nan }));
            }
            "ke2" if t / sq < np => out.extend(rows.map(|_| 0.0)),
            "ke2" => {
                let d = t / sq - np;
                out.extend(rows.map(|(r, tr)| if tr { r[o.dep2 + d * sq + t % sq] } else { nan }));
            }
            "ve" | "ae" if t < np => {
                // A prescribed row moves as its input, if it is one; a constant row does not move.
                let q = if block.name == "ve" { o.qd } else { o.qdd };
                out.extend(rows.map(|(r, _)| self.input_of[t].map_or(0.0, |j| r[q + j])));
            }
            "ve" | "ae" => {
                let d = t - np;
                let acc = block.name == "ae";
                out.extend(rows.map(|(r, tr)| {
                    if !tr {
                        return nan;
                    }
                    let (d1, d2) = (&r[o.dep1 + d * nd..][..nd], &r[o.dep2 + d * sq..][..sq]);
                    let (qd, qdd) = (&r[o.qd..][..nd], &r[o.qdd..][..nd]);
                    if acc {
                        acceleration(d1, d2, qd, qdd)
                    } else {
                        velocity(d1, qd)
                    }
                }));
            }
            "time" => out.extend(rows.map(|(r, _)| r[o.time])),
            "det" => out.extend(rows.map(|(r, _)| r[o.det])),
            // The blocks of inverse dynamics, kept as they are.
            _ => out.extend(rows.map(|(r, _)| r[o.dynamic + c - at.sigma])),
        }
    }
}
