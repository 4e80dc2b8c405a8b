//! The deck generator: plausible decks from a stream of choices, with a
//! dose of hostility that the first choice sets.

use mechfem_core::ElementType;

mod blocks;

/// A stream of choices. Choice 0 is always the plainest option, so that a
/// stream of zeros (what shrinking heads for) gives a plain deck.
pub trait Choose {
    /// A number in `0..n` (0 when `n` is 0 or the stream is used up).
    fn below(&mut self, n: usize) -> usize;

    /// `true` with probability about `percent` / 100.
    fn chance(&mut self, percent: usize) -> bool {
        self.below(100) >= 100 - percent.min(100)
    }

    /// One of `items` (which must not be empty).
    fn pick<'a>(&mut self, items: &[&'a str]) -> &'a str {
        items[self.below(items.len())]
    }
}

/// Choices read from a byte string, one or two bytes each; zeros once it
/// is used up.
pub struct Bytes<'a> {
    data: &'a [u8],
    at: usize,
}

impl<'a> Bytes<'a> {
    /// Choices from `data`.
    pub fn new(data: &'a [u8]) -> Self {
        Bytes { data, at: 0 }
    }

    fn byte(&mut self) -> usize {
        let b = self.data.get(self.at).copied().unwrap_or(0);
        self.at += 1;
        usize::from(b)
    }
}

impl Choose for Bytes<'_> {
    fn below(&mut self, n: usize) -> usize {
        match n {
            0 | 1 => 0,
            2..=256 => self.byte() % n,
            _ => (self.byte() << 8 | self.byte()) % n,
        }
    }
}

/// Tokens that are numbers to a human but not all to the lexer.
const ODD_NUMBERS: &[&str] = &[
    "nan", "NaN", "inf", "-inf", "1e999", "-1D999", "1e", ".", "-", "+", "1.5.5", "0x10", "1,5", "--1", "1e-",
    "Infinity",
];
/// Whole numbers at and beyond the limits of i64, u32 and f64's integers.
const HUGE_INTEGERS: &[&str] = &[
    "4294967295",
    "4294967296",
    "9007199254740993",
    "9223372036854775807",
    "-9223372036854775808",
    "9223372036854775808",
    "18446744073709551616",
    "99999999999999999999999",
];
/// Finite reals at the ends of f64's range.
const EXTREME_REALS: &[&str] =
    &["1e308", "-1e308", "1.7976931348623157e308", "1D300", "1e-308", "-1e-308", "5e-324", "1d-300", "1e154", "1e-154"];
/// Words that are keywords, element types or form names.
const WORDS: &[&str] = &[
    "KIN",
    "ANA",
    "DYN",
    "TOPOLOGY",
    "GEOMETRY",
    "MOVEMENT",
    "STORAGE",
    "END",
    "ELEM",
    "FORM",
    "NRDOF",
    "XFIX",
    "XMOV",
    "PARA",
    "TSTEPE",
    "MOV_RELE",
    "MOV_ABSE",
    "MOV_FUNC",
    "MOV_FREE",
    "ACCURACY",
    "MAXITER",
    "BUFINP",
    "BUFTIME",
    "BUFX0",
    "BUFKX2",
    "BUFAE",
    "BUFDET",
    "PRINTBUF",
    "SAVEDATA",
    "ANIMATE",
    "BEGINPIC",
    "ENDPIC",
    "PLOTFUNC",
    "PLOTHODO",
    "BIN",
    "TR2",
    "GR1",
    "BLT",
    "CRD",
    "LENL",
    "ANGB",
    "GEAR",
    "BELT",
    "COOR",
    ";",
    "\t",
    "Ä",
    "\u{0}",
    "\r",
    "DYNAMICS",
    "MASS",
    "PMASS",
    "GRAVITY",
    "LOADFUNC",
    "SPRING",
    "MOTOR",
    "BUFSIG",
    "BUFREA",
    "BUFMRED",
    "SIM",
    "MOV_DYN",
    "INTTOL",
    "OPT",
    "OPTIMISE",
    "INERTIA",
    "FORCE",
    "LOAD",
    "BUFDRV",
    "BUFEKIN",
    "BUFEPOT",
    "BUFPOW",
    "VARY",
    "VARYX",
    "TARGET",
    "TARGETAT",
    "TARGETEXT",
    "BOUND",
    "MINIMISE",
    "MAXIMISE",
    "OPTSTEPS",
    "OPTTOL",
    "MAX",
    "MAXABS",
    "RMS",
];

/// How hostile a generated deck is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum Level {
    /// Ordinary numbers, every reference in range: most such decks compile.
    Tame,
    /// Also zeros and finite numbers at the ends of f64's range.
    Extreme,
    /// Anything: numbers that are none, references out of range, wrong
    /// counts, lines dropped, repeated, swapped or given a stray word.
    Wild,
}

/// The mode line of a generated deck, and with it the blocks it has.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Mode {
    /// `KIN ANA`.
    KinAna,
    /// `DYN ANA`: a DYNAMICS block, a timed motion.
    DynAna,
    /// `DYN SIM`: a DYNAMICS block, DOFs moved by the forces (MOV_DYN).
    DynSim,
    /// `KIN OPT`: a driven motion and an OPTIMISE block.
    KinOpt,
}

impl Mode {
    fn line(self) -> &'static str {
        match self {
            Mode::KinAna => "KIN ANA",
            Mode::DynAna => "DYN ANA",
            Mode::DynSim => "DYN SIM",
            Mode::KinOpt => "KIN OPT",
        }
    }

    fn dynamic(self) -> bool {
        matches!(self, Mode::DynAna | Mode::DynSim)
    }
}

/// The sizes of a generated model that buffers refer to.
struct Sizes {
    n_dof: usize,
    n_coords: usize,
    n_rows: usize,
    n_dep: usize,
    fixed: usize,
    mode: Mode,
}

/// A generator of deck text from a stream of choices.
pub struct Gen<'a, C: Choose> {
    c: &'a mut C,
    level: Level,
}

impl<C: Choose> Gen<'_, C> {
    fn below(&mut self, n: usize) -> usize {
        self.c.below(n)
    }

    fn chance(&mut self, percent: usize) -> bool {
        self.c.chance(percent)
    }

    /// `true` with probability `percent` / 100 in a wild deck, never otherwise.
    fn wild(&mut self, percent: usize) -> bool {
        self.level == Level::Wild && self.c.chance(percent)
    }

    fn pick<'w>(&mut self, items: &[&'w str]) -> &'w str {
        self.c.pick(items)
    }

    /// A real number: ordinary ones (multiples of 1/40 in -5..5, small
    /// whole numbers, Fortran's ways of writing them), then, as the level
    /// allows, zeros, extremes, huge whole numbers and words that are no
    /// number.
    pub fn real(&mut self) -> String {
        let kinds = match self.level {
            Level::Tame => 4,
            Level::Extreme => 8,
            Level::Wild => 10,
        };
        match self.below(kinds) {
            0 | 1 => format!("{}", (self.below(401) as f64 - 200.0) / 40.0),
            2 => format!("{}", self.below(10)),
            3 => self.pick(&["-3.d-2", "1.5D0", ".5", "5.", "+2.5E+1", "1d0", "-.25", "1E1"]).to_string(),
            4 => self.pick(&["0", "0.0", "-0.", ".0D0", "-0"]).to_string(),
            5 | 6 => self.pick(EXTREME_REALS).to_string(),
            7 => format!("{}e{}", 1 + self.below(9), self.below(61) as i64 - 30),
            8 => self.pick(HUGE_INTEGERS).to_string(),
            _ => self.pick(ODD_NUMBERS).to_string(),
        }
    }

    /// A number meant to be positive (a mass, a stiffness, a tolerance):
    /// in a tame deck 0.1 to 5, otherwise any [`Gen::real`], and now and
    /// then far too large for the other numbers of the model.
    fn positive(&mut self) -> String {
        let level = self.level;
        match level {
            Level::Tame => format!("{}", (1 + self.below(50)) as f64 / 10.0),
            _ if self.chance(10) => self.pick(&["1e12", "1e15", "1e30", "1e-12"]).to_string(),
            _ => self.real(),
        }
    }

    /// A whole number meant to lie in `1..=n`; in a wild deck sometimes
    /// just outside (0, n+1, negative) or far outside, or no whole number.
    pub fn index(&mut self, n: usize) -> String {
        if !self.wild(15) {
            return format!("{}", 1 + self.below(n.max(1)));
        }
        match self.below(4) {
            0 => format!("{}", n + 1),
            1 => self.pick(&["0", "-1", "-0"]).to_string(),
            2 => self.pick(HUGE_INTEGERS).to_string(),
            _ => self.real(),
        }
    }

    /// Line `s` of a FORM table: a form parameter of one of the elements
    /// (of the right type) to destination `dest`, now and then with a factor.
    fn form(&mut self, types: &[ElementType], used: &mut Vec<(usize, usize)>, seq: usize, dest: i64) -> String {
        // A form parameter not used yet, unless all are (or by chance).
        let all: Vec<(usize, usize)> =
            types.iter().enumerate().flat_map(|(e, t)| (0..t.form_names().len()).map(move |f| (e, f))).collect();
        let unused: Vec<(usize, usize)> = all.iter().copied().filter(|ef| !used.contains(ef)).collect();
        let pool = if unused.is_empty() || self.chance(5) { &all } else { &unused };
        let (e, f) = pool[self.below(pool.len())];
        used.push((e, f));
        let name = types[e].form_names()[f];
        let kw = if seq == 1 { "FORM" } else { "" };
        let factor = if self.chance(10) { self.real() } else { String::new() };
        format!("{kw} {seq} {name} {} {dest} {factor}", e + 1).trim().to_string()
    }

    /// The deck: see [`deck`].
    fn deck(&mut self) -> String {
        let mode = match self.below(8) {
            0..=4 => Mode::KinAna,
            5 => Mode::DynAna,
            6 => Mode::DynSim,
            _ => Mode::KinOpt,
        };
        let mut lines = vec![mode.line().to_string(), "TOPOLOGY".to_string()];

        // Elements sharing points (pairs of co-ordinates) and angles.
        let n_elem = 1 + self.below(4);
        let (mut n_coords, mut points, mut scalars) = (0, Vec::<[usize; 2]>::new(), Vec::<usize>::new());
        let mut types = Vec::new();
        for k in 1..=n_elem {
            let ty = ElementType::ALL[self.below(ElementType::ALL.len())];
            let mut coords = Vec::new();
            for &slot in slots(ty) {
                if slot == 'p' {
                    let fresh: Vec<[usize; 2]> = points.iter().copied().filter(|p| !coords.contains(&p[0])).collect();
                    let p = if !fresh.is_empty() && self.chance(50) {
                        fresh[self.below(fresh.len())]
                    } else {
                        n_coords += 2;
                        points.push([n_coords - 1, n_coords]);
                        [n_coords - 1, n_coords]
                    };
                    coords.extend(p);
                } else {
                    let c = if !scalars.is_empty() && self.chance(30) {
                        scalars[self.below(scalars.len())]
                    } else {
                        n_coords += 1;
                        scalars.push(n_coords);
                        n_coords
                    };
                    coords.push(c);
                }
            }
            if self.wild(5) {
                match self.below(3) {
                    0 => drop(coords.pop()),
                    1 => coords.push(1 + self.below(n_coords)),
                    _ => {
                        let at = self.below(coords.len());
                        coords[at] = 1 + self.below(n_coords);
                    }
                }
            }
            let words: Vec<String> = coords.iter().map(|c| c.to_string()).collect();
            let kw = if k == 1 { "ELEM " } else { "" };
            lines.push(format!("{kw}{k} {} {}", ty.name(), words.join(" ")));
            types.push(ty);
        }
        let mut moving: Vec<bool> = (0..n_coords).map(|_| self.chance(50)).collect();
        if !moving.contains(&true) {
            moving[n_coords - 1] = true;
        }
        let n_moving = moving.iter().filter(|&&m| m).count();

        // Form parameters: one row per moving co-ordinate, some combined,
        // some dependent.
        let mut n_rows = n_moving;
        if self.wild(10) {
            n_rows = (n_rows + self.below(3)).saturating_sub(1);
        }
        let (mut seq, mut used) = (0, Vec::new());
        for r in 1..=n_rows {
            for _ in 0..if self.chance(10) { 2 } else { 1 } {
                seq += 1;
                let line = self.form(&types, &mut used, seq, r as i64);
                lines.push(line);
            }
        }
        let n_dep = self.below(3);
        for d in 1..=n_dep {
            seq += 1;
            let line = self.form(&types, &mut used, seq, -(d as i64));
            lines.push(line);
        }
        let n_dof = 1 + self.below(n_rows.clamp(1, 3));
        let nrdof = if self.wild(5) { self.index(3) } else { n_dof.to_string() };
        lines.push(format!("NRDOF {nrdof}"));

        // Co-ordinates and prescribed values.
        lines.push("GEOMETRY".into());
        for (i, &m) in moving.iter().enumerate() {
            let number = if self.wild(3) { self.index(n_coords) } else { (i + 1).to_string() };
            let value = self.real();
            lines.push(format!("{} {number} {value}", if m { "XMOV" } else { "XFIX" }));
        }
        // A KIN OPT deck varies rows with a PARA value: more of them have one.
        let mut paras = Vec::new();
        let fixed: Vec<usize> = (1..=n_coords).filter(|&i| !moving[i - 1]).collect();
        for r in 1..=n_rows {
            if self.chance(if mode == Mode::KinOpt { 60 } else { 20 }) {
                let value = self.real();
                lines.push(format!("PARA {r} {value}"));
                paras.push((r, value));
            }
        }
        if mode.dynamic() && !self.wild(10) {
            self.dynamics(&mut lines, &types, &points, &scalars, (n_rows, n_dep));
        }

        // The motion.
        let needs_motion = matches!(mode, Mode::DynSim | Mode::KinOpt) && !self.wild(10);
        let mut steps_taken = 0;
        if needs_motion || self.below(10) < 8 {
            lines.push("MOVEMENT".into());
            let mut steps = match self.below(10) {
                0..=7 => (1 + self.below(20)).to_string(),
                8 => (1 + self.below(3000)).to_string(),
                _ => self.index(10),
            };
            // The motion files and their lengths in steps.
            let file = match self.below(if self.level == Level::Wild { 6 } else { 2 }) {
                0 => ("crank.dat", 4),
                1 => ("table.dat", 2),
                2 => ("bad_motion.dat", 2),
                3 => ("none.dat", 1),
                4 => (".", 1),
                _ => ("/dev/null", 1),
            };
            let mut motions = Vec::new();
            for j in 1..=n_dof {
                let dof = if self.wild(5) { self.index(n_dof) } else { j.to_string() };
                let kinds = if n_dof == 1 || self.level == Level::Wild { 10 } else { 7 };
                // A DYN SIM deck lets the forces move a DOF now and then,
                // the others (and every other mode's) follow a driven or free
                // motion; KIN OPT and DYN ANA decks are driven, except wild ones.
                let kinds = match mode {
                    Mode::DynSim if self.chance(60) => 11,
                    Mode::KinOpt | Mode::DynAna if self.level != Level::Wild => 8,
                    _ => kinds,
                };
                let what = match self.below(kinds).max(if kinds == 11 { 10 } else { 0 }) {
                    0..=3 => format!("MOV_RELE {dof} {}", self.real()),
                    4 | 5 => format!("MOV_ABSE {dof} {}", self.real()),
                    6 | 7 => {
                        if !self.wild(50) {
                            steps = file.1.to_string();
                        }
                        format!("MOV_FUNC {dof} {}", file.0)
                    }
                    10 => format!("MOV_DYN {dof} {}", self.real()),
                    _ => {
                        let ds = self.real();
                        let ds = if self.level == Level::Wild {
                            ds
                        } else {
                            format!("{}", ds.parse::<f64>().unwrap_or(0.1).abs().max(1e-3))
                        };
                        format!("MOV_FREE {dof} {ds}")
                    }
                };
                motions.push(what);
            }
            let dt = match self.below(3) {
                0 => None,
                1 => Some(["0.01", "1", "0.5"][self.below(3)].to_string()),
                _ if self.level == Level::Wild => Some(self.real()),
                _ => Some(self.real().trim_start_matches('-').to_string())
                    .filter(|dt| dt.parse::<f64>().is_ok_and(|v| v > 0.0)),
            };
            steps_taken = steps.parse().unwrap_or(0);
            match dt {
                Some(dt) => lines.push(format!("TSTEPE {steps} {dt}")),
                None => lines.push(format!("TSTEPE {steps}")),
            }
            lines.extend(motions);
            if self.chance(15) {
                let tol = if self.level == Level::Tame { format!("1e-{}", 3 + self.below(12)) } else { self.real() };
                lines.push(format!("ACCURACY {tol}"));
            }
            if self.chance(15) {
                let m = self.index(50);
                lines.push(format!("MAXITER {m}"));
            }
            if mode == Mode::DynSim && self.chance(20) {
                let (rtol, atol) = match self.level {
                    Level::Tame => (format!("1e-{}", 4 + self.below(9)), format!("1e-{}", 4 + self.below(9))),
                    _ => (self.real(), self.real()),
                };
                lines.push(format!("INTTOL {rtol} {atol}"));
            }
        }

        // Buffers are numbered across OPTIMISE and STORAGE.
        let mut buffers = 0;
        let sizes = Sizes { n_dof, n_coords, n_rows, n_dep, fixed: fixed.len(), mode };
        if mode == Mode::KinOpt && !self.wild(10) {
            self.optimise(&mut lines, &sizes, &paras, &fixed, steps_taken, &mut buffers);
        }

        // Buffers and what to do with them.
        if self.below(10) < 7 {
            lines.push("STORAGE".into());
            for _ in 0..self.below(8) {
                buffers += 1;
                let b = if self.wild(5) { self.index(buffers) } else { buffers.to_string() };
                let line = self.buffer(&sizes, &b);
                lines.push(line);
            }
            if self.chance(40) {
                let named = if buffers > 0 && self.chance(50) { self.index(buffers) } else { String::new() };
                lines.push(format!("PRINTBUF {named}").trim().to_string());
            }
            if buffers > 0 && self.chance(30) {
                let b = self.index(buffers);
                lines.push(format!("SAVEDATA {b}"));
            }
            if self.chance(20) {
                lines.push("ANIMATE film".into());
            }
            if buffers > 0 && self.chance(30) {
                lines.push("BEGINPIC a picture".into());
                let item = match self.below(3) {
                    0 => format!("PLOTFUNC {} {}", self.index(buffers), self.index(buffers)),
                    1 => format!("PLOTCURV {} {}", self.index(buffers), self.index(buffers)),
                    _ => format!("PLOTHODO {} {}", self.index(n_coords), self.index(n_coords)),
                };
                lines.push(item);
                if !self.wild(10) {
                    lines.push("ENDPIC".into());
                }
            }
        }
        if self.chance(30) {
            lines.push("END".into());
        }

        // A few lines mangled.
        let mangled = if self.level == Level::Wild { self.below(4) } else { 0 };
        for _ in 0..mangled {
            if lines.is_empty() {
                break;
            }
            let k = self.below(lines.len());
            match self.below(4) {
                0 => {
                    lines.remove(k);
                }
                1 => {
                    let copy = lines[k].clone();
                    let to = self.below(lines.len());
                    lines.insert(to, copy);
                }
                2 => {
                    let word = self.pick(WORDS);
                    lines[k] = format!("{} {word}", lines[k]);
                }
                _ => {
                    let other = self.below(lines.len());
                    lines.swap(k, other);
                }
            }
        }
        lines.join("\n") + "\n"
    }
}

/// A deck that is plausible line by line: elements of catalogue types with
/// the right number of co-ordinates on shared co-ordinates, one prescribed
/// row per moving co-ordinate, a motion and buffers. The first choice sets
/// the [`Level`]: half of the decks are tame, a quarter extreme, a quarter
/// wild.
pub fn deck(c: &mut impl Choose) -> String {
    let level = match c.below(4) {
        0 | 1 => Level::Tame,
        2 => Level::Extreme,
        _ => Level::Wild,
    };
    Gen { c, level }.deck()
}

/// The kinds of co-ordinate of an element type, in deck order: `p` the two
/// co-ordinates of a point, `s` a single one (an angle, a ratio, a radius).
fn slots(ty: ElementType) -> &'static [char] {
    match ty {
        ElementType::Bin => &['p', 'p'],
        ElementType::Hlf => &['p', 's'],
        ElementType::Tr1 => &['p', 's', 'p'],
        ElementType::Tr2 => &['p', 'p', 'p'],
        ElementType::Gr1 => &['s', 's', 's', 's'],
        ElementType::Gr2 => &['s', 's', 's', 's', 's'],
        ElementType::Rk1 => &['p', 's', 'p', 's', 's'],
        ElementType::Rk2 => &['p', 'p', 'p', 's', 's'],
        ElementType::Blt => &['p', 's', 'p', 's', 's', 's'],
        ElementType::Crd => &['s'],
    }
}
