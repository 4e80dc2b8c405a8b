//! The OPTIMISE block of a `DYN ANA` deck: mass variables (VARYM), an
//! objective of a force's magnitude (`MINIMISE RMS b b2`), the final
//! design's deck, and what is refused, each with the line and a hint.

use std::path::Path;

use mechfem_core::dynamics::MassVar;
use mechfem_deck::rewrite::design_deck;
use mechfem_deck::rewrite_masses::with_masses;
use mechfem_deck::{compile, load, parse_str, Compiled, DiagnosticKind, Diagnostics, MassItem, Mode, Reduce};

const EXAMPLE: &str = "../../examples/balancing/slider_crank_balance.mec";

fn example_text() -> String {
    std::fs::read_to_string(EXAMPLE).expect("the example deck")
}

/// The example with its OPTIMISE block's lines replaced by `block`.
fn with_block(block: &str) -> String {
    let text = example_text();
    let start = text.find("OPTIMISE\n").expect("OPTIMISE");
    let end = text.find("STORAGE").expect("STORAGE");
    format!("{}OPTIMISE\n{block}\n{}", &text[..start], &text[end..])
}

fn compiled(text: &str) -> Result<Compiled, Diagnostics> {
    parse_str(text, "dyn.mec").and_then(|d| compile(&d, Path::new("../../examples/balancing")))
}

/// The one diagnostic of `text`: its kind, line, message and hint.
fn refused(text: &str) -> (DiagnosticKind, usize, String) {
    let e = compiled(text).expect_err("refused");
    let d = e.iter().next().expect("a diagnostic");
    (d.kind, d.line, format!("{} / {}", d.message, d.hint.clone().unwrap_or_default()))
}

#[test]
fn the_balancing_example_varies_the_cranks_centre_of_mass_and_minimises_the_rms_shaking_force() {
    let c = load(EXAMPLE).expect("compiles");
    assert_eq!(c.mode, Mode::DynAna);
    let o = c.optimise.as_ref().expect("a DYN ANA deck with OPTIMISE has an optimisation");
    assert!(o.vary.is_empty());
    let vars: Vec<_> = o.mass_vary.iter().map(|m| (m.item, m.number, m.var, m.lo, m.hi)).collect();
    assert_eq!(
        vars,
        [(MassItem::U, 1, MassVar::CentreU(0), -0.2, 0.2), (MassItem::V, 1, MassVar::CentreV(0), -0.2, 0.2)]
    );
    let objective = o.objective.expect("MINIMISE");
    assert_eq!((objective.reduce, objective.buffer, objective.with), (Reduce::Rms, 3, Some(4)));
    // The start values are the MASS line's.
    let model = c.dynamics.as_ref().expect("dynamics");
    assert_eq!(o.mass_vary[0].var.value(model), 0.03);
}

#[test]
fn every_kind_of_mass_variable_names_its_dynamics_line() {
    let c = compiled(&with_block(
        "VARYM MASS 2 0 5\nVARYM J 2 0 1\nVARYM pmass 7 0 4\nMINIMISE MAXABS 3 4\nBOUND 2 -1E5 1E5",
    ))
    .expect("compiles");
    let o = c.optimise.expect("optimise");
    let vars: Vec<_> = o.mass_vary.iter().map(|m| m.var).collect();
    assert_eq!(vars, [MassVar::Mass(1), MassVar::BodyInertia(1), MassVar::PointMass(0)]);
    assert_eq!(o.bounds.len(), 1);
}

#[test]
fn mistakes_in_varym_are_refused_with_the_line_and_how_to_fix_them() {
    let line = 60;
    let cases: [(&str, DiagnosticKind, &str); 7] = [
        ("VARYM W 1 0 1", DiagnosticKind::BadValue, "unknown item `W` of VARYM"),
        ("VARYM MASS 3 0 1", DiagnosticKind::DesignVariable, "VARYM MASS needs a MASS line on element 3"),
        ("VARYM PMASS 5 0 1", DiagnosticKind::DesignVariable, "PMASS lines on co-ordinate 7"),
        ("VARYM INERTIA 4 0 1", DiagnosticKind::DesignVariable, "has no INERTIA line"),
        ("VARYM MASS 1 -1 3", DiagnosticKind::DesignVariable, "may become negative"),
        ("VARYM U 1 0.05 0.2", DiagnosticKind::DesignVariable, "starts at 0.03 (its DYNAMICS line), outside"),
        ("VARYM U 1 0.2 -0.2", DiagnosticKind::BadValue, "lower end first"),
    ];
    for (statement, kind, words) in cases {
        let (k, l, said) = refused(&with_block(&format!("{statement}\nMINIMISE RMS 3 4")));
        assert_eq!((k, l), (kind, line), "{statement}: {said}");
        assert!(said.contains(words), "{statement}: {said}");
    }
    let (k, l, said) = refused(&with_block("VARYM U 1 -1 1\nVARYM U 1 -1 1\nMINIMISE RMS 3 4"));
    assert_eq!((k, l), (DiagnosticKind::DesignVariable, 61), "{said}");
    assert!(said.contains("varied twice (first at line 60)"), "{said}");
}

#[test]
fn an_objective_of_two_buffers_is_an_rms_or_a_peak_of_their_magnitude() {
    let (k, l, said) = refused(&with_block("VARYM U 1 -1 1\nMINIMISE MAX 3 4"));
    assert_eq!((k, l), (DiagnosticKind::BadValue, 61), "{said}");
    assert!(said.contains("MINIMISE MAX takes one buffer") && said.contains("RMS b b2"), "{said}");
    let (k, _, said) = refused(&with_block("VARYM U 1 -1 1\nMINIMISE RMS 3 40"));
    assert_eq!(k, DiagnosticKind::UnknownBuffer, "{said}");
}

#[test]
fn kinematic_synthesis_statements_and_varym_stay_in_their_own_modes() {
    let (k, l, said) = refused(&with_block("VARYM U 1 -1 1\nMINIMISE RMS 3 4\nFULLROT 4"));
    assert_eq!((k, l), (DiagnosticKind::WrongMode, 62), "{said}");
    assert!(said.contains("FULLROT belongs to the kinematic synthesis of a KIN OPT deck"), "{said}");
    let (k, l, said) = refused(&with_block("MINIMISE RMS 3 4"));
    assert_eq!((k, l), (DiagnosticKind::NothingToOptimise, 59), "{said}");
    assert!(said.contains("VARYM what n lo hi"), "{said}");
    // A DYN ANA deck without OPTIMISE has no optimisation, as before.
    let plain = load("../../examples/balancing/slider_crank_dyn.mec").expect("compiles");
    assert!(plain.optimise.is_none());
    // A DYN SIM deck has no OPTIMISE block.
    let sim = with_block("VARYM U 1 -1 1\nMINIMISE RMS 3 4").replacen("\nDYN ANA\n", "\nDYN SIM\n", 1);
    let e = parse_str(&sim, "sim.mec").expect_err("refused");
    let d = e.iter().find(|d| d.kind == DiagnosticKind::WrongMode).expect("wrong mode");
    assert!(d.message.contains("belong to the modes KIN OPT and DYN ANA"), "{}", d.message);
}

#[test]
fn the_final_design_is_a_dyn_ana_deck_with_the_new_masses_and_without_optimise() {
    let text = example_text();
    let masses = [(MassItem::U, 1, -0.0889), (MassItem::V, 1, 0.0), (MassItem::PointMass, 7, 1.25)];
    let out = with_masses(&text, "b.mec", &masses).expect("rewritten");
    let out = design_deck(&out, "b.mec", &[], &[], None).expect("rewritten");
    assert!(out.contains("\nDYN ANA\n"));
    assert!(out.contains("MASS  1 2.0 -0.0889 0 0.004    ; crank with its counterweight"), "{out}");
    assert!(out.contains("PMASS 7 8 1.25                 ; piston"), "{out}");
    assert!(!out.contains("VARYM") && !out.contains("\nOPTIMISE"));
    let c = compiled(&out).expect("the written deck compiles");
    assert!(c.optimise.is_none());
    let model = c.dynamics.expect("dynamics");
    assert_eq!((model.bodies[0].u, model.point_masses[0].mass), (-0.0889, 1.25));
}
