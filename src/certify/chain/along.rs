//! The along coordinate of a link: the parameter a link's curve is graphed over (see
//! `segment.rs`), chosen by speed and monotonicity between the link's ends, and the others
//! to try where it turns.

use super::walker::{Link, Node, Walker};
use crate::certify::lean_patch::LeanPatch;
use inari::Interval;

impl<'a> Walker<'a> {
    /// How well `x_i` serves as the along coordinate from `a` to `b`: its smaller scaled speed at
    /// the two ends, if it moves between them the way both velocities point.
    fn along_score(&self, a: &Node, b: &Node, i: usize) -> Option<f64> {
        let d = b.x[i] - a.x[i];
        let ok = d != 0.0 && d.signum() == a.t[i].signum() && d.signum() == b.t[i].signum();
        ok.then(|| a.t[i].abs().min(b.t[i].abs()) / self.scales[i])
    }

    /// The coordinates other than `j` that move monotonically from `a` to `b`, best first, each
    /// with whether [`Self::along`] would take it (at least a quarter of the fastest speed);
    /// none next to a pole, where the coordinate is fixed. Slow ones are listed too: one just
    /// under a quarter of the fastest one's speed is the one to graph over where the fastest
    /// turns.
    pub(super) fn other_alongs(&self, a: &Node, b: &Node, j: usize) -> Vec<(usize, bool)> {
        if self.pole_along(a, b).is_some() {
            return Vec::new();
        }
        let top = (0..4)
            .map(|i| a.t[i].abs() / self.scales[i])
            .fold(0.0, f64::max);
        let mut ranked: Vec<(usize, f64)> = (0..4)
            .filter(|&i| i != j)
            .filter_map(|i| self.along_score(a, b, i).map(|s| (i, s)))
            .collect();
        ranked.sort_by(|x, y| y.1.total_cmp(&x.1));
        ranked
            .into_iter()
            .map(|(i, s)| (i, s >= 0.25 * top))
            .collect()
    }

    /// The along coordinate for a link from `a` to `b`: monotone between them with both
    /// velocities agreeing, the largest scaled speed (on the costlier patch, see
    /// [`Self::costly_side`], if that is at least half of it); the previous link's if nearly as
    /// good.
    pub(super) fn along(&self, a: &Node, b: &Node) -> Option<usize> {
        if let Some(j) = self.pole_along(a, b) {
            return Some(j);
        }
        let score = |i: usize| self.along_score(a, b, i);
        let top = (0..4)
            .map(|i| a.t[i].abs() / self.scales[i])
            .fold(0.0, f64::max);
        let best = (0..4)
            .filter_map(|i| score(i).map(|s| (i, s)))
            .max_by(|x, y| x.1.total_cmp(&y.1))?;
        if best.1 < 0.25 * top {
            return None;
        }
        // On the costlier patch an along coordinate is an affine series, which makes its
        // evaluation along the predictor several times cheaper (Horner's rule puts the affine
        // argument inside): take the best coordinate there if it is at least half as fast.
        if let Some(side) = self.costly_side {
            let on_side = (side..side + 2)
                .filter_map(|i| score(i).map(|s| (i, s)))
                .max_by(|x, y| x.1.total_cmp(&y.1));
            if let Some((i, s)) = on_side.filter(|(_, s)| *s >= 0.5 * best.1) {
                let prev = self.links.last().map(|l| l.proof.pred.along);
                return Some(match prev {
                    Some(k) if k / 2 == side / 2 && score(k).is_some_and(|v| v >= 0.9 * s) => k,
                    _ => i,
                });
            }
        }
        if let Some(prev) = self.links.last().map(|l| l.proof.pred.along) {
            if score(prev).is_some_and(|s| s >= 0.9 * best.1) {
                return Some(prev);
            }
        }
        Some(best.0)
    }

    /// The narrowest of `link` and the same link graphed over each other coordinate that
    /// [`Self::along`] would take, for a link about to be kept although wider than the
    /// tolerance: a halving can switch the along coordinate (two nearly equal speeds), and a
    /// short link over the other one was then kept at twice the width of its parent (seed
    /// 8 700 191 of the quadric oracle: 2.0e-9 where the parent had 9.4e-10). Slow coordinates
    /// are tried too: the link is kept anyway, and over a slow one it can be the narrowest
    /// (seed 8 700 246: 6.0e-10 over `σ` at a quarter of the top speed, 1.3e-9 over `t`).
    pub(super) fn narrowest_over_others(
        &self,
        a: &Node,
        b: &Node,
        must_end: Option<&[Interval; 4]>,
        link: Link,
    ) -> Link {
        let lean = [&self.lean[0], &self.lean[1]];
        let exact = self.precise_at(&a.x);
        let others = self.other_alongs(a, b, link.proof.pred.along);
        let ends = (a, b, must_end);
        self.narrowest_over(lean, ends, exact, others, Some(link), |_| false)
            .unwrap_or(link)
    }

    /// The narrowest of `best` and the link from `a` to `b` graphed over each coordinate of
    /// `candidates` (with whether it is fast), on the exact residual if `exact`, in order
    /// until `done` holds of the narrowest so far.
    fn narrowest_over(
        &self,
        lean: [&LeanPatch<'a>; 2],
        (a, b, must_end): (&Node, &Node, Option<&[Interval; 4]>),
        exact: bool,
        candidates: impl IntoIterator<Item = (usize, bool)>,
        mut best: Option<Link>,
        done: impl Fn(&Option<Link>) -> bool,
    ) -> Option<Link> {
        for (k, fast) in candidates {
            if let Some(mut e) = self.link_along(lean, k, a, b, must_end, exact) {
                if best.as_ref().is_none_or(|b| e.radius_xyz < b.radius_xyz) {
                    e.slow = !fast;
                    best = Some(e);
                }
            }
            if done(&best) {
                break;
            }
        }
        best
    }

    /// [`Self::try_link`] on the forms `lean`.
    ///
    /// On nearly tangent surfaces a link wider than the aim (or failing) is tried again on the
    /// exact residual, then graphed over each other acceptable coordinate (on the exact
    /// residual), and the narrowest proof kept. Near a singular point (the cylinders' nodes)
    /// the width is the conditioning's whatever the form: proving every link there twice, the
    /// second form centred at the link's start, cost a sixth more links and 1.6 times the
    /// chain's time, so the retries are only for links that need them. The other coordinates
    /// serve where the fastest one is about to turn (the vertex of a curve that turns within
    /// 1e-7 on nearly tangent surfaces): graphed over it the curve has a branch point just
    /// past the link, and the tube there stayed at 1.5e-9 however short the link; graphed
    /// over the coordinate that keeps moving, 1e-14.
    pub(super) fn link_on(
        &self,
        lean: [&LeanPatch<'a>; 2],
        a: &Node,
        b: &Node,
        must_end: Option<&[Interval; 4]>,
    ) -> Option<Link> {
        let j = self.along(a, b)?;
        let aim = 0.5 * self.opts.required_tolerance;
        let best = self.link_along(lean, j, a, b, must_end, false);
        let wide = |l: &Option<Link>| l.as_ref().is_none_or(|l| l.radius_xyz > aim);
        if !wide(&best) || !self.precise_at(&a.x) {
            return best;
        }
        let retries = std::iter::once((j, true)).chain(self.other_alongs(a, b, j));
        self.narrowest_over(lean, (a, b, must_end), true, retries, best, |l| !wide(l))
    }
}
