//! A recording of chosen quantities in named blocks: what a deck's run
//! records ([`Selection::deck`]), laid out as the full [`Layout`] is, so
//! that a reader slices either table by block name and never counts
//! columns itself.
//!
//! ```
//! use mechfem_core::run::Selection;
//! use mechfem_core::Quantity;
//! // Two buffers and the hodograph of co-ordinates 9 and 10 (0-based 8, 9)
//! // of a kinematic deck with one input.
//! let s = Selection::deck(&[Quantity::X0(8), Quantity::X0(9)], &[8, 9], 1, false);
//! let names: Vec<&str> = s.blocks().iter().map(|b| b.name).collect();
//! assert_eq!(names, ["buffers", "hodograph", "time", "det"]);
//! let hodograph = s.block("hodograph").unwrap();
//! assert_eq!((hodograph.start, hodograph.shape.clone()), (2, vec![2]));
//! assert_eq!(s.quantities()[hodograph.start], Quantity::Kx1 { coord: 8, j: 0 });
//! assert_eq!(s.quantities().len(), s.width());
//! ```
//!
//! [`Layout`]: super::Layout

use super::layout::Block;
use super::record::Quantity;
use crate::solver::TransferOrder;

/// Named blocks of chosen quantities: the quantity of every column
/// ([`Self::quantities`], what a [`Recorder`](super::Recorder) of them
/// records) and the blocks that name them ([`Self::blocks`]), which cover
/// the columns once each, in order.
#[derive(Debug, Clone, Default)]
pub struct Selection {
    blocks: Vec<Block>,
    quantities: Vec<Quantity>,
}

impl Selection {
    /// What a deck's run records, for a mechanism of `n_dof` inputs, block
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
    ///
    /// and last `time` and `det` (det(D^c)), one value each. The hodograph
    /// needs an input: without one (`n_dof` 0) the block is empty.
    pub fn deck(buffers: &[Quantity], hodograph: &[usize], n_dof: usize, dynamic: bool) -> Selection {
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
        }
        s.add("time", vec![], [Quantity::Time]);
        s.add("det", vec![], [Quantity::Det]);
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
}
