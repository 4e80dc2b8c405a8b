//! The mode `DYN SIM`: what MOV_DYN and INTTOL compile to (the core's
//! [`InputMotion::Dynamic`] and [`Integration`]), and what is refused.

use std::path::Path;

use mechfem_core::dynamics::Integration;
use mechfem_core::{InputMotion, Params};
use mechfem_deck::{compile, parse_str, Compiled, DiagnosticKind, Diagnostics, Mode};

/// A pendulum: a bar of length 1 about (0, 0), its angle the one DOF, a
/// point mass at its end and gravity: lines 2..14 of a deck.
const PENDULUM: &str = "TOPOLOGY
ELEM 1 BIN 1 2 3 4
FORM 1 LENL 1 1
     2 ANGB 1 2
NRDOF 1
GEOMETRY
XFIX 1 0.0
     2 0.0
XMOV 3 1.0
     4 0.0
DYNAMICS
PMASS 3 4 2.0
GRAVITY 0 -9.81
";

/// A pendulum hanging from a crank: DOF 1 the crank angle, DOF 2 the
/// pendulum's angle: lines 2..19 of a deck.
const CRANK_AND_PENDULUM: &str = "TOPOLOGY
ELEM 1 BIN 1 2 3 4
     2 BIN 3 4 5 6
FORM 1 LENL 1 1
     2 LENL 2 2
     3 ANGB 1 3
     4 ANGB 2 4
NRDOF 2
GEOMETRY
XFIX 1 0.0
     2 0.0
XMOV 3 0.2
     4 0.0
     5 0.2
     6 -1.0
DYNAMICS
PMASS 5 6 1.0
GRAVITY 0 -9.81
";

fn compiled(text: &str) -> Result<Compiled, Diagnostics> {
    parse_str(text, "sim.mec").and_then(|d| compile(&d, Path::new(".")))
}

fn ok(text: &str) -> Compiled {
    compiled(text).unwrap_or_else(|e| panic!("should compile:\n{e}"))
}

/// The pendulum in `mode` with the MOVEMENT block `movement` (its header
/// at line 15, its keywords from line 16); in `KIN ANA` without the
/// DYNAMICS block (lines 12..14), which that mode does not have.
fn pendulum(mode: &str, movement: &str) -> String {
    let text = format!("{mode}\n{PENDULUM}MOVEMENT\n{movement}");
    if mode == "KIN ANA" {
        text.replace("DYNAMICS\nPMASS 3 4 2.0\nGRAVITY 0 -9.81\n", "\n\n\n")
    } else {
        text
    }
}

/// Every diagnostic's kind and line.
fn errors(text: &str) -> Vec<(DiagnosticKind, usize)> {
    compiled(text).expect_err("should be refused").iter().map(|d| (d.kind, d.line)).collect()
}

#[test]
fn mov_dyn_compiles_to_an_input_moved_by_the_forces() {
    let c = ok(&pendulum("DYN SIM", "TSTEPE 240 0.01\nMOV_DYN 1 0\n"));
    assert_eq!(c.mode, Mode::DynSim);
    let motion = c.motion.as_ref().expect("motion");
    assert_eq!((motion.steps, motion.dt), (240, 0.01));
    assert_eq!(motion.inputs, [InputMotion::Dynamic { v0: 0.0 }]);
    assert!(c.dynamics.is_some_and(|d| d.point_masses.len() == 1 && d.gravity == [0.0, -9.81]));
}

#[test]
fn the_initial_velocity_is_0_or_of_a_magnitude_from_1e_minus_100_to_1e100() {
    for (word, v0) in [("-3.5", -3.5), ("1.5D1", 15.0), ("-0", 0.0), ("1e100", 1e100), ("-1e-100", -1e-100)] {
        let c = ok(&pendulum("DYN SIM", &format!("TSTEPE 10 0.01\nMOV_DYN 1 {word}\n")));
        assert_eq!(c.motion.expect("motion").inputs, [InputMotion::Dynamic { v0 }], "{word}");
    }
    for (word, kind) in [
        ("nan", DiagnosticKind::NotANumber),
        ("-inf", DiagnosticKind::NotANumber),
        ("1e300", DiagnosticKind::NumberOutOfRange),
        ("-1.1e100", DiagnosticKind::NumberOutOfRange),
        ("1e-320", DiagnosticKind::NumberOutOfRange),
    ] {
        let text = pendulum("DYN SIM", &format!("TSTEPE 10 0.01\nMOV_DYN 1 {word}\n"));
        assert_eq!(errors(&text), [(kind, 17)], "{word}");
    }
}

#[test]
fn a_dof_moved_by_the_forces_beside_a_driven_one() {
    // The motions come in DOF order, whatever the order of their lines.
    let text = format!("DYN SIM\n{CRANK_AND_PENDULUM}MOVEMENT\nTSTEPE 100 0.02\nMOV_DYN 2 0.5\nMOV_RELE 1 12.5\n");
    let c = ok(&text);
    let motion = c.motion.expect("motion");
    assert_eq!(motion.inputs, [InputMotion::Relative { delta: 12.5 }, InputMotion::Dynamic { v0: 0.5 }]);
}

#[test]
fn a_simulation_may_drive_every_dof() {
    let c = ok(&pendulum("DYN SIM", "TSTEPE 10 0.01\nMOV_ABSE 1 1.0\n"));
    assert_eq!(c.motion.expect("motion").inputs, [InputMotion::Absolute { end: 1.0 }]);
}

#[test]
fn inttol_sets_the_integrators_tolerances() {
    let c = ok(&pendulum("DYN SIM", "TSTEPE 10 0.01\nMOV_DYN 1 0\nACCURACY 1e-11\nINTTOL 1e-9 1E-12\n"));
    assert_eq!(c.integration, Integration::new(1e-9, 1e-12));
    assert_eq!(c.params.tol, 1e-11);
}

#[test]
fn without_inttol_the_integrator_follows_accuracy() {
    let c = ok(&pendulum("DYN SIM", "TSTEPE 10 0.01\nMOV_DYN 1 0\nACCURACY 1e-9\n"));
    assert_eq!(c.integration, Integration::from_accuracy(1e-9));
    assert_eq!(c.integration, Integration::new(1e-9, 1e-9));
    let c = ok(&pendulum("DYN SIM", "TSTEPE 10 0.01\nMOV_DYN 1 0\n"));
    assert_eq!(c.integration, Integration::from_accuracy(Params::default().tol));
}

#[test]
fn every_deck_has_the_integrators_tolerances() {
    let kin = ok(&pendulum("KIN ANA", "TSTEPE 10 0.01\nMOV_RELE 1 1\n"));
    assert_eq!(kin.integration, Integration::from_accuracy(Params::default().tol));
    let ana = ok(&pendulum("DYN ANA", "TSTEPE 10 0.01\nMOV_RELE 1 1\nACCURACY 1e-8\n"));
    assert_eq!(ana.integration, Integration::from_accuracy(1e-8));
}

#[test]
fn inttol_tolerances_are_finite_and_positive() {
    for (args, kind) in [
        ("0 1e-10", DiagnosticKind::BadValue),
        ("1e-8 -1e-10", DiagnosticKind::BadValue),
        ("-0 1e-10", DiagnosticKind::BadValue),
        ("nan 1e-10", DiagnosticKind::NotANumber),
        ("1e-8 1e999", DiagnosticKind::NumberOutOfRange),
        ("1e-8", DiagnosticKind::ArgumentCount),
        ("1e-8 1e-10 1e-12", DiagnosticKind::ArgumentCount),
    ] {
        let text = pendulum("DYN SIM", &format!("TSTEPE 10 0.01\nMOV_DYN 1 0\nINTTOL {args}\n"));
        assert_eq!(errors(&text), [(kind, 18)], "INTTOL {args}");
    }
    let twice = pendulum("DYN SIM", "TSTEPE 10 0.01\nMOV_DYN 1 0\nINTTOL 1e-8 1e-10\nINTTOL 1e-8 1e-10\n");
    assert_eq!(errors(&twice), [(DiagnosticKind::DuplicateKeyword, 19)]);
}

#[test]
fn mov_dyn_and_inttol_belong_to_dyn_sim() {
    for mode in ["KIN ANA", "DYN ANA"] {
        let text = pendulum(mode, "TSTEPE 10 0.01\nMOV_DYN 1 0\nINTTOL 1e-8 1e-10\n");
        let e = compiled(&text).expect_err("refused");
        let found: Vec<(DiagnosticKind, &str)> = e.iter().map(|d| (d.kind, d.text.as_str())).collect();
        assert_eq!(
            found,
            [(DiagnosticKind::WrongMode, "MOV_DYN 1 0"), (DiagnosticKind::WrongMode, "INTTOL 1e-8 1e-10")],
            "{mode}"
        );
        let hint = e.0[0].hint.as_deref().unwrap_or_default();
        assert!(hint.contains("`DYN SIM`") && hint.contains("MOV_RELE"), "{hint}");
        assert!(e.0[0].message.contains(mode), "{}", e.0[0].message);
    }
}

#[test]
fn a_simulation_needs_dynamics_and_movement() {
    let bare = format!("DYN SIM\n{}", PENDULUM.split("DYNAMICS").next().unwrap_or_default());
    let e = compiled(&bare).expect_err("refused");
    let found: Vec<(DiagnosticKind, usize, &str)> = e.iter().map(|d| (d.kind, d.line, d.message.as_str())).collect();
    assert_eq!(
        found,
        [
            (DiagnosticKind::MissingBlock, 1, "this DYN SIM deck has no DYNAMICS block"),
            (
                DiagnosticKind::MissingBlock,
                1,
                "this DYN SIM deck has no MOVEMENT block: a simulation needs its output times"
            ),
        ]
    );
    // Inverse dynamics may still compute position 1 alone.
    assert!(ok(&format!("DYN ANA\n{PENDULUM}")).motion.is_none());
}

#[test]
fn free_motion_cannot_drive_a_simulation() {
    let text = pendulum("DYN SIM", "TSTEPE 10 0.01\nMOV_FREE 1 0.01\n");
    let e = compiled(&text).expect_err("refused");
    assert_eq!((e.0[0].kind, e.0[0].line), (DiagnosticKind::WrongMode, 17));
    assert!(e.0[0].hint.as_deref().is_some_and(|h| h.contains("MOV_DYN j v0")), "{e}");
}

#[test]
fn every_dof_of_a_simulation_has_one_motion() {
    let head = format!("DYN SIM\n{CRANK_AND_PENDULUM}MOVEMENT\nTSTEPE 10 0.01\n");
    let e = compiled(&format!("{head}MOV_DYN 2 0\n")).expect_err("refused");
    assert_eq!((e.0[0].kind, e.0[0].message.as_str()), (DiagnosticKind::MissingMotion, "DOF 1 has no motion"));
    let hint = e.0[0].hint.as_deref().unwrap_or_default();
    assert!(hint.contains("`MOV_DYN 1 v0`") && !hint.contains("MOV_FREE"), "{hint}");
    let e = compiled(&format!("{head}MOV_DYN 1 0\nMOV_DYN 2 0\nMOV_RELE 1 1\n")).expect_err("refused");
    assert_eq!((e.0[0].kind, e.0[0].line), (DiagnosticKind::DuplicateMotion, 24));
    let e = compiled(&format!("{head}MOV_DYN 3 0\n")).expect_err("refused");
    assert_eq!(e.0[0].kind, DiagnosticKind::UnknownDof);
}

#[test]
fn only_a_simulation_offers_mov_dyn_for_a_dof_without_motion() {
    for (mode, offered) in [("KIN ANA", false), ("DYN ANA", false), ("DYN SIM", true)] {
        let e = compiled(&pendulum(mode, "TSTEPE 10 0.01\n")).expect_err("refused");
        assert_eq!(e.0[0].kind, DiagnosticKind::MissingMotion, "{mode}");
        let hint = e.0[0].hint.as_deref().unwrap_or_default();
        assert_eq!(hint.contains("MOV_DYN"), offered, "{mode}: {hint}");
    }
}

#[test]
fn the_modes_with_dynamics() {
    assert!(Mode::DynAna.has_dynamics() && Mode::DynSim.has_dynamics());
    assert!(!Mode::KinAna.has_dynamics() && !Mode::KinOpt.has_dynamics());
}

#[test]
fn without_accuracy_the_newton_tolerance_follows_inttol() {
    let c = ok(&pendulum("DYN SIM", "TSTEPE 10 0.01\nMOV_DYN 1 0\nINTTOL 1e-12 1e-13\n"));
    assert!((c.params.tol - 1e-14).abs() < 1e-28);
    let c = ok(&pendulum("DYN SIM", "TSTEPE 10 0.01\nMOV_DYN 1 0\nINTTOL 1e-6 1e-6\n"));
    assert_eq!(c.params.tol, Params::default().tol);
    let c = ok(&pendulum("DYN SIM", "TSTEPE 10 0.01\nMOV_DYN 1 0\nINTTOL 1e-10 1e-10\n"));
    assert!((c.params.tol - 1e-11).abs() < 1e-25);
    assert!(c.integration.conflict(c.params.tol).is_none());
    let c = ok(&pendulum("DYN SIM", "TSTEPE 10 0.01\nMOV_DYN 1 0\nACCURACY 1e-10\nINTTOL 1e-13 1e-13\n"));
    assert!(c.integration.conflict(c.params.tol).is_some_and(|w| w.contains("ACCURACY")));
}

#[test]
fn integrator_and_stopwhen_choose_the_method_and_the_end() {
    use mechfem_core::dynamics::Integrator;
    let c = ok(&pendulum("DYN SIM", "TSTEPE 10 0.01\nMOV_DYN 1 0\n"));
    assert_eq!((c.integration.integrator, c.integration.stop_when), (Integrator::Auto, None));
    for (word, method) in [
        ("auto", Integrator::Auto),
        ("explicit", Integrator::Dopri5),
        ("Implicit", Integrator::Radau5),
        ("DOP853", Integrator::Dop853),
        ("dopri5", Integrator::Dopri5),
        ("radau5", Integrator::Radau5),
    ] {
        let c = ok(&pendulum("DYN SIM", &format!("TSTEPE 10 0.01\nMOV_DYN 1 0\nINTEGRATOR {word}\n")));
        assert_eq!(c.integration.integrator, method, "{word}");
    }
    let c = ok(&pendulum("DYN SIM", "TSTEPE 10 0.01\nMOV_DYN 1 0\nSTOPWHEN 2 -1.5\nSTORAGE\nBUFTIME 1\nBUFINP 1 2\n"));
    let sw = c.integration.stop_when.expect("STOPWHEN");
    assert_eq!((sw.buffer, sw.value), (2, -1.5));
    assert_eq!(Some(sw.quantity), c.buffers.iter().find(|b| b.number == 2).map(|b| b.quantity));
}
