//! A recording of chosen quantities in named blocks: what a deck's run
//! records ([`Selection::deck`]), laid out as the full [`Layout`] is, so
//! that a reader slices either table by block name and never counts
//! columns itself.
//!
//! ```
//! use mechfem_core::run::Selection;
//! use mechfem_core::Quantity;
//! # let deck = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/fourbar/fourbar.mec");
//! # let model = mechfem_deck::load(deck).unwrap();
//! // Two buffers and the hodograph of co-ordinates 9 and 10 (0-based 8, 9)
//! // of a kinematic deck of one input.
//! let s = Selection::deck(&model.mechanism, &[Quantity::X0(8), Quantity::X0(9)], &[8, 9], false);
//! let names: Vec<&str> = s.blocks().iter().map(|b| b.name).collect();
//! assert_eq!(names, ["buffers", "hodograph", "time", "det"]);
//! let hodograph = s.block("hodograph").unwrap();
//! assert_eq!((hodograph.start, hodograph.shape.clone()), (2, vec![2]));
//! assert_eq!(s.quantities()[hodograph.start], Quantity::Kx1 { coord: 8, j: 0 });
//! assert_eq!(s.quantities().len(), s.width());
//! ```
//!
//! [`Layout`]: super::Layout

use super::inverse::InverseDynamics;
use super::layout::{acceleration, velocity, Block};
use super::observe::PositionView;
use super::record::{recorded_value, Quantity};
use crate::model::{FormRef, Mechanism, FIXED};
use crate::solver::TransferOrder;

/// Named blocks of chosen quantities of one mechanism: the quantity of
/// every column ([`Self::quantities`]) and the blocks that name them
/// ([`Self::blocks`]), which cover the columns once each, in order.
/// [`Self::record`] records a position of them.
#[derive(Debug, Clone, Default)]
pub struct Selection {
    blocks: Vec<Block>,
    quantities: Vec<Quantity>,
    /// How each column is read at a position.
    reads: Vec<Read>,
    /// Whether a column is one of inverse dynamics.
    dynamic: bool,
}

/// How [`Selection::record`] reads one column: the quantities a deck
/// records most of a mechanism of one input from its transfer functions
/// directly, by the column of the co-ordinate in them (found once), to the
/// same values and sums as [`Quantity::value`]; any other as
/// [`record_evaluated`](super::record::record_evaluated) does.
#[derive(Debug, Clone, Copy)]
enum Read {
    Coord(usize),
    Time,
    Det,
    /// d x_i / d input 1 of the co-ordinate at this column (FIXED for a fixed one).
    Kx1(usize),
    /// The velocity of the co-ordinate at this column.
    Velocity(usize),
    /// The acceleration of the co-ordinate at this column.
    Acceleration(usize),
    Other,
}

impl Selection {
    /// What a deck's run of `mech` (D inputs) records, block
    /// by block:
    ///
    /// | block | shape | value |
    /// |---|---|---|
    /// | `buffers` | buffers | the quantity of each buffer, in the deck's order |
    /// | `hodograph` | `hodograph.len()` | d x_i / d input 1 of each co-ordinate i of `hodograph` |
    ///
    /// with a mass and load model (`dynamic`), then
    ///
    /// | block | shape | value |
    /// |---|---|---|
    /// | `inputs` | D | input values |
    /// | `drive` | D | drive force or torque of each input |
    /// | `ekin`, `epot`, `power` | one value | kinetic and potential energy, drive power |
    /// | `loadpow` | one value | power of the loads (forces, loads, tables, motors, dampers) |
    /// | `vin` | D | speed of each input |
    ///
    /// and last `time` and `det` (det(D^c)), one value each. The hodograph
    /// needs an input: without one the block is empty.
    pub fn deck(mech: &Mechanism, buffers: &[Quantity], hodograph: &[usize], dynamic: bool) -> Selection {
        let n_dof = mech.n_dof();
        let mut s = Selection::default();
        s.add("buffers", vec![buffers.len()], buffers.iter().copied());
        let hodograph = if n_dof > 0 { hodograph } else { &[] };
        s.add("hodograph", vec![hodograph.len()], hodograph.iter().map(|&coord| Quantity::Kx1 { coord, j: 0 }));
        if dynamic {
            s.add("inputs", vec![n_dof], (0..n_dof).map(Quantity::Input));
            s.add("drive", vec![n_dof], (0..n_dof).map(Quantity::Drive));
            s.add("ekin", vec![], [Quantity::Ekin]);
            s.add("epot", vec![], [Quantity::Epot]);
            s.add("power", vec![], [Quantity::Power]);
            // For the report's energy balance: the loads' power and every
            // input's speed (a motor's power is its drive times the speed).
            s.add("loadpow", vec![], [Quantity::LoadPower]);
            s.add("vin", vec![n_dof], (0..n_dof).map(|j| Quantity::Ve(FormRef::Prescribed(mech.input_row(j)))));
        }
        s.add("time", vec![], [Quantity::Time]);
        s.add("det", vec![], [Quantity::Det]);
        s.reads = s.quantities.iter().map(|&q| read(mech, q)).collect();
        s.dynamic = s.quantities.iter().any(Quantity::is_dynamic);
        s
    }

    /// Appends block `name` of `shape`, whose quantities, row-major, are `quantities`.
    fn add(&mut self, name: &'static str, shape: Vec<usize>, quantities: impl IntoIterator<Item = Quantity>) {
        let block = Block { name, start: self.quantities.len(), shape };
        self.quantities.extend(quantities);
        debug_assert_eq!(self.quantities.len(), block.start + block.width(), "block {name}");
        self.blocks.push(block);
    }

    /// The blocks, in column order; they cover the columns `0..width()` once each.
    pub fn blocks(&self) -> &[Block] {
        &self.blocks
    }

    /// The block called `name`, if the selection has it.
    pub fn block(&self, name: &str) -> Option<&Block> {
        self.blocks.iter().find(|b| b.name == name)
    }

    /// Number of columns.
    pub fn width(&self) -> usize {
        self.quantities.len()
    }

    /// The quantity of every column, in order.
    pub fn quantities(&self) -> &[Quantity] {
        &self.quantities
    }

    /// The transfer functions the columns need, but for det(D^c) in the
    /// block `det`: a reader asks for that one when it wants it (a buffer
    /// that records det(D^c) still asks for it).
    pub fn transfer_order(&self) -> Option<TransferOrder> {
        let det = self.block("det").map(Block::columns).unwrap_or_default();
        let asked = self.quantities.iter().enumerate().filter(|(c, _)| !det.contains(c));
        asked.map(|(_, q)| q.transfer_order()).max().flatten()
    }

    /// Appends the values of every column at the position `v` to `out`,
    /// each the one [`Quantity::value`] (or [`Quantity::dynamic_value`])
    /// gives, to the last bit; those of inverse dynamics from `dynamics`,
    /// evaluated here (NaN without it).
    pub fn record(&self, v: &PositionView<'_>, dynamics: Option<&mut InverseDynamics>, out: &mut Vec<f64>) {
        let dynamics = match dynamics {
            Some(d) if self.dynamic => {
                d.evaluate(v);
                Some(&*d)
            }
            _ => None,
        };
        self.record_evaluated(v, dynamics, out);
    }

    /// Whether the columns hold results of inverse dynamics.
    pub fn is_dynamic(&self) -> bool {
        self.dynamic
    }

    /// As [`Self::record`], with inverse dynamics already evaluated at the
    /// position `v` ([`InverseDynamics::evaluate`]).
    pub fn record_evaluated(&self, v: &PositionView<'_>, dynamics: Option<&InverseDynamics>, out: &mut Vec<f64>) {
        let dynamics = dynamics.filter(|_| self.dynamic);
        let kin = v.kin;
        // The direct reads are those of one input; without transfer
        // functions (a limit position) the quantities made of them are NaN.
        let transfer = kin.order().is_some() && v.mech.n_dof() == 1;
        let (x1, x2, qd, qdd) = if transfer {
            (kin.x1(0), kin.x2(0, 0), v.input_vel[0], v.input_acc[0])
        } else {
            (&[][..], &[][..], f64::NAN, f64::NAN)
        };
        let at = |x: &[f64], c: usize| if c == FIXED { 0.0 } else { x[c] };
        // The row is made room for once and written column by column.
        let start = out.len();
        out.resize(start + self.reads.len(), f64::NAN);
        for ((slot, r), q) in out[start..].iter_mut().zip(&self.reads).zip(&self.quantities) {
            *slot = match *r {
                Read::Coord(i) => v.state.x[i],
                Read::Time => v.time,
                Read::Det => kin.det(),
                Read::Kx1(c) if transfer => at(x1, c),
                Read::Velocity(c) if transfer => velocity(&[at(x1, c)], &[qd]),
                Read::Acceleration(c) if transfer => acceleration(&[at(x1, c)], &[at(x2, c)], &[qd], &[qdd]),
                _ => recorded_value(*q, v, dynamics),
            };
        }
    }
}

/// How [`Selection::record`] reads quantity `q` of `mech`.
fn read(mech: &Mechanism, q: Quantity) -> Read {
    match q {
        Quantity::X0(i) => Read::Coord(i),
        Quantity::Time => Read::Time,
        Quantity::Det => Read::Det,
        Quantity::Kx1 { coord, j: 0 } => Read::Kx1(mech.column(coord)),
        Quantity::Vx(i) => Read::Velocity(mech.column(i)),
        Quantity::Ax(i) => Read::Acceleration(mech.column(i)),
        _ => Read::Other,
    }
}
