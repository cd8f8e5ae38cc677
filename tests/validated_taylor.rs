//! Taylor-mode AD: coefficients and Jacobians against closed forms (computed independently in
//! interval arithmetic), the naive `Series` scheme against the tape scheme, and the domain guards.

#![allow(clippy::needless_range_loop)] // index loops mirror the formulas

mod common;

use common::intervals::meets;
use common::odes::{Rotation, Square};
use ssitrace::numeric::scalar::{interval, point};
use ssitrace::validated::series::naive_expand;
use ssitrace::validated::tape::Tape;
use ssitrace::validated::{DomainError, Expansion, OdeSystem, Series, TaylorAd};
use ssitrace::Scalar;

fn ad_for<F: OdeSystem>(f: &F) -> TaylorAd {
    TaylorAd::new(Tape::record(f).unwrap())
}

#[test]
fn y_squared_coefficients_and_jacobians_to_order_30() {
    // y = y0/(1 − y0 t) = Σ y0^{i+1} tⁱ, so yᵢ = y0^{i+1} and ∂yᵢ/∂y0 = (i+1)·y0ⁱ.
    let y0 = 0.75;
    let mut ad = ad_for(&Square);
    let mut e = Expansion::default();
    ad.expand(&[point(y0)], 30, true, &mut e).unwrap();
    for i in 0..=30 {
        let want = point(y0).powi(i as i32 + 1);
        let got = e.coeff(i)[0];
        assert!(meets(got, want), "y_{i}: {got:?} vs {want:?}");
        assert!(got.wid() <= 1e-13 * want.mag(), "y_{i} too wide: {got:?}");
    }
    for i in 0..30 {
        let want = point((i + 1) as f64) * point(y0).powi(i as i32);
        let got = e.jacobian(i)[0];
        assert!(meets(got, want), "J_{i}: {got:?} vs {want:?}");
        assert!(got.wid() <= 1e-13 * want.mag());
    }
}

#[test]
fn rotation_coefficients_and_jacobians_are_the_exponential_series() {
    // z = x + iy, z' = iz: z_m = iᵐ/m!·z0. With z0 = 1: x_m = Re(iᵐ)/m!, y_m = Im(iᵐ)/m!.
    let mut ad = ad_for(&Rotation);
    let mut e = Expansion::default();
    ad.expand(&[point(1.0), point(0.0)], 30, true, &mut e)
        .unwrap();
    let mut fact = point(1.0);
    for m in 0..=30usize {
        if m > 0 {
            fact *= point(m as f64);
        }
        let (re, im) = [(1.0, 0.0), (0.0, 1.0), (-1.0, 0.0), (0.0, -1.0)][m % 4];
        let (x, y) = (point(re) / fact, point(im) / fact);
        assert!(
            meets(e.coeff(m)[0], x) && meets(e.coeff(m)[1], y),
            "order {m}"
        );
        if m < 30 {
            // J_m = Gᵐ/m! with G = [[0,−1],[1,0]]: Gᵐ = [[re, −im], [im, re]].
            let j = e.jacobian(m);
            let want = [x, -y, y, x];
            for (g, w) in j.iter().zip(&want) {
                assert!(meets(*g, *w), "J_{m}: {j:?}");
            }
        }
    }
}

struct Reciprocal;
impl OdeSystem for Reciprocal {
    fn dim(&self) -> usize {
        1
    }
    fn eval<S: Scalar>(&self, y: &[S]) -> Vec<S> {
        vec![S::one() / y[0]]
    }
}

struct Root;
impl OdeSystem for Root {
    fn dim(&self) -> usize {
        1
    }
    fn eval<S: Scalar>(&self, y: &[S]) -> Vec<S> {
        vec![y[0].sqrt()]
    }
}

#[test]
fn division_and_square_root_recurrences_match_binomial_series() {
    // y' = 1/y, y(0) = 1: y = √(1 + 2t) = Σ C(1/2, i)·2ⁱ·tⁱ.
    let mut ad = ad_for(&Reciprocal);
    let mut e = Expansion::default();
    ad.expand(&[point(1.0)], 25, true, &mut e).unwrap();
    let mut c = point(1.0);
    for i in 0..=25usize {
        if i > 0 {
            c = c * (point(0.5) - point((i - 1) as f64)) / point(i as f64) * point(2.0);
        }
        assert!(
            meets(e.coeff(i)[0], c),
            "1/y order {i}: {:?} vs {c:?}",
            e.coeff(i)[0]
        );
    }
    // y' = √y, y(0) = 4: y = (2 + t/2)² = 4 + 2t + t²/4; higher coefficients vanish.
    let mut ad = ad_for(&Root);
    ad.expand(&[point(4.0)], 20, true, &mut e).unwrap();
    let want = [4.0, 2.0, 0.25];
    for i in 0..=20 {
        let w = if i < 3 { want[i] } else { 0.0 };
        assert!(
            e.coeff(i)[0].contains(w),
            "√y order {i}: {:?}",
            e.coeff(i)[0]
        );
        assert!(e.coeff(i)[0].wid() < 1e-13);
    }
    // ∂y₁/∂y0 = d√y0/dy0 = 1/(2√y0) = 1/4; ∂y₂/∂y0 = 0.
    assert!(e.jacobian(1)[0].contains(0.25) && e.jacobian(2)[0].contains(0.0));
}

/// A field using every operation, for comparing the two AD schemes.
struct Mixed;
impl OdeSystem for Mixed {
    fn dim(&self) -> usize {
        3
    }
    fn eval<S: Scalar>(&self, y: &[S]) -> Vec<S> {
        let r2 = y[0].sqr() + y[1].sqr() + S::from_f64(0.5);
        vec![
            y[1] * y[2] - y[0] / r2.sqrt(),
            -y[0] + y[2].powi(3) / S::from_f64(3.0),
            S::from_interval(interval(0.1, 0.1000001).unwrap()) - y[2] * r2.powi(-2),
        ]
    }
}

#[test]
fn tape_recurrences_agree_with_naive_series_evaluation() {
    let y0 = [
        interval(0.3, 0.31).unwrap(),
        point(-0.2),
        interval(0.5, 0.5001).unwrap(),
    ];
    let naive = naive_expand(&Mixed, &y0, 30).unwrap();
    let mut ad = ad_for(&Mixed);
    let mut e = Expansion::default();
    ad.expand(&y0, 30, false, &mut e).unwrap();
    for (i, row) in naive.iter().enumerate() {
        for j in 0..3 {
            // Both enclose the same set of coefficients, so they must meet.
            assert!(meets(row[j], e.coeff(i)[j]), "order {i}, component {j}");
        }
    }
    // Point input: both are tight and agree closely.
    let p = [point(0.3), point(-0.2), point(0.5)];
    let naive = naive_expand(&Mixed, &p, 30).unwrap();
    ad.expand(&p, 30, false, &mut e).unwrap();
    for (i, row) in naive.iter().enumerate() {
        for j in 0..3 {
            let (a, b) = (row[j], e.coeff(i)[j]);
            assert!(meets(a, b));
            assert!(
                (a.mid() - b.mid()).abs() <= 1e-9 * (a.mag() + 1e-300) + 1e-15,
                "order {i}: {a:?} vs {b:?}"
            );
        }
    }
}

#[test]
fn jacobians_match_finite_differences_of_point_expansions() {
    // Non-rigorous cross-check of the derivative recurrences on the mixed field.
    let mut ad = ad_for(&Mixed);
    let base = [0.3, -0.2, 0.5];
    let mut e = Expansion::default();
    ad.expand(&base.map(point), 12, true, &mut e).unwrap();
    let step = 1e-6;
    for l in 0..3 {
        let (mut plus, mut minus) = (base, base);
        plus[l] += step;
        minus[l] -= step;
        let (mut ep, mut em) = (Expansion::default(), Expansion::default());
        ad.expand(&plus.map(point), 12, false, &mut ep).unwrap();
        ad.expand(&minus.map(point), 12, false, &mut em).unwrap();
        for i in 0..12 {
            for j in 0..3 {
                let fd = (ep.coeff(i)[j].mid() - em.coeff(i)[j].mid()) / (2.0 * step);
                let jac = e.jacobian(i)[j * 3 + l].mid();
                assert!(
                    (fd - jac).abs() < 1e-6 * (1.0 + jac.abs()),
                    "J_{i}[{j},{l}]: {jac} vs fd {fd}"
                );
            }
        }
    }
}

#[test]
fn domain_guards_reject_undefined_fields() {
    let mut ad = ad_for(&Reciprocal);
    let mut e = Expansion::default();
    assert_eq!(
        ad.expand(&[interval(-1.0, 1.0).unwrap()], 5, false, &mut e),
        Err(DomainError::DivisionByZero)
    );
    let mut ad = ad_for(&Root);
    assert_eq!(
        ad.expand(&[interval(-1.0, 1.0).unwrap()], 5, true, &mut e),
        Err(DomainError::SqrtOfNonPositive)
    );
    // The Series type marks the same cases as undefined (whole-line coefficients).
    let s = Series::new(&[interval(-1.0, 1.0).unwrap(), point(1.0)]);
    assert!(!(Series::one() / s).coeff(0).is_common_interval());
    assert!(!s.sqrt().coeff(1).is_common_interval());
}

#[test]
fn series_is_copy_and_broadcasts_constants() {
    let t = Series::new(&[point(0.0), point(1.0), point(0.0), point(0.0)]);
    let u = t; // Copy
    let p = (u + Series::from_f64(1.0)).powi(3); // (1 + t)³ = 1 + 3t + 3t² + t³
    for (i, w) in [1.0, 3.0, 3.0, 1.0].iter().enumerate() {
        assert!(p.coeff(i).contains(*w) && p.coeff(i).wid() == 0.0);
    }
    assert_eq!(p.coeffs().len(), 4);
    assert!(t.coeff(1).contains(1.0));
}
