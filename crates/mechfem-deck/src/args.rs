//! Reading a keyword's arguments: counts, numbers, whole numbers, words.

use std::path::Path;

use crate::ast::diagnostic_at;
use crate::diagnostic::{Diagnostic, DiagnosticKind, Hint, Span, Spanned};
use crate::keywords::Keyword;
use crate::lexer::{parse_number, Line, NumberError, Word};

/// Whole numbers from this (2^53) on are refused: f64 holds every whole
/// number below it exactly, but 2^53 + 1 already reads as 2^53.
const MAX_WHOLE: f64 = 9_007_199_254_740_992.0;

/// Where diagnostics go: the file's path and raw lines.
pub(crate) struct Source<'a> {
    pub path: &'a Path,
    pub lines: &'a [String],
}

impl Source<'_> {
    pub fn error(&self, kind: DiagnosticKind, span: Span, message: impl Into<String>) -> Box<Diagnostic> {
        diagnostic_at(self.path, self.lines, kind, span, message)
    }

    /// The word read as a finite number.
    pub fn real(&self, w: &Word, what: &str) -> Result<Spanned<f64>, Box<Diagnostic>> {
        match parse_number(&w.text) {
            Ok(v) => Ok(Spanned::new(v, w.span)),
            Err(NumberError::Syntax) => Err(self
                .error(DiagnosticKind::NotANumber, w.span, format!("expected a number for {what}, got `{}`", w.text))
                .with_hint("numbers are written like 12, -3.6, .5, 4E5 or 1.5D0")),
            Err(NumberError::Overflow) => Err(self
                .error(DiagnosticKind::NumberOutOfRange, w.span, format!("the number `{}` is too large", w.text))
                .with_hint("numbers must lie within about +-1.8E308")),
        }
    }

    /// The word read as a whole number (`3`, also `3.0` or `3E0`).
    pub fn whole(&self, w: &Word, what: &str) -> Result<Spanned<i64>, Box<Diagnostic>> {
        let v = self.real(w, what)?;
        if v.value.fract() != 0.0 {
            return Err(self
                .error(
                    DiagnosticKind::NotAWholeNumber,
                    w.span,
                    format!("{what} must be a whole number, got `{}`", w.text),
                )
                .with_hint(format!("write {what} without a fraction, e.g. `{}`", v.value.trunc())));
        }
        if v.value.abs() >= MAX_WHOLE {
            return Err(self.error(
                DiagnosticKind::NumberOutOfRange,
                w.span,
                format!("{what} `{}` is too large", w.text),
            ));
        }
        // The value is integral and below 2^53, so the conversion is exact.
        Ok(Spanned::new(v.value as i64, w.span))
    }

    /// The word as a buffer number: a whole number in 1..=u32::MAX.
    pub fn buffer(&self, w: &Word) -> Result<Spanned<i64>, Box<Diagnostic>> {
        let b = self.whole(w, "a buffer number")?;
        if b.value < 1 || b.value > i64::from(u32::MAX) {
            return Err(self
                .error(DiagnosticKind::BadValue, w.span, format!("buffer number {} is not allowed", b.value))
                .with_hint("buffer numbers are whole numbers from 1 to 4294967295"));
        }
        Ok(b)
    }

    /// Checks the number of arguments of a keyword against its table entry.
    pub fn check_count(&self, kw: Keyword, line: &Line, args: &[Word], repeated: bool) -> Result<(), Box<Diagnostic>> {
        let (min, max) = kw.arity();
        let n = args.len();
        if n >= min && !matches!(max, Some(m) if n > m) {
            return Ok(());
        }
        let expects = match kw.arity_text().as_str() {
            "no" => "no arguments".to_string(),
            "1" => "1 argument".to_string(),
            t => format!("{t} arguments"),
        };
        let usage = if kw.usage().is_empty() { String::new() } else { format!(" ({})", kw.usage()) };
        let subject = if repeated { format!("this line repeats {kw}, which") } else { kw.name().to_string() };
        let message = format!("{subject} expects {expects}{usage}, got {n}");
        Err(self
            .count_error(line, args, max.filter(|&m| n > m), message)
            .with_hint(format!("usage: {}", kw.synopsis())))
    }

    /// An argument-count error: at the first surplus word when `surplus_from`
    /// is given, else just after the last word of the line.
    pub fn count_error(
        &self,
        line: &Line,
        args: &[Word],
        surplus_from: Option<usize>,
        message: String,
    ) -> Box<Diagnostic> {
        let span = match (surplus_from.and_then(|k| args.get(k)), args.last()) {
            (Some(first), Some(last)) => first.span.to(last.span),
            _ => line.end(),
        };
        self.error(DiagnosticKind::ArgumentCount, span, message)
    }
}
