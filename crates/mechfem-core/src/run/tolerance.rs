//! Tolerance bands: how far a quantity y can be from its nominal value at
//! every position of a motion when the dimensions p_k are made within
//! +-t_k, to first order, from one run with the exact design
//! sensitivities s_k = dy/dp_k ([`super::design::evaluate`]):
//!
//! * worst case W = sum_k |s_k| t_k, the largest first-order deviation
//!   over every combination of the dimensions within their tolerances;
//! * root sum of squares R = sqrt(sum_k (s_k t_k)^2) (for independent
//!   uniform draws within +-t_k the first-order standard deviation of y is
//!   R / sqrt(3)).
//!
//! Where W is widest over the motion, each dimension's share is
//! |s_k| t_k / W of the worst case and (s_k t_k)^2 / R^2 of the variance:
//! which tolerance to tighten.

use super::design::evaluate;
use super::observe::RunReport;
use super::record::Quantity;
use crate::dynamics::Dynamics;
use crate::error::SolveError;
use crate::model::{Mechanism, State};
use crate::motion::Motion;
use crate::solver::{DesignVar, Params};

/// A dimension known to within +-t.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Toleranced {
    /// The dimension: a prescribed row's value or a fixed co-ordinate.
    pub var: DesignVar,
    /// Its tolerance t (positive, in the core's units).
    pub t: f64,
}

/// One dimension's part of a band at one position.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Share {
    /// Which toleranced dimension (its index in the list given).
    pub dim: usize,
    /// dy/dp there.
    pub sensitivity: f64,
    /// |dy/dp| t: how far the dimension alone moves y.
    pub deviation: f64,
    /// deviation / W (the shares add up to 1).
    pub of_worst: f64,
    /// deviation^2 / R^2 (the shares add up to 1).
    pub of_variance: f64,
}

/// Where a band is widest over the motion, and who makes it so.
#[derive(Debug, Clone, PartialEq)]
pub struct Widest {
    /// The position (0-based; the first of equal ones).
    pub position: usize,
    /// Every dimension's share there, largest deviation first.
    pub shares: Vec<Share>,
}

/// The bands of some quantities at every position of a motion.
#[derive(Debug, Clone)]
pub struct Bands {
    /// The run with the sensitivities (how far it got, why it stopped).
    pub report: RunReport,
    /// Positions computed.
    pub positions: usize,
    /// The tolerances t_k, in the order given.
    pub tolerances: Vec<f64>,
    /// Row-major, positions x inputs: the inputs' values.
    pub inputs: Vec<f64>,
    /// Row-major, positions x quantities: the nominal values.
    pub values: Vec<f64>,
    /// Row-major, positions x quantities x dimensions: s_k.
    pub sensitivity: Vec<f64>,
    /// Row-major, positions x quantities: W.
    pub worst: Vec<f64>,
    /// Row-major, positions x quantities: R.
    pub rss: Vec<f64>,
    /// Per quantity, where W is widest (None when no position has a
    /// finite W).
    pub widest: Vec<Option<Widest>>,
}

impl Bands {
    /// W and R of the sensitivities `s` of one quantity at one position.
    pub fn of(s: &[f64], t: &[f64]) -> (f64, f64) {
        let worst = s.iter().zip(t).map(|(s, t)| s.abs() * t).sum();
        let rss = s.iter().zip(t).map(|(s, t)| (s * t).powi(2)).sum::<f64>().sqrt();
        (worst, rss)
    }

    /// The shares of the dimensions at one position with sensitivities `s`.
    pub fn shares(s: &[f64], t: &[f64]) -> Vec<Share> {
        let (w, r) = Bands::of(s, t);
        let mut out: Vec<Share> = s
            .iter()
            .zip(t)
            .enumerate()
            .map(|(dim, (&s, &t))| {
                let deviation = s.abs() * t;
                Share {
                    dim,
                    sensitivity: s,
                    deviation,
                    of_worst: if w > 0.0 { deviation / w } else { f64::NAN },
                    of_variance: if r > 0.0 { (deviation / r).powi(2) } else { f64::NAN },
                }
            })
            .collect();
        out.sort_by(|a, b| b.deviation.total_cmp(&a.deviation));
        out
    }
}

/// The bands of `quantities` over `motion` from `state`, when each of
/// `dims` is within its tolerance. The results of the dynamics (drive,
/// stresses, reactions, pin forces, shaking, energies) take the
/// sensitivities of inverse dynamics with the mass and load model
/// `dynamics`; without one they, like det(D^c), have NaN bands, as has any
/// quantity at a position where its sensitivities do not exist (a limit
/// position). Fails when position 1 cannot be computed; a motion that
/// stops early gives the positions it reached.
#[allow(clippy::too_many_arguments)]
pub fn bands(
    mech: &Mechanism,
    state: &mut State,
    motion: &Motion,
    params: &Params,
    dynamics: Option<&Dynamics>,
    dims: &[Toleranced],
    quantities: &[Quantity],
) -> Result<Bands, SolveError> {
    let vars: Vec<DesignVar> = dims.iter().map(|d| d.var).collect();
    let t: Vec<f64> = dims.iter().map(|d| d.t).collect();
    let nj = mech.n_dof();
    let mut all = quantities.to_vec();
    all.extend((0..nj).map(Quantity::Input));
    let run = match dynamics.filter(|_| quantities.iter().any(Quantity::is_dynamic)) {
        Some(d) => super::dynamic_design::evaluate(mech, state, motion, params, d, &vars, &[], &all)?,
        None => evaluate(mech, state, motion, params, &vars, &all, &[])?,
    };
    let (n, nb, na, nv) = (run.positions, quantities.len(), all.len(), vars.len());
    let mut out = Bands {
        report: run.report,
        positions: n,
        tolerances: t,
        inputs: Vec::with_capacity(n * nj),
        values: Vec::with_capacity(n * nb),
        sensitivity: Vec::with_capacity(n * nb * nv),
        worst: Vec::with_capacity(n * nb),
        rss: Vec::with_capacity(n * nb),
        widest: Vec::with_capacity(nb),
    };
    for p in 0..n {
        out.values.extend_from_slice(&run.values[p * na..p * na + nb]);
        out.inputs.extend_from_slice(&run.values[p * na + nb..(p + 1) * na]);
        out.sensitivity.extend_from_slice(&run.gradient[p * na * nv..(p * na + nb) * nv]);
        for q in 0..nb {
            let (w, r) = Bands::of(&run.gradient[(p * na + q) * nv..(p * na + q + 1) * nv], &out.tolerances);
            out.worst.push(w);
            out.rss.push(r);
        }
    }
    for q in 0..nb {
        // The first position of the largest finite W.
        let mut at: Option<usize> = None;
        for p in 0..n {
            let w = out.worst[p * nb + q];
            if w.is_finite() && at.is_none_or(|a| w > out.worst[a * nb + q]) {
                at = Some(p);
            }
        }
        out.widest.push(at.map(|p| Widest {
            position: p,
            shares: Bands::shares(&out.sensitivity[(p * nb + q) * nv..(p * nb + q + 1) * nv], &out.tolerances),
        }));
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::Bands;

    #[test]
    fn worst_case_rss_and_shares_of_one_position() {
        // s = (2, -3, 0), t = (0.1, 0.2, 0.5): deviations 0.2, 0.6, 0.
        let (s, t) = ([2.0, -3.0, 0.0], [0.1, 0.2, 0.5]);
        let (w, r) = Bands::of(&s, &t);
        assert!((w - 0.8).abs() < 1e-15);
        assert!((r - 0.4_f64.sqrt()).abs() < 1e-15);
        let shares = Bands::shares(&s, &t);
        assert_eq!(shares.iter().map(|x| x.dim).collect::<Vec<_>>(), [1, 0, 2]);
        assert!((shares[0].of_worst - 0.75).abs() < 1e-15);
        assert!((shares[0].of_variance - 0.9).abs() < 1e-15);
        assert_eq!(shares[2].of_worst, 0.0);
    }

    #[test]
    fn a_band_without_any_deviation_has_no_shares() {
        let shares = Bands::shares(&[0.0, 0.0], &[0.1, 0.2]);
        assert!(shares.iter().all(|s| s.of_worst.is_nan() && s.of_variance.is_nan()));
    }
}
