//! Reading the files a run is given: the deck and the tables it names.
//!
//! Every file is read as data, within bounds: it must be a regular file (a
//! device such as `/dev/zero` or a pipe would be read without end, and
//! opening a pipe waits for a writer), it is read through a cap of one byte
//! more than allowed (so a file that grows while it is read is still
//! refused), and a deck is read only up to its `END` line.

use std::io::{BufRead, BufReader, ErrorKind, Read};
use std::path::Path;

use crate::diagnostic::{Diagnostic, DiagnosticKind, Diagnostics};

/// The largest deck read (up to its END line): some 200 000 lines, far
/// more than any mechanism needs, and few enough that reading any deck
/// this size takes less than a gigabyte of memory.
pub const MAX_DECK_BYTES: u64 = 16 << 20;

/// Why a file was not read.
pub(crate) enum Refused {
    /// It cannot be opened or read, or it is no regular file; the reason in words.
    Io(String),
    /// It is larger than allowed.
    TooLarge,
}

/// The file at `path`, open, once it is known to be a regular file of at
/// most `max` bytes.
fn open_regular(path: &Path, max: u64) -> Result<std::fs::File, Refused> {
    let regular = |meta: &std::fs::Metadata| {
        if meta.is_dir() {
            Err(Refused::Io("it is a folder".to_string()))
        } else if !meta.is_file() {
            Err(Refused::Io("it is not a regular file".to_string()))
        } else if meta.len() > max {
            Err(Refused::TooLarge)
        } else {
            Ok(())
        }
    };
    // Asked before opening (opening a pipe would wait for a writer), and
    // again of the open file, in case the name changed hands in between.
    regular(&std::fs::metadata(path).map_err(io_reason)?)?;
    let file = std::fs::File::open(path).map_err(io_reason)?;
    regular(&file.metadata().map_err(io_reason)?)?;
    Ok(file)
}

fn io_reason(e: std::io::Error) -> Refused {
    Refused::Io(match e.kind() {
        ErrorKind::NotFound => "it does not exist".to_string(),
        ErrorKind::PermissionDenied => "permission denied".to_string(),
        _ => e.to_string(),
    })
}

/// The bytes of a regular file, at most `max` of them.
pub(crate) fn bytes(path: &Path, max: u64) -> Result<Vec<u8>, Refused> {
    let file = open_regular(path, max)?;
    // The file may have grown since: read one byte more than allowed to see.
    let mut out = Vec::new();
    file.take(max + 1).read_to_end(&mut out).map_err(io_reason)?;
    if out.len() as u64 > max {
        return Err(Refused::TooLarge);
    }
    Ok(out)
}

/// The bytes of a regular file up to and including its first `END` line
/// (all of it when it has none), at most `max` of them: what follows END
/// is never read, whatever its size.
fn bytes_to_end(path: &Path, max: u64) -> Result<Vec<u8>, Refused> {
    // The size of the whole file does not matter: only what comes before END is read.
    let file = open_regular(path, u64::MAX)?;
    let mut reader = BufReader::new(file.take(max + 1));
    let mut out = Vec::new();
    loop {
        let start = out.len();
        if reader.read_until(b'\n', &mut out).map_err(io_reason)? == 0 {
            break;
        }
        if out.len() as u64 > max {
            return Err(Refused::TooLarge);
        }
        if is_end_line(&String::from_utf8_lossy(&out[start..])) {
            break;
        }
    }
    Ok(out)
}

/// Whether a deck line is the END line: its first word is END (in any case).
pub(crate) fn is_end_line(line: &str) -> bool {
    let words = line.split(';').next().unwrap_or("");
    words
        .split([' ', '\t', '\r', '\n', '\x0c', '\x0b'])
        .find(|w| !w.is_empty())
        .is_some_and(|w| w.eq_ignore_ascii_case("END"))
}

/// The text of the deck at `path` up to its END line, read as
/// `bytes_to_end` reads it (invalid UTF-8 replaced, a byte-order mark
/// kept for the lexer to drop).
pub fn read_deck(path: &Path) -> Result<String, Diagnostics> {
    let refused = |message: String, hint: String| -> Diagnostics {
        Diagnostic::file(DiagnosticKind::Io, path, message).with_hint(hint).into()
    };
    match bytes_to_end(path, MAX_DECK_BYTES) {
        Ok(bytes) => Ok(String::from_utf8_lossy(&bytes).into_owned()),
        Err(Refused::Io(why)) => Err(refused(
            format!("cannot read the deck: {why}"),
            "give the path of a deck file: a text file, not a folder, a device or a pipe".into(),
        )),
        Err(Refused::TooLarge) => Err(refused(
            format!("the deck is larger than {} MiB before its END line", MAX_DECK_BYTES >> 20),
            "a deck holds one short line per element, co-ordinate or keyword: check that this is the deck meant, \
             and end it with an END line"
                .into(),
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_end_line_is_found_in_any_case_and_before_a_comment() {
        assert!(is_end_line("END\n"));
        assert!(is_end_line("  end ; the rest is notes\r\n"));
        assert!(is_end_line("End"));
        assert!(!is_end_line("ENDPIC\n"));
        assert!(!is_end_line("; END\n"));
        assert!(!is_end_line("XMOV 1 END\n"));
    }

    #[test]
    fn a_deck_is_read_up_to_its_end_line_only() {
        let dir = std::env::temp_dir().join(format!("mechfem-files-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("after_end.mec");
        let mut text = b"KIN ANA\nTOPOLOGY\nend\n".to_vec();
        text.extend(std::iter::repeat_n(b'x', (MAX_DECK_BYTES + 10) as usize));
        std::fs::write(&path, &text).unwrap();
        assert_eq!(read_deck(&path).unwrap(), "KIN ANA\nTOPOLOGY\nend\n");
        std::fs::write(&path, &text[21..]).unwrap();
        let err = read_deck(&path).unwrap_err().to_string();
        assert!(err.contains("larger than 16 MiB before its END line"), "{err}");
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn a_device_or_a_folder_is_not_read_as_a_deck() {
        let err = read_deck(Path::new("/dev/zero")).unwrap_err().to_string();
        assert!(err.contains("it is not a regular file"), "{err}");
        let err = read_deck(&std::env::temp_dir()).unwrap_err().to_string();
        assert!(err.contains("it is a folder"), "{err}");
    }
}
