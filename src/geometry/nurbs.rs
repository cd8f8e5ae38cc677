//! Tensor-product NURBS surfaces and their rigorous split into rational Bézier patches.
//!
//! A NURBS surface of degree `(p, q)` has knot vectors `U = (u_0, …, u_{nu+p})` and
//! `V = (v_0, …, v_{nv+q})`, `nu·nv` Cartesian control points `P_ij` (index `i·nv + j`) with
//! positive weights `w_ij`, and is the rational B-spline surface
//!
//! ```text
//! S(u, v) = Σᵢ Σⱼ N_{i,p}(u) N_{j,q}(v) w_ij P_ij  /  Σᵢ Σⱼ N_{i,p}(u) N_{j,q}(v) w_ij
//! ```
//!
//! on the domain `[u_p, u_nu] × [v_q, v_nv]`. Knot vectors may be clamped or not.
//!
//! [`NurbsSurface::to_bezier`] splits the surface at its distinct knots into rational Bézier
//! patches by Boehm knot insertion on the homogeneous net `(w·x, w·y, w·z, w)`: every distinct
//! knot value of the domain (its two ends included, which clamps an unclamped vector) is
//! inserted until it has multiplicity equal to the degree, after which each knot span's
//! `(p+1)·(q+1)` control points are the Bernstein net of the surface on that span. Each new
//! control point is a convex combination `α·P_i + (1 − α)·P_{i−1}` with
//! `α = (t − u_i)/(u_{i+p} − u_i)`; both `α` and `1 − α` (computed as `(u_{i+p} − t)/(…)`) and
//! the combination are evaluated in outward-rounded interval arithmetic, so each Bézier net
//! encloses the exact one, and, since the map from control data to the new net is linear with
//! non-negative coefficients, interval control data are enclosed too. Each patch keeps its knot
//! span as its domain, so it is parametrised by the NURBS's own parameters.
//!
//! The knot insertion is written here rather than taken from a crate: the B-spline crates on
//! crates.io work in floating point only, and none offers an interval (outward-rounded)
//! knot insertion.

use crate::error::{Error, InputProblem, Result};
use crate::geometry::bezier::{check_control_data, RationalBezierPatch};
use crate::geometry::surface::Domain;
use crate::numeric::scalar::Scalar;
use inari::Interval;

/// A homogeneous control point `(w·x, w·y, w·z, w)`.
type Hom = [Interval; 4];

/// A tensor-product NURBS surface with interval control data (see the module documentation).
///
/// Invariants (checked by [`NurbsSurface::new`]): degrees at least 1; finite, non-decreasing
/// knots; no knot value of multiplicity above `degree + 1`, none inside the domain above
/// `degree`; a domain of positive width; `nu·nv` finite control points; strictly positive
/// weights.
#[derive(Debug, Clone, PartialEq)]
pub struct NurbsSurface {
    degree: [usize; 2],
    knots: [Vec<f64>; 2],
    count: [usize; 2],
    points: Vec<[Interval; 3]>,
    weights: Vec<Interval>,
}

/// Check one knot vector for degree `p`; the number of control points it implies.
fn check_knots(knots: &[f64], p: usize, k: usize) -> Result<usize> {
    let field = format!("knots[{k}]");
    if knots.len() < 2 * p + 2 {
        return Err(Error::input(
            field,
            InputProblem::WrongShape(format!(
                "{} knots where at least {} are needed for degree {p}",
                knots.len(),
                2 * p + 2
            )),
        ));
    }
    for (i, t) in knots.iter().enumerate() {
        if !t.is_finite() {
            return Err(Error::input(
                format!("{field}[{i}]"),
                InputProblem::NonFinite,
            ));
        }
        if i > 0 && *t < knots[i - 1] {
            return Err(Error::input(
                format!("{field}[{i}]"),
                InputProblem::WrongShape(format!("knots decrease ({} after {})", t, knots[i - 1])),
            ));
        }
    }
    let n = knots.len() - p - 1;
    let (a, b) = (knots[p], knots[n]);
    if a >= b {
        return Err(Error::input(
            field,
            InputProblem::EmptyDomain { lo: a, hi: b },
        ));
    }
    let mut i = 0;
    while i < knots.len() {
        let t = knots[i];
        let m = knots[i..].iter().take_while(|&&s| s == t).count();
        let limit = if a < t && t < b { p } else { p + 1 };
        if m > limit {
            return Err(Error::input(
                format!("{field}[{i}]"),
                InputProblem::WrongShape(format!(
                    "knot {t} has multiplicity {m}, more than {limit} for degree {p}"
                )),
            ));
        }
        i += m;
    }
    Ok(n)
}

impl NurbsSurface {
    /// A NURBS surface from its degrees, knot vectors, Cartesian control points (index
    /// `i·nv + j`) and optional weights (all 1 if `None`).
    ///
    /// Errors ([`Error::InvalidInput`] without a surface index): `degree[k]` 0; `knots[k]` too
    /// short for its degree, with an empty domain, or `knots[k][i]` non-finite, decreasing or of
    /// too high a multiplicity; a wrong `points` / `weights` count; non-finite or empty
    /// `points[k][c]` / `weights[k]`; a weight not strictly positive.
    pub fn new(
        degree: [usize; 2],
        knots: [Vec<f64>; 2],
        points: Vec<[Interval; 3]>,
        weights: Option<Vec<Interval>>,
    ) -> Result<Self> {
        for (k, d) in degree.into_iter().enumerate() {
            if d == 0 {
                return Err(Error::input(
                    format!("degree[{k}]"),
                    InputProblem::BadDegree(0),
                ));
            }
            if d > 64 {
                return Err(Error::input(
                    format!("degree[{k}]"),
                    InputProblem::WrongShape("degree too large".into()),
                ));
            }
        }
        let nu = check_knots(&knots[0], degree[0], 0)?;
        let nv = check_knots(&knots[1], degree[1], 1)?;
        let count = nu
            .checked_mul(nv)
            .filter(|&c| c < (1 << 24))
            .ok_or_else(|| Error::input("knots", InputProblem::WrongShape("too many".into())))?;
        let weights = check_control_data(&points, weights, count)?;
        Ok(NurbsSurface {
            degree,
            knots,
            count: [nu, nv],
            points,
            weights,
        })
    }

    /// The degrees `[p, q]`.
    pub fn degree(&self) -> [usize; 2] {
        self.degree
    }

    /// The knot vectors `[U, V]` as given.
    pub fn knots(&self) -> &[Vec<f64>; 2] {
        &self.knots
    }

    /// The control-point counts `[nu, nv]`.
    pub fn count(&self) -> [usize; 2] {
        self.count
    }

    /// The Cartesian control points, index `i·nv + j`.
    pub fn points(&self) -> &[[Interval; 3]] {
        &self.points
    }

    /// The weights, index `i·nv + j`.
    pub fn weights(&self) -> &[Interval] {
        &self.weights
    }

    /// The parameter domain `[u_p, u_nu] × [v_q, v_nv]`.
    pub fn domain(&self) -> Domain {
        let [p, q] = self.degree;
        let [nu, nv] = self.count;
        Domain {
            u: [self.knots[0][p], self.knots[0][nu]],
            v: [self.knots[1][q], self.knots[1][nv]],
        }
    }

    /// The knot spans of the domain in each direction: consecutive distinct knot values.
    pub fn spans(&self) -> [Vec<[f64; 2]>; 2] {
        let d = self.domain();
        [0, 1].map(|k| {
            let [a, b] = if k == 0 { d.u } else { d.v };
            distinct_in(&self.knots[k], a, b)
                .windows(2)
                .map(|w| [w[0], w[1]])
                .collect()
        })
    }

    /// The rational Bézier patches of the surface, one per pair of knot spans, u-span major
    /// (patch `(s, r)` at index `s·(number of v-spans) + r`, spans as in
    /// [`NurbsSurface::spans`]); each on its knot span as domain, each net an outward-rounded
    /// enclosure of the exact one.
    ///
    /// Errors: a piece whose control points all coincide ([`InputProblem::Degenerate`],
    /// field `points`).
    pub fn to_bezier(&self) -> Result<Vec<RationalBezierPatch>> {
        let [p, q] = self.degree;
        let [nu, nv] = self.count;
        let net: Vec<Hom> = self
            .points
            .iter()
            .zip(&self.weights)
            .map(|(x, &w)| [x[0] * w, x[1] * w, x[2] * w, w])
            .collect();
        // Refine in u: the curves are the columns j (fixed j, running i).
        let columns: Vec<Vec<Hom>> = (0..nv)
            .map(|j| (0..nu).map(|i| net[i * nv + j]).collect())
            .collect();
        let (ku, columns) = refine(&self.knots[0], p, columns);
        let nu2 = columns[0].len();
        // Then in v: the rows i of the refined net.
        let rows: Vec<Vec<Hom>> = (0..nu2)
            .map(|i| (0..nv).map(|j| columns[j][i]).collect())
            .collect();
        let (kv, rows) = refine(&self.knots[1], q, rows);
        let su = span_starts(&ku, p, nu2);
        let sv = span_starts(&kv, q, rows[0].len());
        let poles = self.poles();
        let dom = self.domain();
        let mut out = Vec::with_capacity(su.len() * sv.len());
        for &(iu, a0, a1) in &su {
            for &(iv, b0, b1) in &sv {
                let mut piece = Vec::with_capacity((p + 1) * (q + 1));
                for ii in 0..=p {
                    for jj in 0..=q {
                        piece.push(rows[iu - p + ii][iv - q + jj]);
                    }
                }
                let domain = Domain {
                    u: [a0, a1],
                    v: [b0, b1],
                };
                // A side of the piece on a side of the surface that collapses to a point.
                let on = [
                    a0 == dom.u[0],
                    a1 == dom.u[1],
                    b0 == dom.v[0],
                    b1 == dom.v[1],
                ];
                let collapsed = std::array::from_fn(|k| poles[k].filter(|_| on[k]));
                out.push(
                    RationalBezierPatch::from_homogeneous([p, q], piece, domain)?
                        .with_collapsed_sides(collapsed),
                );
            }
        }
        Ok(out)
    }

    /// The sides of the surface (`u = u_p`, `u = u_nu`, `v = v_q`, `v = v_nv`) that it maps to
    /// one point, with that point: the knot vector is clamped at that end (so the side is the
    /// curve of the boundary row of control points) and the row's points are one exact point.
    fn poles(&self) -> [Option<[f64; 3]>; 4] {
        let [p, q] = self.degree;
        let [nu, nv] = self.count;
        std::array::from_fn(|side| {
            let (dir, upper) = (side / 2, side % 2 == 1);
            let (knots, deg) = (&self.knots[dir], [p, q][dir]);
            let clamped = if upper {
                let end = knots.len() - 1;
                knots[end - deg..].iter().all(|&t| t == knots[end])
            } else {
                knots[..=deg].iter().all(|&t| t == knots[0])
            };
            let row: Vec<usize> = match (dir, upper) {
                (0, false) => (0..nv).collect(),
                (0, true) => (0..nv).map(|j| (nu - 1) * nv + j).collect(),
                (_, false) => (0..nu).map(|i| i * nv).collect(),
                (_, true) => (0..nu).map(|i| i * nv + nv - 1).collect(),
            };
            let first = self.points[row[0]];
            let exact = |x: &[Interval; 3]| x.iter().all(|c| c.inf() == c.sup());
            (clamped
                && row
                    .iter()
                    .all(|&k| exact(&self.points[k]) && self.points[k] == first))
            .then(|| first.map(|c| c.inf()))
        })
    }
}

/// The distinct values of `knots` in `[a, b]`, ascending.
fn distinct_in(knots: &[f64], a: f64, b: f64) -> Vec<f64> {
    let mut out: Vec<f64> = Vec::new();
    for &t in knots {
        if a <= t && t <= b && out.last() != Some(&t) {
            out.push(t);
        }
    }
    out
}

/// How often `t` occurs in `knots`.
fn multiplicity(knots: &[f64], t: f64) -> usize {
    knots.iter().filter(|&&s| s == t).count()
}

/// Insert every distinct knot value of the domain (ends included) of the curves `curves` (each
/// with `knots.len() − p − 1` homogeneous control points over `knots`) until it has multiplicity
/// at least `p`; the new knot vector and curves.
fn refine(knots: &[f64], p: usize, mut curves: Vec<Vec<Hom>>) -> (Vec<f64>, Vec<Vec<Hom>>) {
    let mut knots = knots.to_vec();
    let n = knots.len() - p - 1;
    let (a, b) = (knots[p], knots[n]);
    for t in distinct_in(&knots.clone(), a, b) {
        while multiplicity(&knots, t) < p {
            // The span: u_k ≤ t < u_{k+1} inside the domain, u_k < t = u_{k+1} at its end; in
            // both cases p ≤ k ≤ n − 1 and u_i < u_{i+p} for k − p < i ≤ k (see the module
            // documentation), so every α below has a positive denominator.
            let k = if t < b {
                knots.iter().rposition(|&s| s <= t)
            } else {
                knots.iter().rposition(|&s| s < t)
            }
            .unwrap_or(p);
            for c in curves.iter_mut() {
                *c = insert(&knots, p, k, t, c);
            }
            knots.insert(k + 1, t);
        }
    }
    (knots, curves)
}

/// Boehm's insertion of `t` into span `k` of a degree-`p` curve, in interval arithmetic.
fn insert(knots: &[f64], p: usize, k: usize, t: f64, pts: &[Hom]) -> Vec<Hom> {
    let ti = Interval::from_f64(t);
    let mut out = Vec::with_capacity(pts.len() + 1);
    for i in 0..=pts.len() {
        let h = if i + p <= k {
            pts[i]
        } else if i > k {
            pts[i - 1]
        } else {
            let lo = Interval::from_f64(knots[i]);
            let hi = Interval::from_f64(knots[i + p]);
            let den = hi - lo;
            let alpha = (ti - lo) / den;
            let beta = (hi - ti) / den;
            let (new, old) = (pts[i], pts[i - 1]);
            [0, 1, 2, 3].map(|c| alpha * new[c] + beta * old[c])
        };
        out.push(h);
    }
    out
}

/// For each knot span `[t_s, t_{s+1}]` of the refined vector's domain: the index `k` of the
/// last knot equal to `t_s` (the span's Bézier net is control points `k − p ..= k`) and the
/// span's ends.
fn span_starts(knots: &[f64], p: usize, n: usize) -> Vec<(usize, f64, f64)> {
    let (a, b) = (knots[p], knots[n]);
    distinct_in(knots, a, b)
        .windows(2)
        .map(|w| {
            let k = knots.iter().rposition(|&s| s == w[0]).unwrap_or(p);
            (k, w[0], w[1])
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pt(x: f64) -> Interval {
        Interval::from_f64(x)
    }

    #[test]
    fn a_single_span_surface_is_its_own_bezier_patch() {
        let points: Vec<[Interval; 3]> = (0..9)
            .map(|k| [pt((k / 3) as f64), pt((k % 3) as f64), pt((k * k) as f64)])
            .collect();
        let knots = [
            vec![0.0, 0.0, 0.0, 2.0, 2.0, 2.0],
            vec![1.0, 1.0, 1.0, 3.0, 3.0, 3.0],
        ];
        let s = NurbsSurface::new([2, 2], knots, points.clone(), None).unwrap();
        let b = s.to_bezier().unwrap();
        assert_eq!(b.len(), 1);
        assert_eq!(b[0].domain().u, [0.0, 2.0]);
        assert_eq!(b[0].domain().v, [1.0, 3.0]);
        for (h, x) in b[0].homogeneous().iter().zip(&points) {
            assert_eq!(&h[..3], &x[..]);
        }
    }

    #[test]
    fn unclamped_uniform_knots_give_one_patch_per_span() {
        // Uniform cubic × quadratic, unclamped: 6 × 4 control points.
        let ku: Vec<f64> = (0..10).map(f64::from).collect();
        let kv: Vec<f64> = (0..7).map(f64::from).collect();
        let points: Vec<[Interval; 3]> = (0..24)
            .map(|k| {
                [
                    pt((k / 4) as f64),
                    pt((k % 4) as f64),
                    pt(((k * 7) % 5) as f64),
                ]
            })
            .collect();
        let s = NurbsSurface::new([3, 2], [ku, kv], points, None).unwrap();
        assert_eq!(s.domain().u, [3.0, 6.0]);
        assert_eq!(s.domain().v, [2.0, 4.0]);
        let b = s.to_bezier().unwrap();
        assert_eq!(b.len(), 3 * 2);
        assert_eq!(b[3].domain().u, [4.0, 5.0]);
        assert_eq!(b[3].domain().v, [3.0, 4.0]);
    }
}
