//! A typed [`Deck`] to a runnable [`Compiled`]: cross-references between
//! lines are checked here, and the core model is built.

mod coordinates;
mod design;
mod dynamics;
mod model;
mod motion;
mod names;
mod optimise;
mod refs;
mod rows;
mod storage;
mod table;

use std::path::Path;

use crate::ast::Deck;
use crate::compiled::Compiled;
use crate::diagnostic::Diagnostics;

/// Compiles a parsed deck. `deck_dir` is the folder MOV_FUNC, LOADFUNC and
/// TARGET file names are relative to (the deck's own folder).
///
/// Checks every reference between lines (co-ordinates, elements, rows,
/// DOFs, buffers, positions), reads MOV_FUNC, LOADFUNC and TARGET files,
/// and builds the core model, for `DYN ANA` and `DYN SIM` its masses and
/// loads, and for `KIN OPT` its optimisation problem; the first mistake
/// found is returned.
pub fn compile(deck: &Deck, deck_dir: &Path) -> Result<Compiled, Diagnostics> {
    let m = model::model(deck)?;
    let sizes = refs::Sizes::of(&m.mechanism);
    let dynamics = dynamics::dynamics(deck, &m.mechanism, &sizes, deck_dir)?;
    let (motion, mut params) = motion::motion(deck, sizes.n_dof, deck_dir)?;
    let mut integration = motion::integration(deck, &mut params);
    if let Some(mo) = &motion {
        motion::check_rates(deck, mo, &m.mechanism, &m.state)?;
    }
    let out = storage::outputs(deck, &sizes)?;
    integration.stop_when = motion::stop_when(deck, &out.buffers)?;
    let optimise = optimise::optimise(deck, &m, &sizes, motion.as_ref(), &out.buffers, deck_dir)?;
    Ok(Compiled {
        mode: deck.mode.value,
        mechanism: m.mechanism,
        state: m.state,
        motion,
        params,
        integration,
        buffers: out.buffers,
        printbuf: out.printbuf,
        savedata: out.savedata,
        animate: out.animate,
        pictures: out.pictures,
        elements: m.elements,
        prescribed: m.prescribed,
        dependent: m.dependent,
        names: m.names,
        dynamics,
        optimise,
    })
}

/// A deck number (1-based, already checked to be positive) as a 0-based index.
fn index(number: i64) -> usize {
    usize::try_from(number - 1).unwrap_or(0)
}
