//! The integration tests of mechfem-core, one module per former test file, in one test binary: each
//! binary links the whole core, and one link instead of one per file saves minutes of a clean `make test`.
//! A new test file goes beside this one and gets its `mod` line here.

// The models several modules share (the benchmarks include them by path too).
#[path = "../common/chain.rs"]
mod common_chain;
#[path = "../common/dynamics.rs"]
mod common_dynamics;
#[path = "../common/fourbar.rs"]
mod common_fourbar;

mod allocations;
mod andrews;
mod balancing;
mod branch;
mod chain;
mod design;
mod dynamic_design;
mod dynamics;
mod errors;
mod fourbar;
mod free_motion;
mod layout;
mod manipulator;
mod sensitivity;
mod simulate;
mod simulate_dop853;
mod simulate_implicit;
mod simulate_methods;
mod slider_crank;
mod stephenson;
mod transmission;
mod worded;
