//! A deck with UNITS is compiled into the core's units (SI): its numbers
//! agree with those of the same deck written in SI, and every label and
//! unit of its buffers comes from its NAMES and UNITS.

use std::f64::consts::PI;
use std::path::Path;

use mechfem_core::{InputMotion, Quantity};
use mechfem_deck::{parse_str, Compiled, DiagnosticKind};

fn compile(text: &str) -> Compiled {
    let deck = parse_str(text, "units.mec").unwrap_or_else(|e| panic!("{e}"));
    mechfem_deck::compile(&deck, Path::new(".")).unwrap_or_else(|e| panic!("{e}"))
}

/// A slider-crank with a point mass, in `length` units of the SI metre.
fn slider_crank(units: &str, l: f64, angle: f64, time: f64) -> String {
    format!(
        "DYN ANA\n{units}\nTOPOLOGY\nELEM 1 BIN 1 2 3 4\n 2 BIN 3 4 5 6\nFORM 1 LENL 1 1\n 2 LENL 2 2\n 3 ANGB 1 3\n\
         4 ANGB 2 -1\nNRDOF 1\nGEOMETRY\nXFIX 1 0\n 2 0\n 6 0\nXMOV 3 {a}\n 4 {b}\n 5 {c}\nPARA 1 {r}\n 2 {k}\n 3 {phi}\n\
         DYNAMICS\nMASS 1 2 {u} 0 {j}\nPMASS 5 6 0.5\nGRAVITY 0 {g}\nLOAD 3 {torque}\nSPRING -1 {kt} {e0} {damper}\n\
         MOVEMENT\nTSTEPE 10 {dt}\nMOV_RELE 1 {delta}\nSTORAGE\nBUFX0 5 1\nBUFKX1 5 1 2\nBUFDRV 1 3\nBUFMRED 1 1 4\n",
        a = 0.1 * l,
        b = 0.05 * l,
        c = 0.4 * l,
        r = 0.1 * l,
        k = 0.3 * l,
        phi = 0.5 * angle,
        u = 0.05 * l,
        j = 0.01 * l * l,
        g = -9.81 * l / (time * time),
        torque = 2.0 * l,
        kt = 3.0 * l / angle,
        e0 = 0.25 * angle,
        damper = 0.5 * l / angle * time,
        dt = 0.01 * time,
        delta = 1.0 * angle,
    )
}

#[test]
fn numbers_in_mm_degrees_and_ms_are_read_as_the_same_deck_in_si() {
    let si = compile(&slider_crank("", 1.0, 1.0, 1.0));
    let deg = 180.0 / PI;
    let mm = compile(&slider_crank("UNITS LENGTH mm ANGLE deg TIME ms MASS kg FORCE N", 1000.0, deg, 1000.0));
    let near = |a: f64, b: f64| (a - b).abs() <= 1e-12 * b.abs().max(1.0);
    for (a, b) in mm.state.x.iter().zip(&si.state.x) {
        assert!(near(*a, *b), "{a} {b}");
    }
    for (a, b) in mm.state.target.iter().zip(&si.state.target) {
        assert!(near(*a, *b), "{a} {b}");
    }
    let (m1, m2) = (mm.motion.as_ref().unwrap(), si.motion.as_ref().unwrap());
    assert!(near(m1.dt, m2.dt));
    let (InputMotion::Relative { delta: d1 }, InputMotion::Relative { delta: d2 }) = (&m1.inputs[0], &m2.inputs[0])
    else {
        panic!("relative motions")
    };
    assert!(near(*d1, *d2));
    let (y1, y2) = (mm.dynamics.as_ref().unwrap(), si.dynamics.as_ref().unwrap());
    assert!(near(y1.gravity[1], y2.gravity[1]));
    assert!(near(y1.bodies[0].inertia, y2.bodies[0].inertia) && near(y1.bodies[0].u, y2.bodies[0].u));
    assert_eq!(format!("{:?}", y1.loads.len()), format!("{:?}", y2.loads.len()));
    for (a, b) in y1.loads.iter().zip(&y2.loads) {
        let (a, b) = (format!("{:?}", a.kind), format!("{:?}", b.kind));
        let nums = |s: &str| -> Vec<f64> {
            s.split(|c: char| !(c.is_ascii_digit() || c == '.' || c == '-' || c == 'e'))
                .filter_map(|w| w.parse().ok())
                .collect()
        };
        for (x, y) in nums(&a).iter().zip(nums(&b)) {
            assert!(near(*x, y), "{a} / {b}");
        }
    }
    // The echo keeps the numbers as written.
    assert_eq!(mm.rows_as_written()[0][0].para, Some(100.0));
    assert!((mm.prescribed[0].para.unwrap() - 0.1).abs() < 1e-15);
    let unit = |c: &Compiled, k: usize| c.unit(&c.buffers[k]);
    assert_eq!([unit(&mm, 0), unit(&mm, 1), unit(&mm, 2), unit(&mm, 3)], ["mm", "mm/deg", "N·mm", "kg·mm²"]);
    assert_eq!(unit(&si, 0), "");
    assert!((mm.out_scale(Quantity::X0(4)) - 1000.0).abs() < 1e-9);
}

#[test]
fn a_deck_without_units_is_compiled_bit_for_bit_as_before() {
    let plain = compile(&slider_crank("", 1.0, 1.0, 1.0));
    let si = compile(&slider_crank("UNITS LENGTH m ANGLE rad TIME s", 1.0, 1.0, 1.0));
    assert_eq!(plain.state.x, si.state.x);
    assert_eq!(plain.state.target, si.state.target);
    assert!(plain.warnings.is_empty());
    assert!(!plain.units.declared && si.units.declared && si.units.is_identity());
}

#[test]
fn an_angle_in_degrees_where_radians_are_meant_is_warned_about() {
    let text = slider_crank("", 1.0, 1.0, 1.0).replace("MOV_RELE 1 1", "MOV_RELE 1 720");
    let c = compile(&text);
    assert_eq!(c.warnings.len(), 1);
    let w = &c.warnings[0];
    assert_eq!(w.kind, DiagnosticKind::SuspiciousUnit);
    assert!(w.message.contains("720") && w.message.contains("radians"), "{}", w.message);
    assert!(w.hint.as_deref().unwrap_or("").contains("UNITS ANGLE deg"));
    let degrees =
        slider_crank("UNITS ANGLE deg", 1.0, 180.0 / PI, 1.0).replace("MOV_RELE 1 57.29", "MOV_RELE 1 6.2832 ;");
    let c = compile(&degrees);
    assert_eq!(c.warnings.len(), 1, "{:?}", c.warnings);
    assert!(c.warnings[0].message.contains("looks like radians"));
}

#[test]
fn a_final_design_is_written_in_the_decks_units() {
    let text =
        "KIN OPT\nUNITS LENGTH mm ANGLE deg\nTOPOLOGY\nELEM 1 BIN 1 2 3 4\nFORM 1 LENL 1 1\n 2 ANGB 1 2\nNRDOF 1\n\
                GEOMETRY\nXFIX 1 0\n 2 0\nXMOV 3 1000\n 4 500\nPARA 1 1000\n 2 0\nMOVEMENT\nTSTEPE 4\n\
                MOV_RELE 1 90\nOPTIMISE\nVARY 1 500 2000\nBUFX0 4 1\nTARGETAT 1 5 500\nNAMES\nBUF 1 tip height\n";
    // The core's numbers: a crank of 0.75 m whose tip starts at (0.7 m, 0).
    let out = mechfem_deck::rewrite::design_deck(text, "design.mec", &[(1, 0.75)], &[(3, 0.7)], None).unwrap();
    assert!(out.contains("PARA 1 750\n"), "{out}");
    assert!(out.contains("XMOV 3 700\n"), "{out}");
    assert!(out.contains("UNITS LENGTH mm ANGLE deg\n"));
    // The buffer went with the OPTIMISE block (there is no STORAGE), and so did its label.
    assert!(!out.contains("BUF 1 tip height"), "{out}");
    let c = compile(&out);
    assert!((c.state.target[0] - 0.75).abs() < 1e-15);
    // Its targets are read in millimetres: 500 mm is 0.5 m.
    let c = compile(text);
    let o = c.optimise.unwrap();
    assert_eq!(o.targets[0].kind, mechfem_deck::TargetKind::At { position: 4, value: 0.5 });
    assert!((o.vary[0].lo - 0.5).abs() < 1e-15 && (o.vary[0].hi - 2.0).abs() < 1e-15);
}

#[test]
fn the_numbers_as_written_come_back_in_the_decks_units() {
    let deg = 180.0 / PI;
    let (l, t) = (1000.0, 1000.0);
    let mm = compile(&slider_crank("UNITS LENGTH mm ANGLE deg TIME ms MASS kg FORCE N", l, deg, t));
    let plain = compile(&slider_crank("", l, deg, t));
    let near = |a: f64, b: f64| (a - b).abs() <= 1e-12 * b.abs().max(1.0);
    // The plain deck's compiled numbers are the numbers as written.
    for (a, b) in mm.coords_as_written().iter().zip(&plain.state.x) {
        assert!(near(*a, *b), "{a} {b}");
    }
    let (m, p) = (mm.motion_as_written().unwrap(), plain.motion.clone().unwrap());
    assert!(near(m.dt, p.dt));
    assert_eq!(format!("{:.9?}", m.inputs), format!("{:.9?}", p.inputs));
    let (d, p) = (mm.dynamics_as_written().unwrap(), plain.dynamics.clone().unwrap());
    assert_eq!(format!("{:.6?}", d), format!("{:.6?}", p));
    let [rows, _] = mm.rows_as_written();
    for (a, b) in rows.iter().zip(&plain.prescribed) {
        assert!(near(a.para.unwrap(), b.para.unwrap()));
    }
    // Without UNITS they are the compiled numbers, bit for bit.
    assert_eq!(plain.coords_as_written(), plain.state.x);
}
