//! A deck's OPTIMISE block as Python reads it (`DeckDescription.optimise`):
//! typed objects with getters, in the deck's numbering. Its numbers are the
//! core's (SI with UNITS), as the engine computes; each variable, target and
//! bound carries the `unit` it has in the deck ("" without UNITS) and the
//! `scale` that gives a core number in it (1 without UNITS), so that a print
//! file or report says the deck's numbers.

use mechfem_core::{DesignVar, Dim, FormRef};
use mechfem_deck::{Compiled, Optimise, Sense, TargetKind};
use pyo3::prelude::*;

/// A design variable: VARY (`kind` 1, prescribed row `number`) or VARYX
/// (`kind` 0, fixed co-ordinate `number`) within `lo`..`hi`.
#[pyclass(module = "mechfem._core", frozen, eq, get_all, from_py_object)]
#[derive(Debug, Clone, PartialEq)]
pub struct DeckVary {
    kind: i64,
    number: usize,
    lo: f64,
    hi: f64,
    line: usize,
    unit: String,
    scale: f64,
}

/// A TARGET (`kind` `values`: one value a position, None where not
/// compared, read from `file`), TARGETAT (`at`: `position`, 1-based, and
/// `value`) or TARGETEXT (`extremum`: at the extrema of buffer `reference`,
/// `value`); the other fields are None.
#[pyclass(module = "mechfem._core", frozen, eq, get_all, from_py_object)]
#[derive(Debug, Clone, PartialEq)]
pub struct DeckTarget {
    buffer: u32,
    kind: &'static str,
    values: Option<Vec<Option<f64>>>,
    file: Option<String>,
    position: Option<usize>,
    reference: Option<u32>,
    value: Option<f64>,
    weight: f64,
    line: usize,
    unit: String,
    scale: f64,
}

/// A BOUND: buffer `buffer` within `lo`..`hi` at every position.
#[pyclass(module = "mechfem._core", frozen, eq, get_all, from_py_object)]
#[derive(Debug, Clone, PartialEq)]
pub struct DeckBound {
    buffer: u32,
    lo: f64,
    hi: f64,
    line: usize,
    unit: String,
    scale: f64,
}

/// The MINIMISE or MAXIMISE term: `sense` (`minimise`, `maximise`),
/// `reduce` (`max`, `maxabs`, `rms`, `end`) of `buffer`, with
/// `with_buffer` the magnitude `sqrt(b^2 + b2^2)` judged.
#[pyclass(module = "mechfem._core", frozen, eq, get_all, from_py_object)]
#[derive(Debug, Clone, PartialEq)]
pub struct DeckObjective {
    sense: &'static str,
    reduce: String,
    buffer: u32,
    with_buffer: Option<u32>,
    line: usize,
}

/// A VARYM line: `item` (MASS, U, V, J, PMASS, INERTIA) of the element or
/// co-ordinate `number`, the variable `kind` of a dynamic design model
/// (10..15), within `lo`..`hi`.
#[pyclass(module = "mechfem._core", frozen, eq, get_all, from_py_object)]
#[derive(Debug, Clone, PartialEq)]
pub struct DeckMassVary {
    item: &'static str,
    number: usize,
    kind: i64,
    lo: f64,
    hi: f64,
    line: usize,
    unit: String,
    scale: f64,
}

/// A synthesis statement: FREETIME (`row`, `ordered`, `within` in the core's
/// units with the input's deck `unit` and `scale`), FULLROT (`row`) or
/// VARYFRAME (the pivot's x `coordinate`, the range `lo`..`hi` in radians,
/// its deck `unit` and `scale`); the other fields are None.
#[pyclass(module = "mechfem._core", frozen, eq, get_all, from_py_object)]
#[derive(Debug, Clone, PartialEq)]
pub struct DeckSynthesis {
    row: Option<usize>,
    coordinate: Option<usize>,
    lo: Option<f64>,
    hi: Option<f64>,
    ordered: bool,
    within: Option<f64>,
    line: usize,
    unit: String,
    scale: f64,
}

/// The OPTIMISE block of a KIN OPT or DYN ANA deck.
#[pyclass(module = "mechfem._core", frozen, eq, get_all, from_py_object)]
#[derive(Debug, Clone, PartialEq)]
pub struct OptimiseBlock {
    vary: Vec<DeckVary>,
    targets: Vec<DeckTarget>,
    bounds: Vec<DeckBound>,
    objective: Option<DeckObjective>,
    /// OPTSTEPS.
    steps: usize,
    /// OPTTOL.
    tol: Option<f64>,
    /// OPTFTOL's (rtol, atol).
    ftol: Option<(f64, f64)>,
    /// The line of the OPTIMISE header.
    line: usize,
    free_time: Option<DeckSynthesis>,
    full_rotation: Option<DeckSynthesis>,
    frame: Option<DeckSynthesis>,
    mass_vary: Vec<DeckMassVary>,
}

impl OptimiseBlock {
    /// The OPTIMISE block `o` of the compiled deck `c`, with the deck's unit
    /// of every number.
    pub fn of(c: &Compiled, o: &Optimise) -> OptimiseBlock {
        // (unit, scale) of a kind of quantity in the deck's UNITS; ("", 1) without.
        let said = |dim: Dim| {
            if c.units.declared {
                (dim.symbol(&c.units), dim.out_scale(&c.units))
            } else {
                (String::new(), 1.0)
            }
        };
        let buffer = |b: u32| {
            c.buffers.iter().find(|x| x.number == b).map_or(Dim::NONE, |x| c.dims.quantity(&c.mechanism, x.quantity))
        };
        let vary = o
            .vary
            .iter()
            .map(|v| {
                let (kind, number, dim) = match v.var {
                    DesignVar::Fixed(i) => (0, i + 1, c.dims.coord(i)),
                    DesignVar::Row(r) => (1, r + 1, c.dims.form(FormRef::Prescribed(r))),
                };
                let (unit, scale) = said(dim);
                DeckVary { kind, number, lo: v.lo, hi: v.hi, line: v.line, unit, scale }
            })
            .collect();
        let targets = o
            .targets
            .iter()
            .map(|t| {
                let (kind, values, file, position, reference, value) = match &t.kind {
                    TargetKind::Values { file, values } => {
                        ("values", Some(values.clone()), Some(file.clone()), None, None, None)
                    }
                    TargetKind::At { position, value } => ("at", None, None, Some(position + 1), None, Some(*value)),
                    TargetKind::Extremum { reference, value } => {
                        ("extremum", None, None, None, Some(*reference), Some(*value))
                    }
                };
                let (unit, scale) = said(buffer(t.buffer));
                DeckTarget {
                    buffer: t.buffer,
                    kind,
                    values,
                    file,
                    position,
                    reference,
                    value,
                    weight: t.weight,
                    line: t.line,
                    unit,
                    scale,
                }
            })
            .collect();
        let bounds = o
            .bounds
            .iter()
            .map(|b| {
                let (unit, scale) = said(buffer(b.buffer));
                DeckBound { buffer: b.buffer, lo: b.lo, hi: b.hi, line: b.line, unit, scale }
            })
            .collect();
        let objective = o.objective.map(|ob| DeckObjective {
            sense: if ob.sense == Sense::Minimise { "minimise" } else { "maximise" },
            reduce: ob.reduce.name().to_ascii_lowercase(),
            buffer: ob.buffer,
            with_buffer: ob.with,
            line: ob.line,
        });
        let coord = |n: usize| c.dims.coord(n.saturating_sub(1));
        let mass_vary = o
            .mass_vary
            .iter()
            .map(|v| {
                let (unit, scale) = said(v.item.dim(coord(v.number)));
                let kind = 10 + mechfem_deck::MassItem::ALL.iter().position(|&m| m == v.item).unwrap_or(0) as i64;
                DeckMassVary {
                    item: v.item.name(),
                    number: v.number,
                    kind,
                    lo: v.lo,
                    hi: v.hi,
                    line: v.line,
                    unit,
                    scale,
                }
            })
            .collect();
        let synthesis = |row: Option<usize>, line: usize| DeckSynthesis {
            row: row.map(|r| r + 1),
            coordinate: None,
            lo: None,
            hi: None,
            ordered: false,
            within: None,
            line,
            unit: String::new(),
            scale: 1.0,
        };
        // FREETIME's WITHIN, a difference of the input's values in the input row's unit.
        let free_time = o.free_time.map(|f| {
            let (unit, scale) = said(c.dims.form(FormRef::Prescribed(f.row)));
            DeckSynthesis { ordered: f.ordered, within: f.within, unit, scale, ..synthesis(Some(f.row), f.line) }
        });
        // VARYFRAME's angle, which the engine varies in radians.
        let frame = o.frame.map(|f| {
            let (unit, scale) = said(Dim::ANGLE);
            DeckSynthesis {
                row: None,
                coordinate: Some(f.x + 1),
                lo: Some(f.lo),
                hi: Some(f.hi),
                ordered: false,
                within: None,
                line: f.line,
                unit,
                scale,
            }
        });
        OptimiseBlock {
            vary,
            targets,
            bounds,
            objective,
            steps: o.steps,
            tol: o.tol,
            ftol: o.ftol,
            line: o.line,
            free_time,
            full_rotation: o.full_rotation.map(|f| synthesis(Some(f.row), f.line)),
            frame,
            mass_vary,
        }
    }
}
