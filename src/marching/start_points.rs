//! Start points for every branch of the intersection of two patches.
//!
//! Two searches, both subdivision with rigorous bounding-box exclusion followed by Newton:
//! - **boundary points**: each of the four boundary curves of each patch against the other patch
//!   (a curve/surface problem: 3 equations in 3 unknowns), which gives both ends of every open
//!   branch;
//! - **interior candidates**: pairs of sub-patches whose enclosures overlap, refined down to a
//!   leaf size, then projected onto the intersection by Gauss–Newton. Closed loops lying wholly
//!   inside both domains are found here.
//!
//! A box pair is discarded only when its interval enclosures are disjoint, which proves it holds
//! no intersection. Leaves where Newton fails are counted as *undecided* and reported, never
//! silently dropped.

use super::newton::{refine, Constraint};
use crate::geometry::enclosure::boxes_disjoint;
use crate::geometry::subdivision::SubPatch;
use crate::geometry::{Domain, ParametricSurface, RationalBezierPatch};
use inari::Interval;
use nalgebra::{Matrix3x4, Vector3};

/// Tuning of the start-point search.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SearchOptions {
    /// Leaf size as a fraction of the larger model extent of the two patches.
    pub leaf_fraction: f64,
    /// Upper bound on leaves examined per search (protects against tangential surfaces, where
    /// exclusion never succeeds); hitting it is reported in [`SearchReport::truncated`].
    pub max_leaves: usize,
    /// Newton converges when the model-space residual is below this (relative to model size).
    pub residual_tol: f64,
}

impl Default for SearchOptions {
    fn default() -> Self {
        SearchOptions {
            leaf_fraction: 1.0 / 64.0,
            max_leaves: 200_000,
            residual_tol: 1e-12,
        }
    }
}

/// Where a start point came from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StartKind {
    /// On the boundary of surface `surface` (0 = P, 1 = Q).
    Boundary {
        /// 0 for P, 1 for Q.
        surface: usize,
    },
    /// Inside both domains (a candidate for a closed loop or a missed branch).
    Interior,
}

/// A point on the intersection: parameters `(σ, t, u, v)`, refined by Newton.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StartPoint {
    /// `(σ, t)` on P then `(u, v)` on Q.
    pub params: [f64; 4],
    /// Where it came from.
    pub kind: StartKind,
}

/// Result of the start-point search.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct SearchReport {
    /// Points on a boundary of either patch, deduplicated.
    pub boundary: Vec<StartPoint>,
    /// Interior points, one or more per surviving leaf pair (not deduplicated against branches).
    pub interior: Vec<StartPoint>,
    /// Leaf boxes examined.
    pub leaves: usize,
    /// Leaf boxes whose enclosures overlapped even after refinement to 1/16 of the leaf size
    /// but where Newton found no point (undecided).
    pub undecided: usize,
    /// The leaf budget ran out: some regions were not examined.
    pub truncated: bool,
}

/// Finds boundary start points and interior candidates for the intersection of `p` and `q`.
pub fn find_start_points(
    p: &RationalBezierPatch,
    q: &RationalBezierPatch,
    opts: &SearchOptions,
) -> SearchReport {
    let (dp, dq) = (p.domain(), q.domain());
    let size = diameter(&p.bounding_box())
        .max(diameter(&q.bounding_box()))
        .max(f64::MIN_POSITIVE);
    let ctx = Ctx {
        leaf: size * opts.leaf_fraction,
        tol: opts.residual_tol * size.max(1.0),
        max_leaves: opts.max_leaves,
    };
    let mut report = SearchReport::default();
    for (a, b, swapped) in [(p, q, false), (q, p, true)] {
        for (fixed_index, upper) in [(0, false), (0, true), (1, false), (1, true)] {
            let edge = SubPatch::boundary(a, fixed_index, upper);
            search_pairs(
                &ctx,
                a,
                b,
                edge,
                SubPatch::whole(b),
                Some(swapped),
                &mut report,
            );
        }
    }
    dedup(&mut report.boundary, dp, dq);
    search_pairs(
        &ctx,
        p,
        q,
        SubPatch::whole(p),
        SubPatch::whole(q),
        None,
        &mut report,
    );
    report
}

struct Ctx {
    leaf: f64,
    tol: f64,
    max_leaves: usize,
}

/// A leaf where Newton finds nothing is subdivided further, down to this fraction of the leaf
/// size, before it is reported as undecided (most such leaves are then excluded outright).
const REFINE_FAILED_LEAF: f64 = 1.0 / 16.0;

fn diameter(b: &[Interval; 3]) -> f64 {
    b.iter().map(|x| x.wid()).fold(0.0, f64::max)
}

fn mid(r: [f64; 2]) -> f64 {
    0.5 * (r[0] + r[1])
}

/// Pair subdivision of a piece `a0` of surface `a` against a piece `b0` of surface `b`, pruned
/// where the bounding boxes are disjoint; Newton at every leaf pair.
///
/// `edge = Some(swapped)`: `a0` is a boundary curve of `a` (degree 0 in its fixed direction),
/// and `a` is Q when `swapped`; results are boundary points. `edge = None`: `a = P`, `b = Q`,
/// interior candidates.
fn search_pairs(
    ctx: &Ctx,
    a: &RationalBezierPatch,
    b: &RationalBezierPatch,
    a0: SubPatch,
    b0: SubPatch,
    edge: Option<bool>,
    report: &mut SearchReport,
) {
    let budget = report.leaves + ctx.max_leaves;
    let (da, db) = (a.domain(), b.domain());
    let mut stack = vec![(a0, b0, ctx.leaf)];
    while let Some((pa, pb, mut leaf)) = stack.pop() {
        let (ea, eb) = (pa.bounds(), pb.bounds());
        if boxes_disjoint(&ea, &eb) {
            continue;
        }
        let (wa, wb) = (diameter(&ea), diameter(&eb));
        if wa <= leaf && wb <= leaf {
            report.leaves += 1;
            if report.leaves > budget {
                report.truncated = true;
                return;
            }
            let guess = [mid(pa.u), mid(pa.v), mid(pb.u), mid(pb.v)];
            let found = match edge {
                Some(_) => edge_newton(a, b, &pa, guess, ctx.tol),
                None => project_onto_intersection(a, b, guess, ctx.tol),
            };
            match found {
                Some(x) if da.contains(x[0], x[1], 1e-12) && db.contains(x[2], x[3], 1e-12) => {
                    let (kind, params) = match edge {
                        Some(swapped) => (
                            StartKind::Boundary {
                                surface: usize::from(swapped),
                            },
                            if swapped { [x[2], x[3], x[0], x[1]] } else { x },
                        ),
                        None => (StartKind::Interior, x),
                    };
                    let list = if edge.is_some() {
                        &mut report.boundary
                    } else {
                        &mut report.interior
                    };
                    list.push(StartPoint { params, kind });
                    continue;
                }
                Some(_) => continue,
                None if leaf > ctx.leaf * REFINE_FAILED_LEAF => leaf *= 0.5,
                None => {
                    report.undecided += 1;
                    continue;
                }
            }
        }
        // Split the piece with the larger box, across its longer parameter direction (a
        // boundary curve only along its free direction).
        if wa >= wb {
            let dir = split_direction(&pa);
            for half in pa.split(dir) {
                stack.push((half, pb.clone(), leaf));
            }
        } else {
            let dir = split_direction(&pb);
            for half in pb.split(dir) {
                stack.push((pa.clone(), half, leaf));
            }
        }
    }
}

/// The direction to split a piece: the one of larger relative parameter extent (never one of
/// degree 0).
fn split_direction(piece: &SubPatch) -> usize {
    let [m, n] = piece.degree();
    if m == 0 {
        return 1;
    }
    if n == 0 {
        return 0;
    }
    let (du, dv) = (piece.u[1] - piece.u[0], piece.v[1] - piece.v[0]);
    usize::from(dv * (n as f64) > du * (m as f64))
}

/// Newton on `A(edge) − B(u, v) = 0`: the marcher's [`refine`] with the boundary parameter of
/// `A` held fixed. `x = (a0, a1, b0, b1)` in the parameters of `A` then `B`.
fn edge_newton(
    a: &RationalBezierPatch,
    b: &RationalBezierPatch,
    edge: &SubPatch,
    x: [f64; 4],
    tol: f64,
) -> Option<[f64; 4]> {
    // The fixed parameter of the edge: 0 (u) when the piece has degree 0 in u, else 1 (v).
    let index = if edge.degree()[0] == 0 { 0 } else { 1 };
    let constraint = Constraint::Fixed {
        index,
        value: x[index],
    };
    refine(a, b, x, constraint, tol, 40).ok().map(|r| r.x)
}

/// Gauss–Newton (minimum-norm steps) from `x` onto `P(σ,t) = Q(u,v)`; `None` if it does not
/// converge to a residual below `tol`.
pub fn project_onto_intersection<P, Q>(p: &P, q: &Q, mut x: [f64; 4], tol: f64) -> Option<[f64; 4]>
where
    P: ParametricSurface + ?Sized,
    Q: ParametricSurface + ?Sized,
{
    for _ in 0..40 {
        let a = p.derivs(x[0], x[1]);
        let b = q.derivs(x[2], x[3]);
        let f: Vector3<f64> = a.p - b.p;
        let j = Matrix3x4::from_columns(&[a.su, a.sv, -b.su, -b.sv]);
        let jjt = j * j.transpose();
        let y = jjt.lu().solve(&f)?;
        let step = j.transpose() * y;
        for (xi, si) in x.iter_mut().zip(step.iter()) {
            *xi -= si;
        }
        if !x.iter().all(|v| v.is_finite()) {
            return None;
        }
        if f.norm() <= tol && step.norm() <= 1e-10 {
            return Some(x);
        }
        if step.norm() <= 1e-15 * (1.0 + x.iter().map(|v| v.abs()).fold(0.0, f64::max)) {
            let r = (p.point(x[0], x[1]) - q.point(x[2], x[3])).norm();
            return (r <= tol).then_some(x);
        }
    }
    None
}

/// Removes boundary points that are the same point found twice (e.g. at a corner, or from two
/// neighbouring leaves), comparing parameters relative to the domain sizes.
fn dedup(points: &mut Vec<StartPoint>, dp: Domain, dq: Domain) {
    let scale = [
        dp.u[1] - dp.u[0],
        dp.v[1] - dp.v[0],
        dq.u[1] - dq.u[0],
        dq.v[1] - dq.v[0],
    ];
    let mut kept: Vec<StartPoint> = Vec::with_capacity(points.len());
    for pt in points.drain(..) {
        let dup = kept
            .iter()
            .any(|k| (0..4).all(|i| (k.params[i] - pt.params[i]).abs() <= 1e-7 * scale[i]));
        if !dup {
            kept.push(pt);
        }
    }
    *points = kept;
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::PowerSurface;

    /// The graph z = a·(u² + v²) + c·u + d over [−1, 1]², as a Bézier patch.
    fn graph(a: f64, c: f64, d: f64) -> RationalBezierPatch {
        PowerSurface::graph(
            Domain::new(-1.0, 1.0, -1.0, 1.0),
            vec![(2, 0, a), (0, 2, a), (1, 0, c), (0, 0, d), (1, 1, 0.0)],
        )
        .to_bezier()
        .unwrap()
    }

    #[test]
    fn interior_loop_is_found_and_lies_on_the_circle() {
        // Paraboloid z = u² + v² − 0.25 against the plane z = 0: the circle of radius 0.5.
        let r = find_start_points(
            &graph(1.0, 0.0, -0.25),
            &graph(0.0, 0.0, 0.0),
            &SearchOptions::default(),
        );
        assert!(r.boundary.is_empty(), "{:?}", r.boundary);
        assert!(!r.interior.is_empty());
        assert!(!r.truncated && r.undecided == 0);
        for s in &r.interior {
            let [x, y, ..] = s.params;
            assert!((x.hypot(y) - 0.5).abs() < 1e-10, "{:?}", s.params);
        }
    }

    #[test]
    fn tiny_loop_is_found() {
        // Circle of radius 1e-3: far below the leaf size, still found.
        let r = find_start_points(
            &graph(1.0, 0.0, -1e-6),
            &graph(0.0, 0.0, 0.0),
            &SearchOptions::default(),
        );
        assert!(r
            .interior
            .iter()
            .any(|s| (s.params[0].hypot(s.params[1]) - 1e-3).abs() < 1e-9));
    }

    #[test]
    fn open_branch_ends_are_found_on_the_boundaries() {
        // Tilted plane z = 0.5·u + 0.1 against z = 0: the line u = −0.2 crossing v = ±1, found
        // once each (on P's and on Q's boundary at the same place, deduplicated).
        let q = graph(0.0, 0.0, 0.0);
        let r = find_start_points(&graph(0.0, 0.5, 0.1), &q, &SearchOptions::default());
        assert_eq!(r.boundary.len(), 2, "{:?}", r.boundary);
        for s in &r.boundary {
            assert!((s.params[0] + 0.2).abs() < 1e-12);
            assert!((s.params[1].abs() - 1.0).abs() < 1e-12);
            assert!(
                (s.params[2] - s.params[0]).abs() < 1e-12
                    && (s.params[3] - s.params[1]).abs() < 1e-12
            );
        }
        // Disjoint surfaces: nothing, and no leaf is even reached.
        let r = find_start_points(&graph(0.0, 0.0, 5.0), &q, &SearchOptions::default());
        assert!(r.boundary.is_empty() && r.interior.is_empty() && r.leaves == 0);
    }
}
