//! The full recording of a run: every quantity of the deck's buffer table
//! for every input, co-ordinate and row, in one column layout made of named
//! blocks ([`Layout`]), recorded a whole position at a time.
//!
//! A block holds one kind of quantity for every co-ordinate, row or input
//! at once (`kx1`: d x_i / d input_j for every i and j), so that a reader
//! slices the table by block name and reshapes it, and a position is
//! recorded by copying the transfer functions out of
//! [`Kinematics`](crate::Kinematics) block by block instead of evaluating one
//! [`Quantity`] per value. Every value is the one [`Quantity::value`] (or
//! [`Quantity::dynamic_value`]) gives, to the last bit:
//! [`Layout::quantities`] names the quantity of each column. [`Columns`]
//! keeps such a recording column by column, as a reader of one quantity over
//! the positions (numpy, in Fortran order) wants it. A run that records
//! everything for later reading keeps what the motion computes instead
//! ([`TransferRecord`](super::TransferRecord)) and makes this table from it
//! when it is asked for ([`Layout::table`]), the same values to the last bit.
//!
//! ```
//! use mechfem_core::run::Layout;
//! # let deck = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/supply/supply.mec");
//! # let model = mechfem_deck::load(deck).unwrap();
//! let layout = Layout::full(&model.mechanism, false);
//! let kx1 = layout.block("kx1").unwrap();
//! // d x_i / d input_j of every co-ordinate i and input j, row-major in (i, j).
//! assert_eq!(kx1.shape, vec![model.mechanism.n_coords(), model.mechanism.n_dof()]);
//! assert_eq!(layout.blocks().iter().map(|b| b.width()).sum::<usize>(), layout.width());
//! ```

use std::ops::Range;

use super::inverse::InverseDynamics;
use super::observe::PositionView;
use super::record::Quantity;
use crate::dynamics::Component;
use crate::elements::Slot;
use crate::model::{FormRef, Mechanism, FIXED};

/// Every element's points: (element, x, y) in element order, each
/// element's points in the order of its co-ordinates.
pub fn element_points(mech: &Mechanism) -> Vec<(usize, usize, usize)> {
    let mut out = Vec::new();
    for (e, el) in mech.elements().iter().enumerate() {
        let coords = el.coords();
        let mut at = 0;
        for slot in el.ty.slots() {
            if slot == Slot::Point {
                out.push((e, coords[at], coords[at + 1]));
                at += 2;
            } else {
                at += 1;
            }
        }
    }
    out
}

/// One block of a [`Layout`]: the quantity `name` over an array of `shape`
/// per position (row-major), in the columns `start..start + width()`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Block {
    /// What the block holds (see [`Layout::full`]).
    pub name: &'static str,
    /// Its first column.
    pub start: usize,
    /// Its shape at one position; empty for a single value.
    pub shape: Vec<usize>,
}

impl Block {
    /// Number of columns.
    pub fn width(&self) -> usize {
        self.shape.iter().product()
    }

    /// Its columns.
    pub fn columns(&self) -> Range<usize> {
        self.start..self.start + self.width()
    }
}

/// The full column layout of a mechanism's recording (N co-ordinates, D
/// inputs, R rows: the prescribed ones, then the dependent ones), block by
/// block:
///
/// | block | shape | value |
/// |---|---|---|
/// | `inputs` | D | input values |
/// | `kx1` | N x D | d x_i / d input_j |
/// | `kx2` | N x D x D | d2 x_i / d input_j d input_m |
/// | `vx`, `ax` | N | velocity and acceleration of each co-ordinate |
/// | `e0` | R | row values |
/// | `ke1` | R x D | d eps_r / d input_j |
/// | `ke2` | R x D x D | d2 eps_r / d input_j d input_m |
/// | `ve`, `ae` | R | velocity and acceleration of each row |
///
/// with a mass and load model (`dynamic`), then
///
/// | block | shape | value |
/// |---|---|---|
/// | `sigma` | prescribed rows | stress of each prescribed row |
/// | `drive` | D | drive force or torque of each input |
/// | `reaction` | N | reaction on each co-ordinate (NaN for a moving one) |
/// | `ekin`, `epot`, `power` | one value | kinetic and potential energy, drive power |
/// | `mass` | D x D | the mass matrix in the inputs |
/// | `pin` | P x 2 | the force each element exerts on each of its points (x, y), elements in order, each one's points in its co-ordinates' order ([`Layout::pins`]) |
/// | `shaking` | 3 | shaking force x, y and moment about the origin |
/// | `loadpow` | one value | power of the loads (forces, loads, tables, motors, dampers) |
///
/// and last `time` and `det` (det(D^c)), one value each. Co-ordinate values
/// are not in it: a recorder keeps them beside it.
#[derive(Debug, Clone)]
pub struct Layout {
    pub(super) blocks: Vec<Block>,
    pub(super) width: usize,
    pub(super) n_dof: usize,
    pub(super) n_coords: usize,
    pub(super) n_prescribed: usize,
    pub(super) n_dependent: usize,
    pub(super) dynamic: bool,
    /// The column of each co-ordinate in the transfer functions, FIXED for a fixed one.
    pub(super) columns: Vec<usize>,
    /// The input each prescribed row is, if any.
    pub(super) input_of: Vec<Option<usize>>,
    /// The prescribed rows' part of `ke1`.
    pub(super) prescribed_ke1: Vec<f64>,
    /// The first column of each block, looked up once.
    pub(super) at: Starts,
    /// The rows of the `pin` block: element, x and y co-ordinate.
    pub(super) pins: Vec<(usize, usize, usize)>,
}

/// The first column of every block of a [`Layout`] (its width where the
/// layout has no such block).
#[derive(Debug, Clone, Default)]
pub(super) struct Starts {
    pub(super) inputs: usize,
    pub(super) kx1: usize,
    pub(super) kx2: usize,
    pub(super) vx: usize,
    pub(super) ax: usize,
    pub(super) e0: usize,
    pub(super) ke1: usize,
    pub(super) ke2: usize,
    pub(super) ve: usize,
    pub(super) ae: usize,
    pub(super) sigma: usize,
    pub(super) drive: usize,
    pub(super) reaction: usize,
    pub(super) ekin: usize,
    pub(super) epot: usize,
    pub(super) power: usize,
    pub(super) mass: usize,
    pub(super) pin: usize,
    pub(super) shaking: usize,
    pub(super) loadpow: usize,
    pub(super) time: usize,
    pub(super) det: usize,
}

impl Layout {
    /// The full layout of `mech`, with the blocks of inverse dynamics when `dynamic`.
    pub fn full(mech: &Mechanism, dynamic: bool) -> Layout {
        let (nd, n, np, ndep) = (mech.n_dof(), mech.n_coords(), mech.n_prescribed(), mech.n_dependent());
        let nr = np + ndep;
        let pins = if dynamic { element_points(mech) } else { Vec::new() };
        let mut blocks = Vec::new();
        let mut start = 0;
        let mut add = |name: &'static str, shape: Vec<usize>| {
            let block = Block { name, start, shape };
            start += block.width();
            blocks.push(block);
        };
        add("inputs", vec![nd]);
        add("kx1", vec![n, nd]);
        add("kx2", vec![n, nd, nd]);
        add("vx", vec![n]);
        add("ax", vec![n]);
        add("e0", vec![nr]);
        add("ke1", vec![nr, nd]);
        add("ke2", vec![nr, nd, nd]);
        add("ve", vec![nr]);
        add("ae", vec![nr]);
        if dynamic {
            add("sigma", vec![np]);
            add("drive", vec![nd]);
            add("reaction", vec![n]);
            add("ekin", vec![]);
            add("epot", vec![]);
            add("power", vec![]);
            add("mass", vec![nd, nd]);
            add("pin", vec![pins.len(), 2]);
            add("shaking", vec![3]);
            add("loadpow", vec![]);
        }
        add("time", vec![]);
        add("det", vec![]);
        let width = start;
        let input_of: Vec<Option<usize>> = (0..np).map(|r| mech.input_of(r)).collect();
        let prescribed_ke1 =
            input_of.iter().flat_map(|input| (0..nd).map(move |j| f64::from(u8::from(*input == Some(j))))).collect();
        let start = |name: &str| blocks.iter().find(|b| b.name == name).map_or(width, |b| b.start);
        let at = Starts {
            inputs: start("inputs"),
            kx1: start("kx1"),
            kx2: start("kx2"),
            vx: start("vx"),
            ax: start("ax"),
            e0: start("e0"),
            ke1: start("ke1"),
            ke2: start("ke2"),
            ve: start("ve"),
            ae: start("ae"),
            sigma: start("sigma"),
            drive: start("drive"),
            reaction: start("reaction"),
            ekin: start("ekin"),
            epot: start("epot"),
            power: start("power"),
            mass: start("mass"),
            pin: start("pin"),
            shaking: start("shaking"),
            loadpow: start("loadpow"),
            time: start("time"),
            det: start("det"),
        };
        Layout {
            blocks,
            width,
            n_dof: nd,
            n_coords: n,
            n_prescribed: np,
            n_dependent: ndep,
            dynamic,
            columns: (0..n).map(|i| mech.column(i)).collect(),
            input_of,
            prescribed_ke1,
            at,
            pins,
        }
    }

    /// The blocks, in column order; they cover the columns `0..width()` once each.
    pub fn blocks(&self) -> &[Block] {
        &self.blocks
    }

    /// The block called `name`, if the layout has it.
    pub fn block(&self, name: &str) -> Option<&Block> {
        self.blocks.iter().find(|b| b.name == name)
    }

    /// Number of columns.
    pub fn width(&self) -> usize {
        self.width
    }

    /// The rows of the `pin` block: every element's points (element, x and
    /// y co-ordinate, 0-based), elements in order (empty unless dynamic).
    pub fn pins(&self) -> &[(usize, usize, usize)] {
        &self.pins
    }

    /// Whether the layout has the blocks of inverse dynamics.
    pub fn is_dynamic(&self) -> bool {
        self.dynamic
    }

    /// The quantity of every column, in order: what [`Self::record`] records.
    pub fn quantities(&self) -> Vec<Quantity> {
        let (nd, n) = (self.n_dof, self.n_coords);
        let pairs = || (0..nd).flat_map(move |j| (0..nd).map(move |m| (j, m)));
        let rows =
            || (0..self.n_prescribed).map(FormRef::Prescribed).chain((0..self.n_dependent).map(FormRef::Dependent));
        let mut q = Vec::with_capacity(self.width);
        for block in &self.blocks {
            match block.name {
                "inputs" => q.extend((0..nd).map(Quantity::Input)),
                "kx1" => q.extend((0..n).flat_map(|coord| (0..nd).map(move |j| Quantity::Kx1 { coord, j }))),
                "kx2" => q.extend((0..n).flat_map(|coord| pairs().map(move |(j, m)| Quantity::Kx2 { coord, j, m }))),
                "vx" => q.extend((0..n).map(Quantity::Vx)),
                "ax" => q.extend((0..n).map(Quantity::Ax)),
                "e0" => q.extend(rows().map(Quantity::E0)),
                "ke1" => q.extend(rows().flat_map(|f| (0..nd).map(move |j| Quantity::Ke1(f, j)))),
                "ke2" => q.extend(rows().flat_map(|f| pairs().map(move |(j, m)| Quantity::Ke2(f, j, m)))),
                "ve" => q.extend(rows().map(Quantity::Ve)),
                "ae" => q.extend(rows().map(Quantity::Ae)),
                "sigma" => q.extend((0..self.n_prescribed).map(Quantity::Sigma)),
                "drive" => q.extend((0..nd).map(Quantity::Drive)),
                "reaction" => q.extend((0..n).map(Quantity::Reaction)),
                "ekin" => q.push(Quantity::Ekin),
                "epot" => q.push(Quantity::Epot),
                "power" => q.push(Quantity::Power),
                "mass" => q.extend(pairs().map(|(j, m)| Quantity::Mred(j, m))),
                "pin" => q.extend(self.pins.iter().flat_map(|&(element, x, y)| {
                    [Component::X, Component::Y].map(|component| Quantity::Pin { element, x, y, component })
                })),
                "shaking" => q.extend([Component::X, Component::Y, Component::Moment].map(Quantity::Shaking)),
                "loadpow" => q.push(Quantity::LoadPower),
                "time" => q.push(Quantity::Time),
                "det" => q.push(Quantity::Det),
                other => unreachable!("a layout has no block {other}"),
            }
        }
        q
    }

    /// The column that holds quantity `q`, if the layout has it (it has
    /// every quantity but the co-ordinate values, [`Quantity::X0`], and
    /// those of inverse dynamics when it is not [dynamic](Self::is_dynamic)):
    /// `quantities()[column(q)] == q`.
    pub fn column(&self, q: Quantity) -> Option<usize> {
        let (nd, n, np) = (self.n_dof, self.n_coords, self.n_prescribed);
        let sq = nd * nd;
        let at = &self.at;
        let row = |f: FormRef| match f {
            FormRef::Prescribed(r) => (r < np).then_some(r),
            FormRef::Dependent(d) => (d < self.n_dependent).then_some(np + d),
        };
        let dynamic = |c: usize| self.dynamic.then_some(c);
        match q {
            Quantity::Input(j) if j < nd => Some(at.inputs + j),
            Quantity::Time => Some(at.time),
            Quantity::Det => Some(at.det),
            Quantity::Kx1 { coord, j } if coord < n && j < nd => Some(at.kx1 + coord * nd + j),
            Quantity::Kx2 { coord, j, m } if coord < n && j < nd && m < nd => Some(at.kx2 + coord * sq + j * nd + m),
            Quantity::Vx(i) if i < n => Some(at.vx + i),
            Quantity::Ax(i) if i < n => Some(at.ax + i),
            Quantity::E0(f) => Some(at.e0 + row(f)?),
            Quantity::Ke1(f, j) if j < nd => Some(at.ke1 + row(f)? * nd + j),
            Quantity::Ke2(f, j, m) if j < nd && m < nd => Some(at.ke2 + row(f)? * sq + j * nd + m),
            Quantity::Ve(f) => Some(at.ve + row(f)?),
            Quantity::Ae(f) => Some(at.ae + row(f)?),
            Quantity::Sigma(r) if r < np => dynamic(at.sigma + r),
            Quantity::Drive(j) if j < nd => dynamic(at.drive + j),
            Quantity::Reaction(i) if i < n => dynamic(at.reaction + i),
            Quantity::Ekin => dynamic(at.ekin),
            Quantity::Epot => dynamic(at.epot),
            Quantity::Power => dynamic(at.power),
            Quantity::Mred(j, m) if j < nd && m < nd => dynamic(at.mass + j * nd + m),
            Quantity::Pin { element, x, y, component: c @ (Component::X | Component::Y) } => {
                let k = self.pins.iter().position(|&p| p == (element, x, y))?;
                dynamic(at.pin + 2 * k + usize::from(c == Component::Y))
            }
            Quantity::Shaking(c) => dynamic(at.shaking + c as usize),
            Quantity::LoadPower => dynamic(at.loadpow),
            _ => None,
        }
    }

    /// Appends the values of every column at the position `v` to `out`;
    /// those of inverse dynamics from `dynamics`, evaluated at this position
    /// ([`InverseDynamics::evaluate`]; NaN without it).
    pub fn record(&self, v: &PositionView<'_>, dynamics: Option<&InverseDynamics>, out: &mut Vec<f64>) {
        let at = out.len();
        out.resize(at + self.width, f64::NAN);
        self.fill(v, dynamics, &mut out[at..]);
    }

    /// Writes one position into `row` (`width()` values), which holds NaN
    /// where nothing is written.
    fn fill(&self, v: &PositionView<'_>, dynamics: Option<&InverseDynamics>, row: &mut [f64]) {
        let (mech, kin) = (v.mech, v.kin);
        let (nd, n, np, nr) = (self.n_dof, self.n_coords, self.n_prescribed, self.n_prescribed + self.n_dependent);
        let (qd, qdd) = (v.input_vel, v.input_acc);
        // At a limit position D^c has no inverse: the transfer functions,
        // and the velocities and accelerations made from them, do not exist
        // (NaN, as `row` holds); the prescribed rows' are those of an identity.
        let transfer = kin.order().is_some();
        let at = &self.at;
        for (j, x) in row[at.inputs..][..nd].iter_mut().enumerate() {
            *x = v.input(j);
        }
        let sq = nd * nd;
        if transfer && nd == 1 {
            // One input, the common case: the same values and sums as below,
            // without the loops over the inputs.
            let (x1, x2, qd, qdd) = (kin.x1(0), kin.x2(0, 0), [qd[0]], [qdd[0]]);
            for (i, &c) in self.columns.iter().enumerate() {
                let (d1, d2) = if c == FIXED { (0.0, 0.0) } else { (x1[c], x2[c]) };
                row[at.kx1 + i] = d1;
                row[at.kx2 + i] = d2;
                row[at.vx + i] = velocity(&[d1], &qd);
                row[at.ax + i] = acceleration(&[d1], &[d2], &qd, &qdd);
            }
        } else if transfer {
            let (kx1, kx2) = (at.kx1, at.kx2);
            for j in 0..nd {
                let x1 = kin.x1(j);
                for (i, &c) in self.columns.iter().enumerate() {
                    row[kx1 + i * nd + j] = if c == FIXED { 0.0 } else { x1[c] };
                }
                for m in 0..nd {
                    let x2 = kin.x2(j, m);
                    for (i, &c) in self.columns.iter().enumerate() {
                        row[kx2 + i * sq + j * nd + m] = if c == FIXED { 0.0 } else { x2[c] };
                    }
                }
            }
            for i in 0..n {
                let (d1, d2) = (&row[kx1 + i * nd..][..nd], &row[kx2 + i * sq..][..sq]);
                let (vel, acc) = (velocity(d1, qd), acceleration(d1, d2, qd, qdd));
                (row[at.vx + i], row[at.ax + i]) = (vel, acc);
            }
        }
        let (e0, ke1, ke2, ve, ae) = (at.e0, at.ke1, at.ke2, at.ve, at.ae);
        // A prescribed row's transfer functions are those of an identity: 1
        // for its own input, 0 otherwise, the same at every position.
        row[ke1..][..np * nd].copy_from_slice(&self.prescribed_ke1);
        row[ke2..][..np * sq].fill(0.0);
        for (r, input) in self.input_of.iter().enumerate() {
            row[e0 + r] = kin.row_value(r);
            row[ve + r] = input.map_or(0.0, |j| qd[j]);
            row[ae + r] = input.map_or(0.0, |j| qdd[j]);
        }
        for (d, r) in (np..nr).enumerate() {
            row[e0 + r] = kin.dep(d);
            if transfer {
                for j in 0..nd {
                    row[ke1 + r * nd + j] = kin.dep1(d, j);
                    for m in 0..nd {
                        row[ke2 + r * sq + j * nd + m] = kin.dep2(d, j, m);
                    }
                }
                let (d1, d2) = (&row[ke1 + r * nd..][..nd], &row[ke2 + r * sq..][..sq]);
                let (vel, acc) = (velocity(d1, qd), acceleration(d1, d2, qd, qdd));
                (row[ve + r], row[ae + r]) = (vel, acc);
            }
        }
        if let (true, Some(d)) = (self.dynamic, dynamics) {
            let (sigma, drive, reaction, mass) = (at.sigma, at.drive, at.reaction, at.mass);
            for r in 0..np {
                row[sigma + r] = d.sigma(r);
            }
            for j in 0..nd {
                row[drive + j] = d.drive(mech, j);
                for m in 0..nd {
                    row[mass + j * nd + m] = d.mass_matrix_entry(mech, j, m);
                }
            }
            for i in 0..n {
                row[reaction + i] = d.reaction(mech, i);
            }
            row[at.ekin] = d.kinetic_energy();
            row[at.epot] = d.potential_energy();
            row[at.power] = d.drive_power();
            for (k, &(e, x, y)) in self.pins.iter().enumerate() {
                row[at.pin + 2 * k] = d.pin_force(e, x, y, Component::X);
                row[at.pin + 2 * k + 1] = d.pin_force(e, x, y, Component::Y);
            }
            for c in [Component::X, Component::Y, Component::Moment] {
                row[at.shaking + c as usize] = d.shaking(c);
            }
            row[at.loadpow] = d.load_power();
        }
        row[at.time] = v.time;
        row[at.det] = kin.det();
    }
}

/// A velocity from first-order transfer functions `d1` and the input
/// velocities `qd` (eq. 5.29), summed as [`crate::Kinematics::velocity`] does.
#[inline]
pub(super) fn velocity(d1: &[f64], qd: &[f64]) -> f64 {
    d1.iter().zip(qd).map(|(d, q)| d * q).sum()
}

/// An acceleration from first- and second-order transfer functions `d1`,
/// `d2` (row-major in the input pairs) and the input velocities and
/// accelerations (eq. 5.30), summed as [`crate::Kinematics::acceleration`] does.
#[inline]
pub(super) fn acceleration(d1: &[f64], d2: &[f64], qd: &[f64], qdd: &[f64]) -> f64 {
    let nd = d1.len();
    let mut a = 0.0;
    for j in 0..nd {
        a += d1[j] * qdd[j];
        for m in 0..nd {
            a += d2[j * nd + m] * qd[j] * qd[m];
        }
    }
    a
}

/// A table recorded a position at a time and kept column by column: the
/// values of each column over all positions are contiguous, as a reader of
/// single quantities wants them (a numpy array in Fortran order).
///
/// Room for the positions expected is made up front, so recording moves
/// nothing and a table never exists twice; a run that stops early has its
/// columns closed up in place ([`Columns::into_vec`]).
#[derive(Debug, Clone, Default)]
pub struct Columns {
    width: usize,
    /// Positions each column has room for.
    room: usize,
    positions: usize,
    /// Column c at `c * room..`.
    data: Vec<f64>,
}

impl Columns {
    /// An empty table of `width` columns with room for `positions` positions.
    pub fn new(width: usize, positions: usize) -> Columns {
        Columns { width, room: positions, positions: 0, data: vec![0.0; width * positions] }
    }

    /// Appends one position, `width` values.
    pub fn push(&mut self, row: &[f64]) {
        debug_assert_eq!(row.len(), self.width);
        if self.positions == self.room {
            self.grow();
        }
        let (k, room) = (self.positions, self.room);
        for (c, &x) in row.iter().enumerate() {
            self.data[c * room + k] = x;
        }
        self.positions += 1;
    }

    /// More positions than expected: twice the room, each column moved to its new place.
    fn grow(&mut self) {
        let room = (2 * self.room).max(1);
        let mut data = vec![0.0; self.width * room];
        for c in 0..self.width {
            data[c * room..][..self.positions].copy_from_slice(&self.data[c * self.room..][..self.positions]);
        }
        (self.data, self.room) = (data, room);
    }

    /// Number of positions recorded.
    pub fn positions(&self) -> usize {
        self.positions
    }

    /// Value of column `c` at position `k`.
    pub fn get(&self, k: usize, c: usize) -> f64 {
        self.data[c * self.room + k]
    }

    /// The values, column after column, each `positions()` long.
    pub fn into_vec(mut self) -> Vec<f64> {
        if self.positions < self.room {
            for c in 1..self.width {
                let from = c * self.room;
                self.data.copy_within(from..from + self.positions, c * self.positions);
            }
            self.data.truncate(self.width * self.positions);
        }
        self.data
    }
}
