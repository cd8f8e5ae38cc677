//! Recursive midpoint subdivision of a patch's interval control net.
//!
//! Search algorithms descend a tree of sub-patches; splitting a parent's net at its midpoint is
//! far cheaper than restricting the original net to every box from scratch. The split is done
//! in interval arithmetic on the homogeneous net, so each child's net encloses the exact net of
//! its half, and the two halves together cover the parent: a bound computed from a child net is
//! as rigorous as one from [`RationalBezierPatch::enclose`].

use crate::geometry::enclosure::hull_of_net;
use crate::geometry::RationalBezierPatch;
use crate::numeric::scalar::point;
use inari::Interval;

/// A rectangular piece of a patch (or of one of its boundary curves): its parameter ranges and
/// an interval homogeneous control net enclosing the exact one.
#[derive(Debug, Clone, PartialEq)]
pub struct SubPatch {
    /// The piece's `u` range in the patch's declared parameters (approximate at the ulp level:
    /// the net, not these numbers, carries the rigour).
    pub u: [f64; 2],
    /// The piece's `v` range.
    pub v: [f64; 2],
    degree: [usize; 2],
    net: Vec<[Interval; 4]>,
    bounds: [Interval; 3],
}

impl SubPatch {
    /// The whole patch.
    pub fn whole(patch: &RationalBezierPatch) -> Self {
        let d = patch.domain();
        SubPatch::new(d.u, d.v, patch.degree(), patch.homogeneous().to_vec())
    }

    /// One of the four boundary curves, as a piece of degree 0 in the fixed direction:
    /// `fixed_index` 0 holds `u` at its lower (`upper = false`) or upper end, 1 holds `v`.
    pub fn boundary(patch: &RationalBezierPatch, fixed_index: usize, upper: bool) -> Self {
        let [m, n] = patch.degree();
        let d = patch.domain();
        let net = patch.homogeneous();
        if fixed_index == 0 {
            let i = if upper { m } else { 0 };
            let edge = (0..=n).map(|j| net[i * (n + 1) + j]).collect();
            SubPatch::new([d.u[usize::from(upper)]; 2], d.v, [0, n], edge)
        } else {
            let j = if upper { n } else { 0 };
            let edge = (0..=m).map(|i| net[i * (n + 1) + j]).collect();
            SubPatch::new(d.u, [d.v[usize::from(upper)]; 2], [m, 0], edge)
        }
    }

    fn new(u: [f64; 2], v: [f64; 2], degree: [usize; 2], net: Vec<[Interval; 4]>) -> Self {
        let bounds = hull_of_net(&net).unwrap_or([Interval::ENTIRE; 3]);
        SubPatch {
            u,
            v,
            degree,
            net,
            bounds,
        }
    }

    /// Degrees `(m, n)` (0 in a fixed direction of a boundary curve).
    pub fn degree(&self) -> [usize; 2] {
        self.degree
    }

    /// A rigorous bounding box of the piece (convex hull of its projected net); the whole space
    /// if some weight is not provably positive.
    pub fn bounds(&self) -> [Interval; 3] {
        self.bounds
    }

    /// Splits at the parameter midpoint in direction `dir` (0 = u, 1 = v) into two halves.
    /// A direction of degree 0 cannot be split; the piece is returned twice then.
    pub fn split(&self, dir: usize) -> [SubPatch; 2] {
        let [m, n] = self.degree;
        if self.degree[dir] == 0 {
            return [self.clone(), self.clone()];
        }
        let (mut lo, mut hi) = (self.net.clone(), self.net.clone());
        // Index of control point k along the split direction, in line `l` across it.
        let (count, lines) = if dir == 0 {
            (m + 1, n + 1)
        } else {
            (n + 1, m + 1)
        };
        let idx = |k: usize, l: usize| {
            if dir == 0 {
                k * (n + 1) + l
            } else {
                l * (n + 1) + k
            }
        };
        let mut work = vec![[point(0.0); 4]; count];
        for l in 0..lines {
            for (k, w) in work.iter_mut().enumerate() {
                *w = self.net[idx(k, l)];
            }
            // de Casteljau at 1/2: the left half takes the first entry of every level, the
            // right half the last.
            lo[idx(0, l)] = work[0];
            hi[idx(count - 1, l)] = work[count - 1];
            for level in 1..count {
                for k in 0..count - level {
                    let next = work[k + 1];
                    for (w, n) in work[k].iter_mut().zip(next) {
                        *w = halve(*w + n);
                    }
                }
                lo[idx(level, l)] = work[0];
                hi[idx(count - 1 - level, l)] = work[count - 1 - level];
            }
        }
        let a = self.range(dir);
        let mid = 0.5 * (a[0] + a[1]);
        if dir == 0 {
            [
                SubPatch::new([a[0], mid], self.v, self.degree, lo),
                SubPatch::new([mid, a[1]], self.v, self.degree, hi),
            ]
        } else {
            [
                SubPatch::new(self.u, [a[0], mid], self.degree, lo),
                SubPatch::new(self.u, [mid, a[1]], self.degree, hi),
            ]
        }
    }

    /// The range in direction `dir`.
    pub fn range(&self, dir: usize) -> [f64; 2] {
        if dir == 0 {
            self.u
        } else {
            self.v
        }
    }
}

/// `x / 2`, rigorously: halving each bound is exact in binary floating point unless it lands in
/// the subnormal range, where the interval product (rounded outward) is used instead.
fn halve(x: Interval) -> Interval {
    let (lo, hi) = (0.5 * x.inf(), 0.5 * x.sup());
    if lo.abs() >= f64::MIN_POSITIVE && hi.abs() >= f64::MIN_POSITIVE {
        if let Ok(h) = Interval::try_from((lo, hi)) {
            return h;
        }
    }
    x * point(0.5)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::{Domain, ParametricSurface};
    use crate::numeric::scalar::interval;

    fn wavy() -> RationalBezierPatch {
        let mut pts = Vec::new();
        for i in 0..4 {
            for j in 0..3 {
                let (x, y) = (i as f64 / 3.0, j as f64 / 2.0);
                pts.push([x, y, ((i * 7 + j * 3) % 5) as f64 * 0.3 - 0.5]);
            }
        }
        let w: Vec<f64> = (0..12).map(|k| 1.0 + 0.1 * (k % 3) as f64).collect();
        RationalBezierPatch::from_f64_points(
            [3, 2],
            &pts,
            Some(&w),
            Domain::new(-1.0, 2.0, 0.5, 1.5),
        )
        .unwrap()
    }

    #[test]
    fn split_pieces_bound_their_part_of_the_patch() {
        let patch = wavy();
        let mut pieces = vec![SubPatch::whole(&patch)];
        for level in 0..6 {
            pieces = pieces.iter().flat_map(|s| s.split(level % 2)).collect();
        }
        assert_eq!(pieces.len(), 64);
        for piece in &pieces {
            let b = piece.bounds();
            for a in 0..=6 {
                for c in 0..=6 {
                    let u = piece.u[0] + (piece.u[1] - piece.u[0]) * a as f64 / 6.0;
                    let v = piece.v[0] + (piece.v[1] - piece.v[0]) * c as f64 / 6.0;
                    let p = patch.point(u, v);
                    for k in 0..3 {
                        assert!(b[k].inf() - 1e-12 <= p[k] && p[k] <= b[k].sup() + 1e-12);
                    }
                }
            }
            // About as tight as restricting the original net directly.
            let direct = patch.enclose(
                interval(piece.u[0], piece.u[1]).unwrap(),
                interval(piece.v[0], piece.v[1]).unwrap(),
            );
            for k in 0..3 {
                assert!(b[k].wid() <= 1.5 * direct[k].wid() + 1e-12);
            }
        }
    }

    #[test]
    fn halving_is_exact_or_outward() {
        let x = crate::numeric::scalar::interval(-3.0, 1e-310).unwrap();
        let h = halve(x);
        assert!(h.inf() <= -1.5 && h.sup() >= 0.5e-310);
        assert_eq!(
            halve(crate::numeric::scalar::interval(2.0, 6.0).unwrap()),
            crate::numeric::scalar::interval(1.0, 3.0).unwrap()
        );
    }

    #[test]
    fn boundary_curves_are_the_patch_edges() {
        let patch = wavy();
        let d = patch.domain();
        let mut edge = SubPatch::boundary(&patch, 1, true);
        for _ in 0..4 {
            edge = edge.split(0)[1].clone();
        }
        let b = edge.bounds();
        let p = patch.point(edge.u[1], d.v[1]);
        for k in 0..3 {
            assert!(b[k].inf() - 1e-12 <= p[k] && p[k] <= b[k].sup() + 1e-12);
        }
        assert_eq!(edge.split(1)[0], edge);
    }
}
