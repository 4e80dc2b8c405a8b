//! Finite-difference checks shared by the element tests: first derivatives
//! against central differences of the value, second derivatives against
//! central differences of the first derivatives, and the directional second
//! derivatives of [`ElementType::second`] against the Hessian.

use super::{hess_product, ElementType, FormEval, Order};

/// A small seeded generator (xorshift64*) so the sweeps are repeatable
/// without a dependency.
pub(crate) struct Rng(u64);

impl Rng {
    pub fn new(seed: u64) -> Rng {
        Rng(seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1)
    }
    /// Uniform in [lo, hi).
    pub fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        let r = self.0.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11;
        lo + (hi - lo) * (r as f64 / (1u64 << 53) as f64)
    }
}

fn eval(ty: ElementType, form: usize, x: &[f64], order: Order) -> FormEval {
    let mut out = FormEval::default();
    // A fresh branch: the principal value, as at a model's first evaluation.
    let mut branch = f64::NAN;
    ty.eval(form, x, &mut branch, order, &mut out).expect("element evaluation failed");
    out
}

/// Checks every form parameter of `ty` at `x`; panics with a description of
/// the worst entry when a derivative is off by more than `tol` relative to
/// the scale of the derivatives.
pub(crate) fn check_derivatives(ty: ElementType, x: &[f64], tol: f64) {
    let n = ty.n_coords();
    for form in 0..ty.form_names().len() {
        let mut centre_branch = f64::NAN;
        let mut centre = FormEval::default();
        ty.eval(form, x, &mut centre_branch, Order::Second, &mut centre).unwrap();
        let order0 = eval(ty, form, x, Order::Value);
        assert_eq!(order0.value, centre.value, "{} value depends on the order asked", ty.name());
        let h = 1e-5 * (1.0 + x.iter().fold(0.0f64, |m, v| m.max(v.abs())));
        let scale1 = 1.0 + centre.grad[..n].iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let scale2 = 1.0 + centre.hess[..n].iter().flat_map(|r| r[..n].iter()).fold(0.0f64, |m, v| m.max(v.abs()));
        // A first-order evaluation gives the gradient of a second-order one.
        let order1 = eval(ty, form, x, Order::First);
        assert_eq!(order1.value, centre.value, "{} value depends on the order asked", ty.name());
        for k in 0..n {
            let d = (order1.grad[k] - centre.grad[k]).abs() / scale1;
            assert!(d < 1e-14, "{} {} gradient depends on the order asked", ty.name(), ty.form_names()[form]);
        }
        // Outside the declared dependencies the value does not change at
        // all, and every derivative is exactly zero.
        let mask = ty.depends(form);
        assert!(mask != 0 && mask < 1 << n, "{} {} dependency mask", ty.name(), ty.form_names()[form]);
        for k in (0..n).filter(|&k| mask & (1 << k) == 0) {
            let mut moved = x.to_vec();
            moved[k] += 0.37 * (1.0 + x[k].abs());
            let (name, form_name) = (ty.name(), ty.form_names()[form]);
            assert_eq!(eval(ty, form, &moved, Order::Value).value, centre.value, "{name} {form_name} depends on {k}");
            assert_eq!(centre.grad[k], 0.0, "{name} {form_name} gradient {k}");
            assert!(centre.hess[k][..n].iter().all(|&v| v == 0.0), "{name} {form_name} Hessian row {k}");
        }
        // The directional second derivative is the Hessian contracted with
        // two directions (here two directions made from x itself).
        let a: Vec<f64> = (0..n).map(|k| (1.3 * k as f64 + x[0]).sin()).collect();
        let b: Vec<f64> = (0..n).map(|k| (0.7 * k as f64 - x[n - 1]).cos()).collect();
        for (p, q, first) in [(&a, &b, &order1), (&a, &a, &centre), (&b, &a, &order1)] {
            let want = hess_product(&centre, n, p, q);
            let got = ty.second(form, x, first, p, q);
            assert!(
                (got - want).abs() < 1e-12 * scale2 * n as f64,
                "{} {} second derivative along directions: {} vs Hessian {} at {:?}",
                ty.name(),
                ty.form_names()[form],
                got,
                want,
                x
            );
        }
        for k in 0..n {
            let mut xp = x.to_vec();
            let mut xm = x.to_vec();
            xp[k] += h;
            xm[k] -= h;
            // Evaluate on the centre's branch so the value is continuous.
            let (mut bp, mut bm) = (centre_branch, centre_branch);
            let (mut ep, mut em) = (FormEval::default(), FormEval::default());
            ty.eval(form, &xp, &mut bp, Order::First, &mut ep).unwrap();
            ty.eval(form, &xm, &mut bm, Order::First, &mut em).unwrap();
            let fd1 = (ep.value - em.value) / (2.0 * h);
            let err1 = (fd1 - centre.grad[k]).abs() / scale1;
            assert!(
                err1 < tol,
                "{} {} d/dx{}: analytic {} vs fd {} at {:?}",
                ty.name(),
                ty.form_names()[form],
                k,
                centre.grad[k],
                fd1,
                x
            );
            for l in 0..n {
                let fd2 = (ep.grad[l] - em.grad[l]) / (2.0 * h);
                let err2 = (fd2 - centre.hess[k][l]).abs() / scale2;
                assert!(
                    err2 < tol,
                    "{} {} d2/dx{}dx{}: analytic {} vs fd {} at {:?}",
                    ty.name(),
                    ty.form_names()[form],
                    k,
                    l,
                    centre.hess[k][l],
                    fd2,
                    x
                );
                let asym = (centre.hess[k][l] - centre.hess[l][k]).abs() / scale2;
                assert!(asym < 1e-14, "{} Hessian not symmetric", ty.name());
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Random configurations: co-ordinates in [-2, 2], angle co-ordinates
    /// over several revolutions. Points that must not coincide are kept at
    /// least 0.2 apart so the check measures the derivatives, not the
    /// conditioning.
    fn sweep(ty: ElementType, seed: u64, valid: impl Fn(&[f64]) -> bool) {
        let mut rng = Rng::new(seed);
        let mut checked = 0;
        while checked < 500 {
            let x: Vec<f64> = (0..ty.n_coords()).map(|_| rng.uniform(-2.0, 2.0)).collect();
            if !valid(&x) {
                continue;
            }
            check_derivatives(ty, &x, 2e-6);
            checked += 1;
        }
    }

    fn apart(x: &[f64], p: usize, q: usize) -> bool {
        (x[q] - x[p]).hypot(x[q + 1] - x[p + 1]) > 0.2
    }

    #[test]
    fn bin_derivatives_match_finite_differences() {
        sweep(ElementType::Bin, 1, |x| apart(x, 0, 2));
    }

    #[test]
    fn hlf_derivatives_match_finite_differences() {
        sweep(ElementType::Hlf, 2, |_| true);
    }

    #[test]
    fn tr1_derivatives_match_finite_differences() {
        sweep(ElementType::Tr1, 3, |_| true);
    }

    #[test]
    fn tr1_is_defined_when_r_coincides_with_p() {
        check_derivatives(ElementType::Tr1, &[0.3, -0.2, 1.1, 0.3, -0.2], 2e-6);
    }

    #[test]
    fn tr2_derivatives_match_finite_differences() {
        sweep(ElementType::Tr2, 4, |x| apart(x, 0, 2));
    }

    #[test]
    fn crd_derivatives_match_finite_differences() {
        sweep(ElementType::Crd, 5, |_| true);
    }

    #[test]
    fn gr1_derivatives_match_finite_differences() {
        sweep(ElementType::Gr1, 6, |_| true);
    }

    #[test]
    fn gr2_derivatives_match_finite_differences() {
        sweep(ElementType::Gr2, 7, |x| x[3].abs() > 0.2 && x[4].abs() > 0.2);
    }

    #[test]
    fn rk1_derivatives_match_finite_differences() {
        sweep(ElementType::Rk1, 8, |_| true);
    }

    #[test]
    fn rk2_derivatives_match_finite_differences() {
        sweep(ElementType::Rk2, 9, |x| apart(x, 0, 2));
    }

    /// Belt with a span: the centre distance exceeds |R_P - R_Q| by a margin.
    fn belt_ok(x: &[f64], margin: f64) -> bool {
        let l = (x[3] - x[0]).hypot(x[4] - x[1]);
        l > 0.2 && l > (x[6] - x[7]).abs() * (1.0 + margin) + 0.05
    }

    #[test]
    fn blt_derivatives_match_finite_differences() {
        sweep(ElementType::Blt, 10, |x| belt_ok(x, 0.05));
    }

    #[test]
    fn blt_derivatives_hold_near_the_limit_of_its_span() {
        // l* / l down to about 0.03: the second derivatives grow like 1/l*.
        for (k, eps) in [1e-1, 1e-2, 1e-3].into_iter().enumerate() {
            let (rp, rq) = (1.3, -0.4 + 0.1 * k as f64);
            let l = (rp - rq) * (1.0 + eps);
            let x = [0.2, -0.1, 0.7, 0.2 + l * 0.6, -0.1 + l * 0.8, -2.0, rp, rq];
            check_derivatives(ElementType::Blt, &x, 5e-5);
        }
    }

    #[test]
    fn blt_without_span_is_an_error() {
        let mut out = FormEval::default();
        let mut b = f64::NAN;
        let x = [0.0, 0.0, 0.0, 0.5, 0.0, 0.0, 1.0, 0.3];
        let r = ElementType::Blt.eval(2, &x, &mut b, Order::Value, &mut out);
        assert!(matches!(r, Err(crate::error::ElementError::NoBeltSpan { .. })));
    }

    #[test]
    fn gr2_with_zero_radius_is_an_error() {
        let mut out = FormEval::default();
        let mut b = f64::NAN;
        let r = ElementType::Gr2.eval(0, &[0.0, 0.0, 0.0, 1.0, 0.0], &mut b, Order::Value, &mut out);
        assert!(matches!(r, Err(crate::error::ElementError::ZeroRadius { name: "R_c" })));
    }

    #[test]
    fn every_catalogue_type_is_swept() {
        // Guards against adding a type without a derivative sweep above.
        assert_eq!(ElementType::ALL.len(), 10);
    }

    #[test]
    fn bin_reports_coincident_points() {
        // Length and angle, at every order (the angle's value alone is
        // checked on the squared length), and a point at infinity.
        let mut out = FormEval::default();
        for x in [[1.0, 2.0, 1.0, 2.0], [1.0, 2.0, f64::INFINITY, 2.0], [0.0, 0.0, 1e200, 0.0]] {
            for form in 0..2 {
                for order in [Order::Value, Order::First, Order::Second] {
                    let mut b = f64::NAN;
                    let r = ElementType::Bin.eval(form, &x, &mut b, order, &mut out);
                    assert!(matches!(r, Err(crate::error::ElementError::CoincidentPoints)), "{x:?} {form} {order:?}");
                }
            }
        }
    }

    #[test]
    fn angle_is_tracked_across_the_branch_cut() {
        let mut out = FormEval::default();
        let mut b = f64::NAN;
        ElementType::Bin.eval(1, &[0.0, 0.0, -1.0, 0.1], &mut b, Order::Value, &mut out).unwrap();
        assert!(out.value > 3.0);
        // Just below the negative x axis: principal value near -pi, tracked near +pi.
        ElementType::Bin.eval(1, &[0.0, 0.0, -1.0, -0.1], &mut b, Order::Value, &mut out).unwrap();
        assert!((out.value - (std::f64::consts::PI + 0.1f64.atan())).abs() < 1e-12);
    }
}
