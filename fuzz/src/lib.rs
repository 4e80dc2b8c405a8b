//! What the fuzz targets share: the deck generator and the checks of
//! `crates/mechfem-deck/tests/support` (the property tests' own, included
//! by path), and the folder MOV_FUNC files are read from.

use std::path::{Path, PathBuf};

#[path = "../../crates/mechfem-deck/tests/support/mod.rs"]
pub mod support;

pub use support::{check_deck, compile_text, deck, Bytes, Choose, Outcome, FUZZ_MAX_STEPS as MAX_STEPS};

/// The folder MOV_FUNC file names are relative to: the hostile test decks,
/// which hold a few motion files (`crank.dat`, `table.dat`, `bad_motion.dat`).
pub fn deck_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../crates/mechfem-deck/tests/decks/hostile")
}

/// Prints the deck under test to standard error when `MECHFEM_FUZZ_PRINT`
/// is set (to see what a crash input of `deck_grammar` stands for).
pub fn show(text: &str) {
    if std::env::var_os("MECHFEM_FUZZ_PRINT").is_some() {
        eprintln!("----- deck -----\n{text}----------------");
    }
}
