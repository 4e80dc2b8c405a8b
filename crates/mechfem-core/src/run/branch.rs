//! The assembly branch an optimiser's designs are evaluated on: the start
//! design's, whatever was evaluated before.
//!
//! D^c splits into diagonal blocks, the groups of co-ordinates found
//! together (a four-bar's crank, then its dyad, then the coupler point).
//! The sign of each block's determinant is the group's orientation: for a
//! dyad it is the sign of the triangle of its three joints, which tells its
//! two assemblies apart. A sign changes only where the block is singular,
//! so a motion that keeps to its branch keeps every sign, and a position
//! whose signs differ from the start design's lies on another branch.
//!
//! Position 1 of a design is assembled from a prediction that depends on
//! the design alone, never on the design evaluated before: the start
//! design's position 1 moved by its design sensitivities, else that
//! position as it is, else a continuation from the start design to this
//! one in stages. The first of them whose orientation is the start
//! design's is the design's position 1; when none is, the design is on
//! another branch, and infeasible.

use super::design::{evaluate, DesignRun, ExtremumSpec};
use super::record::Quantity;
use crate::error::SolveError;
use crate::model::{Mechanism, State};
use crate::motion::{InputMotion, Motion};
use crate::solver::{adjust, DesignVar, Kinematics, Params, TransferOrder};

/// The orientation of a position: the sign of the determinant of every
/// diagonal block of D^c, in the order the blocks are solved.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Orientation {
    positive: Vec<bool>,
}

impl Orientation {
    /// The orientation of the position `kin` last factorised D^c at.
    pub(crate) fn of(kin: &Kinematics, dets: &mut Vec<f64>) -> Orientation {
        kin.lu.block_dets(dets);
        Orientation { positive: dets.iter().map(|d| *d > 0.0).collect() }
    }

    /// The first block whose sign differs from `other`'s.
    pub fn reversed(&self, other: &Orientation) -> Option<usize> {
        self.positive.iter().zip(&other.positive).position(|(a, b)| a != b)
    }

    /// The first block whose determinant in `dets` (see
    /// [`Lu::block_dets`](crate::solver::lu::Lu::block_dets)) has another
    /// sign than this orientation's.
    pub(crate) fn reversed_in(&self, dets: &[f64]) -> Option<usize> {
        self.positive.iter().zip(dets).position(|(p, d)| *p != (*d > 0.0))
    }
}

/// The co-ordinates (0-based) of block `block` of D^c, ascending.
pub(crate) fn block_coords(mech: &Mechanism, kin: &Kinematics, block: usize) -> Vec<usize> {
    let mut coords: Vec<usize> = kin.lu.block_columns()[block].iter().map(|&c| mech.moving_coords()[c]).collect();
    coords.sort_unstable();
    coords
}

/// Where a motion left the branch of its position 1.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct BranchChange {
    /// The last position (0-based) on the branch; the next one is not.
    pub after: usize,
    /// The co-ordinates (0-based) of the group whose orientation reversed.
    pub coords: Vec<usize>,
}

/// Why a design could not be evaluated on the start design's branch. The
/// fields number co-ordinates from 0; the messages, as a deck does, from 1.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum DesignFailure {
    /// Position 1, or a quantity along the motion, cannot be computed.
    #[error("{0}")]
    Solve(#[from] SolveError),
    /// Position 1 assembles, but only with a group of co-ordinates mirrored
    /// against the start design's.
    #[error(
        "position 1 assembles only on another assembly branch than the start design's: co-ordinates {} lie \
         mirrored (the determinant of their group in D^c has the other sign)",
        numbers(coords)
    )]
    OtherBranch {
        /// The co-ordinates (0-based) of the group whose orientation differs.
        coords: Vec<usize>,
    },
    /// The motion changes branch between two positions.
    #[error(
        "the motion changes assembly branch between positions {} and {}: co-ordinates {} flip to their mirrored \
         assembly (the determinant of their group in D^c changes sign: a limit position jumped over, or a change \
         point where two branches meet)",
        .0.after + 1,
        .0.after + 2,
        numbers(&.0.coords)
    )]
    LeftBranch(BranchChange),
}

/// Co-ordinate indices as the deck numbers them.
fn numbers(coords: &[usize]) -> String {
    coords.iter().map(|i| (i + 1).to_string()).collect::<Vec<_>>().join(", ")
}

/// The start design of an optimisation: what every later evaluation keeps
/// to and predicts position 1 from.
#[derive(Debug, Clone)]
pub struct Anchor {
    values: Vec<f64>,
    /// Its position 1, converged, with its angle memory.
    state: State,
    /// dx/dp at position 1, variable v's column at `slope[v * N..]`.
    slope: Vec<f64>,
    orientation: Orientation,
}

impl Anchor {
    /// The orientation of the start design's position 1.
    pub fn orientation(&self) -> &Orientation {
        &self.orientation
    }
}

/// An optimisation's model, motion and what every evaluation records.
#[derive(Debug, Clone, Copy)]
pub struct Design<'a> {
    /// The model.
    pub mech: &'a Mechanism,
    /// Its state as compiled: the co-ordinates given and the prescribed values.
    pub base: &'a State,
    /// The motion every design runs.
    pub motion: &'a Motion,
    /// The position analysis' tuning.
    pub params: &'a Params,
    /// The design variables.
    pub vars: &'a [DesignVar],
    /// The quantities recorded at every position.
    pub quantities: &'a [Quantity],
    /// The extrema located.
    pub extrema: &'a [ExtremumSpec],
}

impl Design<'_> {
    /// Evaluates the start design `values` from the given co-ordinates: its
    /// run, and the anchor of every later evaluation.
    pub fn start(&self, values: &[f64]) -> Result<(DesignRun, Anchor), DesignFailure> {
        let mut state = self.with_values(self.base.clone(), values);
        let (mut kin, mut dets) = (self.workspace(), Vec::new());
        let orientation = self.assemble(&mut state, &mut kin, &mut dets)?;
        let one = state.clone();
        let run = self.run(state)?;
        let anchor = Anchor { values: values.to_vec(), state: one, slope: run.slope_one.clone(), orientation };
        Ok((run, anchor))
    }

    /// Evaluates the design `values` on the branch of `anchor`.
    pub fn evaluate(&self, anchor: &Anchor, values: &[f64]) -> Result<DesignRun, DesignFailure> {
        let (mut kin, mut dets) = (self.workspace(), Vec::new());
        let mut first_error = None;
        let mut mirrored = None;
        let mut note = |found: Result<Orientation, SolveError>, kin: &Kinematics| match found {
            Ok(o) => match o.reversed(&anchor.orientation) {
                None => true,
                Some(b) => {
                    mirrored.get_or_insert_with(|| block_coords(self.mech, kin, b));
                    false
                }
            },
            Err(e) => {
                first_error.get_or_insert(e);
                false
            }
        };
        // The start design's position 1 moved by its sensitivities, then as it is.
        for predicted in [true, false] {
            let mut state = self.towards(anchor, values, 1.0, predicted);
            let found = self.assemble(&mut state, &mut kin, &mut dets);
            if note(found, &kin) {
                return self.run(state);
            }
        }
        // A continuation from the start design in stages, each a prediction
        // from the last one assembled on the branch, halved when it fails.
        let mut at = anchor.state.clone();
        let (mut lambda, mut h) = (0.0f64, 0.25f64);
        // Each stage may need the adjustment's own continuation: a few
        // halvings, not the motion's many.
        let min_h = 1.0 / 64.0;
        while lambda < 1.0 {
            let next = (lambda + h).min(1.0);
            let mut state = self.towards(anchor, values, next, true);
            for &i in self.mech.moving_coords() {
                state.x[i] += at.x[i] - self.towards_x(anchor, values, lambda, i);
            }
            state.branch.clone_from(&at.branch);
            let found = self.assemble(&mut state, &mut kin, &mut dets);
            if note(found, &kin) {
                (at, lambda) = (state, next);
                h *= 2.0;
            } else {
                h *= 0.5;
                if h < min_h {
                    break;
                }
            }
        }
        if lambda == 1.0 {
            return self.run(at);
        }
        // Every attempt either assembled on another branch or failed.
        Err(match (mirrored, first_error) {
            (Some(coords), _) => DesignFailure::OtherBranch { coords },
            (None, e) => DesignFailure::Solve(e.unwrap_or(SolveError::NotComputed)),
        })
    }

    /// The run from a converged position 1; a motion that leaves its branch
    /// fails.
    fn run(&self, mut state: State) -> Result<DesignRun, DesignFailure> {
        let d = self;
        let run = evaluate(d.mech, &mut state, d.motion, d.params, d.vars, d.quantities, d.extrema)?;
        match &run.left_branch {
            Some(change) => Err(DesignFailure::LeftBranch(change.clone())),
            None => Ok(run),
        }
    }

    /// `state` with the design's values in it.
    fn with_values(&self, mut state: State, values: &[f64]) -> State {
        for (v, &x) in self.vars.iter().zip(values) {
            match *v {
                DesignVar::Row(r) => state.target[r] = x,
                DesignVar::Fixed(i) => state.x[i] = x,
            }
        }
        state
    }

    /// The design a fraction `lambda` of the way from the start design to
    /// `values`, its position 1 predicted from the start design's (moved by
    /// the sensitivities when `predicted`).
    fn towards(&self, anchor: &Anchor, values: &[f64], lambda: f64, predicted: bool) -> State {
        let design: Vec<f64> = if lambda == 1.0 {
            values.to_vec()
        } else {
            // Weighted, so that the ends are exact and no difference overflows.
            anchor.values.iter().zip(values).map(|(a, b)| (1.0 - lambda) * a + lambda * b).collect()
        };
        let mut state = self.with_values(anchor.state.clone(), &design);
        if predicted {
            for &i in self.mech.moving_coords() {
                state.x[i] = self.towards_x(anchor, values, lambda, i);
            }
        }
        state
    }

    /// Moving co-ordinate i predicted a fraction `lambda` of the way.
    fn towards_x(&self, anchor: &Anchor, values: &[f64], lambda: f64, i: usize) -> f64 {
        let nc = self.mech.n_coords();
        let mut x = anchor.state.x[i];
        for (v, (a, b)) in anchor.values.iter().zip(values).enumerate() {
            x += anchor.slope[v * nc + i] * lambda * (b - a);
        }
        x
    }

    /// A workspace of the storage a run uses for this motion, so that the
    /// orientations compare with those of the run.
    fn workspace(&self) -> Kinematics {
        if self.motion.inputs.iter().any(|m| matches!(m, InputMotion::Free { .. })) {
            Kinematics::dense(self.mech)
        } else {
            Kinematics::new(self.mech)
        }
    }

    /// Assembles position 1 from the state's co-ordinates as a run does,
    /// and returns its orientation.
    fn assemble(
        &self,
        state: &mut State,
        kin: &mut Kinematics,
        dets: &mut Vec<f64>,
    ) -> Result<Orientation, SolveError> {
        self.motion.apply_initial_inputs(self.mech, state);
        adjust(self.mech, state, kin, self.params)?;
        kin.transfer(self.mech, state, TransferOrder::First)?;
        Ok(Orientation::of(kin, dets))
    }
}
