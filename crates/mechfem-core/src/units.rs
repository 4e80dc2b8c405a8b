//! Units: the scale of each kind of quantity between a model's own numbers
//! and the core's.
//!
//! The core computes in one consistent system: metres, radians, kilograms,
//! newtons and seconds (SI), or, for a model that declares no unit of a
//! kind, that kind's numbers as they are. A model declares its units
//! ([`Units`], a deck's `UNITS LENGTH mm ANGLE deg ...` line); every number
//! it gives is multiplied by the scale of its [`Dim`] when it is read, and
//! every number handed out is divided by it at the edge. The scales are
//! pure factors (no offsets), so results agree with the same model written
//! in SI to rounding, and a model without units is computed bit for bit as
//! its numbers say.
//!
//! A quantity's kind is a [`Dim`]: its exponents of length, angle, mass,
//! force and time. A torque is force x length (an angle does not count in
//! a generalised force: it is work per radian), an inertia mass x length²,
//! a transfer function the quantity's dimension over the input's
//! ([`Dim::symbol`] writes `mm/deg`, and `-` for deg/deg).

use std::f64::consts::PI;
use std::fmt::Write as _;

use crate::dynamics::Component;
use crate::elements::Dimension;
use crate::model::{FormRef, Mechanism, Term};
use crate::run::Quantity;

macro_rules! unit_enum {
    ($(#[$doc:meta])* $name:ident { $($(#[$vdoc:meta])* $variant:ident $symbol:literal $scale:expr, $per:expr;)* }) => {
        $(#[$doc])*
        #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
        pub enum $name {
            $($(#[$vdoc])* $variant,)*
        }

        impl $name {
            /// Every unit of the kind, in the order of the deck reference.
            pub const ALL: &'static [$name] = &[$($name::$variant,)*];

            /// The unit as written (`mm`, `deg`).
            pub fn symbol(self) -> &'static str {
                match self { $($name::$variant => $symbol,)* }
            }

            /// How many of the core's units one of these is.
            pub fn scale(self) -> f64 {
                match self { $($name::$variant => $scale,)* }
            }

            /// How many of these one of the core's units is (`1 / scale`,
            /// written exactly where it is a round number: 1000 mm in a m).
            pub fn per_core(self) -> f64 {
                match self { $($name::$variant => $per,)* }
            }

            /// The unit written `symbol` (exactly as in the table: `mm`, `kN`).
            pub fn from_symbol(symbol: &str) -> Option<$name> {
                $name::ALL.iter().copied().find(|u| u.symbol() == symbol)
            }
        }
    };
}

unit_enum! {
    /// A unit of length.
    Length {
        /// Metre.
        M "m" 1.0, 1.0;
        /// Millimetre.
        Mm "mm" 1e-3, 1e3;
        /// Centimetre.
        Cm "cm" 1e-2, 1e2;
        /// Inch.
        In "in" 0.0254, 1.0 / 0.0254;
    }
}

unit_enum! {
    /// A unit of angle.
    Angle {
        /// Radian.
        Rad "rad" 1.0, 1.0;
        /// Degree.
        Deg "deg" PI / 180.0, 180.0 / PI;
    }
}

unit_enum! {
    /// A unit of mass.
    Mass {
        /// Kilogram.
        Kg "kg" 1.0, 1.0;
        /// Gram.
        G "g" 1e-3, 1e3;
    }
}

unit_enum! {
    /// A unit of force.
    Force {
        /// Newton.
        N "N" 1.0, 1.0;
        /// Kilonewton.
        KN "kN" 1e3, 1e-3;
    }
}

unit_enum! {
    /// A unit of time.
    Time {
        /// Second.
        S "s" 1.0, 1.0;
        /// Millisecond.
        Ms "ms" 1e-3, 1e3;
    }
}

/// The units a model declares. `declared` is false for a model that
/// declares none (a deck without a UNITS line): then every number is the
/// core's own and no unit is shown. With `declared`, an angle is in radians
/// and time in seconds unless said otherwise; a length, mass or force
/// without a unit is taken as it is, and shown without a unit.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct Units {
    /// Whether the model declares units at all.
    pub declared: bool,
    /// The unit of length, if declared.
    pub length: Option<Length>,
    /// The unit of angle, if declared (radians otherwise).
    pub angle: Option<Angle>,
    /// The unit of mass, if declared.
    pub mass: Option<Mass>,
    /// The unit of force, if declared.
    pub force: Option<Force>,
    /// The unit of time, if declared (seconds otherwise).
    pub time: Option<Time>,
}

/// The five base kinds, in the order of [`Dim`]'s exponents.
const KINDS: usize = 5;

impl Units {
    /// No units: every number is the core's own.
    pub const NONE: Units = Units { declared: false, length: None, angle: None, mass: None, force: None, time: None };

    /// Whether every scale is 1: numbers pass unchanged (a model without
    /// units, or one in SI).
    pub fn is_identity(&self) -> bool {
        self.scales().iter().all(|&s| s == 1.0)
    }

    /// The scale of each base kind: length, angle, mass, force, time.
    fn scales(&self) -> [f64; KINDS] {
        [
            self.length.map_or(1.0, Length::scale),
            self.angle.map_or(1.0, Angle::scale),
            self.mass.map_or(1.0, Mass::scale),
            self.force.map_or(1.0, Force::scale),
            self.time.map_or(1.0, Time::scale),
        ]
    }

    /// The inverse scale of each base kind.
    fn per_core(&self) -> [f64; KINDS] {
        [
            self.length.map_or(1.0, Length::per_core),
            self.angle.map_or(1.0, Angle::per_core),
            self.mass.map_or(1.0, Mass::per_core),
            self.force.map_or(1.0, Force::per_core),
            self.time.map_or(1.0, Time::per_core),
        ]
    }

    /// The symbol of each base kind; `None` where it is not shown (no
    /// units declared, or a length, mass or force without a unit).
    fn symbols(&self) -> [Option<&'static str>; KINDS] {
        if !self.declared {
            return [None; KINDS];
        }
        [
            self.length.map(Length::symbol),
            Some(self.angle.unwrap_or(Angle::Rad).symbol()),
            self.mass.map(Mass::symbol),
            self.force.map(Force::symbol),
            Some(self.time.unwrap_or(Time::S).symbol()),
        ]
    }

    /// The symbol of each base kind as a model's units shows it, by name:
    /// `length`, `angle`, `mass`, `force`, `time` (`None`: not declared; an
    /// angle and time have their defaults once any unit is declared).
    pub fn fields(&self) -> [(&'static str, Option<&'static str>); KINDS] {
        let s = self.symbols();
        [("length", s[0]), ("angle", s[1]), ("mass", s[2]), ("force", s[3]), ("time", s[4])]
    }

    /// `value` given in `dim`'s units, in the core's.
    pub fn to_core(&self, dim: Dim, value: f64) -> f64 {
        let s = dim.scale(self);
        if s == 1.0 {
            value
        } else {
            value * s
        }
    }

    /// `value` in the core's units, in `dim`'s units of the model.
    pub fn from_core(&self, dim: Dim, value: f64) -> f64 {
        let s = dim.out_scale(self);
        if s == 1.0 {
            value
        } else {
            value * s
        }
    }

    /// `value`, a number of the core that a model gave in `dim`'s units
    /// ([`Units::to_core`]), as the model gave it. [`Units::from_core`] can
    /// miss the given number by an ulp (26.252 mm is 0.026252 m, and that
    /// times 1000 is 26.252000000000002), so that a model written and read
    /// again would drift: of the numbers a few ulps around it that
    /// [`Units::to_core`] takes to `value`, this is the one with the fewest
    /// decimal digits (the nearest of those). Every such number is the same
    /// number to the core.
    pub fn as_written(&self, dim: Dim, value: f64) -> f64 {
        let back = self.from_core(dim, value);
        if dim.scale(self) == 1.0 || !back.is_finite() {
            return back;
        }
        let digits = |v: f64| format!("{v:e}").len();
        let (mut best, mut best_digits) = (None, usize::MAX);
        // Nearest first, so that among equally short numbers the nearest wins.
        let (mut up, mut down) = (back, back);
        for k in 0..=WRITTEN_ULPS {
            let candidates = if k == 0 { [Some(back), None] } else { [Some(up), Some(down)] };
            for v in candidates.into_iter().flatten() {
                if self.to_core(dim, v) == value && digits(v) < best_digits {
                    (best, best_digits) = (Some(v), digits(v));
                }
            }
            (up, down) = (up.next_up(), down.next_down());
        }
        best.unwrap_or(back)
    }
}

/// How many ulps around the converted number [`Units::as_written`] looks
/// for the given one (a conversion there and back is off by one or two).
const WRITTEN_ULPS: usize = 4;

/// The kind of a quantity: its exponents of length, angle, mass, force and
/// time, and whether it is work (an energy). Work and a torque have the same
/// exponents (force x length; the radian a torque is per does not count),
/// but work is shown in joules (`J`, `mJ`) and a torque in `N·m`, `N·mm`:
/// the second field tells them apart.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct Dim(pub [i8; KINDS], pub bool);

impl Dim {
    /// A pure number.
    pub const NONE: Dim = Dim([0; KINDS], false);
    /// A length.
    pub const LENGTH: Dim = Dim([1, 0, 0, 0, 0], false);
    /// An angle.
    pub const ANGLE: Dim = Dim([0, 1, 0, 0, 0], false);
    /// A mass.
    pub const MASS: Dim = Dim([0, 0, 1, 0, 0], false);
    /// A force.
    pub const FORCE: Dim = Dim([0, 0, 0, 1, 0], false);
    /// A time.
    pub const TIME: Dim = Dim([0, 0, 0, 0, 1], false);
    /// Work, an energy (force x length).
    pub const ENERGY: Dim = Dim([1, 0, 0, 1, 0], true);
    /// A torque (force x length, per radian).
    pub const TORQUE: Dim = Dim([1, 0, 0, 1, 0], false);
    /// A moment of inertia (mass x length²).
    pub const INERTIA: Dim = Dim([2, 0, 1, 0, 0], false);
    /// A power (force x length / time).
    pub const POWER: Dim = Dim([1, 0, 0, 1, -1], false);

    /// The kind of a catalogue dimension (`Any` taken as a length).
    pub fn of(d: Dimension) -> Dim {
        match d {
            Dimension::Length | Dimension::Any => Dim::LENGTH,
            Dimension::Angle => Dim::ANGLE,
            Dimension::Ratio => Dim::NONE,
        }
    }

    /// `self x other`.
    pub fn times(self, other: Dim) -> Dim {
        Dim(std::array::from_fn(|k| self.0[k] + other.0[k]), false)
    }

    /// `self / other`.
    pub fn over(self, other: Dim) -> Dim {
        Dim(std::array::from_fn(|k| self.0[k] - other.0[k]), false)
    }

    /// `self` to the power `n`.
    pub fn pow(self, n: i8) -> Dim {
        Dim(self.0.map(|e| e * n), self.1 && n == 1)
    }

    /// `self` without its angle: what a generalised force divides work by.
    fn without_angle(self) -> Dim {
        let mut d = self;
        d.0[1] = 0;
        d
    }

    /// The generalised force on a quantity of this kind: work over it, an
    /// angle not counted (force on a length, torque force x length on an
    /// angle, energy on a pure number).
    pub fn generalised_force(self) -> Dim {
        Dim::ENERGY.over(self.without_angle())
    }

    /// How many of the core's units one of this kind in `units` is.
    pub fn scale(self, units: &Units) -> f64 {
        product(self, units.scales())
    }

    /// How many of this kind in `units` one of the core's units is: what a
    /// number of the core is multiplied by to be given in `units`.
    pub fn out_scale(self, units: &Units) -> f64 {
        product(self, units.per_core())
    }

    /// The unit as shown: `mm`, `deg/s`, `N·mm`, `kg·mm²`, `mm/deg`, `-`
    /// for a pure number; "" when `units` declares none, or not every base
    /// unit the kind needs.
    pub fn symbol(self, units: &Units) -> String {
        let symbols = units.symbols();
        if !units.declared || self.0.iter().zip(&symbols).any(|(&e, s)| e != 0 && s.is_none()) {
            return String::new();
        }
        if self == Dim::POWER {
            if let Some(watt) = watts(self.scale(units)) {
                return watt.to_string();
            }
        }
        if self == Dim::ENERGY {
            if let Some(joule) = joules(self.scale(units)) {
                return joule.to_string();
            }
        }
        let part = |positive: bool| {
            let mut out = String::new();
            // Force and mass first, as in N·mm and kg·mm².
            for k in [3, 2, 0, 1, 4] {
                let (e, s) = (self.0[k], symbols[k]);
                let n = if positive { e } else { -e };
                if n <= 0 {
                    continue;
                }
                if !out.is_empty() {
                    out.push('·');
                }
                out.push_str(s.unwrap_or(""));
                match n {
                    1 => {}
                    2 => out.push('²'),
                    3 => out.push('³'),
                    _ => {
                        let _ = write!(out, "^{n}");
                    }
                }
            }
            out
        };
        let (num, den) = (part(true), part(false));
        match (num.is_empty(), den.is_empty()) {
            (true, true) => "-".to_string(),
            (false, true) => num,
            (true, false) => format!("1/{den}"),
            (false, false) if den.contains('·') => format!("{num}/({den})"),
            (false, false) => format!("{num}/{den}"),
        }
    }
}

/// A power whose unit is `size` watts, by the watt's name where `size` is
/// one of its decimal multiples (N·m/s and N·mm/ms are `W`, N·mm/s is
/// `mW`); `None` for any other size (N·in/s keeps its compound symbol).
fn watts(size: f64) -> Option<&'static str> {
    [(1e-6, "µW"), (1e-3, "mW"), (1.0, "W"), (1e3, "kW"), (1e6, "MW")]
        .into_iter()
        .find(|&(w, _)| (size - w).abs() <= 1e-12 * w)
        .map(|(_, name)| name)
}

/// Work whose unit is `size` joules, by the joule's name where `size` is one
/// of its decimal multiples (N·m and kN·mm are `J`, N·mm is `mJ`); `None`
/// for any other size (N·cm, N·in keep their compound symbol).
fn joules(size: f64) -> Option<&'static str> {
    [(1e-3, "mJ"), (1.0, "J"), (1e3, "kJ")]
        .into_iter()
        .find(|&(w, _)| (size - w).abs() <= 1e-12 * w)
        .map(|(_, name)| name)
}

impl Dim {
    /// The unit as an axis or a sentence shows it: [`Dim::symbol`] in
    /// `units`; a model that declares no units shows its angles in radians
    /// and time in seconds (the core's own), and nothing for a kind that
    /// needs a length, mass or force (their numbers are as the model gives
    /// them, in no unit mechfem knows).
    pub fn shown(self, units: &Units) -> String {
        if units.declared {
            self.symbol(units)
        } else {
            self.symbol(&Units { declared: true, ..Units::NONE })
        }
    }
}

/// The product of the base factors `s` raised to the exponents of `dim`.
fn product(dim: Dim, s: [f64; KINDS]) -> f64 {
    let mut out = 1.0;
    for (k, &e) in dim.0.iter().enumerate() {
        if e != 0 && s[k] != 1.0 {
            out *= s[k].powi(i32::from(e));
        }
    }
    out
}

/// The kinds of a model's co-ordinates and rows, from its elements: what
/// each number of the model measures.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct ModelDims {
    /// Co-ordinates 0..N.
    pub coords: Vec<Dim>,
    /// Prescribed rows 0..n_p.
    pub prescribed: Vec<Dim>,
    /// Dependent form parameters 0..n_d.
    pub dependent: Vec<Dim>,
}

impl ModelDims {
    /// The kinds of `mech`'s co-ordinates and rows. A co-ordinate takes the
    /// dimension the first element that says one gives it (a length when
    /// none does); a row that of its terms with factor ±1 when they agree,
    /// else that of its first term (a factor carries the difference).
    pub fn of(mech: &Mechanism) -> ModelDims {
        let mut coords: Vec<Option<Dim>> = vec![None; mech.n_coords()];
        for e in mech.elements() {
            for (&i, &d) in e.coords().iter().zip(e.ty.coord_dimensions()) {
                if d != Dimension::Any && coords[i].is_none() {
                    coords[i] = Some(Dim::of(d));
                }
            }
        }
        let coords: Vec<Dim> = coords.into_iter().map(|d| d.unwrap_or(Dim::LENGTH)).collect();
        let form = |t: &Term| {
            let e = &mech.elements()[t.element];
            match e.ty.form_dimensions().get(t.form) {
                Some(Dimension::Any) => e.coords().first().map_or(Dim::LENGTH, |&i| coords[i]),
                Some(&d) => Dim::of(d),
                None => Dim::NONE,
            }
        };
        let row = |terms: &[Term]| {
            let plain: Vec<Dim> = terms.iter().filter(|t| t.factor.abs() == 1.0).map(form).collect();
            match plain.first() {
                Some(&d) if plain.iter().all(|&p| p == d) => d,
                _ => terms.first().map_or(Dim::NONE, form),
            }
        };
        ModelDims {
            prescribed: (0..mech.n_prescribed()).map(|r| row(mech.prescribed_terms(r))).collect(),
            dependent: (0..mech.n_dependent()).map(|d| row(mech.dependent_terms(d))).collect(),
            coords,
        }
    }

    /// The kind of a row.
    pub fn form(&self, f: FormRef) -> Dim {
        match f {
            FormRef::Prescribed(r) => self.prescribed.get(r),
            FormRef::Dependent(d) => self.dependent.get(d),
        }
        .copied()
        .unwrap_or(Dim::NONE)
    }

    /// The kind of a co-ordinate.
    pub fn coord(&self, i: usize) -> Dim {
        self.coords.get(i).copied().unwrap_or(Dim::LENGTH)
    }

    /// The kind of input j (that of its row).
    pub fn input(&self, mech: &Mechanism, j: usize) -> Dim {
        self.prescribed.get(mech.input_row(j)).copied().unwrap_or(Dim::NONE)
    }

    /// The kind of what a buffer records.
    pub fn quantity(&self, mech: &Mechanism, q: Quantity) -> Dim {
        let input = |j: usize| self.input(mech, j);
        let per_time = |d: Dim, n: i8| d.over(Dim::TIME.pow(n));
        match q {
            Quantity::Input(j) => input(j),
            Quantity::Time => Dim::TIME,
            Quantity::X0(i) => self.coord(i),
            Quantity::Kx1 { coord, j } => self.coord(coord).over(input(j)),
            Quantity::Kx2 { coord, j, m } => self.coord(coord).over(input(j)).over(input(m)),
            Quantity::Vx(i) => per_time(self.coord(i), 1),
            Quantity::Ax(i) => per_time(self.coord(i), 2),
            Quantity::E0(f) => self.form(f),
            Quantity::Ke1(f, j) => self.form(f).over(input(j)),
            Quantity::Ke2(f, j, m) => self.form(f).over(input(j)).over(input(m)),
            Quantity::Ve(f) => per_time(self.form(f), 1),
            Quantity::Ae(f) => per_time(self.form(f), 2),
            Quantity::Det => self.det(mech),
            Quantity::Sigma(r) => self.form(FormRef::Prescribed(r)).generalised_force(),
            Quantity::Drive(j) => input(j).generalised_force(),
            Quantity::Reaction(i) => self.coord(i).generalised_force(),
            Quantity::Ekin | Quantity::Epot => Dim::ENERGY,
            Quantity::Power | Quantity::LoadPower => Dim::ENERGY.over(Dim::TIME),
            Quantity::Mred(j, m) => {
                // Mass times one length for each input that is not a length.
                let lengths = 2 - input(j).0[0] - input(m).0[0];
                Dim::MASS.times(Dim::LENGTH.pow(lengths))
            }
            Quantity::Transmission(..) => Dim::ANGLE,
            Quantity::Pin { x, .. } => self.coord(x).generalised_force(),
            Quantity::Shaking(Component::Moment) => Dim::ANGLE.generalised_force(),
            Quantity::Shaking(_) => Dim::LENGTH.generalised_force(),
        }
    }

    /// The kind of det(D^c): the rows' over the moving co-ordinates'.
    pub fn det(&self, mech: &Mechanism) -> Dim {
        let rows = self.prescribed.iter().fold(Dim::NONE, |a, &d| a.times(d));
        mech.moving_coords().iter().fold(rows, |a, &i| a.over(self.coord(i)))
    }
}

#[cfg(test)]
mod tests;
