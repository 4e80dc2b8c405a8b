//! Files a deck names as input (MOV_FUNC, LOADFUNC, TARGET) are read as
//! data only: a folder, a pipe, a device, a binary file, a file too large or
//! with too many lines is refused with a diagnostic at the deck's line, and
//! never read without bound.

use std::path::{Path, PathBuf};
use std::sync::mpsc;
use std::time::Duration;

use mechfem_deck::{load, DiagnosticKind};

/// The golden deck `name` with its table file `from` renamed `to`, written
/// into `dir`; returns the deck's path.
fn deck_naming(dir: &Path, name: &str, from: &str, to: &str) -> PathBuf {
    let text = std::fs::read_to_string(Path::new("tests/decks/invalid").join(name)).expect("golden deck");
    assert!(text.contains(from), "{name} names no {from}");
    let path = dir.join(name);
    std::fs::write(&path, text.replace(from, to)).expect("deck");
    path
}

/// The MOV_FUNC, LOADFUNC and TARGET decks, each naming `file`.
fn decks_naming(dir: &Path, file: &str) -> Vec<(PathBuf, DiagnosticKind)> {
    vec![
        (deck_naming(dir, "mov_func_not_a_file.mec", "/dev/zero", file), DiagnosticKind::MotionFile),
        (deck_naming(dir, "loadfunc_not_a_file.mec", "/dev/zero", file), DiagnosticKind::LoadFile),
        (deck_naming(dir, "opt_target_missing_file.mec", "no_such_target.dat", file), DiagnosticKind::TargetFile),
    ]
}

/// The first diagnostic of the deck at `path`, given within ten seconds.
fn refusal(path: &Path) -> (DiagnosticKind, String, usize) {
    let (send, receive) = mpsc::channel();
    let owned = path.to_path_buf();
    std::thread::spawn(move || {
        let e = load(&owned).expect_err("should be refused");
        let d = &e.0[0];
        send.send((d.kind, d.message.clone(), d.line)).ok();
    });
    receive.recv_timeout(Duration::from_secs(10)).unwrap_or_else(|_| panic!("{} hangs", path.display()))
}

/// A fresh folder for files a test writes.
fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("mechfem-input-{}-{name}", std::process::id()));
    std::fs::remove_dir_all(&dir).ok();
    std::fs::create_dir_all(&dir).expect("scratch folder");
    dir
}

#[test]
fn a_pipe_named_as_a_table_is_refused_without_waiting_for_a_writer() {
    let dir = scratch("fifo");
    let fifo = dir.join("table.fifo");
    let made = std::process::Command::new("mkfifo").arg(&fifo).status().expect("mkfifo");
    assert!(made.success());
    for (deck, kind) in decks_naming(&dir, "table.fifo") {
        let (got, message, line) = refusal(&deck);
        assert_eq!(got, kind, "{message}");
        assert!(message.ends_with("it is not a regular file"), "{message}");
        assert!(line > 0);
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_device_named_as_a_table_is_refused() {
    let dir = scratch("device");
    for device in ["/dev/zero", "/dev/urandom", "/dev/null"] {
        for (deck, kind) in decks_naming(&dir, device) {
            let (got, message, _) = refusal(&deck);
            assert_eq!(got, kind, "{message}");
            assert!(message.ends_with("it is not a regular file"), "{message}");
        }
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_folder_named_as_a_table_is_refused() {
    let dir = scratch("folder");
    std::fs::create_dir_all(dir.join("tables")).expect("folder");
    for (deck, kind) in decks_naming(&dir, "tables") {
        let (got, message, _) = refusal(&deck);
        assert_eq!(got, kind, "{message}");
        assert!(message.ends_with("it is a folder"), "{message}");
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_binary_file_named_as_a_table_is_refused() {
    let dir = scratch("binary");
    std::fs::write(dir.join("table.bin"), b"0 1\n\x7fELF\x02\x01\x01\x00\x00\x00\n").expect("binary");
    for (deck, kind) in decks_naming(&dir, "table.bin") {
        let (got, message, _) = refusal(&deck);
        assert_eq!(got, kind, "{message}");
        assert!(message.contains("is a binary file, not a table of numbers"), "{message}");
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_table_file_larger_than_the_limit_is_refused_before_reading() {
    let dir = scratch("huge");
    // A sparse file: 65 MiB long, but nothing is written (nor read).
    std::fs::File::create(dir.join("huge.dat")).expect("file").set_len(65 << 20).expect("length");
    for (deck, kind) in decks_naming(&dir, "huge.dat") {
        let (got, message, _) = refusal(&deck);
        assert_eq!(got, kind, "{message}");
        // LOADFUNC has a smaller limit of its own.
        assert!(message.ends_with("MiB") && message.contains("is larger than"), "{message}");
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_table_file_of_more_lines_than_the_limit_is_refused() {
    let dir = scratch("lines");
    std::fs::write(dir.join("long.dat"), "\n".repeat(2_000_001)).expect("long table");
    for (deck, kind) in decks_naming(&dir, "long.dat") {
        let (got, message, _) = refusal(&deck);
        assert_eq!(got, kind, "{message}");
        assert!(message.ends_with("has 2000001 lines, more than 2000000"), "{message}");
    }
    std::fs::remove_dir_all(&dir).ok();
}
