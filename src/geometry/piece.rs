//! Pieces of a patch for the start-point search: an interval Bernstein net over an exact
//! parameter box, with rigorous bounds of the piece and of its partial derivatives.
//!
//! The box is kept in the patch's *normalised* parameters `(s, r) ∈ [0, 1]²` and only ever
//! halved, so its ends are dyadic numbers, exact in `f64`, and the net (split by de Casteljau at
//! 1/2 in interval arithmetic) encloses the exact sub-net over exactly that box. Declared
//! parameters are derived from it with outward rounding when needed.
//!
//! Partial derivatives are bounded from the net, optionally over a box *widened* by a fraction
//! `δ` of its width on every side (an extrapolation): for a polynomial `g` of degree `k` with
//! Bernstein coefficients `c_i` on `[0, 1]` and any `m`, `g(x) − m = Σ (c_i − m) B_i(x)` and
//! `Σ |B_i(x)| = (1 + 2δ)^k` at worst for `x ∈ [−δ, 1 + δ]`, so
//! `|g(x) − m| ≤ max |c_i − m| · (1 + 2δ)^k` there (per direction for tensor products).

use crate::geometry::enclosure::{hull_of_net, restrict_net};
use crate::geometry::{Domain, RationalBezierPatch};
use crate::numeric::rounding::{average, dot_point, sub};
use crate::numeric::scalar::{interval, point, Scalar};
use inari::Interval;

/// A rectangular piece of a patch, or of one of its boundary curves / faces (degree 0 in the
/// fixed direction).
#[derive(Debug, Clone, PartialEq)]
pub struct Piece {
    /// Normalised `s` range (exact, dyadic).
    pub s: [f64; 2],
    /// Normalised `r` range (exact, dyadic).
    pub r: [f64; 2],
    degree: [usize; 2],
    net: Vec<[Interval; 4]>,
    bounds: [Interval; 3],
    polynomial: bool,
}

impl Piece {
    /// The whole patch.
    pub fn whole(patch: &RationalBezierPatch) -> Self {
        let polynomial = patch
            .homogeneous()
            .iter()
            .all(|h| h[3].inf() == 1.0 && h[3].sup() == 1.0);
        Piece::new(
            [0.0, 1.0],
            [0.0, 1.0],
            patch.degree(),
            patch.homogeneous().to_vec(),
            polynomial,
        )
    }

    /// A piece with the given net (index `i*(n+1)+j`, homogeneous) over the normalised box
    /// `s × r`; `polynomial` when every weight is exactly 1.
    pub(crate) fn new(
        s: [f64; 2],
        r: [f64; 2],
        degree: [usize; 2],
        net: Vec<[Interval; 4]>,
        polynomial: bool,
    ) -> Self {
        let bounds = hull_of_net(&net).unwrap_or([Interval::ENTIRE; 3]);
        Piece {
            s,
            r,
            degree,
            net,
            bounds,
            polynomial,
        }
    }

    /// The piece of `patch` over the normalised box `s × r` (sub-ranges of `[0, 1]`, e.g. the
    /// dyadic box around a singular point, not aligned with any halving), by blossoming in
    /// interval arithmetic (`restrict_net` in `enclosure.rs`): the net encloses the exact
    /// sub-net over exactly that box. `None` if a range is empty or leaves `[0, 1]`.
    pub fn over(patch: &RationalBezierPatch, s: [f64; 2], r: [f64; 2]) -> Option<Self> {
        let valid = |x: [f64; 2]| 0.0 <= x[0] && x[0] < x[1] && x[1] <= 1.0;
        if !(valid(s) && valid(r)) {
            return None;
        }
        let whole = Piece::whole(patch);
        let net = restrict_net(&whole.net, whole.degree, s.map(point), r.map(point));
        Some(Piece::new(s, r, whole.degree, net, whole.polynomial))
    }

    /// A rigorous enclosure of `d·x` over the piece, `x` its points: the hull of `d·X` over the
    /// Cartesian control points `X` (a rational Bézier piece with positive weights lies in their
    /// convex hull). `None` if a weight is not provably positive.
    pub fn range_along(&self, d: &[f64; 3]) -> Option<Interval> {
        let d = d.map(point);
        let mut out: Option<Interval> = None;
        for h in &self.net {
            if h[3].is_empty() || h[3].inf() <= 0.0 {
                return None;
            }
            let x = d[0] * h[0] + d[1] * h[1] + d[2] * h[2];
            let x = if self.polynomial { x } else { x / h[3] };
            out = Some(out.map_or(x, |o| o.convex_hull(x)));
        }
        out
    }

    /// A direction across the piece (`f64`, from the chords between the corners of its control
    /// net; any direction makes [`Piece::range_along`] rigorous): the normal of a flat piece.
    /// `None` for a face or a degenerate net.
    pub fn corner_normal(&self) -> Option<[f64; 3]> {
        let [m, n] = self.degree;
        if m == 0 || n == 0 {
            return None;
        }
        let at = |i: usize, j: usize| {
            let h = self.net[i * (n + 1) + j];
            [0, 1, 2].map(|k| h[k].mid() / h[3].mid())
        };
        let (x00, x10, x01, x11) = (at(0, 0), at(m, 0), at(0, n), at(m, n));
        let a: [f64; 3] = std::array::from_fn(|k| x11[k] - x00[k]);
        let b: [f64; 3] = std::array::from_fn(|k| x10[k] - x01[k]);
        let c = [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ];
        let len = c.iter().map(|v| v * v).sum::<f64>().sqrt();
        (len > 0.0 && len.is_finite()).then(|| c.map(|v| v / len))
    }

    /// The homogeneous interval net, index `i*(n+1)+j`.
    pub(crate) fn net(&self) -> &[[Interval; 4]] {
        &self.net
    }

    /// The sides of the patch (`u = u0`, `u = u1`, `v = v0`, `v = v1`) this piece touches.
    pub(crate) fn touches(&self) -> [bool; 4] {
        [
            self.s[0] == 0.0,
            self.s[1] == 1.0,
            self.r[0] == 0.0,
            self.r[1] == 1.0,
        ]
    }

    /// Degrees (0 in the fixed direction of a face).
    pub fn degree(&self) -> [usize; 2] {
        self.degree
    }

    /// A rigorous bounding box of the piece (hull of its projected net).
    pub fn bounds(&self) -> [Interval; 3] {
        self.bounds
    }

    /// The face of the piece where direction `fixed` (0 = s, 1 = r) is at its lower or upper
    /// end: a piece of degree 0 in that direction whose net is the exact boundary row.
    pub fn face(&self, fixed: usize, upper: bool) -> Piece {
        let [m, n] = self.degree;
        if fixed == 0 {
            let i = if upper { m } else { 0 };
            let row = (0..=n).map(|j| self.net[i * (n + 1) + j]).collect();
            let x = self.s[usize::from(upper)];
            Piece::new([x, x], self.r, [0, n], row, self.polynomial)
        } else {
            let j = if upper { n } else { 0 };
            let col = (0..=m).map(|i| self.net[i * (n + 1) + j]).collect();
            let x = self.r[usize::from(upper)];
            Piece::new(self.s, [x, x], [m, 0], col, self.polynomial)
        }
    }

    /// The direction to split: the one of larger degree-weighted extent, never one of degree 0.
    pub fn split_direction(&self) -> usize {
        let [m, n] = self.degree;
        if m == 0 {
            return 1;
        }
        if n == 0 {
            return 0;
        }
        let (ds, dr) = (self.s[1] - self.s[0], self.r[1] - self.r[0]);
        usize::from(dr * (n as f64) > ds * (m as f64))
    }

    /// The two halves in direction `dir` (de Casteljau at 1/2, interval arithmetic).
    pub fn split(&self, dir: usize) -> [Piece; 2] {
        let [m, n] = self.degree;
        if self.degree[dir] == 0 {
            return [self.clone(), self.clone()];
        }
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
        let coords = if self.polynomial { 3 } else { 4 };
        let (mut lo, mut hi) = (self.net.clone(), self.net.clone());
        let mut work = vec![[point(0.0); 4]; count];
        for l in 0..lines {
            for (k, w) in work.iter_mut().enumerate() {
                *w = self.net[idx(k, l)];
            }
            lo[idx(0, l)] = work[0];
            hi[idx(count - 1, l)] = work[count - 1];
            for level in 1..count {
                for k in 0..count - level {
                    // A polynomial piece's weights stay exactly 1: only x, y, z are averaged.
                    // (The next point by reference: copied by value, it went through
                    // overlapping stack stores, a store-forwarding stall per step.)
                    let (here, next) = work.split_at_mut(k + 1);
                    for (w, x) in here[k][..coords].iter_mut().zip(&next[0]) {
                        *w = average(*w, *x);
                    }
                }
                lo[idx(level, l)] = work[0];
                hi[idx(count - 1 - level, l)] = work[count - 1 - level];
            }
        }
        let halves = |x: [f64; 2]| {
            let c = 0.5 * (x[0] + x[1]);
            ([x[0], c], [c, x[1]])
        };
        let poly = self.polynomial;
        if dir == 0 {
            let (a, b) = halves(self.s);
            [
                Piece::new(a, self.r, self.degree, lo, poly),
                Piece::new(b, self.r, self.degree, hi, poly),
            ]
        } else {
            let (a, b) = halves(self.r);
            [
                Piece::new(self.s, a, self.degree, lo, poly),
                Piece::new(self.s, b, self.degree, hi, poly),
            ]
        }
    }

    /// The point of the patch at the centre of the piece's box, enclosed (de Casteljau at 1/2
    /// on the net, in interval arithmetic), with the centre's declared parameters (rounded
    /// outward).
    pub fn centre(&self, d: &Domain) -> ([Interval; 2], [Interval; 3]) {
        let [m, n] = self.degree;
        let coords = if self.polynomial { 3 } else { 4 };
        let collapse = |pts: &mut Vec<[Interval; 4]>| {
            while pts.len() > 1 {
                for k in 0..pts.len() - 1 {
                    // The next point by reference, as in `split`; a polynomial piece's
                    // weights stay 1.
                    let (here, next) = pts.split_at_mut(k + 1);
                    for (w, x) in here[k][..coords].iter_mut().zip(&next[0]) {
                        *w = average(*w, *x);
                    }
                }
                pts.pop();
            }
        };
        let mut row = Vec::with_capacity(n + 1);
        let mut column = Vec::with_capacity(m + 1);
        for j in 0..=n {
            column.clear();
            column.extend((0..=m).map(|i| self.net[i * (n + 1) + j]));
            collapse(&mut column);
            row.push(column[0]);
        }
        collapse(&mut row);
        let h = row[0];
        let p = if self.polynomial {
            [h[0], h[1], h[2]]
        } else {
            [h[0] / h[3], h[1] / h[3], h[2] / h[3]]
        };
        let at = |dom: [f64; 2], x: [f64; 2]| {
            let c = 0.5 * (x[0] + x[1]);
            point(dom[0]) + point(c) * (point(dom[1]) - point(dom[0]))
        };
        ([at(d.u, self.s), at(d.v, self.r)], p)
    }

    /// The declared parameter box `[u, v]`, rounded outward, after widening the normalised box
    /// by `grow` times its width on each side (not clipped to the domain).
    pub fn declared(&self, d: &Domain, grow: f64) -> [Interval; 2] {
        [
            declared_range(d.u, self.s, grow),
            declared_range(d.v, self.r, grow),
        ]
    }

    /// Rigorous enclosures of `R·S_u` and `R·S_v` (declared parameters, `R` the rows of
    /// `frame`) over the piece's box widened by `grow` times its width on each side; `None` for a
    /// direction of degree 0, and `None` overall if the weights are not provably positive there.
    /// The net is translated to `origin` first (partials do not change; it keeps the products
    /// `X·w_s` of a rational patch small).
    pub fn partials(
        &self,
        d: &Domain,
        frame: Option<&[[f64; 3]; 3]>,
        origin: &[f64; 3],
        grow: f64,
    ) -> Option<[Option<[Interval; 3]>; 2]> {
        let [m, n] = self.degree;
        let rotate = |x: [Interval; 3]| match frame {
            Some(r) => std::array::from_fn(|k| dot_point(&r[k], &x)),
            None => x,
        };
        // Σ|B| growth factors for degrees (a, b) under the widening.
        let factor = |a: usize, b: usize| {
            let g = point(1.0) + point(2.0) * point(grow);
            g.powi(a as i32) * g.powi(b as i32)
        };
        let widen3 = |h: [Interval; 3], f: Interval| h.map(|x| widen(x, f));
        // `deg / width` with width = (range₁ − range₀)·(dom₁ − dom₀) > 0.
        let scale = |deg: usize, range: [f64; 2], dom: [f64; 2]| {
            let width = (point(range[1]) - point(range[0])) * (point(dom[1]) - point(dom[0]));
            (width.inf() > 0.0).then(|| point(deg as f64) / width)
        };
        if self.polynomial {
            // S_s = m·Σ B ΔX: only the differences of the net matter (no translation needed).
            // The net is rotated first (R·ΔX ⊂ R·X₁ − R·X₀, one rotation per control point
            // rather than per difference).
            let net: Vec<[Interval; 3]> = self
                .net
                .iter()
                .map(|h| rotate([h[0], h[1], h[2]]))
                .collect();
            let diff = |a: usize, b: usize| -> [Interval; 3] {
                std::array::from_fn(|c| sub(net[b][c], net[a][c]))
            };
            let (mut hs, mut hr) = (Hull3::default(), Hull3::default());
            for i in 0..=m {
                for j in 0..=n {
                    let k = i * (n + 1) + j;
                    if i < m {
                        hs.add(&diff(k, k + n + 1));
                    }
                    if j < n {
                        hr.add(&diff(k, k + 1));
                    }
                }
            }
            let su = match (m > 0, hs.0, scale(m, self.s, d.u)) {
                (true, Some(h), Some(k)) => Some(widen3(h, factor(m - 1, n)).map(|x| x * k)),
                _ => None,
            };
            let sv = match (n > 0, hr.0, scale(n, self.r, d.v)) {
                (true, Some(h), Some(k)) => Some(widen3(h, factor(m, n - 1)).map(|x| x * k)),
                _ => None,
            };
            return Some([su, sv]);
        }
        let o = origin.map(point);
        let y: Vec<([Interval; 3], Interval)> = self
            .net
            .iter()
            .map(|h| {
                let w = if self.polynomial { point(1.0) } else { h[3] };
                let x: [Interval; 3] = std::array::from_fn(|c| h[c] - o[c] * w);
                (rotate(x), w)
            })
            .collect();
        let at = |i: usize, j: usize| y[i * (n + 1) + j];
        let (mut hx, mut hw) = (Hull3::default(), Hull1::default());
        let (mut hxs, mut hws) = (Hull3::default(), Hull1::default());
        let (mut hxr, mut hwr) = (Hull3::default(), Hull1::default());
        for i in 0..=m {
            for j in 0..=n {
                let (xij, wij) = at(i, j);
                hx.add(&xij);
                hw.add(wij);
                if i < m {
                    let (x1, w1) = at(i + 1, j);
                    hxs.add(&std::array::from_fn(|c| x1[c] - xij[c]));
                    hws.add(w1 - wij);
                }
                if j < n {
                    let (x1, w1) = at(i, j + 1);
                    hxr.add(&std::array::from_fn(|c| x1[c] - xij[c]));
                    hwr.add(w1 - wij);
                }
            }
        }
        let hx = widen3(hx.0?, factor(m, n));
        let hw = widen(hw.0?, factor(m, n));
        if !self.polynomial && (hw.inf() <= 0.0 || hw.inf().is_nan()) {
            return None;
        }
        let partial = |dx: Option<[Interval; 3]>,
                       dw: Option<Interval>,
                       deg: usize,
                       f: Interval,
                       range: [f64; 2],
                       dom: [f64; 2]| {
            let dx = widen3(dx?, f);
            let scale = scale(deg, range, dom)?;
            let dw = widen(dw?, f);
            let w2 = hw.sqr();
            Some(std::array::from_fn(|c| {
                (dx[c] * hw - hx[c] * dw) / w2 * scale
            }))
        };
        let su = if m > 0 {
            partial(hxs.0, hws.0, m, factor(m - 1, n), self.s, d.u)
        } else {
            None
        };
        let sv = if n > 0 {
            partial(hxr.0, hwr.0, n, factor(m, n - 1), self.r, d.v)
        } else {
            None
        };
        Some([su, sv])
    }
}

impl Piece {
    /// Enclosures of positive multiples of `n · ∂X/∂s` and `n · ∂X/∂r` on the piece, valid for
    /// every vector `n` of the interval box `n`: the sign of each, where it has one, is the
    /// sign of that component everywhere on the piece. `None` for a direction the piece is
    /// constant in, and for both when the weights are not proven positive.
    ///
    /// Tighter than the dot product of `n` with [`Piece::partials`]: `n` is applied to the
    /// control points before any hull is taken, so a partial that keeps one direction while its
    /// length varies with the weights (the rulings of a rational cylinder) has a component that
    /// is enclosed to rounding. With the homogeneous net `(Y, w)` translated to the piece's
    /// centre `c` (`Y − c·w`, which leaves `Y_d·w − Y·w_d` unchanged), `X_d = (Y_d·w − Y·w_d)/w²`
    /// and `n·(Y_d·w − Y·w_d) ∈ hull(Δ(n·Y))·hull(w) − hull(n·Y)·hull(Δw)`, where `Δ` takes the
    /// differences of the net along `d` (the derivative's net over the normalised box, up to
    /// the positive factor degree/width).
    pub(crate) fn partials_along(&self, n: &[Interval; 3]) -> [Option<Interval>; 2] {
        let [m, k] = self.degree;
        let c = self.bounds.map(|x| point(x.mid()));
        let scalar = |h: &[Interval; 4]| {
            let w = if self.polynomial { point(1.0) } else { h[3] };
            let y: [Interval; 3] = std::array::from_fn(|i| h[i] - c[i] * w);
            (n[0] * y[0] + n[1] * y[1] + n[2] * y[2], w)
        };
        let (mut ha, mut hw) = (Hull1::default(), Hull1::default());
        let mut hda = [Hull1::default(), Hull1::default()];
        let mut hdw = [Hull1::default(), Hull1::default()];
        // One row at a time: the differences along `r` within it, along `s` to the next row.
        let mut row: Vec<(Interval, Interval)> = self.net[..=k].iter().map(scalar).collect();
        for i in 0..=m {
            for j in 0..=k {
                let (a, w) = row[j];
                ha.add(a);
                hw.add(w);
                if j < k {
                    hda[1].add(row[j + 1].0 - a);
                    hdw[1].add(row[j + 1].1 - w);
                }
            }
            if i < m {
                for (j, x) in row.iter_mut().enumerate() {
                    let next = scalar(&self.net[(i + 1) * (k + 1) + j]);
                    hda[0].add(next.0 - x.0);
                    hdw[0].add(next.1 - x.1);
                    *x = next;
                }
            }
        }
        let (Some(ha), Some(hw)) = (ha.0, hw.0) else {
            return [None, None];
        };
        if !self.polynomial && (hw.inf() <= 0.0 || hw.inf().is_nan()) {
            return [None, None];
        }
        std::array::from_fn(|d| {
            let (da, dw) = (hda[d].0?, hdw[d].0?);
            let out = if self.polynomial {
                da
            } else {
                da * hw - ha * dw
            };
            (!out.is_empty()).then_some(out)
        })
    }
}

/// `x` widened about its midpoint: `mid ± rad·f` (outward); `x` itself when `f` is exactly 1.
fn widen(x: Interval, f: Interval) -> Interval {
    if f.inf() == 1.0 && f.sup() == 1.0 {
        return x;
    }
    let m = x.mid();
    let rad = (point(x.sup()) - point(m))
        .sup()
        .max((point(m) - point(x.inf())).sup());
    let r = (point(rad) * f).sup();
    point(m) + interval(-r, r).unwrap_or(Interval::ENTIRE)
}

/// `d0 + x·(d1 − d0)` over `x ∈ [s0 − g·w, s1 + g·w]`, `w = s1 − s0`, rounded outward.
pub(crate) fn declared_range(d: [f64; 2], s: [f64; 2], grow: f64) -> Interval {
    let w = point(s[1]) - point(s[0]);
    let lo = point(s[0]) - point(grow) * w;
    let hi = point(s[1]) + point(grow) * w;
    let (d0, dw) = (point(d[0]), point(d[1]) - point(d[0]));
    let a = d0 + lo * dw;
    let b = d0 + hi * dw;
    // Exact ends where nothing was rounded (the whole domain).
    let lo = if grow == 0.0 && s[0] == 0.0 {
        d[0]
    } else {
        a.inf()
    };
    let hi = if grow == 0.0 && s[1] == 1.0 {
        d[1]
    } else {
        b.sup()
    };
    interval(lo, hi).unwrap_or(Interval::ENTIRE)
}

#[derive(Default)]
struct Hull3(Option<[Interval; 3]>);

impl Hull3 {
    fn add(&mut self, x: &[Interval; 3]) {
        self.0 = Some(match self.0 {
            None => *x,
            Some(h) => std::array::from_fn(|c| h[c].convex_hull(x[c])),
        });
    }
}

#[derive(Default)]
struct Hull1(Option<Interval>);

impl Hull1 {
    fn add(&mut self, x: Interval) {
        self.0 = Some(match self.0 {
            None => x,
            Some(h) => h.convex_hull(x),
        });
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::ParametricSurface;

    fn wavy() -> RationalBezierPatch {
        let pts: Vec<[f64; 3]> = (0..12)
            .map(|k| {
                let (i, j) = ((k / 3) as f64, (k % 3) as f64);
                [i, j, 0.3 * ((k * 5) % 7) as f64 - 0.9]
            })
            .collect();
        let w: Vec<f64> = (0..12).map(|k| 1.0 + 0.15 * (k % 4) as f64).collect();
        RationalBezierPatch::from_f64_points(
            [3, 2],
            &pts,
            Some(&w),
            Domain::new(-1.0, 2.0, 0.5, 1.5),
        )
        .unwrap()
    }

    #[test]
    fn partials_along_have_the_sign_of_the_sampled_components() {
        // Pieces of a rational patch with weights from 0.2 to 3 (and of the polynomial one with
        // the same points), and directions n of all sorts: wherever an enclosure excludes 0,
        // n · ∂X/∂s (or ∂X/∂r) has its sign at every sample of the piece.
        let pts: Vec<[f64; 3]> = (0..12)
            .map(|k| {
                let (i, j) = ((k / 3) as f64, (k % 3) as f64);
                [
                    i + 0.2 * j,
                    j - 0.1 * i * i,
                    0.3 * ((k * 5) % 7) as f64 - 0.9,
                ]
            })
            .collect();
        let w: Vec<f64> = (0..12).map(|k| [0.2, 3.0, 1.0, 0.5][k % 4]).collect();
        let d = Domain::new(-1.0, 2.0, 0.5, 1.5);
        let rational = RationalBezierPatch::from_f64_points([3, 2], &pts, Some(&w), d).unwrap();
        let polynomial = RationalBezierPatch::from_f64_points([3, 2], &pts, None, d).unwrap();
        let mut decided = 0;
        for patch in [&rational, &polynomial] {
            let mut pieces = vec![Piece::whole(patch)];
            for level in 0..4 {
                let next: Vec<Piece> = pieces.iter().flat_map(|s| s.split(level % 2)).collect();
                pieces.extend(next);
            }
            for (k, piece) in pieces.iter().enumerate() {
                let [u, v] = piece.declared(&d, 0.0);
                let a = k as f64;
                let n = [a.sin(), (1.7 * a).cos(), 0.3 * (0.4 * a).sin()];
                let along = piece.partials_along(&n.map(point));
                for (dir, e) in along.iter().enumerate() {
                    let Some(e) = e.filter(|e| e.inf() > 0.0 || e.sup() < 0.0) else {
                        continue;
                    };
                    decided += 1;
                    for i in 0..49 {
                        let x = u.inf() + u.wid() * (i % 7) as f64 / 6.0;
                        let y = v.inf() + v.wid() * (i / 7) as f64 / 6.0;
                        let ds = patch.derivs(x, y);
                        let part = [ds.su, ds.sv][dir];
                        let c = n[0] * part.x + n[1] * part.y + n[2] * part.z;
                        assert!(c * e.inf().signum() > 0.0, "{c} against {e:?}");
                    }
                }
            }
        }
        assert!(decided > 40, "{decided}");
    }

    #[test]
    fn split_pieces_bound_their_part_of_the_patch() {
        let patch = wavy();
        let d = patch.domain();
        let mut pieces = vec![Piece::whole(&patch)];
        for level in 0..6 {
            pieces = pieces.iter().flat_map(|s| s.split(level % 2)).collect();
        }
        assert_eq!(pieces.len(), 64);
        for piece in &pieces {
            let b = piece.bounds();
            let [u, v] = piece.declared(&d, 0.0);
            for a in 0..=6 {
                for c in 0..=6 {
                    let x = u.inf() + (u.sup() - u.inf()) * a as f64 / 6.0;
                    let y = v.inf() + (v.sup() - v.inf()) * c as f64 / 6.0;
                    let p = patch.point(x, y);
                    for k in 0..3 {
                        assert!(b[k].inf() - 1e-12 <= p[k] && p[k] <= b[k].sup() + 1e-12);
                    }
                }
            }
            // About as tight as restricting the original net directly.
            let direct = patch.enclose(u, v);
            for k in 0..3 {
                assert!(b[k].wid() <= 1.5 * direct[k].wid() + 1e-12);
            }
        }
    }

    #[test]
    fn boundary_curves_are_the_patch_edges() {
        let patch = wavy();
        let d = patch.domain();
        let mut edge = Piece::whole(&patch).face(1, true);
        for _ in 0..4 {
            edge = edge.split(0)[1].clone();
        }
        let b = edge.bounds();
        let [u, _] = edge.declared(&d, 0.0);
        let p = patch.point(u.sup(), d.v[1]);
        for k in 0..3 {
            assert!(b[k].inf() - 1e-12 <= p[k] && p[k] <= b[k].sup() + 1e-12);
        }
        assert_eq!(edge.split(1)[0], edge);
    }

    #[test]
    fn pieces_bound_points_and_widened_partials() {
        let patch = wavy();
        let d = patch.domain();
        let mut piece = Piece::whole(&patch);
        for k in 0..5 {
            piece = piece.split(k % 2)[k % 2].clone();
        }
        let grow = 1.0 / 16.0;
        let [u, v] = piece.declared(&d, grow);
        let [su, sv] = piece.partials(&d, None, &[0.2, 0.3, 0.0], grow).unwrap();
        let (su, sv) = (su.unwrap(), sv.unwrap());
        let b = piece.bounds();
        let [u0, v0] = piece.declared(&d, 0.0);
        for a in 0..=6 {
            for c in 0..=6 {
                // Points of the widened box: partials enclosed.
                let x = u.inf() + (u.sup() - u.inf()) * a as f64 / 6.0;
                let y = v.inf() + (v.sup() - v.inf()) * c as f64 / 6.0;
                let dd = patch.derivs(x, y);
                for k in 0..3 {
                    assert!(su[k].inf() - 1e-12 <= dd.su[k] && dd.su[k] <= su[k].sup() + 1e-12);
                    assert!(sv[k].inf() - 1e-12 <= dd.sv[k] && dd.sv[k] <= sv[k].sup() + 1e-12);
                }
                // Points of the box itself: inside the bounds.
                let x = u0.inf() + (u0.sup() - u0.inf()) * a as f64 / 6.0;
                let y = v0.inf() + (v0.sup() - v0.inf()) * c as f64 / 6.0;
                let p = patch.point(x, y);
                for k in 0..3 {
                    assert!(b[k].inf() - 1e-12 <= p[k] && p[k] <= b[k].sup() + 1e-12);
                }
            }
        }
        // A face is the boundary curve: degree 0 across, no partial across.
        let face = piece.face(1, true);
        assert_eq!(face.degree(), [3, 0]);
        let [fu, fv] = face.partials(&d, None, &[0.0; 3], 0.0).unwrap();
        assert!(fu.is_some() && fv.is_none());
        let y = face.declared(&d, 0.0)[1];
        assert_eq!(y.inf(), y.sup());
    }

    #[test]
    fn range_along_holds_the_piece_and_is_thin_across_a_flat_one() {
        // The wavy rational patch: its points along several directions lie in the ranges of the
        // pieces that hold them.
        let p = wavy();
        let d = p.domain();
        let piece = Piece::over(&p, [0.25, 0.75], [0.125, 0.5]).unwrap();
        for dir in [[1.0, 0.0, 0.0], [0.6, -0.8, 0.0], [0.3, 0.4, -0.866]] {
            let range = piece.range_along(&dir).unwrap();
            for i in 0..=10 {
                for j in 0..=10 {
                    let (a, b) = (0.25 + 0.05 * i as f64, 0.125 + 0.0375 * j as f64);
                    let x = p.point(
                        d.u[0] + a * (d.u[1] - d.u[0]),
                        d.v[0] + b * (d.v[1] - d.v[0]),
                    );
                    let v = dir[0] * x.x + dir[1] * x.y + dir[2] * x.z;
                    assert!(range.inf() - 1e-12 <= v && v <= range.sup() + 1e-12);
                }
            }
        }
        // A parallelogram in an oblique plane: across it, along its corner normal, the range is
        // as thin as the rounding.
        let corners = [
            [0.0, 0.0, 1.0],
            [0.5, 1.0, 1.25],
            [1.0, -0.5, 2.0],
            [1.5, 0.5, 2.25],
        ];
        let flat = RationalBezierPatch::from_f64_points(
            [1, 1],
            &corners,
            None,
            Domain::new(0.0, 1.0, 0.0, 1.0),
        )
        .unwrap();
        let whole = Piece::whole(&flat);
        let n = whole.corner_normal().unwrap();
        assert!(whole.range_along(&n).unwrap().wid() < 1e-14);
        assert!(whole.bounds()[2].wid() > 1.0);
        assert!(whole.face(0, false).corner_normal().is_none());
    }
}
