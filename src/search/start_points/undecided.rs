//! Regions the search could not decide, and their merging.

/// A pair of parameter boxes where the search could not decide whether (further) intersection
/// components exist. The boxes are rounded outward: they contain the region examined.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct UndecidedRegion {
    /// `[[σ0, σ1], [t0, t1]]` on P.
    pub p: [[f64; 2]; 2],
    /// `[[u0, u1], [v0, v1]]` on Q.
    pub q: [[f64; 2]; 2],
}

impl UndecidedRegion {
    /// Whether the two closed regions meet (in all four parameters).
    fn meets(&self, other: &Self) -> bool {
        let overlap = |a: [f64; 2], b: [f64; 2]| a[0] <= b[1] && b[0] <= a[1];
        (0..2).all(|k| overlap(self.p[k], other.p[k]) && overlap(self.q[k], other.q[k]))
    }

    /// The smallest region holding both.
    fn hull(&self, other: &Self) -> Self {
        let hull = |a: [f64; 2], b: [f64; 2]| [a[0].min(b[0]), a[1].max(b[1])];
        Self {
            p: std::array::from_fn(|k| hull(self.p[k], other.p[k])),
            q: std::array::from_fn(|k| hull(self.q[k], other.q[k])),
        }
    }
}

/// Most regions merged (the merging is quadratic in their number; more are kept as they are).
const MAX_MERGED: usize = 1024;

/// The regions with every two that meet replaced by their hull, until none meet: the boundary
/// searches' leaves that failed round one point (a node on a domain side fails the eight leaves
/// round it, on each side through it) are reported as one region. The hulls hold every region
/// given.
pub(super) fn merged(mut regions: Vec<UndecidedRegion>) -> Vec<UndecidedRegion> {
    if regions.len() > MAX_MERGED {
        return regions;
    }
    let mut out: Vec<UndecidedRegion> = Vec::with_capacity(regions.len());
    while let Some(mut r) = regions.pop() {
        // Absorb every kept region that meets the growing hull, until none does.
        while let Some(k) = out.iter().position(|o| o.meets(&r)) {
            r = r.hull(&out.swap_remove(k));
        }
        out.push(r);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn region(s: f64, t: f64, w: f64) -> UndecidedRegion {
        UndecidedRegion {
            p: [[s, s + w], [t, t + w]],
            q: [[0.0, w], [0.0, w]],
        }
    }

    #[test]
    fn touching_regions_merge_and_separate_ones_stay() {
        // Four round the origin (touching at corners and sides), one far away.
        let regions = vec![
            region(-1.0, -1.0, 1.0),
            region(0.0, -1.0, 1.0),
            region(-1.0, 0.0, 1.0),
            region(0.0, 0.0, 1.0),
            region(5.0, 5.0, 1.0),
        ];
        let out = merged(regions.clone());
        assert_eq!(out.len(), 2);
        let big = out.iter().find(|r| r.p[0][0] == -1.0).unwrap();
        assert_eq!(big.p, [[-1.0, 1.0], [-1.0, 1.0]]);
        for r in &regions {
            assert!(out.iter().any(|o| (0..2).all(|k| o.p[k][0] <= r.p[k][0]
                && r.p[k][1] <= o.p[k][1]
                && o.q[k][0] <= r.q[k][0]
                && r.q[k][1] <= o.q[k][1])));
        }
    }

    #[test]
    fn regions_apart_in_q_do_not_merge() {
        let a = region(0.0, 0.0, 1.0);
        let mut b = region(0.5, 0.5, 1.0);
        b.q = [[3.0, 4.0], [0.0, 1.0]];
        assert_eq!(merged(vec![a, b]).len(), 2);
    }

    #[test]
    fn a_chain_of_regions_merges_whatever_the_order() {
        // A chain merged from its middle first: the hull must absorb both ends.
        let regions = vec![
            region(0.0, 0.0, 1.0),
            region(2.0, 0.0, 1.0),
            region(1.0, 0.0, 1.0),
        ];
        assert_eq!(merged(regions).len(), 1);
    }
}
