//! Compiled decks kept between calls of `run_deck` and `check_deck`: a deck
//! file run again unchanged is not parsed or compiled again.
//!
//! A deck is known by its path and its whole text, so that no two texts
//! can be taken for one another. Reading the text again costs a few
//! microseconds, most of a short run's call, so a call first asks the file
//! system for the file's [`Stamp`] (size, inode, modification and change
//! times): the same stamp as when the kept text was read means the same
//! text, and the file is not read. A time stamp is only as fine as the
//! kernel's clock tick, so a file changed less than [`SETTLED`] before it
//! was read might change again with the same stamp: its stamp is not kept,
//! and its text is read and compared on every call until it has settled
//! (git's rule for "racily clean" files). A deck that reads MOV_FUNC or
//! LOADFUNC tables from other files is not kept: those files could change
//! without the deck.
//!
//! Beside each kept deck sits its [`Echo`]: the model echo and storage
//! requests as Python was given them after a run. They depend only on the
//! deck and on its position 1, so a run of the same text that reaches the
//! same position 1 hands Python the very same objects again, and Python
//! converts them once (`mechfem.results.result` keeps what it made of them). So
//! does the layout of its runs' tables, which depends on the deck alone.

use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};
use std::time::{Duration, SystemTime};

use pyo3::prelude::*;

use mechfem_deck::ast::{Deck, LoadDefKind, MotionKind};
use mechfem_deck::{Compiled, Diagnostics};

use crate::echo::EchoModel;
use crate::report::Report;

/// How many compiled decks are kept (the least recently used goes first).
const CAPACITY: usize = 16;

/// What identifies one version of a deck file: its path and its text.
#[derive(PartialEq, Eq, Clone)]
struct Key {
    path: PathBuf,
    text: Vec<u8>,
}

/// How long before it was read a file must have been changed last for its
/// [`Stamp`] to stand for its text: longer than any file system's time
/// stamp granularity (FAT's two seconds included).
const SETTLED: Duration = Duration::from_secs(3);

/// What the file system says of a deck file: a file with the same stamp
/// has the same text, once it has settled ([`Stamp::of`]).
#[derive(PartialEq, Eq, Clone, Copy)]
struct Stamp {
    len: u64,
    device: u64,
    inode: u64,
    modified: (i64, i64),
    changed: (i64, i64),
}

impl Stamp {
    /// The stamp of the regular file at `path`, or `None` when it has none
    /// (no such file, not a regular one, or a system without inodes).
    #[cfg(unix)]
    fn of(path: &Path) -> Option<(Stamp, SystemTime)> {
        use std::os::unix::fs::MetadataExt;
        let m = std::fs::metadata(path).ok().filter(|m| m.is_file())?;
        let stamp = Stamp {
            len: m.len(),
            device: m.dev(),
            inode: m.ino(),
            modified: (m.mtime(), m.mtime_nsec()),
            changed: (m.ctime(), m.ctime_nsec()),
        };
        Some((stamp, m.modified().ok()?))
    }

    #[cfg(not(unix))]
    fn of(_path: &Path) -> Option<(Stamp, SystemTime)> {
        None
    }

    /// The stamp of a file read now, if it may stand for the text read:
    /// only once the file has settled.
    fn settled(seen: Option<(Stamp, SystemTime)>) -> Option<Stamp> {
        let (stamp, modified) = seen?;
        let age = SystemTime::now().duration_since(modified).ok()?;
        (age >= SETTLED).then_some(stamp)
    }
}

/// What Python was given for a deck's model and storage, and the numbers
/// of position 1 they were made from (bit patterns: equal means identical).
pub struct Echo {
    position_1: Vec<u64>,
    model: Py<EchoModel>,
    storage: Py<PyAny>,
}

/// The echo of one kept deck, filled after its first run, the report of
/// its last run that met nothing to report (see [`EchoSlot::report`]), and
/// what its runs' dicts hold that depends on the deck alone
/// ([`EchoSlot::shape`]).
#[derive(Default)]
pub struct EchoSlot(Mutex<Option<Echo>>, Mutex<Option<(Vec<u64>, Py<Report>)>>, Mutex<Option<[Py<PyAny>; 3]>>);

impl EchoSlot {
    /// The model echo and storage dicts for a run whose position 1 is
    /// `position_1`: the kept ones when they were made from the same
    /// numbers, else those `make` builds (then kept).
    pub fn get_or_make<'py>(
        &self,
        py: Python<'py>,
        position_1: &[&[f64]],
        make: impl FnOnce() -> PyResult<(Bound<'py, EchoModel>, Bound<'py, PyAny>)>,
    ) -> PyResult<(Bound<'py, EchoModel>, Bound<'py, PyAny>)> {
        let bits: Vec<u64> = position_1.iter().flat_map(|s| s.iter().map(|v| v.to_bits())).collect();
        let lock = || self.0.lock().unwrap_or_else(|e| e.into_inner());
        if let Some(e) = lock().as_ref().filter(|e| e.position_1 == bits) {
            return Ok((e.model.bind(py).clone(), e.storage.bind(py).clone()));
        }
        // Made without the lock held: making them runs Python code.
        let (model, storage) = make()?;
        *lock() = Some(Echo { position_1: bits, model: model.clone().unbind(), storage: storage.clone().unbind() });
        Ok((model, storage))
    }

    /// The report of a run that met no limit position and did not
    /// stop, described by `numbers` (its adjustment, positions and steps,
    /// as bit patterns): the one given for the last such run with the same
    /// numbers, else the one `make` builds (then kept). Such a report holds
    /// nothing but those numbers, so Python converts it once too.
    pub fn report<'py>(
        &self,
        py: Python<'py>,
        numbers: Vec<u64>,
        make: impl FnOnce() -> PyResult<Bound<'py, Report>>,
    ) -> PyResult<Bound<'py, Report>> {
        let lock = || self.1.lock().unwrap_or_else(|e| e.into_inner());
        if let Some((_, d)) = lock().as_ref().filter(|(k, _)| *k == numbers) {
            return Ok(d.bind(py).clone());
        }
        let d = make()?;
        *lock() = Some((numbers, d.clone().unbind()));
        Ok(d)
    }

    /// The objects of a run that depend on the deck alone (its
    /// layout and numbers of buffers and co-ordinates): those of the last
    /// run, else those `make` builds (then kept). Every run of the deck
    /// shares them, and Python converts them once.
    pub fn shape<'py>(
        &self,
        py: Python<'py>,
        make: impl FnOnce() -> PyResult<[Bound<'py, PyAny>; 3]>,
    ) -> PyResult<[Bound<'py, PyAny>; 3]> {
        let lock = || self.2.lock().unwrap_or_else(|e| e.into_inner());
        if let Some(kept) = lock().as_ref() {
            return Ok(kept.each_ref().map(|o| o.bind(py).clone()));
        }
        let made = make()?;
        *lock() = Some(made.each_ref().map(|o| o.clone().unbind()));
        Ok(made)
    }
}

/// A kept deck: its key, the compiled deck, the echo of its runs, and the
/// stamp of its file when it had settled.
type Entry = (Key, Arc<Compiled>, Arc<EchoSlot>, Option<Stamp>);

/// The kept decks, most recently used last.
static KEPT: Mutex<Vec<Entry>> = Mutex::new(Vec::new());

/// Whether the deck reads tables from other files.
fn reads_files(deck: &Deck) -> bool {
    let motion =
        deck.movement.as_ref().is_some_and(|m| m.motions.iter().any(|md| matches!(md.kind, MotionKind::Function(_))));
    let loads =
        deck.dynamics.as_ref().is_some_and(|d| d.loads.iter().any(|l| matches!(l.kind, LoadDefKind::Function(_))));
    motion || loads
}

/// The kept deck `k`, made the most recently used, its stamp now `stamp`.
fn used(kept: &mut Vec<Entry>, k: usize, stamp: Option<Stamp>) -> (Arc<Compiled>, Arc<EchoSlot>) {
    let mut entry = kept.remove(k);
    entry.3 = stamp;
    let found = (entry.1.clone(), entry.2.clone());
    kept.push(entry);
    found
}

/// Reads and compiles the deck at `path` (as [`mechfem_deck::load`] would
/// compile it), or shares the deck compiled from the same text before, with
/// the echo slot of that text (a slot of its own for a deck that is not
/// kept).
pub fn load(path: &Path) -> Result<(Arc<Compiled>, Arc<EchoSlot>), Diagnostics> {
    // Asked before the text is read: a change after this is seen next time.
    let seen = Stamp::of(path);
    let mut kept = KEPT.lock().unwrap_or_else(|e| e.into_inner());
    let unchanged = seen.map(|(stamp, _)| stamp);
    if let Some(k) = kept.iter().position(|(k, .., s)| s.is_some() && *s == unchanged && k.path == path) {
        return Ok(used(&mut kept, k, unchanged));
    }
    drop(kept);
    let key = Key { path: path.to_path_buf(), text: mechfem_deck::read_deck(path)?.into_bytes() };
    let stamp = Stamp::settled(seen);
    {
        let mut kept = KEPT.lock().unwrap_or_else(|e| e.into_inner());
        if let Some(k) = kept.iter().position(|(k, ..)| *k == key) {
            return Ok(used(&mut kept, k, stamp));
        }
    }
    let deck = mechfem_deck::parse_str(&String::from_utf8_lossy(&key.text), path)?;
    let dir = path.parent().filter(|p| !p.as_os_str().is_empty()).unwrap_or(Path::new("."));
    let compiled = Arc::new(mechfem_deck::compile(&deck, dir)?);
    let slot = Arc::new(EchoSlot::default());
    if !reads_files(&deck) {
        let mut kept = KEPT.lock().unwrap_or_else(|e| e.into_inner());
        kept.retain(|(k, ..)| k.path != key.path);
        if kept.len() >= CAPACITY {
            kept.remove(0);
        }
        kept.push((key, compiled.clone(), slot.clone(), stamp));
    }
    Ok((compiled, slot))
}
