//! Shells: many faces against many faces.
//!
//! A [`Face`] is one surface of a scene, held as the rational Bézier patches it is made of (one
//! for a Bézier or polynomial surface; one per pair of knot spans for a NURBS surface, each on
//! its knot span so its parameters are the NURBS's own). [`intersect_shells`] intersects every
//! Bézier piece of every face of shell A with every piece of every face of shell B: pairs whose
//! rigorous bounding boxes (the hulls of their control nets) are disjoint are skipped, the rest
//! go through [`intersect`] in parallel on rayon's thread pool, and the results come back in a
//! fixed order (faces of A, faces of B, pieces of A, pieces of B, all ascending) whatever the
//! scheduling.
//!
//! Each piece pair is traced on its own: a curve that crosses a knot line or passes from one
//! face to another comes back as one branch per piece pair, and a curve that runs *along* an
//! edge two pieces share is traced by both pairs and reported once (`edge_copies.rs`). The
//! branches are then joined end
//! to end across knot lines, periodic seams and edges shared by two faces ([`join`]): the
//! result also lists one [`JoinedCurve`] per connected curve, each join proven or flagged.

mod chart;
pub mod corner;
mod edge_copies;
pub mod edges;
pub mod join;
mod near;
mod own_corner;
mod pole_cap;
mod sites;
mod slivers;

use rayon::prelude::*;

use crate::error::Result;
use crate::geometry::bezier::RationalBezierPatch;
use crate::geometry::enclosure::boxes_disjoint;
use crate::geometry::nurbs::NurbsSurface;
use crate::geometry::surface::Domain;
use crate::solve::{intersect, Options, SurfaceIntersection};
use inari::Interval;
use std::time::Instant;

use crate::solve::TracedBranch;
pub use join::{BranchEnd, CurvePart, Join, JoinStatus, JoinedCurve};

/// One face of a shell: its rational Bézier pieces and their rigorous bounding boxes.
#[derive(Debug, Clone, PartialEq)]
pub struct Face {
    pieces: Vec<RationalBezierPatch>,
    boxes: Vec<[Interval; 3]>,
    domain: Domain,
}

impl Face {
    /// A face that is one Bézier patch.
    pub fn from_patch(p: RationalBezierPatch) -> Face {
        let domain = p.domain();
        Face {
            boxes: vec![p.bounding_box()],
            pieces: vec![p],
            domain,
        }
    }

    /// A face that is a NURBS surface, split into its Bézier pieces
    /// ([`NurbsSurface::to_bezier`]).
    ///
    /// Errors: as [`NurbsSurface::to_bezier`].
    pub fn from_nurbs(s: &NurbsSurface) -> Result<Face> {
        let pieces = s.to_bezier()?;
        Ok(Face {
            boxes: pieces.iter().map(|p| p.bounding_box()).collect(),
            pieces,
            domain: s.domain(),
        })
    }

    /// The Bézier pieces, each on its own part of the face's domain.
    pub fn pieces(&self) -> &[RationalBezierPatch] {
        &self.pieces
    }

    /// The face's parameter domain (the union of its pieces' domains).
    pub fn domain(&self) -> Domain {
        self.domain
    }

    /// The single patch of a one-piece face.
    pub fn as_patch(&self) -> Option<&RationalBezierPatch> {
        match self.pieces.as_slice() {
            [p] => Some(p),
            _ => None,
        }
    }
}

/// The intersection of one Bézier piece of a face of A with one of a face of B.
#[derive(Debug)]
pub struct PieceIntersection {
    /// `[face of A, face of B]`.
    pub faces: [usize; 2],
    /// `[piece of that face of A, piece of that face of B]`.
    pub pieces: [usize; 2],
    /// The result of [`intersect`] on the two pieces (parameters are the faces' own).
    pub result: SurfaceIntersection,
}

/// The intersection of two shells.
#[derive(Debug)]
pub struct ShellIntersection {
    /// The options every piece pair ran with.
    pub options: Options,
    /// The piece pairs that were traced (bounding boxes not disjoint), in a fixed order.
    pub pairs: Vec<PieceIntersection>,
    /// How many piece pairs there were in all.
    pub piece_pairs: usize,
    /// How many the bounding-box pre-filter proved disjoint (not traced).
    pub skipped_pairs: usize,
    /// Branches removed as copies of another: a curve running along an edge two pieces share
    /// (a knot line, a seam, a face edge) is traced by both pieces' pairs, and one copy is kept
    /// (see `shell/edge_copies.rs`).
    pub edge_copies: usize,
    /// Undecided search regions removed from their pairs because a proven join through a pole
    /// covers them (every curve point there lies on its arc; `shell/pole_cap.rs`).
    pub pole_settled: usize,
    /// The branches of all pairs joined into connected curves ([`join::join_branches`]); every
    /// branch is a part of exactly one curve. Branches are numbered shell-wide, pair after
    /// pair ([`ShellIntersection::branch`]).
    pub curves: Vec<JoinedCurve>,
    /// Wall-clock seconds spent joining.
    pub join_seconds: f64,
}

impl ShellIntersection {
    /// Whether every traced piece pair settled its search ([`SurfaceIntersection::is_complete`]).
    pub fn is_complete(&self) -> bool {
        self.pairs.iter().all(|p| p.result.is_complete())
    }

    /// The number of branches over all piece pairs.
    pub fn branch_count(&self) -> usize {
        self.pairs.iter().map(|p| p.result.branches.len()).sum()
    }

    /// The branch with shell-wide index `g` (the branches of [`Self::pairs`] numbered in
    /// order, as in the result document) and its piece pair.
    pub fn branch(&self, g: usize) -> Option<(&PieceIntersection, &TracedBranch)> {
        let mut g = g;
        for p in &self.pairs {
            match p.result.branches.get(g) {
                Some(b) => return Some((p, b)),
                None => g -= p.result.branches.len(),
            }
        }
        None
    }
}

/// Intersect every Bézier piece of every face of `a` with every piece of every face of `b`
/// (see the module documentation), and join the branches into curves.
///
/// [`Options::time_limit`] applies to the whole shell pair, counted from this call: each piece
/// pair runs with what is left of it when it starts, so a pair that starts
/// after it has expired certifies its first links only and ends its halves unproven.
///
/// Errors: the first error of [`intersect`] in pair order (bad options).
pub fn intersect_shells(a: &[Face], b: &[Face], opts: &Options) -> Result<ShellIntersection> {
    opts.check()?;
    let mut all = Vec::new();
    for (fa, face_a) in a.iter().enumerate() {
        for (fb, face_b) in b.iter().enumerate() {
            for pa in 0..face_a.pieces.len() {
                for pb in 0..face_b.pieces.len() {
                    all.push(([fa, fb], [pa, pb]));
                }
            }
        }
    }
    let piece_pairs = all.len();
    let deadline = opts.time_limit.map(|limit| Instant::now() + limit);
    let kept: Vec<([usize; 2], [usize; 2])> = all
        .into_iter()
        .filter(|&([fa, fb], [pa, pb])| !boxes_disjoint(&a[fa].boxes[pa], &b[fb].boxes[pb]))
        .collect();
    let skipped_pairs = piece_pairs - kept.len();
    let pairs = kept
        .into_par_iter()
        .map(|(faces, pieces)| {
            let p = &a[faces[0]].pieces[pieces[0]];
            let q = &b[faces[1]].pieces[pieces[1]];
            intersect(p, q, &pair_options(opts, deadline, Instant::now())).map(|result| {
                PieceIntersection {
                    faces,
                    pieces,
                    result,
                }
            })
        })
        .collect::<Result<Vec<_>>>()?;
    let started = Instant::now();
    let mut pairs = pairs;
    let edge_copies = edge_copies::drop_edge_copies(a, b, &mut pairs);
    let (curves, settled) = join::join_and_settle(a, b, &pairs);
    let pole_settled = settled.len();
    settle(&mut pairs, settled);
    Ok(ShellIntersection {
        options: *opts,
        pairs,
        piece_pairs,
        skipped_pairs,
        edge_copies,
        pole_settled,
        curves,
        join_seconds: started.elapsed().as_secs_f64(),
    })
}

/// Removes the undecided search regions `settled` (`(pair, index)`) from their pairs, which
/// are then complete if nothing else is left undecided.
fn settle(pairs: &mut [PieceIntersection], mut settled: Vec<(usize, usize)>) {
    settled.sort_unstable();
    settled.dedup();
    for &(k, i) in settled.iter().rev() {
        let search = &mut pairs[k].result.stats.search;
        if i < search.undecided_regions.len() {
            search.undecided_regions.remove(i);
            search.search_complete =
                !search.search_truncated && search.undecided_regions.is_empty();
        }
    }
}

/// The options of a piece pair that starts at `now`: `opts` with the time left before the
/// shell's `deadline` (zero once it has passed) as its time limit.
pub(crate) fn pair_options(opts: &Options, deadline: Option<Instant>, now: Instant) -> Options {
    Options {
        time_limit: deadline.map(|d| d.saturating_duration_since(now)),
        ..*opts
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::time::Duration;

    #[test]
    fn the_time_limit_is_the_shells_not_each_pairs() {
        let start = Instant::now();
        let opts = Options {
            time_limit: Some(Duration::from_secs(2)),
            ..Options::default()
        };
        let deadline = opts.time_limit.map(|l| start + l);
        let at = |s: u64| pair_options(&opts, deadline, start + Duration::from_secs(s));
        assert_eq!(at(0).time_limit, Some(Duration::from_secs(2)));
        assert_eq!(at(1).time_limit, Some(Duration::from_secs(1)));
        // A pair that starts after the shell's deadline has no time left.
        assert_eq!(at(3).time_limit, Some(Duration::ZERO));
        let none = Options::default();
        assert_eq!(pair_options(&none, None, start).time_limit, None);
        assert_eq!(at(1).step, opts.step);
    }
}
