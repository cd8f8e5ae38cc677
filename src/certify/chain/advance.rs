//! The walk along the marched nodes: strides over several marched intervals while links hold,
//! links that end between marched nodes where the learnt length reaches past one, single
//! intervals (split where needed) where strides fail.

use super::walker::{point_box, scaled_dist, Attempt, Node, Stop, Walker};
use super::MIN_LINK;
use crate::certify::curve::CertifiedEnd;
use inari::Interval;

impl Walker<'_> {
    /// Links from the first node to the last, skipping marched points while links hold (the
    /// stride doubles after a success and halves after a failure; a single marched interval
    /// that fails is split). Where the learnt length reaches well past a marched point but not
    /// to the next, the link ends at a curve point between the two ([`Self::free_end`]): links
    /// as long as the predictor allows, not a whole number of marched intervals. The link into
    /// the last node meets [`Self::end_tolerance`] when set. The last link must also hold
    /// `closing` if given.
    pub(super) fn advance(
        &mut self,
        nodes: &[Node],
        closing: Option<&[Interval; 4]>,
    ) -> std::result::Result<(), CertifiedEnd> {
        let n = nodes.len();
        let mut i = 0;
        // Where the walk is: `nodes[i]`, or a curve point between it and `nodes[i + 1]`.
        let mut cur = match nodes.first() {
            Some(c) => *c,
            None => return Ok(()),
        };
        // After a stride to a marched point fails (not merely too wide), the points up to it are linked one interval
        // at a time: a stride that fails there has usually met a point where the links must
        // shorten, as the marched points do (towards a singular point they halve their
        // distance to it, every stride reaching the last one fails, and each success would
        // otherwise lengthen the next stride back to it).
        let mut single_until = 0;
        // In that stretch, two intervals at a time while that holds: towards a singular point
        // a link from distance `r` to `r/4` holds where one to `r/8` fails (the cylinders:
        // widths far below the tolerance down to `r ≈ 1e-5`), so this halves the links there.
        // After a pair fails, the next two intervals are single.
        let mut singles_before_pair = 0;
        // After a link to a point between marched nodes is not proven, the walk takes the
        // marched nodes up to the next one (every failure makes progress there).
        let mut free_blocked_until = 0;
        while i + 1 < n {
            // As many marched points ahead as the predicted length reaches (at least one).
            let mut k = 1;
            if i < single_until && i + 2 < n {
                if singles_before_pair == 0 {
                    k = 2;
                } else {
                    singles_before_pair -= 1;
                }
            }
            let mut free = None;
            if let (true, Some(l)) = (i >= single_until, self.l_pred) {
                while i + k + 1 < n && scaled_dist(&cur.x, &nodes[i + k + 1].x, &self.scales) <= l {
                    k += 1;
                }
                if i + k + 1 < n && i >= free_blocked_until {
                    free = self.free_end(&cur, &nodes[i + k], &nodes[i + k + 1], l);
                }
            }
            if let Some(f) = free {
                if let Some(reason) = self.out_of_budget() {
                    return Err(CertifiedEnd::Unproven {
                        reason,
                        near: point_box(&cur.x),
                    });
                }
                let len = scaled_dist(&cur.x, &f.x, &self.scales);
                let attempt = self.link(&cur, &f, None);
                self.learn(len, &attempt);
                if let Attempt::Proven(link) = attempt {
                    let limited = self.conditioning_limited(len, link.radius_xyz);
                    if self.push(link, len) {
                        return Ok(());
                    }
                    if let Some(end) = self.stopped_outside(&nodes[i + k + 1], true) {
                        return Err(end);
                    }
                    if let Some(end) = self.conditioning_end(limited, len, &cur.x, &f.x) {
                        return Err(end);
                    }
                    cur = f;
                    i += k;
                } else {
                    free_blocked_until = i + k + 1;
                }
                continue;
            }
            let last = i + k == n - 1;
            let must = last.then_some(closing).flatten();
            self.at_end = last;
            if k > 1 {
                if let Some(reason) = self.out_of_budget() {
                    return Err(CertifiedEnd::Unproven {
                        reason,
                        near: point_box(&cur.x),
                    });
                }
                let len = scaled_dist(&cur.x, &nodes[i + k].x, &self.scales);
                let attempt = self.link(&cur, &nodes[i + k], must);
                self.learn(len, &attempt);
                self.at_end = false;
                if let Attempt::Proven(link) = attempt {
                    let limited = self.conditioning_limited(len, link.radius_xyz);
                    if self.push(link, len) {
                        return Ok(());
                    }
                    if let Some(end) = self.stopped_outside(&nodes[i + k], false) {
                        return Err(end);
                    }
                    if let Some(end) = self.conditioning_end(limited, len, &cur.x, &nodes[i + k].x)
                    {
                        return Err(end);
                    }
                    i += k;
                    cur = nodes[i];
                } else {
                    if i < single_until {
                        singles_before_pair = 2;
                    } else if matches!(attempt, Attempt::Failed) {
                        single_until = i + k;
                    }
                    if self.l_pred.is_some_and(|l| l >= len) {
                        // Not learnt anything that shortens the stride: take one interval.
                        self.l_pred = Some(0.5 * len);
                    }
                }
                continue;
            }
            let stop = self.span(cur, nodes[i + 1], must);
            self.at_end = false;
            if let Stop::Failed(e) = stop {
                return Err(e);
            }
            if self.closed {
                return Ok(());
            }
            i += 1;
            cur = nodes[i];
        }
        Ok(())
    }

    /// A curve point between the marched nodes `a` and `b` for a link from `cur` (at or before
    /// `a`) of scaled length about `l`, when that reaches at least a fifth of the way from `a`
    /// to `b` (and stops a fifth short of `b`); none otherwise or if no point is found.
    fn free_end(&self, cur: &Node, a: &Node, b: &Node, l: f64) -> Option<Node> {
        let to_a = scaled_dist(&cur.x, &a.x, &self.scales);
        let ab = scaled_dist(&a.x, &b.x, &self.scales);
        let frac = (l - to_a) / ab;
        if !(frac >= 0.2 && ab > MIN_LINK) {
            return None;
        }
        self.midpoint(a, b, frac.min(0.8))
    }
}
