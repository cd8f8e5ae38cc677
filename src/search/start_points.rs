//! Start points for every branch of the intersection of two patches, with a proof of
//! completeness or an explicit list of the regions left undecided.
//!
//! Two searches, both subdivision with rigorous exclusion:
//! - **boundary points**: each of the four boundary curves of each patch against the other patch
//!   (a curve/surface problem: 3 equations in 3 unknowns), which gives both ends of every open
//!   branch. A leaf box of this search is settled by one parametric Krawczyk step
//!   ([`settle_box`], Jacobian enclosed from the pieces' Bernstein nets over the leaf widened by
//!   1/32): either its image is disjoint from the box (no curve point) or it proves a unique
//!   curve point, which Newton then polishes; a leaf still open at 1/65536 of the leaf size is
//!   an undecided region (a Newton point from it is still offered);
//! - **interior pairs**: pairs of sub-patches, subdivided level by level until each pair is
//!   (a) *disjoint* (interval bounding boxes do not meet), or (b) *loop-free*
//!   ([`prove_loop_free`](crate::search::loop_exclusion::prove_loop_free): every intersection
//!   component inside the pair reaches the pair's
//!   boundary), in which case the (upper) faces of both sub-patches that lie inside the domains are
//!   searched like the patch boundaries above, which yields a point on every component crossing
//!   the pair; or (c) too small, or too many pairs at one level (tangential contact), in which
//!   case the pair is an [`UndecidedRegion`], reported with its parameter boxes (and Newton
//!   projections from its centre and corners are still offered as start points).
//!
//! Only the *upper* faces (`s = s₁`, `r = r₁` of the normalised box) of each loop-free pair's
//! pieces are searched, each once per partner piece. That suffices: the leaf pairs of the
//! subdivision tile the product of the two domains, and a pair holding an intersection point in
//! its closed boxes is never proven disjoint. A closed loop meets the boundary of a loop-free
//! pair it passes through; if it meets it on an upper face, that pair's search finds the point;
//! if on a lower face inside the domain, the leaf pair on the other side of that face holding
//! the point (not disjoint, so loop-free or undecided) has it on an upper face; on the domain
//! boundary the boundary search finds it.
//!
//! Every closed loop inside the domains either lies in an undecided region or crosses a face of a
//! loop-free pair; every open branch reaches a patch boundary. So when no region is undecided and
//! no budget ran out ([`SearchReport::complete`]), every branch has a start point.

use crate::geometry::enclosure::boxes_disjoint;
use crate::geometry::piece::Piece;
use crate::geometry::{Domain, RationalBezierPatch};
use crate::pair::curve_surface::{settle_box, BoxVerdict};
pub use crate::pair::newton::project_onto_intersection;
use crate::pair::newton::{refine, Constraint};
use crate::search::point_exclusion::point_off_patch;
use faces::Needs;
use faces::{face_search, face_searches_ahead};
use inari::Interval;
use node_region::NodeRegions;
use pair_verdict::{classify_pair, separated_across, PairVerdict};
use rayon::prelude::*;
use std::collections::HashMap;
use tangent_leaf::{along_edge_point, arc_through, edge_newton, leaf_point};

mod critical_cover;
mod faces;
mod node_region;
mod pair_verdict;
mod tangent_leaf;
mod undecided;
pub use undecided::UndecidedRegion;

/// Tuning of the start-point search.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SearchOptions {
    /// Leaf size of the curve/surface (boundary and face) searches, as a fraction of the larger
    /// model extent of the two patches.
    pub leaf_fraction: f64,
    /// Upper bound on leaf boxes plus sub-patch pairs examined per search (protects against
    /// tangential surfaces, where exclusion never succeeds); hitting it is reported in
    /// [`SearchReport::truncated`] and the unexamined pairs become undecided regions.
    pub max_leaves: usize,
    /// Newton converges when the model-space residual is below this (relative to model size).
    pub residual_tol: f64,
    /// Sub-patch pairs are subdivided until both pieces are smaller than this fraction of the
    /// model extent; a pair still neither disjoint nor loop-free then is undecided.
    pub min_pair_fraction: f64,
    /// Most unsettled pairs carried from one subdivision level to the next; beyond it (a
    /// tangential contact along a curve makes the count double every level) all of them are
    /// reported as undecided regions.
    pub max_frontier: usize,
}

impl Default for SearchOptions {
    fn default() -> Self {
        SearchOptions {
            leaf_fraction: 1.0 / 64.0,
            max_leaves: 200_000,
            residual_tol: 1e-12,
            min_pair_fraction: 1e-9,
            max_frontier: 1024,
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
    /// Inside both domains (on a face of a loop-free pair, or from an undecided region).
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
    /// Interior points: where branches cross faces of loop-free pairs (deduplicated), and Newton
    /// projections from the centres of undecided regions.
    pub interior: Vec<StartPoint>,
    /// Leaf boxes of the curve/surface searches examined.
    pub leaves: usize,
    /// Curve/surface leaf boxes of the boundary search that were neither excluded nor proven to
    /// hold one point, down to 1/65536 of the leaf size (each also makes an undecided region).
    pub undecided: usize,
    /// The leaf budget ran out: some regions were not examined (they are undecided regions).
    pub truncated: bool,
    /// Sub-patch pairs examined by the interior search.
    pub pairs: usize,
    /// Pairs proven to hold no intersection (disjoint interval bounding boxes).
    pub disjoint_pairs: usize,
    /// Pairs proven loop-free (every component inside reaches the pair's boundary) whose faces
    /// were then searched.
    pub loop_free_pairs: usize,
    /// Regions not settled: neither proven free of further branches nor searched completely.
    pub undecided_regions: Vec<UndecidedRegion>,
    /// Neighbourhoods of singular points proven to hold no closed component (every component
    /// inside reaches a face, which was searched): their pairs are settled at once instead of
    /// being subdivided to the smallest size.
    pub node_regions: usize,
    /// True only when every pair was settled (disjoint, or loop-free with all its faces
    /// searched to proven leaves), every boundary leaf was settled and no budget ran out: then
    /// every branch inside the domains has a start point in `boundary` or `interior`.
    pub complete: bool,
}

/// Finds start points on every branch of the intersection of `p` and `q` (see the module
/// documentation for what is proven and what is reported as undecided).
pub fn find_start_points(
    p: &RationalBezierPatch,
    q: &RationalBezierPatch,
    opts: &SearchOptions,
) -> SearchReport {
    let (dp, dq) = (p.domain(), q.domain());
    let size = p.model_width().max(q.model_width()).max(f64::MIN_POSITIVE);
    let ctx = Ctx {
        leaf: size * opts.leaf_fraction,
        min_pair: size * opts.min_pair_fraction,
        tol: opts.residual_tol * size.max(1.0),
        budget: opts.max_leaves,
        max_frontier: opts.max_frontier,
    };
    let mut report = SearchReport::default();
    boundary_search(&ctx, p, q, &mut report);
    dedup(&mut report.boundary, dp, dq);
    pair_search(&ctx, p, q, &mut report);
    dedup(&mut report.interior, dp, dq);
    report.complete = !report.truncated && report.undecided_regions.is_empty();
    report
}

/// The boundary search: each of the four boundary curves of each patch against the other patch.
///
/// The eight searches are independent and run in parallel, each as if nothing had been spent
/// before it; they are merged in order, and a search whose budget could have run out at its place
/// in the sequential order (or did run out) is run again there with the budget spent before it, so
/// the result is the one of running them one after another.
fn boundary_search(
    ctx: &Ctx,
    p: &RationalBezierPatch,
    q: &RationalBezierPatch,
    report: &mut SearchReport,
) {
    let mut jobs = Vec::new();
    for (a, b, swapped) in [(p, q, false), (q, p, true)] {
        for (fixed_index, upper) in [(0, false), (0, true), (1, false), (1, true)] {
            // A side collapsed to a point proven off the other patch holds no boundary point.
            let side = 2 * fixed_index + usize::from(upper);
            if let Some(x) = a.collapsed_sides()[side] {
                if point_off_patch(x, b) {
                    continue;
                }
            }
            let edge = Piece::whole(a).face(fixed_index, upper);
            let problem = EdgeProblem {
                a,
                b,
                swapped,
                kind: StartKind::Boundary {
                    surface: usize::from(swapped),
                },
                needs: Needs::Each,
            };
            jobs.push((problem, edge, Piece::whole(b)));
        }
    }
    let run = |(problem, edge, whole): &(EdgeProblem, Piece, Piece), report: &mut SearchReport| {
        let mut found = Vec::new();
        let undecided = edge_search(
            ctx,
            problem,
            edge.clone(),
            whole.clone(),
            ctx.leaf,
            ctx.leaf * REFINE_FAILED_LEAF,
            report,
            &mut found,
        );
        (found, undecided)
    };
    let ahead: Vec<_> = jobs
        .par_iter()
        .map(|job| {
            let mut local = SearchReport {
                pairs: report.pairs,
                ..SearchReport::default()
            };
            let out = run(job, &mut local);
            (out, local.leaves, local.truncated)
        })
        .collect();
    for (job, (out, leaves, truncated)) in jobs.iter().zip(ahead) {
        // Without the budget in reach, the search from `report.leaves` spent leaves is the one
        // run ahead from none (the budget is the only thing it reads from the report).
        let (found, undecided) = if !truncated && report.leaves + leaves + report.pairs < ctx.budget
        {
            report.leaves += leaves;
            out
        } else {
            run(job, report)
        };
        report.boundary.extend(found);
        report.undecided += undecided.len();
        report.undecided_regions.extend(undecided);
    }
    // The leaves round one point, of one side or of sides meeting there, as one region.
    report.undecided_regions = undecided::merged(std::mem::take(&mut report.undecided_regions));
}

struct Ctx {
    leaf: f64,
    min_pair: f64,
    tol: f64,
    budget: usize,
    max_frontier: usize,
}

impl Ctx {
    /// Counts one unit of work; false once the budget is spent.
    fn spend(&self, report: &mut SearchReport) -> bool {
        if report.leaves + report.pairs >= self.budget {
            report.truncated = true;
            return false;
        }
        true
    }
}

/// A leaf where the Krawczyk test decides nothing is subdivided further, down to this fraction
/// of the leaf size, before it is reported as undecided (only undecided leaves are refined, so
/// a deep limit costs nothing where everything is settled; `DEEP_REFINES` below `SHALLOW_REFINE`).
const REFINE_FAILED_LEAF: f64 = 1.0 / 65536.0;
const SHALLOW_REFINE: f64 = 1.0 / 1024.0;
const DEEP_REFINES: usize = 256;

fn diameter(b: &[Interval; 3]) -> f64 {
    b.iter().map(|x| x.wid()).fold(0.0, f64::max)
}

/// Identifies a face search: which surface, the face (direction, value, free range) and the
/// partner piece (its ranges), all exact.
type FaceKey = [u64; 9];

/// `[[lo, hi]; 2]` of two intervals.
fn bounds2(x: &[Interval; 2]) -> [[f64; 2]; 2] {
    [[x[0].inf(), x[0].sup()], [x[1].inf(), x[1].sup()]]
}

/// The interior search: level by level, every pair of pieces is proven disjoint, proven
/// loop-free (then its inner faces are searched), or split; what is left is undecided.
fn pair_search(
    ctx: &Ctx,
    p: &RationalBezierPatch,
    q: &RationalBezierPatch,
    report: &mut SearchReport,
) {
    let mut frontier = vec![(Piece::whole(p), Piece::whole(q))];
    let mut searched = HashMap::new();
    let mut nodes = NodeRegions::default();
    while !frontier.is_empty() {
        let mut next = Vec::new();
        // The tests of a level are independent: run them in parallel, then act on them in
        // order (the result is the one of the sequential loop; only work past a spent budget
        // is wasted).
        let verdicts: Vec<PairVerdict> = frontier
            .par_iter()
            .map(|(a, b)| classify_pair(ctx, p, q, a, b))
            .collect();
        let loop_free: Vec<(&Piece, &Piece)> = frontier
            .iter()
            .zip(&verdicts)
            .filter(|(_, v)| matches!(v, PairVerdict::LoopFree))
            .map(|((a, b), _)| (a, b))
            .collect();
        let mut pre = face_searches_ahead(ctx, p, q, &loop_free, &searched, report);
        let mut rest = frontier.into_iter().zip(verdicts);
        for ((a, b), verdict) in rest.by_ref() {
            if !ctx.spend(report) {
                undecided_pair(ctx, p, q, &a, &b, report);
                break;
            }
            report.pairs += 1;
            match verdict {
                PairVerdict::Disjoint => report.disjoint_pairs += 1,
                PairVerdict::LoopFree => {
                    report.loop_free_pairs += 1;
                    if !face_search(ctx, p, q, &a, &b, &mut searched, &mut pre, report) {
                        undecided_pair(ctx, p, q, &a, &b, report);
                    }
                }
                PairVerdict::Undecided => {
                    if !(nodes.try_pair(ctx, p, q, &a, &b, report) && nodes.settles(&a, &b)) {
                        undecided_pair(ctx, p, q, &a, &b, report);
                    }
                }
                PairVerdict::Split(halves) => {
                    nodes.try_pair(ctx, p, q, &a, &b, report);
                    next.extend(halves);
                }
            }
        }
        let rest = rest.map(|(pair, _)| pair);
        // Budget spent: everything not examined is undecided.
        for (a, b) in rest.chain(if report.truncated {
            std::mem::take(&mut next)
        } else {
            Vec::new()
        }) {
            undecided_pair(ctx, p, q, &a, &b, report);
        }
        // Pairs inside a proven neighbourhood of a singular point are settled.
        next.retain(|(a, b)| !nodes.settles(a, b));
        if next.len() > ctx.max_frontier {
            // Hundreds of regions along a tangential contact: a Newton projection from each
            // centre gives points all along it; the corners' would add four times as many
            // (each Gauss–Newton run slow where the surfaces touch) and nothing new.
            // (Their projections are independent: computed in parallel, recorded in order.)
            let settled: Vec<_> = next
                .par_iter()
                .map(|(a, b)| undecided_region_at(ctx, p, q, a, b, false))
                .collect();
            next.clear();
            for (region, points) in settled {
                report.undecided_regions.push(region);
                report.interior.extend(points);
            }
        }
        frontier = next;
    }
    report.node_regions = nodes.regions.len();
}

/// Records an undecided pair, and offers Newton projections from its centre and from the
/// corners of its P box as start points (they find tangential contacts and singular points,
/// which no exclusion test can settle, along the whole undecided region).
fn undecided_pair(
    ctx: &Ctx,
    p: &RationalBezierPatch,
    q: &RationalBezierPatch,
    a: &Piece,
    b: &Piece,
    report: &mut SearchReport,
) {
    undecided_pair_at(ctx, p, q, a, b, report, true);
}

/// [`undecided_pair`], offering the projections from the corners only if `corners`.
fn undecided_pair_at(
    ctx: &Ctx,
    p: &RationalBezierPatch,
    q: &RationalBezierPatch,
    a: &Piece,
    b: &Piece,
    report: &mut SearchReport,
    corners: bool,
) {
    let (region, points) = undecided_region_at(ctx, p, q, a, b, corners);
    report.undecided_regions.push(region);
    report.interior.extend(points);
}

/// The undecided region of a pair and the start points projected from it (its centre, and the
/// corners of its P box if `corners`), for [`undecided_pair_at`].
fn undecided_region_at(
    ctx: &Ctx,
    p: &RationalBezierPatch,
    q: &RationalBezierPatch,
    a: &Piece,
    b: &Piece,
    corners: bool,
) -> (UndecidedRegion, Vec<StartPoint>) {
    let (dp, dq) = (p.domain(), q.domain());
    let (bp, bq) = (a.declared(&dp, 0.0), b.declared(&dq, 0.0));
    let region = UndecidedRegion {
        p: bounds2(&bp),
        q: bounds2(&bq),
    };
    let (qu, qv) = (bq[0].mid(), bq[1].mid());
    let guesses = [
        [bp[0].mid(), bp[1].mid()],
        [bp[0].inf(), bp[1].inf()],
        [bp[0].inf(), bp[1].sup()],
        [bp[0].sup(), bp[1].inf()],
        [bp[0].sup(), bp[1].sup()],
    ];
    let offered = if corners { &guesses[..] } else { &guesses[..1] };
    let mut points = Vec::new();
    for &[pu, pv] in offered {
        if let Some(x) = project_onto_intersection(p, q, [pu, pv, qu, qv], ctx.tol) {
            if dp.contains(x[0], x[1], 1e-12) && dq.contains(x[2], x[3], 1e-12) {
                points.push(StartPoint {
                    params: x,
                    kind: StartKind::Interior,
                });
            }
        }
    }
    (region, points)
}

/// A curve/surface problem: a boundary curve (or face) of `a` against a piece of `b`.
struct EdgeProblem<'a> {
    a: &'a RationalBezierPatch,
    b: &'a RationalBezierPatch,
    /// `a` is Q (the found parameters are swapped back to `(P, Q)` order).
    swapped: bool,
    kind: StartKind,
    /// What the caller needs of the undecided leaves.
    needs: Needs,
}

/// Outcome of one leaf of a curve/surface search.
enum Leaf {
    /// Proven: exactly one curve point in (an inflation of) the leaf, here.
    Root([f64; 4]),
    /// Proven: no curve point in the leaf (or the one point lies outside the domains).
    Empty,
    /// Not decided.
    Unknown,
}

/// Pair subdivision of the edge piece `a0` of `problem.a` against the piece `b0` of `problem.b`,
/// pruned where bounding boxes are disjoint; every leaf is settled by Krawczyk ([`settle_leaf`]).
/// Found points go to `out` in `(P, Q)` order; returns the leaves left undecided (or not
/// examined when the budget ran out) — all of them, or as many as `problem.needs` asks for (an
/// arc proof at a deepest leaf is the search's dearest step, and a face search whose leaf is
/// already undecided needs none: measured on two cones within 1e-8 of tangent along a line,
/// 33 000 failing proofs made 9 of their 10 s).
#[allow(clippy::too_many_arguments)]
fn edge_search(
    ctx: &Ctx,
    problem: &EdgeProblem,
    a0: Piece,
    b0: Piece,
    leaf0: f64,
    min_leaf: f64,
    report: &mut SearchReport,
    out: &mut Vec<StartPoint>,
) -> Vec<UndecidedRegion> {
    let (a, b) = (problem.a, problem.b);
    let (da, db) = (a.domain(), b.domain());
    let mut undecided = Vec::new();
    let region = |pa: &Piece, pb: &Piece| {
        let (ra, rb) = (
            bounds2(&pa.declared(&da, 0.0)),
            bounds2(&pb.declared(&db, 0.0)),
        );
        if problem.swapped {
            UndecidedRegion { p: rb, q: ra }
        } else {
            UndecidedRegion { p: ra, q: rb }
        }
    };
    // A point inside both domains goes to `out`, in `(P, Q)` order.
    let offer = |x: [f64; 4], out: &mut Vec<StartPoint>| {
        if da.contains(x[0], x[1], 1e-12) && db.contains(x[2], x[3], 1e-12) {
            let params = if problem.swapped {
                [x[2], x[3], x[0], x[1]]
            } else {
                x
            };
            out.push(StartPoint {
                params,
                kind: problem.kind,
            });
        }
    };
    let mut stack = vec![(a0, b0, leaf0)];
    let mut deep = DEEP_REFINES;
    while let Some((pa, pb, mut leaf)) = stack.pop() {
        let (ea, eb) = (pa.bounds(), pb.bounds());
        // Also apart along a flat piece's normal: a boundary curve running beside a plane at
        // a small distance (a sphere's meridian beside a plane parallel to its own) is settled
        // without leaves as small as that distance.
        if boxes_disjoint(&ea, &eb) || separated_across(&pa, &pb) {
            continue;
        }
        let (wa, wb) = (diameter(&ea), diameter(&eb));
        if wa <= leaf && wb <= leaf {
            if !ctx.spend(report) {
                undecided.push(region(&pa, &pb));
                undecided.extend(stack.drain(..).map(|(x, y, _)| region(&x, &y)));
                return undecided;
            }
            report.leaves += 1;
            match settle_leaf(a, b, &pa, &pb, ctx.tol) {
                Leaf::Root(x) => {
                    offer(x, out);
                    continue;
                }
                Leaf::Empty => continue,
                Leaf::Unknown if leaf > min_leaf && (leaf > leaf0 * SHALLOW_REFINE || deep > 0) => {
                    deep -= usize::from(leaf <= leaf0 * SHALLOW_REFINE);
                    // A curve running along the edge (a section along a knot line) is settled
                    // at once by the arc proof rather than at the deepest leaves: every leaf
                    // along it is undecided by the leaf's own test.
                    if let Some(x) = along_edge_point(a, b, &pa, &pb, ctx.tol)
                        .filter(|x| arc_through(a, b, &pa, &pb, x))
                    {
                        // Over a small enough leaf a curve that only touches the edge looks
                        // as if it ran along it (its distance from the edge, curvature times
                        // the leaf squared, is below `along_edge_point`'s allowance): where
                        // Newton on the edge itself lands on the proven arc, that point, on
                        // the edge, is offered instead (the touching point, which the march
                        // then recognises as one).
                        let on_edge = edge_newton(a, b, &pa, &pb, ctx.tol).filter(|y| {
                            da.contains(y[0], y[1], 1e-12)
                                && db.contains(y[2], y[3], 1e-12)
                                && arc_through(a, b, &pa, &pb, y)
                        });
                        offer(on_edge.unwrap_or(x), out);
                        continue;
                    }
                    leaf *= 0.5
                }
                Leaf::Unknown => {
                    // Still offer a Newton point (not proven unique): at a tangential contact
                    // or a singular point it is where the marcher reports the event. Where the
                    // curve merely touches the edge, every curve point of the leaf is proven
                    // to lie on the arc through it: settled.
                    let interior = matches!(problem.kind, StartKind::Interior);
                    let x = leaf_point(a, b, &pa, &pb, ctx.tol, interior);
                    let moot = problem.needs != Needs::Each && !undecided.is_empty();
                    let on_arc = !moot
                        && x.is_some_and(|x| {
                            da.contains(x[0], x[1], 1e-12)
                                && db.contains(x[2], x[3], 1e-12)
                                && arc_through(a, b, &pa, &pb, &x)
                        });
                    if !on_arc && !moot {
                        undecided.push(region(&pa, &pb));
                        if problem.needs == Needs::None {
                            return undecided;
                        }
                    }
                    if let Some(x) = x {
                        offer(x, out);
                    }
                    continue;
                }
            }
        }
        // Split the piece with the larger box, across its longer parameter direction (a
        // boundary curve only along its free direction).
        if wa >= wb {
            for half in pa.split(pa.split_direction()) {
                stack.push((half, pb.clone(), leaf));
            }
        } else {
            for half in pb.split(pb.split_direction()) {
                stack.push((pa.clone(), half, leaf));
            }
        }
    }
    undecided
}

/// Widening of a leaf box, as a fraction of its width on each side, for the Krawczyk test: a
/// curve point on the leaf's boundary (e.g. on a subdivision line) is then interior to the
/// tested box.
const LEAF_GROWTH: f64 = 1.0 / 32.0;

/// Settles one leaf of a curve/surface search with one Krawczyk step ([`settle_box`]) on
/// `A(edge) − B(u, v) = 0`: the edge's fixed parameter held in its (outward-rounded) value, the
/// three free parameters over the leaf box widened by [`LEAF_GROWTH`], the Jacobian enclosed from
/// the pieces' nets over that widened box. A proven point is polished by Newton.
fn settle_leaf(
    a: &RationalBezierPatch,
    b: &RationalBezierPatch,
    edge: &Piece,
    other: &Piece,
    tol: f64,
) -> Leaf {
    let index = if edge.degree()[0] == 0 { 0 } else { 1 };
    let (da, db) = (a.domain(), b.domain());
    let [xa, ya] = edge.declared(&da, LEAF_GROWTH);
    let [xb, yb] = other.declared(&db, LEAF_GROWTH);
    let y = [xa, ya, xb, yb];
    // The centre of the box: exact piece centres, evaluated on the nets.
    let ([ca0, ca1], pa) = edge.centre(&da);
    let ([cb0, cb1], pb) = other.centre(&db);
    let mut xm = [ca0, ca1, cb0, cb1];
    xm[index] = y[index];
    let f: [Interval; 3] = std::array::from_fn(|c| pa[c] - pb[c]);
    let oa = pa.map(|x| x.mid());
    let ob = pb.map(|x| x.mid());
    let (Some(ja), Some(jb)) = (
        edge.partials(&da, None, &oa, LEAF_GROWTH),
        other.partials(&db, None, &ob, LEAF_GROWTH),
    ) else {
        return Leaf::Unknown;
    };
    let (Some(a_free), Some(bu), Some(bv)) = (ja[1 - index], jb[0], jb[1]) else {
        return Leaf::Unknown;
    };
    match settle_box(y, xm, f, index, [a_free, bu, bv]) {
        BoxVerdict::One(enclosure) => {
            let centre = enclosure.map(|x| x.mid());
            let constraint = Constraint::Fixed {
                index,
                value: centre[index],
            };
            let polished = refine(a, b, centre, constraint, tol, 40)
                .ok()
                .map(|r| r.x)
                .filter(|x| {
                    (0..4).all(|k| {
                        let e = enclosure[k];
                        let pad = 1e-9 * (1.0 + e.mag());
                        x[k] >= e.inf() - pad && x[k] <= e.sup() + pad
                    })
                });
            Leaf::Root(polished.unwrap_or(centre))
        }
        BoxVerdict::None => Leaf::Empty,
        BoxVerdict::Unknown => Leaf::Unknown,
    }
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
    fn loops_on_subdivision_lines_are_found() {
        // Circles of radius ρ about (a, b) (graph z = (x−a)² + (y−b)² − ρ² against z = 0) whose
        // centres sit on or near the dyadic subdivision lines, small and large: each is found,
        // on the circle, and the search is complete. (A circle *tangent* to subdivision lines,
        // e.g. radius 0.125 about (0.75, 0.25), leaves its tangent faces undecided: a double
        // root no Krawczyk step settles.)
        let plane = graph(0.0, 0.0, 0.0);
        for (a, b, rho) in [
            (0.0, 0.0, 0.3),
            (0.5, 0.0, 1e-2),
            (0.5, 0.5, 0.2),
            (-0.25, 0.5, 1e-4),
            (0.501, -0.499, 0.05),
            (0.75, 0.25, 0.1),
        ] {
            let bump = PowerSurface::graph(
                Domain::new(-1.0, 1.0, -1.0, 1.0),
                vec![
                    (2, 0, 1.0),
                    (0, 2, 1.0),
                    (1, 0, -2.0 * a),
                    (0, 1, -2.0 * b),
                    (0, 0, a * a + b * b - rho * rho),
                ],
            )
            .to_bezier()
            .unwrap();
            let r = find_start_points(&bump, &plane, &SearchOptions::default());
            assert!(
                r.complete,
                "({a}, {b}, {rho}) {:?}",
                (
                    r.undecided_regions.len(),
                    r.truncated,
                    r.pairs,
                    r.interior.len()
                )
            );
            assert!(!r.interior.is_empty(), "({a}, {b}, {rho})");
            for s in &r.interior {
                let [x, y, ..] = s.params;
                let off = ((x - a).hypot(y - b) - rho).abs();
                assert!(off < 1e-9 * (1.0 + rho.recip()), "({a}, {b}, {rho}) {s:?}");
            }
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
