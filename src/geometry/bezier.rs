//! Tensor-product rational Bézier patches with interval control data.
//!
//! A patch of degree `(m, n)` maps its declared domain `[u0,u1] × [v0,v1]` to space through the
//! normalised parameters `s = (u − u0)/(u1 − u0)`, `r = (v − v0)/(v1 − v0)`:
//!
//! ```text
//! S(u, v) = Σᵢ Σⱼ Bᵢᵐ(s) Bⱼⁿ(r) wᵢⱼ Pᵢⱼ  /  Σᵢ Σⱼ Bᵢᵐ(s) Bⱼⁿ(r) wᵢⱼ
//! ```
//!
//! The control net is stored in homogeneous form `(w·x, w·y, w·z, w)`, each entry an
//! [`Interval`], so "interval Bézier surfaces" (uncertain control data) are first-class: every
//! rigorous operation encloses every patch whose exact control data lie in the intervals.

use crate::error::{Error, InputProblem, Result};
use crate::geometry::bernstein::{
    bernstein, bernstein_first, bernstein_values, binomial, forward_difference,
};
use crate::geometry::surface::{Domain, ParametricSurface, SurfaceDerivs, Vec3};
use crate::numeric::scalar::{point, Scalar};
use inari::Interval;

/// A surface point with all first and second partial derivatives, over any [`Scalar`].
///
/// Derivatives are with respect to the declared parameters `(u, v)` of the patch.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PatchDerivs<S> {
    /// The point S(u, v).
    pub p: [S; 3],
    /// ∂S/∂u.
    pub su: [S; 3],
    /// ∂S/∂v.
    pub sv: [S; 3],
    /// ∂²S/∂u².
    pub suu: [S; 3],
    /// ∂²S/∂u∂v.
    pub suv: [S; 3],
    /// ∂²S/∂v².
    pub svv: [S; 3],
}

/// A tensor-product rational Bézier patch of degree `(m, n)`, both at least 1, on a declared
/// parameter domain, with a homogeneous interval control net.
///
/// Invariants (checked by every constructor): finite, non-empty control intervals; every weight
/// interval strictly positive; a finite domain with `u0 < u1`, `v0 < v1`; control points that do
/// not all coincide.
#[derive(Debug, Clone)]
pub struct RationalBezierPatch {
    degree: [usize; 2],
    /// `(w·x, w·y, w·z, w)` per control point, index `i*(n+1)+j`.
    homogeneous: Vec<[Interval; 4]>,
    /// Midpoints of `homogeneous`, the net used by the fast `f64` evaluation.
    mid: Vec<[f64; 4]>,
    /// The Cartesian control data `(x, y, z, w)` as given to [`RationalBezierPatch::new`], kept so
    /// that writing the patch out reproduces the input exactly.
    cartesian: Option<Vec<[Interval; 4]>>,
    domain: Domain,
    /// [`RationalBezierPatch::collapsed_sides`].
    collapsed: [Option<[f64; 3]>; 4],
    /// [`RationalBezierPatch::net_differences`], formed on first use.
    differences: std::sync::OnceLock<Vec<[Interval; 4]>>,
}

/// Equal patches: the same degree, net, input data and domain (the cache of
/// the net's differences is derived from them and does not count: a patch
/// whose differences were formed equals a copy whose differences were not).
impl PartialEq for RationalBezierPatch {
    fn eq(&self, other: &Self) -> bool {
        self.degree == other.degree
            && self.homogeneous == other.homogeneous
            && self.mid == other.mid
            && self.cartesian == other.cartesian
            && self.domain == other.domain
            && self.collapsed == other.collapsed
    }
}

mod checks;
mod exact;

use checks::check_degree;
pub(crate) use checks::{check_control_data, check_domain, check_interval};

impl RationalBezierPatch {
    /// A patch from Cartesian control points `(x, y, z)` and optional weights (all 1 if `None`),
    /// index `i*(n+1)+j`. The homogeneous net is computed in interval arithmetic, so it encloses
    /// the exact products `w·x`.
    ///
    /// Errors ([`Error::InvalidInput`] without a surface index): `degree[k]` 0, wrong `points` /
    /// `weights` counts, non-finite or empty intervals in `points[k][c]` / `weights[k]`, weights
    /// not strictly positive, a bad `domain[k]`, or all control points coinciding (`points`).
    pub fn new(
        degree: [usize; 2],
        points: Vec<[Interval; 3]>,
        weights: Option<Vec<Interval>>,
        domain: Domain,
    ) -> Result<Self> {
        let count = check_degree(degree)?;
        let weights = check_control_data(&points, weights, count)?;
        check_domain(&domain)?;
        let cartesian: Vec<[Interval; 4]> = points
            .iter()
            .zip(&weights)
            .map(|(p, &w)| [p[0], p[1], p[2], w])
            .collect();
        let homogeneous = cartesian
            .iter()
            .map(|&[x, y, z, w]| [x * w, y * w, z * w, w])
            .collect();
        let mut patch = Self::assemble(degree, homogeneous, domain)?;
        patch.collapsed = crate::geometry::collapsed::collapsed_rows(degree, &points);
        patch.cartesian = Some(cartesian);
        Ok(patch)
    }

    /// A patch from a homogeneous net `(w·x, w·y, w·z, w)`, index `i*(n+1)+j`.
    ///
    /// Same checks as [`RationalBezierPatch::new`]; the weight of entry `k` is reported as
    /// `weights[k]`, its other components as `points[k][c]`.
    pub fn from_homogeneous(
        degree: [usize; 2],
        hpoints: Vec<[Interval; 4]>,
        domain: Domain,
    ) -> Result<Self> {
        let count = check_degree(degree)?;
        if hpoints.len() != count {
            return Err(Error::input(
                "points",
                InputProblem::WrongCount {
                    expected: count,
                    found: hpoints.len(),
                },
            ));
        }
        for (k, h) in hpoints.iter().enumerate() {
            for (c, x) in h[..3].iter().enumerate() {
                check_interval(*x).map_err(|e| Error::input(format!("points[{k}][{c}]"), e))?;
            }
            check_interval(h[3]).map_err(|e| Error::input(format!("weights[{k}]"), e))?;
            if h[3].inf() <= 0.0 {
                return Err(Error::input(
                    format!("weights[{k}]"),
                    InputProblem::NonPositiveWeight,
                ));
            }
        }
        check_domain(&domain)?;
        Self::assemble(degree, hpoints, domain)
    }

    /// Convenience: a patch from exact `f64` points and optional weights (see
    /// [`RationalBezierPatch::new`] for the checks).
    pub fn from_f64_points(
        degree: [usize; 2],
        points: &[[f64; 3]],
        weights: Option<&[f64]>,
        domain: Domain,
    ) -> Result<Self> {
        let to_interval = |x: f64| {
            if x.is_finite() {
                Ok(Interval::from_f64(x))
            } else {
                Err(InputProblem::NonFinite)
            }
        };
        let mut pts = Vec::with_capacity(points.len());
        for (k, p) in points.iter().enumerate() {
            let mut q = [Interval::from_f64(0.0); 3];
            for c in 0..3 {
                q[c] =
                    to_interval(p[c]).map_err(|e| Error::input(format!("points[{k}][{c}]"), e))?;
            }
            pts.push(q);
        }
        let ws = match weights {
            Some(ws) => Some(
                ws.iter()
                    .enumerate()
                    .map(|(k, &w)| {
                        to_interval(w).map_err(|e| Error::input(format!("weights[{k}]"), e))
                    })
                    .collect::<Result<Vec<_>>>()?,
            ),
            None => None,
        };
        Self::new(degree, pts, ws, domain)
    }

    /// Build the patch from a checked net; rejects a degenerate net (all points coincide).
    fn assemble(
        degree: [usize; 2],
        homogeneous: Vec<[Interval; 4]>,
        domain: Domain,
    ) -> Result<Self> {
        let mid: Vec<[f64; 4]> = homogeneous
            .iter()
            .map(|h| [h[0].mid(), h[1].mid(), h[2].mid(), h[3].mid()])
            .collect();
        let project = |m: &[f64; 4]| [m[0] / m[3], m[1] / m[3], m[2] / m[3]];
        let first = project(&mid[0]);
        if mid.iter().all(|m| project(m) == first) {
            return Err(Error::input("points", InputProblem::Degenerate));
        }
        Ok(RationalBezierPatch {
            degree,
            homogeneous,
            mid,
            cartesian: None,
            domain,
            collapsed: [None; 4],
            differences: std::sync::OnceLock::new(),
        })
    }

    /// The degree `[m, n]` (in u, in v).
    pub fn degree(&self) -> [usize; 2] {
        self.degree
    }

    /// The declared parameter domain.
    pub fn domain(&self) -> Domain {
        self.domain
    }

    /// The sides the patch collapses to a single point (a pole), each with that point, indexed
    /// `u = u0`, `u = u1`, `v = v0`, `v = v1`: the control points of that side's row are one
    /// exact point (given so, or known so from the NURBS surface the patch was cut from), so
    /// the patch maps the whole side exactly to it.
    pub fn collapsed_sides(&self) -> [Option<[f64; 3]>; 4] {
        self.collapsed
    }

    /// The patch with sides `sides` marked as collapsed to their points (see
    /// [`Self::collapsed_sides`]). Only for a caller that knows the side is exactly one point
    /// (the NURBS decomposition, from its boundary rows): the search relies on it.
    pub(crate) fn with_collapsed_sides(mut self, sides: [Option<[f64; 3]>; 4]) -> Self {
        self.collapsed = sides;
        self
    }

    /// The patch moved by `−by` (every point `P(u, v) − by`, enclosed: the homogeneous net
    /// `(w·x − w·c_x, …, w)` in interval arithmetic); its collapsed sides are not marked.
    /// `None` if the moved net cannot be a patch (it overflows). Evaluations of differences
    /// and derivatives near `by` are tighter on it: next to a pole `X` moved to the origin,
    /// the numerator of every term is small, and the quotient rule's terms no longer cancel
    /// from values near `X`.
    pub(crate) fn translated(&self, by: [f64; 3]) -> Option<Self> {
        let moved = self
            .homogeneous
            .iter()
            .map(|h| {
                let w = h[3];
                [
                    h[0] - w * point(by[0]),
                    h[1] - w * point(by[1]),
                    h[2] - w * point(by[2]),
                    w,
                ]
            })
            .collect();
        Self::from_homogeneous(self.degree, moved, self.domain).ok()
    }

    /// The homogeneous interval control net `(w·x, w·y, w·z, w)`, index `i*(n+1)+j`.
    pub fn homogeneous(&self) -> &[[Interval; 4]] {
        &self.homogeneous
    }

    /// The mixed forward differences `Δₛᵏ Δᵣˡ h_ij` of the homogeneous net, enclosed, for
    /// `k ≤ m`, `l ≤ n`, `i ≤ m − k`, `j ≤ n − l`, in that nesting order (the `(k, l)` block
    /// holds `(m − k + 1)(n − l + 1)` entries, row `i`): each is
    /// `Σ_{a ≤ k, b ≤ l} (−1)^{k−a+l−b} C(k,a) C(l,b) h_{i+a, j+b}`, summed in that order. They
    /// do not depend on where the patch is evaluated, so they are formed once per patch (the
    /// centred power form of the search's second-order enclosures re-formed them per box).
    pub(crate) fn net_differences(&self) -> &[[Interval; 4]] {
        self.differences.get_or_init(|| {
            let [m, n] = self.degree;
            let at = |i: usize, j: usize| self.homogeneous[i * (n + 1) + j];
            let mut out = Vec::new();
            for k in 0..=m {
                for l in 0..=n {
                    for i in 0..=m - k {
                        for j in 0..=n - l {
                            let mut diff = [Interval::zero(); 4];
                            for a in 0..=k {
                                for b in 0..=l {
                                    let c = binomial(k, a) * binomial(l, b);
                                    let sign = (k - a + l - b) % 2 == 0;
                                    let f = Interval::from_f64(if sign { c } else { -c });
                                    let p = at(i + a, j + b);
                                    for x in 0..4 {
                                        diff[x] += f * p[x];
                                    }
                                }
                            }
                            out.push(diff);
                        }
                    }
                }
            }
            out
        })
    }

    /// The Cartesian control data `(x, y, z, w)` per control point: exactly as given to
    /// [`RationalBezierPatch::new`] if the patch was built that way, otherwise the rigorous
    /// interval projection `(w·x)/w` of the homogeneous net (which encloses the exact points).
    pub fn cartesian(&self) -> Vec<[Interval; 4]> {
        match &self.cartesian {
            Some(c) => c.clone(),
            None => self
                .homogeneous
                .iter()
                .map(|h| [h[0] / h[3], h[1] / h[3], h[2] / h[3], h[3]])
                .collect(),
        }
    }

    /// What a power form centred at `(cu, cv)` evaluates `(u, v)` with, in `S`: the centre's
    /// normalised parameters `[cs, cr]`, the offsets `[ds, dr] = [(u − cu)/Δu, (v − cv)/Δv]`, and
    /// the chain rule's factors `[1/Δu, 1/Δv]` (`Δ` the domain's sides).
    pub(crate) fn centred_offsets<S: Scalar>(&self, u: S, v: S, cu: S, cv: S) -> [[S; 2]; 3] {
        let d = &self.domain;
        let du = S::from_f64(d.u[1]) - S::from_f64(d.u[0]);
        let dv = S::from_f64(d.v[1]) - S::from_f64(d.v[0]);
        [
            [
                (cu - S::from_f64(d.u[0])) / du,
                (cv - S::from_f64(d.v[0])) / dv,
            ],
            [(u - cu) / du, (v - cv) / dv],
            [S::one() / du, S::one() / dv],
        ]
    }

    /// The normalised parameters `(s, r) ∈ [0,1]²` of declared parameters `(u, v)`, in `S`.
    fn normalise<S: Scalar>(&self, u: S, v: S) -> (S, S, S, S) {
        let d = &self.domain;
        let du = S::from_f64(d.u[1]) - S::from_f64(d.u[0]);
        let dv = S::from_f64(d.v[1]) - S::from_f64(d.v[0]);
        let s = (u - S::from_f64(d.u[0])) / du;
        let r = (v - S::from_f64(d.v[0])) / dv;
        (s, r, S::one() / du, S::one() / dv)
    }

    /// The point S(u, v), evaluated in `S` (intervals: a rigorous enclosure over all patches of
    /// the interval net and all parameters in `u × v`).
    pub fn eval<S: Scalar>(&self, u: S, v: S) -> [S; 3] {
        let (s, r, _, _) = self.normalise(u, v);
        let h = homogeneous_point(self.degree, s, r, |k| {
            self.homogeneous[k].map(S::from_interval)
        });
        let inv_w = S::one() / h[3];
        [h[0] * inv_w, h[1] * inv_w, h[2] * inv_w]
    }

    /// The point and its first and second partials in the declared parameters, evaluated in `S`
    /// (intervals: rigorous enclosures). Uses only [`Scalar`] operations, no branching on values.
    pub fn eval_derivs<S: Scalar>(&self, u: S, v: S) -> PatchDerivs<S> {
        let (s, r, ku, kv) = self.normalise(u, v);
        let h = homogeneous_derivs(self.degree, s, r, |k| {
            self.homogeneous[k].map(S::from_interval)
        });
        rational_derivs(&h, ku, kv)
    }

    /// The point and its first partials `[S, S_u, S_v]` in the declared parameters, evaluated in
    /// `S` (intervals: rigorous enclosures). Cheaper than [`eval_derivs`](Self::eval_derivs): no
    /// second derivatives are formed.
    pub fn first_derivs<S: Scalar>(&self, u: S, v: S) -> [[S; 3]; 3] {
        let (s, r, ku, kv) = self.normalise(u, v);
        let [h, hs, hr] = homogeneous_first(self.degree, s, r, |k| {
            self.homogeneous[k].map(S::from_interval)
        });
        let inv_w = S::one() / h[3];
        let z = S::zero();
        let mut out = [[z; 3]; 3];
        for c in 0..3 {
            let x = h[c] * inv_w;
            out[0][c] = x;
            out[1][c] = (hs[c] - x * hs[3]) * inv_w * ku;
            out[2][c] = (hr[c] - x * hr[3]) * inv_w * kv;
        }
        out
    }

    /// `(a, b, g)` with `S_u = a/g`, `S_v = b/g`, `g = w² > 0` (`w` the weight function): the
    /// quotient rule without its division, `a = (H_u w − H w_u)`, `b = (H_v w − H w_v)` on the
    /// homogeneous point `(H, w)`. Rigorous in intervals. `g` is formed as `(√(w²))²`, so a
    /// rigorous evaluation (and the validated engine's domain guard) fails rather than returning
    /// a value where `w` may vanish (where the patch is undefined).
    pub fn scaled_partials<S: Scalar>(&self, u: S, v: S) -> ([S; 3], [S; 3], S) {
        let (s, r, ku, kv) = self.normalise(u, v);
        let [h, hs, hr] = homogeneous_first(self.degree, s, r, |k| {
            self.homogeneous[k].map(S::from_interval)
        });
        let w = h[3];
        let z = S::zero();
        let (mut a, mut b) = ([z; 3], [z; 3]);
        for c in 0..3 {
            a[c] = (hs[c] * w - h[c] * hs[3]) * ku;
            b[c] = (hr[c] * w - h[c] * hr[3]) * kv;
        }
        (a, b, w.sqr().sqrt().sqr())
    }

    /// As [`scaled_partials`](Self::scaled_partials), with the patch written in the power basis
    /// around the centre `(cu, cv)` (any values; the result is the same function, only its
    /// interval widths change). Near the centre the terms are powers of the small offsets
    /// `u − cu`, `v − cv`, so interval and Taylor arithmetic see little dependency, unlike the
    /// Bernstein sums whose large terms cancel. The power-basis coefficients at the centre are
    /// `C(m,k)·C(n,l)·Σᵢⱼ (Δₛᵏ Δᵣˡ h)ᵢⱼ Bᵢ^{m−k}(cs) Bⱼ^{n−l}(cr)` (forward differences of the
    /// homogeneous net), formed in `S` (rigorous in intervals).
    #[allow(clippy::needless_range_loop)] // index arithmetic mirrors the formulas
    pub fn scaled_partials_centred<S: Scalar>(
        &self,
        u: S,
        v: S,
        cu: S,
        cv: S,
    ) -> ([S; 3], [S; 3], S) {
        let n = self.degree[1];
        let net = |i: usize, j: usize| self.homogeneous[i * (n + 1) + j].map(S::from_interval);
        self.scaled_partials_centred_by(u, v, cu, cv, |i, j, k, l| {
            forward_difference(&net, i, j, k, l)
        })
    }

    /// [`scaled_partials_centred`](Self::scaled_partials_centred) with the forward differences
    /// `Δₛᵏ Δᵣˡ` of the homogeneous net at `(i, j)` given by `diff(i, j, k, l)` (a caller that
    /// evaluates one patch many times computes them once).
    #[allow(clippy::needless_range_loop)] // index arithmetic mirrors the formulas
    pub(crate) fn scaled_partials_centred_by<S: Scalar>(
        &self,
        u: S,
        v: S,
        cu: S,
        cv: S,
        diff: impl Fn(usize, usize, usize, usize) -> [S; 4],
    ) -> ([S; 3], [S; 3], S) {
        let [m, n] = self.degree;
        let [[cs, cr], [ds, dr], [ku, kv]] = self.centred_offsets(u, v, cu, cv);
        let z = S::zero();
        // Forward differences Δₛᵏ Δᵣˡ of the homogeneous net, then the coefficients T_kl.
        let mut t = vec![[z; 4]; (m + 1) * (n + 1)];
        let mut bs = vec![z; m + 1];
        let mut br = vec![z; n + 1];
        for k in 0..=m {
            bernstein_values(m - k, cs, &mut bs);
            for l in 0..=n {
                bernstein_values(n - l, cr, &mut br);
                let mut acc = [z; 4];
                for i in 0..=m - k {
                    for j in 0..=n - l {
                        let diff = diff(i, j, k, l);
                        let b = bs[i] * br[j];
                        for c in 0..4 {
                            acc[c] = acc[c] + b * diff[c];
                        }
                    }
                }
                let scale = S::from_f64(binomial(m, k) * binomial(n, l));
                t[k * (n + 1) + l] = acc.map(|x| x * scale);
            }
        }
        // H, H_s, H_r by Horner in (ds, dr).
        let mut h = [z; 4];
        let mut hs = [z; 4];
        let mut hr = [z; 4];
        for k in (0..=m).rev() {
            let mut row = [z; 4];
            let mut row_r = [z; 4];
            for l in (0..=n).rev() {
                let c = t[k * (n + 1) + l];
                for x in 0..4 {
                    row[x] = row[x] * dr + c[x];
                    if l >= 1 {
                        row_r[x] = row_r[x] * dr + c[x] * S::from_f64(l as f64);
                    }
                }
            }
            for x in 0..4 {
                h[x] = h[x] * ds + row[x];
                hr[x] = hr[x] * ds + row_r[x];
                if k >= 1 {
                    hs[x] = hs[x] * ds + row[x] * S::from_f64(k as f64);
                }
            }
        }
        let w = h[3];
        let (mut a, mut b) = ([z; 3], [z; 3]);
        for c in 0..3 {
            a[c] = (hs[c] * w - h[c] * hs[3]) * ku;
            b[c] = (hr[c] * w - h[c] * hr[3]) * kv;
        }
        (a, b, w.sqr().sqrt().sqr())
    }

    /// Fast `f64` point and derivatives from the midpoint net (non-rigorous).
    pub fn derivs_f64(&self, u: f64, v: f64) -> PatchDerivs<f64> {
        let (s, r, ku, kv) = self.normalise(u, v);
        let h = homogeneous_derivs(self.degree, s, r, |k| self.mid[k]);
        rational_derivs(&h, ku, kv)
    }

    /// Fast `f64` point from the midpoint net (non-rigorous).
    pub fn point_f64(&self, u: f64, v: f64) -> [f64; 3] {
        let (s, r, _, _) = self.normalise(u, v);
        let h = homogeneous_point(self.degree, s, r, |k| self.mid[k]);
        [h[0] / h[3], h[1] / h[3], h[2] / h[3]]
    }
}

/// Largest degree handled with stack buffers; higher degrees use heap buffers.
const STACK_DEGREE: usize = 15;

/// Homogeneous point and its first partials in the normalised parameters: `[H, H_s, H_r]`.
#[allow(clippy::needless_range_loop)] // index arithmetic mirrors the formulas
fn homogeneous_first<S: Scalar>(
    [m, n]: [usize; 2],
    s: S,
    r: S,
    coeff: impl Fn(usize) -> [S; 4],
) -> [[S; 4]; 3] {
    let z = S::zero();
    let sum = |bu: &[S], du: &[S], bv: &[S], dv: &[S]| {
        let mut out = [[z; 4]; 3];
        for i in 0..=m {
            let mut row = [[z; 4]; 2];
            for j in 0..=n {
                let p = coeff(i * (n + 1) + j);
                for c in 0..4 {
                    row[0][c] = row[0][c] + bv[j] * p[c];
                    row[1][c] = row[1][c] + dv[j] * p[c];
                }
            }
            for c in 0..4 {
                out[0][c] = out[0][c] + bu[i] * row[0][c];
                out[1][c] = out[1][c] + du[i] * row[0][c];
                out[2][c] = out[2][c] + bu[i] * row[1][c];
            }
        }
        out
    };
    if m.max(n) <= STACK_DEGREE {
        let mut buf = [[z; STACK_DEGREE + 1]; 4];
        let [bu, du, bv, dv] = &mut buf;
        bernstein_first(m, s, bu, du);
        bernstein_first(n, r, bv, dv);
        sum(bu, du, bv, dv)
    } else {
        let (mut bu, mut du) = (vec![z; m + 1], vec![z; m + 1]);
        let (mut bv, mut dv) = (vec![z; n + 1], vec![z; n + 1]);
        bernstein_first(m, s, &mut bu, &mut du);
        bernstein_first(n, r, &mut bv, &mut dv);
        sum(&bu, &du, &bv, &dv)
    }
}

/// Homogeneous point and its partials in the normalised parameters `(s, r)`:
/// `[H, H_s, H_r, H_ss, H_sr, H_rr]`, each 4 components.
fn homogeneous_derivs<S: Scalar>(
    degree: [usize; 2],
    s: S,
    r: S,
    coeff: impl Fn(usize) -> [S; 4],
) -> [[S; 4]; 6] {
    let [m, n] = degree;
    if m.max(n) <= STACK_DEGREE {
        let z = S::zero();
        let mut buf = [[z; STACK_DEGREE + 1]; 6];
        let [bu, du, ddu, bv, dv, ddv] = &mut buf;
        bernstein(m, s, bu, du, ddu);
        bernstein(n, r, bv, dv, ddv);
        tensor_derivs(degree, [bu, du, ddu], [bv, dv, ddv], coeff)
    } else {
        let z = S::zero();
        let (mut bu, mut du, mut ddu) = (vec![z; m + 1], vec![z; m + 1], vec![z; m + 1]);
        let (mut bv, mut dv, mut ddv) = (vec![z; n + 1], vec![z; n + 1], vec![z; n + 1]);
        bernstein(m, s, &mut bu, &mut du, &mut ddu);
        bernstein(n, r, &mut bv, &mut dv, &mut ddv);
        tensor_derivs(degree, [&bu, &du, &ddu], [&bv, &dv, &ddv], coeff)
    }
}

#[allow(clippy::needless_range_loop)] // index arithmetic mirrors the formulas
/// Sum the tensor product of the u- and v-basis (values, first, second derivatives) with the net.
fn tensor_derivs<S: Scalar>(
    [m, n]: [usize; 2],
    [bu, du, ddu]: [&[S]; 3],
    [bv, dv, ddv]: [&[S]; 3],
    coeff: impl Fn(usize) -> [S; 4],
) -> [[S; 4]; 6] {
    let z = S::zero();
    let mut out = [[z; 4]; 6];
    for i in 0..=m {
        // Row sums over j of the basis in v and its derivatives.
        let mut row = [[z; 4]; 3];
        for j in 0..=n {
            let p = coeff(i * (n + 1) + j);
            for c in 0..4 {
                let p = p[c];
                row[0][c] = row[0][c] + bv[j] * p;
                row[1][c] = row[1][c] + dv[j] * p;
                row[2][c] = row[2][c] + ddv[j] * p;
            }
        }
        for c in 0..4 {
            out[0][c] = out[0][c] + bu[i] * row[0][c];
            out[1][c] = out[1][c] + du[i] * row[0][c];
            out[2][c] = out[2][c] + bu[i] * row[1][c];
            out[3][c] = out[3][c] + ddu[i] * row[0][c];
            out[4][c] = out[4][c] + du[i] * row[1][c];
            out[5][c] = out[5][c] + bu[i] * row[2][c];
        }
    }
    out
}

/// Homogeneous point only.
#[allow(clippy::needless_range_loop)] // index arithmetic mirrors the formulas
fn homogeneous_point<S: Scalar>(
    [m, n]: [usize; 2],
    s: S,
    r: S,
    coeff: impl Fn(usize) -> [S; 4],
) -> [S; 4] {
    let z = S::zero();
    let sum = |bu: &[S], bv: &[S]| {
        let mut out = [z; 4];
        for i in 0..=m {
            let mut row = [z; 4];
            for j in 0..=n {
                let p = coeff(i * (n + 1) + j);
                for (x, p) in row.iter_mut().zip(p) {
                    *x = *x + bv[j] * p;
                }
            }
            for c in 0..4 {
                out[c] = out[c] + bu[i] * row[c];
            }
        }
        out
    };
    if m.max(n) <= STACK_DEGREE {
        let (mut bu, mut bv) = ([z; STACK_DEGREE + 1], [z; STACK_DEGREE + 1]);
        bernstein_values(m, s, &mut bu);
        bernstein_values(n, r, &mut bv);
        sum(&bu, &bv)
    } else {
        let (mut bu, mut bv) = (vec![z; m + 1], vec![z; n + 1]);
        bernstein_values(m, s, &mut bu);
        bernstein_values(n, r, &mut bv);
        sum(&bu, &bv)
    }
}

/// Quotient rule on the homogeneous derivatives, then the chain rule `∂/∂u = ku ∂/∂s`,
/// `∂/∂v = kv ∂/∂r`.
fn rational_derivs<S: Scalar>(h: &[[S; 4]; 6], ku: S, kv: S) -> PatchDerivs<S> {
    let [n, ns, nr, nss, nsr, nrr] = h;
    let inv_w = S::one() / n[3];
    let (ws, wr, wss, wsr, wrr) = (ns[3], nr[3], nss[3], nsr[3], nrr[3]);
    let z = S::zero();
    let mut d = PatchDerivs {
        p: [z; 3],
        su: [z; 3],
        sv: [z; 3],
        suu: [z; 3],
        suv: [z; 3],
        svv: [z; 3],
    };
    let (ku2, kv2, kuv) = (ku.sqr(), kv.sqr(), ku * kv);
    let two = S::from_f64(2.0);
    for c in 0..3 {
        let x = n[c] * inv_w;
        let xs = (ns[c] - x * ws) * inv_w;
        let xr = (nr[c] - x * wr) * inv_w;
        let xss = (nss[c] - two * xs * ws - x * wss) * inv_w;
        let xsr = (nsr[c] - xs * wr - xr * ws - x * wsr) * inv_w;
        let xrr = (nrr[c] - two * xr * wr - x * wrr) * inv_w;
        d.p[c] = x;
        d.su[c] = xs * ku;
        d.sv[c] = xr * kv;
        d.suu[c] = xss * ku2;
        d.suv[c] = xsr * kuv;
        d.svv[c] = xrr * kv2;
    }
    d
}

fn vec3(a: [f64; 3]) -> Vec3 {
    Vec3::new(a[0], a[1], a[2])
}

impl ParametricSurface for RationalBezierPatch {
    fn domain(&self) -> Domain {
        self.domain
    }

    fn derivs(&self, u: f64, v: f64) -> SurfaceDerivs {
        let d = self.derivs_f64(u, v);
        SurfaceDerivs {
            p: vec3(d.p),
            su: vec3(d.su),
            sv: vec3(d.sv),
            suu: vec3(d.suu),
            suv: vec3(d.suv),
            svv: vec3(d.svv),
        }
    }

    fn point(&self, u: f64, v: f64) -> Vec3 {
        vec3(self.point_f64(u, v))
    }

    fn poles(&self) -> Vec<Vec3> {
        crate::geometry::collapsed::distinct_poles(&self.collapsed)
    }
}

/// Test fixture: a quarter of the unit cylinder `x² + y² = 1`, `0 ≤ z ≤ 1` (rational, degree
/// 2 × 1, weights `cos 45°` on the middle row), over `domain`.
#[cfg(test)]
pub(crate) fn quarter_cylinder_over(domain: crate::geometry::Domain) -> RationalBezierPatch {
    let h = std::f64::consts::FRAC_1_SQRT_2;
    let net = [
        [1.0, 0.0, 0.0],
        [1.0, 0.0, 1.0],
        [1.0, 1.0, 0.0],
        [1.0, 1.0, 1.0],
        [0.0, 1.0, 0.0],
        [0.0, 1.0, 1.0],
    ];
    let w = [1.0, 1.0, h, h, 1.0, 1.0];
    RationalBezierPatch::from_f64_points([2, 1], &net, Some(&w), domain).unwrap()
}
