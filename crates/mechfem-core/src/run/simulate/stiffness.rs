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
pub(super) const STIFF_REASON: &str = "the motion became stiff (a very stiff spring or damper?): the explicit \
                                       integrator's steps are held by its stability to less than 1/2000 of the \
                                       output interval (let `INTEGRATOR auto` or `INTEGRATOR implicit` integrate it)";

/// The stiffness test of Hairer and Wanner (Solving ODEs II, section IV.2,
/// as in their DOPRI5 and DOP853), with one condition more for an explicit
/// method that must not switch: stiffness is a problem only when it is
/// expensive.
///
/// The method's last stage and the next step's first are both at the
/// step's end, so `rho = |f1 - f2| / |y1 - y2|` estimates the largest
/// |eigenvalue| of the equations' Jacobian, and `h rho` near the method's
/// stability bound (3.25 for Dormand-Prince 5(4), 6.1 for DOP853) says that
/// stability, not accuracy, holds the step. That is also true of every
/// motion that has come to rest: nothing limits the step but stability,
/// and it settles near the bound, one to two steps per period of the
/// mechanism's own slowest oscillation. For the automatic choice that is
/// reason enough to go implicit; an explicit method chosen by the deck
/// stops only when the step is held far below the output interval (a very
/// stiff spring's oscillation, far faster than anything the outputs show),
/// shorter than 1/2000 of it (the step budget's average). Fifteen stiff
/// steps with fewer than six others in between make the motion stiff, as
/// in DOPRI5.
pub(super) struct Stiffness {
    /// Stiff steps counted, and other steps since the last stiff one.
    stiff: u32,
    calm: u32,
    /// The method's stability bound on `h rho`.
    bound: f64,
    /// Whether only steps far below the output interval count.
    costly_only: bool,
}

/// The share of the stability bound on `h rho` from which a step of the
/// automatic choice counts as held by stability: well above the `h rho`
/// of the accuracy-limited steps of a smooth motion (below 0.65 of the
/// bound on Andrews' squeezing mechanism after its first steps).
const AUTO_SHARE: f64 = 0.7;

/// The share for a step of the automatic choice shorter than 1/2000 of the
/// output interval: such a step is a cost, and within a factor of four of
/// the bound it is stability that holds it.
const AUTO_SHARE_COSTLY: f64 = 0.25;

impl Stiffness {
    pub(super) fn new(bound: f64, costly_only: bool) -> Stiffness {
        Stiffness { stiff: 0, calm: 0, bound, costly_only }
    }

    /// Whether the step of length `h` just accepted, ending at `t`, makes
    /// the motion stiff; `sys` holds its last evaluations.
    pub(super) fn stiff(&mut self, h: f64, t: f64, dt: f64, sys: &super::system::System<'_>) -> bool {
        let distance = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(a, b)| (a - b) * (a - b)).sum::<f64>().sqrt();
        // At a tight tolerance the step-size control settles just inside
        // the stability bound (h rho near 0.85 of it on a stiff damper at
        // 1e-10), where Hairer's test (above the bound) rarely fires and an
        // automatic choice would integrate a stiff motion explicitly for
        // hundreds of thousands of steps: the automatic choice counts a
        // step from `AUTO_SHARE` of the bound on.
        // A step far below the output interval is counted from a lower
        // share still: at 1e-12 the step settles at half the bound there.
        let share = match (self.costly_only, h * 2000.0 < dt) {
            (true, _) => 1.0,
            (false, false) => AUTO_SHARE,
            (false, true) => AUTO_SHARE_COSTLY,
        };
        let held = sys.pair_at(t, |a, b| h * distance(&a.dy, &b.dy) > share * self.bound * distance(&a.y, &b.y));
        if held && (!self.costly_only || h * 2000.0 < dt) {
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
