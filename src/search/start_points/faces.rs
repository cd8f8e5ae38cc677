//! The face searches of loop-free pairs: each upper face of one piece against the other piece,
//! a face shared by neighbouring pairs searched once, a level's new faces searched in parallel
//! and merged in order.

use super::{
    diameter, edge_search, Ctx, EdgeProblem, FaceKey, SearchReport, StartKind, StartPoint,
    REFINE_FAILED_LEAF,
};
use crate::geometry::piece::Piece;
use crate::geometry::RationalBezierPatch;
use rayon::prelude::*;
use std::collections::HashMap;

/// What the caller of an [`edge_search`](super::edge_search) needs of its undecided leaves.
#[derive(Clone, Copy, PartialEq, Eq)]
pub(super) enum Needs {
    /// Each one (the boundary search reports every undecided leaf as a region).
    Each,
    /// Whether there is any, and the start points of the whole search (a face search: one
    /// undecided leaf leaves its pair undecided, whatever the others' verdicts; after it, the
    /// leaves still offer their Newton points but no arc is proven through them).
    Any,
    /// Whether there is any, and the start points only when there is none (the faces of a
    /// node region): the search stops at the first undecided leaf.
    None,
}

/// One face search of a loop-free pair: the face of one piece against the other piece.
struct FaceJob<'a> {
    key: FaceKey,
    problem: EdgeProblem<'a>,
    face: Piece,
    partner: Piece,
    leaf: f64,
    min_leaf: f64,
}

/// What one face search found.
pub(super) struct FaceOutcome {
    found: Vec<StartPoint>,
    /// Some leaf was left undecided.
    undecided: bool,
    /// Leaves it examined.
    leaves: usize,
    /// The leaf budget ran out during it.
    truncated: bool,
}

/// The face searches of a loop-free pair that lie inside the domains (faces on a domain
/// boundary are covered by the boundary search): each upper face of the P piece against the Q
/// piece and of the Q piece against the P piece.
fn face_jobs<'a>(
    ctx: &Ctx,
    p: &'a RationalBezierPatch,
    q: &'a RationalBezierPatch,
    pp: &Piece,
    pq: &Piece,
) -> Vec<FaceJob<'a>> {
    // Leaves a quarter of the smaller piece: the faces are that small anyway, a large partner
    // piece (a plane against a small curved piece) is cut down to them, and Krawczyk settles
    // most such leaves at the first try (measured: fewer leaves than at the piece size).
    let size = diameter(&pp.bounds()).min(diameter(&pq.bounds()));
    let leaf = ctx.leaf.min(size * 0.25);
    let min_leaf = leaf * REFINE_FAILED_LEAF;
    let mut jobs = Vec::new();
    for (a, b, piece_a, piece_b, swapped) in [(p, q, pp, pq, false), (q, p, pq, pp, true)] {
        // Upper faces only: see the module documentation for why they suffice.
        for (fixed_index, upper) in [(0, true), (1, true)] {
            let range = if fixed_index == 0 {
                piece_a.s
            } else {
                piece_a.r
            };
            let value = range[usize::from(upper)];
            if value == 0.0 || value == 1.0 {
                continue;
            }
            // A face shared with a neighbouring pair against the same partner piece is
            // searched once; its outcome is reused (the key).
            let free = if fixed_index == 0 {
                piece_a.r
            } else {
                piece_a.s
            };
            let key = [
                u64::from(swapped),
                fixed_index as u64,
                value.to_bits(),
                free[0].to_bits(),
                free[1].to_bits(),
                piece_b.s[0].to_bits(),
                piece_b.s[1].to_bits(),
                piece_b.r[0].to_bits(),
                piece_b.r[1].to_bits(),
            ];
            jobs.push(FaceJob {
                key,
                problem: EdgeProblem {
                    a,
                    b,
                    swapped,
                    kind: StartKind::Interior,
                    needs: Needs::Any,
                },
                face: piece_a.face(fixed_index, upper),
                partner: piece_b.clone(),
                leaf,
                min_leaf,
            });
        }
    }
    jobs
}

/// Runs one face search as if `leaves` leaves and `pairs` pairs had been spent before it.
fn run_face(ctx: &Ctx, job: &FaceJob<'_>, leaves: usize, pairs: usize) -> FaceOutcome {
    let mut local = SearchReport {
        leaves,
        pairs,
        ..SearchReport::default()
    };
    let mut found = Vec::new();
    let undecided = edge_search(
        ctx,
        &job.problem,
        job.face.clone(),
        job.partner.clone(),
        job.leaf,
        job.min_leaf,
        &mut local,
        &mut found,
    );
    FaceOutcome {
        found,
        undecided: !undecided.is_empty(),
        leaves: local.leaves - leaves,
        truncated: local.truncated,
    }
}

/// Searches the faces of a loop-free pair (see [`face_jobs`]), taking the outcomes already
/// computed in `pre` and running the others. True when every leaf was settled.
#[allow(clippy::too_many_arguments)]
pub(super) fn face_search(
    ctx: &Ctx,
    p: &RationalBezierPatch,
    q: &RationalBezierPatch,
    pp: &Piece,
    pq: &Piece,
    searched: &mut HashMap<FaceKey, bool>,
    pre: &mut HashMap<FaceKey, FaceOutcome>,
    report: &mut SearchReport,
) -> bool {
    let mut settled = true;
    for job in face_jobs(ctx, p, q, pp, pq) {
        if let Some(&done) = searched.get(&job.key) {
            settled &= done;
            continue;
        }
        let out = pre
            .remove(&job.key)
            .unwrap_or_else(|| run_face(ctx, &job, report.leaves, report.pairs));
        report.leaves += out.leaves;
        report.truncated |= out.truncated;
        report.interior.extend(out.found);
        let done = !out.undecided && !report.truncated;
        searched.insert(job.key, done);
        settled &= done;
    }
    settled
}

/// The face searches of a level's loop-free pairs, run in parallel (each new face once), as if
/// the budget spent so far had been spent before each; [`face_search`] merges them in order.
pub(super) fn face_searches_ahead(
    ctx: &Ctx,
    p: &RationalBezierPatch,
    q: &RationalBezierPatch,
    pairs: &[(&Piece, &Piece)],
    searched: &HashMap<FaceKey, bool>,
    report: &SearchReport,
) -> HashMap<FaceKey, FaceOutcome> {
    let mut seen = std::collections::HashSet::new();
    let jobs: Vec<FaceJob<'_>> = pairs
        .iter()
        .flat_map(|(a, b)| face_jobs(ctx, p, q, a, b))
        .filter(|j| !searched.contains_key(&j.key) && seen.insert(j.key))
        .collect();
    let (leaves, spent) = (report.leaves, report.pairs);
    let outcomes: Vec<FaceOutcome> = jobs
        .par_iter()
        .map(|j| run_face(ctx, j, leaves, spent))
        .collect();
    jobs.iter().map(|j| j.key).zip(outcomes).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::pair::fixtures::square_graph as graph;

    /// The face `v = 0` of P (over `u ∈ [−0.5, 0.5]`) against the whole of Q, searched with
    /// `needs`: the start points found and the number of undecided leaves returned.
    fn search(
        p: &RationalBezierPatch,
        q: &RationalBezierPatch,
        needs: Needs,
    ) -> (Vec<[f64; 4]>, usize) {
        let ctx = Ctx {
            leaf: 2.0 / 64.0,
            min_pair: 2.0 / 1024.0,
            tol: 1e-10,
            budget: 1_000_000,
            max_frontier: 1024,
        };
        let problem = EdgeProblem {
            a: p,
            b: q,
            swapped: false,
            kind: StartKind::Interior,
            needs,
        };
        let face = Piece::over(p, [0.25, 0.75], [0.25, 0.5])
            .unwrap()
            .face(1, true);
        let mut report = SearchReport::default();
        let mut found = Vec::new();
        let undecided = edge_search(
            &ctx,
            &problem,
            face,
            Piece::whole(q),
            ctx.leaf,
            ctx.leaf * REFINE_FAILED_LEAF,
            &mut report,
            &mut found,
        );
        (found.iter().map(|s| s.params).collect(), undecided.len())
    }

    #[test]
    fn crossings_two_millionths_apart_at_a_grazing_angle_are_each_proven() {
        // z = (u − 0.1)² − 1e-12 against z = 0: the lines u = 0.1 ± 1e-6 cross the face v = 0
        // where the surfaces meet at an angle of 2e-6. Leaves refined to 1/65536 of the leaf
        // size (5e-7 here) separate the two crossings and prove each; at 1/1024 they stayed
        // undecided.
        let p = graph(vec![(2, 0, 1.0), (1, 0, -0.2), (0, 0, 0.01 - 1e-12)]);
        let q = graph(vec![(0, 0, 0.0), (1, 0, 0.0)]);
        let (found, undecided) = search(&p, &q, Needs::Each);
        assert_eq!(undecided, 0, "every leaf settled");
        let mut us: Vec<f64> = found.iter().map(|x| x[0]).collect();
        us.sort_by(f64::total_cmp);
        us.dedup_by(|a, b| (*a - *b).abs() < 1e-12);
        assert_eq!(us.len(), 2, "two crossings: {us:?}");
        for (u, want) in us.iter().zip([0.1 - 1e-6, 0.1 + 1e-6]) {
            assert!((u - want).abs() < 1e-9, "{u} against {want}");
        }
    }

    #[test]
    fn a_face_search_that_needs_any_verdict_finds_the_same_points() {
        // z = (u − 0.1)² − 1e-16 against z = 0: the lines u = 0.1 ± 1e-8 cross the face v = 0
        // where the surfaces meet at an angle of 2e-8; the deepest leaves (about 5e-7) hold
        // both lines and stay undecided.
        let p = graph(vec![(2, 0, 1.0), (1, 0, -0.2), (0, 0, 0.01 - 1e-16)]);
        let q = graph(vec![(0, 0, 0.0), (1, 0, 0.0)]);
        let (each, n_each) = search(&p, &q, Needs::Each);
        assert!(
            n_each >= 2,
            "the case needs several undecided leaves: {n_each}"
        );
        let (any, n_any) = search(&p, &q, Needs::Any);
        assert!(n_any >= 1, "still undecided");
        assert_eq!(each, any, "the same start points");
        assert!(!each.is_empty());
        for x in &each {
            assert!((x[0] - 0.1).abs() < 2e-7 && x[1] == 0.0, "{x:?}");
        }
        let (none, n_none) = search(&p, &q, Needs::None);
        assert_eq!(n_none, 1, "stops at the first undecided leaf");
        assert!(none.len() <= each.len());
    }
}
