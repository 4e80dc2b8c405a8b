//! Names: what a designer calls the numbers of a model (`C` for the point
//! of co-ordinates 9 and 10, `psi` for dependent form parameter 1, `phi`
//! for prescribed row 13), kept beside the model so that every output can
//! say them, and the labels of the buffers made from them.
//!
//! A buffer is labelled by its explicit label if it has one, else from the
//! names of what it records (`psi`, `dpsi/dphi`, `C.x`, `vC.x`), else as
//! the deck's numbers say (`x9`, `ANGB(8)`, `dANGB(3)/dinput1`).

use std::collections::BTreeMap;

use crate::model::{FormRef, Mechanism, Term};
use crate::run::Quantity;

/// The names of a model's things, by 0-based index; `None` where a thing
/// has no name.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct Names {
    /// Co-ordinates 0..N: `C.x` and `C.y` for the co-ordinates of a point
    /// `C`, `s` for a single co-ordinate named `s`.
    pub coordinates: Vec<Option<String>>,
    /// The named points: the co-ordinates of x and y (0-based) and the name.
    pub points: Vec<(usize, usize, String)>,
    /// Elements 0..n_e.
    pub elements: Vec<Option<String>>,
    /// Prescribed rows 0..n_p.
    pub prescribed: Vec<Option<String>>,
    /// Dependent form parameters 0..n_d.
    pub dependent: Vec<Option<String>>,
    /// Explicit labels of buffers, by buffer number.
    pub buffers: BTreeMap<u32, String>,
}

fn get(names: &[Option<String>], k: usize) -> Option<&str> {
    names.get(k).and_then(Option::as_deref)
}

impl Names {
    /// No names, for a model of `n` co-ordinates, `e` elements, `p`
    /// prescribed rows and `d` dependent form parameters.
    pub fn empty(n: usize, e: usize, p: usize, d: usize) -> Names {
        Names {
            coordinates: vec![None; n],
            points: Vec::new(),
            elements: vec![None; e],
            prescribed: vec![None; p],
            dependent: vec![None; d],
            buffers: BTreeMap::new(),
        }
    }

    /// Whether no thing has a name and no buffer a label.
    pub fn is_empty(&self) -> bool {
        let none = |v: &[Option<String>]| v.iter().all(Option::is_none);
        none(&self.coordinates)
            && none(&self.elements)
            && none(&self.prescribed)
            && none(&self.dependent)
            && self.points.is_empty()
            && self.buffers.is_empty()
    }

    /// The explicit label of buffer `number`, if any.
    pub fn buffer(&self, number: u32) -> Option<&str> {
        self.buffers.get(&number).map(String::as_str)
    }

    /// Co-ordinate i by name: its name, else `x<i+1>`.
    pub fn coordinate(&self, i: usize) -> String {
        get(&self.coordinates, i).map_or_else(|| format!("x{}", i + 1), str::to_string)
    }

    /// A row by name: its name, else its formula (`ANGB(8)`, `ANGB(2)-ANGB(4)`).
    pub fn row(&self, mech: &Mechanism, f: FormRef) -> String {
        let (name, terms) = match f {
            FormRef::Prescribed(r) if r < mech.n_prescribed() => (get(&self.prescribed, r), mech.prescribed_terms(r)),
            FormRef::Dependent(d) if d < mech.n_dependent() => (get(&self.dependent, d), mech.dependent_terms(d)),
            FormRef::Prescribed(r) => return format!("eps({})", r + 1),
            FormRef::Dependent(d) => return format!("eps(-{})", d + 1),
        };
        name.map_or_else(|| formula(mech, terms), str::to_string)
    }

    /// Element e by name: its name, else its deck number.
    pub fn element(&self, e: usize) -> String {
        get(&self.elements, e).map_or_else(|| (e + 1).to_string(), str::to_string)
    }

    /// The point of co-ordinates `x`, `y` by name: its name, else `x<x+1>,x<y+1>`.
    pub fn point(&self, x: usize, y: usize) -> String {
        let named = self.points.iter().find(|p| p.0 == x && p.1 == y);
        named.map_or_else(|| format!("{},{}", self.coordinate(x), self.coordinate(y)), |p| p.2.clone())
    }

    /// Input j in a derivative: its row's name, else `input<j+1>`.
    pub fn input(&self, mech: &Mechanism, j: usize) -> String {
        let r = (j < mech.n_dof()).then(|| mech.input_row(j));
        r.and_then(|r| get(&self.prescribed, r)).map_or_else(|| format!("input{}", j + 1), str::to_string)
    }

    /// Input j as a quantity: its row by name (name or formula).
    pub fn input_value(&self, mech: &Mechanism, j: usize) -> String {
        if j < mech.n_dof() {
            self.row(mech, FormRef::Prescribed(mech.input_row(j)))
        } else {
            format!("input{}", j + 1)
        }
    }

    /// The label of buffer `number` recording `q`: its explicit label,
    /// else made from the names of what it records.
    pub fn label(&self, mech: &Mechanism, number: u32, q: Quantity) -> String {
        if let Some(label) = self.buffer(number) {
            return label.to_string();
        }
        let d1 = |what: String, j: usize| format!("d{}/d{}", wrapped(&what), self.input(mech, j));
        let d2 = |what: String, j: usize, m: usize| {
            let what = wrapped(&what);
            if j == m {
                format!("d2{what}/d{}^2", self.input(mech, j))
            } else {
                format!("d2{what}/d{}d{}", self.input(mech, j), self.input(mech, m))
            }
        };
        match q {
            Quantity::Input(j) => self.input_value(mech, j),
            Quantity::Time => "time".to_string(),
            Quantity::X0(i) => self.coordinate(i),
            Quantity::Kx1 { coord, j } => d1(self.coordinate(coord), j),
            Quantity::Kx2 { coord, j, m } => d2(self.coordinate(coord), j, m),
            Quantity::Vx(i) => format!("v{}", wrapped(&self.coordinate(i))),
            Quantity::Ax(i) => format!("a{}", wrapped(&self.coordinate(i))),
            Quantity::E0(f) => self.row(mech, f),
            Quantity::Ke1(f, j) => d1(self.row(mech, f), j),
            Quantity::Ke2(f, j, m) => d2(self.row(mech, f), j, m),
            Quantity::Ve(f) => format!("v{}", wrapped(&self.row(mech, f))),
            Quantity::Ae(f) => format!("a{}", wrapped(&self.row(mech, f))),
            Quantity::Det => "det(D^c)".to_string(),
            Quantity::Sigma(r) => format!("sigma({})", self.row(mech, FormRef::Prescribed(r))),
            Quantity::Drive(j) => format!("drive({})", self.input_value(mech, j)),
            Quantity::Reaction(i) => format!("reaction({})", self.coordinate(i)),
            Quantity::Ekin => "Ekin".to_string(),
            Quantity::Epot => "Epot".to_string(),
            Quantity::Power => "power".to_string(),
            Quantity::LoadPower => "load power".to_string(),
            Quantity::Mred(j, m) => {
                let named = |j: usize| {
                    (j < mech.n_dof()).then(|| mech.input_row(j)).and_then(|r| get(&self.prescribed, r)).is_some()
                };
                if named(j) || named(m) {
                    format!("M({},{})", self.input(mech, j), self.input(mech, m))
                } else {
                    format!("M({},{})", j + 1, m + 1)
                }
            }
            Quantity::Transmission(a, b) => format!("mu({},{})", self.element(a), self.element(b)),
            Quantity::Pin { element, x, y, component } => {
                format!("pin({},{}){}", self.element(element), self.point(x, y), component.suffix())
            }
            Quantity::Shaking(c) => format!("shaking{}", c.suffix()),
        }
    }
}

/// A row's formula without blanks: `ANGB(2)-ANGB(4)`, `2*LENL(1)+ANGB(3)`.
fn formula(mech: &Mechanism, terms: &[Term]) -> String {
    let mut out = String::new();
    for (k, t) in terms.iter().enumerate() {
        let ty = mech.elements().get(t.element).map(|e| e.ty);
        let form = ty.and_then(|ty| ty.form_names().get(t.form)).copied().unwrap_or("FORM");
        let mag = t.factor.abs();
        let text = if mag == 1.0 {
            format!("{form}({})", t.element + 1)
        } else {
            format!("{}*{form}({})", general(mag), t.element + 1)
        };
        if k == 0 {
            out.push_str(if t.factor < 0.0 { "-" } else { "" });
        } else {
            out.push(if t.factor < 0.0 { '-' } else { '+' });
        }
        out.push_str(&text);
    }
    out
}

/// `name` bracketed when an operator in it would make a derivative's name
/// ambiguous.
fn wrapped(name: &str) -> String {
    let inner = name.get(1..).unwrap_or("");
    if name.starts_with('-') || inner.contains(['+', '-', '*', '/', ' ']) {
        format!("({name})")
    } else {
        name.to_string()
    }
}

/// `x` with six significant digits, trailing zeros dropped, in exponent
/// form below 1e-4 and from 1e6 (C's and Python's `%g`).
fn general(x: f64) -> String {
    if x == 0.0 || !x.is_finite() {
        return format!("{x}");
    }
    let sci = format!("{x:.5e}");
    let (mantissa, exp) = sci.split_once('e').unwrap_or((&sci, "0"));
    let exp: i32 = exp.parse().unwrap_or(0);
    let trim = |s: String| {
        if s.contains('.') {
            s.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            s
        }
    };
    if (-4..6).contains(&exp) {
        let decimals = usize::try_from(5 - exp).unwrap_or(0);
        trim(format!("{x:.decimals$}"))
    } else {
        let sign = if exp < 0 { '-' } else { '+' };
        format!("{}e{sign}{:02}", trim(mantissa.to_string()), exp.abs())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::elements::ElementType;
    use crate::model::MechanismBuilder;

    /// A crank (element 1, BIN 1 2 3 4) with a second bar (element 2, BIN
    /// 3 4 5 6): rows LENL(1), ANGB(1), LENL(2), ANGB(2) - ANGB(1) (the
    /// input is row 2), dependent 2*LENL(1).
    fn crank() -> Mechanism {
        let mut b = MechanismBuilder::new();
        let c: Vec<usize> = [0.0, 0.0].iter().map(|&v| b.fixed(v)).collect();
        let m: Vec<usize> = [1.0, 0.0, 2.0, 0.0].iter().map(|&v| b.moving(v)).collect();
        let bin = ElementType::from_name("BIN").unwrap();
        let e1 = b.element(bin, &[c[0], c[1], m[0], m[1]]);
        let e2 = b.element(bin, &[m[0], m[1], m[2], m[3]]);
        let (lenl, angb) = (bin.form_index("LENL").unwrap(), bin.form_index("ANGB").unwrap());
        b.prescribe(&[Term::new(e1, lenl)]);
        b.input(&[Term::new(e1, angb)]);
        b.prescribe(&[Term::new(e2, lenl)]);
        b.prescribe(&[Term::new(e2, angb), Term::scaled(e1, angb, -1.0)]);
        b.dependent(&[Term::scaled(e1, lenl, 2.0)]);
        b.build().unwrap().0
    }

    #[test]
    fn buffers_without_names_keep_the_decks_numbers() {
        let mech = crank();
        let n = Names::empty(6, 2, 4, 1);
        let (phi, last) = (mech.input_row(0), (0..4).find(|&r| mech.prescribed_terms(r).len() == 2).unwrap());
        assert_eq!(n.label(&mech, 1, Quantity::X0(4)), "x5");
        assert_eq!(n.label(&mech, 1, Quantity::E0(FormRef::Prescribed(phi))), "ANGB(1)");
        assert_eq!(n.label(&mech, 1, Quantity::Ke1(FormRef::Prescribed(last), 0)), "d(ANGB(2)-ANGB(1))/dinput1");
        assert_eq!(n.label(&mech, 1, Quantity::E0(FormRef::Dependent(0))), "2*LENL(1)");
        assert_eq!(n.label(&mech, 1, Quantity::Kx2 { coord: 2, j: 0, m: 0 }), "d2x3/dinput1^2");
        assert_eq!(n.label(&mech, 1, Quantity::Vx(3)), "vx4");
        assert_eq!(n.label(&mech, 1, Quantity::Input(0)), "ANGB(1)");
        assert_eq!(n.label(&mech, 1, Quantity::Drive(0)), "drive(ANGB(1))");
        assert_eq!(n.label(&mech, 1, Quantity::Mred(0, 0)), "M(1,1)");
        assert_eq!(n.label(&mech, 1, Quantity::Det), "det(D^c)");
    }

    #[test]
    fn buffers_are_labelled_from_names_and_explicit_labels_win() {
        let mech = crank();
        let mut n = Names::empty(6, 2, 4, 1);
        n.coordinates[4] = Some("B.x".into());
        n.coordinates[5] = Some("B.y".into());
        n.prescribed[mech.input_row(0)] = Some("phi".into());
        n.dependent[0] = Some("psi".into());
        n.buffers.insert(7, "the tip's height".into());
        assert_eq!(n.label(&mech, 1, Quantity::E0(FormRef::Dependent(0))), "psi");
        assert_eq!(n.label(&mech, 1, Quantity::Ke1(FormRef::Dependent(0), 0)), "dpsi/dphi");
        assert_eq!(n.label(&mech, 1, Quantity::Ke2(FormRef::Dependent(0), 0, 0)), "d2psi/dphi^2");
        assert_eq!(n.label(&mech, 1, Quantity::X0(4)), "B.x");
        assert_eq!(n.label(&mech, 1, Quantity::Ax(5)), "aB.y");
        assert_eq!(n.label(&mech, 1, Quantity::Kx1 { coord: 2, j: 0 }), "dx3/dphi");
        assert_eq!(n.label(&mech, 1, Quantity::Input(0)), "phi");
        assert_eq!(n.label(&mech, 1, Quantity::Mred(0, 0)), "M(phi,phi)");
        assert_eq!(n.label(&mech, 7, Quantity::X0(5)), "the tip's height");
    }

    #[test]
    fn factors_are_written_as_percent_g() {
        assert_eq!(general(2.0), "2");
        assert_eq!(general(0.5), "0.5");
        assert_eq!(general(1.0 / 3.0), "0.333333");
        assert_eq!(general(123456.7), "123457");
        assert_eq!(general(1234567.0), "1.23457e+06");
        assert_eq!(general(0.00001), "1e-05");
    }
}
