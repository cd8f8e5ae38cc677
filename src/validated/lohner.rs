//! Lohner's QR method: the set `{x̂ + A·r : r ∈ [r]}` and its rigorous update.
//!
//! After one step the set of solutions is enclosed by `u + M·[r]` with `u` an interval vector
//! (the Taylor polynomial at the centre plus the remainder) and `M = S·A` an interval matrix
//! (`S = Σ Jᵢ hⁱ`, the mean-value Jacobian of the step). Evaluating `M·[r]` as a box would wrap
//! (rotate a box, enclose it in a box, repeat: widths grow geometrically). Instead we keep
//!
//! `y ∈ x̂' + A'·[r']`, `A' = Q` from the QR factorisation of `mid(M)` with its columns sorted by
//! decreasing `‖column‖·wid(rⱼ)` (so the most uncertain direction is kept exactly),
//! `[r'] = (Q⁻¹M)·[r] + Q⁻¹(u − x̂')`, with `x̂' = mid(u)`.
//!
//! `Q` is computed in `f64` (nalgebra); it is nearly but not exactly orthogonal, so `Q⁻¹` is
//! enclosed rigorously ([`verified_inverse`]) rather than taken as `Qᵀ`. Every product above is
//! an interval product, so the update is a sound enclosure whatever `Q` is.

use crate::numeric::scalar::point;
use inari::{const_interval, Interval};
use nalgebra::DMatrix;

const ZERO: Interval = const_interval!(0.0, 0.0);

/// Row-major `n×n` interval matrix times `n×n` interval matrix.
pub(crate) fn mat_mul(a: &[Interval], b: &[Interval], n: usize) -> Vec<Interval> {
    let mut c = vec![ZERO; n * n];
    for i in 0..n {
        for l in 0..n {
            let ail = a[i * n + l];
            for j in 0..n {
                c[i * n + j] += ail * b[l * n + j];
            }
        }
    }
    c
}

/// Row-major `n×n` interval matrix times interval vector.
pub(crate) fn mat_vec(a: &[Interval], x: &[Interval], n: usize) -> Vec<Interval> {
    (0..n)
        .map(|i| (0..n).fold(ZERO, |acc, j| acc + a[i * n + j] * x[j]))
        .collect()
}

/// An interval enclosure (row-major) of the exact inverse of the `f64` matrix `q`, or `None` if
/// `q` is too ill-conditioned for the test below.
///
/// Method: `X ≈ q⁻¹` in `f64` (for an orthonormal `q`, `X = qᵀ`), `E = I − X·q` in intervals,
/// `η ≥ ‖E‖∞`. If `η < 1/2` then `q⁻¹ = (I − E)⁻¹X = X + E·X + E²(I − E)⁻¹X` and the last term
/// is bounded entrywise by `η²‖X‖∞/(1 − η)`.
pub fn verified_inverse(q: &DMatrix<f64>) -> Option<Vec<Interval>> {
    let n = q.nrows();
    let approx = q.clone().try_inverse()?;
    let x: Vec<Interval> = (0..n * n).map(|k| point(approx[(k / n, k % n)])).collect();
    let qi: Vec<Interval> = (0..n * n).map(|k| point(q[(k / n, k % n)])).collect();
    let xq = mat_mul(&x, &qi, n);
    let e: Vec<Interval> = (0..n * n)
        .map(|k| {
            if k / n == k % n {
                point(1.0) - xq[k]
            } else {
                -xq[k]
            }
        })
        .collect();
    let row_norm = |m: &[Interval]| {
        (0..n)
            .map(|i| {
                (0..n)
                    .fold(ZERO, |acc, j| acc + point(m[i * n + j].mag()))
                    .sup()
            })
            .fold(0.0f64, f64::max)
    };
    let eta = row_norm(&e);
    if eta.is_nan() || eta >= 0.5 {
        return None;
    }
    let xnorm = row_norm(&x);
    let tail = (point(eta).sqr() * point(xnorm) / (point(1.0) - point(eta))).sup();
    let pad = crate::validated::enclosure::symmetric(tail);
    let ex = mat_mul(&e, &x, n);
    Some((0..n * n).map(|k| x[k] + ex[k] + pad).collect())
}

/// The orthonormal basis for the next set: `Q` of the QR factorisation of `mid(M)`, columns
/// pivoted by decreasing `‖mid(M) column j‖₂ · wid(r_j)`.
pub(crate) fn qr_basis(m: &[Interval], r: &[Interval], n: usize) -> DMatrix<f64> {
    let mid = DMatrix::from_fn(n, n, |i, j| m[i * n + j].mid());
    let mut order: Vec<usize> = (0..n).collect();
    let key = |j: usize| mid.column(j).norm() * r[j].wid();
    order.sort_by(|&a, &b| {
        key(b)
            .partial_cmp(&key(a))
            .unwrap_or(std::cmp::Ordering::Equal)
    });
    let permuted = DMatrix::from_fn(n, n, |i, j| mid[(i, order[j])]);
    permuted.qr().q()
}

/// The set `{x̂ + A·r : r ∈ [r]}` of Lohner's method.
#[derive(Clone, Debug)]
pub struct LohnerSet {
    /// Centre `x̂` (exact `f64` values).
    pub(crate) center: Vec<f64>,
    /// Basis `A`, row-major, exact `f64` entries.
    pub(crate) basis: Vec<f64>,
    /// Coefficients `[r]`.
    pub(crate) r: Vec<Interval>,
}

impl LohnerSet {
    /// The centre `x̂`.
    pub fn center(&self) -> &[f64] {
        &self.center
    }

    /// The basis `A` (row-major `n×n`; orthonormal up to rounding when QR is used).
    pub fn basis(&self) -> &[f64] {
        &self.basis
    }

    /// The coefficient box `[r]`.
    pub fn r(&self) -> &[Interval] {
        &self.r
    }

    /// The set equal to the box `y` (`A = I`, centre the midpoint).
    pub fn from_box(y: &[Interval]) -> Self {
        let n = y.len();
        let center: Vec<f64> = y.iter().map(|v| v.mid()).collect();
        let r = y.iter().zip(&center).map(|(v, c)| *v - point(*c)).collect();
        let mut basis = vec![0.0; n * n];
        for i in 0..n {
            basis[i * n + i] = 1.0;
        }
        LohnerSet { center, basis, r }
    }

    /// The interval hull `x̂ + A·[r]`.
    pub fn hull(&self) -> Vec<Interval> {
        let n = self.center.len();
        let a: Vec<Interval> = self.basis.iter().map(|v| point(*v)).collect();
        mat_vec(&a, &self.r, n)
            .iter()
            .zip(&self.center)
            .map(|(v, c)| *v + point(*c))
            .collect()
    }

    /// The basis as an interval matrix.
    pub fn basis_intervals(&self) -> Vec<Interval> {
        self.basis.iter().map(|v| point(*v)).collect()
    }

    /// The next set enclosing `u + M·[r]` (`M = S·A`). With `qr` the basis is re-orthonormalised;
    /// without it the basis stays the identity (a plain interval method, which wraps).
    pub(crate) fn advance(&self, u: &[Interval], m: &[Interval], qr: bool) -> LohnerSet {
        let n = u.len();
        let center: Vec<f64> = u.iter().map(|v| v.mid()).collect();
        let du: Vec<Interval> = u.iter().zip(&center).map(|(v, c)| *v - point(*c)).collect();
        if qr {
            let q = qr_basis(m, &self.r, n);
            if let Some(qinv) = verified_inverse(&q) {
                let qm = mat_mul(&qinv, m, n);
                let r: Vec<Interval> = mat_vec(&qm, &self.r, n)
                    .iter()
                    .zip(mat_vec(&qinv, &du, n))
                    .map(|(a, b)| *a + b)
                    .collect();
                let basis = (0..n * n).map(|k| q[(k / n, k % n)]).collect();
                return LohnerSet { center, basis, r };
            }
        }
        let r: Vec<Interval> = mat_vec(m, &self.r, n)
            .iter()
            .zip(&du)
            .map(|(a, b)| *a + *b)
            .collect();
        let mut basis = vec![0.0; n * n];
        for i in 0..n {
            basis[i * n + i] = 1.0;
        }
        LohnerSet { center, basis, r }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::numeric::scalar::interval;

    #[test]
    fn verified_inverse_encloses_inverse_of_rotation_like_matrix() {
        let c = 0.6f64;
        let s = 0.8f64;
        let q = DMatrix::from_row_slice(2, 2, &[c, -s, s, c]);
        let inv = verified_inverse(&q).unwrap();
        // The enclosure times q must contain the identity (checked in intervals).
        let qrow: Vec<Interval> = vec![point(c), point(-s), point(s), point(c)];
        let prod = mat_mul(&inv, &qrow, 2);
        for (k, p) in prod.iter().enumerate() {
            let want = if k == 0 || k == 3 { 1.0 } else { 0.0 };
            assert!(p.contains(want), "{k}: {p:?}");
            assert!(p.wid() < 1e-14);
        }
    }

    #[test]
    fn qr_advance_does_not_wrap_under_repeated_rotation() {
        // M = rotation by an angle with cos = 0.6, sin = 0.8 (exact binary approximations; M is
        // taken as point intervals of those values, so M is the map being applied).
        let m = [point(0.6), point(-0.8), point(0.8), point(0.6)];
        let start = [
            interval(0.99, 1.01).unwrap(),
            interval(-0.01, 0.01).unwrap(),
        ];
        let mut qr = LohnerSet::from_box(&start);
        let mut plain = LohnerSet::from_box(&start);
        for _ in 0..200 {
            let u_qr = mat_vec(
                &m,
                &qr.center.iter().map(|c| point(*c)).collect::<Vec<_>>(),
                2,
            );
            let mq = mat_mul(&m, &qr.basis_intervals(), 2);
            qr = qr.advance(&u_qr, &mq, true);
            let u_pl = mat_vec(
                &m,
                &plain.center.iter().map(|c| point(*c)).collect::<Vec<_>>(),
                2,
            );
            let mp = mat_mul(&m, &plain.basis_intervals(), 2);
            plain = plain.advance(&u_pl, &mp, false);
        }
        let w = |set: &LohnerSet| set.hull().iter().map(|v| v.wid()).fold(0.0, f64::max);
        // The exact image of the box is a rotated square of side 0.02: hull width ≤ 0.02·√2.
        assert!(w(&qr) < 0.0283, "QR hull width {}", w(&qr));
        assert!(w(&plain) > 1e6, "plain hull width {}", w(&plain));
    }
}
