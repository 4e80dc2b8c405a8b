//! A deck with UNITS to the core's units: every number it gives is
//! multiplied by the scale of its kind, before anything is compiled, so
//! that the checks and the model see the numbers the core computes with.
//! Numbers read from tables (MOV_FUNC, LOADFUNC, TARGET files) and the
//! targets and bounds of buffers are scaled where they are compiled
//! ([`CoreScale`]).
//!
//! The kinds: co-ordinates and rows as their elements say
//! ([`ModelDims`]); a FORM factor converts its term's kind into its row's;
//! a load, spring or motor on a row is a generalised force on it (a force
//! on a length, a torque on an angle); time steps are times, ACCURACY a
//! length. INTTOL's tolerances and the weights of targets are the core's.

use mechfem_core::{Dim, Mechanism, ModelDims, Units};

use crate::ast::{CoreScale, Deck, LoadDefKind, MotionKind};
use crate::diagnostic::Spanned;

fn scale(units: &Units, dim: Dim, v: &mut Spanned<f64>) {
    v.value = units.to_core(dim, v.value);
}

/// The mass-like kind of an inertia on a co-ordinate of kind `d`: a mass
/// on a length, mass x length² on an angle or a pure number.
pub(crate) fn inertia_on(d: Dim) -> Dim {
    Dim::MASS.times(Dim::LENGTH.pow(2 * (1 - d.0[0])))
}

/// A copy of `deck` with its numbers in the core's units, for the model
/// `mech` compiled from it as it is.
pub(crate) fn to_core(deck: &Deck, units: Units, mech: &Mechanism) -> Deck {
    let dims = ModelDims::of(mech);
    let inputs: Vec<Dim> = (0..mech.n_dof()).map(|j| dims.input(mech, j)).collect();
    let mut d = deck.clone();
    let u = &units;
    let coord = |i: i64| usize::try_from(i - 1).map_or(Dim::LENGTH, |i| dims.coord(i));
    let row = |r: i64| {
        let k = usize::try_from(r.unsigned_abs().saturating_sub(1)).unwrap_or(0);
        let list = if r > 0 { &dims.prescribed } else { &dims.dependent };
        list.get(k).copied().unwrap_or(Dim::NONE)
    };
    let input = |j: i64| usize::try_from(j - 1).ok().and_then(|j| inputs.get(j)).copied().unwrap_or(Dim::NONE);

    // A FORM factor f makes its term's number into its row's: f_core = f s_row / s_term.
    for f in &mut d.topology.forms {
        let Some(e) = usize::try_from(f.element.value - 1).ok().and_then(|k| deck.topology.elements.get(k)) else {
            continue;
        };
        let ty = e.ty.value;
        let term = match ty.form_index(&f.name.value).and_then(|k| ty.form_dimensions().get(k)) {
            Some(mechfem_core::Dimension::Any) => e.coords.first().map_or(Dim::LENGTH, |c| coord(c.value)),
            Some(&dim) => Dim::of(dim),
            None => continue,
        };
        let ratio = row(f.dest.value).scale(u) / term.scale(u);
        if ratio != 1.0 {
            let factor = f.factor.get_or_insert(Spanned::new(1.0, f.dest.span));
            factor.value *= ratio;
        }
    }
    for c in &mut d.geometry.coords {
        scale(u, coord(c.index.value), &mut c.value);
    }
    for p in &mut d.geometry.paras {
        scale(u, row(p.row.value), &mut p.value);
    }
    if let Some(dy) = &mut d.dynamics {
        for m in &mut dy.masses {
            scale(u, Dim::MASS, &mut m.mass);
            scale(u, Dim::LENGTH, &mut m.u);
            scale(u, Dim::LENGTH, &mut m.v);
            if let Some(j) = &mut m.inertia {
                scale(u, Dim::INERTIA, j);
            }
        }
        for p in &mut dy.point_masses {
            scale(u, Dim::MASS, &mut p.mass);
        }
        for i in &mut dy.inertias {
            scale(u, inertia_on(coord(i.coord.value)), &mut i.inertia);
        }
        if let Some(g) = &mut dy.gravity {
            let accel = Dim::LENGTH.over(Dim::TIME.pow(2));
            scale(u, accel, &mut g.gx);
            scale(u, accel, &mut g.gy);
        }
        for f in &mut dy.forces {
            scale(u, Dim::FORCE, &mut f.fx);
            scale(u, Dim::FORCE, &mut f.fy);
        }
        for l in &mut dy.loads {
            let e = row(l.form.value);
            let q = e.generalised_force();
            match &mut l.kind {
                LoadDefKind::Constant(v) => scale(u, q, v),
                LoadDefKind::Function(_) => {}
                LoadDefKind::Spring { k, e0, c } => {
                    scale(u, q.over(e), k);
                    scale(u, e, e0);
                    if let Some(c) = c {
                        scale(u, q.over(e).times(Dim::TIME), c);
                    }
                }
                LoadDefKind::Motor { t0, w0 } => {
                    scale(u, q, t0);
                    scale(u, e.over(Dim::TIME), w0);
                }
            }
        }
    }
    if let Some(mv) = &mut d.movement {
        if let Some(dt) = &mut mv.tstepe.dt {
            scale(u, Dim::TIME, dt);
        }
        for m in &mut mv.motions {
            let e = input(m.dof.value);
            match &mut m.kind {
                MotionKind::Relative(v) | MotionKind::Absolute(v) => scale(u, e, v),
                MotionKind::Free(ds) => scale(u, Dim::LENGTH, ds),
                MotionKind::Dynamic(v0) => scale(u, e.over(Dim::TIME), v0),
                MotionKind::Function(_) => {}
            }
        }
        if let Some(tol) = &mut mv.accuracy {
            scale(u, Dim::LENGTH, tol);
        }
    }
    if let Some(o) = &mut d.optimise {
        for v in &mut o.vary {
            let dim = if v.keyword.value == crate::keywords::Keyword::VaryX {
                coord(v.index.value)
            } else {
                row(v.index.value)
            };
            scale(u, dim, &mut v.lo);
            scale(u, dim, &mut v.hi);
        }
        for v in &mut o.mass_vary {
            use crate::optimise::MassItem;
            let dim = match v.what.value {
                MassItem::Mass | MassItem::PointMass => Dim::MASS,
                MassItem::U | MassItem::V => Dim::LENGTH,
                MassItem::J => Dim::INERTIA,
                MassItem::Inertia => inertia_on(coord(v.index.value)),
            };
            scale(u, dim, &mut v.lo);
            scale(u, dim, &mut v.hi);
        }
        if let Some(f) = &mut o.free_time {
            // FREETIME's sweep is a difference of the input's values, in its row's unit.
            let dim = row(f.row.value);
            if let Some(w) = &mut f.within {
                scale(u, dim, w);
            }
        }
        if let Some(f) = &mut o.frame {
            // VARYFRAME's range is an angle, in the deck's angle unit.
            scale(u, Dim::ANGLE, &mut f.lo);
            scale(u, Dim::ANGLE, &mut f.hi);
        }
    }
    if let Some(t) = &mut d.tolerance {
        for def in &mut t.dims {
            let dim = if def.keyword.value == crate::keywords::Keyword::TolX {
                coord(def.index.value)
            } else {
                row(def.index.value)
            };
            scale(u, dim, &mut def.t);
        }
    }
    d.scale = Some(Box::new(CoreScale { units, dims, inputs }));
    d
}
