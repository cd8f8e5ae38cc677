//! The two patch enclosures the contact cover evaluates thousands of times, without the work
//! that does not depend on the box.
//!
//! [`CoverPatch::enclose`] is [`RationalBezierPatch::enclose`] (naive evaluation ∩ hull of the
//! sub-patch net) and [`CoverPatch::scaled_partials_centred`] is
//! [`RationalBezierPatch::scaled_partials_centred`], operation for operation in the same order,
//! so their intervals are the same bit for bit (tested); only what the patch's own functions
//! redo on every call is done once or not at all: the forward differences of the net are
//! computed once per patch, and the de Casteljau restriction ([`restrict_curve`], the one the
//! patch uses) works in buffers kept across calls instead of allocating per column.

use crate::geometry::bernstein::binomial;
use crate::geometry::enclosure::{hull_of_net, restrict_curve, RestrictBuffers};
use crate::geometry::RationalBezierPatch;
use crate::numeric::scalar::point;
use inari::Interval;

/// Largest degree handled in the fixed buffers; higher degrees use the patch's own functions.
const MAX_DEGREE: usize = 15;

/// A homogeneous control point `(w·x, w·y, w·z, w)`.
pub(crate) type Net4 = [Interval; 4];

/// The normalised parameter `(x − lo)/(hi − lo)`, as the patch computes it.
fn normalised(x: f64, [lo, hi]: [f64; 2]) -> Interval {
    (point(x) - point(lo)) / (point(hi) - point(lo))
}

/// Reusable buffers of [`CoverPatch::enclose_with`] (no allocation per enclosure).
#[derive(Debug, Default)]
pub(crate) struct Scratch {
    /// The de Casteljau restriction's buffers.
    restrict: RestrictBuffers,
    column: Vec<Net4>,
    restricted: Vec<Net4>,
    out: Vec<Net4>,
}

/// A patch with the box-independent parts of its cover enclosures prepared.
#[derive(Debug, Clone)]
pub(crate) struct CoverPatch<'a> {
    patch: &'a RationalBezierPatch,
    /// `Δₛᵏ Δᵣˡ` of the homogeneous net at `(i, j)`, index `((k·(n+1) + l)·(m+1) + i)·(n+1) + j`
    /// (empty above [`MAX_DEGREE`]).
    diffs: Vec<Net4>,
}

impl<'a> CoverPatch<'a> {
    /// The patch with its forward differences.
    pub(crate) fn new(patch: &'a RationalBezierPatch) -> Self {
        let [m, n] = patch.degree();
        let mut diffs = Vec::new();
        if m <= MAX_DEGREE && n <= MAX_DEGREE {
            let net = patch.homogeneous();
            let z = point(0.0);
            diffs = vec![[z; 4]; (m + 1) * (n + 1) * (m + 1) * (n + 1)];
            for k in 0..=m {
                for l in 0..=n {
                    for i in 0..=m - k {
                        for j in 0..=n - l {
                            let mut out = [z; 4];
                            for a in 0..=k {
                                for b in 0..=l {
                                    let c = binomial(k, a) * binomial(l, b);
                                    let sign = if (k - a + l - b).is_multiple_of(2) {
                                        c
                                    } else {
                                        -c
                                    };
                                    let p = net[(i + a) * (n + 1) + j + b];
                                    let f = point(sign);
                                    for x in 0..4 {
                                        out[x] += f * p[x];
                                    }
                                }
                            }
                            diffs[((k * (n + 1) + l) * (m + 1) + i) * (n + 1) + j] = out;
                        }
                    }
                }
            }
        }
        CoverPatch { patch, diffs }
    }

    /// The patch.
    pub(crate) fn patch(&self) -> &'a RationalBezierPatch {
        self.patch
    }

    /// [`RationalBezierPatch::enclose`], bit for bit.
    pub(crate) fn enclose(&self, u: Interval, v: Interval) -> [Interval; 3] {
        self.enclose_with(u, v, &mut Scratch::default())
    }

    /// [`enclose`](Self::enclose) with reusable buffers.
    pub(crate) fn enclose_with(&self, u: Interval, v: Interval, s: &mut Scratch) -> [Interval; 3] {
        if self.diffs.is_empty() || u.is_empty() || v.is_empty() {
            return self.patch.enclose(u, v);
        }
        let columns = self.columns(u, s);
        self.enclose_rows(&columns, u, v, s)
    }

    /// The first half of the sub-patch net over `u × v`: every u-column restricted to `u` (it
    /// does not depend on `v`, so boxes that differ only in `v` share it). Empty where the
    /// patch's own functions are used.
    pub(crate) fn columns(&self, u: Interval, s: &mut Scratch) -> Vec<Net4> {
        let [m, n] = self.patch.degree();
        if self.diffs.is_empty() || u.is_empty() {
            return Vec::new();
        }
        let d = self.patch.domain();
        let (ua, ub) = (normalised(u.inf(), d.u), normalised(u.sup(), d.u));
        let net = self.patch.homogeneous();
        let z = [point(0.0); 4];
        let mut sub = vec![z; net.len()];
        s.restricted.clear();
        s.restricted.resize(m.max(n) + 1, z);
        for j in 0..=n {
            s.column.clear();
            s.column.extend((0..=m).map(|i| net[i * (n + 1) + j]));
            restrict_curve(&s.column, ua, ub, &mut s.restrict, &mut s.restricted);
            for i in 0..=m {
                sub[i * (n + 1) + j] = s.restricted[i];
            }
        }
        sub
    }

    /// [`enclose`](Self::enclose) over `u × v` from the [`columns`](Self::columns) of `u`.
    pub(crate) fn enclose_rows(
        &self,
        columns: &[Net4],
        u: Interval,
        v: Interval,
        s: &mut Scratch,
    ) -> [Interval; 3] {
        let [m, n] = self.patch.degree();
        if columns.is_empty() || u.is_empty() || v.is_empty() {
            return self.patch.enclose(u, v);
        }
        let naive = self.patch.naive_bound(u, v);
        let d = self.patch.domain();
        let (va, vb) = (normalised(v.inf(), d.v), normalised(v.sup(), d.v));
        let z = [point(0.0); 4];
        s.restricted.clear();
        s.restricted.resize(m.max(n) + 1, z);
        s.out.clear();
        for i in 0..=m {
            let row = &columns[i * (n + 1)..(i + 1) * (n + 1)];
            restrict_curve(row, va, vb, &mut s.restrict, &mut s.restricted);
            s.out.extend_from_slice(&s.restricted[..=n]);
        }
        match hull_of_net(&s.out) {
            Some(hull) => {
                let mut enc = naive;
                for c in 0..3 {
                    let both = naive[c].intersection(hull[c]);
                    if !both.is_empty() {
                        enc[c] = both;
                    }
                }
                enc
            }
            None => naive,
        }
    }

    /// [`RationalBezierPatch::scaled_partials_centred`] in intervals, bit for bit (the same code,
    /// with the forward differences computed once per patch).
    pub(crate) fn scaled_partials_centred(
        &self,
        u: Interval,
        v: Interval,
        cu: Interval,
        cv: Interval,
    ) -> ([Interval; 3], [Interval; 3], Interval) {
        if self.diffs.is_empty() {
            return self.patch.scaled_partials_centred(u, v, cu, cv);
        }
        let [m, n] = self.patch.degree();
        self.patch
            .scaled_partials_centred_by(u, v, cu, cv, |i, j, k, l| {
                self.diffs[((k * (n + 1) + l) * (m + 1) + i) * (n + 1) + j]
            })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::numeric::scalar::interval;

    #[test]
    fn cover_enclosures_are_the_patch_ones_bit_for_bit() {
        for weights in [false, true] {
            let p = crate::pair::fixtures::wavy_patch(weights);
            let c = CoverPatch::new(&p);
            for k in 0..60 {
                let s = k as f64;
                let u0 = -1.0 + 3.0 * ((s * 0.37).fract());
                let v0 = 0.5 + ((s * 0.61).fract());
                let (wu, wv) = (0.3 / (1.0 + s), 0.2 / (1.0 + 0.5 * s));
                let u = interval(u0, (u0 + wu).min(2.0)).unwrap();
                let v = interval(v0, (v0 + wv).min(1.5)).unwrap();
                assert_eq!(c.enclose(u, v), p.enclose(u, v), "{u:?} {v:?}");
                let (cu, cv) = (point(u.mid()), point(v.mid()));
                assert_eq!(
                    c.scaled_partials_centred(u, v, cu, cv),
                    p.scaled_partials_centred(u, v, cu, cv),
                    "{u:?} {v:?}"
                );
            }
            // Degenerate and whole-domain ranges.
            let whole = (interval(-1.0, 2.0).unwrap(), interval(0.5, 1.5).unwrap());
            assert_eq!(c.enclose(whole.0, whole.1), p.enclose(whole.0, whole.1));
            let pt = (point(0.25), point(0.75));
            assert_eq!(c.enclose(pt.0, pt.1), p.enclose(pt.0, pt.1));
        }
    }
}
