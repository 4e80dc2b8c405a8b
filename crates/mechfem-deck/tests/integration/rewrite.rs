//! The final design of a `KIN OPT` deck written as a `KIN ANA` deck
//! ([`mechfem_deck::rewrite::design_deck`]).

use std::path::Path;

use mechfem_core::Quantity;
use mechfem_deck::rewrite::design_deck;
use mechfem_deck::{compile, parse_str, DiagnosticKind, Mode};

const SUPPLY: &str = "tests/decks/valid/supply_optimise.mec";

fn supply() -> String {
    std::fs::read_to_string(SUPPLY).expect("deck")
}

#[test]
fn the_rewritten_supply_deck_is_a_kin_ana_deck_of_the_new_kappa() {
    let kappa = -5.175_158_123_456_789_f64;
    let text = design_deck(&supply(), SUPPLY, &[(5, kappa)], &[(9, 0.21), (10, -0.3312)], None).expect("rewritten");
    let c = parse_str(&text, "supply_opt.mec").and_then(|d| compile(&d, Path::new("."))).expect("compiles");
    assert_eq!(c.mode, Mode::KinAna);
    assert!(c.optimise.is_none());
    assert_eq!(c.state.target[4], kappa);
    assert_eq!((c.state.x[8], c.state.x[9]), (0.21, -0.3312));
    // Every other number as before.
    let before = parse_str(&supply(), SUPPLY).and_then(|d| compile(&d, Path::new("tests/decks/valid"))).unwrap();
    assert_eq!(c.state.target[..4], before.state.target[..4]);
    assert_eq!(c.state.x[..8], before.state.x[..8]);
    // OPTIMISE's buffers now stand in STORAGE, and SAVEDATA still finds 30.
    let buffers: Vec<(u32, Quantity)> = c.buffers.iter().map(|b| (b.number, b.quantity)).collect();
    assert_eq!(buffers, before.buffers.iter().map(|b| (b.number, b.quantity)).collect::<Vec<_>>());
    assert_eq!(c.savedata, before.savedata);
    // Comments and layout are kept.
    assert!(text.contains(&format!("      5 {kappa} ; the angle kappa = beta2-beta4 in the coupler plane\n")));
    assert!(text.contains("BUFKE2 -1 1 30   ; the output's second-order transfer function\n"));
    assert!(!text.contains("OPTIMISE") && !text.contains("TARGETEXT") && !text.contains("OPTSTEPS"));
    assert_eq!(text.lines().count(), supply().lines().count() - 5);
}

#[test]
fn a_repeated_buffer_line_moves_with_its_keyword() {
    let text = supply().replace("BUFE0  -1   31", "       -1 1 31");
    let text = text.replace("TARGETEXT 30 31 0.0", "TARGETAT 31 3 0.0");
    let out = design_deck(&text, SUPPLY, &[], &[], None).expect("rewritten");
    assert!(out.contains("  BUFKE2 -1 1 31   ; the output angle"));
    parse_str(&out, "x.mec").and_then(|d| compile(&d, Path::new("."))).expect("compiles");
}

#[test]
fn a_row_without_para_is_reported() {
    let e = design_deck(&supply(), SUPPLY, &[(12, 1.0)], &[], None).unwrap_err();
    assert_eq!(e.iter().next().map(|d| d.kind), Some(DiagnosticKind::UnknownRow));
    let e = design_deck(&supply(), SUPPLY, &[], &[(21, 1.0)], None).unwrap_err();
    assert_eq!(e.iter().next().map(|d| d.kind), Some(DiagnosticKind::CoordinateNotDeclared));
}

#[test]
fn motion_files_are_named_from_where_the_new_deck_is_written() {
    let text = supply().replace("MOV_RELE 1 6.283185307179586", "MOV_FUNC 1 crank.txt");
    let out = design_deck(&text, SUPPLY, &[], &[], Some(Path::new("../decks"))).expect("rewritten");
    assert!(out.contains("MOV_FUNC 1 ../decks/crank.txt\n"));
    let kept = design_deck(&text, SUPPLY, &[], &[], None).expect("rewritten");
    assert!(kept.contains("MOV_FUNC 1 crank.txt\n"));
}
