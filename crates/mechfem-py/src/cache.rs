//! Compiled decks kept between calls of `run_deck` and `check_deck`: a deck
//! file run again unchanged is not parsed or compiled again.
//!
//! A deck is known by its path and its whole text, read on every call (a
//! few microseconds for a deck): any edit is seen, whatever the file's time
//! stamp says, and no two texts can be taken for one another. A deck that
//! reads MOV_FUNC or LOADFUNC tables from other files is not kept: those
//! files could change without the deck.

use std::path::{Path, PathBuf};
use std::sync::Mutex;

use mechfem_deck::ast::{Deck, LoadDefKind, MotionKind};
use mechfem_deck::{Compiled, Diagnostic, DiagnosticKind, Diagnostics};

/// How many compiled decks are kept (the least recently used goes first).
const CAPACITY: usize = 16;

/// What identifies one version of a deck file: its path and its text.
#[derive(PartialEq, Eq, Clone)]
struct Key {
    path: PathBuf,
    text: Vec<u8>,
}

/// The kept decks, most recently used last.
static KEPT: Mutex<Vec<(Key, Compiled)>> = Mutex::new(Vec::new());

/// Whether the deck reads tables from other files.
fn reads_files(deck: &Deck) -> bool {
    let motion =
        deck.movement.as_ref().is_some_and(|m| m.motions.iter().any(|md| matches!(md.kind, MotionKind::Function(_))));
    let loads =
        deck.dynamics.as_ref().is_some_and(|d| d.loads.iter().any(|l| matches!(l.kind, LoadDefKind::Function(_))));
    motion || loads
}

/// Reads and compiles the deck at `path`, or returns a copy of the deck
/// compiled from the same text before (as [`mechfem_deck::load`] would
/// compile it).
pub fn load(path: &Path) -> Result<Compiled, Diagnostics> {
    let io = |e: std::io::Error| -> Diagnostics {
        Diagnostic::file(DiagnosticKind::Io, path, format!("cannot read the deck: {e}")).into()
    };
    let key = Key { path: path.to_path_buf(), text: std::fs::read(path).map_err(io)? };
    {
        let mut kept = KEPT.lock().unwrap_or_else(|e| e.into_inner());
        if let Some(k) = kept.iter().position(|(k, _)| *k == key) {
            let entry = kept.remove(k);
            let compiled = entry.1.clone();
            kept.push(entry);
            return Ok(compiled);
        }
    }
    let deck = mechfem_deck::parse_str(&String::from_utf8_lossy(&key.text), path)?;
    let dir = path.parent().filter(|p| !p.as_os_str().is_empty()).unwrap_or(Path::new("."));
    let compiled = mechfem_deck::compile(&deck, dir)?;
    if !reads_files(&deck) {
        let mut kept = KEPT.lock().unwrap_or_else(|e| e.into_inner());
        kept.retain(|(k, _)| k.path != key.path);
        if kept.len() >= CAPACITY {
            kept.remove(0);
        }
        kept.push((key, compiled.clone()));
    }
    Ok(compiled)
}
