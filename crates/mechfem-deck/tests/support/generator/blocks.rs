//! The generator's lines beside the elements: a row of a form parameter,
//! buffer definitions, the DYNAMICS block and the OPTIMISE block (and a
//! design variable's range).

use super::*;

impl<C: Choose> Gen<'_, C> {
    /// A destination of a buffer: a prescribed row, or (as `-k`) a
    /// dependent form parameter.
    pub(super) fn row(&mut self, n_rows: usize, n_dep: usize) -> String {
        if n_dep > 0 && self.chance(30) {
            format!("-{}", self.index(n_dep))
        } else {
            self.index(n_rows)
        }
    }

    /// A buffer definition `BUF... b`: the kinematic ones in every mode,
    /// the dynamic ones in a dynamics mode (BUFMRED in DYN ANA only).
    pub(super) fn buffer(&mut self, z: &Sizes, b: &str) -> String {
        let (n_dof, n_coords, n_rows, n_dep) = (z.n_dof, z.n_coords, z.n_rows, z.n_dep);
        let kinds = if z.mode.dynamic() || self.wild(5) { 20 } else { 13 };
        match self.below(kinds) {
            0 => format!("BUFINP {} {b}", self.index(n_dof)),
            1 => format!("BUFTIME {b}"),
            2 => format!("BUFX0 {} {b}", self.index(n_coords)),
            3 => format!("BUFKX1 {} {} {b}", self.index(n_coords), self.index(n_dof)),
            4 => format!("BUFKX2 {} {} {} {b}", self.index(n_coords), self.index(n_dof), self.index(n_dof)),
            5 => format!("BUFVX {} {b}", self.index(n_coords)),
            6 => format!("BUFAX {} {b}", self.index(n_coords)),
            7 => format!("BUFE0 {} {b}", self.row(n_rows, n_dep)),
            8 => format!("BUFKE1 {} {} {b}", self.row(n_rows, n_dep), self.index(n_dof)),
            9 => format!("BUFKE2 {} {} {b}", self.row(n_rows, n_dep), self.index(n_dof)),
            10 => format!("BUFVE {} {b}", self.row(n_rows, n_dep)),
            11 => format!("BUFAE {} {b}", self.row(n_rows, n_dep)),
            12 => format!("BUFDET {b}"),
            13 => format!("BUFSIG {} {b}", self.index(n_rows)),
            14 => format!("BUFDRV {} {b}", self.index(n_dof)),
            15 => format!("BUFREA {} {b}", self.index(z.fixed.max(1))),
            16 => format!("BUFEKIN {b}"),
            17 => format!("BUFEPOT {b}"),
            18 => format!("BUFPOW {b}"),
            _ => format!("BUFMRED {} {} {b}", self.index(n_dof), self.index(n_dof)),
        }
    }

    /// The DYNAMICS block: masses on elements with a frame, point masses,
    /// inertias on angles, gravity, forces, loads, springs and motors.
    pub(super) fn dynamics(
        &mut self,
        lines: &mut Vec<String>,
        types: &[ElementType],
        points: &[[usize; 2]],
        scalars: &[usize],
        (n_rows, n_dep): (usize, usize),
    ) {
        lines.push("DYNAMICS".into());
        for (k, &ty) in types.iter().enumerate() {
            let framed = matches!(ty, ElementType::Bin | ElementType::Hlf | ElementType::Tr1 | ElementType::Tr2);
            if (framed && self.chance(70)) || self.wild(10) {
                let (m, u, v) = (self.positive(), self.real(), self.real());
                let j = if self.chance(60) { format!(" {}", self.positive()) } else { String::new() };
                lines.push(format!("MASS {} {m} {u} {v}{j}", k + 1));
            }
        }
        if !points.is_empty() && self.chance(30) {
            let p = points[self.below(points.len())];
            let m = self.positive();
            lines.push(format!("PMASS {} {} {m}", p[0], p[1]));
        }
        if !scalars.is_empty() && self.chance(20) {
            let i = scalars[self.below(scalars.len())];
            let j = self.positive();
            lines.push(format!("INERTIA {i} {j}"));
        }
        if self.chance(40) {
            let g = if self.level == Level::Tame { "-9.81".to_string() } else { self.real() };
            let gx = if self.chance(80) { "0".to_string() } else { self.real() };
            lines.push(format!("GRAVITY {gx} {g}"));
        }
        if !points.is_empty() && self.chance(20) {
            let p = points[self.below(points.len())];
            let (fx, fy) = (self.real(), self.real());
            lines.push(format!("FORCE {} {} {fx} {fy}", p[0], p[1]));
        }
        if self.chance(30) {
            let (r, value) = (self.row(n_rows, n_dep), self.real());
            lines.push(format!("LOAD {r} {value}"));
        }
        if self.chance(10) {
            let r = self.row(n_rows, n_dep);
            lines.push(format!("LOADFUNC {r} torque.dat"));
        }
        if self.chance(30) {
            let (r, k, e0) = (self.row(n_rows, n_dep), self.positive(), self.real());
            let c = if self.chance(50) { format!(" {}", self.positive()) } else { String::new() };
            lines.push(format!("SPRING {r} {k} {e0}{c}"));
        }
        if self.chance(20) {
            let (r, t0, w0) = (self.row(n_rows, n_dep), self.real(), self.positive());
            lines.push(format!("MOTOR {r} {t0} {w0}"));
        }
    }

    /// The OPTIMISE block of a KIN OPT deck: design variables among the
    /// rows with a PARA value (`paras`) and the fixed co-ordinates, a few
    /// buffers, targets of each kind, bounds, an objective and the
    /// optimiser's settings. `buffers` counts the buffers defined.
    pub(super) fn optimise(
        &mut self,
        lines: &mut Vec<String>,
        z: &Sizes,
        paras: &[(usize, String)],
        fixed: &[usize],
        steps: usize,
        buffers: &mut usize,
    ) {
        lines.push("OPTIMISE".into());
        let mut vary = 0;
        for (r, value) in paras {
            if vary < 3 && self.chance(60) {
                let (lo, hi) = self.range(value);
                lines.push(format!("VARY {r} {lo} {hi}"));
                vary += 1;
            }
        }
        if !fixed.is_empty() && (vary == 0 || self.chance(20)) {
            let i = fixed[self.below(fixed.len())];
            let (lo, hi) = (self.real(), self.real());
            let (lo, hi) = if self.level == Level::Wild { (lo, hi) } else { ("-1e3".into(), "1e3".into()) };
            lines.push(format!("VARYX {i} {lo} {hi}"));
        }
        // Buffers: one of any kind, and a position quantity as a reference
        // of extrema.
        let mut defined = Vec::new();
        for _ in 0..1 + self.below(3) {
            *buffers += 1;
            let b = buffers.to_string();
            let line = if self.chance(40) {
                if z.n_dep > 0 && self.chance(50) {
                    format!("BUFE0 -{} {b}", self.index(z.n_dep))
                } else {
                    format!("BUFX0 {} {b}", self.index(z.n_coords))
                }
            } else {
                self.buffer(z, &b)
            };
            lines.push(line);
            defined.push(*buffers);
        }
        let mut terms = 0;
        for _ in 0..self.below(4) {
            let b = defined[self.below(defined.len())];
            let w = if self.chance(20) { format!(" {}", self.positive()) } else { String::new() };
            let line = match self.below(4) {
                0 => format!("TARGETAT {b} {} {}{w}", self.index(steps + 1), self.real()),
                1 => format!("TARGETEXT {b} {} {}{w}", defined[self.below(defined.len())], self.real()),
                2 => format!("TARGET {b} target.dat{w}"),
                _ => format!("BOUND {b} {} {}", self.real(), self.real()),
            };
            terms += usize::from(!line.starts_with("BOUND"));
            lines.push(line);
        }
        if self.chance(30) || (terms == 0 && !self.wild(50)) {
            let kind = self.pick(&["MAX", "MAXABS", "RMS", "END", "MIN"]);
            let sense = self.pick(&["MINIMISE", "MAXIMISE"]);
            let b = defined[self.below(defined.len())];
            lines.push(format!("{sense} {kind} {b}"));
        }
        if self.chance(20) {
            let n = if self.level == Level::Tame { (1 + self.below(5)).to_string() } else { self.index(300) };
            lines.push(format!("OPTSTEPS {n}"));
        }
        if self.chance(20) {
            let tol = if self.level == Level::Tame { "1e-6".to_string() } else { self.real() };
            lines.push(format!("OPTTOL {tol}"));
        }
    }

    /// A range `lo hi` of a design variable whose start is `value`: around
    /// it in a tame deck, anything (empty, reversed, not finite) otherwise.
    pub(super) fn range(&mut self, value: &str) -> (String, String) {
        match value.parse::<f64>() {
            Ok(v) if v.is_finite() && !self.wild(30) && !(self.level == Level::Extreme && self.chance(20)) => {
                let (a, b) = ((1 + self.below(8)) as f64 / 4.0, (1 + self.below(8)) as f64 / 4.0);
                (format!("{}", v - a * v.abs().max(1.0)), format!("{}", v + b * v.abs().max(1.0)))
            }
            _ => (self.real(), self.real()),
        }
    }
}
