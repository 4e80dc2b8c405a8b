//! Any bytes, read as a deck, compiled and, when that succeeds, run (at
//! most `MAX_STEPS` steps): never a panic, and no recorded value is NaN or
//! infinite unless the run said why.
#![no_main]

use libfuzzer_sys::fuzz_target;
use mechfem_fuzz::{check_deck, deck_dir, show, MAX_STEPS};

fuzz_target!(|data: &[u8]| {
    let text = String::from_utf8_lossy(data);
    show(&text);
    check_deck(&text, &deck_dir(), MAX_STEPS);
});
