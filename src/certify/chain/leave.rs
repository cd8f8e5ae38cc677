//! A half that has lost its marched path and leaves the domains.
//!
//! Where the marched points jump between two curves that nearly cross, a half cannot link the
//! last node on its curve to the next marched node (on the other curve); the split links follow
//! the curve they are on, away from the marched points, and can walk it far outside both domains
//! before they stop (thousands of links, boxes far from the patches, and an end that says
//! nothing of what happened). A link towards a split point whose end slice lies wholly outside
//! one of the domains, while the marched node it is heading for lies inside both, shows that:
//! the curve of the chain leaves the domain there, the marched branch does not. The half stops
//! at that link with an unproven end that says so (not a boundary end: the certificate would
//! then claim the whole curve of a marched branch it does not follow).

use super::walker::{Node, Walker};
use crate::certify::curve::CertifiedEnd;
use crate::geometry::surface::pair_bounds;

impl Walker<'_> {
    /// An unproven end if the last link's end slice lies wholly outside P's or Q's domain in
    /// some parameter while the marched node `target` lies inside both.
    pub(super) fn left_marched_path(&self, target: &Node) -> Option<CertifiedEnd> {
        let last = self.links.last()?;
        let (dp, dq) = (self.p.domain(), self.q.domain());
        let bounds = |i: usize| pair_bounds(&dp, &dq, i);
        let inside = (0..4).all(|i| {
            let [lo, hi] = bounds(i);
            lo <= target.x[i] && target.x[i] <= hi
        });
        let e = &last.end_slice;
        let outside = (0..4).any(|i| {
            let [lo, hi] = bounds(i);
            e[i].sup() < lo || e[i].inf() > hi
        });
        (inside && outside).then(|| CertifiedEnd::Unproven {
            reason: "the chain left the marched points and its curve leaves the domain".into(),
            near: *e,
        })
    }
}
