//! Design sensitivities against central differences of whole runs: for
//! every prescribed value (lengths, u and v, fixed angles, gear ratios, an
//! input's start value) and every fixed co-ordinate (frame pivots) of a
//! four-bar, the supply mechanism and geared mechanisms, at every position,
//! of every co-ordinate and dependent form parameter and their first- and
//! second-order transfer functions.

use mechfem_core::{
    run, DesignVar, InputMotion, Kinematics, Mechanism, Observer, Params, PositionView, Sensitivity, State,
    TransferOrder,
};

/// Everything at one position: x, x'_0, x''_00 of every co-ordinate, then
/// eps, eps'_0, eps''_00 of every dependent form parameter.
fn values(mech: &Mechanism, kin: &Kinematics, state: &State) -> Vec<f64> {
    let mut out = Vec::new();
    for i in 0..mech.n_coords() {
        out.extend([state.x[i], kin.dx(mech, i, 0), kin.d2x(mech, i, 0, 0)]);
    }
    for d in 0..mech.n_dependent() {
        out.extend([kin.dep(d), kin.dep1(d, 0), kin.dep2(d, 0, 0)]);
    }
    out
}

struct Values(Vec<Vec<f64>>);

impl Observer for Values {
    fn position(&mut self, v: &PositionView<'_>) {
        self.0.push(values(v.mech, v.kin, v.state));
    }
}

/// The sensitivities of the same values for every variable, per position.
struct Sensitivities {
    sens: Sensitivity,
    motion: mechfem_core::Motion,
    rows: Vec<Vec<Vec<f64>>>,
}

impl Observer for Sensitivities {
    fn position(&mut self, v: &PositionView<'_>) {
        let (mech, s) = (v.mech, &mut self.sens);
        s.compute(mech, v.kin, v.state, TransferOrder::Second).expect("sensitivities");
        let vars = s.vars().to_vec();
        for (k, var) in vars.iter().enumerate() {
            if *var == DesignVar::Row(mech.input_row(0)) {
                let (factor, rate) = self.motion.start_rates(0, v.index);
                s.scale_input(k, 0, factor, rate);
            }
        }
        let mut per_var = Vec::new();
        for k in 0..vars.len() {
            let mut out = Vec::new();
            for i in 0..mech.n_coords() {
                out.extend([s.dx(i, k), s.dx1(i, 0, k), s.dx2(i, 0, 0, k)]);
            }
            for d in 0..mech.n_dependent() {
                out.extend([s.dep(d, k), s.dep1(d, 0, k), s.dep2(d, 0, 0, k)]);
            }
            per_var.push(out);
        }
        self.rows.push(per_var);
    }
}

fn tight() -> Params {
    Params { tol: 1e-13, ..Params::default() }
}

fn run_values(mech: &Mechanism, state: &State, motion: &mechfem_core::Motion) -> Vec<Vec<f64>> {
    let mut state = state.clone();
    let mut obs = Values(Vec::new());
    let report = run(mech, &mut state, Some(motion), &tight(), &mut obs).expect("run");
    assert!(report.stop.is_none(), "the run stopped: {:?}", report.stop);
    obs.0
}

fn perturbed(state: &State, var: DesignVar, h: f64) -> State {
    let mut s = state.clone();
    match var {
        DesignVar::Row(r) => s.target[r] += h,
        DesignVar::Fixed(i) => s.x[i] += h,
    }
    s
}

/// Every design variable of a model: every prescribed row and every fixed
/// co-ordinate.
fn all_vars(mech: &Mechanism) -> Vec<DesignVar> {
    let rows = (0..mech.n_prescribed()).map(DesignVar::Row);
    rows.chain((0..mech.n_coords()).filter(|&i| !mech.is_moving(i)).map(DesignVar::Fixed)).collect()
}

/// Checks every sensitivity of `deck` against central differences, at
/// `every`-th position; returns the largest relative error seen.
fn check_deck(deck: &str, every: usize) -> f64 {
    let c = mechfem_deck::load(deck).unwrap_or_else(|d| panic!("{deck}: {d:?}"));
    let (mech, motion) = (&c.mechanism, c.motion.clone().expect("a motion"));
    // The start from a converged position 1, so that the runs at p +- h
    // adjust only by the change.
    let mut state = c.state.clone();
    run(mech, &mut state, None, &tight(), &mut Values(Vec::new())).expect("position 1");
    state.target.clone_from(&c.state.target);
    let vars = all_vars(mech);
    let mut obs = Sensitivities { sens: Sensitivity::new(mech, &vars).unwrap(), motion: motion.clone(), rows: vec![] };
    let mut s = state.clone();
    run(mech, &mut s, Some(&motion), &tight(), &mut obs).expect("run");
    let base = run_values(mech, &state, &motion);
    let mut worst = 0.0f64;
    for (k, &var) in vars.iter().enumerate() {
        let scale = match var {
            DesignVar::Row(r) => state.target[r].abs().max(1.0),
            DesignVar::Fixed(i) => state.x[i].abs().max(1.0),
        };
        let h = 1e-5 * scale;
        let plus = run_values(mech, &perturbed(&state, var, h), &motion);
        let minus = run_values(mech, &perturbed(&state, var, -h), &motion);
        for p in (0..base.len()).step_by(every) {
            for q in 0..base[p].len() {
                let fd = (plus[p][q] - minus[p][q]) / (2.0 * h);
                let exact = obs.rows[p][k][q];
                // The size of what is differentiated: its value's and its
                // sensitivity's magnitude.
                let size = 1.0 + base[p][q].abs() + exact.abs();
                let err = (fd - exact).abs() / size;
                assert!(
                    err < 2e-6,
                    "{deck}: {var:?}, position {}, value {q}: finite difference {fd}, sensitivity {exact}",
                    p + 1
                );
                worst = worst.max(err);
            }
        }
    }
    worst
}

fn example(name: &str) -> String {
    format!("{}/../../examples/{name}", env!("CARGO_MANIFEST_DIR"))
}

#[test]
fn fourbar_every_variable() {
    let worst = check_deck(&example("fourbar/fourbar.mec"), 3);
    eprintln!("four-bar: largest relative difference {worst:.1e}");
}

#[test]
fn supply_every_variable() {
    let worst = check_deck(&example("supply/supply.mec"), 5);
    eprintln!("supply: largest relative difference {worst:.1e}");
}

#[test]
fn geared_slider_crank_every_variable() {
    let worst = check_deck(&example("gears/geared_slider_crank.mec"), 3);
    eprintln!("geared slider-crank: largest relative difference {worst:.1e}");
}

#[test]
fn planetary_gear_every_variable() {
    let worst = check_deck(&example("gears/planetary_gr2.mec"), 3);
    eprintln!("planetary: largest relative difference {worst:.1e}");
}

#[test]
fn input_start_under_an_absolute_motion() {
    let c = mechfem_deck::load(example("fourbar/fourbar.mec")).unwrap();
    let mut motion = c.motion.clone().unwrap();
    let start = c.state.target[c.mechanism.input_row(0)];
    motion.inputs[0] = InputMotion::Absolute { end: start + 2.0 };
    // At position k of n the input is start + k/n (end - start): one unit
    // of the start moves it by 1 - k/n, and its velocity by -1/(n dt).
    let (n, dt) = (motion.steps as f64, motion.dt);
    assert_eq!(motion.start_rates(0, 0), (1.0, -1.0 / (n * dt)));
    let (f, _) = motion.start_rates(0, motion.steps);
    assert!(f.abs() < 1e-15);
}

#[test]
fn a_moving_coordinate_is_not_a_design_variable() {
    let c = mechfem_deck::load(example("fourbar/fourbar.mec")).unwrap();
    let moving = (0..c.mechanism.n_coords()).find(|&i| c.mechanism.is_moving(i)).unwrap();
    let err = Sensitivity::new(&c.mechanism, &[DesignVar::Fixed(moving)]).unwrap_err();
    assert!(err.to_string().contains("moves"), "{err}");
    assert!(Sensitivity::new(&c.mechanism, &[DesignVar::Row(99)]).is_err());
}
