//! The boundary ends of a marched branch, checked by the boundary-direction test.
//!
//! A marched branch runs from its first point to its last. Where an end lies on a domain face,
//! Grandine's test ([`classify_on_faces`]) says whether the curve enters or leaves the domain
//! there; read along the branch's direction of travel the first end must be `Enters` and the
//! last `Leaves`. Anything else (`Touches`, `Isolated`, the wrong way round) is a start treated
//! as an end or the reverse, and is flagged as inconsistent.

use crate::error::Result;
use crate::geometry::ParametricSurface;
use crate::march::branch::{Branch, EndReason};
use crate::pair::boundary_direction::{
    classify_on_faces, BoundaryClassification, BoundaryDirection, BoundaryOptions, BoundarySide,
};
use crate::pair::field::ScalarSurface;

/// The check of one face at one boundary end of a branch.
#[derive(Debug, Clone, PartialEq)]
pub struct BranchEndCheck {
    /// Which end: 0 = the first point, 1 = the last.
    pub end: usize,
    /// The face the end point lies on.
    pub side: BoundarySide,
    /// The classification of the point on that face.
    pub classification: BoundaryClassification,
    /// What the curve does there for a traveller moving along the branch.
    pub seen: BoundaryDirection,
    /// `seen` is `Enters` at the first end and `Leaves` at the last.
    pub consistent: bool,
}

/// Checks every boundary end of `branch` (ends whose reason is [`EndReason::Boundary`]) on each
/// face its point lies on. A branch of fewer than two points has no direction of travel and
/// gives no checks. An end whose point cannot be classified (not within the classifier's
/// tolerances of a face or of the curve) gives its error in place of checks.
pub fn check_branch_ends<P, Q>(
    p: &P,
    q: &Q,
    branch: &Branch,
    opts: &BoundaryOptions,
) -> Vec<Result<Vec<BranchEndCheck>>>
where
    P: ParametricSurface + ScalarSurface + ?Sized,
    Q: ParametricSurface + ScalarSurface + ?Sized,
{
    let n = branch.points.len();
    if n < 2 {
        return Vec::new();
    }
    let pts = &branch.points;
    let chord =
        |a: usize, b: usize| -> [f64; 3] { std::array::from_fn(|i| pts[b].xyz[i] - pts[a].xyz[i]) };
    let mut out = Vec::new();
    for end in 0..2 {
        if !matches!(branch.ends[end], EndReason::Boundary { .. }) {
            continue;
        }
        let (at, travel, expected) = if end == 0 {
            (0, chord(0, 1), BoundaryDirection::Enters)
        } else {
            (n - 1, chord(n - 2, n - 1), BoundaryDirection::Leaves)
        };
        let c = &pts[at];
        let y = [c.p[0], c.p[1], c.q[0], c.q[1]];
        out.push(classify_on_faces(p, q, y, opts).map(|faces| {
            faces
                .into_iter()
                .map(|(side, classification)| {
                    let seen = classification.along(travel);
                    BranchEndCheck {
                        end,
                        side,
                        classification,
                        seen,
                        consistent: seen == expected,
                    }
                })
                .collect()
        }));
    }
    out
}
