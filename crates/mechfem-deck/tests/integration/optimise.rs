//! The mode `KIN OPT` and its OPTIMISE block: what a deck compiles to, with
//! the core's 0-based indices, and what is refused. (Every refusal with its
//! exact message: the invalid golden decks `opt_*.mec`.)

use std::path::Path;

use mechfem_core::{DesignVar, FormRef, InputMotion, Quantity};
use mechfem_deck::{
    compile, load, parse_str, Bound, Compiled, DiagnosticKind, Diagnostics, Mode, Objective, Optimise, Reduce, Sense,
    Target, TargetKind, Vary,
};

fn valid(name: &str) -> Compiled {
    let path = Path::new("tests/decks/valid").join(name);
    load(&path).unwrap_or_else(|e| panic!("{} should load:\n{e}", path.display()))
}

/// The four-bar of `fourbar_optimise.mec` up to its MOVEMENT block.
fn four_bar(mode: &str) -> String {
    let text = std::fs::read_to_string("tests/decks/valid/fourbar_optimise.mec").expect("deck");
    let end = text.find("STORAGE").expect("STORAGE");
    text[..end].replacen("KIN OPT", mode, 1)
}

fn compiled(text: &str) -> Result<Compiled, Diagnostics> {
    parse_str(text, "opt.mec").and_then(|d| compile(&d, Path::new("tests/decks/valid")))
}

fn kinds(e: &Diagnostics) -> Vec<(DiagnosticKind, usize)> {
    e.iter().map(|d| (d.kind, d.line)).collect()
}

#[test]
fn the_supply_mechanism_varies_kappa_to_flatten_the_dead_positions() {
    let c = valid("supply_optimise.mec");
    assert_eq!(c.mode, Mode::KinOpt);
    assert!(c.dynamics.is_none());
    let o = c.optimise.as_ref().expect("a KIN OPT deck has an optimisation");
    assert_eq!(o.vary, [Vary { var: DesignVar::Row(4), lo: -5.4, hi: -5.0, line: 71 }]);
    assert_eq!(c.state.target[4], -5.17514);
    assert_eq!(
        o.targets,
        [Target { buffer: 30, kind: TargetKind::Extremum { reference: 31, value: 0.0 }, weight: 1.0, line: 74 }]
    );
    assert!(o.bounds.is_empty() && o.objective.is_none());
    assert_eq!((o.steps, o.tol, o.line), (50, None, 70));
    // The buffers of OPTIMISE join those of STORAGE, in deck order.
    let buffers: Vec<(u32, Quantity)> = c.buffers.iter().map(|b| (b.number, b.quantity)).collect();
    assert_eq!(
        buffers[..3],
        [
            (30, Quantity::Ke2(FormRef::Dependent(0), 0, 0)),
            (31, Quantity::E0(FormRef::Dependent(0))),
            (99, Quantity::Input(0))
        ]
    );
    assert_eq!(buffers.len(), 6);
    assert_eq!(c.savedata, [99, 100, 101, 102, 30]);
}

#[test]
fn every_keyword_of_the_optimise_block() {
    let c = valid("fourbar_optimise.mec");
    let o = c.optimise.expect("optimise");
    assert_eq!(
        o.vary,
        [
            Vary { var: DesignVar::Row(1), lo: 3.0, hi: 4.0, line: 34 },
            Vary { var: DesignVar::Row(2), lo: 2.5, hi: 3.5, line: 35 },
            Vary { var: DesignVar::Row(3), lo: -0.5, hi: 0.5, line: 36 },
            Vary { var: DesignVar::Fixed(2), lo: 3.5, hi: 4.5, line: 37 },
        ]
    );
    // Blank and `*` rows are positions without a value; the comment line and
    // the blank line at the end of the file are no rows.
    let values = vec![Some(1.9), None, None, Some(2.3), Some(1.8)];
    assert_eq!(
        o.targets,
        [
            Target {
                buffer: 10,
                kind: TargetKind::Values { file: "rocker.dat".into(), values },
                weight: 2.0,
                line: 41
            },
            Target { buffer: 11, kind: TargetKind::At { position: 2, value: 3.2 }, weight: 1.0, line: 42 },
            Target { buffer: 11, kind: TargetKind::Extremum { reference: 10, value: 3.1 }, weight: 0.5, line: 43 },
        ]
    );
    assert_eq!(o.bounds, [Bound { buffer: 12, lo: -1.0, hi: 1.0, line: 44 }]);
    assert_eq!(
        o.objective,
        Some(Objective { sense: Sense::Maximise, reduce: Reduce::Rms, buffer: 12, with: None, line: 45 })
    );
    assert_eq!((o.steps, o.tol, o.line), (30, Some(1e-9), 33));
    // STORAGE comes first in this deck and names OPTIMISE's buffers.
    let numbers: Vec<u32> = c.buffers.iter().map(|b| b.number).collect();
    assert_eq!(numbers, [1, 10, 11, 12]);
    assert_eq!(c.printbuf, Some(vec![1, 10, 11]));
    assert_eq!(c.motion.expect("motion").inputs, [InputMotion::Absolute { end: 3.0 }]);
}

#[test]
fn optsteps_defaults_to_200() {
    let c = compiled(&format!("{}OPTIMISE\nVARY 2 3 4\nBUFE0 -1 1\nMINIMISE MAXABS 1\n", four_bar("KIN OPT"))).unwrap();
    let o = c.optimise.expect("optimise");
    assert_eq!((o.steps, o.tol), (Optimise::DEFAULT_STEPS, None));
    assert_eq!(o.objective.map(|o| (o.sense, o.reduce)), Some((Sense::Minimise, Reduce::MaxAbs)));
}

#[test]
fn only_kin_opt_and_dyn_ana_decks_have_an_optimisation() {
    let c = compiled(&four_bar("KIN ANA")).unwrap();
    assert!(c.optimise.is_none());
    let e = compiled(&format!("{}OPTIMISE\nVARY 2 3 4\n", four_bar("KIN ANA"))).unwrap_err();
    assert_eq!(kinds(&e), [(DiagnosticKind::WrongMode, 30)]);
    let e = compiled(&format!("{}OPTIMISE\nVARY 2 3 4\n", four_bar("DYN SIM"))).unwrap_err();
    assert!(kinds(&e).contains(&(DiagnosticKind::WrongMode, 30)), "{e}");
}

#[test]
fn a_buffer_number_is_unique_across_optimise_and_storage() {
    let text =
        format!("{}OPTIMISE\nVARY 2 3 4\nBUFE0 -1 1\nMINIMISE MAX 1\nSTORAGE\nBUFINP 1 1\n", four_bar("KIN OPT"));
    let e = compiled(&text).unwrap_err();
    assert_eq!(kinds(&e), [(DiagnosticKind::DuplicateBuffer, 35)]);
}

#[test]
fn optimise_takes_buffer_definitions_but_not_what_storage_does_with_them() {
    let text = format!("{}OPTIMISE\nVARY 2 3 4\nBUFE0 -1 1\nPRINTBUF 1\nMINIMISE MAX 1\n", four_bar("KIN OPT"));
    let e = compiled(&text).unwrap_err();
    assert_eq!(kinds(&e), [(DiagnosticKind::WrongBlock, 33)]);
    assert_eq!(e.0[0].message, "PRINTBUF belongs in the STORAGE block, not in OPTIMISE");
}

#[test]
fn mistakes_on_separate_lines_are_all_reported() {
    let text = format!(
        "{}OPTIMISE\nVARY 2 4 3\nBOUND 1 2 2\nTARGETAT 1 1 0 -1\nMINIMISE MEAN 1\nOPTTOL 0\nOPTSTEPS 0\n",
        four_bar("KIN OPT")
    );
    let e = compiled(&text).unwrap_err();
    let lines: Vec<usize> = e.iter().map(|d| d.line).collect();
    assert_eq!(lines, [31, 32, 33, 34, 35, 36]);
    assert!(e.iter().all(|d| d.kind == DiagnosticKind::BadValue), "{e}");
}

#[test]
fn the_input_of_a_mov_func_motion_is_no_design_variable() {
    let text = four_bar("KIN OPT").replace("TSTEPE 4 0.1\nMOV_ABSE 1 3.0", "TSTEPE 4\nMOV_FUNC 1 crank.dat");
    let e = compiled(&format!("{text}OPTIMISE\nVARY 4 -1 1\nBUFE0 -1 1\nMINIMISE MAX 1\n")).unwrap_err();
    assert_eq!(kinds(&e), [(DiagnosticKind::DesignVariable, 31)]);
    // Its other rows are.
    let c = compiled(&format!("{text}OPTIMISE\nVARY 1 0.5 1.5\nBUFE0 -1 1\nMINIMISE MAX 1\n")).unwrap();
    assert_eq!(c.optimise.expect("optimise").vary[0].var, DesignVar::Row(0));
}

#[test]
fn optftol_gives_a_relative_and_an_absolute_tolerance_and_excludes_opttol() {
    let block = "OPTIMISE\nVARY 2 3 4\nBUFE0 -1 1\nMINIMISE MAX 1\n";
    let c = compiled(&format!("{}{block}OPTFTOL 1E-12 0\n", four_bar("KIN OPT"))).unwrap();
    let o = c.optimise.expect("optimise");
    assert_eq!((o.tol, o.ftol), (None, Some((1e-12, 0.0))));
    let c = compiled(&format!("{}{block}OPTTOL 1E-8\n", four_bar("KIN OPT"))).unwrap();
    assert_eq!(c.optimise.expect("optimise").ftol, None);
    for (lines, kind) in [
        ("OPTFTOL 1E-10 1E-14\nOPTTOL 1E-8\n", DiagnosticKind::DuplicateKeyword),
        ("OPTFTOL 0 0\n", DiagnosticKind::BadValue),
        ("OPTFTOL -1E-3 0\n", DiagnosticKind::BadValue),
        ("OPTFTOL 1 0\n", DiagnosticKind::BadValue),
    ] {
        let e = compiled(&format!("{}{block}{lines}", four_bar("KIN OPT"))).unwrap_err();
        assert_eq!(e.iter().map(|d| d.kind).collect::<Vec<_>>(), [kind], "{lines}: {e}");
    }
}

/// FREETIME's sweep is in the input's unit: degrees under `UNITS ANGLE deg`,
/// compiled to radians as every angle of the deck.
#[test]
fn freetime_within_is_read_in_the_decks_angle_unit() {
    let block = "OPTIMISE\nVARY 2 3.0 4.0\nBUFX0 7 11\nTARGETAT 11 3 3.2\nFREETIME 4 ORDERED WITHIN 90\n";
    let free = |units: &str| {
        let text = four_bar("KIN OPT").replacen("KIN OPT\n", &format!("KIN OPT\n{units}"), 1);
        let c = compiled(&format!("{text}{block}")).unwrap_or_else(|e| panic!("{e}"));
        c.optimise.and_then(|o| o.free_time).expect("FREETIME")
    };
    let deg = free("UNITS ANGLE deg\n");
    assert!(deg.ordered && (deg.within.expect("WITHIN") - std::f64::consts::FRAC_PI_2).abs() < 1e-15);
    assert_eq!((free("").row, free("").within), (3, Some(90.0)));
    let plain = compiled(&format!("{}{}", four_bar("KIN OPT"), block.replace(" WITHIN 90", "")));
    assert_eq!(plain.expect("FREETIME 4 ORDERED").optimise.and_then(|o| o.free_time).map(|f| f.within), Some(None));
}
