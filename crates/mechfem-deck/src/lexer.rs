//! Lexical rules of the deck: lines, words, comments and Fortran numbers.
//!
//! A line is split at blanks and tabs into words; `;` starts a comment that
//! runs to the end of the line and means nothing (names are declared in the
//! NAMES block, never in comments). Words keep their spelling
//! (file names and titles are case-sensitive); keywords are compared
//! case-insensitively by the parser. Numbers follow Fortran's free format.

use crate::diagnostic::Span;
use crate::files::is_end_line;

/// One word of a line and where it stands.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Word {
    /// The word as written.
    pub text: String,
    /// Its place on the line.
    pub span: Span,
}

/// A line that holds at least one word.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Line {
    /// Line number, 1-based.
    pub number: usize,
    /// The words, in order (never empty).
    pub words: Vec<Word>,
}

impl Line {
    /// The empty span just after the last word: where a missing argument goes.
    pub fn end(&self) -> Span {
        let end = self.words.last().map_or(0, |w| w.span.end);
        Span::new(self.number, end, end)
    }
}

/// Why a word is not a usable number.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum NumberError {
    /// Not written as a number at all (this includes NaN and inf).
    Syntax,
    /// Written as a number, but too large for f64.
    Overflow,
}

fn is_separator(c: char) -> bool {
    matches!(c, ' ' | '\t' | '\r' | '\x0c' | '\x0b')
}

/// The raw lines of a deck (for diagnostics) up to and including its END
/// line: what follows END is no part of the deck, and is not kept.
pub(crate) fn source_lines(text: &str) -> Vec<String> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let mut raw = Vec::new();
    for line in text.lines() {
        raw.push(line.trim_end_matches('\r').to_string());
        if is_end_line(line) {
            break;
        }
    }
    raw
}

/// The lines with words of the raw lines `raw`, lexed one at a time as
/// they are asked for (a line's words are dropped once it is read).
pub(crate) fn lex(raw: &[String]) -> impl Iterator<Item = Line> + '_ {
    raw.iter().enumerate().filter_map(|(k, l)| lex_line(k + 1, l))
}

/// The words of one line, or `None` for a line that is blank or only a comment.
pub(crate) fn lex_line(number: usize, text: &str) -> Option<Line> {
    let mut words = Vec::new();
    let mut current: Option<(usize, String)> = None;
    let mut col = 0;
    for c in text.chars() {
        if c == ';' {
            break;
        }
        if is_separator(c) {
            if let Some((start, w)) = current.take() {
                words.push(Word { text: w, span: Span::new(number, start, col) });
            }
        } else {
            current.get_or_insert_with(|| (col, String::new())).1.push(c);
        }
        col += 1;
    }
    if let Some((start, w)) = current {
        words.push(Word { text: w, span: Span::new(number, start, col) });
    }
    (!words.is_empty()).then_some(Line { number, words })
}

/// Whether a word starts like a number; a line starting with such a word
/// repeats the previous keyword of its block.
pub(crate) fn looks_numeric(word: &str) -> bool {
    let mut chars = word.chars();
    match chars.next() {
        Some(c) if c.is_ascii_digit() || c == '.' => true,
        Some('+' | '-') => chars.next().is_some_and(|c| c.is_ascii_digit() || c == '.'),
        _ => false,
    }
}

/// Reads a number in Fortran's free format: `-3.6`, `4E5`, `-3.d-2`,
/// `1.5D0`, `.5`, `5.`, `+2`. NaN and infinity are not numbers; a value too
/// large for f64 is an overflow.
pub(crate) fn parse_number(word: &str) -> Result<f64, NumberError> {
    let b = word.as_bytes();
    let mut i = 0;
    if matches!(b.first(), Some(b'+' | b'-')) {
        i += 1;
    }
    let digits = |i: &mut usize| {
        let start = *i;
        while b.get(*i).is_some_and(u8::is_ascii_digit) {
            *i += 1;
        }
        *i - start
    };
    let mut mantissa = digits(&mut i);
    if b.get(i) == Some(&b'.') {
        i += 1;
        mantissa += digits(&mut i);
    }
    if mantissa == 0 {
        return Err(NumberError::Syntax);
    }
    let mut normal = word[..i].to_string();
    if matches!(b.get(i), Some(b'e' | b'E' | b'd' | b'D')) {
        i += 1;
        let sign_at = i;
        if matches!(b.get(i), Some(b'+' | b'-')) {
            i += 1;
        }
        if digits(&mut i) == 0 {
            return Err(NumberError::Syntax);
        }
        normal.push('e');
        normal.push_str(&word[sign_at..i]);
    }
    if i != b.len() {
        return Err(NumberError::Syntax);
    }
    let value: f64 = normal.parse().map_err(|_| NumberError::Syntax)?;
    if value.is_finite() {
        Ok(value)
    } else {
        Err(NumberError::Overflow)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn words(text: &str) -> Vec<String> {
        lex_line(1, text).map(|l| l.words.into_iter().map(|w| w.text).collect()).unwrap_or_default()
    }

    #[test]
    fn fortran_numbers_are_read() {
        let cases = [
            ("-3.6", -3.6),
            ("4E5", 4e5),
            ("-3.d-2", -0.03),
            ("1.5D0", 1.5),
            (".5", 0.5),
            ("5.", 5.0),
            ("+2", 2.0),
            ("0", 0.0),
            ("1e-400", 0.0),
            ("2.5e+3", 2500.0),
            ("-.25D+1", -2.5),
            ("6.283185307179586", std::f64::consts::TAU),
        ];
        for (text, value) in cases {
            assert_eq!(parse_number(text), Ok(value), "{text}");
        }
    }

    #[test]
    fn non_numbers_are_refused() {
        for text in [
            "", ".", "-", "+.", "1e", "1d+", "e5", "1.2.3", "nan", "NaN", "inf", "-inf", "infinity", "1x", "0x10",
            "1_0", "1,5", "--1", "1e5.0",
        ] {
            assert_eq!(parse_number(text), Err(NumberError::Syntax), "{text}");
        }
    }

    #[test]
    fn overflowing_numbers_are_refused() {
        assert_eq!(parse_number("1e999"), Err(NumberError::Overflow));
        assert_eq!(parse_number("-1.8D308"), Err(NumberError::Overflow));
    }

    #[test]
    fn comments_end_the_line() {
        assert_eq!(words("XFIX 1 0.0 ; the frame"), ["XFIX", "1", "0.0"]);
        assert_eq!(words("XFIX 1 0.0;no blank before"), ["XFIX", "1", "0.0"]);
        assert!(lex_line(1, "   ; only a comment").is_none());
        assert!(lex_line(1, "").is_none());
    }

    #[test]
    fn tabs_and_blanks_separate_words() {
        assert_eq!(words("\t2\tBIN\t11 12 9 10"), ["2", "BIN", "11", "12", "9", "10"]);
        assert_eq!(words("NRDOF\t1\t\t"), ["NRDOF", "1"]);
        assert_eq!(words("TOPOLOGY\t\t\t\r"), ["TOPOLOGY"]);
    }

    #[test]
    fn spans_count_characters() {
        let line = lex_line(7, "\tELEM  1 BIN").unwrap();
        let spans: Vec<_> = line.words.iter().map(|w| (w.span.start, w.span.end)).collect();
        assert_eq!(spans, [(1, 5), (7, 8), (9, 12)]);
        assert_eq!(line.end(), Span::new(7, 12, 12));
        let line = lex_line(1, "ÄÖ x").unwrap();
        assert_eq!(line.words[1].span, Span::new(1, 3, 4));
    }

    #[test]
    fn a_line_starting_with_a_number_is_a_repetition() {
        for w in ["1", "-1", "+2", ".5", "-.5", "10"] {
            assert!(looks_numeric(w), "{w}");
        }
        for w in ["ELEM", "-", "+", "-x", "BUFX0", ""] {
            assert!(!looks_numeric(w), "{w}");
        }
    }

    #[test]
    fn lex_keeps_raw_lines_and_skips_blank_ones() {
        let raw = source_lines("\u{feff}KIN ANA\r\n\r\n; note\r\nTOPOLOGY\r\nEnd ; of the deck\r\nnotes\r\n");
        assert_eq!(raw, ["KIN ANA", "", "; note", "TOPOLOGY", "End ; of the deck"]);
        let numbers: Vec<_> = lex(&raw).map(|l| l.number).collect();
        assert_eq!(numbers, [1, 4, 5]);
    }
}
