//! The MOVEMENT-block lines that choose how a simulation is integrated and
//! when it ends: `INTEGRATOR method` and `STOPWHEN b value`. What the line
//! alone can tell; whether buffer b exists is checked by
//! [`crate::compile`].

use mechfem_core::dynamics::Integrator;

use crate::args::Source;
use crate::ast::StopWhenDef;
use crate::diagnostic::{Diagnostic, DiagnosticKind, Spanned};
use crate::lexer::Word;

/// The word of `INTEGRATOR` as a method.
pub(crate) fn integrator(src: &Source<'_>, w: &Word) -> Result<Spanned<Integrator>, Box<Diagnostic>> {
    match Integrator::from_word(&w.text) {
        Some(m) => Ok(Spanned::new(m, w.span)),
        None => Err(Box::new(
            src.error(DiagnosticKind::BadValue, w.span, format!("`{}` is not an integration method", w.text))
                .with_hint(format!(
                    "give one of {}: `auto` (the default) integrates with Dormand-Prince 5(4) and goes over to the \
                 implicit Radau IIA where the motion is stiff, `explicit` (= `dopri5`) and `dop853` never do, \
                 `implicit` (= `radau5`) always does",
                    Integrator::WORDS.join(", ")
                )),
        )),
    }
}

/// `STOPWHEN b value`: buffer b and the value whose crossing ends the
/// simulation.
pub(crate) fn stop_when(src: &Source<'_>, line: usize, args: &[Word]) -> Result<StopWhenDef, Box<Diagnostic>> {
    let buffer = src.buffer(&args[0])?;
    let value = src.real(&args[1], "the value of STOPWHEN")?;
    Ok(StopWhenDef { line, buffer, value })
}
