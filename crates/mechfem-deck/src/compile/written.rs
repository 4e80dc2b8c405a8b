//! The numbers of a compiled deck with UNITS back in the deck's units, for
//! a description of the deck as written (its co-ordinates, motion, masses
//! and loads): the inverse of [`super::scale`] and [`super::tables`].

use mechfem_core::dynamics::{Dynamics, LoadKind};
use mechfem_core::{Dim, ElementError, FormRef, InputMotion, LimitPosition, Motion, RunReport, SimReport, SolveError};

use super::scale::inertia_on;
use crate::compiled::Compiled;

impl Compiled {
    /// The co-ordinates as the deck gives them (XFIX and XMOV values), in
    /// its units.
    pub fn coords_as_written(&self) -> Vec<f64> {
        let (u, d) = (&self.units, &self.dims);
        self.state.x.iter().enumerate().map(|(i, &x)| u.as_written(d.coord(i), x)).collect()
    }

    /// The motion in the deck's units (steps, increments, tables, speeds).
    pub fn motion_as_written(&self) -> Option<Motion> {
        let mut m = self.motion.clone()?;
        let u = &self.units;
        if u.is_identity() {
            return Some(m);
        }
        m.dt = u.as_written(Dim::TIME, m.dt);
        for (j, input) in m.inputs.iter_mut().enumerate() {
            let e = self.dims.input(&self.mechanism, j);
            match input {
                InputMotion::Relative { delta: v } | InputMotion::Absolute { end: v } => *v = u.as_written(e, *v),
                InputMotion::Free { ds } => *ds = u.as_written(Dim::LENGTH, *ds),
                InputMotion::Dynamic { v0 } => *v0 = u.as_written(e.over(Dim::TIME), *v0),
                InputMotion::Table { rows } => {
                    let k = [Dim::TIME, e, e.over(Dim::TIME), e.over(Dim::TIME.pow(2))].map(|d| d.out_scale(u));
                    for row in rows.iter_mut() {
                        for (v, k) in row.iter_mut().zip(k) {
                            *v *= k;
                        }
                    }
                }
            }
        }
        Some(m)
    }

    /// The masses and loads in the deck's units.
    pub fn dynamics_as_written(&self) -> Option<Dynamics> {
        let mut d = self.dynamics.clone()?;
        let u = &self.units;
        if u.is_identity() {
            return Some(d);
        }
        for b in &mut d.bodies {
            b.mass = u.as_written(Dim::MASS, b.mass);
            b.u = u.as_written(Dim::LENGTH, b.u);
            b.v = u.as_written(Dim::LENGTH, b.v);
            b.inertia = u.as_written(Dim::INERTIA, b.inertia);
        }
        for p in &mut d.point_masses {
            p.mass = u.as_written(Dim::MASS, p.mass);
        }
        for i in &mut d.inertias {
            i.inertia = u.as_written(inertia_on(self.dims.coord(i.coord)), i.inertia);
        }
        let accel = Dim::LENGTH.over(Dim::TIME.pow(2));
        d.gravity = d.gravity.map(|g| u.as_written(accel, g));
        for f in &mut d.forces {
            f.f = f.f.map(|v| u.as_written(Dim::FORCE, v));
        }
        for l in &mut d.loads {
            let e = self.dims.form(l.form);
            let q = e.generalised_force();
            match &mut l.kind {
                LoadKind::Constant(v) => *v = u.as_written(q, *v),
                LoadKind::Table(rows) => {
                    for row in rows.iter_mut() {
                        row[0] = u.as_written(Dim::TIME, row[0]);
                        row[1] = u.as_written(q, row[1]);
                    }
                }
                LoadKind::Spring { k, e0, c } => {
                    *k = u.as_written(q.over(e), *k);
                    *e0 = u.as_written(e, *e0);
                    *c = u.as_written(q.over(e).times(Dim::TIME), *c);
                }
                LoadKind::Motor { t0, w0 } => {
                    *t0 = u.as_written(q, *t0);
                    *w0 = u.as_written(e.over(Dim::TIME), *w0);
                }
            }
        }
        Some(d)
    }
}

impl Compiled {
    /// A run's report in the deck's units: the initial deformations of the
    /// adjustment, the inputs, co-ordinates and det(D^c) of every limit
    /// position and of a stop, and the numbers its error quotes (a belt's
    /// centre distance, the time a simulation reached), so that what a
    /// designer reads of the run speaks the deck's numbers.
    pub fn report_as_written(&self, r: &RunReport) -> RunReport {
        let mut r = r.clone();
        if self.units.is_identity() {
            return r;
        }
        let (u, d, mech) = (&self.units, &self.dims, &self.mechanism);
        for (k, e) in r.adjust.initial_deformations.iter_mut().enumerate() {
            *e = u.as_written(d.form(FormRef::Prescribed(k)), *e);
        }
        let inputs = |values: &mut [f64]| {
            for (j, v) in values.iter_mut().enumerate() {
                *v = u.as_written(d.input(mech, j), *v);
            }
        };
        let limit = |l: &mut LimitPosition| {
            inputs(&mut l.inputs);
            for (i, x) in l.coords.iter_mut().enumerate() {
                *x = u.as_written(d.coord(i), *x);
            }
            l.det = u.as_written(d.det(mech), l.det);
        };
        r.limits.iter_mut().for_each(limit);
        if let Some(s) = &mut r.stop {
            inputs(&mut s.inputs);
            inputs(&mut s.last_inputs);
            if let Some(l) = &mut s.limit {
                limit(l);
            }
            s.error = self.error_as_written(&s.error);
        }
        r
    }

    /// A failure of the core with the numbers it quotes in the deck's units.
    pub fn error_as_written(&self, e: &SolveError) -> SolveError {
        let (u, det) = (&self.units, self.dims.det(&self.mechanism));
        let mut e = e.clone();
        match &mut e {
            SolveError::Element { source: ElementError::NoBeltSpan { l, d }, .. } => {
                *l = u.as_written(Dim::LENGTH, *l);
                *d = u.as_written(Dim::LENGTH, *d);
            }
            SolveError::Simulation { time, .. } => *time = u.as_written(Dim::TIME, *time),
            SolveError::DetSignChange { before, after } => {
                *before = u.as_written(det, *before);
                *after = u.as_written(det, *after);
            }
            _ => {}
        }
        e
    }
}

impl Compiled {
    /// What a simulation's integrator did, in the deck's units: the time
    /// reached, the stretches of each method and where STOPWHEN ended it
    /// (the value crossed in its buffer's unit, the time and the inputs).
    pub fn sim_as_written(&self, s: &SimReport) -> SimReport {
        let mut s = s.clone();
        if self.units.is_identity() {
            return s;
        }
        let (u, d, mech) = (&self.units, &self.dims, &self.mechanism);
        let time = |t: &mut f64| *t = u.as_written(Dim::TIME, *t);
        time(&mut s.reached);
        for g in &mut s.segments {
            time(&mut g.from);
            time(&mut g.to);
        }
        if let Some(e) = &mut s.event {
            time(&mut e.time);
            if let Some(b) = self.buffers.iter().find(|b| b.number == e.buffer) {
                e.value = u.as_written(d.quantity(mech, b.quantity), e.value);
            }
            for (j, v) in e.inputs.iter_mut().enumerate() {
                *v = u.as_written(d.input(mech, j), *v);
            }
        }
        s.run = self.report_as_written(&s.run);
        s
    }
}
