//! Any bytes, read as a deck (lossy UTF-8), parsed and compiled: never a
//! panic, and every diagnostic renders.
#![no_main]

use libfuzzer_sys::fuzz_target;
use mechfem_fuzz::{compile_text, deck_dir, show};

fuzz_target!(|data: &[u8]| {
    let text = String::from_utf8_lossy(data);
    show(&text);
    let _ = compile_text(&text, &deck_dir());
});
