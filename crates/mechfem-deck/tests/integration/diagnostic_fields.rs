//! A diagnostic names what it is about in fields (its kind's stable code,
//! the element, the co-ordinate, the core's reason), so that a front end can
//! word it without reading the message.

use std::path::Path;

use mechfem_deck::{compile, parse_str, Diagnostic, DiagnosticKind};

const SLIDER_CRANK: &str = "KIN ANA\nTOPOLOGY\nELEM 1 BIN 1 2 3 4\n 2 BIN 3 4 5 6\n 3 CRD 6\n\
FORM 1 LENL 1 1\n 2 LENL 2 2\n 3 COOR 3 3\n 4 ANGB 1 4\nNRDOF 1\nGEOMETRY\nXFIX 1 0.0\n 2 0.0\n\
XMOV 3 0.0878\n 4 0.0479\n 5 0.384\n 6 0.0\nPARA 1 0.1\n 2 0.3\n 3 0.0\n";

/// The first diagnostic of `text`, which must be refused.
fn refusal(text: &str) -> Diagnostic {
    let path = Path::new("deck.mec");
    let result = parse_str(text, path).and_then(|deck| compile(&deck, Path::new(".")));
    let Err(d) = result else { panic!("the deck was accepted") };
    d.iter().next().expect("at least one diagnostic").clone()
}

#[test]
fn codes_are_the_kinds_in_snake_case() {
    assert_eq!(DiagnosticKind::CoordinateUnused.code(), "coordinate_unused");
    assert_eq!(DiagnosticKind::NotANumber.code(), "not_a_number");
    assert_eq!(DiagnosticKind::Io.code(), "io");
    assert_eq!(DiagnosticKind::NoFrame.code(), "no_frame");
}

#[test]
fn an_unused_coordinate_is_named_by_number() {
    let d = refusal(&SLIDER_CRANK.replace(" 2 0.0\n", " 2 0.0\n 7 1.0\n"));
    assert_eq!(d.kind.code(), "coordinate_unused");
    assert_eq!(d.coordinate, Some(7));
    assert_eq!(d.element, None);
}

#[test]
fn an_element_the_core_refuses_is_named_with_its_reason() {
    // The crank from (0, 0) to (0, 0): its points coincide, its angle is undefined.
    let d = refusal(&SLIDER_CRANK.replace("XMOV 3 0.0878\n 4 0.0479\n", "XMOV 3 0.0\n 4 0.0\n"));
    assert_eq!(d.kind, DiagnosticKind::Model);
    assert_eq!(d.element, Some(1));
    assert!(d.detail.as_deref().is_some_and(|r| r.contains("coincide")), "{d:?}");
}
