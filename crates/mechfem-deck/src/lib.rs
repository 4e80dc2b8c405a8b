//! The keyword deck of mechfem: text in, a checked core model out.
//!
//! This crate reads the deck language of the classic RUNMEC program
//! (`KIN ANA`, then the blocks TOPOLOGY, GEOMETRY, MOVEMENT, STORAGE) and
//! turns it into what [`mechfem_core`] runs. It does **not** solve anything:
//! no Newton iteration, no transfer functions, no output files. It only
//! reads, checks and translates, and says precisely what is wrong when a
//! deck does not fit.
//!
//! A tour, in the order data flows:
//!
//! * [`parse_file`] / [`parse_str`]: text to a typed [`Deck`]. The lexer
//!   splits lines at blanks and tabs, drops `;` comments and reads Fortran
//!   numbers (`-3.d-2`, `1.5D0`, `.5`); a line that starts with a number
//!   repeats the previous keyword of its block, and a keyword alone on its
//!   line (as `FORM` in the theory's tables) waits for such lines. What one
//!   line can tell on its own is checked here.
//! * [`compile`]: a [`Deck`] to a [`Compiled`] model: the core
//!   [`mechfem_core::Mechanism`] and [`mechfem_core::State`] (PARA values in
//!   `state.target`), the [`mechfem_core::Motion`] (MOV_FUNC files read
//!   relative to the deck's folder), solver [`mechfem_core::Params`], the
//!   output [`Buffer`]s, lists and [`Picture`]s, and a description of the
//!   elements and rows for echoing the model. References between lines are
//!   checked here.
//! * [`load`]: both steps for a file.
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
//! let err = mechfem_deck::parse_str("KIN ANA\nTOPOLOGY\nELEM 1 BNI 1 2 3 4\n", "x.mec").unwrap_err();
//! assert!(err.to_string().starts_with("error: unknown element type `BNI`"));
//! ```

mod args;
pub mod ast;
mod compile;
mod compiled;
mod diagnostic;
mod keywords;
mod lexer;
mod parse;
mod statements;

use std::path::Path;

pub use ast::Deck;
pub use compile::compile;
pub use compiled::{Buffer, Compiled, ElementInfo, Picture, PlotItem, RowInfo, TermInfo};
pub use diagnostic::{Diagnostic, DiagnosticKind, Diagnostics, Span, Spanned};
pub use keywords::{Block, Keyword};
pub use parse::{parse_file, parse_str};

/// Reads, checks and compiles the deck at `path`; MOV_FUNC files are read
/// from the deck's folder.
pub fn load(path: impl AsRef<Path>) -> Result<Compiled, Diagnostics> {
    let path = path.as_ref();
    let deck = parse_file(path)?;
    let dir = path.parent().filter(|p| !p.as_os_str().is_empty()).unwrap_or(Path::new("."));
    compile(&deck, dir)
}
