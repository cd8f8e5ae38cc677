//! One link of a cover chain: the curve over an interval of one parameter, proven to be a graph
//! within a thin tube around a polynomial predictor.
//!
//! Write the four parameters as `x_j` (the *along* coordinate) and the other three `x_o`. A
//! segment has an interval `Ξ` of `ξ = x_j − x0`, a predictor `o(ξ)` (of degree
//! [`PREDICTOR_DEGREE`] in `ξ`, `f64` coefficients, exact as written) and a box `Y` of
//! offsets around it. With
//! `F = P(σ,t) − Q(u,v)`, `g(ξ) = F(x0 + ξ, o(ξ))`, a preconditioner `C` and the Jacobian
//! `J_o = ∂F/∂x_o` enclosed over the tube's hull `B = (x0 + Ξ) × (o(Ξ) + Y)`:
//!
//! ```text
//! K = −C·g(Ξ) + (I − C·J_o(B))·Y ⊂ int Y
//! ```
//!
//! proves that for every `ξ ∈ Ξ` the curve meets the slice `x_j = x0 + ξ` of the tube
//! `{(x0 + ξ, o(ξ) + y) : y ∈ Y}` in exactly one point, and that its offset lies in `K`. (For
//! fixed `ξ` this is Krawczyk's operator of `y ↦ F(x0 + ξ, o(ξ) + y)` with centre 0, and every
//! term is enclosed over all of `Ξ`.) So inside the tube the curve is one arc, a graph over
//! `x_j`, from the first slice to the last, within `K` of the predictor.
//!
//! The width of `g(Ξ)` decides everything: evaluated directly it would be as wide as `F` varies
//! over the tube's diagonal. It is enclosed instead by a Taylor form in `ξ`: the coefficients of
//! `g` at the centre of `Ξ` up to order [`ORDER`] ([`SeriesN`] arithmetic on the patches), and the
//! Lagrange remainder with the next coefficient enclosed over all of `Ξ`. The predictor
//! interpolates two curve points and their tangents, so the low coefficients nearly cancel and
//! `g(Ξ)` is about as wide as the predictor's error, not the segment's length.
//!
//! This replaces, for transversal branches, the validated ODE step of [`crate::validated`]: no
//! solution series, no a-priori box over the diagonal in all four parameters, no Lohner
//! wrapping; one Taylor form of `F` along a known polynomial and one interval Jacobian.

use crate::certify::exact_residual::exact_residual;
use crate::certify::lean_patch::{Centred, LeanPatch};
use crate::geometry::bernstein::binomial;
use crate::numeric::imul::mul as imul;
use crate::numeric::scalar::{meet, point};
#[cfg(not(target_feature = "avx512f"))]
use crate::validated::MidRadSeries;
use crate::validated::SeriesN;
use inari::Interval;
use nalgebra::Matrix3;

/// Order of the Taylor form of `g` (the remainder uses the next coefficient).
pub(crate) const ORDER: usize = 8;

/// Degree of the predictor.
pub(crate) const PREDICTOR_DEGREE: usize = 7;

pub(crate) use super::jet::{others, Jet};

/// A polynomial predictor of the three other coordinates as functions of `ξ = x_j − x0`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Predictor {
    /// The along coordinate `j`.
    pub(crate) along: usize,
    /// Origin of `ξ`.
    pub(crate) x0: f64,
    /// `o_r(ξ) = Σₖ c[k][r]·ξᵏ`, `r` over [`others`]`(along)`.
    pub(crate) c: [[f64; 3]; PREDICTOR_DEGREE + 1],
}

impl Predictor {
    /// The septic Hermite predictor matching the jets `a` and `b` (values and three
    /// derivatives at both ends; graphed over the same
    /// coordinate `along`); `None` if `along` does not move between them.
    pub(crate) fn hermite(along: usize, a: &Jet, b: &Jet) -> Option<Predictor> {
        let l = b.x[along] - a.x[along];
        if l == 0.0 || !l.is_finite() {
            return None;
        }
        let o = others(along);
        let mut c = [[0.0; 3]; PREDICTOR_DEGREE + 1];
        let l2 = l * l;
        let l3 = l2 * l;
        for (r, &i) in o.iter().enumerate() {
            let (va, vb) = (a.x[i], b.x[i]);
            let (da, db) = (l * a.d1[r], l * b.d1[r]);
            let (dda, ddb) = (l2 * a.d2[r], l2 * b.d2[r]);
            let (ddda, dddb) = (l3 * a.d3[r], l3 * b.d3[r]);
            let q = [va, da, 0.5 * dda, ddda / 6.0];
            let r0 = vb - (q[0] + q[1] + q[2] + q[3]);
            let r1 = db - (q[1] + 2.0 * q[2] + 3.0 * q[3]);
            let r2 = ddb - (2.0 * q[2] + 6.0 * q[3]);
            let r3 = dddb - 6.0 * q[3];
            let s = [
                q[0],
                q[1],
                q[2],
                q[3],
                35.0 * r0 - 15.0 * r1 + 2.5 * r2 - r3 / 6.0,
                -84.0 * r0 + 39.0 * r1 - 7.0 * r2 + 0.5 * r3,
                70.0 * r0 - 34.0 * r1 + 6.5 * r2 - 0.5 * r3,
                -20.0 * r0 + 10.0 * r1 - 2.0 * r2 + r3 / 6.0,
            ];
            let mut lk = 1.0;
            for k in 0..=PREDICTOR_DEGREE {
                c[k][r] = s[k] / lk;
                lk *= l;
            }
        }
        let p = Predictor {
            along,
            x0: a.x[along],
            c,
        };
        p.c.iter().flatten().all(|v| v.is_finite()).then_some(p)
    }

    /// The predicted point `(σ, t, u, v)` at `x_j = x0 + ξ` (`f64`, not a bound).
    pub(crate) fn eval(&self, xi: f64) -> [f64; 4] {
        let mut y = [0.0; 4];
        y[self.along] = self.x0 + xi;
        for (r, &i) in others(self.along).iter().enumerate() {
            y[i] = self.c.iter().rev().fold(0.0, |acc, c| acc * xi + c[r]);
        }
        y
    }

    /// Enclosure of the predicted other coordinates over `ξ ∈ xi`.
    pub(crate) fn others_over(&self, xi: Interval) -> [Interval; 3] {
        std::array::from_fn(|r| {
            self.c
                .iter()
                .rev()
                .fold(point(0.0), |acc, c| imul(acc, xi) + point(c[r]))
        })
    }

    /// The coefficients of `o(ζ + τ)` in `τ`, enclosed for every `ζ ∈ centre`
    /// (`Σ_{i≥k} C(i,k)·c_i·ζ^{i−k}`).
    fn shifted(&self, centre: Interval) -> [[Interval; 3]; PREDICTOR_DEGREE + 1] {
        let mut pow = [point(1.0); PREDICTOR_DEGREE + 1];
        for m in 1..=PREDICTOR_DEGREE {
            pow[m] = imul(pow[m - 1], centre);
        }
        std::array::from_fn(|k| {
            std::array::from_fn(|r| {
                (k..=PREDICTOR_DEGREE).fold(point(0.0), |acc, i| {
                    acc + imul(imul(point(BINOMIAL[i][k]), point(self.c[i][r])), pow[i - k])
                })
            })
        })
    }

    /// The four coordinates as series in `τ` around `ζ ∈ centre`, of length `len ≤ N`, from
    /// `sh`, the coefficients [`shifted`](Self::shifted) to `centre`.
    fn series<const N: usize>(
        &self,
        sh: &[[Interval; 3]; PREDICTOR_DEGREE + 1],
        centre: Interval,
        len: usize,
    ) -> [SeriesN<N>; 4] {
        let zero = point(0.0);
        let mut out = [SeriesN::<N>::constant(zero); 4];
        let mut coeffs = [zero; 16];
        coeffs[0] = point(self.x0) + centre;
        coeffs[1] = point(1.0);
        out[self.along] = SeriesN::new(&coeffs[..len]);
        for (r, &i) in others(self.along).iter().enumerate() {
            let mut c = [zero; 16];
            for k in 0..=PREDICTOR_DEGREE {
                c[k] = sh[k][r];
            }
            out[i] = SeriesN::new(&c[..len]);
        }
        out
    }
}

/// The series type of the residual: coefficients up to the remainder's order.
type Long = SeriesN<{ ORDER + 2 }>;
/// The series type of the Jacobian: coefficients up to its remainder's order (3).
type Short = SeriesN<4>;

/// The series arithmetic of the patches along the predictor ([`both_along`], [`jacobian`]):
/// without AVX-512, the midpoint–radius form in round-to-nearest, since inari then switches the
/// rounding mode around every interval operation (built for AVX2, a chain takes 12–27 % less
/// time on the sphere, Viviani, the cylinders and Fig. 7); with AVX-512, inari's intervals,
/// whose products round in the instruction (the midpoint–radius form measured 0–4 % slower
/// there). Both enclose the exact series.
#[cfg(not(target_feature = "avx512f"))]
fn fast<const N: usize>(s: &SeriesN<N>) -> MidRadSeries<N> {
    MidRadSeries::from_series(s)
}
#[cfg(not(target_feature = "avx512f"))]
fn back<const N: usize>(s: MidRadSeries<N>) -> SeriesN<N> {
    s.to_series()
}
#[cfg(target_feature = "avx512f")]
fn fast<const N: usize>(s: &SeriesN<N>) -> SeriesN<N> {
    *s
}
#[cfg(target_feature = "avx512f")]
fn back<const N: usize>(s: SeriesN<N>) -> SeriesN<N> {
    s
}

/// `P` and `Q` along `y` (series arguments).
#[inline(never)]
fn both_along(p: &Centred<'_>, q: &Centred<'_>, y: &[Long; 4]) -> [[Long; 3]; 2] {
    let y = y.each_ref().map(fast);
    [p.eval(y[0], y[1]).map(back), q.eval(y[2], y[3]).map(back)]
}

/// Narrows the residual's value at the centre, `g_c`'s first coefficients, to the exact
/// residual there ([`exact_residual`]) when the centre's point is exact (`f64` coordinates)
/// and so are both patches; the interval evaluation leaves tens of ulps of the model's size in
/// it, which over nearly tangent surfaces sets the tube.
fn with_exact_residual(g_c: &mut [Long; 3], at_centre: &[Long; 4], lean: [&LeanPatch<'_>; 2]) {
    let x = at_centre.each_ref().map(|s| s.coeff(0));
    if x.iter().any(|v| v.inf() != v.sup()) {
        return;
    }
    let x = x.map(|v| v.inf());
    let Some(exact) = exact_residual(lean[0].source(), lean[1].source(), &x) else {
        return;
    };
    for (g, e) in g_c.iter_mut().zip(exact) {
        let mut c = [point(0.0); ORDER + 2];
        let kept = g.coeffs();
        c[..kept.len()].copy_from_slice(kept);
        c[0] = meet(c[0], e);
        *g = Long::new(&c[..kept.len()]);
    }
}

/// `P − Q` from [`both_along`].
fn residual([a, b]: &[[Long; 3]; 2]) -> [Long; 3] {
    std::array::from_fn(|r| a[r] - b[r])
}

/// The model points of the curve over the whole segment, enclosed on one surface: the surface
/// along the predictor (its Taylor form: coefficients `at_c` at the centre, the next one
/// `at_o` over all of Ξ) plus the mean-value change to the curve, `Σ ∂S/∂x_c · k_c` over that
/// surface's free coordinates (`jac` holds `±∂S/∂x_c` over the segments from the predictor to
/// the curve; `sign` undoes the minus of `Q`'s columns).
fn model_along(
    at_c: &[Long; 3],
    at_o: &[Long; 3],
    tau: Interval,
    proof: &SegmentProof,
    surface: usize,
) -> [Interval; 3] {
    let sign = if surface == 0 { 1.0 } else { -1.0 };
    std::array::from_fn(|r| {
        let mut acc = at_o[r].coeff(ORDER + 1);
        for k in (0..=ORDER).rev() {
            acc = imul(acc, tau) + at_c[r].coeff(k);
        }
        for (c, &i) in others(proof.pred.along).iter().enumerate() {
            if i / 2 == surface {
                acc += imul(point(sign), imul(proof.jac[r][c], proof.k[c]));
            }
        }
        acc
    })
}

/// The Jacobian columns of `P − Q` for the coordinates `free` along `y` (`jac[col][row]`).
#[inline(never)]
fn jacobian(
    p: &Centred<'_>,
    q: &Centred<'_>,
    y: &[Short; 4],
    free: &[usize; 3],
) -> [[Short; 3]; 3] {
    let y = y.each_ref().map(fast);
    let [a_s, a_t] = p.partials(y[0], y[1]).map(|v| v.map(back));
    let [b_u, b_v] = q.partials(y[2], y[3]).map(|v| v.map(back));
    let neg = |v: [Short; 3]| v.map(|x| -x);
    let cols = [a_s, a_t, neg(b_u), neg(b_v)];
    free.map(|k| cols[k])
}

/// Interval 3×3 matrices, `m[row][col]`.
type IMat = [[Interval; 3]; 3];

fn imat(m: &Matrix3<f64>) -> IMat {
    std::array::from_fn(|r| std::array::from_fn(|c| point(m[(r, c)])))
}

/// `a·b`.
fn mul(a: &IMat, b: &IMat) -> IMat {
    std::array::from_fn(|r| {
        std::array::from_fn(|c| {
            imul(a[r][0], b[0][c]) + imul(a[r][1], b[1][c]) + imul(a[r][2], b[2][c])
        })
    })
}

/// The Jacobian's Taylor coefficient `k` as a matrix `[row][col]`.
fn coeff_mat(jac: &[[Short; 3]; 3], k: usize) -> IMat {
    std::array::from_fn(|r| std::array::from_fn(|c| jac[c][r].coeff(k)))
}

fn combine(a: &IMat, b: &IMat, f: impl Fn(Interval, Interval) -> Interval) -> IMat {
    std::array::from_fn(|r| std::array::from_fn(|c| f(a[r][c], b[r][c])))
}

/// Second derivatives of `P − Q` over the box `b`: `h[col][c2]` is
/// `∂²F/∂x_free[col]∂x_free[c2]` (a 3-vector; zero between a P and a Q parameter).
type Hessian = [[[Interval; 3]; 3]; 3];

/// The second derivatives of `P − Q` in the coordinates `free`, enclosed over `b`.
#[inline(never)]
fn hessian_over(p: &Centred<'_>, q: &Centred<'_>, b: &[Interval; 4], free: &[usize; 3]) -> Hessian {
    let [puu, puv, pvv] = p.second_partials(b[0], b[1]);
    let [quu, quv, qvv] = q.second_partials(b[2], b[3]);
    let zero = [point(0.0); 3];
    let second = |i: usize, k: usize| -> [Interval; 3] {
        match (i, k) {
            (0, 0) => puu,
            (0, 1) | (1, 0) => puv,
            (1, 1) => pvv,
            (2, 2) => quu.map(|x| -x),
            (2, 3) | (3, 2) => quv.map(|x| -x),
            (3, 3) => qvv.map(|x| -x),
            _ => zero,
        }
    };
    std::array::from_fn(|col| std::array::from_fn(|c2| second(free[col], free[c2])))
}

/// Enclosure of the change of the Jacobian columns over the offsets `y` from the predictor,
/// `Σ_c' h[col][c'] · y_c'` (`h` over a box holding those points), as a matrix `[row][col]`.
fn jacobian_change(h: &Hessian, y: &[Interval; 3]) -> IMat {
    std::array::from_fn(|r| {
        std::array::from_fn(|col| {
            (0..3).fold(point(0.0), |acc, c2| acc + imul(h[col][c2][r], y[c2]))
        })
    })
}

/// `A(τ) = I − C(τ)·J_o(τ)` on the predictor over `τ ∈ tau`, as
/// `A0 + A1·τ + A2·τ² + A3(η)·τ³` (`Aₖ = δₖ₀·I − Σ_{a+b=k} C_a·J_b`, the last with the Taylor
/// coefficients of `C` and `J` at any `η` of the segment).
#[inline(never)]
fn contraction_along(
    j_c: &[[Short; 3]; 3],
    j_o: &[[Short; 3]; 3],
    cs: &[IMat; 3],
    tau: Interval,
) -> IMat {
    let jc: [IMat; 3] = std::array::from_fn(|k| coeff_mat(j_c, k));
    let jo: [IMat; 4] = std::array::from_fn(|k| coeff_mat(j_o, k));
    let add = |a: &IMat, b: &IMat| combine(a, b, |x, y| x + y);
    let neg = |a: &IMat| combine(a, a, |x, _| -x);
    let eye: IMat =
        std::array::from_fn(|r| std::array::from_fn(|c| point(if r == c { 1.0 } else { 0.0 })));
    let a0 = add(&eye, &neg(&mul(&cs[0], &jc[0])));
    let a1 = neg(&add(&mul(&cs[0], &jc[1]), &mul(&cs[1], &jc[0])));
    let a2 = neg(&add(
        &add(&mul(&cs[0], &jc[2]), &mul(&cs[1], &jc[1])),
        &mul(&cs[2], &jc[0]),
    ));
    // Taylor coefficients of C at η = centre + τ, τ ∈ tau.
    let c_eta0: IMat = std::array::from_fn(|r| {
        std::array::from_fn(|c| cs[0][r][c] + imul(tau, cs[1][r][c] + imul(tau, cs[2][r][c])))
    });
    let c_eta1: IMat = std::array::from_fn(|r| {
        std::array::from_fn(|c| cs[1][r][c] + imul(imul(point(2.0), cs[2][r][c]), tau))
    });
    let a3 = neg(&add(
        &add(&mul(&c_eta0, &jo[3]), &mul(&c_eta1, &jo[2])),
        &mul(&cs[2], &jo[1]),
    ));
    std::array::from_fn(|r| {
        std::array::from_fn(|c| {
            a0[r][c] + imul(tau, a1[r][c] + imul(tau, a2[r][c] + imul(tau, a3[r][c])))
        })
    })
}

/// The Jacobian columns along the predictor over `τ ∈ tau`: `J0 + J1·τ + J2·τ² + J3(η)·τ³`.
fn jacobian_along(j_c: &[[Short; 3]; 3], j_o: &[[Short; 3]; 3], tau: Interval) -> IMat {
    let jc: [IMat; 3] = std::array::from_fn(|k| coeff_mat(j_c, k));
    let j3 = coeff_mat(j_o, 3);
    std::array::from_fn(|r| {
        std::array::from_fn(|c| {
            jc[0][r][c]
                + imul(
                    tau,
                    jc[1][r][c] + imul(tau, jc[2][r][c] + imul(tau, j3[r][c])),
                )
        })
    })
}

/// `C(τ)·g(τ)` over `τ ∈ tau`, coefficient by coefficient so that the components'
/// cancellation is kept: `h_k = Σ_a C_a·g_{k−a}` up to the order, and the top term (times
/// `τ^{n+1}`) `C0·R + C1·(g_n + R·τ) + C2·(g_{n−1} + g_n·τ + R·τ²)` with `R` the next
/// coefficient over Ξ.
#[inline(never)]
fn preconditioned_residual(
    g_c: &[Long; 3],
    g_o: &[Long; 3],
    cs: &[IMat; 3],
    tau: Interval,
) -> [Interval; 3] {
    let gk = |k: usize, i: usize| g_c[i].coeff(k);
    let rem = |i: usize| g_o[i].coeff(ORDER + 1);
    std::array::from_fn(|r| {
        let dot = |m: &IMat, v: &dyn Fn(usize) -> Interval| {
            imul(m[r][0], v(0)) + imul(m[r][1], v(1)) + imul(m[r][2], v(2))
        };
        let mut h = [point(0.0); ORDER + 2];
        h[ORDER + 1] = dot(&cs[0], &rem)
            + dot(&cs[1], &|i| gk(ORDER, i) + imul(rem(i), tau))
            + dot(&cs[2], &|i| {
                gk(ORDER - 1, i) + imul(tau, gk(ORDER, i) + imul(rem(i), tau))
            });
        for (k, hk) in h.iter_mut().enumerate().take(ORDER + 1) {
            for (a, m) in cs.iter().enumerate() {
                if k >= a {
                    *hk += dot(m, &|i| gk(k - a, i));
                }
            }
        }
        polynomial_range(&h, tau)
    })
}

/// The range of `Σ h_k τ^k` over `τ ∈ tau` (interval coefficients: every polynomial with
/// coefficients in them), enclosed: Horner's rule, intersected with the hull of the Bernstein
/// coefficients on `[tau.inf, 0]` and on `[0, tau.sup]` when `tau` holds 0 inside.
///
/// The residual along a link's predictor vanishes to third order at both ends, like
/// `(τ² − r²)³`; Horner over `[−r, r]` bounds it by the sum of its coefficients' magnitudes, 8
/// times its maximum, while the Bernstein hulls of the two halves hold it exactly (on each
/// half, `τ = b·x` with `x ∈ [0, 1]`, so the coefficients in `x` are `h_k·bᵏ`, and the Bernstein
/// coefficients of a degree-`n` polynomial `Σ c_k xᵏ` are `b_i = Σ_{k ≤ i} C(i,k)/C(n,k)·c_k`).
fn polynomial_range(h: &[Interval; ORDER + 2], tau: Interval) -> Interval {
    let horner = h
        .iter()
        .rev()
        .fold(point(0.0), |acc, &c| imul(acc, tau) + c);
    let (lo, hi) = (tau.inf(), tau.sup());
    if !(lo < 0.0 && 0.0 < hi && lo.is_finite() && hi.is_finite()) {
        return horner;
    }
    let ratios = bernstein_ratios();
    let mut hull: Option<Interval> = None;
    for end in [lo, hi] {
        // c_k = h_k·endᵏ.
        let mut c = [point(0.0); ORDER + 2];
        let mut pow = point(1.0);
        for k in 0..=ORDER + 1 {
            c[k] = imul(h[k], pow);
            pow = imul(pow, point(end));
        }
        for (i, row) in ratios.iter().enumerate() {
            let b = (0..=i).fold(point(0.0), |acc, k| acc + imul(row[k], c[k]));
            hull = Some(hull.map_or(b, |x| x.convex_hull(b)));
        }
    }
    match hull {
        Some(b) if !b.is_empty() && !horner.intersection(b).is_empty() => horner.intersection(b),
        _ => horner,
    }
}

/// `C(n, k)` for `n, k ≤ ORDER + 1` (exact small integers; zero for `k > n`), tabled at compile
/// time from [`binomial`].
const BINOMIAL: [[f64; ORDER + 2]; ORDER + 2] = {
    let mut t = [[0.0; ORDER + 2]; ORDER + 2];
    let mut n = 0;
    while n < ORDER + 2 {
        let mut k = 0;
        while k <= n {
            t[n][k] = binomial(n, k);
            k += 1;
        }
        n += 1;
    }
    t
};

/// `C(i, k)/C(n, k)` for `k ≤ i ≤ n = ORDER + 1`, enclosed: the Bernstein coefficient `b_i` of
/// `Σ c_k xᵏ` on `[0, 1]` in degree `n` is `Σ_{k ≤ i} C(i,k)/C(n,k)·c_k`.
fn bernstein_ratios() -> &'static [[Interval; ORDER + 2]; ORDER + 2] {
    static RATIOS: std::sync::OnceLock<[[Interval; ORDER + 2]; ORDER + 2]> =
        std::sync::OnceLock::new();
    RATIOS.get_or_init(|| {
        let n = ORDER + 1;
        std::array::from_fn(|i| {
            std::array::from_fn(|k| {
                if k <= i {
                    point(BINOMIAL[i][k]) / point(BINOMIAL[n][k])
                } else {
                    point(0.0)
                }
            })
        })
    })
}

/// The Krawczyk image `−C·g + (A − C·ΔJ(x))·x` of the offsets `x`; `None` if unbounded.
#[inline(never)]
fn krawczyk_image(
    h: &Hessian,
    x: &[Interval; 3],
    a_over: &IMat,
    c_over: &IMat,
    cg: &[Interval; 3],
) -> Option<[Interval; 3]> {
    // The Jacobian over the segments from the predictor (offset 0) to every offset in x.
    let dj = jacobian_change(h, &with_zero(x));
    let m = combine(a_over, &mul(c_over, &dj), |a, b| a - b);
    let k: [Interval; 3] = std::array::from_fn(|r| {
        -cg[r] + imul(m[r][0], x[0]) + imul(m[r][1], x[1]) + imul(m[r][2], x[2])
    });
    k.iter()
        .all(|v| !v.is_empty() && v.inf().is_finite() && v.sup().is_finite())
        .then_some(k)
}

/// The smallest box holding `x` and the origin (the segments from the predictor to the points
/// of `x` lie in it).
fn with_zero(x: &[Interval; 3]) -> [Interval; 3] {
    x.map(|v| v.convex_hull(point(0.0)))
}

/// Why a segment could not be proven.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum SegmentFailure {
    /// The Jacobian at the centre is singular or an enclosure is unbounded.
    Singular,
    /// The Krawczyk image does not fit inside the box (segment too long, or near-singular).
    NotContracting,
    /// The two patches' forms are moved by different vectors (`LeanPatch::moved`): their
    /// differences are not the patches', and nothing is proven.
    MovedApart,
}

/// A proven segment: for every `x_j ∈ x0 + xi` the curve meets the tube in exactly one point,
/// with offsets from the predictor in `k` (uniquely within `y`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct SegmentProof {
    /// The predictor.
    pub(crate) pred: Predictor,
    /// The interval of `ξ = x_j − x0` covered (outward-rounded from `f64` ends `x_range`).
    pub(crate) xi: Interval,
    /// The covered values of `x_j` (`f64` ends, increasing).
    pub(crate) x_range: [f64; 2],
    /// The uniqueness box of the offsets.
    pub(crate) y: [Interval; 3],
    /// The enclosure of the offsets, for every `ξ ∈ xi`.
    pub(crate) k: [Interval; 3],
    /// The Jacobian columns `∂(P − Q)/∂x_o` (`[row][col]`, columns in [`others`] order),
    /// enclosed over every point between the predictor and the curve within the segment (offsets
    /// in the hull of `k` and 0).
    pub(crate) jac: [[Interval; 3]; 3],
    /// The model-space points of the curve for every `ξ ∈ xi`, enclosed (on `P` and on `Q`,
    /// intersected).
    pub(crate) model: [Interval; 3],
}

impl SegmentProof {
    /// The box `(σ, t, u, v)` holding the curve for `x_j ∈ [lo, hi]` (a part of `x_range`).
    pub(crate) fn box_over(&self, lo: f64, hi: f64) -> [Interval; 4] {
        self.box_with(lo, hi, &self.k)
    }

    /// The box of the tube (offsets `y`) over `x_j ∈ [lo, hi]`.
    pub(crate) fn tube_over(&self, lo: f64, hi: f64) -> [Interval; 4] {
        self.box_with(lo, hi, &self.y)
    }

    fn box_with(&self, lo: f64, hi: f64, off: &[Interval; 3]) -> [Interval; 4] {
        let j = self.pred.along;
        let xj = hull(lo, hi);
        let xi = xj - point(self.pred.x0);
        let o = self.pred.others_over(xi);
        let mut b = [xj; 4];
        for (r, &i) in others(j).iter().enumerate() {
            b[i] = o[r] + off[r];
        }
        b
    }

    /// Whether every point of `bx` lies in the tube (so the curve through any curve point of
    /// `bx` is the arc this segment proves).
    pub(crate) fn tube_contains(&self, bx: &[Interval; 4]) -> bool {
        let j = self.pred.along;
        let xj = hull(self.x_range[0], self.x_range[1]);
        if !bx[j].subset(xj) {
            return false;
        }
        let o = self.pred.others_over(bx[j] - point(self.pred.x0));
        others(j)
            .iter()
            .enumerate()
            .all(|(r, &i)| (bx[i] - o[r]).subset(self.y[r]))
    }
}

/// The interval `[min(a, b), max(a, b)]`.
pub(crate) fn hull(a: f64, b: f64) -> Interval {
    inari::interval!(a.min(b), a.max(b)).unwrap_or(Interval::ENTIRE)
}

/// Proves the segment of `pred` over `x_j ∈ x_range` (increasing `f64` ends), with a uniqueness
/// box at least `need` wide in each offset (half-widths; so that boxes that must lie in the tube
/// do).
pub(crate) fn prove_segment(
    lean: [&LeanPatch<'_>; 2],
    pred: Predictor,
    x_range: [f64; 2],
    need: [f64; 3],
    precise: bool,
) -> Result<SegmentProof, SegmentFailure> {
    if lean[0].shift() != lean[1].shift() {
        return Err(SegmentFailure::MovedApart);
    }
    // The patches' forms are truncated to a window: the predictor's range over the segment and
    // room for the offsets' box. Should the tube leave it, the proof runs again on whole forms.
    let xi = hull(x_range[0], x_range[1]) - point(pred.x0);
    let o = pred.others_over(xi);
    let mut window = [point(pred.x0) + xi; 4];
    for (r, &i) in others(pred.along).iter().enumerate() {
        let room = 1.5 * need[r];
        window[i] = o[r] + inari::interval!(-room, room).unwrap_or(Interval::ENTIRE);
    }
    match prove_within(lean, pred, x_range, need, Some(window), precise) {
        Ok(proof) => Ok(proof),
        Err(Some(failure)) => Err(failure),
        Err(None) => prove_within(lean, pred, x_range, need, None, precise)
            .map_err(|f| f.unwrap_or(SegmentFailure::Singular)),
    }
}

/// [`prove_segment`] with the patches' forms truncated to `window` (a box in all four
/// parameters); `Err(None)` if the tube does not lie inside it.
fn prove_within(
    lean: [&LeanPatch<'_>; 2],
    pred: Predictor,
    x_range: [f64; 2],
    need: [f64; 3],
    window: Option<[Interval; 4]>,
    precise: bool,
) -> Result<SegmentProof, Option<SegmentFailure>> {
    let j = pred.along;
    let free = others(j);
    let xi = hull(x_range[0], x_range[1]) - point(pred.x0);
    // Any centre in Ξ serves; ξ = 0 (the link's start) makes the centre's point the
    // predictor's exact (x0, c[0]), whose residual can be exact (`with_exact_residual`).
    let centre = if precise && xi.contains(0.0) {
        0.0
    } else {
        xi.mid()
    };
    let tau = xi - point(centre);
    // F and J_o along the predictor: Taylor coefficients at the centre, and over all of Ξ (for
    // the Lagrange remainders); both patches written around the predictor's point at the centre.
    let (sh_c, sh_o) = (pred.shifted(point(centre)), pred.shifted(xi));
    let at_centre: [Long; 4] = pred.series(&sh_c, point(centre), ORDER + 1);
    let c = at_centre.each_ref().map(|s| s.coeff(0).mid());
    let (wp, wq) = (window.map(|w| [w[0], w[1]]), window.map(|w| [w[2], w[3]]));
    let (lp, lq) = (
        lean[0].centred_within(c[0], c[1], wp),
        lean[1].centred_within(c[2], c[3], wq),
    );
    let pq_c = both_along(&lp, &lq, &at_centre);
    let pq_o = both_along(&lp, &lq, &pred.series(&sh_o, xi, ORDER + 2));
    let (mut g_c, g_o) = (residual(&pq_c), residual(&pq_o));
    if precise {
        with_exact_residual(&mut g_c, &at_centre, lean);
    }
    let j_c = jacobian(&lp, &lq, &pred.series(&sh_c, point(centre), 3), &free);
    let j_o = jacobian(&lp, &lq, &pred.series(&sh_o, xi, 4), &free);
    // The preconditioner follows the Jacobian along the segment: C(τ) = C0 + C1·τ + C2·τ², the
    // inverse of J0 + J1·τ + J2·τ² to second order (midpoints; any C(τ) is rigorous, this one
    // keeps I − C·J third order in τ).
    let mid = |m: &IMat| Matrix3::from_fn(|r, c| m[r][c].mid());
    let c0 = mid(&coeff_mat(&j_c, 0))
        .try_inverse()
        .ok_or(SegmentFailure::Singular)?;
    let (j1, j2) = (mid(&coeff_mat(&j_c, 1)), mid(&coeff_mat(&j_c, 2)));
    let c1 = -(c0 * j1 * c0);
    let c2 = c0 * j1 * c0 * j1 * c0 - c0 * j2 * c0;
    let cs = [imat(&c0), imat(&c1), imat(&c2)];
    let c_over: IMat = std::array::from_fn(|r| {
        std::array::from_fn(|c| cs[0][r][c] + imul(tau, cs[1][r][c] + imul(tau, cs[2][r][c])))
    });
    let a_over = contraction_along(&j_c, &j_o, &cs, tau);
    let cg = preconditioned_residual(&g_c, &g_o, &cs, tau);
    if cg
        .iter()
        .chain(a_over.iter().flatten())
        .any(|v| v.is_empty() || !v.inf().is_finite() || !v.sup().is_finite())
    {
        return Err(Some(SegmentFailure::Singular));
    }
    // The uniqueness box: room for twice the residual's image and for what must fit inside.
    let rad: [f64; 3] = std::array::from_fn(|r| {
        let e = cg[r].mag();
        (2.0 * e + 1.25 * need[r]) * (1.0 + 1e-9) + f64::MIN_POSITIVE
    });
    // No radius far below the others: the contraction's coupling (rounding-sized entries of
    // `I − C·J`) carries the widest offset into every other, and an offset that is exact (a
    // curve running along a side, its join a few 1e-46 wide there) would then never hold its
    // image. Any box is rigorous; this one is at most a thousandth of the widest wider.
    let widest = rad.iter().fold(0.0f64, |m, &r| m.max(r));
    let rad = rad.map(|r| r.max(1e-3 * widest));
    let y: [Interval; 3] = std::array::from_fn(|r| inari::interval!(-rad[r], rad[r]).unwrap());
    let mut proof = SegmentProof {
        pred,
        xi,
        x_range,
        y,
        k: y,
        jac: [[Interval::ENTIRE; 3]; 3],
        model: [Interval::ENTIRE; 3],
    };
    let b = proof.tube_over(x_range[0], x_range[1]);
    // Every evaluation of the forms below is on the tube or inside it (the predictor's range
    // lies in it too).
    if !(lp.covers(b[0], b[1]) && lq.covers(b[2], b[3])) {
        return Err(None);
    }
    // K = −C·g + (A − C·ΔJ(x))·x for the offsets x (ΔJ: the Jacobian's change off the
    // predictor, over the segment from 0 to x, inside Y and so inside B).
    // The second derivatives over the tube, once for every use below.
    let h = hessian_over(&lp, &lq, &b, &free);
    let image = |x: &[Interval; 3]| krawczyk_image(&h, x, &a_over, &c_over, &cg);
    let k = image(&y).ok_or(SegmentFailure::Singular)?;
    let inside = (0..3).all(|r| k[r].interior(y[r]));
    if !inside {
        return Err(Some(SegmentFailure::NotContracting));
    }
    // Every zero in Y lies in K; the image of K encloses them too.
    if let Some(k2) = image(&k) {
        proof.k = std::array::from_fn(|r| meet(k[r], k2[r]));
    } else {
        proof.k = k;
    }
    // The Jacobian along the predictor (Taylor form) plus its change off it, over K.
    let j_pred = jacobian_along(&j_c, &j_o, tau);
    let dj = jacobian_change(&h, &with_zero(&proof.k));
    proof.jac = combine(&j_pred, &dj, |a, b| a + b);
    // Four enclosures of the same points: each surface along the curve, and over the
    // parameter box of the curve (tighter where a coordinate is nearly affine in the
    // parameters, as a height field's x and y). Rounding cannot make them disjoint, but never
    // report an empty box.
    let b = proof.box_over(x_range[0], x_range[1]);
    let all = [
        model_along(&pq_c[0], &pq_o[0], tau, &proof, 0),
        model_along(&pq_c[1], &pq_o[1], tau, &proof, 1),
        lp.eval(b[0], b[1]),
        lq.eval(b[2], b[3]),
    ];
    // Back by the shift the lean forms were moved by (both alike: `prove_segment` checks).
    let shift = lean[0].shift();
    proof.model = std::array::from_fn(|r| {
        all[1..].iter().fold(all[0][r], |acc, e| meet(acc, e[r])) + point(shift[r])
    });
    Ok(proof)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn eval(h: &[f64], t: f64) -> f64 {
        h.iter().rev().fold(0.0, |acc, c| acc * t + c)
    }

    /// The range encloses every sampled value of random polynomials over off-centre intervals,
    /// and is exact, not 8 times too wide, on `(τ² − r²)³`, the shape of a link's residual.
    #[test]
    fn polynomial_range_encloses_and_is_tight_on_the_residual_shape() {
        let mut state = 0x2545_f491_4f6c_dd1du64;
        let mut next = || crate::numeric::rounding::uniform_pm1(&mut state);
        for _ in 0..200 {
            let c: Vec<f64> = (0..ORDER + 2).map(|_| next()).collect();
            let (lo, hi) = (-0.1 - next().abs(), 0.05 + next().abs());
            let h: [Interval; ORDER + 2] = std::array::from_fn(|k| point(c[k]));
            let tau = inari::interval!(lo, hi).unwrap();
            let range = polynomial_range(&h, tau);
            for s in 0..=400 {
                let t = lo + (hi - lo) * s as f64 / 400.0;
                let y = eval(&c, t);
                assert!(
                    range.inf() - 1e-12 <= y && y <= range.sup() + 1e-12,
                    "{y} outside {range:?}"
                );
            }
        }
        let r = 0.01f64;
        let mut c = [0.0; ORDER + 2];
        (c[0], c[2], c[4], c[6]) = (-r.powi(6), 3.0 * r.powi(4), -3.0 * r * r, 1.0);
        let h: [Interval; ORDER + 2] = std::array::from_fn(|k| point(c[k]));
        let range = polynomial_range(&h, inari::interval!(-r, r).unwrap());
        assert!(
            range.mag() <= 1.001 * r.powi(6),
            "{range:?} against {}",
            r.powi(6)
        );
    }
}
