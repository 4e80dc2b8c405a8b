//! A typed [`Deck`] to a runnable [`Compiled`]: cross-references between
//! lines are checked here, and the core model is built.

mod coordinates;
mod design;
mod designer;
mod dynamics;
mod mass_vary;
mod model;
mod motion;
mod names;
mod optimise;
mod refs;
mod rows;
mod scale;
pub(crate) use scale::inertia_on;
mod storage;
mod synthesis;
mod table;
mod tables;
mod tolerance;
mod warn;
mod written;

use std::path::Path;

use mechfem_core::{ModelDims, Units};

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
    let written = deck;
    let units = deck.units.as_ref().map_or(Units::NONE, |u| u.units);
    // With UNITS, the deck is compiled from a copy in the core's units.
    let core =
        if units.is_identity() { None } else { Some(scale::to_core(deck, units, &model::model(deck)?.mechanism)) };
    let deck = core.as_ref().unwrap_or(deck);
    let m = model::model(deck)?;
    let sizes = refs::Sizes::of(&m.mechanism);
    let (mut dynamics, dynamics_lines) = match dynamics::dynamics(deck, &m.mechanism, &sizes, deck_dir)? {
        Some((d, lines)) => (Some(d), lines),
        None => (None, Vec::new()),
    };
    let (mut motion, mut params) = motion::motion(deck, sizes.n_dof, deck_dir)?;
    let mut integration = motion::integration(deck, &mut params);
    if let Some(mo) = &motion {
        motion::check_rates(deck, mo, &m.mechanism, &m.state)?;
    }
    let mut buffers = storage::buffers(deck, &sizes)?;
    let tolerance = tolerance::tolerance(deck, &m, &sizes, motion.as_ref(), &buffers)?;
    tolerance::record_bands(tolerance.as_ref(), &mut buffers);
    let out = storage::outputs(deck, &sizes, buffers)?;
    integration.stop_when = motion::stop_when(deck, &out.buffers)?;
    let mut optimise =
        optimise::optimise(deck, &m, &sizes, motion.as_ref(), dynamics.as_ref(), &out.buffers, deck_dir)?;
    let dims = match &deck.scale {
        Some(s) => {
            tables::to_core(
                s,
                &m.mechanism,
                motion.as_mut(),
                dynamics.as_mut(),
                &mut integration,
                optimise.as_mut(),
                &out.buffers,
            );
            s.dims.clone()
        }
        None => ModelDims::of(&m.mechanism),
    };
    let counts = [sizes.n_coords, m.elements.len(), sizes.n_prescribed, sizes.n_dependent];
    let names = names::declared(deck, counts, &out.buffers)?;
    let warnings = warn::suspicious(written, &units, &dims, &m.mechanism, &out.buffers);
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
        names,
        units,
        dims,
        warnings,
        dynamics,
        dynamics_lines,
        optimise,
        tolerance,
    })
}

/// The kinds of the co-ordinates and rows of `deck`'s model, as written.
pub(crate) fn dims(deck: &Deck) -> Result<ModelDims, Box<crate::diagnostic::Diagnostic>> {
    Ok(ModelDims::of(&model::model(deck)?.mechanism))
}

/// A deck number (1-based, already checked to be positive) as a 0-based index.
fn index(number: i64) -> usize {
    usize::try_from(number - 1).unwrap_or(0)
}
