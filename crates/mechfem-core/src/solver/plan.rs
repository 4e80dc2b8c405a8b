//! D^c's storage for a mechanism, and where every prescribed term's
//! gradient goes in it: what every workspace ([`Kinematics`]) of the
//! mechanism starts from.
//!
//! Choosing the storage (blocks, band or dense, with their orderings) costs
//! a run of the four-bar about 1.5 µs, a sixth of a run of eight positions,
//! and depends on D^c's structure alone. So the plans made on a thread are
//! kept there, each under the structure it was made for, and a workspace of
//! a mechanism with that structure clones its plan: the runs of one
//! mechanism, of its variants in a design study or of an optimiser's
//! designs choose the storage once per thread. The model itself stays
//! plain data.
//!
//! [`Kinematics`]: super::Kinematics

use super::assemble::{dc_pattern, dc_positions, writes_every_place_once};
use super::lu::Lu;
use crate::elements::{ElementType, MAX_COORDS};
use crate::model::Mechanism;
use std::cell::RefCell;

/// D^c's storage as [`Lu::for_pattern`] chose it for a mechanism, and where
/// each prescribed term's gradient goes in it.
#[derive(Debug, Clone)]
pub(crate) struct DcPlan {
    pub(crate) lu: Lu,
    pub(crate) dc_pos: Vec<[usize; MAX_COORDS]>,
    /// Whether the gradients write every place of `lu` once.
    pub(crate) overwrite: bool,
}

impl DcPlan {
    /// The plan of `mech`'s D^c, from the plans kept on this thread when
    /// one was made for its structure, made (and kept) otherwise.
    pub(crate) fn of(mech: &Mechanism) -> DcPlan {
        KEPT.with(|kept| {
            let mut kept = kept.borrow_mut();
            if let Some(k) = kept.iter().position(|p| p.fits(mech)) {
                // The latest used first, so that the oldest is dropped.
                kept[..=k].rotate_right(1);
                return kept[0].plan.clone();
            }
            let plan = DcPlan::for_lu(mech, Lu::for_pattern(mech.n_moving(), &dc_pattern(mech)));
            kept.truncate(KEEP - 1);
            kept.insert(0, Kept { n: mech.n_moving(), entries: entries(mech).collect(), plan: plan.clone() });
            plan
        })
    }

    /// The plan for storage `lu` (which must hold D^c's pattern).
    pub(crate) fn for_lu(mech: &Mechanism, lu: Lu) -> DcPlan {
        let dc_pos = dc_positions(mech, &lu);
        let overwrite = writes_every_place_once(&dc_pos, lu.values().len());
        DcPlan { lu, dc_pos, overwrite }
    }
}

/// How many plans a thread keeps.
const KEEP: usize = 4;

thread_local! {
    /// The plans made on this thread, the one used last first.
    static KEPT: RefCell<Vec<Kept>> = const { RefCell::new(Vec::new()) };
}

/// A plan and the structure of D^c it was made for: the number of moving
/// co-ordinates and the [`Entry`] of every prescribed term, everything the
/// plan is made from.
#[derive(Debug)]
struct Kept {
    n: usize,
    entries: Vec<Entry>,
    plan: DcPlan,
}

/// Where a prescribed term's gradient enters D^c: its row, its element's
/// type and its form parameter (which of the element's co-ordinates it
/// depends on), and the column of D^c of each of the element's
/// co-ordinates. Read straight from the compiled rows, so that finding a
/// kept plan costs a run a comparison of a few numbers per term.
type Entry = (usize, ElementType, usize, [usize; MAX_COORDS]);

impl Kept {
    /// Whether `mech`'s D^c has the structure this plan was made for.
    fn fits(&self, mech: &Mechanism) -> bool {
        self.n == mech.n_moving()
            && self.entries.len() == mech.prescribed.terms().len()
            && entries(mech).eq(self.entries.iter().copied())
    }
}

/// The [`Entry`] of every prescribed term of `mech`, in order.
fn entries(mech: &Mechanism) -> impl Iterator<Item = Entry> + '_ {
    let rows = &mech.prescribed;
    rows.row_of().iter().zip(rows.terms()).zip(rows.slots()).map(|((&row, t), s)| (row, s.ty, t.form, s.cols))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::elements::ElementType;
    use crate::model::{MechanismBuilder, Term};

    /// A serial chain of `n` bars from a fixed point, each `length` long,
    /// with every bar's length and angle prescribed (the last angle is the
    /// input); as a `star`, every bar starts at the fixed point, so that
    /// D^c is of the same size but without the entries that tie each bar
    /// to the one before.
    fn chain(n: usize, length: f64, star: bool) -> Mechanism {
        let mut b = MechanismBuilder::new();
        let origin = [b.fixed(0.0), b.fixed(0.0)];
        let mut p = origin;
        for k in 0..n {
            let q = [b.moving(length * (k + 1) as f64), b.moving(0.1 * k as f64)];
            let bar = b.element(ElementType::Bin, &[p[0], p[1], q[0], q[1]]);
            b.prescribe(&[Term::new(bar, 0)]);
            if k + 1 == n {
                b.input(&[Term::new(bar, 1)]);
            } else {
                b.prescribe(&[Term::new(bar, 1)]);
            }
            p = if star { origin } else { q };
        }
        b.build().unwrap().0
    }

    /// The plan made afresh, as if none were kept.
    fn made(mech: &Mechanism) -> DcPlan {
        DcPlan::for_lu(mech, Lu::for_pattern(mech.n_moving(), &dc_pattern(mech)))
    }

    /// The same plan: the same storage with its orderings, and the same
    /// places of the terms in it.
    fn assert_same(a: &DcPlan, b: &DcPlan) {
        assert_eq!(format!("{a:?}"), format!("{b:?}"));
    }

    #[test]
    fn a_kept_plan_is_the_plan_of_its_structure() {
        // More structures than a thread keeps, of equal sizes in pairs, twice
        // through: plans are found, made again and dropped on the way.
        let mechs: Vec<Mechanism> = (1..=KEEP).flat_map(|n| [chain(n, 1.0, false), chain(n, 1.0, true)]).collect();
        assert_ne!(format!("{:?}", made(&mechs[2])), format!("{:?}", made(&mechs[3])), "the pair differs");
        for _ in 0..2 {
            for m in &mechs {
                assert_same(&DcPlan::of(m), &made(m));
            }
        }
        KEPT.with(|k| assert_eq!(k.borrow().len(), KEEP));
    }

    #[test]
    fn mechanisms_of_one_structure_share_a_plan() {
        let (a, b) = (chain(3, 1.0, false), chain(3, 2.5, false));
        let kept = || KEPT.with(|k| k.borrow().len());
        let before = kept();
        assert_same(&DcPlan::of(&a), &made(&a));
        assert_eq!(kept(), before + 1);
        assert_same(&DcPlan::of(&b), &made(&b));
        assert_eq!(kept(), before + 1, "a variant of other dimensions made a plan of its own");
    }
}
