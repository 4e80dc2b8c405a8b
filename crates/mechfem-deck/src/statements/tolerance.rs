//! One line of the TOLERANCE block: what the line alone can tell (the
//! numbers, a positive tolerance). Whether the rows, co-ordinates and
//! buffers it names exist and can be toleranced is checked by
//! [`crate::compile`].

use crate::ast::{BufTolDef, TolDef};
use crate::diagnostic::{real, Diagnostic, DiagnosticKind, Hint, Spanned};
use crate::keywords::Keyword;
use crate::lexer::{Line, Word};
use crate::parse::Parser;
use crate::statements::dynamics::bounded;

impl Parser<'_> {
    /// Reads one line of the TOLERANCE block (its argument count is checked).
    pub(crate) fn tolerance_statement(
        &mut self,
        kw: Spanned<Keyword>,
        line: &Line,
        args: &[Word],
    ) -> Result<(), Box<Diagnostic>> {
        let arg =
            |k: usize| args.get(k).ok_or_else(|| self.src.count_error(line, args, None, "missing argument".into()));
        let src = &self.src;
        if kw.value == Keyword::BufTol {
            let source = src.buffer(arg(0)?)?;
            let buffer = src.buffer(arg(1)?)?;
            self.tolerance.bands.push(BufTolDef { line: line.number, source, buffer });
            return Ok(());
        }
        let what = if kw.value == Keyword::Tol { "the row number" } else { "the co-ordinate number" };
        let index = src.whole(arg(0)?, what)?;
        let t = bounded(src, arg(1)?, "the tolerance")?;
        if t.value <= 0.0 {
            return Err(src
                .error(
                    DiagnosticKind::BadValue,
                    t.span,
                    format!("{} tolerance must be positive, got {}", kw.value, real(t.value)),
                )
                .with_hint(
                    "give the half-width t of the band the value is made within (value +- t), in the deck's units; \
                     leave a dimension made exactly out of the block",
                ));
        }
        self.tolerance.dims.push(TolDef { line: line.number, keyword: kw, index, t });
        Ok(())
    }
}
