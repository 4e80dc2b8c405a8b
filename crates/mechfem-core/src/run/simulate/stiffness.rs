//! When a simulation is stiff: the integrator's steps held by its
//! stability far below what its outputs need.

/// One evaluation of the equations by the integrator: time, state and
/// derivative.
pub(super) struct Evaluation {
    pub(super) t: f64,
    pub(super) y: Vec<f64>,
    pub(super) dy: Vec<f64>,
}

/// Why a stiff simulation stops.
pub(super) const STIFF_REASON: &str = "the motion became stiff (a very stiff spring or damper?): the integrator's \
                                       steps are held by its stability to less than 1/2000 of the output interval, \
                                       and an explicit method would need very many steps";

/// The stiffness test of Hairer and Wanner (Solving ODEs II, section IV.2,
/// as in their DOPRI5), which `Dopri5`'s own test is, with one condition
/// more: stiffness is a problem only when it is expensive.
///
/// Dormand and Prince's last two stages are both at the step's end, so
/// `rho = |k7 - k6| / |y7 - y6|` estimates the largest |eigenvalue| of the
/// equations' Jacobian, and `h rho` near the method's stability bound
/// (3.25) says that stability, not accuracy, holds the step. That is also
/// true of every motion that has come to rest: nothing limits the step but
/// stability, and it settles near the bound, one to two steps per period of
/// the mechanism's own slowest oscillation. Such a step is not short and
/// the motion not expensive; only a step held far below the output interval
/// (a very stiff spring's oscillation, far faster than anything the
/// outputs show) is. So a step counts as stiff when `h rho > 3.25` and it
/// is shorter than 1/2000 of the output interval (the step budget's
/// average); fifteen of them with fewer than six others in between stop
/// the simulation, as in DOPRI5.
#[derive(Default)]
pub(super) struct Stiffness {
    /// Stiff steps counted, and other steps since the last stiff one.
    stiff: u32,
    calm: u32,
}

impl Stiffness {
    /// Whether the step of length `h` just accepted, whose last two
    /// evaluations are `evals`, makes the motion stiff.
    pub(super) fn stiff(&mut self, h: f64, dt: f64, evals: &[Evaluation; 2]) -> bool {
        let [stage6, stage7] = evals;
        // Both at the step's end, or the step is not what it is taken for.
        if stage6.t != stage7.t {
            return false;
        }
        let distance = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(a, b)| (a - b) * (a - b)).sum::<f64>().sqrt();
        let (num, den) = (distance(&stage7.dy, &stage6.dy), distance(&stage7.y, &stage6.y));
        let held = den > 0.0 && h * num > 3.25 * den;
        if held && h * 2000.0 < dt {
            self.calm = 0;
            self.stiff += 1;
            return self.stiff >= 15;
        }
        self.calm += 1;
        if self.calm >= 6 {
            self.stiff = 0;
        }
        false
    }
}
