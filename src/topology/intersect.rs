//! All branches of the intersection of two patches: start-point search, then one trace per branch.
//!
//! Boundary start points are traced first (they begin and end every open branch), then interior
//! candidates (closed loops, and arcs cut off by singular points), then the arcs leaving the
//! singular points met ([`trace_graph`]). A start point that lies on a branch already traced is
//! skipped and an arc reached from its other end is not traced again, so no arc is traced twice.

use crate::geometry::RationalBezierPatch;
use crate::march::branch::Intersection;
use crate::march::MarchOptions;
use crate::pair::branch_point::SingularNode;
use crate::search::start_points::UndecidedRegion;
use crate::search::start_points::{find_start_points, SearchOptions, SearchReport};
use crate::topology::graph::{has_arcs, trace_graph};
use std::time::Instant;

/// Counts and timings of one [`intersect`] run.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct IntersectStats {
    /// Boundary start points found.
    pub boundary_starts: usize,
    /// Interior candidates found.
    pub interior_candidates: usize,
    /// Start points skipped because a traced branch already passes through them.
    pub skipped_covered: usize,
    /// Start points from which tracing failed (Newton could not refine them).
    pub failed_starts: usize,
    /// Leaf boxes of the search where Newton found no point (undecided regions).
    pub undecided_leaves: usize,
    /// The search ran out of its leaf budget.
    pub search_truncated: bool,
    /// Start points where the surfaces are tangent (normals parallel): reported as singular
    /// events, not as branches.
    pub contact_points: usize,
    /// Points over all branches.
    pub points: usize,
    /// Sub-patch pairs the search proved to hold no intersection.
    pub disjoint_pairs: usize,
    /// Sub-patch pairs the search proved loop-free (their faces were then searched).
    pub loop_free_pairs: usize,
    /// Neighbourhoods of singular points the search proved to hold no closed component (their
    /// faces were then searched; no pair inside was subdivided further).
    pub node_regions: usize,
    /// Regions the search could not settle (parameter boxes on P and Q, rounded outward).
    pub undecided_regions: Vec<UndecidedRegion>,
    /// The search settled every region: every branch inside the domains got a start point.
    pub search_complete: bool,
    /// Seconds spent in the start-point search.
    pub search_seconds: f64,
    /// Seconds spent marching.
    pub march_seconds: f64,
}

/// The branches, events and statistics of one surface pair.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct IntersectOutcome {
    /// Branches and events.
    pub intersection: Intersection,
    /// Counts and timings.
    pub stats: IntersectStats,
    /// The singular points met (branch points, contact points) with their exits.
    pub nodes: Vec<SingularNode>,
}

/// Finds and traces every branch of `P ∩ Q` that the start-point search reaches.
///
/// Each branch is traced once: a start point that, refined onto the curve, lies within an already
/// traced branch's chord deviation bound (see `covers`; in model space, and within 2 % of the
/// domains in parameters) is skipped; singular
/// points are nodes of a graph whose arcs are each traced once (see [`trace_graph`]). Events are
/// merged, duplicates (the same point reached from two sides) removed.
pub fn intersect(
    p: &RationalBezierPatch,
    q: &RationalBezierPatch,
    march: &MarchOptions,
    search: &SearchOptions,
) -> IntersectOutcome {
    let t0 = Instant::now();
    let report: SearchReport = find_start_points(p, q, search);
    let t1 = Instant::now();
    let mut stats = IntersectStats {
        boundary_starts: report.boundary.len(),
        interior_candidates: report.interior.len(),
        undecided_leaves: report.undecided,
        search_truncated: report.truncated,
        disjoint_pairs: report.disjoint_pairs,
        loop_free_pairs: report.loop_free_pairs,
        node_regions: report.node_regions,
        undecided_regions: report.undecided_regions.clone(),
        search_complete: report.complete,
        search_seconds: (t1 - t0).as_secs_f64(),
        ..Default::default()
    };
    let starts: Vec<[f64; 4]> = report
        .boundary
        .iter()
        .chain(&report.interior)
        .map(|s| s.params)
        .collect();
    let graph = trace_graph(p, q, &starts, march);
    stats.skipped_covered = graph.stats.skipped_covered;
    stats.failed_starts = graph.stats.failed_starts;
    stats.contact_points = graph.nodes.iter().filter(|n| !has_arcs(n)).count();
    stats.points = graph.branches.iter().map(|b| b.points.len()).sum();
    stats.march_seconds = t1.elapsed().as_secs_f64();
    IntersectOutcome {
        intersection: Intersection {
            branches: graph.branches,
            events: graph.events,
        },
        stats,
        nodes: graph.nodes,
    }
}
