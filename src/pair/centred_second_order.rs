//! Second-order patch derivatives written around a centre, for tight interval Taylor
//! coefficients of the tangential field.
//!
//! The tangential field needs `S_uu, S_uv, S_vv`. Evaluated from Bernstein sums over a box,
//! their large terms cancel and interval (and interval Taylor) arithmetic overestimates badly;
//! the validated engine then takes tiny steps. Written in the power basis around a centre
//! `(cu, cv)` the terms are powers of the small offsets `u − cu`, `v − cv`, as
//! [`RationalBezierPatch::scaled_partials_centred`] does for first order.

use crate::geometry::bernstein::{bernstein_products as bernstein, binomial};
use crate::geometry::RationalBezierPatch;
use crate::pair::field::ScalarSurface;
use crate::Scalar;

/// A surface whose point and first and second partials can also be written around a centre.
pub trait CentredSecondOrder: ScalarSurface {
    /// `[S, S_u, S_v, S_uu, S_uv, S_vv]` at `(u, v)`, written around `(cu, cv)`: the same
    /// function for every centre (only interval widths change). The default ignores the centre.
    fn second_order_centred<T: Scalar>(&self, u: T, v: T, cu: T, cv: T) -> [[T; 3]; 6] {
        let _ = (cu, cv);
        self.second_order(u, v)
    }
}

/// `[x⁰, x¹, …, xᵈ]`.
fn powers<T: Scalar>(x: T, d: usize) -> Vec<T> {
    let mut out = vec![T::one(); d + 1];
    for i in 1..=d {
        out[i] = out[i - 1] * x;
    }
    out
}

impl CentredSecondOrder for RationalBezierPatch {
    fn second_order_centred<T: Scalar>(&self, u: T, v: T, cu: T, cv: T) -> [[T; 3]; 6] {
        centred_orders(self, u, v, cu, cv, 6)
    }
}

impl RationalBezierPatch {
    /// `[S, S_u, S_v]` at `(u, v)`, written around `(cu, cv)`: the first three of
    /// [`CentredSecondOrder::second_order_centred`], without the work of the second partials.
    pub(crate) fn first_order_centred<T: Scalar>(&self, u: T, v: T, cu: T, cv: T) -> [[T; 3]; 3] {
        let [s, su, sv, ..] = centred_orders(self, u, v, cu, cv, 3);
        [s, su, sv]
    }
}

/// The first `orders` (3: the point and first partials; 6: and the second partials) of
/// `[S, S_u, S_v, S_uu, S_uv, S_vv]` at `(u, v)` written around `(cu, cv)`; the others zero.
#[allow(clippy::needless_range_loop)] // index arithmetic mirrors the formulas
fn centred_orders<T: Scalar>(
    patch: &RationalBezierPatch,
    u: T,
    v: T,
    cu: T,
    cv: T,
    orders: usize,
) -> [[T; 3]; 6] {
    let [m, n] = patch.degree();
    let [[cs, cr], [ds, dr], [ku, kv]] = patch.centred_offsets(u, v, cu, cv);
    let z = T::zero();
    // The net's forward differences, in the order of the loops below.
    let mut differences = patch.net_differences().iter();
    // Power coefficients at the centre: T_kl = C(m,k) C(n,l) Σ Δₛᵏ Δᵣˡ h_ij B_i^{m−k}(cs) B_j^{n−l}(cr).
    let mut t = vec![[z; 4]; (m + 1) * (n + 1)];
    // The Bernstein values of every degree the sums need, each once.
    let brs: Vec<Vec<T>> = (0..=n).map(|l| bernstein(n - l, cr)).collect();
    for k in 0..=m {
        let bs = bernstein(m - k, cs);
        for (l, br) in brs.iter().enumerate() {
            let mut acc = [z; 4];
            for i in 0..=m - k {
                for j in 0..=n - l {
                    let diff = differences
                        .next()
                        .map_or([z; 4], |d| d.map(T::from_interval));
                    let w = bs[i] * br[j];
                    for x in 0..4 {
                        acc[x] = acc[x] + w * diff[x];
                    }
                }
            }
            let scale = T::from_f64(binomial(m, k) * binomial(n, l));
            t[k * (n + 1) + l] = acc.map(|x| x * scale);
        }
    }
    // H and its partials in the normalised offsets.
    let (ps, pr) = (powers(ds, m), powers(dr, n));
    let mut h = [[z; 4]; 6]; // H, H_s, H_r, H_ss, H_sr, H_rr
    for k in 0..=m {
        for l in 0..=n {
            let c = t[k * (n + 1) + l];
            let (kf, lf) = (k as f64, l as f64);
            let mut terms = [(T::one(), true); 6];
            terms[0].0 = ps[k] * pr[l];
            terms[1] = if k >= 1 {
                (T::from_f64(kf) * ps[k - 1] * pr[l], true)
            } else {
                (z, false)
            };
            terms[2] = if l >= 1 {
                (T::from_f64(lf) * ps[k] * pr[l - 1], true)
            } else {
                (z, false)
            };
            terms[3] = if k >= 2 {
                (T::from_f64(kf * (kf - 1.0)) * ps[k - 2] * pr[l], true)
            } else {
                (z, false)
            };
            terms[4] = if k >= 1 && l >= 1 {
                (T::from_f64(kf * lf) * ps[k - 1] * pr[l - 1], true)
            } else {
                (z, false)
            };
            terms[5] = if l >= 2 {
                (T::from_f64(lf * (lf - 1.0)) * ps[k] * pr[l - 2], true)
            } else {
                (z, false)
            };
            for (slot, (f, used)) in h.iter_mut().zip(terms).take(orders) {
                if used {
                    for x in 0..4 {
                        slot[x] = slot[x] + f * c[x];
                    }
                }
            }
        }
    }
    // Quotient rule for S = H/w in (s, r), then the chain rule to (u, v).
    let inv_w = T::one() / h[0][3];
    let mut out = [[z; 3]; 6];
    for x in 0..3 {
        let s = h[0][x] * inv_w;
        let ss = (h[1][x] - s * h[1][3]) * inv_w;
        let sr = (h[2][x] - s * h[2][3]) * inv_w;
        out[0][x] = s;
        out[1][x] = ss * ku;
        out[2][x] = sr * kv;
        if orders < 6 {
            continue;
        }
        let sss = (h[3][x] - T::from_f64(2.0) * ss * h[1][3] - s * h[3][3]) * inv_w;
        let ssr = (h[4][x] - ss * h[2][3] - sr * h[1][3] - s * h[4][3]) * inv_w;
        let srr = (h[5][x] - T::from_f64(2.0) * sr * h[2][3] - s * h[5][3]) * inv_w;
        out[3][x] = sss * ku * ku;
        out[4][x] = ssr * ku * kv;
        out[5][x] = srr * kv * kv;
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::numeric::scalar::{interval, point};
    use inari::Interval;

    #[test]
    fn the_cached_differences_do_not_change_equality() {
        let p = crate::pair::fixtures::wavy_patch(true);
        let fresh = p.clone();
        let _ = p.second_order_centred(0.1, 0.6, 0.3, 1.1);
        assert!(!p.net_differences().is_empty());
        assert_eq!(p, fresh);
    }

    #[test]
    fn centred_derivatives_equal_the_bernstein_ones_and_are_tighter() {
        let p = crate::pair::fixtures::wavy_patch(true);
        for k in 0..30 {
            let (u, v) = (-1.0 + 0.1 * k as f64, 0.5 + 0.033 * k as f64);
            let want = p.second_order(u, v);
            let got = p.second_order_centred(u, v, 0.3, 1.1);
            for (a, b) in want.iter().zip(&got) {
                for x in 0..3 {
                    assert!(
                        (a[x] - b[x]).abs() < 1e-9 * (1.0 + a[x].abs()),
                        "{a:?} vs {b:?}"
                    );
                }
            }
        }
        // Over a small box: both enclose the point values, the centred form is tighter.
        let (u, v) = (
            interval(0.299, 0.301).unwrap(),
            interval(1.099, 1.101).unwrap(),
        );
        let plain: [[Interval; 3]; 6] = p.second_order(u, v);
        let centred = p.second_order_centred(u, v, point(0.3), point(1.1));
        let at = p.second_order(0.3005, 1.0995);
        let (mut wp, mut wc) = (0.0f64, 0.0f64);
        for d in 0..6 {
            for x in 0..3 {
                assert!(centred[d][x].contains(at[d][x]) && plain[d][x].contains(at[d][x]));
                wp = wp.max(plain[d][x].wid());
                wc = wc.max(centred[d][x].wid());
            }
        }
        assert!(wc < wp, "centred {wc:e} vs plain {wp:e}");
    }
}
