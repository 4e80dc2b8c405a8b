//! What `check_deck` and `deck_files` hand Python, as typed objects with
//! getters: [`Check`] (position 1 of a deck, its sizes and its model echo)
//! and [`DeckFiles`] (what a deck reads and writes, from its text alone).

use numpy::PyArray1;
use pyo3::prelude::*;

use crate::echo::EchoModel;

/// Position 1 of a deck, computed without its motion: the model's sizes,
/// det(D^c) and the co-ordinates there (in the deck's units), the
/// adjustment that led there and the model echo.
#[pyclass(module = "mechfem._core", frozen, get_all)]
pub struct Check {
    /// Number of co-ordinates.
    pub n_coords: usize,
    /// Number of moving co-ordinates.
    pub n_moving: usize,
    /// Number of prescribed rows.
    pub n_prescribed: usize,
    /// Number of dependent rows.
    pub n_dependent: usize,
    /// Degrees of freedom.
    pub n_dof: usize,
    /// det(D^c) at position 1.
    pub det: f64,
    /// Every co-ordinate at position 1.
    pub coords: Py<PyArray1<f64>>,
    /// The adjustment to position 1.
    pub adjust: crate::report::Adjust,
    /// The model echo (see `convert::model`).
    pub model: Py<EchoModel>,
}

/// What a deck reads and writes, from its text alone.
#[pyclass(module = "mechfem._core", frozen, get_all)]
pub struct DeckFiles {
    /// `KIN ANA`, `KIN OPT`, `DYN ANA` or `DYN SIM`.
    pub mode: &'static str,
    /// The files of MOV_FUNC, LOADFUNC and TARGET tables as the deck names
    /// them (relative to its folder).
    pub tables: Vec<String>,
    /// Whether the deck saves a data set.
    pub savedata: bool,
    /// How many pictures it draws.
    pub pictures: usize,
    /// Its ANIMATE name, if any.
    pub animate: Option<String>,
}
