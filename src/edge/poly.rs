//! Interval polynomials of one span: the reported curve re-expanded on `u ∈ [0, 1]`, conversions
//! between the power and the Bernstein basis, and Taylor shifts. Every result is an enclosure of
//! the exact one (outward rounding by `inari`).

use crate::numeric::scalar::point;
use inari::Interval;

/// The degree of a link's reported polynomial (the cover chain's predictor degree).
pub(crate) const DEGREE: usize = crate::certify::PREDICTOR_DEGREE;

/// The degree of the coarse curves (the 3D curve and the p-curves).
pub(crate) const SPLINE_DEGREE: usize = 8;

/// Coefficients `c[k]` of `Σ c[k]·uᵏ`, `D` components, `N − 1` the degree.
pub(crate) type PolyN<const N: usize, const D: usize> = [[Interval; D]; N];

/// A link's reported polynomial: degree [`DEGREE`].
pub(crate) type Poly<const D: usize> = PolyN<{ DEGREE + 1 }, D>;

/// A coarse curve's polynomial on one span: degree [`SPLINE_DEGREE`].
pub(crate) type SPoly<const D: usize> = PolyN<{ SPLINE_DEGREE + 1 }, D>;

/// `C(n, k)` (exact in `f64` for the sizes used here).
pub(crate) fn binom(n: usize, k: usize) -> f64 {
    (0..k).fold(1.0, |acc, i| acc * (n - i) as f64 / (i + 1) as f64)
}

/// The coefficients of `x ↦ c(a + x)` (Taylor shift by `a`), enclosed for every `a ∈ shift`.
pub(crate) fn taylor_shift<const N: usize, const D: usize>(
    c: &PolyN<N, D>,
    shift: Interval,
) -> PolyN<N, D> {
    let mut out = *c;
    let deg = N - 1;
    // Repeated synthetic division: after pass k, out[k] is final.
    for k in 0..deg {
        for i in (k..deg).rev() {
            let (here, next) = out.split_at_mut(i + 1);
            for (v, n) in here[i].iter_mut().zip(&next[0]) {
                *v += shift * *n;
            }
        }
    }
    out
}

/// The reported polynomial of a tube piece (`f64` coefficients in `τ`, padded to [`DEGREE`]) as
/// a polynomial in `u` with `τ = ta + (tb − ta)·u`, enclosed for the exact real `tb − ta`.
pub(crate) fn reparametrised(coeffs: &[[f64; 4]], ta: f64, tb: f64) -> Poly<4> {
    let mut c = [[point(0.0); 4]; DEGREE + 1];
    for (k, row) in coeffs.iter().enumerate().take(DEGREE + 1) {
        c[k] = row.map(point);
    }
    let shifted = taylor_shift(&c, point(ta));
    let len = point(tb) - point(ta);
    let mut pow = point(1.0);
    let mut out = shifted;
    for row in out.iter_mut() {
        for v in row.iter_mut() {
            *v *= pow;
        }
        pow *= len;
    }
    out
}

#[cfg(test)]
/// Bernstein (Bézier) coefficients on `[0, 1]` of the power-basis polynomial `c`:
/// `b_i = Σ_{k ≤ i} C(i, k) / C(n, k) · c_k`.
pub(crate) fn bezier_from_power<const N: usize, const D: usize>(c: &PolyN<N, D>) -> PolyN<N, D> {
    std::array::from_fn(|i| {
        std::array::from_fn(|d| {
            (0..=i).fold(point(0.0), |acc, k| {
                acc + point(binom(i, k)) / point(binom(N - 1, k)) * c[k][d]
            })
        })
    })
}

/// Power-basis coefficients of the Bézier polynomial with control points `b`:
/// `c_k = C(n, k)·Σ_{i ≤ k} C(k, i)·(−1)^{k−i}·b_i`.
pub(crate) fn power_from_bezier<const N: usize, const D: usize>(b: &PolyN<N, D>) -> PolyN<N, D> {
    std::array::from_fn(|k| {
        std::array::from_fn(|d| {
            let s = (0..=k).fold(point(0.0), |acc, i| {
                let sign = if (k - i) % 2 == 0 { 1.0 } else { -1.0 };
                acc + point(sign * binom(k, i)) * b[i][d]
            });
            point(binom(N - 1, k)) * s
        })
    })
}

/// Horner enclosure of `c` over `u ∈ x`, component `d`.
pub(crate) fn eval<const N: usize, const D: usize>(
    c: &PolyN<N, D>,
    x: Interval,
    d: usize,
) -> Interval {
    c.iter().rev().fold(point(0.0), |acc, row| acc * x + row[d])
}

/// `f64` value of the midpoint polynomial at `u` (guidance only).
pub(crate) fn eval_mid<const N: usize, const D: usize>(c: &PolyN<N, D>, u: f64) -> [f64; D] {
    std::array::from_fn(|d| c.iter().rev().fold(0.0, |acc, row| acc * u + row[d].mid()))
}

/// An upper bound of `sqrt(Σ vᵢ²)` over the box `v` (`+∞` if unbounded).
pub(crate) fn norm_sup(v: &[Interval]) -> f64 {
    let s = v.iter().fold(point(0.0), |acc, x| acc + x.sqr());
    let r = s.sqrt().sup();
    if r.is_nan() {
        f64::INFINITY
    } else {
        r
    }
}

/// An upper bound of `a + b` (rounded up).
pub(crate) fn add_up(a: f64, b: f64) -> f64 {
    (point(a) + point(b)).sup()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bezier_round_trip_and_shift() {
        let b = [[1.0], [2.0], [-1.0], [0.5], [3.0], [0.25]];
        let c = power_from_bezier(&b.map(|r| r.map(point)));
        let back = bezier_from_power(&c);
        for i in 0..b.len() {
            assert!(back[i][0].contains(b[i][0]));
        }
        // c(1 + x) at x = 0 is c(1) = b_5.
        let s = taylor_shift(&c, point(1.0));
        assert!(s[0][0].contains(0.25));
        let r = reparametrised(&[[1.0, 2.0, 0.0, 0.0], [3.0, 0.0, 0.0, 0.0]], 1.0, 3.0);
        // 1 + 3τ with τ = 1 + 2u: 4 + 6u.
        assert!(r[0][0].contains(4.0) && r[1][0].contains(6.0));
    }
}
