//! Which run a compiled deck makes (mode, transfer functions, motion of
//! position 1 alone), the changes of its numbers a kept model is run with
//! (given in the deck's UNITS), and the design setup of an optimiser: what
//! every front end asks of the deck crate instead of deciding itself.

use std::f64::consts::PI;
use std::path::Path;

use mechfem_core::run::{Extent, RunMode};
use mechfem_core::{DesignVar, InputMotion, TransferOrder};
use mechfem_deck::{Change, ChangeKindError, Compiled, DesignSetupError};

fn valid(name: &str) -> Compiled {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/decks/valid").join(name);
    let deck = mechfem_deck::parse_file(&path).unwrap_or_else(|e| panic!("{e}"));
    mechfem_deck::compile(&deck, path.parent().unwrap()).unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn each_mode_runs_as_its_deck_says() {
    assert!(matches!(valid("free_motion.mec").run_mode(), RunMode::Kinematic));
    assert!(matches!(valid("fourbar_optimise.mec").run_mode(), RunMode::Kinematic));
    let ana = valid("slider_crank.mec");
    assert!(matches!(ana.run_mode(), RunMode::Inverse { .. }), "{:?}", ana.mode);
    assert!(matches!(valid("pendulum_released.mec").run_mode(), RunMode::Simulated { .. }));
    assert!(valid("free_motion.mec").run_mode().dynamics().is_none());
    assert!(ana.run_mode().dynamics().is_some());
}

#[test]
fn the_transfer_order_is_the_asked_one_or_what_the_buffers_need_and_the_second_with_dynamics() {
    let kin = valid("names_units.mec");
    // BUFKE1 needs the first order.
    assert_eq!(kin.transfer_order(None), Ok(TransferOrder::First));
    assert_eq!(kin.transfer_order(Some(1)), Ok(TransferOrder::First));
    assert_eq!(kin.transfer_order(Some(2)), Ok(TransferOrder::Second));
    let e = kin.transfer_order(Some(3)).unwrap_err();
    assert_eq!(e.to_string(), "order must be 1, 2 or None, not 3");
    let dynamic = valid("slider_crank.mec");
    for degree in [None, Some(1), Some(2)] {
        assert_eq!(dynamic.transfer_order(degree), Ok(TransferOrder::Second));
    }
    assert!(dynamic.transfer_order(Some(0)).is_err());
}

#[test]
fn position_one_alone_runs_no_motion_but_a_free_one_of_no_steps() {
    let free = valid("free_motion.mec");
    let mut state = free.state.clone();
    let whole = free.motion_for(&mut state, Extent::Motion).expect("the deck's motion");
    assert_eq!(whole.steps, free.motion.as_ref().unwrap().steps);
    let one = free.motion_for(&mut state, Extent::PositionOne).expect("a free motion of no steps");
    assert_eq!(one.steps, 0);
    assert!(matches!(one.inputs[0], InputMotion::Free { .. }));

    let relative = valid("names_units.mec");
    let mut state = relative.state.clone();
    assert!(relative.motion_for(&mut state, Extent::PositionOne).is_none());
    assert!(valid("no_movement.mec").motion_for(&mut state, Extent::Motion).is_none());
}

#[test]
fn a_change_is_given_in_the_decks_units_and_names_what_the_deck_lacks() {
    let c = valid("names_units.mec");
    // Co-ordinate 5 is in mm, prescribed row 1 (LENL) in mm, row 4 (the crank's ANGB) in degrees.
    let n = c.numbers(&[Change::Coord(5, 900.0), Change::Row(1, 1100.0), Change::Row(4, 90.0)]).unwrap();
    assert!((n.state.x[4] - 0.9).abs() < 1e-15, "{}", n.state.x[4]);
    assert!((n.para[0].unwrap() - 1.1).abs() < 1e-15);
    assert!((n.state.target[3] - PI / 2.0).abs() < 1e-15);
    assert_eq!(c.in_core_units(Change::Row(4, 180.0)), Change::Row(4, PI));
    // The deck's own numbers when nothing changes.
    let same = c.numbers(&[]).unwrap();
    assert_eq!(same.state.x, c.state.x);
    let e = c.numbers(&[Change::Row(99, 1.0)]).unwrap_err();
    assert_eq!(e.to_string(), "the deck has no prescribed row 99");
    let e = c.numbers(&[Change::Coord(0, 1.0)]).unwrap_err();
    assert_eq!(e.to_string(), "the deck has no co-ordinate 0");
    assert_eq!(Change::of_kind(1, 4, 2.0), Ok(Change::Row(4, 2.0)));
    assert_eq!(Change::of_kind(7, 4, 2.0), Err(ChangeKindError(7)));
    assert_eq!(ChangeKindError(7).to_string(), "a change is of kind 0 (co-ordinate) or 1 (row), not 7");
}

#[test]
fn a_design_setup_names_what_does_not_fit_the_deck() {
    let c = valid("fourbar_optimise.mec");
    let setup = c.design_setup(&[(0, 3), (1, 1)], &[10, 11], &[(11, 10)]).unwrap();
    assert_eq!(setup.vars, vec![DesignVar::Fixed(2), DesignVar::Row(0)]);
    assert_eq!((setup.quantities.len(), setup.extrema.len()), (2, 1));
    let err = |variables: &[(u8, usize)], buffers: &[u32], extrema: &[(u32, u32)]| {
        c.design_setup(variables, buffers, extrema).unwrap_err()
    };
    assert_eq!(err(&[(0, 0)], &[], &[]), DesignSetupError::NumberZero);
    assert_eq!(err(&[(2, 1)], &[], &[]), DesignSetupError::VariableKind(2));
    assert_eq!(err(&[], &[99], &[]), DesignSetupError::NoBuffer(99));
    // Buffer 12 (a first-order transfer function) has no extrema to locate.
    let e = err(&[], &[], &[(11, 12)]);
    assert_eq!(e, DesignSetupError::NoReference(12));
    assert!(e.to_string().starts_with("buffer 12 cannot locate extrema"), "{e}");
    assert!(matches!(err(&[(0, 5)], &[], &[]), DesignSetupError::Variables(_)));
    let no_motion = valid("no_movement.mec").design_setup(&[], &[], &[]).unwrap_err();
    assert_eq!(no_motion.to_string(), "an optimisation needs a motion: its positions are where it looks");
    assert_eq!(setup.check(&[1.0]).unwrap_err().to_string(), "1 values for 2 design variables");
    assert_eq!(setup.check(&[1.0, f64::NAN]).unwrap_err().to_string(), "design value 1 is NaN");
    assert!(setup.check(&[1.0, 2.0]).is_ok());
}
