//! The neighbourhood of a singular point or an isolated contact, settled once instead of
//! subdivided to the level cap.
//!
//! Round a point where the normals of P and Q are parallel (a branch point, the crossing of
//! Viviani's curve, two cylinders tangent at their top) no pair of pieces containing it is ever
//! loop-free, and the pairs next to it fail at every level too: the pair search subdivides them
//! to its smallest size or frontier cap and reports hundreds of undecided regions. Here a box
//! `N = N_P × N_Q` round such a point is proven, once, to hold no component of the intersection
//! that stays inside it; the pairs inside `N` are then settled, and the four faces of `N_P` are
//! searched like the faces of a loop-free pair.
//!
//! **The argument.** Take a basis `(e₁, e₂, n)` of model space (here `n` the unit normal of P at
//! the point; any basis will do) and `G = (e₁·(P − Q), e₂·(P − Q))`.
//!
//! 1. *`C ∩ N` is a level set of a function on a rectangle.* A parametric Krawczyk test on
//!    `G(σ, t, ·, ·) = 0` over `(u, v) ∈ N_Q`, for all `(σ, t) ∈ N_P` at once, proves that for
//!    each `(σ, t)` there is exactly one solution `(u, v)(σ, t)`, in the interior of `N_Q` (its
//!    image lies inside `N_Q`). So every point of `C = {P = Q}` in `N` is `(σ, t, u(σ,t),
//!    v(σ,t))` with `f(σ, t) = n·(P(σ,t) − Q(u(σ,t), v(σ,t))) = 0`, and none lies on `∂N_Q`.
//! 2. *The critical points of `f` are the points of parallel normals.* Differentiating `G = 0`,
//!    `W = P_σ − Q_u u_σ − Q_v v_σ` has no `e₁`, `e₂` components, so `f_σ = n·W = 0` exactly when
//!    `W = 0`, i.e. `P_σ ∈ span(Q_u, Q_v)`; likewise for `t`. So `∇f = 0` exactly when the
//!    normals are parallel, and then `Φ = (G, e₁·(N^P × N^Q), e₂·(N^P × N^Q)) = 0`. A Krawczyk
//!    test on the square system `Φ = 0` over `N` proves that it has no zero, or exactly one,
//!    in a small box `X̂`.
//! 3. *A unique critical point that is a saddle rules out closed components.* At a critical
//!    point the Hessian of `f` is a non-zero multiple of the contact quadratic
//!    `b₁₁ σ'² + 2 b₁₂ σ' t' + b₂₂ t'²` (the `Q_u u_σσ` terms drop against the common normal),
//!    so `Δ = b₁₂² − b₁₁ b₂₂ > 0`, enclosed over `X̂`, proves a saddle. Now let `K` be a
//!    component of `{f = 0}` in the closed rectangle `N_P` that does not reach its boundary. `K`
//!    is a compact graph whose vertices are critical points; a smooth closed curve, or a loop
//!    through the saddle, bounds a disc `Ω` in the rectangle with `f = 0` on `∂Ω` and `f ≢ 0` in
//!    `Ω` (a critical point would fill an open set otherwise), so `f` has an extremum inside `Ω`
//!    at a critical point that is not a saddle, or not on `K`: there is none. (A tree cannot
//!    occur: away from critical points the level set is a 1-manifold without ends, and the
//!    saddle has four arcs.) With no critical point at all the same holds.
//!
//! So **every component of `C ∩ N` reaches `∂N_P × int N_Q`**, which is what the pair search
//! needs: a closed loop through `N` crosses a face of `N_P` inside `N_Q`, and the face searches
//! find it there (faces on P's domain boundary are the boundary search's). The box proven is
//! the declared (outward-rounded) one; the statement holds for the exact dyadic box inside it,
//! whose faces are searched, because `(u, v)` is kept a rounding margin inside `N_Q`.
//!
//! **An isolated contact** (`Δ < 0` over `X̂`: `f` has a strict extremum at the unique critical
//! point `x*`, and the surfaces need not meet there). The same disc argument shows that a closed
//! component of `C ∩ N` bounds a disc whose only critical point is `x*`, where `f` takes its
//! extremum over the disc with the sign of `f(x*)`. The Hessian of `f` is `−B/(m·n)` (`B` the
//! contact quadratic, `m` the common unit normal), so its sign is proven with `b₁₁` and `m·n`,
//! and `f(x*)` is enclosed by the mean-value form over `X̂`. A minimum with `f(x*) > 0` or a
//! maximum with `f(x*) < 0` rules a loop out: the region is settled like a saddle's. Otherwise
//! one loop round `x*` is possible (two nested loops would bound an annulus with a critical
//! point of its own), and it crosses every segment from a point `c` of its disc to `∂N_P`: with
//! `f ≠ 0` proven over a small box `B ∋ x*, c`, `c` lies inside any loop, and the segment from
//! `c` to the upper `σ`-face of `N_P` is searched with the faces. So a bump above or below a
//! plane settles at once, and a tiny loop round the contact point is found.
//!
//! **A node on a domain side.** The boxes are proven before they are clipped to the domains
//! (the patches' formulas hold past them): then a node on a side, or just past it, lies inside
//! the box that steps 1–3 prove, and a component inside the clipped `N` is a piece of one of the
//! unclipped box's, so it reaches a face of `N_P` or leaves a domain across a side (the
//! boundary search's). Only the boundary search's own leaves at such a node stay undecided (the
//! side's curve touches the other surface there); no interval test can settle them, since
//! moving the input by an ulp can make a small curve piece there that touches only the side.
//!
//! Tangential contact curves (critical points not isolated) and touching points (`f(x*)` not
//! proven non-zero) are not settled here: the pair search goes on as before and reports them
//! undecided.

use super::{
    diameter, edge_search, Ctx, EdgeProblem, Needs, SearchReport, StartKind, REFINE_FAILED_LEAF,
};
use crate::geometry::piece::{declared_range, Piece};
use crate::geometry::{ParametricSurface, RationalBezierPatch};
use crate::numeric::rounding::dot_point;
use crate::numeric::scalar::point;
use crate::numeric::vec3::{cross, dot};
use crate::pair::branch_point::locate_singular_point_within;
use crate::pair::centred_second_order::CentredSecondOrder;
use crate::pair::contact_quadratic::{contact_quadratic, ContactQuadratic};
use crate::pair::field::ScalarSurface;
use crate::pair::krawczyk::krawczyk_image_n;
use crate::Scalar;
use inari::Interval;
use nalgebra::{Matrix2, Matrix4, Vector3, Vector4};

/// A proven neighbourhood of a singular point (see the module documentation): every component
/// of the intersection inside `p × q` reaches a face of `p`.
pub(super) struct NodeRegion {
    /// `N_P`, a piece of P over an exact box of its normalised parameters.
    pub(super) p: Piece,
    /// `N_Q`, a piece of Q.
    pub(super) q: Piece,
}

impl NodeRegion {
    /// Whether the pair of pieces lies inside the region (exact comparison of normalised boxes).
    pub(super) fn holds(&self, a: &Piece, b: &Piece) -> bool {
        within(a.s, self.p.s)
            && within(a.r, self.p.r)
            && within(b.s, self.q.s)
            && within(b.r, self.q.r)
    }
}

fn within(x: [f64; 2], y: [f64; 2]) -> bool {
    y[0] <= x[0] && x[1] <= y[1]
}

/// Node regions proven so far and the points already tried, for one pair search.
#[derive(Default)]
pub(super) struct NodeRegions {
    pub(super) regions: Vec<NodeRegion>,
    tried: Vec<[f64; 4]>,
    /// Pairs (normalised boxes of both pieces) from whose centre no singular point was found:
    /// their sub-pairs are not tried again until eight times smaller.
    failed: Vec<[[f64; 2]; 4]>,
    attempts: usize,
}

/// Most singular-point locations tried per search (each up to 30 Gauss–Newton steps and, when it
/// converges, a few interval tests): near-tangent pairs without a singular point (Fig. 7's loops
/// 3.5e-4 from a common plane) try and fail.
const MAX_ATTEMPTS: usize = 32;

/// Pairs are tried once one of the pieces is at most this fraction of the model size (a flat
/// piece is never split, so its partner alone localises the point).
const TRY_BELOW: f64 = 0.25;

/// Model radii of the regions tried round a located point, as fractions of the model size,
/// largest first (a large region settles more pairs; a small one is easier to prove).
const RADII: [f64; 6] = [
    1.0 / 16.0,
    1.0 / 64.0,
    1.0 / 256.0,
    1.0 / 1024.0,
    1.0 / 8192.0,
    1.0 / 65536.0,
];

/// Grid of the normalised region boxes (their ends are multiples of it, so pieces halved from
/// the whole patch nest in them exactly once small enough).
const GRID: f64 = 1.0 / (1u64 << 40) as f64;

impl NodeRegions {
    /// Whether a proven region holds the pair.
    pub(super) fn settles(&self, a: &Piece, b: &Piece) -> bool {
        self.regions.iter().any(|r| r.holds(a, b))
    }

    /// Tries to prove a region round a singular point near the unsettled pair `(a, b)`; on
    /// success searches its faces (found points go to `report.interior`) and keeps it. True when
    /// a new region was added.
    pub(super) fn try_pair(
        &mut self,
        ctx: &Ctx,
        p: &RationalBezierPatch,
        q: &RationalBezierPatch,
        a: &Piece,
        b: &Piece,
        report: &mut SearchReport,
    ) -> bool {
        let size = ctx.leaf * 64.0;
        if self.attempts >= MAX_ATTEMPTS
            || diameter(&a.bounds()).min(diameter(&b.bounds())) > TRY_BELOW * size
        {
            return false;
        }
        let (dp, dq) = (p.domain(), q.domain());
        let (bp, bq) = (a.declared(&dp, 0.0), b.declared(&dq, 0.0));
        let x0 = [bp[0].mid(), bp[1].mid(), bq[0].mid(), bq[1].mid()];
        // Only where the normals are nearly parallel already.
        let (np, nq) = (
            p.derivs(x0[0], x0[1]).normal(),
            q.derivs(x0[2], x0[3]).normal(),
        );
        if np.cross(&nq).norm() > 0.5 * np.norm() * nq.norm() {
            return false;
        }
        // Skip pairs whose box, widened by its width (the reach of the search below), holds a
        // point already tried.
        let inside = |x: &[f64; 4]| {
            [bp[0], bp[1], bq[0], bq[1]].iter().zip(x).all(|(i, v)| {
                let w = i.wid();
                i.inf() - w <= *v && *v <= i.sup() + w
            })
        };
        if self.tried.iter().any(inside) {
            return false;
        }
        let boxes = [a.s, a.r, b.s, b.r];
        let below = |f: &[[f64; 2]; 4]| {
            boxes.iter().zip(f).all(|(x, y)| within(*x, *y))
                && boxes
                    .iter()
                    .zip(f)
                    .any(|(x, y)| 8.0 * (x[1] - x[0]) > y[1] - y[0])
        };
        if self.failed.iter().any(below) {
            return false;
        }
        self.attempts += 1;
        // Anywhere in the pair's box or next to it (a singular point on a subdivision line is
        // found from the pairs on both sides).
        let reach = bp.iter().chain(&bq).map(|i| i.wid()).fold(0.0, f64::max);
        // A singular point (P = Q, normals parallel), or else a critical point of the height
        // difference: an isolated contact, P ≠ Q there (a tiny loop round it, or none).
        let located = locate_singular_point_within(p, q, x0, 1e-6 * size, 1e-6, reach, 30)
            .or_else(|| locate_critical_point(p, q, x0, reach).filter(|x| definite(p, q, x)));
        let Some(x) = located else {
            self.failed.push(boxes);
            return false;
        };
        if self.tried.iter().any(|t| same(t, &x)) {
            return false;
        }
        self.tried.push(x);
        for frac in RADII {
            let Some((region, ray)) = prove_region(p, q, x, frac * size) else {
                continue;
            };
            if search_faces(ctx, p, q, &region, ray, report) {
                self.regions.push(region);
                return true;
            }
        }
        false
    }
}

fn same(a: &[f64; 4], b: &[f64; 4]) -> bool {
    a.iter()
        .zip(b)
        .all(|(x, y)| (x - y).abs() <= 1e-9 * (1.0 + x.abs()))
}

/// The exact normalised range `[lo, hi]` round the declared `centre ± half` of a domain
/// `[d0, d1]`, widened outward to the grid; not clipped to `[0, 1]` (see [`clipped`]) but kept
/// within `[−1/4, 5/4]`.
fn normalised(d: [f64; 2], centre: f64, half: f64) -> Option<[f64; 2]> {
    let w = d[1] - d[0];
    let lo = ((centre - half - d[0]) / w / GRID).floor() * GRID;
    let hi = ((centre + half - d[0]) / w / GRID).ceil() * GRID;
    let (lo, hi) = (lo.max(-0.25), hi.min(1.25));
    (lo.is_finite() && hi.is_finite() && lo < hi).then_some([lo, hi])
}

/// The part of a normalised range inside the domain, `[0, 1]`.
fn clipped(x: [f64; 2]) -> Option<[f64; 2]> {
    let (lo, hi) = (x[0].max(0.0), x[1].min(1.0));
    (lo < hi).then_some([lo, hi])
}

/// The basis `(e₁, e₂, n)` at P's point of `x`: `n` P's unit normal, `e₁`, `e₂` across it.
pub(super) fn frame_at(p: &RationalBezierPatch, x: &[f64; 4]) -> Option<Frame> {
    let n = p.derivs(x[0], x[1]).normal().try_normalize(0.0)?;
    let axis = if n.x.abs() <= n.y.abs() && n.x.abs() <= n.z.abs() {
        Vector3::x()
    } else if n.y.abs() <= n.z.abs() {
        Vector3::y()
    } else {
        Vector3::z()
    };
    let e1 = n.cross(&axis).try_normalize(0.0)?;
    let e2 = n.cross(&e1);
    Some([[e1.x, e1.y, e1.z], [e2.x, e2.y, e2.z], [n.x, n.y, n.z]])
}

/// `(e₁, e₂, n)`, rows.
pub(super) type Frame = [[f64; 3]; 3];

/// Newton in `f64` on `Φ = 0` (the critical points of `f`, see the module documentation) from
/// `x0`, in the frame at `x0`: a point to centre a region on, or `None` when it does not converge within
/// the parameter distance `reach` inside both domains. Only places the region; the proof is
/// [`prove_region`]'s.
fn locate_critical_point(
    p: &RationalBezierPatch,
    q: &RationalBezierPatch,
    x0: [f64; 4],
    reach: f64,
) -> Option<[f64; 4]> {
    let frame = frame_at(p, &x0)?;
    let mut x = x0;
    for _ in 0..12 {
        let (pd, qd) = (p.second_order(x[0], x[1]), q.second_order(x[2], x[3]));
        let first = |d: &[[f64; 3]; 6]| [d[0], d[1], d[2]];
        let f = phi_values(&frame, &first(&pd), &first(&qd));
        let jac = phi_jacobian(&frame, &pd, &qd);
        let step = Matrix4::from_fn(|r, k| jac[r][k])
            .lu()
            .solve(&Vector4::from(f))?;
        x = std::array::from_fn(|i| x[i] - step[i]);
        let moved = step.amax();
        if !moved.is_finite() {
            return None;
        }
        if moved <= 1e-15 * (1.0 + x.iter().map(|v| v.abs()).fold(0.0, f64::max)) {
            break;
        }
    }
    let (dp, dq) = (p.domain(), q.domain());
    let near = (0..4).all(|i| (x[i] - x0[i]).abs() <= reach);
    (near && dp.contains(x[0], x[1], 0.0) && dq.contains(x[2], x[3], 0.0)).then_some(x)
}

/// Whether the contact quadratic at `x` (`f64`) is clearly definite: `−Δ` at least a thousandth
/// of the squared size of its coefficients. A flatter extremum (near-tangent loops lying along a
/// common plane, as in Fig. 7) is not proven unique by the interval tests and costs their price
/// at every radius.
fn definite(p: &RationalBezierPatch, q: &RationalBezierPatch, x: &[f64; 4]) -> bool {
    let c = contact_quadratic(p, q, x);
    let size = c.b11 * c.b11 + 2.0 * c.b12 * c.b12 + c.b22 * c.b22;
    -c.discriminant >= 1e-3 * size && size.is_finite()
}

/// Proves the region of model radius `radius` round the singular or critical point `x` (see the
/// module documentation), or `None`. With it comes the ray to search as well when a closed loop
/// round an isolated contact is possible (see [`ray_from_extremum`]).
fn prove_region(
    p: &RationalBezierPatch,
    q: &RationalBezierPatch,
    x: [f64; 4],
    radius: f64,
) -> Option<(NodeRegion, Option<Piece>)> {
    let (dp, dq) = (p.domain(), q.domain());
    let (a, b) = (p.derivs(x[0], x[1]), q.derivs(x[2], x[3]));
    let frame = frame_at(p, &x)?;
    let [e1, e2, _] = frame.map(Vector3::from);
    // N_P: the model radius in each parameter direction.
    let (hs, ht) = (radius / a.su.norm(), radius / a.sv.norm());
    let ps = normalised(dp.u, x[0], hs)?;
    let pr = normalised(dp.v, x[1], ht)?;
    // N_Q: half again the parameter range that the corners of N_P project to.
    let eq =
        Matrix2::new(e1.dot(&b.su), e1.dot(&b.sv), e2.dot(&b.su), e2.dot(&b.sv)).try_inverse()?;
    let (mut hu, mut hv) = (0.0f64, 0.0f64);
    for (s, t) in [(-hs, -ht), (-hs, ht), (hs, -ht), (hs, ht)] {
        let d = p.point(x[0] + s, x[1] + t) - a.p;
        let off = eq * nalgebra::Vector2::new(e1.dot(&d), e2.dot(&d));
        hu = hu.max(off.x.abs());
        hv = hv.max(off.y.abs());
    }
    let qs = normalised(dq.u, x[2], 1.5 * hu)?;
    let qr = normalised(dq.v, x[3], 1.5 * hv)?;
    let region = NodeRegion {
        p: Piece::over(p, clipped(ps)?, clipped(pr)?)?,
        q: Piece::over(q, clipped(qs)?, clipped(qr)?)?,
    };
    // The proofs run over the boxes before clipping to the domains (the patches' formulas hold
    // past their domains): a node on a domain side is then inside them (see the module
    // documentation).
    let xp = [declared_range(dp.u, ps, 0.0), declared_range(dp.v, pr, 0.0)];
    let xq = [declared_range(dq.u, qs, 0.0), declared_range(dq.v, qr, 0.0)];
    if !graph_over_p(p, q, &frame, &xp, &xq) {
        return None;
    }
    match critical_points(p, q, &frame, xp, xq)? {
        Critical::Settled => Some((region, None)),
        Critical::LoopPossible(xhat) => {
            let ray = ray_from_extremum(p, q, &frame, &region, &xhat)?;
            Some((region, Some(ray)))
        }
    }
}

/// Step 1: for every `(σ, t) ∈ xp` exactly one `(u, v) ∈ xq` solves `G = 0`, kept a rounding
/// margin inside `xq` (parametric Krawczyk, [`graph_image`]).
fn graph_over_p(
    p: &RationalBezierPatch,
    q: &RationalBezierPatch,
    e: &Frame,
    xp: &[Interval; 2],
    xq: &[Interval; 2],
) -> bool {
    graph_image(p, q, e, xp, xq).is_some_and(|k| {
        k.iter().zip(xq).all(|(k, x)| {
            let margin = 1e-12 * (1.0 + x.mag());
            k.inf() > x.inf() + margin && k.sup() < x.sup() - margin
        })
    })
}

/// The parametric Krawczyk image of `G(σ, t, ·, ·) = 0` over `xq`, for all `(σ, t) ∈ xp` at once
/// (`G` at the centre of `xq` by the mean-value form over `xp`): every solution `(u, v) ∈ xq` for
/// some `(σ, t) ∈ xp` lies in it, and when it lies inside `xq` there is exactly one per `(σ, t)`.
pub(super) fn graph_image(
    p: &RationalBezierPatch,
    q: &RationalBezierPatch,
    e: &Frame,
    xp: &[Interval; 2],
    xq: &[Interval; 2],
) -> Option<[Interval; 2]> {
    let mp = xp.map(|i| point(i.mid()));
    let cq = xq.map(|i| point(i.mid()));
    let [pm, ..] = p.first_order(mp[0], mp[1]);
    let [qc, ..] = q.first_order(cq[0], cq[1]);
    let [_, ps, pt] = p.first_order_centred(xp[0], xp[1], mp[0], mp[1]);
    let [_, qu, qv] = q.first_order_centred(xq[0], xq[1], cq[0], cq[1]);
    let gap: [Interval; 3] = std::array::from_fn(|k| pm[k] - qc[k]);
    let f: [Interval; 2] = std::array::from_fn(|i| dot_point(&e[i], &gap));
    let jp: [[Interval; 2]; 2] =
        std::array::from_fn(|i| [dot_point(&e[i], &ps), dot_point(&e[i], &pt)]);
    let jac: [[Interval; 2]; 2] =
        std::array::from_fn(|i| [-dot_point(&e[i], &qu), -dot_point(&e[i], &qv)]);
    let c = Matrix2::from_fn(|r, k| jac[r][k].mid()).try_inverse()?;
    let c = [[c[(0, 0)], c[(0, 1)]], [c[(1, 0)], c[(1, 1)]]];
    // G(σ, t, c_q) ∈ G(m_p, c_q) + J_P·((σ, t) − m_p) (mean value over xp). Its term is added
    // as (C·J_P)·(xp − m_p), not C·(J_P·(xp − m_p)): the product C·J_P is nearly the tangent
    // map between the parameters, so the box maps to a box without wrapping.
    let k = krawczyk_image_n(xq, &cq, &f, &jac, &c);
    proper(std::array::from_fn(|r| {
        let mut acc = k[r];
        for col in 0..2 {
            let cj = point(c[r][0]) * jp[0][col] + point(c[r][1]) * jp[1][col];
            acc -= cj * (xp[col] - mp[col]);
        }
        acc
    }))
}

/// The image, unless one of its intervals is empty: an evaluation divided by a weight that is
/// exactly zero there (possible past a domain, where the boxes of a region on its side reach),
/// which proves nothing. (An empty interval would pass every inclusion and disjointness test.)
fn proper<const N: usize>(k: [Interval; N]) -> Option<[Interval; N]> {
    k.iter().all(|x| !x.is_empty()).then_some(k)
}

/// What steps 2 and 3 proved about the critical points of `f` in the region.
enum Critical {
    /// Every component of `C ∩ N` reaches `∂N_P`: no critical point, a saddle, or an extremum
    /// whose value rules a closed loop round it out.
    Settled,
    /// A unique critical point, in the box `X̂`, that is an extremum of `f` round which one
    /// closed loop is possible (see [`ray_from_extremum`]).
    LoopPossible([Interval; 4]),
}

/// Steps 2 and 3: `Φ = 0` has no zero in `xp × xq`, or exactly one, in a box `X̂` where the
/// contact quadratic's discriminant is proven positive (a saddle of `f`) or negative (an
/// extremum, [`extremum_excludes_loop`]); `None` when neither is proven.
fn critical_points(
    p: &RationalBezierPatch,
    q: &RationalBezierPatch,
    e: &Frame,
    xp: [Interval; 2],
    xq: [Interval; 2],
) -> Option<Critical> {
    let mut x = [xp[0], xp[1], xq[0], xq[1]];
    let mut unique = false;
    for _ in 0..4 {
        let k = phi_image(p, q, e, &x)?;
        if k.iter().zip(&x).any(|(k, x)| k.disjoint(*x)) {
            // No zero of Φ: f has no critical point.
            return Some(Critical::Settled);
        }
        unique |= k
            .iter()
            .zip(&x)
            .all(|(k, x)| x.inf() < k.inf() && k.sup() < x.sup());
        if !unique {
            return None;
        }
        x = std::array::from_fn(|i| k[i].intersection(x[i]));
    }
    let c = contact_quadratic(p, q, &x);
    if sign(c.discriminant) == Some(1.0) {
        return Some(Critical::Settled);
    }
    match extremum_excludes_loop(p, q, &e[2], &c, &x)? {
        true => Some(Critical::Settled),
        false => Some(Critical::LoopPossible(x)),
    }
}

/// The sign of an interval that excludes zero (`None` for an empty one, whose bounds would
/// pass either test).
pub(super) fn sign(x: Interval) -> Option<f64> {
    if x.is_empty() {
        None
    } else if x.inf() > 0.0 {
        Some(1.0)
    } else if x.sup() < 0.0 {
        Some(-1.0)
    } else {
        None
    }
}

/// At the unique critical point `x* ∈ X̂` with `Δ < 0` proven, `f` has a strict extremum: its
/// Hessian is `−B/(m·n)`, `B` the contact quadratic's matrix `[[b₁₁, b₁₂], [b₁₂, b₂₂]]` (definite)
/// and `m` P's unit normal (the normal of both surfaces there). A closed component of `f = 0` in
/// `N_P` bounds a disc whose only critical point is `x*`, where `f` then has its extremum over
/// the disc with the sign of `f(x*)`: a maximum if `f(x*) > 0`, a minimum if `f(x*) < 0`. So a
/// minimum with `f(x*) > 0` or a maximum with `f(x*) < 0` rules it out (`Some(true)`); the other
/// two allow one loop round `x*` (`Some(false)`); `None` when a sign is not proven (`f(x*)` may
/// be zero: the surfaces may touch there).
fn extremum_excludes_loop(
    p: &RationalBezierPatch,
    q: &RationalBezierPatch,
    n: &[f64; 3],
    c: &ContactQuadratic<Interval>,
    xhat: &[Interval; 4],
) -> Option<bool> {
    if sign(c.discriminant) != Some(-1.0) {
        return None;
    }
    let [_, ps, pt] = p.first_order(xhat[0], xhat[1]);
    let m_dot_n = sign(dot_point(n, &cross(&ps, &pt)))?;
    let hessian = -sign(c.b11)? * m_dot_n;
    let value = sign(height_over(p, q, n, xhat))?;
    Some(value * hessian > 0.0)
}

/// An enclosure of `F = n·(P(σ, t) − Q(u, v))` over the box `x` by the mean-value form at its
/// centre: near a point of parallel normals `∇F` nearly vanishes (`n` is almost the common
/// normal), so this is far tighter than `n·(P(x_P) − Q(x_Q))` evaluated box by box.
pub(super) fn height_over(
    p: &RationalBezierPatch,
    q: &RationalBezierPatch,
    n: &[f64; 3],
    x: &[Interval; 4],
) -> Interval {
    let m = x.map(|i| point(i.mid()));
    let [pm, ..] = p.first_order(m[0], m[1]);
    let [qm, ..] = q.first_order(m[2], m[3]);
    let gap: [Interval; 3] = std::array::from_fn(|k| pm[k] - qm[k]);
    let [_, ps, pt] = p.first_order(x[0], x[1]);
    let [_, qu, qv] = q.first_order(x[2], x[3]);
    let grad = [
        dot_point(n, &ps),
        dot_point(n, &pt),
        -dot_point(n, &qu),
        -dot_point(n, &qv),
    ];
    (0..4).fold(dot_point(n, &gap), |acc, i| acc + grad[i] * (x[i] - m[i]))
}

/// Where one closed loop round the extremum `x*` is possible: it surrounds `x*`, so it crosses
/// every segment from a point `c` of its disc to `∂N_P`. Take a box `B` round `X̂`'s `(σ, t)`
/// (widened to a millionth of `N_P`) and `c` in it: if `f ≠ 0` is proven over `B` (with `(u, v)`
/// from the graph image over `B`), no loop meets `B`, so `c` lies inside any loop (a loop missing
/// the segment would leave `c` outside its disc, and the segment from `c` to `x*`, inside `B`,
/// would cross it). Returns the segment from `c` along `σ` to the face `σ = ` upper end of `N_P`,
/// as a face of a piece, to be searched with the faces.
fn ray_from_extremum(
    p: &RationalBezierPatch,
    q: &RationalBezierPatch,
    e: &Frame,
    region: &NodeRegion,
    xhat: &[Interval; 4],
) -> Option<Piece> {
    let dp = p.domain();
    let np = region.p.declared(&dp, 0.0);
    let widen = |x: Interval, whole: Interval| {
        let pad = 1e-6 * whole.wid();
        inari::interval!(x.inf() - pad, x.sup() + pad).ok()
    };
    let b = [widen(xhat[0], np[0])?, widen(xhat[1], np[1])?];
    let nq = region.q.declared(&q.domain(), 0.0);
    let y = graph_image(p, q, e, &b, &nq)?;
    let y: [Interval; 2] = std::array::from_fn(|i| y[i].intersection(nq[i]));
    if y.iter().any(|i| i.is_empty()) {
        return None;
    }
    sign(height_over(p, q, &e[2], &[b[0], b[1], y[0], y[1]]))?;
    // c: the normalised centre of X̂; the exact point it stands for must lie in B and in N_P.
    let to_unit = |x: Interval, d: [f64; 2]| (x.mid() - d[0]) / (d[1] - d[0]);
    let (cs, ct) = (to_unit(xhat[0], dp.u), to_unit(xhat[1], dp.v));
    let exact = |c: f64, d: [f64; 2]| point(d[0]) + point(c) * (point(d[1]) - point(d[0]));
    let inside = |c: f64, range: [f64; 2]| range[0] < c && c < range[1];
    let in_b_and_n = inside(cs, region.p.s)
        && inside(ct, region.p.r)
        && exact(cs, dp.u).subset(b[0])
        && exact(ct, dp.v).subset(b[1]);
    if !in_b_and_n {
        return None;
    }
    let strip = Piece::over(p, [cs, region.p.s[1]], [ct, region.p.r[1]])?;
    Some(strip.face(1, false))
}

/// `Φ` in the frame `e` from first-order data `[S, S_u, S_v]` of P and Q (at a point, or
/// enclosed over a box).
fn phi_values<T: Scalar>(e: &Frame, pd: &[[T; 3]; 3], qd: &[[T; 3]; 3]) -> [T; 4] {
    let along = |r: usize, v: &[T; 3]| dot(&e[r].map(T::from_f64), v);
    let [pp, ps, pt] = pd;
    let [qq, qu, qv] = qd;
    let gap: [T; 3] = std::array::from_fn(|k| pp[k] - qq[k]);
    let normals = cross(&cross(ps, pt), &cross(qu, qv));
    [
        along(0, &gap),
        along(1, &gap),
        along(0, &normals),
        along(1, &normals),
    ]
}

/// The Jacobian of `Φ` in the frame `e` from second-order data `[S, S_u, S_v, S_uu, S_uv,
/// S_vv]` of P and Q (at a point, or enclosed over a box).
fn phi_jacobian<T: Scalar>(e: &Frame, pd: &[[T; 3]; 6], qd: &[[T; 3]; 6]) -> [[T; 4]; 4] {
    let along = |r: usize, v: &[T; 3]| dot(&e[r].map(T::from_f64), v);
    let [_, ps, pt, pss, pst, ptt] = pd;
    let [_, qu, qv, quu, quv, qvv] = qd;
    let (np, nq) = (cross(ps, pt), cross(qu, qv));
    let add = |a: [T; 3], b: [T; 3]| -> [T; 3] { std::array::from_fn(|k| a[k] + b[k]) };
    let np_s = add(cross(pss, pt), cross(ps, pst));
    let np_t = add(cross(pst, pt), cross(ps, ptt));
    let nq_u = add(cross(quu, qv), cross(qu, quv));
    let nq_v = add(cross(quv, qv), cross(qu, qvv));
    let cols = [
        (*ps, cross(&np_s, &nq)),
        (*pt, cross(&np_t, &nq)),
        (qu.map(|c| -c), cross(&np, &nq_u)),
        (qv.map(|c| -c), cross(&np, &nq_v)),
    ];
    std::array::from_fn(|r| {
        std::array::from_fn(|k| {
            let (g, c) = &cols[k];
            if r < 2 {
                along(r, g)
            } else {
                along(r - 2, c)
            }
        })
    })
}

/// The Krawczyk image of `Φ` over the box `x` (see [`critical_points`]): `Φ` at the box's
/// centre, its Jacobian enclosed over the box by the centred second-order forms.
pub(super) fn phi_image(
    p: &RationalBezierPatch,
    q: &RationalBezierPatch,
    e: &Frame,
    x: &[Interval; 4],
) -> Option<[Interval; 4]> {
    let xm = x.map(|i| point(i.mid()));
    let f = phi_values(
        e,
        &p.first_order(xm[0], xm[1]),
        &q.first_order(xm[2], xm[3]),
    );
    let jac = phi_jacobian(
        e,
        &p.second_order_centred(x[0], x[1], xm[0], xm[1]),
        &q.second_order_centred(x[2], x[3], xm[2], xm[3]),
    );
    let c = Matrix4::from_fn(|r, k| jac[r][k].mid()).try_inverse()?;
    let c: [[f64; 4]; 4] = std::array::from_fn(|r| std::array::from_fn(|k| c[(r, k)]));
    proper(krawczyk_image_n(x, &xm, &f, &jac, &c))
}

/// Searches the faces of `N_P` inside P's domain, and the ray from an extremum if one is given,
/// against `N_Q` (see the module documentation); true when every leaf was settled.
fn search_faces(
    ctx: &Ctx,
    p: &RationalBezierPatch,
    q: &RationalBezierPatch,
    region: &NodeRegion,
    ray: Option<Piece>,
    report: &mut SearchReport,
) -> bool {
    let size = diameter(&region.p.bounds()).min(diameter(&region.q.bounds()));
    let leaf = ctx.leaf.min(size * 0.25);
    let problem = EdgeProblem {
        a: p,
        b: q,
        swapped: false,
        kind: StartKind::Interior,
        needs: Needs::None,
    };
    let mut found = Vec::new();
    // Whether the search of `piece` against `N_Q` settled every leaf.
    let mut settles = |piece: Piece, report: &mut SearchReport| {
        edge_search(
            ctx,
            &problem,
            piece,
            region.q.clone(),
            leaf,
            leaf * REFINE_FAILED_LEAF,
            report,
            &mut found,
        )
        .is_empty()
    };
    for (fixed, upper) in [(0, false), (0, true), (1, false), (1, true)] {
        let range = if fixed == 0 { region.p.s } else { region.p.r };
        let value = range[usize::from(upper)];
        if value == 0.0 || value == 1.0 {
            continue;
        }
        // The points found are kept only if every face settles: stop at the first that does not.
        if !settles(region.p.face(fixed, upper), report) {
            return false;
        }
    }
    let settled = ray.is_none_or(|ray| settles(ray, report));
    if settled {
        report.interior.extend(found);
    }
    settled
}

#[cfg(test)]
#[path = "node_region_tests.rs"]
mod tests;
