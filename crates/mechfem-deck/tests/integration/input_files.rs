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

#[test]
fn a_table_file_with_a_byte_order_mark_reads_as_without() {
    let dir = scratch("bom");
    let rows = "; t value velocity\n0.0 0.0 1.0\n1.0 1.0 1.0\n2.0 2.0 1.0\n";
    let mut with_mark = "\u{feff}".to_string();
    with_mark.push_str(rows);
    // A row first, with the mark right before its first number.
    let first_row_marked = format!("\u{feff}{}", &rows[rows.find('\n').unwrap() + 1..]);
    for (name, text) in [("plain.dat", rows.to_string()), ("marked.dat", with_mark), ("row.dat", first_row_marked)] {
        std::fs::write(dir.join(name), text).expect("table");
    }
    let motion = |table: &str| {
        let deck = deck_naming(&dir, "mov_func_bad_row.mec", "bad_motion.dat", table);
        load(&deck).unwrap_or_else(|e| panic!("{table}: {e}")).motion.expect("motion")
    };
    assert_eq!(motion("marked.dat"), motion("plain.dat"));
    assert_eq!(motion("row.dat"), motion("plain.dat"));
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn an_error_in_a_table_file_quotes_only_the_word_at_fault() {
    let dir = scratch("quote");
    let secret = "machine example.com login me password hunter2";
    for (name, text) in [("six.dat", format!("{secret}\n")), ("four.dat", "letters 0 login hunter2\n".to_string())] {
        std::fs::write(dir.join(name), text).expect("table");
        let deck = deck_naming(&dir, "mov_func_bad_row.mec", "bad_motion.dat", name);
        let shown = load(&deck).expect_err("not a table").to_string();
        assert!(!shown.contains("hunter2") && !shown.contains("example.com"), "{shown}");
        assert_eq!(shown.lines().filter(|l| l.starts_with("1 |")).count(), 1, "{shown}");
    }
    let deck = deck_naming(&dir, "mov_func_bad_row.mec", "bad_motion.dat", "four.dat");
    let d = &load(&deck).expect_err("not a table").0[0];
    assert_eq!((d.text.as_str(), d.columns.clone()), ("letters · ····· ·······", 0..7));
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_deck_that_is_a_pipe_or_a_device_is_refused_without_reading_it() {
    let dir = scratch("deck-fifo");
    let fifo = dir.join("deck.mec");
    let made = std::process::Command::new("mkfifo").arg(&fifo).status().expect("mkfifo");
    assert!(made.success());
    for path in [fifo.as_path(), Path::new("/dev/zero"), Path::new("/dev/urandom")] {
        let (send, receive) = mpsc::channel();
        let owned = path.to_path_buf();
        std::thread::spawn(move || {
            let e = load(&owned).expect_err("should be refused");
            send.send((e.0[0].kind, e.0[0].message.clone())).ok();
        });
        let (kind, message) =
            receive.recv_timeout(Duration::from_secs(10)).unwrap_or_else(|_| panic!("{} hangs", path.display()));
        assert_eq!(kind, DiagnosticKind::Io);
        assert_eq!(message, "cannot read the deck: it is not a regular file");
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn what_follows_end_is_not_read() {
    let dir = scratch("after-end");
    let text = std::fs::read_to_string("tests/decks/valid/two_dof.mec").expect("deck");
    let deck = dir.join("deck.mec");
    // Invalid UTF-8, NUL bytes and 20 MiB of one line after END: none of it is read.
    let before_end = format!("{}\nEND\n", text.trim_end());
    let mut bytes = before_end.clone().into_bytes();
    bytes.extend([0xff, 0x00, b'\n']);
    bytes.extend(std::iter::repeat_n(b'x', 20 << 20));
    std::fs::write(&deck, &bytes).expect("deck");
    assert_eq!(mechfem_deck::read_deck(&deck).expect("deck"), before_end);
    let compiled = load(&deck).expect("deck");
    assert_eq!(compiled.mechanism.n_dof(), 2);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_deck_larger_than_the_limit_before_its_end_is_refused() {
    let dir = scratch("deck-huge");
    let deck = dir.join("deck.mec");
    let mut text = b"KIN ANA\n".to_vec();
    let line = b"; a comment line, again and again\n";
    let lines = usize::try_from(mechfem_deck::MAX_DECK_BYTES).expect("size") / line.len() + 1;
    text.extend(line.repeat(lines));
    text.extend(b"END\n");
    std::fs::write(&deck, &text).expect("deck");
    let e = load(&deck).expect_err("too large");
    assert_eq!(e.0[0].kind, DiagnosticKind::Io);
    assert_eq!(e.0[0].message, "the deck is larger than 16 MiB before its END line");
    std::fs::remove_dir_all(&dir).ok();
}
