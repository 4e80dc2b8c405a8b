//! The keyword deck of mechfem: text in, a checked core model out.
//!
//! This crate reads the deck language of the classic RUNMEC program (the
//! mode `KIN ANA`, `KIN OPT`, `DYN ANA` or `DYN SIM`, then the blocks
//! TOPOLOGY, GEOMETRY, DYNAMICS, MOVEMENT, OPTIMISE, STORAGE, with mechfem's
//! NAMES block and UNITS line) and turns it
//! into what [`mechfem_core`] runs. It does **not** solve anything: no
//! Newton iteration, no transfer functions, no dynamics, no simulation, no
//! optimisation, no output files. It only reads, checks and translates, and
//! says precisely what is wrong when a deck does not fit.
//!
//! A tour, in the order data flows:
//!
//! * [`parse_file`] / [`parse_str`]: text to a typed [`Deck`]. The lexer
//!   splits lines at blanks and tabs, drops a line's `;` comment (comments
//!   mean nothing) and reads Fortran
//!   numbers (`-3.d-2`, `1.5D0`, `.5`); a line that starts with a number
//!   repeats the previous keyword of its block, and a keyword alone on its
//!   line (as `FORM` in the theory's tables) waits for such lines. What one
//!   line can tell on its own (with the mode line) is checked here: a
//!   negative mass, an empty range of a design variable, a DYNAMICS block
//!   in a kinematic deck, an OPTIMISE block outside `KIN OPT`, MOV_FREE in
//!   a `DYN ANA`, `DYN SIM` or `KIN OPT` deck, MOV_DYN or INTTOL outside
//!   `DYN SIM`; so is a block the mode requires (DYNAMICS for both dynamics
//!   modes, MOVEMENT for `DYN SIM` and `KIN OPT`, OPTIMISE for `KIN OPT`).
//! * [`compile`]: a [`Deck`] to a [`Compiled`] model: the core
//!   [`mechfem_core::Mechanism`] and [`mechfem_core::State`] (PARA values in
//!   `state.target`), the [`mechfem_core::Motion`] (MOV_FUNC files read
//!   relative to the deck's folder; a DOF given `MOV_DYN j v0` becomes
//!   [`mechfem_core::InputMotion::Dynamic`], moved by the forces in a
//!   simulation), solver [`mechfem_core::Params`], the integrator's
//!   [`mechfem_core::dynamics::Integration`] (`INTTOL rtol atol`, else both
//!   from ACCURACY), for `DYN ANA` and `DYN SIM` the masses and loads of the
//!   DYNAMICS block as a [`mechfem_core::dynamics::Dynamics`] (LOADFUNC files
//!   read like MOV_FUNC files), for `KIN OPT` the OPTIMISE block as an
//!   [`Optimise`] (design variables as [`mechfem_core::DesignVar`]s,
//!   targets with TARGET files read like MOV_FUNC files, bounds, the
//!   objective), the output [`Buffer`]s of STORAGE and OPTIMISE, lists and
//!   [`Picture`]s, and a description of the elements and rows for echoing
//!   the model, with the [`Names`] of the NAMES block (`POINT 9 10 C`,
//!   `ROW 6 phi`, `DEP 1 psi`, `BUF 30 label`) from which every buffer gets
//!   its label ([`Compiled::label`]). References between lines are checked
//!   here. A deck with a `UNITS LENGTH mm ANGLE deg ...` line is compiled
//!   from a copy of its numbers in the core's units (SI): every number of
//!   the [`Compiled`] is the core's, [`Compiled::units`] and
//!   [`Compiled::dims`] give each output's unit and scale back
//!   ([`Compiled::unit`], [`Compiled::out_scale`]), and a number that looks
//!   like the wrong unit is a warning ([`Compiled::warnings`]).
//! * [`load`]: both steps for a file.
//! * [`DeckBuilder`]: a typed [`Deck`] built item by item by a program that
//!   holds the model in its own objects, compiled by the same [`compile`].
//! * [`Compiled::move_through`]: runs a compiled deck's motion as its mode
//!   says (simulated for `DYN SIM`, kinematically otherwise).
//! * [`rewrite::design_deck`]: a deck's text with new PARA and XFIX/XMOV
//!   values, a `KIN OPT` deck turned into the `KIN ANA` deck of its final
//!   design.
//! * [`Diagnostic`]: every mistake names the file, line and word, renders
//!   like rustc (`error:`, ` --> file:line:col`, the line, a caret, a hint),
//!   and has a [`DiagnosticKind`] for programs.
//!
//! Everything after an `END` line is ignored, as in the classic program.
//!
//! ```
//! let text = "KIN ANA\nTOPOLOGY\nELEM 1 BIN 1 2 3 4\nFORM 1 LENL 1 1\n 2 ANGB 1 2\nNRDOF 1\n\
//!             GEOMETRY\nXFIX 1 0\n 2 0\nXMOV 3 1\n 4 .5\n";
//! let deck = mechfem_deck::parse_str(text, "crank.mec").unwrap();
//! let model = mechfem_deck::compile(&deck, std::path::Path::new(".")).unwrap();
//! assert_eq!(model.mechanism.n_moving(), 2);
//! assert_eq!(model.mechanism.n_dof(), 1);
//!
//! // A pendulum of mass 2 at the end of a bar of length 1, for inverse dynamics.
//! let pendulum = "DYN ANA\nTOPOLOGY\nELEM 1 BIN 1 2 3 4\nFORM 1 LENL 1 1\n 2 ANGB 1 2\nNRDOF 1\n\
//!                 GEOMETRY\nXFIX 1 0\n 2 0\nXMOV 3 1\n 4 0\nDYNAMICS\nMASS 1 2 1 0\nGRAVITY 0 -9.81\n";
//! let deck = mechfem_deck::parse_str(pendulum, "pendulum.mec").unwrap();
//! let model = mechfem_deck::compile(&deck, std::path::Path::new(".")).unwrap();
//! let dynamics = model.dynamics.expect("a DYN ANA deck has dynamics");
//! assert_eq!((dynamics.bodies[0].element, dynamics.bodies[0].mass), (0, 2.0));
//! assert_eq!(dynamics.gravity, [0.0, -9.81]);
//!
//! // The same pendulum released from rest, simulated for 2 s.
//! let released = pendulum.replace("DYN ANA", "DYN SIM") + "MOVEMENT\nTSTEPE 200 0.01\nMOV_DYN 1 0\n";
//! let deck = mechfem_deck::parse_str(&released, "released.mec").unwrap();
//! let model = mechfem_deck::compile(&deck, std::path::Path::new(".")).unwrap();
//! let motion = model.motion.expect("a DYN SIM deck has a motion");
//! assert_eq!(motion.inputs, [mechfem_core::InputMotion::Dynamic { v0: 0.0 }]);
//! assert_eq!(model.integration, mechfem_core::dynamics::Integration::from_accuracy(model.params.tol));
//!
//! // The crank's length as a design variable: the height of its tip at the
//! // last of five positions should be 0.5.
//! let design = text.replace("KIN ANA", "KIN OPT")
//!     + "PARA 1 1\nMOVEMENT\nTSTEPE 4\nMOV_RELE 1 1.5\nOPTIMISE\nVARY 1 0.5 2\nBUFX0 4 1\nTARGETAT 1 5 0.5\n";
//! let deck = mechfem_deck::parse_str(&design, "design.mec").unwrap();
//! let model = mechfem_deck::compile(&deck, std::path::Path::new(".")).unwrap();
//! let optimise = model.optimise.expect("a KIN OPT deck has an optimisation");
//! assert_eq!(optimise.vary[0].var, mechfem_core::DesignVar::Row(0));
//! assert_eq!(optimise.targets[0].kind, mechfem_deck::TargetKind::At { position: 4, value: 0.5 });
//!
//! let err = mechfem_deck::parse_str("KIN ANA\nTOPOLOGY\nELEM 1 BNI 1 2 3 4\n", "x.mec").unwrap_err();
//! assert!(err.to_string().starts_with("error: unknown element type `BNI`"));
//! ```

mod args;
pub mod ast;
mod builder;
mod compile;
mod compiled;
mod design_setup;
mod design_units;
mod diagnostic;
mod dynamic_setup;
mod files;
mod keywords;
mod lexer;
mod numbers;
mod optimise;
mod parse;
pub mod rewrite;
pub mod rewrite_masses;
mod running;
mod statements;
mod tolerance;

use std::path::Path;

pub use ast::{Deck, Mode, NameDef, NameKind, NamesBlock, UnitsDef};
pub use builder::DeckBuilder;
pub use compile::compile;
pub use compiled::{Buffer, Compiled, ElementInfo, Picture, PlotItem, RowInfo, TermInfo};
pub use design_setup::{DesignSetup, DesignSetupError};
pub use design_units::DesignUnits;
pub use diagnostic::{output_name_problem, Diagnostic, DiagnosticKind, Diagnostics, Span, Spanned, MAX_OUTPUT_NAME};
pub use dynamic_setup::{mass_item, DynamicSetup, DynamicSetupError};
pub use files::{read_deck, MAX_DECK_BYTES};
pub use keywords::{Block, Keyword};
pub use mechfem_core::{Names, Units};
pub use numbers::{Change, ChangeKindError, Numbers};
pub use optimise::{
    Bound, FrameAngle, FreeTime, FullRotation, MassItem, MassVary, Objective, Optimise, Reduce, Sense, Target,
    TargetKind, Vary,
};
pub use parse::{parse_file, parse_str};
pub use statements::names::{MAX_LABEL, MAX_NAME};
pub use statements::{MAX_ITER, MAX_STEPS};
pub use tolerance::{without_sensitivity, BandDef, BandsError, EvaluatedBands, Tolerance, Toleranced};

/// Reads, checks and compiles the deck at `path`; MOV_FUNC, LOADFUNC and
/// TARGET files are read from the deck's folder.
pub fn load(path: impl AsRef<Path>) -> Result<Compiled, Diagnostics> {
    let path = path.as_ref();
    let deck = parse_file(path)?;
    let dir = path.parent().filter(|p| !p.as_os_str().is_empty()).unwrap_or(Path::new("."));
    compile(&deck, dir)
}
