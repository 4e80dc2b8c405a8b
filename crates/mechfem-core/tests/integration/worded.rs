//! The words of a failed run ([`mechfem_core::worded`]): the deck's
//! numbering (1-based), the parts a front end rewords, and the analysis of
//! a singular D^c at position 1.

use mechfem_core::worded::{self, Part};
use mechfem_core::{DeckTerm, DesignError, ElementError, Observer, PositionView, SolveError, Unsupported};

/// An observer that keeps nothing.
struct Ignore;

impl Observer for Ignore {
    fn position(&mut self, _: &PositionView<'_>) {}
}

const SUPERFLUOUS: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../tests/decks/superfluous.mec");
const FOURBAR: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/fourbar/fourbar.mec");

#[test]
fn design_errors_number_as_the_deck_does() {
    assert_eq!(DesignError::NoRow(2).to_string(), "the deck has no prescribed row 3");
    assert_eq!(DesignError::NoCoordinate(0).to_string(), "the deck has no co-ordinate 1");
    // A change of number 0 has no index: it is said as the number given.
    assert_eq!(DesignError::NoCoordinate(usize::MAX).to_string(), "the deck has no co-ordinate 0");
    assert!(DesignError::Moving(4).to_string().starts_with("co-ordinate 5 moves (XMOV)"));
}

#[test]
fn an_element_error_names_the_element_by_deck_number_name_and_type() {
    let c = mechfem_deck::load(FOURBAR).unwrap();
    let err = SolveError::Element { element: 1, source: ElementError::CoincidentPoints };
    let worded = err.worded(&c.mechanism, &c.names, &[]);
    let ty = c.mechanism.elements()[1].ty.name();
    // The example's NAMES block calls element 2 the coupler.
    assert_eq!(worded.0[0], Part::Element { number: 2, ty, name: Some("coupler".to_owned()) });
    assert_eq!(worded.0[2], Part::Detail { element: 2, error: ElementError::CoincidentPoints });
    assert_eq!(worded.to_string(), format!("element 2 (coupler, {ty}): {}", ElementError::CoincidentPoints));
    assert_eq!(err.code(), "element");
}

#[test]
fn a_deck_term_stays_a_part_of_its_own() {
    let c = mechfem_deck::load(FOURBAR).unwrap();
    let worded = SolveError::Unsupported(Unsupported::FreeNeedsOneDof).worded(&c.mechanism, &c.names, &[]);
    assert!(worded.0.contains(&Part::Term(DeckTerm::FreeMotion)));
    assert_eq!(worded.to_string(), Unsupported::FreeNeedsOneDof.to_string());
}

#[test]
fn a_singular_position_one_names_the_superfluous_row_and_the_free_coordinates() {
    let mut c = mechfem_deck::load(SUPERFLUOUS).unwrap();
    let err = mechfem_core::run(&c.mechanism, &mut c.state, None, &c.params, &mut Ignore).unwrap_err();
    let (worded, dependence) = worded::position_one(&c.mechanism, &c.names, &[], &mut c.state, &err);
    let d = dependence.expect("a superfluous row makes D^c rank-deficient");
    assert_eq!(d.rank + 1, d.size);
    assert_eq!(d.rows.len(), 1);
    let text = worded.to_string();
    assert!(text.starts_with("D^c is singular"), "{text}");
    assert!(text.contains(&format!("prescribed row {} is superfluous", d.rows[0])), "{text}");
    assert!(worded.0.contains(&Part::Coords { numbers: d.coords.clone(), names: Vec::new() }));
}

#[test]
fn a_named_model_is_told_its_mistakes_by_its_names() {
    // The superfluous four-bar with NAMES: the superfluous row is said with
    // its name beside its number, the points that can move by their names.
    let text = std::fs::read_to_string(SUPERFLUOUS).unwrap()
        + "NAMES\nPOINT 1 2 A0\n      3 4 B0\n      5 6 A\n      7 8 B\nELEM 2 coupler\nROW 3 frame\n";
    let deck = mechfem_deck::parse_str(&text, "named.mec").unwrap();
    let mut c = mechfem_deck::compile(&deck, std::path::Path::new(".")).unwrap();
    let err = mechfem_core::run(&c.mechanism, &mut c.state, None, &c.params, &mut Ignore).unwrap_err();
    let (worded, dependence) = worded::position_one(&c.mechanism, &c.names, &[], &mut c.state, &err);
    let d = dependence.expect("a superfluous row makes D^c rank-deficient");
    let text = worded.to_string();
    assert_eq!(d.rows, vec![3], "{text}");
    assert!(text.contains("prescribed row 3 (frame) is superfluous"), "{text}");
    assert!(text.contains("co-ordinates 8, 5, 6, 7 (B.y, A.x, A.y, B.x) can move"), "{text}");
    // An element is said with its name and type; a point mass by its point.
    let element = SolveError::Element { element: 1, source: ElementError::CoincidentPoints };
    let said = element.worded(&c.mechanism, &c.names, &[]).to_string();
    assert!(said.starts_with("element 2 (coupler, BIN): "), "{said}");
    let fault = mechfem_core::DynamicsFault {
        quantity: mechfem_core::DynamicQuantity::PotentialEnergy,
        source: mechfem_core::DynamicSource::PointMass { x: 4, y: 5 },
    };
    let said = SolveError::Dynamics(fault).worded(&c.mechanism, &c.names, &[]).to_string();
    assert!(said.contains("of the PMASS at point A (co-ordinates 5, 6) is not finite"), "{said}");
    // Without names, the deck's numbers alone, as before.
    let unnamed = mechfem_deck::load(SUPERFLUOUS).unwrap();
    let said = element.worded(&unnamed.mechanism, &unnamed.names, &[]).to_string();
    assert!(said.starts_with("element 2 (BIN): "), "{said}");
    let said = SolveError::Dynamics(fault).worded(&unnamed.mechanism, &unnamed.names, &[]).to_string();
    assert!(said.contains("of the PMASS at co-ordinates 5, 6 is not finite"), "{said}");
}
