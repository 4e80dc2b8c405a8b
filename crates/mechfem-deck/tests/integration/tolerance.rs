//! The TOLERANCE block compiles to the toleranced dimensions (0-based, in
//! the core's units, as the values they tolerance) and the bands; decks
//! without it compile as before.

use std::path::Path;

use mechfem_core::DesignVar;
use mechfem_deck::{load, parse_str, BandDef, Compiled};

const DECK: &str = "tests/decks/valid/tolerance_fourbar.mec";

fn compile(text: &str) -> Compiled {
    let deck = parse_str(text, "tolerance.mec").unwrap_or_else(|e| panic!("{e}"));
    mechfem_deck::compile(&deck, Path::new(".")).unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn tolerances_are_in_the_core_units_of_the_values_they_tolerance() {
    let c = load(DECK).unwrap_or_else(|e| panic!("{e}"));
    let t = c.tolerance.as_ref().expect("the deck has a TOLERANCE block");
    let vars: Vec<DesignVar> = t.dims.iter().map(|d| d.var).collect();
    assert_eq!(vars, [DesignVar::Row(0), DesignVar::Row(4), DesignVar::Row(3), DesignVar::Fixed(2)]);
    // In the deck (mm): crank 10 +- 0.05, rocker 30 +- 0.05, v 12 +- 0.1, B0.x 40 +- 0.1. Whatever the core's
    // unit of length, a tolerance is scaled as the value it belongs to.
    let value = |v: DesignVar| match v {
        DesignVar::Row(r) => c.state.target[r],
        DesignVar::Fixed(i) => c.state.x[i],
    };
    for (d, ratio) in t.dims.iter().zip([0.05 / 10.0, 0.05 / 30.0, 0.1 / 12.0, 0.1 / 40.0]) {
        assert!((d.t / value(d.var) - ratio).abs() < 1e-15, "{d:?}");
    }
    let bands: Vec<(u32, u32)> = t.bands.iter().map(|b: &BandDef| (b.source, b.buffer)).collect();
    assert_eq!(bands, [(100, 200), (101, 202), (102, 204)]);
}

#[test]
fn a_deck_without_tolerance_has_none_and_the_same_model() {
    let text = std::fs::read_to_string(DECK).expect("read the deck");
    let plain = format!("{}END\n", &text[..text.find("TOLERANCE").expect("the block")]);
    let (a, b) = (compile(&plain), compile(&text));
    assert!(a.tolerance.is_none());
    assert_eq!(a.state.x, b.state.x);
    assert_eq!(a.state.target, b.state.target);
    // The bands' buffers (BUFTOL 100 200, 101 202, 102 204) follow the deck's own.
    assert_eq!(a.buffers[..], b.buffers[..a.buffers.len()]);
    let bands: Vec<u32> = b.buffers[a.buffers.len()..].iter().map(|x| x.number).collect();
    assert_eq!(bands, [200, 201, 202, 203, 204, 205]);
}

#[test]
fn dyn_ana_takes_a_tolerance_block_on_its_kinematic_buffers() {
    let text = std::fs::read_to_string(DECK).expect("read the deck");
    let dyn_ana = text.replacen("KIN ANA", "DYN ANA", 1).replacen("MOVEMENT", "DYNAMICS\nMASS 1 1.0 5 0\nMOVEMENT", 1);
    let c = compile(&dyn_ana);
    assert_eq!(c.tolerance.expect("compiled").bands.len(), 3);
}
