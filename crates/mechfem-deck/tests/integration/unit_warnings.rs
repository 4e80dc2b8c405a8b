//! Every angle a designer writes is looked at for the wrong unit: a VARY
//! range, a target or a bound on an angle buffer and STOPWHEN's value warn
//! as a PARA value and a motion do; a length of the same number does not.

use std::path::Path;

use mechfem_deck::{parse_str, Compiled, DiagnosticKind};

fn compile(text: &str) -> Compiled {
    let deck = parse_str(text, "warn.mec").unwrap_or_else(|e| panic!("{e}"));
    mechfem_deck::compile(&deck, Path::new(".")).unwrap_or_else(|e| panic!("{e}"))
}

fn messages(c: &Compiled) -> Vec<String> {
    assert!(c.warnings.iter().all(|w| w.kind == DiagnosticKind::SuspiciousUnit));
    c.warnings.iter().map(|w| w.message.clone()).collect()
}

/// A crank (row 2, its angle, the input) whose tip height is buffer 1 and
/// whose angle is buffer 2, optimised with `optimise`.
fn crank(units: &str, optimise: &str) -> String {
    format!(
        "KIN OPT\n{units}\nTOPOLOGY\nELEM 1 BIN 1 2 3 4\nFORM 1 LENL 1 1\n 2 ANGB 1 2\nNRDOF 1\nGEOMETRY\nXFIX 1 0\n 2 0\n\
         XMOV 3 1\n 4 0.5\nPARA 1 1\n 2 0\nMOVEMENT\nTSTEPE 4\nMOV_RELE 1 1\nOPTIMISE\n{optimise}\nBUFX0 4 1\nBUFINP 1 2\n"
    )
}

#[test]
fn vary_targets_and_bounds_on_angles_that_look_like_degrees_are_warned_about() {
    let c = compile(&crank("", "VARY 1 0.5 2\nTARGETAT 2 5 90\nBOUND 2 -180 180\nTARGETAT 1 5 90"));
    let said = messages(&c);
    assert_eq!(said.len(), 3, "{said:?}");
    assert!(said[0].starts_with("the target 90 is an angle in radians"), "{said:?}");
    assert!(said[1].starts_with("the lower bound -180") && said[2].starts_with("the upper bound 180"), "{said:?}");
    // A range of the angle row in degrees, in a deck in degrees, is what it says.
    let c = compile(&crank("UNITS ANGLE deg", "VARY 2 -180 180\nTARGETAT 1 5 0.5"));
    assert!(c.warnings.is_empty(), "{:?}", c.warnings);
    let c = compile(&crank("UNITS ANGLE deg", "VARY 2 -3.14159 3.14159\nTARGETAT 1 5 0.5"));
    let said = messages(&c);
    assert_eq!(said.len(), 2, "{said:?}");
    assert!(said[0].contains("the lower end of the range -3.14159 is an angle in degrees, but looks like radians"));
}

#[test]
fn stopwhen_on_an_angle_that_looks_like_degrees_is_warned_about() {
    let deck = |units: &str, value: f64| {
        format!(
            "DYN SIM\n{units}\nTOPOLOGY\nELEM 1 BIN 1 2 3 4\nFORM 1 LENL 1 1\n 2 ANGB 1 2\nNRDOF 1\nGEOMETRY\nXFIX 1 0\n\
             2 0\nXMOV 3 1\n 4 0\nPARA 1 1\n 2 0\nDYNAMICS\nPMASS 3 4 1\nGRAVITY 0 -9.81\nMOVEMENT\nTSTEPE 10 0.1\n\
             MOV_DYN 1 0\nSTOPWHEN 1 {value}\nSTORAGE\nBUFINP 1 1\nBUFX0 3 2\n"
        )
    };
    let said = messages(&compile(&deck("", -90.0)));
    assert_eq!(said, ["STOPWHEN's value -90 is an angle in radians, but looks like degrees"]);
    assert!(compile(&deck("", -1.0)).warnings.is_empty());
    assert!(compile(&deck("UNITS ANGLE deg", -90.0)).warnings.is_empty());
}
