//! What the TOLERANCE block of a `KIN ANA` or `DYN ANA` deck compiles to:
//! the toleranced dimensions with their tolerances, and the buffers whose
//! bands are recorded.
//!
//! The deck reader only states the problem; the bands come from the design
//! sensitivities of [`mechfem_core::design::evaluate`]. Tolerances are in
//! the core's units, as every number of a [`crate::Compiled`].

use mechfem_core::run::tolerance::{bands, Bands};
use mechfem_core::run::Extent;
use mechfem_core::{DesignVar, Dim, FormRef, Quantity, SolveError, State};

use crate::Compiled;

/// The compiled TOLERANCE block.
#[derive(Debug, Clone, PartialEq)]
pub struct Tolerance {
    /// The toleranced dimensions (TOL, TOLX), in deck order; at least one.
    pub dims: Vec<Toleranced>,
    /// The bands recorded (BUFTOL), in deck order; at least one.
    pub bands: Vec<BandDef>,
    /// Line of the TOLERANCE header.
    pub line: usize,
}

/// A dimension known to within +-t: `TOL r t` or `TOLX i t`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Toleranced {
    /// [`DesignVar::Row`] (0-based prescribed row) for TOL,
    /// [`DesignVar::Fixed`] (0-based fixed co-ordinate) for TOLX.
    pub var: DesignVar,
    /// The tolerance t (positive, in the core's units).
    pub t: f64,
    /// Line of the keyword.
    pub line: usize,
}

/// `BUFTOL bsrc b`: the band of buffer `source`, worst case into `buffer`
/// and root sum of squares into `buffer + 1`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BandDef {
    /// The buffer whose band is recorded (a number of
    /// [`crate::Compiled::buffers`]).
    pub source: u32,
    /// The worst-case band's number (the RSS band is `buffer + 1`).
    pub buffer: u32,
    /// Line of the keyword.
    pub line: usize,
}

/// Why a buffer has no band: the quantities without exact design
/// sensitivities, in words (`None`: it has them). The one place where a
/// BUFTOL source (and a quantity of `tolerance_bands`) is refused.
pub fn without_sensitivity(q: Quantity) -> Option<&'static str> {
    (q == Quantity::Det).then_some("det(D^c)")
}

/// Why bands of a compiled model cannot be computed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum BandsError {
    /// The model has no motion.
    #[error("tolerance bands need a motion: their positions are where the bands are computed")]
    NoMotion,
    /// A band's source is no buffer of the model.
    #[error("buffer {0} is not defined: a band is of a buffer of the STORAGE block")]
    UnknownSource(u32),
    /// A band's source has no design sensitivity.
    #[error(
        "buffer {number}, {what}, has no design sensitivity: a band is made of the exact first-order \
             sensitivities of its buffer to the toleranced dimensions"
    )]
    NoSensitivity {
        /// The buffer.
        number: u32,
        /// What it records, in words ([`without_sensitivity`]).
        what: &'static str,
    },
    /// A toleranced dimension is no prescribed value nor fixed co-ordinate
    /// of the model (0-based).
    #[error("{} is no dimension of the model: a tolerance is of a prescribed row's value (not an input) or of a \
             fixed co-ordinate", match .0 { DesignVar::Row(r) => format!("row {}", r.wrapping_add(1)),
             DesignVar::Fixed(i) => format!("co-ordinate {}", i.wrapping_add(1)) })]
    NotADimension(DesignVar),
    /// A tolerance is not positive and finite.
    #[error("a tolerance must be positive and finite, not {0}")]
    NotPositive(f64),
    /// The run with the sensitivities failed at position 1.
    #[error(transparent)]
    Solve(#[from] SolveError),
}

/// The kind of a toleranced dimension.
fn dim_of(c: &Compiled, var: DesignVar) -> Dim {
    match var {
        DesignVar::Row(r) => c.dims.form(FormRef::Prescribed(r)),
        DesignVar::Fixed(i) => c.dims.coord(i),
    }
}

/// The bands of a TOLERANCE block evaluated over a compiled model's motion,
/// in the model's units (a BUFTOL's b and b + 1 are [`Bands::worst`] and
/// [`Bands::rss`]), with the names and units that label them.
#[derive(Debug, Clone)]
pub struct EvaluatedBands {
    /// The bands ([`mechfem_core::run::tolerance::bands`]), every number in
    /// the model's units.
    pub bands: Bands,
    /// The label and unit of each band's buffer.
    pub labels: Vec<(String, String)>,
    /// The unit of each toleranced dimension ("" without UNITS).
    pub dim_units: Vec<String>,
    /// The unit of each input ("" without UNITS).
    pub input_units: Vec<String>,
}

impl Tolerance {
    /// A TOLERANCE block of toleranced dimensions `(var, t)` (t in the
    /// model's units) and the band sources `sources` (buffer numbers of
    /// `c`, recorded into no buffer), as a model built item by item states
    /// it.
    pub fn of_items(c: &Compiled, dims: &[(DesignVar, f64)], sources: &[u32]) -> Result<Tolerance, BandsError> {
        let mech = &c.mechanism;
        let mut out = Vec::with_capacity(dims.len());
        for &(var, t) in dims {
            let known = match var {
                DesignVar::Row(r) => r < mech.n_prescribed() && mech.input_of(r).is_none(),
                DesignVar::Fixed(i) => i < mech.n_coords() && !mech.is_moving(i),
            };
            if !known {
                return Err(BandsError::NotADimension(var));
            }
            if !(t.is_finite() && t > 0.0) {
                return Err(BandsError::NotPositive(t));
            }
            out.push(Toleranced { var, t: t / dim_of(c, var).out_scale(&c.units), line: 0 });
        }
        let bands = sources.iter().map(|&source| BandDef { source, buffer: 0, line: 0 }).collect();
        Ok(Tolerance { dims: out, bands, line: 0 })
    }

    /// The bands over `c`'s motion, from `c`'s own numbers.
    pub fn evaluate(&self, c: &Compiled) -> Result<EvaluatedBands, BandsError> {
        self.evaluate_from(c, c.state.clone())
    }

    /// The bands over `c`'s motion from `state` (`c`'s numbers with
    /// changes made, [`Compiled::numbers`]), as a run of it moves.
    pub fn evaluate_from(&self, c: &Compiled, mut state: State) -> Result<EvaluatedBands, BandsError> {
        let motion = c.motion_for(&mut state, Extent::Motion).ok_or(BandsError::NoMotion)?;
        let mut sources = Vec::with_capacity(self.bands.len());
        for band in &self.bands {
            let b = c.buffers.iter().find(|b| b.number == band.source).ok_or(BandsError::UnknownSource(band.source))?;
            if let Some(what) = without_sensitivity(b.quantity) {
                return Err(BandsError::NoSensitivity { number: b.number, what });
            }
            sources.push(b);
        }
        let quantities: Vec<Quantity> = sources.iter().map(|b| b.quantity).collect();
        let dims: Vec<mechfem_core::run::tolerance::Toleranced> =
            self.dims.iter().map(|d| mechfem_core::run::tolerance::Toleranced { var: d.var, t: d.t }).collect();
        let mut bands = bands(&c.mechanism, &mut state, &motion, &c.params, c.dynamics.as_ref(), &dims, &quantities)
            .map_err(|e| BandsError::Solve(c.error_as_written(&e)))?;
        // Into the model's units: a band is in its quantity's unit, a
        // sensitivity in the quantity's per the dimension's.
        let (nb, nv, nj) = (quantities.len(), dims.len(), c.mechanism.n_dof());
        let q_scale: Vec<f64> = quantities.iter().map(|&q| c.out_scale(q)).collect();
        let v_scale: Vec<f64> = self.dims.iter().map(|d| dim_of(c, d.var).out_scale(&c.units)).collect();
        let j_scale: Vec<f64> = (0..nj).map(|j| c.dims.input(&c.mechanism, j).out_scale(&c.units)).collect();
        for (k, t) in bands.tolerances.iter_mut().enumerate() {
            *t *= v_scale[k];
        }
        for p in 0..bands.positions {
            for j in 0..nj {
                bands.inputs[p * nj + j] *= j_scale[j];
            }
            for q in 0..nb {
                bands.values[p * nb + q] *= q_scale[q];
                bands.worst[p * nb + q] *= q_scale[q];
                bands.rss[p * nb + q] *= q_scale[q];
                for v in 0..nv {
                    bands.sensitivity[(p * nb + q) * nv + v] *= q_scale[q] / v_scale[v];
                }
            }
        }
        for (q, w) in bands.widest.iter_mut().enumerate() {
            for s in w.iter_mut().flat_map(|w| w.shares.iter_mut()) {
                s.sensitivity *= q_scale[q] / v_scale[s.dim];
                s.deviation *= q_scale[q];
            }
        }
        Ok(EvaluatedBands {
            bands,
            labels: sources.iter().map(|b| (c.label(b), c.unit(b))).collect(),
            dim_units: self.dims.iter().map(|d| dim_of(c, d.var).symbol(&c.units)).collect(),
            input_units: (0..nj).map(|j| c.dims.input(&c.mechanism, j).symbol(&c.units)).collect(),
        })
    }
}

impl Compiled {
    /// The BUFTOL whose band buffer `number` is, and whether it is the RSS
    /// band (b + 1) rather than the worst case (b).
    pub fn band_of(&self, number: u32) -> Option<(&BandDef, bool)> {
        let bands = self.tolerance.iter().flat_map(|t| &t.bands);
        bands.filter_map(|b| (number == b.buffer || number == b.buffer + 1).then_some((b, number != b.buffer))).next()
    }

    /// Writes BUFTOL's bands into a run's buffer columns: `columns` holds
    /// [`Compiled::buffers`] column after column, `positions` values each,
    /// in the core's units, as the run recorded them from `start` (where
    /// a band's buffer holds its source's values). The bands are those of
    /// [`Tolerance::evaluate_from`] (in the core's units) at the run's
    /// positions; without TOLERANCE nothing is done.
    pub fn fill_bands(&self, mut start: State, columns: &mut [f64], positions: usize) -> Result<(), SolveError> {
        let Some(tolerance) = &self.tolerance else { return Ok(()) };
        // A compiled TOLERANCE block has a motion and sources among the buffers.
        let Some(motion) = self.motion_for(&mut start, Extent::Motion) else { return Ok(()) };
        let source = |d: &BandDef| self.buffers.iter().find(|b| b.number == d.source).map(|b| b.quantity);
        let Some(quantities) = tolerance.bands.iter().map(source).collect::<Option<Vec<Quantity>>>() else {
            return Ok(());
        };
        let dims: Vec<mechfem_core::run::tolerance::Toleranced> =
            tolerance.dims.iter().map(|d| mechfem_core::run::tolerance::Toleranced { var: d.var, t: d.t }).collect();
        let b = bands(&self.mechanism, &mut start, &motion, &self.params, self.dynamics.as_ref(), &dims, &quantities)?;
        let nb = quantities.len();
        for (k, buffer) in self.buffers.iter().enumerate() {
            let Some((def, rss)) = self.band_of(buffer.number) else { continue };
            let q = tolerance.bands.iter().position(|d| d == def).unwrap_or(0);
            let values = if rss { &b.rss } else { &b.worst };
            let column = &mut columns[k * positions..(k + 1) * positions];
            for (p, v) in column.iter_mut().enumerate() {
                *v = values.get(p * nb + q).copied().unwrap_or(f64::NAN);
            }
        }
        Ok(())
    }
}
