//! The builder and the parser make the same compiled model of the same items.

use std::path::Path;

use super::DeckBuilder;
use crate::ast::Mode;
use crate::DiagnosticKind;

/// A pendulum-driven crank with every kind of item the builder takes, as
/// deck text laid out line for line as the builder numbers its items.
const TEXT: &str = "; pendulum
DYN SIM
UNITS LENGTH mm ANGLE deg
TOPOLOGY
ELEM 1 BIN 1 2 3 4 ; crank: A0 A
FORM 1 LENL 1 1 1.0 ; crank.length
FORM 2 ANGB 1 2 1.0 ; crank.angle
NRDOF 1
GEOMETRY
XFIX 1 0.0 ; A0.x
XFIX 2 0.0 ; A0.y
XMOV 3 1.0 ; A.x
XMOV 4 0.5 ; A.y
PARA 1 1.118033988749895 ; crank.length
NAMES
POINT 3 4 A
COORD 1 a0x
ELEM 1 crank
ROW 2 phi
BUF 1 the x of A
DYNAMICS
MASS 1 2.0 0.5 0.0 0.1
PMASS 3 4 0.25
GRAVITY 0.0 -9.81
FORCE 3 4 1.0 0.0
SPRING 2 3.0 0.2 0.05
MOTOR 2 1.5 10.0
MOVEMENT
TSTEPE 20 0.01
MOV_DYN 1 0.5
ACCURACY 1e-10
MAXITER 30
INTTOL 1e-08 1e-10
STORAGE
BUFX0 3 1
BUFVX 4 2
BUFEKIN 3
PRINTBUF
SAVEDATA 1 2
ANIMATE swing
BEGINPIC path of A
PLOTCURV 1 2
PLOTHODO 3 4
ENDPIC
END
";

fn built() -> Result<DeckBuilder, Box<crate::Diagnostic>> {
    let mut b = DeckBuilder::new("pendulum.mec", Mode::DynSim)?;
    b.units(Some("mm"), Some("DEG"), None, None, None)?;
    b.element("BIN", &[1, 2, 3, 4], Some("crank: A0 A"))?;
    b.form("LENL", 1, 1, 1.0, Some("crank.length"))?;
    b.form("angb", 1, 2, 1.0, Some("crank.angle"))?;
    b.nrdof(1)?;
    for (i, v, moving, name) in
        [(1, 0.0, false, "A0.x"), (2, 0.0, false, "A0.y"), (3, 1.0, true, "A.x"), (4, 0.5, true, "A.y")]
    {
        b.coordinate(i, v, moving, Some(name))?;
    }
    b.para(1, 1.118033988749895, Some("crank.length"))?;
    b.name("POINT", &[3, 4], "A")?;
    b.name("coord", &[1], "a0x")?;
    b.name("ELEM", &[1], "crank")?;
    b.name("ROW", &[2], "phi")?;
    b.name("BUF", &[1], " the x of A ")?;
    b.dynamics()?;
    b.mass(1, 2.0, 0.5, 0.0, 0.1, "crank")?;
    b.point_mass(3, 4, 0.25, "A")?;
    b.gravity(0.0, -9.81)?;
    b.force(3, 4, 1.0, 0.0, "A")?;
    b.spring(2, 3.0, 0.2, 0.05, "crank.angle")?;
    b.motor(2, 1.5, 10.0, "crank.angle")?;
    b.movement(20, 0.01)?;
    b.motion(1, "dynamic", 0.5, "crank.angle")?;
    b.tolerances(Some(1e-10), Some(30), Some((1e-8, 1e-10)))?;
    b.storage()?;
    b.buffer("BUFX0", &[3], 1)?;
    b.buffer("bufvx", &[4], 2)?;
    b.buffer("BUFEKIN", &[], 3)?;
    b.printbuf(&[])?;
    b.savedata(&[1, 2])?;
    b.animate("swing")?;
    b.picture(" path of A ", &[("PLOTCURV".into(), 1, 2), ("PLOTHODO".into(), 3, 4)])?;
    Ok(b)
}

#[test]
fn builder_and_parser_compile_the_same_model() {
    let parsed = crate::parse_str(TEXT, "pendulum.mec").unwrap();
    let b = built().unwrap();
    let from_text = format!("{:?}", crate::compile(&parsed, Path::new(".")));
    let from_builder = format!("{:?}", b.build(Path::new(".")));
    assert!(from_text.starts_with("Ok("), "{from_text}");
    assert_eq!(from_builder, from_text);
}

#[test]
fn a_value_the_parser_refuses_is_refused_with_the_items_name() {
    let mut b = DeckBuilder::new("m.mec", Mode::KinAna).unwrap();
    b.element("BIN", &[1, 2, 3, 4], Some("crank: A0 A")).unwrap();
    let e = b.form("LENL", 1, 0, 1.0, Some("crank.length")).unwrap_err();
    assert_eq!(e.kind, DiagnosticKind::ZeroDestination);
    assert!(e.message.contains("\"crank.length\""), "{}", e.message);
    let e = b.element("BIN", &[1, 2, 3], Some("coupler")).unwrap_err();
    assert_eq!(e.kind, DiagnosticKind::ArgumentCount);
    b.form("LENL", 1, 1, 1.0, None).unwrap();
    b.form("ANGB", 1, 2, 1.0, None).unwrap();
    assert_eq!(b.nrdof(0).unwrap_err().kind, DiagnosticKind::BadValue);
    b.nrdof(1).unwrap();
    let e = b.coordinate(3, f64::INFINITY, true, Some("A.x")).unwrap_err();
    assert!(e.message.contains("the value of the co-ordinate \"A.x\" is inf"), "{}", e.message);
    assert_eq!(b.movement(0, 1.0).unwrap_err().kind, DiagnosticKind::BadValue);
    assert_eq!(b.name("ROW", &[1], "crank.length").unwrap_err().kind, DiagnosticKind::BadName);
    b.name("ROW", &[1], "length").unwrap();
    assert_eq!(b.name("ROW", &[2], "length").unwrap_err().kind, DiagnosticKind::DuplicateName);
    assert_eq!(b.coordinate(4, 0.0, true, None).unwrap_err().kind, DiagnosticKind::WrongBlock);
    // A model without masses has no dynamics, and free motion cannot drive one that has them.
    assert_eq!(b.dynamics().unwrap_err().kind, DiagnosticKind::WrongMode);
    let mut d = DeckBuilder::new("d.mec", Mode::DynAna).unwrap();
    d.element("BIN", &[1, 2, 3, 4], None).unwrap();
    d.form("LENL", 1, 1, 1.0, None).unwrap();
    d.form("ANGB", 1, 2, 1.0, None).unwrap();
    d.nrdof(1).unwrap();
    d.dynamics().unwrap();
    assert_eq!(d.mass(1, -1.0, 0.0, 0.0, 0.0, "crank").unwrap_err().kind, DiagnosticKind::BadValue);
    assert_eq!(d.load(2, 1e200, "crank.angle").unwrap_err().kind, DiagnosticKind::NumberOutOfRange);
    d.movement(10, 0.1).unwrap();
    assert_eq!(d.motion(1, "free", 0.1, "crank.angle").unwrap_err().kind, DiagnosticKind::WrongMode);
    d.storage().unwrap();
    d.animate("swing").unwrap();
    assert_eq!(d.animate("again").unwrap_err().kind, DiagnosticKind::DuplicateKeyword);
}

#[test]
fn a_mistake_the_compiler_finds_names_the_item_by_its_number() {
    // A crank whose points coincide, and a co-ordinate on no element: the
    // compiler's diagnostics carry the numbers the builder gave the items.
    let mut b = DeckBuilder::new("m.mec", Mode::KinAna).unwrap();
    b.element("BIN", &[1, 2, 3, 4], Some("crank: A0 A")).unwrap();
    let crank = b.item();
    b.form("LENL", 1, 1, 1.0, None).unwrap();
    b.form("ANGB", 1, 2, 1.0, None).unwrap();
    b.nrdof(1).unwrap();
    let mut numbers = Vec::new();
    for i in 1..=5 {
        b.coordinate(i, 0.0, i > 2, None).unwrap();
        numbers.push(b.item());
    }
    b.para(1, 1.0, None).unwrap();
    let unused = numbers[4];
    let d = b.build(Path::new(".")).unwrap_err();
    let lines: Vec<(DiagnosticKind, usize)> = d.iter().map(|d| (d.kind, d.line)).collect();
    assert!(lines.contains(&(DiagnosticKind::CoordinateUnused, unused)), "{lines:?}");
    let mut b2 = DeckBuilder::new("m.mec", Mode::KinAna).unwrap();
    b2.element("BIN", &[1, 2, 3, 4], Some("crank: A0 A")).unwrap();
    b2.form("LENL", 1, 1, 1.0, None).unwrap();
    b2.form("ANGB", 1, 2, 1.0, None).unwrap();
    b2.nrdof(1).unwrap();
    for i in 1..=4 {
        b2.coordinate(i, 0.0, i > 2, None).unwrap();
    }
    b2.para(1, 1.0, None).unwrap();
    let d = b2.build(Path::new(".")).unwrap_err();
    let model: Vec<usize> = d.iter().filter(|d| d.kind == DiagnosticKind::Model).map(|d| d.line).collect();
    assert_eq!(model, vec![crank], "{d:?}");
}

#[test]
fn a_refused_value_is_said_in_the_models_units() {
    let model = |units: bool| {
        let mut d = DeckBuilder::new("d.mec", Mode::DynAna).unwrap();
        if units {
            d.units(Some("mm"), Some("deg"), Some("g"), Some("N"), Some("ms")).unwrap();
        }
        d.element("BIN", &[1, 2, 3, 4], None).unwrap();
        d.form("LENL", 1, 1, 1.0, None).unwrap();
        d.form("ANGB", 1, 2, 1.0, None).unwrap();
        d.nrdof(1).unwrap();
        d
    };
    let mut d = model(true);
    d.dynamics().unwrap();
    let e = d.mass(1, -0.5, 0.0, 0.0, 0.0, "crank").unwrap_err();
    assert!(e.message.ends_with("the mass of crank must not be negative, got -0.5 g"), "{}", e.message);
    let e = d.mass(1, 1.0, 0.0, 0.0, -2.0, "crank").unwrap_err();
    assert!(e.message.ends_with("got -2 g·mm²"), "{}", e.message);
    assert!(d.movement(10, -1.0).unwrap_err().message.contains("(dt) is -1 ms:"));
    // Without UNITS the numbers are bare, as the deck's own.
    let mut d = model(false);
    d.dynamics().unwrap();
    assert!(d.mass(1, -0.5, 0.0, 0.0, 0.0, "crank").unwrap_err().message.ends_with("got -0.5"));
    assert!(d.movement(10, -1.0).unwrap_err().message.contains("(dt) is -1:"));
}
