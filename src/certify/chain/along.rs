//! The along coordinate of a link: the parameter a link's curve is graphed over (see
//! `segment.rs`), chosen by speed and monotonicity between the link's ends, and the others
//! to try where it turns.

use super::walker::{Node, Walker};

impl Walker<'_> {
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
}
