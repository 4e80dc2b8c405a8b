//! The compiled mechanism and its mutable state.
//!
//! A [`Mechanism`] is immutable and uses flat indices: co-ordinates `0..N`,
//! elements `0..n_e`, prescribed rows `0..n_p` (the rows of D^c) and dependent
//! form parameters `0..n_d`. The columns of D^c are the moving co-ordinates in
//! ascending order. The last `n_dof` prescribed rows are the inputs.
//!
//! A [`State`] holds what changes during a motion: the co-ordinates, the
//! prescribed values of the rows, and each element's angle memory.

use crate::elements::{ElementType, FormEval, Order, MAX_COORDS};
use crate::error::{ModelError, SolveError};

/// One single form parameter with its factor in a (combined) row, eq. 5.33.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Term {
    /// Element index.
    pub element: usize,
    /// Form-parameter index within the element type.
    pub form: usize,
    /// Factor f in `eps = sum f * eps_k`.
    pub factor: f64,
}

impl Term {
    /// A term with factor 1.
    pub fn new(element: usize, form: usize) -> Term {
        Term { element, form, factor: 1.0 }
    }
    /// A term with factor `factor`.
    pub fn scaled(element: usize, form: usize, factor: f64) -> Term {
        Term { element, form, factor }
    }
}

/// A form parameter named by its destination: a prescribed row or a
/// dependent form parameter.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum FormRef {
    /// Prescribed row r (0-based; deck destination r+1).
    Prescribed(usize),
    /// Dependent form parameter d (0-based; deck destination -(d+1)).
    Dependent(usize),
}

/// An element placed in a model: its type and its co-ordinates.
#[derive(Debug, Clone, Copy)]
pub struct Placed {
    /// Element type.
    pub ty: ElementType,
    /// Global co-ordinate indices in the type's order (first `ty.n_coords()`).
    pub coords: [usize; MAX_COORDS],
}

impl Placed {
    /// The element's co-ordinate indices.
    pub fn coords(&self) -> &[usize] {
        &self.coords[..self.ty.n_coords()]
    }
}

/// One single form parameter of a row, compiled for evaluation: its
/// element's type, co-ordinates and the column of D^c of each co-ordinate
/// (entries past the element's `n` co-ordinates have none).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Slot {
    /// Element type.
    pub ty: ElementType,
    /// Number of co-ordinates of the element.
    pub n: usize,
    /// Global co-ordinate indices (first `n`).
    pub coords: [usize; MAX_COORDS],
    /// Column of D^c of each co-ordinate, or [`FIXED`].
    pub cols: [usize; MAX_COORDS],
}

/// What a vector handed to a [`Slot`] is indexed by.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Over {
    /// The columns of D^c (the moving co-ordinates): fixed co-ordinates do
    /// not move.
    Columns,
    /// Every co-ordinate: a fixed one moves too (a design variable).
    Coordinates,
}

impl Slot {
    /// The indices into a vector `over` the columns or the co-ordinates.
    #[inline]
    pub fn indices(&self, over: Over) -> &[usize; MAX_COORDS] {
        match over {
            Over::Columns => &self.cols,
            Over::Coordinates => &self.coords,
        }
    }

    /// A vector `over` the columns or the co-ordinates seen from the
    /// element (0 where it has no entry: a fixed co-ordinate's column).
    #[inline]
    pub fn gather(&self, a: &[f64], over: Over) -> [f64; MAX_COORDS] {
        self.indices(over).map(|c| a.get(c).copied().unwrap_or(0.0))
    }
}

/// Rows of combined form parameters, stored flat (compressed rows), with
/// every term compiled into a [`Slot`].
#[derive(Debug, Clone, Default)]
pub(crate) struct Rows {
    start: Vec<usize>,
    terms: Vec<Term>,
    slots: Vec<Slot>,
    /// The row of every term.
    row_of: Vec<usize>,
    /// Whether every row is one term with factor 1 (most are).
    plain: bool,
}

impl Rows {
    fn push(&mut self, terms: &[Term]) {
        if self.start.is_empty() {
            self.start.push(0);
        }
        let row = self.start.len() - 1;
        self.terms.extend_from_slice(terms);
        self.row_of.extend(terms.iter().map(|_| row));
        self.start.push(self.terms.len());
    }
    /// Compiles every term once the elements and columns are known.
    fn compile(&mut self, elements: &[Placed], column: &[usize]) {
        self.slots = self
            .terms
            .iter()
            .map(|t| {
                let e = &elements[t.element];
                let n = e.ty.n_coords();
                let (mut coords, mut cols) = ([e.coords[0]; MAX_COORDS], [FIXED; MAX_COORDS]);
                for k in 0..n {
                    coords[k] = e.coords[k];
                    cols[k] = column[e.coords[k]];
                }
                Slot { ty: e.ty, n, coords, cols }
            })
            .collect();
        self.plain = self.terms.len() == self.len()
            && self.row_of.iter().enumerate().all(|(k, &row)| row == k)
            && self.terms.iter().all(|t| t.factor == 1.0);
    }
    pub(crate) fn len(&self) -> usize {
        self.start.len().saturating_sub(1)
    }
    pub(crate) fn row(&self, i: usize) -> &[Term] {
        &self.terms[self.start[i]..self.start[i + 1]]
    }
    /// Flat index range of row i's terms.
    pub(crate) fn range(&self, i: usize) -> std::ops::Range<usize> {
        self.start[i]..self.start[i + 1]
    }
    /// All terms, flat.
    pub(crate) fn terms(&self) -> &[Term] {
        &self.terms
    }
    /// The compiled terms, flat (parallel to [`Self::terms`]).
    pub(crate) fn slots(&self) -> &[Slot] {
        &self.slots
    }
    /// Whether every row is a single term with factor 1: its value is the
    /// term's.
    pub(crate) fn plain(&self) -> bool {
        self.plain
    }
    /// The row of every term, flat (parallel to [`Self::terms`]).
    pub(crate) fn row_of(&self) -> &[usize] {
        &self.row_of
    }
}

/// A compiled mechanism model (immutable).
#[derive(Debug, Clone)]
pub struct Mechanism {
    moving: Vec<bool>,
    column: Vec<usize>,
    moving_coords: Vec<usize>,
    elements: Vec<Placed>,
    pub(crate) prescribed: Rows,
    pub(crate) dependent: Rows,
    n_dof: usize,
}

/// Marker for "this co-ordinate is fixed" in [`Mechanism::column`].
pub const FIXED: usize = usize::MAX;

impl Mechanism {
    /// The state a mechanism starts from at the co-ordinates `x`, as
    /// [`MechanismBuilder::build`] makes it: every element evaluated there
    /// (an error when one cannot be, e.g. two of its points coincide), the
    /// angles it tracks taken from its directions there, and every
    /// prescribed row's value the one it has there. A model compiled once
    /// and run with other co-ordinates starts from this state, so that it
    /// runs as the model built with them would.
    pub fn start_state(&self, x: Vec<f64>) -> Result<State, ModelError> {
        let mut state =
            State { x, target: vec![0.0; self.n_prescribed()], branch: vec![f64::NAN; self.elements.len()] };
        // Every element must be evaluable at the start (no coinciding points).
        let mut out = FormEval::default();
        for (element, e) in self.elements.iter().enumerate() {
            let mut xe = [0.0; MAX_COORDS];
            for (k, &c) in e.coords().iter().enumerate() {
                xe[k] = state.x[c];
            }
            for form in 0..e.ty.form_names().len() {
                e.ty.eval(form, &xe[..e.ty.n_coords()], &mut state.branch[element], Order::Value, &mut out)
                    .map_err(|source| ModelError::Element { element, source })?;
            }
        }
        for r in 0..self.n_prescribed() {
            state.target[r] = state.prescribed_value(self, r).expect("every element was evaluated above");
        }
        Ok(state)
    }

    /// Number of co-ordinates N.
    pub fn n_coords(&self) -> usize {
        self.moving.len()
    }
    /// Number of moving co-ordinates (size of D^c).
    pub fn n_moving(&self) -> usize {
        self.moving_coords.len()
    }
    /// Number of prescribed rows (equal to [`Self::n_moving`]).
    pub fn n_prescribed(&self) -> usize {
        self.prescribed.len()
    }
    /// Number of dependent form parameters.
    pub fn n_dependent(&self) -> usize {
        self.dependent.len()
    }
    /// Number of degrees of freedom.
    pub fn n_dof(&self) -> usize {
        self.n_dof
    }
    /// Prescribed row of input `j` (0-based DOF).
    pub fn input_row(&self, j: usize) -> usize {
        self.n_prescribed() - self.n_dof + j
    }
    /// The input (0-based DOF) whose prescribed row is `r`; `None` for a
    /// row that is not an input's (the inputs are the last rows).
    pub fn input_of(&self, r: usize) -> Option<usize> {
        r.checked_sub(self.n_prescribed() - self.n_dof).filter(|&j| j < self.n_dof)
    }
    /// Whether co-ordinate `i` moves.
    pub fn is_moving(&self, i: usize) -> bool {
        self.moving[i]
    }
    /// Column of D^c of co-ordinate `i`, or [`FIXED`].
    pub fn column(&self, i: usize) -> usize {
        self.column[i]
    }
    /// The moving co-ordinates in column order.
    pub fn moving_coords(&self) -> &[usize] {
        &self.moving_coords
    }
    /// The elements.
    pub fn elements(&self) -> &[Placed] {
        &self.elements
    }
    /// Terms of prescribed row `r`.
    pub fn prescribed_terms(&self, r: usize) -> &[Term] {
        self.prescribed.row(r)
    }
    /// Terms of dependent form parameter `d`.
    pub fn dependent_terms(&self, d: usize) -> &[Term] {
        self.dependent.row(d)
    }

    /// Evaluates one single form parameter at the state's co-ordinates.
    #[inline]
    pub(crate) fn eval_term(
        &self,
        t: &Term,
        x: &[f64],
        branch: &mut [f64],
        order: Order,
        out: &mut FormEval,
    ) -> Result<(), SolveError> {
        let e = &self.elements[t.element];
        let n = e.ty.n_coords();
        let mut xe = [0.0; MAX_COORDS];
        for k in 0..n {
            xe[k] = x[e.coords[k]];
        }
        e.ty.eval(t.form, &xe[..n], &mut branch[t.element], order, out)
            .map_err(|source| SolveError::Element { element: t.element, source })
    }

    /// Value of a combined row of terms.
    pub(crate) fn eval_row(&self, terms: &[Term], x: &[f64], branch: &mut [f64]) -> Result<f64, SolveError> {
        let mut out = FormEval::default();
        let mut v = 0.0;
        for t in terms {
            self.eval_term(t, x, branch, Order::Value, &mut out)?;
            v += t.factor * out.value;
        }
        Ok(v)
    }
}

/// The mutable part of an analysis.
#[derive(Debug)]
pub struct State {
    /// All co-ordinates, fixed and moving.
    pub x: Vec<f64>,
    /// Prescribed value of every prescribed row (eps^p).
    pub target: Vec<f64>,
    /// Angle memory per element (NaN before the first evaluation).
    pub branch: Vec<f64>,
}

impl Clone for State {
    fn clone(&self) -> Self {
        State { x: self.x.clone(), target: self.target.clone(), branch: self.branch.clone() }
    }

    /// Copies into the existing buffers (no allocation when the sizes match).
    /// A driven run copies its state once a position into buffers of the
    /// same sizes: those are copied as slices, without `Vec::clone_from`'s
    /// truncation and extension.
    fn clone_from(&mut self, source: &Self) {
        let same = self.x.len() == source.x.len()
            && self.target.len() == source.target.len()
            && self.branch.len() == source.branch.len();
        if same {
            self.x.copy_from_slice(&source.x);
            self.target.copy_from_slice(&source.target);
            self.branch.copy_from_slice(&source.branch);
        } else {
            self.x.clone_from(&source.x);
            self.target.clone_from(&source.target);
            self.branch.clone_from(&source.branch);
        }
    }
}

impl State {
    /// Sets the prescribed values that are given (`values[r]` `Some`),
    /// leaving the others as they are (derived from the co-ordinates).
    pub fn set_given(&mut self, values: &[Option<f64>]) {
        for (t, v) in self.target.iter_mut().zip(values) {
            if let Some(v) = v {
                *t = *v;
            }
        }
    }

    /// Current value of prescribed row `r` at the co-ordinates.
    pub fn prescribed_value(&mut self, mech: &Mechanism, r: usize) -> Result<f64, SolveError> {
        mech.eval_row(mech.prescribed.row(r), &self.x, &mut self.branch)
    }
    /// Current value of dependent form parameter `d`.
    pub fn dependent_value(&mut self, mech: &Mechanism, d: usize) -> Result<f64, SolveError> {
        mech.eval_row(mech.dependent.row(d), &self.x, &mut self.branch)
    }
}

/// Builds a [`Mechanism`] and its initial [`State`] from co-ordinates,
/// elements and rows.
///
/// ```
/// use mechfem_core::{ElementType, MechanismBuilder, Term};
/// // A crank A0-A driven by its angle.
/// let mut b = MechanismBuilder::new();
/// let (x0, y0) = (b.fixed(0.0), b.fixed(0.0));
/// let (xa, ya) = (b.moving(1.0), b.moving(0.1));
/// let crank = b.element(ElementType::Bin, &[x0, y0, xa, ya]);
/// b.prescribe(&[Term::new(crank, 0)]); // length
/// b.input(&[Term::new(crank, 1)]); // angle
/// let (mech, state) = b.build().unwrap();
/// assert_eq!(mech.n_moving(), 2);
/// assert!((state.target[0] - 1.0f64.hypot(0.1)).abs() < 1e-15);
/// ```
#[derive(Debug, Clone, Default)]
pub struct MechanismBuilder {
    x: Vec<f64>,
    moving: Vec<bool>,
    elements: Vec<(ElementType, Vec<usize>)>,
    constant_rows: Vec<Vec<Term>>,
    input_rows: Vec<Vec<Term>>,
    dependent: Vec<Vec<Term>>,
}

impl MechanismBuilder {
    /// An empty model.
    pub fn new() -> Self {
        Self::default()
    }
    /// Adds a fixed co-ordinate; returns its index.
    pub fn fixed(&mut self, value: f64) -> usize {
        self.coord(value, false)
    }
    /// Adds a moving co-ordinate with its (possibly rough) initial value.
    pub fn moving(&mut self, value: f64) -> usize {
        self.coord(value, true)
    }
    /// Adds a co-ordinate; returns its index.
    pub fn coord(&mut self, value: f64, moving: bool) -> usize {
        self.x.push(value);
        self.moving.push(moving);
        self.x.len() - 1
    }
    /// Adds an element on the given co-ordinates; returns its index.
    pub fn element(&mut self, ty: ElementType, coords: &[usize]) -> usize {
        self.elements.push((ty, coords.to_vec()));
        self.elements.len() - 1
    }
    /// Adds a prescribed, constant row (a row of D^c that is not an input).
    /// Rows keep the order in which they are added; returns the row index
    /// among the constant rows.
    pub fn prescribe(&mut self, terms: &[Term]) -> usize {
        self.constant_rows.push(terms.to_vec());
        self.constant_rows.len() - 1
    }
    /// Adds an input row (a degree of freedom); inputs come after all
    /// constant rows in D^c. Returns the DOF index.
    pub fn input(&mut self, terms: &[Term]) -> usize {
        self.input_rows.push(terms.to_vec());
        self.input_rows.len() - 1
    }
    /// Adds a dependent form parameter (an output only); returns its index.
    pub fn dependent(&mut self, terms: &[Term]) -> usize {
        self.dependent.push(terms.to_vec());
        self.dependent.len() - 1
    }

    /// Checks the model and compiles it. The initial state's prescribed
    /// values are the values of the rows at the given co-ordinates
    /// (principal angles); change `State::target` to prescribe others, then
    /// adjust with [`crate::solver::adjust`].
    pub fn build(self) -> Result<(Mechanism, State), ModelError> {
        let n = self.x.len();
        if let Some(i) = self.x.iter().position(|v| !v.is_finite()) {
            return Err(ModelError::NonFiniteCoordinate { coordinate: i });
        }
        let mut elements = Vec::with_capacity(self.elements.len());
        for (k, (ty, coords)) in self.elements.iter().enumerate() {
            if coords.len() != ty.n_coords() {
                return Err(ModelError::WrongCoordinateCount {
                    element: k,
                    ty: ty.name(),
                    expected: ty.n_coords(),
                    got: coords.len(),
                });
            }
            if let Some(&c) = coords.iter().find(|&&c| c >= n) {
                return Err(ModelError::UnknownCoordinate { element: k, coordinate: c, n_coords: n });
            }
            let mut placed = Placed { ty: *ty, coords: [0; MAX_COORDS] };
            placed.coords[..coords.len()].copy_from_slice(coords);
            elements.push(placed);
        }
        let check = |row: usize, terms: &[Term]| -> Result<(), ModelError> {
            if terms.is_empty() {
                return Err(ModelError::EmptyRow { row });
            }
            for t in terms {
                let e = elements
                    .get(t.element)
                    .ok_or(ModelError::UnknownElement { element: t.element, n_elements: elements.len() })?;
                if t.form >= e.ty.form_names().len() {
                    return Err(ModelError::UnknownForm { element: t.element, ty: e.ty.name(), form: t.form });
                }
            }
            Ok(())
        };
        let mut prescribed = Rows::default();
        for (r, terms) in self.constant_rows.iter().chain(&self.input_rows).enumerate() {
            check(r, terms)?;
            prescribed.push(terms);
        }
        let mut dependent = Rows::default();
        for (d, terms) in self.dependent.iter().enumerate() {
            check(d, terms)?;
            dependent.push(terms);
        }
        let moving_coords: Vec<usize> = (0..n).filter(|&i| self.moving[i]).collect();
        let mut column = vec![FIXED; n];
        for (c, &i) in moving_coords.iter().enumerate() {
            column[i] = c;
        }
        let n_dof = self.input_rows.len();
        if prescribed.len() != moving_coords.len() {
            return Err(ModelError::NotSquare { n_rows: prescribed.len(), n_moving: moving_coords.len() });
        }
        prescribed.compile(&elements, &column);
        dependent.compile(&elements, &column);
        let mech = Mechanism { moving: self.moving, column, moving_coords, elements, prescribed, dependent, n_dof };
        let state = mech.start_state(self.x)?;
        Ok((mech, state))
    }
}
