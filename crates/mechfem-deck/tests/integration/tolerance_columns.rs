//! BUFTOL's b and b + 1 are buffers of the compiled deck: named like their
//! source with "worst" and "rss", in its unit, nameable by PRINTBUF, SAVEDATA
//! and pictures, and filled after a run with the bands of the TOLERANCE
//! block at every position.

use std::path::Path;

use mechfem_deck::{parse_str, Compiled};

const DECK: &str = "tests/decks/valid/tolerance_fourbar.mec";

fn compile(text: &str) -> Compiled {
    let deck = parse_str(text, "tolerance.mec").unwrap_or_else(|e| panic!("{e}"));
    mechfem_deck::compile(&deck, Path::new(".")).unwrap_or_else(|e| panic!("{e}"))
}

fn deck_text() -> String {
    std::fs::read_to_string(DECK).expect("the deck")
}

#[test]
fn band_buffers_follow_the_deck_buffers_with_their_sources_quantity_unit_and_label() {
    let c = compile(&deck_text());
    let numbers: Vec<u32> = c.buffers.iter().map(|b| b.number).collect();
    assert_eq!(numbers, [1, 100, 101, 102, 103, 200, 201, 202, 203, 204, 205]);
    let by = |n: u32| *c.buffers.iter().find(|b| b.number == n).expect("buffer");
    for (band, source) in [(200, 100), (202, 101), (204, 102)] {
        for number in [band, band + 1] {
            assert_eq!(by(number).quantity, by(source).quantity);
            assert_eq!(c.unit(&by(number)), c.unit(&by(source)));
        }
        let kind = |n: u32| c.label(&by(n));
        assert_eq!(kind(band), format!("{} worst", kind(source)));
        assert_eq!(kind(band + 1), format!("{} rss", kind(source)));
    }
    assert_eq!(c.label(&by(200)), "psi worst");
    assert_eq!(c.unit(&by(201)), "deg");
}

#[test]
fn filled_columns_are_the_bands_at_every_position() {
    let c = compile(&deck_text());
    let tol = c.tolerance.as_ref().expect("TOLERANCE");
    let evaluated = tol.evaluate(&c).unwrap_or_else(|e| panic!("{e}"));
    let b = &evaluated.bands;
    let positions = b.positions;
    assert_eq!(positions, 37);
    let mut columns = vec![0.0; c.buffers.len() * positions];
    c.fill_bands(c.state.clone(), &mut columns, positions).unwrap_or_else(|e| panic!("{e}"));
    let nb = tol.bands.len();
    for (k, buffer) in c.buffers.iter().enumerate() {
        let column = &columns[k * positions..(k + 1) * positions];
        let Some(q) = tol.bands.iter().position(|d| buffer.number == d.buffer || buffer.number == d.buffer + 1) else {
            assert!(column.iter().all(|&v| v == 0.0), "buffer {} was written", buffer.number);
            continue;
        };
        let values = if buffer.number == tol.bands[q].buffer { &b.worst } else { &b.rss };
        for (p, v) in column.iter().enumerate() {
            // The column is in the core's units, the evaluated bands in the deck's.
            let want = values[p * nb + q];
            let got = v * c.out_scale(buffer.quantity);
            assert!(
                (got - want).abs() <= 1e-12 * want.abs().max(1e-300),
                "buffer {} at {p}: {got} vs {want}",
                buffer.number
            );
            assert!(want > 0.0);
        }
    }
}

#[test]
fn printbuf_savedata_and_pictures_name_the_band_buffers() {
    let text = deck_text()
        .replace("PRINTBUF 100 101", "PRINTBUF 100 200 201\nSAVEDATA 200 203\nBEGINPIC bands\nPLOTFUNC 1 200\nENDPIC");
    let c = compile(&text);
    assert_eq!(c.printbuf.as_deref(), Some(&[100, 200, 201][..]));
    assert_eq!(c.savedata, [200, 203]);
    assert_eq!(c.pictures.len(), 1);
}

#[test]
fn a_band_buffer_of_an_undefined_number_is_still_refused() {
    let text = deck_text().replace("PRINTBUF 100 101", "PRINTBUF 100 206");
    let deck = parse_str(&text, "tolerance.mec").unwrap_or_else(|e| panic!("{e}"));
    let err = mechfem_deck::compile(&deck, Path::new(".")).expect_err("206 is no buffer").to_string();
    assert!(err.contains("206"), "{err}");
    assert!(err.contains("200"), "the defined buffers are listed with the bands: {err}");
}
