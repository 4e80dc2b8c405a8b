//! A design evaluated for an optimiser: the extrema of the supply
//! mechanism's output (its dead positions) located to full precision, and
//! the sensitivities of what is taken there against central differences.

use mechfem_core::design::{evaluate, ExtremumSpec};
use mechfem_core::{DesignVar, FormRef, Params, Quantity, State};

fn supply() -> mechfem_deck::Compiled {
    mechfem_deck::load(format!("{}/../../examples/supply/supply.mec", env!("CARGO_MANIFEST_DIR"))).unwrap()
}

const OUT: FormRef = FormRef::Dependent(0);

fn at(c: &mechfem_deck::Compiled, vars: &[DesignVar], values: &[f64]) -> mechfem_core::design::DesignRun {
    let mut state: State = c.state.clone();
    for (v, x) in vars.iter().zip(values) {
        match *v {
            DesignVar::Row(r) => state.target[r] = *x,
            DesignVar::Fixed(i) => state.x[i] = *x,
        }
    }
    let spec = [
        ExtremumSpec { quantity: Quantity::Ke2(OUT, 0, 0), reference: Quantity::E0(OUT) },
        ExtremumSpec { quantity: Quantity::E0(OUT), reference: Quantity::E0(OUT) },
    ];
    let params = Params { tol: 1e-13, ..Params::default() };
    let q = [Quantity::Ke2(OUT, 0, 0), Quantity::E0(OUT)];
    evaluate(&c.mechanism, &mut state, c.motion.as_ref().unwrap(), &params, vars, &q, &spec).unwrap()
}

#[test]
fn dead_positions_of_the_supply_mechanism() {
    let c = supply();
    let kappa = DesignVar::Row(4);
    let r = at(&c, &[kappa], &[-5.17514]);
    // Two dead positions per turn, each found once for each spec.
    assert_eq!(r.extrema.len(), 4, "{:?}", r.extrema);
    let max_tf2 = (0..r.positions).map(|p| r.values[p * 2].abs()).fold(0.0, f64::max);
    for e in r.extrema.iter().filter(|e| e.spec == 0) {
        // The printed design has almost no acceleration at its dead positions.
        assert!(e.value.abs() < 0.02 * max_tf2, "{e:?} against a largest {max_tf2}");
    }
    // The extremum's value is the largest or smallest of the output anywhere.
    let outs: Vec<f64> = (0..r.positions).map(|p| r.values[p * 2 + 1]).collect();
    let (lo, hi) = outs.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| (a.min(x), b.max(x)));
    for e in r.extrema.iter().filter(|e| e.spec == 1) {
        assert!(e.value >= hi - 1e-12 || e.value <= lo + 1e-12, "{e:?} not beyond [{lo}, {hi}]");
    }
}

#[test]
fn extremum_sensitivities_against_central_differences() {
    let c = supply();
    // kappa, a coupler length, a frame pivot's x and the input's start.
    let vars = [DesignVar::Row(4), DesignVar::Row(6), DesignVar::Fixed(4), DesignVar::Row(11)];
    let x0: Vec<f64> = vec![-5.25, 0.71771, 1.04091, 0.0];
    let base = at(&c, &vars, &x0);
    for (v, _) in vars.iter().enumerate() {
        let h = 1e-5 * x0[v].abs().max(1.0);
        let mut plus = x0.clone();
        plus[v] += h;
        let mut minus = x0.clone();
        minus[v] -= h;
        let (p, m) = (at(&c, &vars, &plus), at(&c, &vars, &minus));
        assert_eq!(p.extrema.len(), base.extrema.len());
        for (k, e) in base.extrema.iter().enumerate() {
            let fd = (p.extrema[k].value - m.extrema[k].value) / (2.0 * h);
            let size = 1.0 + e.value.abs() + e.gradient[v].abs();
            assert!(
                (fd - e.gradient[v]).abs() < 1e-6 * size,
                "{:?} at extremum {k}: finite difference {fd}, sensitivity {}",
                vars[v],
                e.gradient[v]
            );
        }
        // And at every position.
        for q in 0..base.values.len() {
            let fd = (p.values[q] - m.values[q]) / (2.0 * h);
            let g = base.gradient[q * vars.len() + v];
            assert!((fd - g).abs() < 1e-6 * (1.0 + g.abs() + base.values[q].abs()), "{:?}: {fd} vs {g}", vars[v]);
        }
    }
}

#[test]
fn an_angle_row_a_full_turn_from_its_value_needs_no_turn() {
    use mechfem_core::{adjust, Kinematics};
    // The supply mechanism with a short crank, started from its exact position 1: there the plate angle
    // beta2 - beta4 (row 5) reads 1.108 by principal values, a full turn from the prescribed -5.17514.
    let c = supply();
    let mech = &c.mechanism;
    let mut state = c.state.clone();
    state.target[0] = 0.1;
    let mut kin = Kinematics::new(mech);
    adjust(mech, &mut state, &mut kin, &c.params).unwrap();
    let exact = state.x.clone();
    let mut again = c.state.clone();
    again.target[0] = 0.1;
    again.x.clone_from(&exact);
    // As a deck with those co-ordinates compiles: angles by their principal values.
    again.branch.fill(f64::NAN);
    let principal = again.clone().prescribed_value(mech, 4).unwrap();
    assert!((principal - again.target[4] - std::f64::consts::TAU).abs() < 1e-9, "{principal}");
    let info = adjust(mech, &mut again, &mut kin, &c.params).unwrap();
    assert_eq!((info.iterations, info.stages), (0, 1));
    assert!(exact.iter().zip(&again.x).all(|(a, b)| (a - b).abs() < 1e-12));
    assert!((again.clone().prescribed_value(mech, 4).unwrap() - again.target[4]).abs() < 1e-12);
}

/// A crank-rocker four-bar turned once in 36 steps, B.y recorded; co-ordinates 1-2 A0, 3-4 B0, 5-6 A, 7-8 B.
const FOURBAR: &str = "KIN ANA
TOPOLOGY
ELEM 1 BIN 1 2 5 6
     2 BIN 5 6 7 8
     3 BIN 3 4 7 8
FORM 1 LENL 1 1
     2 LENL 2 2
     3 LENL 3 3
     4 ANGB 1 4
NRDOF 1
GEOMETRY
XFIX 1 0.0
     2 0.0
     3 3.2
     4 0.0
XMOV 5 1.0
     6 0.0
     7 3.0
     8 2.4
PARA 1 1.0
     2 3.0
     3 2.5
     4 0.0
MOVEMENT
TSTEPE 36
MOV_RELE 1 6.283185307179586
END
";

fn fourbar() -> mechfem_deck::Compiled {
    let path = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("design_branch_fourbar.mec");
    std::fs::write(&path, FOURBAR).unwrap();
    mechfem_deck::load(&path).unwrap()
}

/// The sign of the triangle A, B, B0 at position 1 of a run: which of the dyad's two assemblies it is.
fn dyad_sign(run: &mechfem_core::design::DesignRun) -> f64 {
    let x = &run.coords;
    ((x[6] - x[4]) * (x[3] - x[5]) - (x[7] - x[5]) * (x[2] - x[4])).signum()
}

#[test]
fn every_design_is_evaluated_on_the_start_designs_branch_in_any_order() {
    use mechfem_core::design::{Design, DesignFailure};
    let c = fourbar();
    // B0 and the rocker length.
    let vars = [DesignVar::Fixed(2), DesignVar::Fixed(3), DesignVar::Row(2)];
    let quantities = [Quantity::X0(7)];
    let design = Design {
        mech: &c.mechanism,
        base: &c.state,
        motion: c.motion.as_ref().unwrap(),
        params: &c.params,
        vars: &vars,
        quantities: &quantities,
        extrema: &[],
    };
    let start = [3.2, 0.0, 2.5];
    let (first, anchor) = design.start(&start).unwrap();
    // From the start design's position 1, Newton alone assembles this one with B mirrored about A-B0.
    let mirroring = [1.5, 2.0, 3.5];
    let designs = [mirroring, [2.5, -2.0, 3.5], [3.5, 3.0, 3.0], start, [1.7, -1.0, 2.0], [4.0, 1.0, 3.5]];
    let forward: Vec<_> = designs.iter().map(|x| design.evaluate(&anchor, x)).collect();
    for (k, x) in designs.iter().enumerate().rev() {
        let again = design.evaluate(&anchor, x);
        match (&forward[k], &again) {
            (Ok(a), Ok(b)) => {
                assert_eq!((&a.values, &a.gradient, &a.coords), (&b.values, &b.gradient, &b.coords), "{x:?}");
                assert_eq!(dyad_sign(a), dyad_sign(&first), "{x:?} is on another branch");
            }
            (a, b) => assert_eq!(a.as_ref().err(), b.as_ref().err(), "{x:?}"),
        }
    }
    assert!(forward.iter().filter(|r| r.is_ok()).count() >= 4);
    // The start design evaluated again is the start design's run, bit for bit.
    let again = forward[3].as_ref().unwrap();
    assert_eq!((&again.values, &again.coords), (&first.values, &first.coords));
    // A crank that cannot turn fully: 36 steps jump over its limit position onto the other branch, unless the
    // stepper stops at the limit position itself.
    let jumping = [1.7343402713614078, 3.7876737360951287, 2.1636385787969443];
    match design.evaluate(&anchor, &jumping) {
        Err(DesignFailure::LeftBranch(change)) => assert_eq!((change.after, change.coords), (24, vec![6, 7])),
        Ok(run) => assert!(run.report.stop.is_some(), "the motion passed its limit position"),
        other => panic!("{other:?}"),
    }
}
