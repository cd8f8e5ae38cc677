//! A half that has lost its marched path and leaves the domains.
//!
//! Where the marched points jump between two curves that nearly cross, a half cannot link the
//! last node on its curve to the next marched node (on the other curve); the split links follow
//! the curve they are on, away from the marched points, and can walk it far outside both domains
//! before they stop (thousands of links, boxes far from the patches, and an end that says
//! nothing of what happened). A link towards a split point whose end slice lies wholly outside
//! one of the domains shows that the curve of the chain leaves the domain inside the chain's
//! boxes: the half stops at that link with a proven boundary end of the curve it follows (the
//! link starts where the chain's boxes are still joined to the domain, and its end slice lies
//! wholly beyond the bound, so the curve crosses it in between).
//!
//! That curve is not the marched branch's all the way when the node the link heads for lies
//! inside both domains (the marched branch went on along another curve after a jump, or over a
//! dip of this one out of the domain): its marched points past the jump are then held by no
//! tube of this certificate. `solve/repair.rs` finds them (a marched end held by no tube of its
//! own certificate) and has them traced again unless another branch's certificate holds them.
//! An unproven end there would say less than is proven: the curve does leave the domain there.
//!
//! The walk past a marched boundary end heads for a curve point found beyond the boundary; where
//! the curve only dips out of the domain (it grazes the boundary), that point can lie back
//! inside, the check above stops the walk at the first link out of the domain, and that link
//! proves the boundary end (the same test as the walk's last link): the half ends there and does
//! not run on into the next marched piece of the curve. Where the link into the marched end
//! itself dips out and back (its end slices inside), the first of its slices wholly beyond the
//! bound proves the boundary end, and the link is cut there.

use super::walker::{newton, point_box, Node, Stop, Walker};
use crate::certify::curve::CertifiedEnd;
use crate::geometry::surface::pair_bounds;
use inari::Interval;

/// Slices of a link tested by [`Walker::dips_out`].
const DIP_SLICES: usize = 32;

impl Walker<'_> {
    /// The surface (0 for P, 1 for Q) whose domain the last link's end slice lies wholly
    /// outside of, in some parameter: the chain's curve leaves that domain inside the link.
    pub(super) fn outside_domain(&self) -> Option<(usize, bool)> {
        let e = &self.last_end_slice()?;
        let (dp, dq) = (self.p.domain(), self.q.domain());
        (0..4).find_map(|i| {
            let [lo, hi] = pair_bounds(&dp, &dq, i);
            if e[i].sup() < lo {
                Some((i / 2, self.collapsed(i, true)))
            } else if e[i].inf() > hi {
                Some((i / 2, self.collapsed(i, false)))
            } else {
                None
            }
        })
    }

    /// Whether the bound of parameter `i` (0..4: σ, t of P, u, v of Q), the lower one if
    /// `below`, is a side its patch collapses to a pole: not a boundary of the surface (the
    /// surface goes on round the pole), so a chain leaving through it proves no boundary end.
    pub(super) fn collapsed(&self, i: usize, below: bool) -> bool {
        let patch = [self.p, self.q][i / 2];
        patch.collapsed_sides()[2 * (i % 2) + usize::from(!below)].is_some()
    }

    /// The end of a half whose chain leaves `surface`'s domain through a bound (`pole`: a side
    /// collapsed to a pole) inside the box `near`: a proven boundary end, or unproven at a pole.
    pub(super) fn leaving(&self, surface: usize, pole: bool, near: [Interval; 4]) -> CertifiedEnd {
        if pole {
            CertifiedEnd::Unproven {
                reason: format!(
                    "the chain's curve leaves {}'s parameters through a side collapsed to a \
                     pole, which is no boundary of the surface",
                    ["P", "Q"][surface]
                ),
                near,
            }
        } else {
            CertifiedEnd::Boundary { surface }
        }
    }

    /// The end of a half whose last link, towards a split point on the way to `target` (a
    /// marched node), left a domain (its end slice lies wholly outside it): a proven boundary
    /// end, whether `target` lies on that bound (the marched branch ends there too) or inside
    /// both domains (the half has left the marched points; see the module documentation);
    /// none if `target` lies outside (the walk past a marched end heads outside on purpose).
    pub(super) fn left_marched_path(&self, target: &Node) -> Option<CertifiedEnd> {
        let e = &self.last_end_slice()?;
        let (dp, dq) = (self.p.domain(), self.q.domain());
        let out = (0..4).find_map(|i| {
            let [lo, hi] = pair_bounds(&dp, &dq, i);
            if e[i].sup() < lo {
                Some((i, lo, true))
            } else if e[i].inf() > hi {
                Some((i, hi, false))
            } else {
                None
            }
        });
        let (i, bound, below) = out?;
        let on_bound = (target.x[i] - bound).abs() <= 1e-9 * self.scales[i];
        let inside = (0..4).all(|k| {
            let [lo, hi] = pair_bounds(&dp, &dq, k);
            lo <= target.x[k] && target.x[k] <= hi
        });
        (on_bound || inside).then(|| self.leaving(i / 2, self.collapsed(i, below), *e))
    }

    /// For a link that heads for a marched node on a bound of a domain (the marched end there):
    /// whether its curve already crosses that bound inside the link (the curve grazes the
    /// boundary, dips out and comes back to the marched end). The link's enclosure is tested on
    /// [`DIP_SLICES`] slices from its start; at the first one wholly beyond the bound the link is
    /// cut (its reported curve and boxes end there; its radii, proven over the whole link,
    /// still hold) and the half ends with a proven boundary end.
    pub(super) fn dips_out(&mut self, target: &Node) -> Option<CertifiedEnd> {
        let (dp, dq) = (self.p.domain(), self.q.domain());
        let (i, bound, below) = (0..4).find_map(|i| {
            let [lo, hi] = pair_bounds(&dp, &dq, i);
            let tol = 1e-9 * self.scales[i];
            if (target.x[i] - lo).abs() <= tol {
                Some((i, lo, true))
            } else if (target.x[i] - hi).abs() <= tol {
                Some((i, hi, false))
            } else {
                None
            }
        })?;
        let link = self.links.last_mut()?;
        let beyond = |e: &[Interval; 4]| {
            if below {
                e[i].sup() < bound
            } else {
                e[i].inf() > bound
            }
        };
        let (from, to) = (link.from, link.to);
        // Only slices before the last: a curve first beyond the bound at the marched end itself
        // leaves there (it does not dip out and come back), and the exit past the boundary
        // ([`Walker::exit`]) proves that end with room beyond the side, where a cut at the
        // node would end the chain a rounding error past it.
        let cut = (1..DIP_SLICES)
            .map(|k| from + (to - from) * k as f64 / DIP_SLICES as f64)
            .find(|&x| beyond(&link.proof.box_over(x, x)))?;
        link.to = cut;
        link.end_slice = link.proof.box_over(cut, cut);
        link.tightened = false;
        let near = link.end_slice;
        Some(self.leaving(i / 2, self.collapsed(i, below), near))
    }

    /// After a link towards `target` (a split point on the way to it if `split`): the end of
    /// the half if the link left a domain ([`Walker::left_marched_path`],
    /// [`Walker::dips_out`]).
    pub(super) fn stopped_outside(&mut self, target: &Node, split: bool) -> Option<CertifiedEnd> {
        if split {
            if let Some(end) = self.left_marched_path(target) {
                return Some(end);
            }
        }
        self.dips_out(target)
    }

    /// Past a marched boundary end, where the walk stopped early: a proven boundary end if the
    /// last link already left a domain (its target, the curve point found past the boundary,
    /// can lie back inside when the curve only dips out of the domain there).
    pub(super) fn exit_stopped(&self, end: CertifiedEnd) -> CertifiedEnd {
        match self.outside_domain() {
            Some((surface, pole)) => {
                let near = self.last_end_slice().unwrap_or([Interval::ENTIRE; 4]);
                self.leaving(surface, pole, near)
            }
            None => end,
        }
    }

    /// At a boundary end: a node past the boundary of `surface` along the curve, proven links
    /// to it, and the end proven when the last slice lies wholly outside.
    pub(super) fn exit(&mut self, last: Node, surface: usize) -> CertifiedEnd {
        let (dp, dq) = (self.p.domain(), self.q.domain());
        let coords = if surface == 0 { [0, 1] } else { [2, 3] };
        // The coordinate nearest its bound, moving outwards (not one the curve runs along, a
        // side of a section along a knot line: its tangent component is rounding).
        let speed = (0..4).fold(0.0f64, |m, k| m.max(last.t[k].abs() / self.scales[k]));
        let mut best: Option<(usize, f64, f64)> = None;
        for &i in &coords {
            let [lo, hi] = pair_bounds(&dp, &dq, i);
            if last.t[i].abs() / self.scales[i] <= 1e-9 * speed {
                continue;
            }
            for (bound, sign) in [(lo, -1.0), (hi, 1.0)] {
                if last.t[i] * sign <= 0.0 {
                    continue;
                }
                let gap = (bound - last.x[i]).abs() / self.scales[i];
                if best.is_none_or(|b| gap < b.1) {
                    best = Some((i, gap, bound));
                }
            }
        }
        let unproven = |reason: &str| CertifiedEnd::Unproven {
            reason: reason.into(),
            near: point_box(&last.x),
        };
        let Some((b, _, bound)) = best else {
            return unproven("the curve does not leave the domain at the marched boundary end");
        };
        let margin = 1e-7 * self.scales[b] + 4.0 * self.join_width();
        let dist = (bound - last.x[b]).abs() + margin;
        let scale = dist / last.t[b].abs();
        let guess: [f64; 4] = std::array::from_fn(|i| last.x[i] + scale * last.t[i]);
        let j = (0..4)
            .max_by(|&x, &y| {
                (last.t[x].abs() / self.scales[x]).total_cmp(&(last.t[y].abs() / self.scales[y]))
            })
            .unwrap_or(b);
        let Some(out) =
            newton(self.p, self.q, guess, j, guess[j]).and_then(|r| self.node(r.x, &last.t))
        else {
            return unproven("no curve point found past the boundary");
        };
        if let Stop::Failed(end) = self.span(last, out, None) {
            return self.exit_stopped(end);
        }
        let end = self.last_end_slice();
        let [lo, hi] = pair_bounds(&dp, &dq, b);
        match end {
            Some(e) if e[b].sup() < lo || e[b].inf() > hi => {
                self.leaving(surface, self.collapsed(b, e[b].sup() < lo), e)
            }
            _ => unproven("the last slice past the boundary is not wholly outside the domain"),
        }
    }

    /// Largest half-width of the current join box (0 without one).
    fn join_width(&self) -> f64 {
        self.join
            .map(|b| b.iter().map(|x| x.wid()).fold(0.0, f64::max))
            .unwrap_or(0.0)
    }
}
