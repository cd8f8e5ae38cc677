//! Where one link hands over to the next: the enclosed slice at a link's end.
//!
//! The join box a link leaves for the next one is its own enclosure of the end slice, narrowed
//! by Krawczyk on that slice ([`tight_slice`]) when the link is wide ([`TIGHTEN_ABOVE`]) or
//! when a link from it fails ([`Walker::tighten_join`]); a test against the domains' bounds
//! narrows it on demand ([`Walker::last_end_slice`]).

use super::walker::{Link, Walker};
use crate::certify::segment::SegmentProof;
use crate::geometry::surface::pair_bounds;
use crate::geometry::RationalBezierPatch;
use crate::pair::krawczyk::{krawczyk, KrawczykResult};
use inari::Interval;

/// A kept link's end slice is narrowed by Krawczyk ([`tight_slice`], about a tenth of a link's
/// cost) only when the link's model-space tube is wider than this part of the tolerance. A
/// narrower link's own enclosure of the slice is as narrow as the link, and the next link's
/// uniqueness box, which takes it in, then barely widens (Fig. 7, the cylinders, Viviani and the
/// sphere: the same links, 5–8 % less chain time). Near-tangent pairs, whose tubes are wide, still
/// narrow every slice, and the domain tests narrow on demand ([`Walker::last_end_slice`]).
const TIGHTEN_ABOVE: f64 = 0.25;

/// The slice `x_j = x` of a proven segment, enclosed tightly: the segment's enclosure there,
/// narrowed by Krawczyk on the slice of its uniqueness tube (the curve point of the slice is the
/// one zero of that box, so any enclosure of it from the narrowing is valid).
pub(super) fn tight_slice(
    p: &RationalBezierPatch,
    q: &RationalBezierPatch,
    proof: &SegmentProof,
    x: f64,
) -> [Interval; 4] {
    let loose = proof.box_over(x, x);
    let tube = proof.tube_over(x, x);
    match krawczyk(p, q, tube, proof.pred.along, 4) {
        KrawczykResult::Proven { enclosure, .. } => {
            let both: [Interval; 4] = std::array::from_fn(|i| enclosure[i].intersection(loose[i]));
            if both.iter().any(|v| v.is_empty()) {
                loose
            } else {
                both
            }
        }
        KrawczykResult::NotProven(_) => loose,
    }
}

impl Walker<'_> {
    /// The end slice of a link about to be kept: its own enclosure, narrowed by [`tight_slice`]
    /// when the link is wider than [`TIGHTEN_ABOVE`] of the tolerance.
    pub(super) fn settle_end_slice(&self, link: &mut Link) {
        if link.radius_xyz > TIGHTEN_ABOVE * self.opts.required_tolerance {
            link.end_slice = tight_slice(self.p, self.q, &link.proof, link.to);
            link.tightened = true;
        }
    }

    /// Narrows the last link's end slice, and the join, by [`tight_slice`] if it was not.
    pub(super) fn tighten_join(&mut self) {
        let (p, q) = (self.p, self.q);
        let Some(last) = self.links.last_mut().filter(|l| !l.tightened) else {
            return;
        };
        last.end_slice = tight_slice(p, q, &last.proof, last.to);
        last.tightened = true;
        self.join = Some(last.end_slice);
    }

    /// The last link's end slice for a test against the domains' bounds: narrowed by
    /// [`tight_slice`] now if it was not and it holds a bound of either domain (a slice clear
    /// of every bound decides the test as well as the narrowed one would).
    pub(super) fn last_end_slice(&self) -> Option<[Interval; 4]> {
        let link = self.links.last()?;
        let e = link.end_slice;
        let (dp, dq) = (self.p.domain(), self.q.domain());
        let straddles = (0..4).any(|i| {
            let [lo, hi] = pair_bounds(&dp, &dq, i);
            e[i].contains(lo) || e[i].contains(hi)
        });
        Some(if straddles && !link.tightened {
            tight_slice(self.p, self.q, &link.proof, link.to)
        } else {
            e
        })
    }
}
