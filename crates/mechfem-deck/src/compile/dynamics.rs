//! DYNAMICS to a core [`Dynamics`]: masses, loads and springs referred to
//! the model's elements, co-ordinates and form parameters; LOADFUNC files.

use std::path::Path;

use mechfem_core::dynamics::{has_frame, Body, Dynamics, Force, Inertia, Load, LoadKind, PointMass};
use mechfem_core::{DynamicSource, Mechanism};

use super::refs::{coordinate, form, Sizes};
use super::table::{self, Layout};
use crate::ast::{self, missing_dynamics, Deck, LoadDefKind, MassDef};
use crate::diagnostic::{count, numbered, Diagnostic, DiagnosticKind, Hint, Span, Spanned, Subject};
use crate::keywords::Keyword;
use crate::statements::dynamics::out_of_bounds;

/// The largest LOADFUNC file read: a load table is a few thousand rows at
/// most, and a larger file is more likely the wrong file.
const MAX_LOAD_FILE: u64 = 8 << 20;

/// Each mass and load with the line of its statement.
pub(crate) type StatementLines = Vec<(DynamicSource, usize)>;

/// The mass and load model of a `DYN ANA` or `DYN SIM` deck (`None` for
/// other modes), with the line of the statement each mass and load comes
/// from (a fault found during the run names it).
pub(crate) fn dynamics(
    deck: &Deck,
    mech: &Mechanism,
    sizes: &Sizes,
    deck_dir: &Path,
) -> Result<Option<(Dynamics, StatementLines)>, Box<Diagnostic>> {
    let mode = deck.mode.value;
    if !mode.has_dynamics() {
        return Ok(None);
    }
    let mut lines: Vec<(DynamicSource, usize)> = Vec::new();
    let Some(block) = &deck.dynamics else {
        return Err(missing_dynamics(&deck.path, &deck.source, mode, deck.mode.span));
    };
    let mut d = Dynamics::default();
    // What each line puts a mass or load on, and the line: a second line
    // of the same keyword on the same thing is refused (its numbers would
    // add up unseen).
    let mut given: Vec<(Keyword, Carrier, usize)> = Vec::new();
    let mut once = |kw: Keyword, carrier: Carrier, line: usize, span: Span| {
        let Some(&(_, _, first)) = given.iter().find(|(k, c, _)| (*k, *c) == (kw, carrier)) else {
            given.push((kw, carrier, line));
            return Ok(());
        };
        let name = carrier.name();
        Err(deck
            .error(DiagnosticKind::DuplicateKeyword, span, format!("{name} already has a {kw}, given at line {first}"))
            .with_hint(format!(
                "give one {kw} line for {name}: add the values of the two lines into one, or correct the number if \
                 the second line is meant for something else"
            )))
    };
    for m in &block.masses {
        once(Keyword::Mass, Carrier::Element(m.element.value), m.line, m.element.span)?;
        let k = element(deck, m)?;
        lines.push((DynamicSource::Body { element: k }, m.line));
        d.bodies.push(Body {
            element: k,
            mass: m.mass.value,
            u: m.u.value,
            v: m.v.value,
            inertia: m.inertia.map_or(0.0, |j| j.value),
        });
    }
    for p in &block.point_masses {
        let (x, y) = (coordinate(deck, sizes, Keyword::Pmass, &p.x)?, coordinate(deck, sizes, Keyword::Pmass, &p.y)?);
        once(Keyword::Pmass, Carrier::Point(p.x.value, p.y.value), p.line, p.x.span.to(p.y.span))?;
        lines.push((DynamicSource::PointMass { x, y }, p.line));
        d.point_masses.push(PointMass { x, y, mass: p.mass.value });
    }
    for i in &block.inertias {
        // Any co-ordinate may carry an inertia; one that is no element's
        // angle is still a rotation the user may mean (a wheel's angle
        // coupled by a combined row, say).
        let coord = coordinate(deck, sizes, Keyword::Inertia, &i.coord)?;
        once(Keyword::Inertia, Carrier::Coordinate(i.coord.value), i.line, i.coord.span)?;
        lines.push((DynamicSource::Inertia { coord }, i.line));
        d.inertias.push(Inertia { coord, inertia: i.inertia.value });
    }
    if let Some(g) = &block.gravity {
        d.gravity = [g.gx.value, g.gy.value];
    }
    for f in &block.forces {
        let (x, y) = (coordinate(deck, sizes, Keyword::Force, &f.x)?, coordinate(deck, sizes, Keyword::Force, &f.y)?);
        once(Keyword::Force, Carrier::Point(f.x.value, f.y.value), f.line, f.x.span.to(f.y.span))?;
        lines.push((DynamicSource::Force { x, y }, f.line));
        d.forces.push(Force { x, y, f: [f.fx.value, f.fy.value] });
    }
    for l in &block.loads {
        let form = form(deck, sizes, l.keyword.value, &l.form)?;
        once(l.keyword.value, Carrier::Form(l.form.value), l.line, l.form.span)?;
        let kind = match &l.kind {
            LoadDefKind::Constant(q) => LoadKind::Constant(q.value),
            LoadDefKind::Function(file) => LoadKind::Table(load_table(deck, file, deck_dir)?),
            LoadDefKind::Spring { k, e0, c } => {
                LoadKind::Spring { k: k.value, e0: e0.value, c: c.map_or(0.0, |c| c.value) }
            }
            LoadDefKind::Motor { t0, w0 } => LoadKind::Motor { t0: t0.value, w0: w0.value },
        };
        lines.push((DynamicSource::Load { form, keyword: l.keyword.value.name() }, l.line));
        d.loads.push(Load { form, kind });
    }
    // Every line has been checked above; this is the core's own check, in
    // case the two ever disagree.
    d.check(mech).map_err(|e| {
        let width = deck.line_text(block.line).trim_end().chars().count();
        deck.error(
            DiagnosticKind::Model,
            Span::new(block.line, 0, width),
            format!("the masses and loads are refused: {e}"),
        )
    })?;
    Ok(Some((d, lines)))
}

/// What a line of the DYNAMICS block puts its mass or load on, in the
/// deck's numbers.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Carrier {
    Element(i64),
    /// A point, by its x and y co-ordinates.
    Point(i64, i64),
    Coordinate(i64),
    /// A form parameter by its destination.
    Form(i64),
}

impl Carrier {
    fn name(self) -> String {
        match self {
            Carrier::Element(k) => format!("element {k}"),
            Carrier::Point(x, y) => format!("the point ({x}, {y})"),
            Carrier::Coordinate(i) => format!("co-ordinate {i}"),
            Carrier::Form(r) if r > 0 => format!("prescribed row {r}"),
            Carrier::Form(r) => format!("dependent form parameter {r}"),
        }
    }
}

/// The element of a MASS line as a 0-based index: it must exist and have a
/// frame.
fn element(deck: &Deck, m: &MassDef) -> Result<usize, Box<Diagnostic>> {
    let elements = &deck.topology.elements;
    let k = m.element.value;
    let n_e = elements.len();
    let Some((index, e)) = usize::try_from(k - 1).ok().and_then(|i| Some((i, elements.get(i)?))) else {
        return Err(deck
            .error(
                DiagnosticKind::UnknownElement,
                m.element.span,
                format!("MASS names element {k}, but the model has {}", count(n_e, "element", "elements")),
            )
            .with_hint(format!("elements are numbered {} by their ELEM lines", numbered(n_e, 1))));
    };
    let ty = e.ty.value;
    if has_frame(ty) {
        return Ok(index);
    }
    Err(deck
        .error(
            DiagnosticKind::NoFrame,
            m.element.span,
            format!("element {k} is a {}, which has no frame to carry a mass", ty.name()),
        )
        .about_element(index)
        .with_hint(no_frame_hint(e)))
}

/// Where the mass of an element without a frame goes instead.
fn no_frame_hint(e: &ast::ElemDef) -> String {
    let ty = e.ty.value;
    let angles: Vec<String> = ty
        .coord_names()
        .iter()
        .zip(&e.coords)
        .filter(|(name, _)| name.starts_with("beta"))
        .map(|(name, c)| format!("{} ({name})", c.value))
        .collect();
    if angles.is_empty() {
        return format!(
            "a {} only constrains co-ordinates: put a mass at a point with `PMASS i j m`, or a body on a BIN, HLF, \
             TR1 or TR2 element with MASS",
            ty.name()
        );
    }
    format!(
        "a {} only couples wheels: put the wheel's mass on its HLF or TR1 element with MASS, or its inertia on its \
         angle co-ordinate with `INERTIA i J` (the angles of this element: {})",
        ty.name(),
        angles.join(", ")
    )
}

/// Reads a LOADFUNC file: rows `t value` in time order, at least one.
fn load_table(deck: &Deck, file: &Spanned<String>, deck_dir: &Path) -> Result<Vec<[f64; 2]>, Box<Diagnostic>> {
    let layout = Layout {
        keyword: Keyword::LoadFunc,
        kind: DiagnosticKind::LoadFile,
        columns: 2..=2,
        names: &["the time", "the load"],
        row: "write one row per time: t value",
        max_bytes: Some((
            MAX_LOAD_FILE,
            "a load table needs far fewer rows: the load is linear between rows, so give it at fewer times",
        )),
    };
    let table = table::read(deck, file, deck_dir, &layout)?;
    if table.rows.is_empty() {
        return Err(deck
            .error(DiagnosticKind::LoadFile, file.span, format!("the LOADFUNC file `{}` has no rows", file.value))
            .with_hint(
                "give at least one row `t value`: the load is linear between rows and keeps the end values outside \
                 the table",
            ));
    }
    let mut rows = Vec::with_capacity(table.rows.len());
    let mut previous: Option<(usize, f64)> = None;
    for (line, values) in &table.rows {
        let [t, value] = values.as_slice() else { continue };
        if let Some((before, t0)) = previous.filter(|(_, t0)| t.value < *t0) {
            return Err(table
                .error(
                    DiagnosticKind::LoadFile,
                    t.span,
                    format!("the time {} comes before the time {t0} of the row above (line {before})", t.value),
                )
                .with_hint(
                    "list the rows of a LOADFUNC file in order of time; two rows at the same time make a jump",
                ));
        }
        for (v, what) in [(t, "the time"), (value, "the load")] {
            if let Some((message, hint)) = out_of_bounds(what, v.value) {
                return Err(table.error(DiagnosticKind::NumberOutOfRange, v.span, message).with_hint(hint));
            }
        }
        previous = Some((*line, t.value));
        rows.push([t.value, value.value]);
    }
    Ok(rows)
}
