//! The masses and loads of a built deck (its DYNAMICS block).

use mechfem_core::units::Dim;

use crate::ast::{Dynamics, ForceDef, GravityDef, InertiaDef, LoadDef, LoadDefKind, MassDef, PointMassDef};
use crate::diagnostic::DiagnosticKind;
use crate::keywords::Keyword;

use super::{at, checks, DeckBuilder, Refused};

impl DeckBuilder {
    /// Begins the masses and loads (DYNAMICS), which a dynamics mode needs.
    pub fn dynamics(&mut self) -> Result<(), Refused> {
        self.in_block(Keyword::Mass, Keyword::Xmov, "the masses and loads")?;
        let line = self.next_line("DYNAMICS");
        let mode = self.deck.mode.value;
        if !mode.has_dynamics() {
            return Err(self.refuse(
                DiagnosticKind::WrongMode,
                line,
                format!("a {} model has no masses or loads", mode.name()),
            ));
        }
        self.deck.dynamics = Some(Dynamics { line, ..Dynamics::default() });
        self.block = Some(Keyword::Mass);
        Ok(())
    }

    fn dynamics_block(&mut self, kw: Keyword, what: &str) -> Result<(usize, String), Refused> {
        self.in_block(kw, Keyword::Mass, what)?;
        let line = self.next_line(what);
        Ok((line, what.to_string()))
    }

    fn dyn_mut(&mut self) -> &mut Dynamics {
        self.deck.dynamics.get_or_insert_with(Dynamics::default)
    }

    /// A body's mass `mass` with centre of mass (`u`, `v`) in the frame of
    /// element `element` and moment of inertia `inertia`, named `what`.
    pub fn mass(&mut self, element: i64, mass: f64, u: f64, v: f64, inertia: f64, what: &str) -> Result<(), Refused> {
        let (line, w) = self.dynamics_block(Keyword::Mass, what)?;
        checks::whole(self, line, element, &w)?;
        let mass = checks::not_negative(self, line, mass, &format!("the mass of {w}"), Some(Dim::MASS))?;
        let u = checks::bounded(self, line, u, &format!("the centre of mass u of {w}"))?;
        let v = checks::bounded(self, line, v, &format!("the centre of mass v of {w}"))?;
        let inertia =
            checks::not_negative(self, line, inertia, &format!("the moment of inertia of {w}"), Some(Dim::INERTIA))?;
        let def = MassDef { line, element: at(element, line), mass, u, v, inertia: Some(inertia) };
        self.dyn_mut().masses.push(def);
        Ok(())
    }

    /// A point mass `mass` at the point of co-ordinates `x`, `y`, named `what`.
    pub fn point_mass(&mut self, x: i64, y: i64, mass: f64, what: &str) -> Result<(), Refused> {
        let (line, w) = self.dynamics_block(Keyword::Pmass, what)?;
        let (x, y) = checks::point(self, line, x, y, &w)?;
        let mass = checks::not_negative(self, line, mass, &format!("the mass of {w}"), Some(Dim::MASS))?;
        self.dyn_mut().point_masses.push(PointMassDef { line, x, y, mass });
        Ok(())
    }

    /// A moment of inertia `inertia` on the angle co-ordinate `coord`, named `what`.
    pub fn inertia(&mut self, coord: i64, inertia: f64, what: &str) -> Result<(), Refused> {
        let (line, w) = self.dynamics_block(Keyword::Inertia, what)?;
        checks::whole(self, line, coord, &w)?;
        let inertia = checks::not_negative(self, line, inertia, &format!("the moment of inertia of {w}"), None)?;
        self.dyn_mut().inertias.push(InertiaDef { line, coord: at(coord, line), inertia });
        Ok(())
    }

    /// The acceleration of gravity (`gx`, `gy`), given once.
    pub fn gravity(&mut self, gx: f64, gy: f64) -> Result<(), Refused> {
        let (line, w) = self.dynamics_block(Keyword::Gravity, "gravity")?;
        if self.deck.dynamics.as_ref().is_some_and(|d| d.gravity.is_some()) {
            return Err(self.refuse(DiagnosticKind::DuplicateKeyword, line, "gravity is given twice"));
        }
        let gx = checks::bounded(self, line, gx, &format!("the acceleration of {w}"))?;
        let gy = checks::bounded(self, line, gy, &format!("the acceleration of {w}"))?;
        self.dyn_mut().gravity = Some(GravityDef { line, gx, gy });
        Ok(())
    }

    /// A constant force (`fx`, `fy`) at the point of co-ordinates `x`, `y`, named `what`.
    pub fn force(&mut self, x: i64, y: i64, fx: f64, fy: f64, what: &str) -> Result<(), Refused> {
        let (line, w) = self.dynamics_block(Keyword::Force, what)?;
        let (x, y) = checks::point(self, line, x, y, &w)?;
        let fx = checks::bounded(self, line, fx, &format!("the force of {w}"))?;
        let fy = checks::bounded(self, line, fy, &format!("the force of {w}"))?;
        self.dyn_mut().forces.push(ForceDef { line, x, y, fx, fy });
        Ok(())
    }

    fn load_def(
        &mut self,
        kw: Keyword,
        row: i64,
        what: &str,
        kind: impl FnOnce(&Self, usize, &str) -> Result<LoadDefKind, Refused>,
    ) -> Result<(), Refused> {
        let (line, w) = self.dynamics_block(kw, what)?;
        checks::whole(self, line, row, &w)?;
        let kind = kind(self, line, &w)?;
        let def = LoadDef { line, keyword: at(kw, line), form: at(row, line), kind };
        self.dyn_mut().loads.push(def);
        Ok(())
    }

    /// A constant generalised force `value` on row `row`, named `what`.
    pub fn load(&mut self, row: i64, value: f64, what: &str) -> Result<(), Refused> {
        self.load_def(Keyword::Load, row, what, |b, line, w| {
            Ok(LoadDefKind::Constant(checks::bounded(b, line, value, &format!("the load on {w}"))?))
        })
    }

    /// A generalised force on row `row` read from the table file `file`
    /// (relative to the folder [`DeckBuilder::build`] is given), named `what`.
    pub fn load_table(&mut self, row: i64, file: &str, what: &str) -> Result<(), Refused> {
        self.load_def(Keyword::LoadFunc, row, what, |b, line, w| {
            Ok(LoadDefKind::Function(at(checks::file_name(b, line, file, w)?, line)))
        })
    }

    /// A spring of stiffness `k` and free value `e0` with damping `c` on row `row`, named `what`.
    pub fn spring(&mut self, row: i64, k: f64, e0: f64, c: f64, what: &str) -> Result<(), Refused> {
        self.load_def(Keyword::Spring, row, what, |b, line, w| {
            Ok(LoadDefKind::Spring {
                k: checks::not_negative(b, line, k, &format!("the stiffness of {w}"), None)?,
                e0: checks::bounded(b, line, e0, &format!("the free value of {w}"))?,
                c: Some(checks::not_negative(b, line, c, &format!("the damping of {w}"), None)?),
            })
        })
    }

    /// A motor of stall torque `t0` and no-load speed `w0` on row `row`, named `what`.
    pub fn motor(&mut self, row: i64, t0: f64, w0: f64, what: &str) -> Result<(), Refused> {
        self.load_def(Keyword::Motor, row, what, |b, line, w| {
            let t0 = checks::bounded(b, line, t0, &format!("the stall torque of {w}"))?;
            let w0 = checks::bounded(b, line, w0, &format!("the no-load speed of {w}"))?;
            if w0.value == 0.0 {
                return Err(b.refuse(DiagnosticKind::BadValue, line, format!("the no-load speed of {w} is 0")));
            }
            Ok(LoadDefKind::Motor { t0, w0 })
        })
    }
}
