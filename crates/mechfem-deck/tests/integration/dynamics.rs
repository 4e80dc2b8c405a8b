//! The DYNAMICS block and the dynamics buffers: what a `DYN ANA` deck
//! compiles to, with the core's 0-based indices, and what is refused.
//! (`DYN SIM` and its MOVEMENT keywords: `tests/simulation.rs`.)

use std::path::{Path, PathBuf};

use mechfem_core::dynamics::{Body, Force, Inertia, Load, LoadKind, PointMass};
use mechfem_core::{FormRef, Quantity};
use mechfem_deck::{compile, parse_str, Compiled, DiagnosticKind, Diagnostics, Mode};

/// A four-bar (crank 1, coupler 2, rocker 3) with a dependent form
/// parameter: 8 co-ordinates, 1..4 fixed, rows 1..4, dependent -1.
const FOUR_BAR: &str = "TOPOLOGY
ELEM 1 BIN 1 2 5 6
     2 BIN 5 6 7 8
     3 BIN 3 4 7 8
FORM 1 LENL 1 1
     2 LENL 2 2
     3 LENL 3 3
     4 ANGB 1 4
     5 ANGB 3 -1
NRDOF 1
GEOMETRY
XFIX 1 0.0
     2 0.0
     3 4.0
     4 0.0
XMOV 5 1.0
     6 0.5
     7 3.5
     8 2.0
";

fn deck(mode: &str, rest: &str) -> String {
    format!("{mode}\n{FOUR_BAR}{rest}")
}

fn compiled(text: &str, dir: &Path) -> Result<Compiled, Diagnostics> {
    parse_str(text, "dyn.mec").and_then(|d| compile(&d, dir))
}

fn ok(text: &str) -> Compiled {
    compiled(text, Path::new(".")).unwrap_or_else(|e| panic!("should compile:\n{e}"))
}

/// The first diagnostic's kind, message and line.
fn first_error(text: &str, dir: &Path) -> (DiagnosticKind, String, usize) {
    let e = compiled(text, dir).expect_err("should be refused");
    let d = &e.0[0];
    (d.kind, d.message.clone(), d.line)
}

/// A fresh folder for files a test writes.
fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("mechfem-deck-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("scratch folder");
    dir
}

#[test]
fn every_item_gets_the_cores_zero_based_indices() {
    let c = ok(&deck(
        "DYN ANA",
        "DYNAMICS
MASS 1 1.0 0.5 0.0
     3 2.0 1.0 0.25 0.3
PMASS 7 8 0.4
      5 6 0.1
INERTIA 2 0.05
GRAVITY 0 -9.81
FORCE 7 8 1.5 -2.5
LOAD 4 3.0
     -1 -1.0
SPRING 2 100 1.2
MOTOR 4 5.0 -20.0
STORAGE
BUFSIG 3 1
BUFDRV 1 2
BUFREA 4 3
BUFEKIN 4
BUFEPOT 5
BUFPOW 6
BUFMRED 1 1 7
",
    ));
    assert_eq!(c.mode, Mode::DynAna);
    let d = c.dynamics.as_ref().expect("dynamics");
    assert_eq!(
        d.bodies,
        [
            Body { element: 0, mass: 1.0, u: 0.5, v: 0.0, inertia: 0.0 },
            Body { element: 2, mass: 2.0, u: 1.0, v: 0.25, inertia: 0.3 },
        ]
    );
    assert_eq!(d.point_masses, [PointMass { x: 6, y: 7, mass: 0.4 }, PointMass { x: 4, y: 5, mass: 0.1 }]);
    assert_eq!(d.inertias, [Inertia { coord: 1, inertia: 0.05 }]);
    assert_eq!(d.gravity, [0.0, -9.81]);
    assert_eq!(d.forces, [Force { x: 6, y: 7, f: [1.5, -2.5] }]);
    assert_eq!(
        d.loads,
        [
            Load { form: FormRef::Prescribed(3), kind: LoadKind::Constant(3.0) },
            Load { form: FormRef::Dependent(0), kind: LoadKind::Constant(-1.0) },
            Load { form: FormRef::Prescribed(1), kind: LoadKind::Spring { k: 100.0, e0: 1.2, c: 0.0 } },
            Load { form: FormRef::Prescribed(3), kind: LoadKind::Motor { t0: 5.0, w0: -20.0 } },
        ]
    );
    let quantities: Vec<Quantity> = c.buffers.iter().map(|b| b.quantity).collect();
    assert_eq!(
        quantities,
        [
            Quantity::Sigma(2),
            Quantity::Drive(0),
            Quantity::Reaction(3),
            Quantity::Ekin,
            Quantity::Epot,
            Quantity::Power,
            Quantity::Mred(0, 0),
        ]
    );
    assert_eq!(d.check(&c.mechanism), Ok(()));
}

#[test]
fn a_kin_ana_deck_has_no_dynamics() {
    let c = ok(&deck("KIN ANA", ""));
    assert_eq!(c.mode, Mode::KinAna);
    assert!(c.dynamics.is_none());
}

#[test]
fn an_empty_dynamics_block_is_a_model_without_masses() {
    let c = ok(&deck("DYN ANA", "DYNAMICS\n"));
    let d = c.dynamics.expect("dynamics");
    assert!(d.is_massless() && d.loads.is_empty() && d.gravity == [0.0, 0.0]);
}

#[test]
fn a_dyn_ana_deck_without_movement_is_position_one_only() {
    let c = ok(&deck("DYN ANA", "DYNAMICS\nMASS 1 1 0.5 0\n"));
    assert!(c.motion.is_none());
    assert!(c.dynamics.is_some());
}

#[test]
fn a_kin_opt_deck_has_no_dynamics() {
    let e = compiled(&deck("KIN OPT", "DYNAMICS\n"), Path::new(".")).expect_err("refused");
    let found: Vec<(DiagnosticKind, usize)> = e.iter().map(|d| (d.kind, d.line)).collect();
    // Besides, it lacks the MOVEMENT and OPTIMISE blocks a KIN OPT deck needs.
    assert_eq!(
        found,
        [(DiagnosticKind::MissingBlock, 1), (DiagnosticKind::MissingBlock, 1), (DiagnosticKind::WrongMode, 21)]
    );
    assert!(e.0[2].message.contains("KIN OPT deck has no DYNAMICS block"), "{e}");
}

#[test]
fn the_dynamics_of_a_kin_ana_deck_are_all_reported() {
    let text = deck("KIN ANA", "DYNAMICS\nMASS 1 1 0.5 0\nSTORAGE\nBUFINP 1 1\nBUFEKIN 2\nBUFPOW 3\n");
    let e = compiled(&text, Path::new(".")).expect_err("refused");
    let found: Vec<(DiagnosticKind, usize)> = e.iter().map(|d| (d.kind, d.line)).collect();
    assert_eq!(
        found,
        [(DiagnosticKind::WrongMode, 21), (DiagnosticKind::WrongMode, 25), (DiagnosticKind::WrongMode, 26)]
    );
}

#[test]
fn dynamics_keywords_belong_in_their_block() {
    let text = format!("DYN ANA\n{FOUR_BAR}GRAVITY 0 -9.81\nDYNAMICS\n");
    let (kind, message, _) = first_error(&text, Path::new("."));
    assert_eq!(kind, DiagnosticKind::WrongBlock);
    assert_eq!(message, "GRAVITY belongs in the DYNAMICS block, not in GEOMETRY");
}

#[test]
fn masses_and_loads_that_are_not_finite_or_negative_are_refused() {
    for (line, kind) in [
        ("MASS 1 nan 0 0", DiagnosticKind::NotANumber),
        ("MASS 1 1 inf 0", DiagnosticKind::NotANumber),
        ("GRAVITY 0 1e999", DiagnosticKind::NumberOutOfRange),
        ("PMASS 5 6 -1e-300", DiagnosticKind::BadValue),
        ("SPRING 1 1 0 -1e-300", DiagnosticKind::BadValue),
        ("MOTOR 4 1 -0.0", DiagnosticKind::BadValue),
    ] {
        let text = deck("DYN ANA", &format!("DYNAMICS\n{line}\n"));
        let (found, message, _) = first_error(&text, Path::new("."));
        assert_eq!(found, kind, "{line}: {message}");
    }
    // -0 is zero, not negative.
    ok(&deck("DYN ANA", "DYNAMICS\nINERTIA 5 -0\n"));
}

#[test]
fn the_arguments_of_dynamics_keywords_are_counted() {
    for line in
        ["MASS 1 1 0", "MASS 1 1 0 0 0 0", "PMASS 5 6", "GRAVITY -9.81", "FORCE 5 6 1", "SPRING 1 1", "MOTOR 4 1"]
    {
        let text = deck("DYN ANA", &format!("DYNAMICS\n{line}\n"));
        let (kind, message, _) = first_error(&text, Path::new("."));
        assert_eq!(kind, DiagnosticKind::ArgumentCount, "{line}: {message}");
    }
}

#[test]
fn a_load_table_is_read_beside_the_deck() {
    let dir = scratch("table");
    std::fs::write(dir.join("load.dat"), "; t value\n0 1\n\n1.0, 2.0  # ramp\n1 3\n").expect("table");
    let c = compiled(&deck("DYN ANA", "DYNAMICS\nLOADFUNC -1 load.dat\n"), &dir).expect("compiles");
    let rows = vec![[0.0, 1.0], [1.0, 2.0], [1.0, 3.0]];
    assert_eq!(
        c.dynamics.expect("dynamics").loads,
        [Load { form: FormRef::Dependent(0), kind: LoadKind::Table(rows) }]
    );
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_load_table_larger_than_the_limit_is_not_read() {
    let dir = scratch("large");
    let file = std::fs::File::create(dir.join("huge.dat")).expect("file");
    // A sparse file: large, but nothing is written.
    file.set_len(9 << 20).expect("length");
    let (kind, message, line) = first_error(&deck("DYN ANA", "DYNAMICS\nLOADFUNC 4 huge.dat\n"), &dir);
    assert_eq!((kind, line), (DiagnosticKind::LoadFile, 22));
    assert_eq!(message, "the LOADFUNC file `huge.dat` is larger than 8 MiB");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_load_table_that_is_a_folder_is_refused() {
    let dir = scratch("folder");
    std::fs::create_dir_all(dir.join("sub")).expect("folder");
    let (kind, message, _) = first_error(&deck("DYN ANA", "DYNAMICS\nLOADFUNC 4 sub\n"), &dir);
    assert_eq!(kind, DiagnosticKind::LoadFile);
    assert!(message.ends_with("it is a folder"), "{message}");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_reaction_is_asked_of_a_fixed_coordinate() {
    let text = deck("DYN ANA", "DYNAMICS\nSTORAGE\nBUFREA 1 1\nBUFREA 5 2\n");
    let (kind, message, line) = first_error(&text, Path::new("."));
    assert_eq!((kind, line), (DiagnosticKind::NotFixed, 24), "{message}");
}

#[test]
fn the_motion_hint_of_a_dyn_ana_deck_offers_no_free_motion() {
    let text = deck("DYN ANA", "DYNAMICS\nMOVEMENT\nTSTEPE 4 0.1\n");
    let e = compiled(&text, Path::new(".")).expect_err("refused");
    assert_eq!(e.0[0].kind, DiagnosticKind::MissingMotion);
    let hint = e.0[0].hint.as_deref().unwrap_or("");
    assert!(hint.contains("MOV_FUNC 1 file") && !hint.contains("MOV_FREE"), "{hint}");
}

/// A result of inverse dynamics that overflows mid-run stops the run at the
/// position before, with the quantity and the mass named; nothing non-finite
/// is recorded.
#[test]
fn an_overflowing_dynamics_result_stops_the_run_and_names_the_mass() {
    use mechfem_core::{DynamicQuantity, DynamicSource, DynamicsFault, InverseDynamics, Recorder, SolveError};
    let text = std::fs::read_to_string("../../tests/decks/dynamics_overflow.mec").expect("deck");
    let c = compiled(&text, Path::new(".")).expect("the deck compiles");
    let model = c.dynamics.clone().expect("a DYN deck");
    let quantities = vec![Quantity::Epot, Quantity::Ekin, Quantity::Drive(0)];
    let mut rec = Recorder::new(quantities, false).with_dynamics(InverseDynamics::new(&c.mechanism, model));
    let mut state = c.state.clone();
    let report = mechfem_core::run(&c.mechanism, &mut state, c.motion.as_ref(), &c.params, &mut rec).expect("run");
    assert_eq!(report.positions, 1);
    let stop = report.stop.expect("a stop");
    assert_eq!(stop.last_good, 0);
    let fault =
        DynamicsFault { quantity: DynamicQuantity::PotentialEnergy, source: DynamicSource::PointMass { x: 2, y: 3 } };
    assert_eq!(stop.error, SolveError::Dynamics(fault));
    assert_eq!(rec.positions(), 1);
    assert!(rec.data().iter().all(|v| v.is_finite()), "{:?}", rec.data());
    // The state is left at the position recorded.
    assert_eq!(state.x[2], 1e100);
}
