//! Decks made by the grammar of `support::deck`, reading the bytes as a
//! stream of choices: plausible line by line, so most of them get past the
//! reader and exercise the solver. Checked as `deck_run` does. Set
//! `MECHFEM_FUZZ_PRINT=1` to see the deck an input stands for.
#![no_main]

use libfuzzer_sys::fuzz_target;
use mechfem_fuzz::{check_deck, deck, deck_dir, show, Bytes, MAX_STEPS};

fuzz_target!(|data: &[u8]| {
    let text = deck(&mut Bytes::new(data));
    show(&text);
    check_deck(&text, &deck_dir(), MAX_STEPS);
});
