//! A typed [`Deck`] to a runnable [`Compiled`]: cross-references between
//! lines are checked here, and the core model is built.

mod coordinates;
mod model;
mod motion;
mod rows;
mod storage;

use std::path::Path;

use crate::ast::Deck;
use crate::compiled::Compiled;
use crate::diagnostic::Diagnostics;

/// Compiles a parsed deck. `deck_dir` is the folder MOV_FUNC file names are
/// relative to (the deck's own folder).
///
/// Checks every reference between lines (co-ordinates, elements, rows,
/// DOFs, buffers), reads MOV_FUNC files, and builds the core model; the
/// first mistake found is returned.
pub fn compile(deck: &Deck, deck_dir: &Path) -> Result<Compiled, Diagnostics> {
    let m = model::model(deck)?;
    let n_dof = m.mechanism.n_dof();
    let (motion, params) = motion::motion(deck, n_dof, deck_dir)?;
    if let Some(mo) = &motion {
        motion::check_rates(deck, mo, &m.mechanism, &m.state)?;
    }
    let sizes = storage::Sizes {
        n_coords: m.mechanism.n_coords(),
        n_prescribed: m.mechanism.n_prescribed(),
        n_dependent: m.mechanism.n_dependent(),
        n_dof,
    };
    let out = storage::outputs(deck, &sizes)?;
    Ok(Compiled {
        mechanism: m.mechanism,
        state: m.state,
        motion,
        params,
        buffers: out.buffers,
        printbuf: out.printbuf,
        savedata: out.savedata,
        animate: out.animate,
        pictures: out.pictures,
        elements: m.elements,
        prescribed: m.prescribed,
        dependent: m.dependent,
    })
}

/// A deck number (1-based, already checked to be positive) as a 0-based index.
fn index(number: i64) -> usize {
    usize::try_from(number - 1).unwrap_or(0)
}
