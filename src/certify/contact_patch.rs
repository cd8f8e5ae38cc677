//! A patch as the tangential field sees it: second-order data written around a centre in the
//! power basis, with the terms that vanish identically left out.
//!
//! The validated engine pays for every operation of the recorded field that varies in time
//! (`O(k²)` per product of two such values at order `k`), while values built from constants and
//! the expansion's centre cost one evaluation. [`RationalBezierPatch`]'s own centred form
//! ([`CentredSecondOrder`]) handles any rational patch: it applies the quotient rule to the
//! homogeneous net, multiplies each derivative term separately by its monomial, and keeps terms
//! whose coefficients are zero for every centre. When all weights are one and the same exact
//! number (a polynomial patch, e.g. every `"polynomial"` scene surface), [`ContactPatch`] writes
//!
//! ```text
//! S(u, v) = Σ_{k,l} T_kl · dsᵏ · drˡ,   ds = (u − cu)/Δu,  dr = (v − cv)/Δv,
//! T_kl = C(m,k)·C(n,l)·Σ_{i,j} Δ^{k,l}p_ij · B_i^{m−k}(cs) · B_j^{n−l}(cr)
//! ```
//!
//! (the Taylor coefficients at the centre `(cs, cr)`, Δ the forward differences of the Cartesian
//! net divided by the common weight) and every partial up to order two from the same monomials,
//! each computed once. Differences that are exactly zero (a coordinate that is linear in one
//! parameter, as the `x` and `y` of a height field) drop their terms, so such partials are
//! constants of the expansion. The function is the patch's (the same polynomial, written about
//! another point); only rounding and interval widths differ, and every coefficient is an
//! outward-rounded enclosure.

use crate::geometry::bernstein::{bernstein_products as bernstein, binomial};
use crate::geometry::RationalBezierPatch;
use crate::pair::centred_second_order::CentredSecondOrder;
use crate::pair::field::ScalarSurface;
use crate::Scalar;
use inari::Interval;

/// The forward differences of a patch's net: of its Cartesian net when it is polynomial
/// ([`PowerNet::of`]), of its homogeneous net otherwise ([`PowerNet::homogeneous`]).
#[derive(Debug, Clone)]
pub(crate) struct PowerNet {
    pub(crate) m: usize,
    pub(crate) n: usize,
    /// Per `(k, l)` (index `k·(n+1) + l`) and coordinate (`x, y, z`, and the weight `w` for a
    /// homogeneous net): the differences `Δ^{k,l}p_ij` for `i ≤ m − k`, `j ≤ n − l` (index
    /// `i·(n−l+1) + j`), or `None` where all are exactly zero.
    pub(crate) diffs: Vec<Vec<Option<Vec<Interval>>>>,
}

impl PowerNet {
    /// The differences of the Cartesian net of `patch` if all its weights are the same exact
    /// (thin) number.
    pub(crate) fn of(patch: &RationalBezierPatch) -> Option<PowerNet> {
        let net = patch.homogeneous();
        let w = net.first()?[3];
        let thin = w.inf() == w.sup();
        if !thin
            || net
                .iter()
                .any(|h| h[3].inf() != w.inf() || h[3].sup() != w.sup())
        {
            return None;
        }
        // Cartesian points: the homogeneous entries divided by the common weight (exact for
        // weight 1, an enclosure otherwise).
        let points: Vec<Vec<Interval>> = net
            .iter()
            .map(|h| (0..3).map(|x| h[x] / w).collect())
            .collect();
        Some(Self::differences(patch.degree(), &points))
    }

    /// The differences of the homogeneous net `(w·x, w·y, w·z, w)` of any patch.
    pub(crate) fn homogeneous(patch: &RationalBezierPatch) -> PowerNet {
        let points: Vec<Vec<Interval>> = patch.homogeneous().iter().map(|h| h.to_vec()).collect();
        Self::differences(patch.degree(), &points)
    }

    /// The forward differences of `points` (`(m+1)·(n+1)` entries, point `(i, j)` at
    /// `i·(n+1) + j`, each with the same number of coordinates), level by level:
    /// `Δ^{k,l}p_ij = Δ^{k−1,l}p_{i+1,j} − Δ^{k−1,l}p_ij` (and in `j` for `k = 0`), each
    /// difference outward rounded, so each level costs one subtraction per entry.
    fn differences([m, n]: [usize; 2], points: &[Vec<Interval>]) -> PowerNet {
        let coords = points.first().map_or(0, |p| p.len());
        // levels[k·(n+1) + l][x]: the differences of coordinate x.
        let mut levels: Vec<Vec<Vec<Interval>>> = Vec::with_capacity((m + 1) * (n + 1));
        for k in 0..=m {
            for l in 0..=n {
                let (rows, cols) = (m - k + 1, n - l + 1);
                let level: Vec<Vec<Interval>> = (0..coords)
                    .map(|x| {
                        let mut out = Vec::with_capacity(rows * cols);
                        for i in 0..rows {
                            for j in 0..cols {
                                out.push(match (k, l) {
                                    (0, 0) => points[i * (n + 1) + j][x],
                                    (0, _) => {
                                        let prev = &levels[l - 1][x];
                                        prev[i * (cols + 1) + j + 1] - prev[i * (cols + 1) + j]
                                    }
                                    _ => {
                                        let prev = &levels[(k - 1) * (n + 1) + l][x];
                                        prev[(i + 1) * cols + j] - prev[i * cols + j]
                                    }
                                });
                            }
                        }
                        out
                    })
                    .collect();
                levels.push(level);
            }
        }
        let diffs = levels
            .into_iter()
            .map(|level| {
                level
                    .into_iter()
                    .map(|d| {
                        let zero = d.iter().all(|v| v.inf() == 0.0 && v.sup() == 0.0);
                        (!zero).then_some(d)
                    })
                    .collect()
            })
            .collect();
        PowerNet { m, n, diffs }
    }
}

/// A patch for the tangential field: [`RationalBezierPatch`] with a leaner centred second-order
/// form for polynomial patches (module documentation); everything else is the patch's own.
#[derive(Debug, Clone)]
pub struct ContactPatch<'a> {
    patch: &'a RationalBezierPatch,
    power: Option<PowerNet>,
}

impl<'a> ContactPatch<'a> {
    /// The patch, with its forward differences prepared if all its weights are equal and exact.
    pub fn new(patch: &'a RationalBezierPatch) -> Self {
        ContactPatch {
            patch,
            power: PowerNet::of(patch),
        }
    }

    /// Whether the lean polynomial form is used.
    pub fn is_polynomial(&self) -> bool {
        self.power.is_some()
    }
}

impl ScalarSurface for ContactPatch<'_> {
    fn first_order<T: Scalar>(&self, u: T, v: T) -> [[T; 3]; 3] {
        self.patch.first_order(u, v)
    }
    fn second_order<T: Scalar>(&self, u: T, v: T) -> [[T; 3]; 6] {
        self.patch.second_order(u, v)
    }
    fn scaled_first_order<T: Scalar>(&self, u: T, v: T) -> ([T; 3], [T; 3], T) {
        self.patch.scaled_first_order(u, v)
    }
    /// For a polynomial patch the partials themselves (`g = 1`: the weight is constant) from the
    /// lean centred form; otherwise the patch's own.
    fn scaled_first_order_centred<T: Scalar>(
        &self,
        u: T,
        v: T,
        cu: T,
        cv: T,
    ) -> ([T; 3], [T; 3], T) {
        match &self.power {
            Some(net) => {
                let [a, b] = self.lean_centred(net, u, v, cu, cv, [(1, 0), (0, 1)]);
                (a, b, T::one())
            }
            None => self.patch.scaled_first_order_centred(u, v, cu, cv),
        }
    }
}

/// The six partial orders `(a, b)` of `[S, S_u, S_v, S_uu, S_uv, S_vv]`.
const ORDERS: [(usize, usize); 6] = [(0, 0), (1, 0), (0, 1), (2, 0), (1, 1), (0, 2)];

impl CentredSecondOrder for ContactPatch<'_> {
    fn second_order_centred<T: Scalar>(&self, u: T, v: T, cu: T, cv: T) -> [[T; 3]; 6] {
        match &self.power {
            Some(net) => self.lean_centred(net, u, v, cu, cv, ORDERS),
            None => self.patch.second_order_centred(u, v, cu, cv),
        }
    }
}

impl ContactPatch<'_> {
    /// The partials `∂ᵃ_u ∂ᵇ_v S` for each `(a, b)` of `orders`, from the monomials written
    /// around `(cu, cv)` (module documentation).
    fn lean_centred<T: Scalar, const K: usize>(
        &self,
        net: &PowerNet,
        u: T,
        v: T,
        cu: T,
        cv: T,
        orders: [(usize, usize); K],
    ) -> [[T; 3]; K] {
        let (m, n) = (net.m, net.n);
        let [[cs, cr], [ds, dr], [ku, kv]] = self.patch.centred_offsets(u, v, cu, cv);
        // Powers of the offsets, and each mixed monomial once (on demand).
        let mut ps = vec![T::one(); m + 1];
        let mut pr = vec![T::one(); n + 1];
        for i in 1..=m {
            ps[i] = if i == 2 { ds.sqr() } else { ps[i - 1] * ds };
        }
        for j in 1..=n {
            pr[j] = if j == 2 { dr.sqr() } else { pr[j - 1] * dr };
        }
        let mut mono: Vec<Option<T>> = vec![None; (m + 1) * (n + 1)];
        let mut monomial = |a: usize, b: usize| -> T {
            *mono[a * (n + 1) + b].get_or_insert_with(|| match (a, b) {
                (0, _) => pr[b],
                (_, 0) => ps[a],
                _ => ps[a] * pr[b],
            })
        };
        // Bernstein values at the centre per degree (constants of the expansion).
        let bs: Vec<Vec<T>> = (0..=m).map(|k| bernstein(m - k, cs)).collect();
        let br: Vec<Vec<T>> = (0..=n).map(|l| bernstein(n - l, cr)).collect();
        let zero = T::zero();
        let mut out = [[zero; 3]; K];
        for x in 0..3 {
            // Taylor coefficients T_kl of this coordinate (None where identically zero).
            let coeff: Vec<Option<T>> = (0..=m)
                .flat_map(|k| (0..=n).map(move |l| (k, l)))
                .map(|(k, l)| {
                    let diffs = net.diffs[k * (n + 1) + l][x].as_ref()?;
                    let mut acc: Option<T> = None;
                    for i in 0..=m - k {
                        for j in 0..=n - l {
                            let c = diffs[i * (n - l + 1) + j];
                            if c.inf() == 0.0 && c.sup() == 0.0 {
                                continue;
                            }
                            let term = T::from_interval(c) * bs[k][i] * br[l][j];
                            acc = Some(acc.map_or(term, |a| a + term));
                        }
                    }
                    let scale = T::from_f64(binomial(m, k) * binomial(n, l));
                    acc.map(|a| a * scale)
                })
                .collect();
            for (slot, &(a, b)) in out.iter_mut().zip(&orders) {
                let mut acc: Option<T> = None;
                for k in a..=m {
                    for l in b..=n {
                        let Some(t) = coeff[k * (n + 1) + l] else {
                            continue;
                        };
                        // ∂ᵃ_s ∂ᵇ_r (dsᵏ drˡ) = k!/(k−a)! · l!/(l−b)! · ds^{k−a} dr^{l−b}.
                        let falling = (0..a).fold(1.0, |f, i| f * (k - i) as f64)
                            * (0..b).fold(1.0, |f, i| f * (l - i) as f64);
                        let c = t * T::from_f64(falling);
                        let term = if k == a && l == b {
                            c
                        } else {
                            c * monomial(k - a, l - b)
                        };
                        acc = Some(acc.map_or(term, |s| s + term));
                    }
                }
                // The chain rule to (u, v): one factor 1/Δu per s-derivative, 1/Δv per r.
                slot[x] = match acc {
                    None => zero,
                    Some(s) => match (a, b) {
                        (0, 0) => s,
                        (1, 0) => s * ku,
                        (0, 1) => s * kv,
                        (2, 0) => s * (ku * ku),
                        (1, 1) => s * (ku * kv),
                        _ => s * (kv * kv),
                    },
                };
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::{Domain, PowerSurface};
    use crate::numeric::scalar::{interval, point};
    use crate::pair::fixtures::TANGENTIAL_CUBIC;

    fn cubic() -> RationalBezierPatch {
        let d = Domain::new(-1.0, 1.0, -0.5, 2.0);
        PowerSurface::graph(d, TANGENTIAL_CUBIC.to_vec())
            .to_bezier()
            .unwrap()
    }

    #[test]
    fn lean_form_equals_the_patch_and_encloses_it() {
        let p = cubic();
        let lean = ContactPatch::new(&p);
        assert!(lean.is_polynomial());
        for k in 0..25 {
            let (u, v) = (-0.9 + 0.07 * k as f64, -0.4 + 0.09 * k as f64);
            let (cu, cv) = (0.1 - 0.02 * k as f64, 0.7 + 0.01 * k as f64);
            let want = p.second_order(u, v);
            let got = lean.second_order_centred(u, v, cu, cv);
            for (a, b) in want.iter().zip(&got) {
                for x in 0..3 {
                    assert!(
                        (a[x] - b[x]).abs() < 1e-12 * (1.0 + a[x].abs()),
                        "{a:?} vs {b:?}"
                    );
                }
            }
            // Interval evaluation at the point: encloses the f64 value of the Bernstein form.
            let iv = lean.second_order_centred(point(u), point(v), point(cu), point(cv));
            for (a, b) in want.iter().zip(&iv) {
                for x in 0..3 {
                    assert!(
                        (b[x].inf() - 1e-12..=b[x].sup() + 1e-12).contains(&a[x]),
                        "{a:?} vs {b:?}"
                    );
                }
            }
        }
        // Over a box: encloses sampled values.
        let (u, v) = (interval(0.2, 0.25).unwrap(), interval(1.0, 1.04).unwrap());
        let iv = lean.second_order_centred(u, v, point(0.225), point(1.02));
        for a in 0..=4 {
            for b in 0..=4 {
                let y = p.second_order(0.2 + 0.0125 * a as f64, 1.0 + 0.01 * b as f64);
                for (s, e) in y.iter().zip(&iv) {
                    for x in 0..3 {
                        assert!(e[x].inf() - 1e-12 <= s[x] && s[x] <= e[x].sup() + 1e-12);
                    }
                }
            }
        }
    }

    #[test]
    fn rational_patches_keep_the_patch_form() {
        let p = crate::pair::fixtures::rational_bilinear();
        let lean = ContactPatch::new(&p);
        assert!(!lean.is_polynomial());
        let want = p.second_order_centred(0.3, 0.6, 0.5, 0.5);
        assert_eq!(lean.second_order_centred(0.3, 0.6, 0.5, 0.5), want);
    }
}
