//! Mechanisms with masses and loads for the dynamics tests: a slider-crank
//! with its closed form, and a four-bar that carries every kind of mass and
//! load (on a TR1 crank with a flywheel, a TR2 coupler with a coupler
//! point, a BIN rocker), numbered two ways.

#![allow(dead_code)] // shared by the dynamics and simulation tests, each using a part

use mechfem_core::dynamics::{Body, Dynamics, Force, Inertia, Load, LoadKind, PointMass};
use mechfem_core::run::InverseDynamics;
use mechfem_core::{
    run, ElementType, FormRef, Mechanism, MechanismBuilder, Motion, Observer, Params, PositionView, Quantity, Recorder,
    State, Term,
};

/// A checked inverse-dynamics workspace.
pub fn inverse(mech: &Mechanism, dynamics: Dynamics) -> InverseDynamics {
    dynamics.check(mech).unwrap();
    InverseDynamics::new(mech, dynamics)
}

/// Runs `motion` recording `q` with the dynamics; the run must complete.
pub fn run_dynamics(
    mech: &Mechanism,
    state: &mut State,
    motion: &Motion,
    dynamics: Dynamics,
    q: &[Quantity],
) -> Recorder {
    let mut rec = Recorder::new(q.to_vec(), false).with_dynamics(inverse(mech, dynamics));
    let report = run(mech, state, Some(motion), &Params::default(), &mut rec).unwrap();
    assert!(report.stop.is_none(), "{:?}", report.stop);
    rec
}

/// An offset slider-crank: crank A0 -> A (BIN, length `r`), rod A -> B
/// (BIN, length `l`), slider B on the line y = `e`, held there by a guide
/// bar G -> B of free length whose angle is prescribed 0.
pub struct SliderCrank {
    pub r: f64,
    pub l: f64,
    pub e: f64,
    /// Crank: mass, centre (u, v), inertia.
    pub crank: [f64; 4],
    /// Rod: mass, centre (u, v), inertia.
    pub rod: [f64; 4],
    /// Slider mass.
    pub slider: f64,
    /// Gas force on the slider, along x.
    pub gas: f64,
    /// Co-ordinate indices of the fixed points A0 and G.
    pub x0: usize,
    pub y0: usize,
    pub xg: usize,
    pub yg: usize,
}

impl Default for SliderCrank {
    fn default() -> Self {
        SliderCrank {
            r: 0.1,
            l: 0.35,
            e: 0.02,
            crank: [1.2, 0.04, 0.01, 2e-3],
            rod: [0.9, 0.12, -0.015, 9e-3],
            slider: 0.6,
            gas: -350.0,
            x0: 0,
            y0: 1,
            xg: 2,
            yg: 3,
        }
    }
}

/// The closed form at one crank angle.
pub struct SliderExact {
    pub tau: f64,
    pub normal: f64,
    pub r0: [f64; 2],
    pub tau_scale: f64,
}

const G: f64 = 9.81;

fn rot(angle: f64, u: f64, v: f64) -> [f64; 2] {
    let (s, c) = angle.sin_cos();
    [u * c - v * s, u * s + v * c]
}

fn cross(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[1] - a[1] * b[0]
}

impl SliderCrank {
    /// Geometry by hand: u = e - r sin(theta), q = sqrt(l^2 - u^2), slider
    /// at s = r cos(theta) + q, rod angle phi = atan2(u, q); derivatives
    /// with respect to theta by the chain rule; the crank turns at speed `w`.
    pub fn exact(&self, theta: f64, w: f64) -> SliderExact {
        let (r, l) = (self.r, self.l);
        let (sn, cs) = theta.sin_cos();
        let (u, du, ddu) = (self.e - r * sn, -r * cs, r * sn);
        let q = (l * l - u * u).sqrt();
        let dq = -u * du / q;
        let ddq = (-du * du - u * ddu - dq * dq) / q;
        let (ds, dds) = (-r * sn + dq, -r * cs + ddq);
        let phi = u.atan2(q);
        let dphi = (du * q - u * dq) / (l * l);
        let ddphi = (ddu * q - u * ddq) / (l * l);
        let a = [r * cs, r * sn];
        let (da, dda) = ([-r * sn, r * cs], [-r * cs, -r * sn]);
        let b = [r * cs + q, self.e];
        // Crank body: its frame turns with theta.
        let [m1, u1, v1, j1] = self.crank;
        let w1 = rot(theta, u1, v1);
        let (dc1, ddc1) = ([-w1[1], w1[0]], [-w1[0], -w1[1]]);
        // Rod body on A with its frame at phi.
        let [m2, u2, v2, j2] = self.rod;
        let w2 = rot(phi, u2, v2);
        let wp = [-w2[1], w2[0]];
        let dc2 = [da[0] + dphi * wp[0], da[1] + dphi * wp[1]];
        let ddc2 = [dda[0] + ddphi * wp[0] - dphi * dphi * w2[0], dda[1] + ddphi * wp[1] - dphi * dphi * w2[1]];
        let m3 = self.slider;
        let dot = |x: [f64; 2], y: [f64; 2]| x[0] * y[0] + x[1] * y[1];
        let inertial = m1 * dot(dc1, ddc1) + m2 * dot(dc2, ddc2) + j2 * dphi * ddphi + m3 * ds * dds;
        let g = [0.0, -G];
        let q_gen = m1 * dot(g, dc1) + m2 * dot(g, dc2) + self.gas * ds;
        let tau = w * w * inertial - q_gen;
        let _ = j1;
        // Forces, crank at constant speed: accelerations are w^2 times the
        // second derivatives.
        let w2s = w * w;
        let (acc1, acc2, s_acc) = ([w2s * ddc1[0], w2s * ddc1[1]], [w2s * ddc2[0], w2s * ddc2[1]], w2s * dds);
        let p_bx = m3 * s_acc - self.gas;
        let ab = [a[0] - b[0], a[1] - b[1]];
        let rhs = j2 * w2s * ddphi + cross(w2, [m2 * (acc2[0] - g[0]), m2 * (acc2[1] - g[1])]) + ab[1] * p_bx;
        let p_by = rhs / ab[0];
        let normal = -p_by + m3 * G;
        let total = m1 + m2 + m3;
        let r0 =
            [m1 * acc1[0] + m2 * acc2[0] + m3 * s_acc - self.gas, m1 * acc1[1] + m2 * acc2[1] + total * G - normal];
        let tau_scale = total * (w2s + G) * (r + l) + self.gas.abs();
        SliderExact { tau, normal, r0, tau_scale }
    }
}

/// The slider-crank at crank angle `theta0` with its masses, gravity and gas force.
pub fn slider_crank(sc: &SliderCrank, theta0: f64) -> (Mechanism, State, Dynamics) {
    let mut b = MechanismBuilder::new();
    let (x0, y0) = (b.fixed(0.0), b.fixed(0.0));
    let (xg, yg) = (b.fixed(-1.0), b.fixed(sc.e));
    assert_eq!([x0, y0, xg, yg], [sc.x0, sc.y0, sc.xg, sc.yg]);
    let u = sc.e - sc.r * theta0.sin();
    let s = sc.r * theta0.cos() + (sc.l * sc.l - u * u).sqrt();
    let (xa, ya) = (b.moving(sc.r * theta0.cos()), b.moving(sc.r * theta0.sin()));
    let (xb, yb) = (b.moving(s), b.moving(sc.e));
    let crank = b.element(ElementType::Bin, &[x0, y0, xa, ya]);
    let rod = b.element(ElementType::Bin, &[xa, ya, xb, yb]);
    let guide = b.element(ElementType::Bin, &[xg, yg, xb, yb]);
    b.prescribe(&[Term::new(crank, 0)]);
    b.prescribe(&[Term::new(rod, 0)]);
    b.prescribe(&[Term::new(guide, 1)]);
    b.input(&[Term::new(crank, 1)]);
    let (mech, state) = b.build().unwrap();
    let body = |element, [mass, u, v, inertia]: [f64; 4]| Body { element, mass, u, v, inertia };
    let dynamics = Dynamics {
        bodies: vec![body(crank, sc.crank), body(rod, sc.rod)],
        point_masses: vec![PointMass { x: xb, y: yb, mass: sc.slider }],
        gravity: [0.0, -G],
        forces: vec![Force { x: xb, y: yb, f: [sc.gas, 0.0] }],
        ..Dynamics::default()
    };
    (mech, state, dynamics)
}

/// A crank-rocker four-bar: crank A0 -> A a TR1 (angle co-ordinate beta,
/// A its point R at (r1, 0)) carrying a flywheel, coupler A -> B a TR2 with
/// coupler point C, rocker B0 -> B a BIN.
#[derive(Clone, Default)]
pub struct Fourbar {
    /// Number the co-ordinates, elements and rows in another order.
    pub permuted: bool,
}

/// A built four-bar and where its parts went.
pub struct FourbarModel {
    pub mech: Mechanism,
    pub state: State,
    pub dynamics: Dynamics,
    /// Co-ordinate indices of A0 (x, y) and B0 (x, y).
    pub fixed: [usize; 4],
    /// Prescribed row index of: crank LENU, crank LENV, coupler LENL,
    /// coupler LENU, coupler LENV, rocker LENL, crank ANGV (the input).
    pub rows: [usize; 7],
}

const R1: f64 = 1.5;
const R2: f64 = 4.5;
const R3: f64 = 3.0;
const D: f64 = 4.0;
const CU: f64 = 2.0;
const CV: f64 = 1.5;

pub fn fourbar(fb: &Fourbar) -> FourbarModel {
    let th = 0.3f64;
    let a = [R1 * th.cos(), R1 * th.sin()];
    // B on both circles, above the line A B0.
    let (dx, dy) = (D - a[0], -a[1]);
    let d2 = dx * dx + dy * dy;
    let along = (R2 * R2 - R3 * R3 + d2) / (2.0 * d2);
    let h = (R2 * R2 / d2 - along * along).sqrt();
    let bpt = [a[0] + along * dx + h * dy, a[1] + along * dy - h * dx];
    let phi = (bpt[1] - a[1]).atan2(bpt[0] - a[0]);
    let c = [a[0] + CU * phi.cos() - CV * phi.sin(), a[1] + CU * phi.sin() + CV * phi.cos()];
    // Co-ordinates: (name, value, moving); the permuted model adds them in reverse.
    let coords = [
        (0.0, false),
        (0.0, false),
        (D, false),
        (0.0, false),
        (th, true),
        (a[0], true),
        (a[1], true),
        (bpt[0], true),
        (bpt[1], true),
        (c[0], true),
        (c[1], true),
    ];
    let mut b = MechanismBuilder::new();
    let mut idx = [0usize; 11];
    let order: Vec<usize> = if fb.permuted { (0..11).rev().collect() } else { (0..11).collect() };
    for &k in &order {
        idx[k] = b.coord(coords[k].0, coords[k].1);
    }
    let [x0, y0, xb0, yb0, beta, xa, ya, xb, yb, xc, yc] = idx;
    let add = |b: &mut MechanismBuilder, which: usize| match which {
        0 => b.element(ElementType::Tr1, &[x0, y0, beta, xa, ya]),
        1 => b.element(ElementType::Tr2, &[xa, ya, xb, yb, xc, yc]),
        _ => b.element(ElementType::Bin, &[xb0, yb0, xb, yb]),
    };
    let mut el = [0usize; 3];
    for which in if fb.permuted { [2, 0, 1] } else { [0, 1, 2] } {
        el[which] = add(&mut b, which);
    }
    let [crank, coupler, rocker] = el;
    // Constant rows in logical order, or reversed.
    let constant = [(crank, 1), (crank, 2), (coupler, 0), (coupler, 2), (coupler, 3), (rocker, 0)];
    let mut rows = [0usize; 7];
    let seq: Vec<usize> = if fb.permuted { (0..6).rev().collect() } else { (0..6).collect() };
    for &k in &seq {
        rows[k] = b.prescribe(&[Term::new(constant[k].0, constant[k].1)]);
    }
    rows[6] = 6;
    b.input(&[Term::new(crank, 0)]);
    let rocker_angle = b.dependent(&[Term::new(rocker, 1)]);
    let coupler_angle = b.dependent(&[Term::new(coupler, 1)]);
    let (mech, state) = b.build().unwrap();
    let dynamics = Dynamics {
        bodies: vec![
            Body { element: crank, mass: 2.0, u: 0.6, v: 0.1, inertia: 0.3 },
            Body { element: coupler, mass: 3.0, u: 2.0, v: 0.7, inertia: 4.0 },
            Body { element: rocker, mass: 1.5, u: 1.4, v: -0.2, inertia: 1.1 },
        ],
        point_masses: vec![PointMass { x: xc, y: yc, mass: 0.8 }],
        inertias: vec![Inertia { coord: beta, inertia: 0.5 }],
        gravity: [0.4, -9.81],
        forces: vec![Force { x: xc, y: yc, f: [3.0, -7.0] }],
        loads: vec![
            Load { form: FormRef::Dependent(rocker_angle), kind: LoadKind::Spring { k: 40.0, e0: 1.2, c: 0.7 } },
            Load { form: FormRef::Prescribed(6), kind: LoadKind::Motor { t0: 20.0, w0: 15.0 } },
            Load { form: FormRef::Dependent(coupler_angle), kind: LoadKind::Constant(-4.0) },
            Load {
                form: FormRef::Dependent(rocker_angle),
                kind: LoadKind::Table(vec![[0.0, 1.0], [0.7, -5.0], [1.5, 2.0], [3.0, 2.0]]),
            },
            Load { form: FormRef::Prescribed(rows[2]), kind: LoadKind::Spring { k: 100.0, e0: R2, c: 0.0 } },
        ],
    };
    FourbarModel { mech, state, dynamics, fixed: [x0, y0, xb0, yb0], rows }
}

/// The loads' conservative part: springs without their dampers.
pub fn conservative(loads: &[Load]) -> Vec<Load> {
    loads
        .iter()
        .filter_map(|l| match l.kind {
            LoadKind::Spring { k, e0, .. } => Some(Load { form: l.form, kind: LoadKind::Spring { k, e0, c: 0.0 } }),
            _ => None,
        })
        .collect()
}

/// Keeps the power of the non-conservative loads at every position.
struct LoadPower(InverseDynamics, Vec<f64>);

impl Observer for LoadPower {
    fn position(&mut self, view: &PositionView<'_>) {
        self.0.evaluate(view);
        self.1.push(self.0.load_power());
    }
}

/// The power of the non-conservative loads at every position of `motion`.
pub fn load_power(model: &FourbarModel, motion: &Motion) -> Vec<f64> {
    let mut state = model.state.clone();
    let mut obs = LoadPower(inverse(&model.mech, model.dynamics.clone()), Vec::new());
    run(&model.mech, &mut state, Some(motion), &Params::default(), &mut obs).unwrap();
    obs.1
}

/// A pendulum P -> Q (length `l`, P fixed at the origin, co-ordinates xP yP
/// xQ yQ = 0..4, the bar element 0) at angle `theta0`, its length row 0
/// and its angle the input, with a point mass `m` at Q and gravity.
pub fn pendulum(l: f64, theta0: f64, m: f64) -> (Mechanism, State, Dynamics) {
    let mut b = MechanismBuilder::new();
    let (xp, yp) = (b.fixed(0.0), b.fixed(0.0));
    let (xq, yq) = (b.moving(l * theta0.cos()), b.moving(l * theta0.sin()));
    let bar = b.element(ElementType::Bin, &[xp, yp, xq, yq]);
    b.prescribe(&[Term::new(bar, 0)]);
    b.input(&[Term::new(bar, 1)]);
    let (mech, state) = b.build().unwrap();
    let dynamics =
        Dynamics { point_masses: vec![PointMass { x: xq, y: yq, mass: m }], gravity: [0.0, -G], ..Dynamics::default() };
    (mech, state, dynamics)
}
