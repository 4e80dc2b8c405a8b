//! Golden decks: every deck in `decks/valid` loads; every deck in
//! `decks/invalid` fails with exactly the diagnostic in its `.snap` file.
//!
//! Run with `UPDATE_SNAPSHOTS=1` to rewrite the snapshots, then read them.

use std::path::{Path, PathBuf};

use mechfem_core::dynamics::{Body, Force, Inertia, Integration, Load, LoadKind, PointMass};
use mechfem_core::{FormRef, InputMotion, Quantity};
use mechfem_deck::{load, Compiled, Mode, PlotItem};

/// Deck paths are relative to the crate folder (cargo's working directory
/// for tests), so rendered diagnostics do not depend on the checkout.
fn decks(folder: &str) -> Vec<PathBuf> {
    let dir = Path::new("tests/decks").join(folder);
    let mut out: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "mec"))
        .collect();
    out.sort();
    out
}

fn valid(name: &str) -> Compiled {
    let path = Path::new("tests/decks/valid").join(name);
    load(&path).unwrap_or_else(|e| panic!("{} should load:\n{e}", path.display()))
}

#[test]
fn every_valid_deck_loads() {
    let all = decks("valid");
    assert!(all.len() >= 6);
    for path in all {
        if let Err(e) = load(&path) {
            panic!("{} should load:\n{e}", path.display());
        }
    }
}

#[test]
fn every_invalid_deck_matches_its_snapshot() {
    let update = std::env::var_os("UPDATE_SNAPSHOTS").is_some_and(|v| v == "1");
    let all = decks("invalid");
    assert!(all.len() >= 25, "only {} invalid decks", all.len());
    let mut failures = Vec::new();
    for path in all {
        let rendered = match load(&path) {
            Ok(_) => {
                failures.push(format!("{} loaded, but should fail", path.display()));
                continue;
            }
            Err(e) => format!("{e}\n"),
        };
        let snap = path.with_extension("snap");
        if update {
            std::fs::write(&snap, &rendered).expect("write snapshot");
            continue;
        }
        match std::fs::read_to_string(&snap) {
            Ok(expected) if expected == rendered => {}
            Ok(expected) => failures.push(format!(
                "{} differs from its snapshot\n--- expected\n{expected}--- got\n{rendered}",
                path.display()
            )),
            Err(_) => failures.push(format!("{} has no snapshot; got\n{rendered}", path.display())),
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn every_snapshot_has_its_deck() {
    let dir = Path::new("tests/decks/invalid");
    for entry in std::fs::read_dir(dir).expect("invalid decks").flatten() {
        let p = entry.path();
        if p.extension().is_some_and(|x| x == "snap") {
            assert!(p.with_extension("mec").exists(), "{} has no deck", p.display());
        }
    }
}

#[test]
fn supply_mechanism_of_tables_5_1_to_5_3() {
    let c = valid("supply_mechanism.mec");
    assert_eq!(c.mode, Mode::KinAna);
    assert!(c.dynamics.is_none());
    let m = &c.mechanism;
    assert_eq!(m.n_coords(), 20);
    assert_eq!(m.n_moving(), 12);
    assert_eq!(m.n_prescribed(), 12);
    assert_eq!(m.n_dependent(), 1);
    assert_eq!(m.n_dof(), 1);
    assert_eq!(m.elements().len(), 8);
    assert_eq!(c.elements[5].ty.name(), "TR2");
    assert_eq!(c.elements[5].coords, [5, 6, 17, 18, 15, 16]);
    // Row 5 combines ANGB of elements 2 and 4; row 12 is the input.
    let row5 = &c.prescribed[4];
    assert_eq!(row5.terms.len(), 2);
    assert_eq!((row5.terms[1].element, row5.terms[1].name, row5.terms[1].factor), (4, "ANGB", -1.0));
    assert_eq!(row5.para, Some(-5.17514));
    assert_eq!(c.prescribed[11].input, Some(1));
    assert_eq!(c.prescribed[11].para, None);
    assert_eq!(m.prescribed_terms(4).len(), 2);
    // PARA values go to the state's targets.
    assert_eq!(c.state.target[0], 0.4);
    assert_eq!(c.state.target[4], -5.17514);
    assert_eq!(c.state.target[10], 0.64952);
    assert_eq!(c.state.x[8], 0.2);
    let motion = c.motion.as_ref().expect("motion");
    assert_eq!((motion.steps, motion.dt), (36, 1.0));
    assert_eq!(motion.inputs, [InputMotion::Relative { delta: std::f64::consts::TAU }]);
    let quantities: Vec<_> = c.buffers.iter().map(|b| (b.number, b.quantity)).collect();
    assert_eq!(
        quantities,
        [
            (99, Quantity::Input(0)),
            (100, Quantity::E0(FormRef::Dependent(0))),
            (101, Quantity::Ke1(FormRef::Dependent(0), 0)),
            (102, Quantity::Ke2(FormRef::Dependent(0), 0, 0)),
        ]
    );
    assert_eq!(c.printbuf, Some(vec![]));
    assert_eq!(c.animate.as_deref(), Some("film"));
    assert_eq!(c.pictures.len(), 2);
    assert_eq!(c.pictures[0].items, [PlotItem::Hodograph { x: 12, y: 13 }]);
    assert_eq!(c.pictures[1].items.len(), 3);
    assert_eq!(c.pictures[1].items[2], PlotItem::Function { x: 99, y: 102 });
}

#[test]
fn tabs_fortran_numbers_lowercase_and_repetition() {
    let c = valid("lexical.mec");
    let m = &c.mechanism;
    assert_eq!((m.n_coords(), m.n_moving(), m.n_dof()), (8, 4, 1));
    assert_eq!(c.state.x[4], 1.0);
    assert_eq!(c.state.x[5], 0.5);
    assert_eq!(c.state.x[7], 4e-1);
    assert_eq!(c.state.target[0], 1.5);
    assert_eq!(c.params.tol, 1e-12);
    assert_eq!(c.params.max_iter, 40);
    let motion = c.motion.as_ref().expect("motion");
    assert_eq!((motion.steps, motion.dt), (12, 0.05));
    assert_eq!(motion.inputs, [InputMotion::Absolute { end: 2.5 }]);
    assert_eq!(c.savedata, [1, 2, 3]);
    assert_eq!(c.pictures[0].title, "Coupler  point, path");
}

#[test]
fn two_degrees_of_freedom() {
    let c = valid("two_dof.mec");
    let m = &c.mechanism;
    assert_eq!((m.n_moving(), m.n_prescribed(), m.n_dof()), (6, 6, 2));
    assert_eq!(m.moving_coords(), [0, 1, 2, 3, 4, 5]);
    assert_eq!(c.prescribed[3].input, None);
    assert_eq!(c.prescribed[4].input, Some(1));
    assert_eq!(c.prescribed[5].input, Some(2));
    let motion = c.motion.as_ref().expect("motion");
    assert!(matches!(motion.inputs[0], InputMotion::Relative { .. }));
    assert!(matches!(motion.inputs[1], InputMotion::Absolute { .. }));
    assert_eq!(c.buffers[1].quantity, Quantity::Kx2 { coord: 4, j: 0, m: 1 });
    assert_eq!(c.buffers[2].quantity, Quantity::Kx2 { coord: 4, j: 1, m: 1 });
}

#[test]
fn motion_from_a_file() {
    let c = valid("motion_file.mec");
    let motion = c.motion.as_ref().expect("motion");
    assert_eq!(motion.steps, 4);
    let InputMotion::Table { rows } = &motion.inputs[0] else { panic!("expected a table") };
    assert_eq!(rows.len(), 5);
    assert_eq!(rows[0], [0.0, 0.0, 0.0, 0.0]);
    assert_eq!(rows[1], [0.1, 0.25, 3.0, 0.0]);
    assert_eq!(rows[4], [0.4, 1.5, 4.0, -1.5]);
}

#[test]
fn combined_and_dependent_rows() {
    let c = valid("combined_rows.mec");
    let m = &c.mechanism;
    assert_eq!(m.n_dependent(), 3);
    assert_eq!(c.dependent[0].dest, -1);
    assert_eq!(c.dependent[2].terms.len(), 2);
    assert_eq!(c.dependent[2].terms[1].factor, -1.0);
    // A PARA on a combined row prescribes the combination.
    let combined = c.prescribed.iter().position(|r| r.terms.len() == 2).expect("a combined row");
    assert_eq!(c.prescribed[combined].para, Some(0.5));
    assert_eq!(c.state.target[combined], 0.5);
}

#[test]
fn without_movement_only_position_one() {
    let c = valid("no_movement.mec");
    assert!(c.motion.is_none());
    assert!(c.buffers.is_empty());
    assert_eq!(c.printbuf, None);
    assert_eq!(c.params, mechfem_core::Params::default());
}

#[test]
fn free_motion_and_all_buffer_kinds() {
    let c = valid("free_motion.mec");
    let motion = c.motion.as_ref().expect("motion");
    assert_eq!(motion.inputs, [InputMotion::Free { ds: 0.02 }]);
    assert_eq!(c.buffers.len(), 13);
    assert_eq!(c.printbuf, Some(vec![1, 2, 13]));
    assert!(matches!(c.pictures[0].items[0], PlotItem::Curve { x: 3, y: 4 }));
}

fn quantities(c: &Compiled) -> Vec<Quantity> {
    c.buffers.iter().map(|b| b.quantity).collect()
}

#[test]
fn pendulum_in_dyn_ana() {
    let c = valid("pendulum.mec");
    assert_eq!(c.mode, Mode::DynAna);
    let d = c.dynamics.as_ref().expect("dynamics");
    assert_eq!(d.bodies, [Body { element: 0, mass: 2.0, u: 1.0, v: 0.0, inertia: 0.01 }]);
    assert_eq!(d.gravity, [0.0, -9.81]);
    assert!(d.point_masses.is_empty() && d.inertias.is_empty() && d.forces.is_empty() && d.loads.is_empty());
    assert_eq!(
        quantities(&c),
        [
            Quantity::Time,
            Quantity::Input(0),
            Quantity::Sigma(0),
            Quantity::Drive(0),
            Quantity::Reaction(0),
            Quantity::Reaction(1),
            Quantity::Ekin,
            Quantity::Epot,
            Quantity::Power,
            Quantity::Mred(0, 0),
        ]
    );
    let motion = c.motion.as_ref().expect("motion");
    assert_eq!((motion.steps, motion.dt), (36, 0.05));
}

#[test]
fn slider_crank_with_every_kind_of_load() {
    let c = valid("slider_crank.mec");
    let d = c.dynamics.as_ref().expect("dynamics");
    assert_eq!(
        d.bodies,
        [
            Body { element: 0, mass: 0.5, u: 0.05, v: 0.0, inertia: 1e-3 },
            Body { element: 1, mass: 1.2, u: 0.15, v: 0.0, inertia: 9e-3 },
        ]
    );
    assert_eq!(d.point_masses, [PointMass { x: 4, y: 5, mass: 0.8 }]);
    assert_eq!(d.forces, [Force { x: 4, y: 5, f: [-100.0, 0.0] }]);
    assert_eq!(d.gravity, [0.0, -9.81]);
    assert_eq!(
        d.loads,
        [
            Load { form: FormRef::Prescribed(3), kind: LoadKind::Constant(2.0) },
            Load { form: FormRef::Dependent(0), kind: LoadKind::Spring { k: 500.0, e0: 0.3, c: 2.0 } },
            Load { form: FormRef::Prescribed(3), kind: LoadKind::Motor { t0: 10.0, w0: 200.0 } },
        ]
    );
    assert_eq!(
        quantities(&c)[1..8],
        [
            Quantity::Sigma(0),
            Quantity::Sigma(1),
            Quantity::Sigma(2),
            Quantity::Drive(0),
            Quantity::Reaction(0),
            Quantity::Reaction(1),
            Quantity::Ekin,
        ]
    );
    assert_eq!(d.check(&c.mechanism), Ok(()));
}

#[test]
fn load_from_a_file_without_movement() {
    let c = valid("load_function.mec");
    assert!(c.motion.is_none());
    let d = c.dynamics.as_ref().expect("dynamics");
    assert_eq!(d.bodies, [Body { element: 0, mass: 1.5, u: 0.0, v: 0.0, inertia: 0.02 }]);
    assert_eq!(d.inertias, [Inertia { coord: 5, inertia: 0.08 }]);
    let rows = vec![[0.0, 0.0], [0.5, 2.0], [0.5, 4.0], [2.0, 1.5]];
    assert_eq!(d.loads, [Load { form: FormRef::Prescribed(1), kind: LoadKind::Table(rows) }]);
    assert_eq!(quantities(&c), [Quantity::Sigma(0), Quantity::Drive(0), Quantity::Mred(0, 0)]);
}

#[test]
fn pendulum_released_from_rest_in_dyn_sim() {
    let c = valid("pendulum_released.mec");
    assert_eq!(c.mode, Mode::DynSim);
    let d = c.dynamics.as_ref().expect("dynamics");
    assert_eq!(d.point_masses, [PointMass { x: 2, y: 3, mass: 2.0 }]);
    assert_eq!(d.gravity, [0.0, -9.81]);
    assert!(d.bodies.is_empty() && d.loads.is_empty());
    let motion = c.motion.as_ref().expect("motion");
    assert_eq!((motion.steps, motion.dt), (240, 0.01));
    assert_eq!(motion.inputs, [InputMotion::Dynamic { v0: 0.0 }]);
    // Without INTTOL the integrator is as accurate as ACCURACY.
    assert_eq!(c.params.tol, 1e-10);
    assert_eq!(c.integration, Integration::new(1e-10, 1e-10));
    assert_eq!(quantities(&c)[5..], [Quantity::Sigma(0), Quantity::Ekin, Quantity::Epot]);
}

#[test]
fn crank_and_pendulum_one_dof_driven_one_free() {
    let c = valid("crank_and_pendulum.mec");
    assert_eq!((c.mode, c.mechanism.n_dof()), (Mode::DynSim, 2));
    let motion = c.motion.as_ref().expect("motion");
    assert_eq!(
        motion.inputs,
        [InputMotion::Relative { delta: 4.0 * std::f64::consts::PI }, InputMotion::Dynamic { v0: 0.5 }]
    );
    assert_eq!(c.integration, Integration::from_accuracy(mechfem_core::Params::default().tol));
    assert_eq!(quantities(&c)[3], Quantity::Drive(0));
}

#[test]
fn motor_run_up_with_its_own_integrator_tolerances() {
    let c = valid("motor_run_up.mec");
    assert_eq!(c.mode, Mode::DynSim);
    assert_eq!(c.motion.as_ref().expect("motion").inputs, [InputMotion::Dynamic { v0: 0.0 }]);
    assert_eq!(c.params.tol, 1e-11);
    assert_eq!(c.integration, Integration::new(1e-9, 1e-12));
    let d = c.dynamics.as_ref().expect("dynamics");
    assert_eq!(d.loads[1], Load { form: FormRef::Prescribed(3), kind: LoadKind::Motor { t0: 20.0, w0: 200.0 } });
    assert_eq!(d.check(&c.mechanism), Ok(()));
}
