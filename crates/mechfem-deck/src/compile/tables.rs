//! The numbers a deck with UNITS gives in tables (MOV_FUNC, LOADFUNC and
//! TARGET files) and for buffers (targets, bounds), to the core's units:
//! scaled once compiled, when the kind of each column is known.

use mechfem_core::dynamics::{Dynamics, Integration, LoadKind};
use mechfem_core::{Dim, InputMotion, Mechanism, Motion};

use crate::ast::CoreScale;
use crate::compiled::Buffer;
use crate::optimise::{Optimise, TargetKind};

/// Scales the tables of `motion` and `dynamics`, the value of a STOPWHEN
/// and the targets and bounds of `optimise` by `s`.
pub(crate) fn to_core(
    s: &CoreScale,
    mech: &Mechanism,
    motion: Option<&mut Motion>,
    dynamics: Option<&mut Dynamics>,
    integration: &mut Integration,
    optimise: Option<&mut Optimise>,
    buffers: &[Buffer],
) {
    let u = &s.units;
    if let Some(stop) = &mut integration.stop_when {
        // The value is given in the unit of the buffer it is compared with.
        stop.value *= s.dims.quantity(mech, stop.quantity).scale(u);
    }
    let time = Dim::TIME.scale(u);
    if let Some(m) = motion {
        for (j, input) in m.inputs.iter_mut().enumerate() {
            let InputMotion::Table { rows } = input else { continue };
            let e = s.inputs.get(j).copied().unwrap_or(Dim::NONE);
            let k = [time, e.scale(u), e.over(Dim::TIME).scale(u), e.over(Dim::TIME.pow(2)).scale(u)];
            for row in rows.iter_mut() {
                for (v, k) in row.iter_mut().zip(k) {
                    *v *= k;
                }
            }
        }
    }
    if let Some(d) = dynamics {
        for l in &mut d.loads {
            let LoadKind::Table(rows) = &mut l.kind else { continue };
            let q = s.dims.form(l.form).generalised_force().scale(u);
            for row in rows.iter_mut() {
                row[0] *= time;
                row[1] *= q;
            }
        }
    }
    let Some(o) = optimise else { return };
    let scale_of =
        |b: u32| buffers.iter().find(|x| x.number == b).map_or(1.0, |x| s.dims.quantity(mech, x.quantity).scale(u));
    for t in &mut o.targets {
        let k = scale_of(t.buffer);
        match &mut t.kind {
            TargetKind::Values { values, .. } => values.iter_mut().flatten().for_each(|v| *v *= k),
            TargetKind::At { value, .. } | TargetKind::Extremum { value, .. } => *value *= k,
        }
    }
    for b in &mut o.bounds {
        let k = scale_of(b.buffer);
        b.lo *= k;
        b.hi *= k;
    }
}
