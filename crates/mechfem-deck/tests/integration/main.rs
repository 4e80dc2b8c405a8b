//! The integration tests of mechfem-deck, one module per former test file, in one test binary: each
//! binary links the whole core, and one link instead of one per file saves minutes of a clean `make test`.
//! A new test file goes beside this one and gets its `mod` line here.

mod diagnostic_fields;
mod dynamic_optimise;
mod dynamics;
mod golden;
mod hostile;
mod input_files;
mod optimise;
mod rewrite;
mod robustness;
mod running;
mod simulation;
mod tolerance;
mod tolerance_bands;
mod tolerance_columns;
mod unit_warnings;
mod units;
