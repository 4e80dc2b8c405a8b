//! What a deck's STORAGE block asks for, as Python reads it
//! (`Run.storage`): typed objects with getters, in the deck's numbering.

use mechfem_core::Quantity;
use mechfem_deck::{Compiled, PlotItem};

use crate::convert::dest;
use pyo3::exceptions::{PyKeyError, PyTypeError};
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// One `BUF...` line: buffer `number` holds the quantity `keyword args`.
#[pyclass(module = "mechfem._core", frozen, eq, get_all, from_py_object)]
#[derive(Debug, Clone, PartialEq)]
pub struct Buffer {
    /// The buffer's number.
    number: u32,
    /// The BUF keyword, e.g. `BUFKE1`.
    keyword: String,
    /// Its arguments before the buffer number, as the deck numbers them.
    args: Vec<i64>,
    /// The line of the BUF keyword.
    line: usize,
    /// Its label (see `mechfem.model.echo.Buffer`).
    name: String,
    /// The unit its values are in; "" without UNITS.
    unit: String,
    /// Which buffer of a keyword that fills several it is (BUFPIN: 1 for
    /// y; BUFSHAKE: 1 for y, 2 for the moment); 0 for the first.
    part: u8,
}

#[pymethods]
impl Buffer {
    /// The buffer with these values (what a pickle of it is made again from).
    #[new]
    #[pyo3(signature = (number, keyword, args, line, name = String::new(), unit = String::new(), part = 0))]
    fn new(number: u32, keyword: String, args: Vec<i64>, line: usize, name: String, unit: String, part: u8) -> Buffer {
        Buffer { number, keyword, args, line, name, unit, part }
    }

    /// The arguments of [`Buffer::new`] that make this buffer again.
    #[allow(clippy::type_complexity)]
    fn __getnewargs__(&self) -> (u32, String, Vec<i64>, usize, String, String, u8) {
        let b = self.clone();
        (b.number, b.keyword, b.args, b.line, b.name, b.unit, b.part)
    }

    fn __repr__(&self) -> String {
        format!("Buffer(number={}, keyword={:?}, args={:?}, line={})", self.number, self.keyword, self.args, self.line)
    }

    /// The definition as written in a deck, e.g. `BUFKE1 -1 1`.
    fn label(&self) -> String {
        let mut words = vec![self.keyword.clone()];
        words.extend(self.args.iter().map(i64::to_string));
        words.join(" ")
    }
}

/// One PLOTFUNC, PLOTCURV or PLOTHODO line.
#[pyclass(module = "mechfem._core", frozen, eq, get_all, from_py_object)]
#[derive(Debug, Clone, PartialEq)]
pub struct Plot {
    /// `PLOTFUNC`, `PLOTCURV` or `PLOTHODO`.
    keyword: String,
    /// The buffer on the horizontal axis (PLOTHODO: the x co-ordinate).
    a: i64,
    /// The buffer on the vertical axis (PLOTHODO: the y co-ordinate).
    b: i64,
}

#[pymethods]
impl Plot {
    /// The plot `keyword a b`.
    #[new]
    fn new(keyword: String, a: i64, b: i64) -> Plot {
        Plot { keyword, a, b }
    }

    /// The arguments of [`Plot::new`] that make this plot again.
    fn __getnewargs__(&self) -> (String, i64, i64) {
        (self.keyword.clone(), self.a, self.b)
    }

    fn __repr__(&self) -> String {
        format!("Plot(keyword={:?}, a={}, b={})", self.keyword, self.a, self.b)
    }
}

impl Plot {
    fn of(item: &PlotItem) -> Plot {
        let (keyword, a, b) = match *item {
            PlotItem::Function { x, y } => ("PLOTFUNC", i64::from(x), i64::from(y)),
            PlotItem::Curve { x, y } => ("PLOTCURV", i64::from(x), i64::from(y)),
            PlotItem::Hodograph { x, y } => ("PLOTHODO", x as i64 + 1, y as i64 + 1),
        };
        Plot { keyword: keyword.to_owned(), a, b }
    }
}

/// One BEGINPIC ... ENDPIC block.
/// Python calls it `EchoPicture`: `mechfem.Picture` is the picture a
/// `Mechanism`'s storage is given.
#[pyclass(module = "mechfem._core", name = "EchoPicture", frozen, eq, get_all, from_py_object)]
#[derive(Debug, Clone, PartialEq)]
pub struct Picture {
    /// Its title (may be empty).
    title: String,
    /// The line of BEGINPIC.
    line: usize,
    /// What is drawn, in deck order.
    plots: Vec<Plot>,
}

#[pymethods]
impl Picture {
    /// The picture `title` of `plots`.
    #[new]
    fn new(title: String, line: usize, plots: Vec<Plot>) -> Picture {
        Picture { title, line, plots }
    }

    /// The arguments of [`Picture::new`] that make this picture again.
    fn __getnewargs__(&self) -> (String, usize, Vec<Plot>) {
        (self.title.clone(), self.line, self.plots.clone())
    }

    fn __repr__(&self) -> String {
        format!("EchoPicture(title={:?}, line={}, plots={})", self.title, self.line, self.plots.len())
    }
}

/// What the STORAGE block asks to be done with the buffers.
/// Python calls it `EchoStorage`: `mechfem.Storage` is the storage a
/// `Mechanism` is run with.
#[pyclass(module = "mechfem._core", name = "EchoStorage", frozen, eq, get_all, from_py_object)]
#[derive(Debug, Clone, PartialEq)]
pub struct Storage {
    /// The buffers, in deck order.
    buffers: Vec<Buffer>,
    /// Buffers to tabulate in the print file (all of them for a PRINTBUF
    /// without numbers); None without PRINTBUF.
    printbuf: Option<Vec<u32>>,
    /// Buffers of the data set, in column order (empty: no data set).
    savedata: Vec<u32>,
    /// The ANIMATE name; None without one.
    animate: Option<String>,
    /// The pictures, in deck order.
    pictures: Vec<Picture>,
}

#[pymethods]
impl Storage {
    /// The storage with these requests.
    #[new]
    fn new(
        buffers: Vec<Buffer>,
        printbuf: Option<Vec<u32>>,
        savedata: Vec<u32>,
        animate: Option<String>,
        pictures: Vec<Picture>,
    ) -> Storage {
        Storage { buffers, printbuf, savedata, animate, pictures }
    }

    /// The arguments of [`Storage::new`] that make this storage again.
    #[allow(clippy::type_complexity)]
    fn __getnewargs__(&self) -> (Vec<Buffer>, Option<Vec<u32>>, Vec<u32>, Option<String>, Vec<Picture>) {
        let s = self.clone();
        (s.buffers, s.printbuf, s.savedata, s.animate, s.pictures)
    }

    fn __repr__(&self) -> String {
        format!(
            "EchoStorage(buffers={}, printbuf={:?}, savedata={:?}, animate={:?}, pictures={})",
            self.buffers.len(),
            self.printbuf,
            self.savedata,
            self.animate,
            self.pictures.len()
        )
    }

    /// This storage with the requests named changed (`buffers`, `printbuf`,
    /// `savedata`, `animate`, `pictures`); a TypeError names a key that is
    /// none of them.
    #[pyo3(signature = (**changes))]
    fn replace(&self, changes: Option<&Bound<'_, PyDict>>) -> PyResult<Storage> {
        let mut s = self.clone();
        for (key, value) in changes.into_iter().flat_map(|c| c.iter()) {
            match key.extract::<String>()?.as_str() {
                "buffers" => s.buffers = value.extract()?,
                "printbuf" => s.printbuf = value.extract()?,
                "savedata" => s.savedata = value.extract()?,
                "animate" => s.animate = value.extract()?,
                "pictures" => s.pictures = value.extract()?,
                _ => return Err(PyTypeError::new_err(key.unbind())),
            }
        }
        Ok(s)
    }

    /// The definition of buffer `number` (KeyError when there is none).
    fn buffer(&self, number: u32) -> PyResult<Buffer> {
        self.buffers.iter().find(|b| b.number == number).cloned().ok_or_else(|| PyKeyError::new_err(number))
    }
}

impl Storage {
    /// The storage requests of `c`: buffer definitions, PRINTBUF (all
    /// buffers for one without numbers), SAVEDATA, ANIMATE, the pictures.
    pub fn of(c: &Compiled) -> Storage {
        let buffers: Vec<Buffer> = c
            .buffers
            .iter()
            .map(|b| {
                let (keyword, args) = match c.band_of(b.number) {
                    // BUFTOL bsrc b fills b and b + 1 (its part 1) with the band of bsrc.
                    Some((band, _)) => ("BUFTOL", vec![i64::from(band.source), i64::from(band.buffer)]),
                    None => keyword(b.quantity),
                };
                // The buffers after the first of a keyword that fills several
                // (BUFPIN: y; BUFSHAKE: y, moment; BUFTOL: rss) say which part they are.
                let part = match (c.band_of(b.number), b.quantity) {
                    (Some((_, rss)), _) => u8::from(rss),
                    (None, Quantity::Pin { component, .. } | Quantity::Shaking(component)) => component as u8,
                    _ => 0,
                };
                Buffer {
                    number: b.number,
                    keyword: keyword.to_owned(),
                    args,
                    line: b.line,
                    name: c.label(b),
                    unit: c.unit(b),
                    part,
                }
            })
            .collect();
        let printbuf =
            c.printbuf.clone().map(|p| if p.is_empty() { buffers.iter().map(|b| b.number).collect() } else { p });
        let pictures = c
            .pictures
            .iter()
            .map(|p| Picture { title: p.title.clone(), line: p.line, plots: p.items.iter().map(Plot::of).collect() })
            .collect();
        Storage { buffers, printbuf, savedata: c.savedata.clone(), animate: c.animate.clone(), pictures }
    }
}

/// A buffer's quantity as the deck line that defines it: keyword and
/// arguments before the buffer number.
fn keyword(q: Quantity) -> (&'static str, Vec<i64>) {
    let n = |i: usize| i as i64 + 1;
    match q {
        Quantity::Input(j) => ("BUFINP", vec![n(j)]),
        Quantity::Time => ("BUFTIME", vec![]),
        Quantity::X0(i) => ("BUFX0", vec![n(i)]),
        Quantity::Kx1 { coord, j } => ("BUFKX1", vec![n(coord), n(j)]),
        Quantity::Kx2 { coord, j, m } => ("BUFKX2", vec![n(coord), n(j), n(m)]),
        Quantity::Vx(i) => ("BUFVX", vec![n(i)]),
        Quantity::Ax(i) => ("BUFAX", vec![n(i)]),
        Quantity::E0(f) => ("BUFE0", vec![dest(f)]),
        Quantity::Ke1(f, j) => ("BUFKE1", vec![dest(f), n(j)]),
        Quantity::Ke2(f, j, m) => ("BUFKE2", vec![dest(f), n(j), n(m)]),
        Quantity::Ve(f) => ("BUFVE", vec![dest(f)]),
        Quantity::Ae(f) => ("BUFAE", vec![dest(f)]),
        Quantity::Det => ("BUFDET", vec![]),
        Quantity::Sigma(r) => ("BUFSIG", vec![n(r)]),
        Quantity::Drive(j) => ("BUFDRV", vec![n(j)]),
        Quantity::Reaction(i) => ("BUFREA", vec![n(i)]),
        Quantity::Ekin => ("BUFEKIN", vec![]),
        Quantity::Epot => ("BUFEPOT", vec![]),
        Quantity::Power => ("BUFPOW", vec![]),
        // No deck buffer records it: a deck's run has it in its `loadpow` block.
        Quantity::LoadPower => ("", vec![]),
        Quantity::Mred(j, m) => ("BUFMRED", vec![n(j), n(m)]),
        Quantity::Transmission(a, b) => ("BUFTRA", vec![n(a), n(b)]),
        Quantity::Pin { element, x, y, .. } => ("BUFPIN", vec![n(element), n(x), n(y)]),
        Quantity::Shaking(_) => ("BUFSHAKE", vec![]),
    }
}
