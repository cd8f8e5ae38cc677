//! Contact covers: every intersection point of a parameter region, enclosed by small boxes.
//!
//! At a tangential contact nothing about the curve itself can be proven by interval evaluation:
//! `P − Q` vanishes to second order, so its enclosures only ever *contain* zero. What can be
//! proven is where the intersection is **not**: a 4-D parameter box `[σ]×[t]×[u]×[v]` whose
//! model-space enclosures `P([σ],[t])` and `Q([u],[v])` ([`RationalBezierPatch::enclose`], convex
//! hull of the sub-patch net ∩ naive interval evaluation) are disjoint, or on which
//! `n·(P − Q)` is proven non-zero for a fixed vector `n` (mean-value form), holds no point with
//! `P(σ,t) = Q(u,v)`. [`contact_cover`] bisects a region and drops every such box; the kept boxes
//! therefore contain every intersection point of the region. They do not prove that any
//! intersection exists.
//!
//! **Width of the band.** At parameter distance `d` from a contact curve `|P − Q| ≈ κ d²`, while
//! the enclosure of a box of width `w` overestimates by `O(κ w²)`: boxes are dropped only once
//! `d ≳ w`, so the band of kept boxes is a few leaf widths wide, down to the floor
//! `d ≈ √(rounding/κ)` where `κ d²` drowns in rounding (≈ 1e-8 in double precision), which no
//! affordable number of 4-D boxes reaches.

use crate::certify::contact_net::{CoverPatch, Net4, Scratch};
use crate::geometry::enclosure::boxes_disjoint;
use crate::geometry::surface::{pair_bounds, pair_widths};
use crate::geometry::RationalBezierPatch;
use crate::numeric::scalar::{interval, point};
use crate::numeric::vec3::{self, cross};
use inari::Interval;
use rayon::prelude::*;
use std::rc::Rc;
use std::sync::atomic::{AtomicUsize, Ordering};

/// Parameters of [`contact_cover`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CoverOptions {
    /// A box is a leaf (kept without further bisection) once each of its four widths is at most
    /// this fraction of its parameter's domain width.
    pub leaf_fraction: f64,
    /// Budget of enclosure evaluations; when spent, undivided boxes are kept as they are (the
    /// cover stays sound, only coarser) and [`ContactCover::resolved`] is `false`.
    pub max_evaluations: usize,
}

impl Default for CoverOptions {
    fn default() -> Self {
        CoverOptions {
            leaf_fraction: 1.0 / 256.0,
            max_evaluations: 400_000,
        }
    }
}

/// One kept box of a cover.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CoverBox {
    /// `[σ] × [t]` on P.
    pub p: [Interval; 2],
    /// `[u] × [v]` on Q.
    pub q: [Interval; 2],
    /// `P([σ],[t]) ∩ Q([u],[v])`: every intersection point of the box lies in it.
    pub xyz: [Interval; 3],
}

impl CoverBox {
    /// The four parameter intervals `(σ, t, u, v)`.
    pub fn params(&self) -> [Interval; 4] {
        [self.p[0], self.p[1], self.q[0], self.q[1]]
    }

    /// Whether the parameter point `y = (σ, t, u, v)` lies in the box.
    pub fn contains(&self, y: &[f64; 4]) -> bool {
        self.params().iter().zip(y).all(|(b, x)| b.contains(*x))
    }
}

/// The result of [`contact_cover`].
///
/// Guarantee: every `(σ, t, u, v)` in the union of [`region`](Self::region) with
/// `P(σ,t) = Q(u,v)` lies in some box of [`boxes`](Self::boxes), and its model point in that
/// box's `xyz` (for every patch of the interval nets).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ContactCover {
    /// The searched region: 4-D parameter boxes, each inside both domains.
    pub region: Vec<[Interval; 4]>,
    /// The kept boxes.
    pub boxes: Vec<CoverBox>,
    /// Every kept box reached the leaf size (`false` if the evaluation budget ran out first).
    pub resolved: bool,
    /// Enclosure evaluations spent.
    pub evaluations: usize,
    /// Largest model-space width (any coordinate) of a kept box's `xyz`.
    pub max_xyz_width: f64,
}

/// Clips a parameter box to both domains; `None` if nothing is left.
pub fn clip_to_domains(
    p: &RationalBezierPatch,
    q: &RationalBezierPatch,
    y: &[Interval; 4],
) -> Option<[Interval; 4]> {
    let (dp, dq) = (p.domain(), q.domain());
    let mut out = *y;
    for (i, x) in out.iter_mut().enumerate() {
        let [lo, hi] = pair_bounds(&dp, &dq, i);
        *x = x.intersection(interval(lo, hi)?);
        if x.is_empty() {
            return None;
        }
    }
    Some(out)
}

/// The normal test runs on leaf-sized boxes only (it costs ≈ 5 hull tests; measured on the
/// cubic × quadratic contact, testing from 2 leaf widths up took 3× longer for the same boxes).
const NORMAL_TEST_LEAVES: f64 = 1.0;

/// Whether `n·(P(σ,t) − Q(u,v)) ≠ 0` is proven on the box, `n` the normal of P at the box
/// centre (any fixed vector would be sound). Mean-value form: `g(c) + Σᵢ ∂ᵢg(box)·(yᵢ − cᵢ)`,
/// with the partials enclosed over the box. Near a contact the partials of `g` are `O(w)` (the
/// tangents are normal to `n`), so this excludes boxes at distance `≳ w` from the contact where
/// the hull test, whose ranges carry the surfaces' slope `O(w)`, needs distance `≳ √w`.
fn normal_separates(cp: &CoverPatch<'_>, cq: &CoverPatch<'_>, y: &[Interval; 4]) -> bool {
    normal_separates_with(
        cp.patch(),
        cq.patch(),
        y,
        |a, b, c, d| cp.scaled_partials_centred(a, b, c, d),
        |a, b, c, d| cq.scaled_partials_centred(a, b, c, d),
    )
}

/// The scaled partials `(a, b, g)` of a patch over a box, written around a centre.
type Partials = ([Interval; 3], [Interval; 3], Interval);

/// [`normal_separates`] with the partials of P and Q over the box given by `p_partials` and
/// `q_partials` (the cover's fast enclosures, or, in the tests, the patches' own).
fn normal_separates_with(
    p: &RationalBezierPatch,
    q: &RationalBezierPatch,
    y: &[Interval; 4],
    p_partials: impl Fn(Interval, Interval, Interval, Interval) -> Partials,
    q_partials: impl Fn(Interval, Interval, Interval, Interval) -> Partials,
) -> bool {
    let c = y.map(|x| x.mid());
    let d = p.derivs_f64(c[0], c[1]);
    let n = cross(&d.su, &d.sv);
    if !n.iter().all(|x| x.is_finite()) {
        return false;
    }
    let n = [point(n[0]), point(n[1]), point(n[2])];
    let dot = |a: &[Interval; 3]| vec3::dot(&n, a);
    let pc = p.eval(point(c[0]), point(c[1]));
    let qc = q.eval(point(c[2]), point(c[3]));
    // Partials over the box, written around its centre (tight: no Bernstein cancellation).
    let ci = c.map(point);
    let (pa, pb, pg) = p_partials(y[0], y[1], ci[0], ci[1]);
    let (qa, qb, qg) = q_partials(y[2], y[3], ci[2], ci[3]);
    let (ps, pt) = (pa.map(|x| x / pg), pb.map(|x| x / pg));
    let (qu, qv) = (qa.map(|x| x / qg), qb.map(|x| x / qg));
    let off = |i: usize| y[i] - point(c[i]);
    let g = dot(&pc) - dot(&qc) + dot(&ps) * off(0) + dot(&pt) * off(1)
        - dot(&qu) * off(2)
        - dot(&qv) * off(3);
    !g.is_empty() && !g.contains(0.0)
}

/// Bisects every box of `region` (clipped to both domains) and keeps the sub-boxes on which
/// `P` and `Q` may meet; see [`ContactCover`] for the guarantee.
///
/// The region boxes are independent and are bisected in parallel; the result is the one of
/// bisecting them one after another (last box first, one shared evaluation budget), box for
/// box: a box whose bisection might have met the budget at its place in that order is bisected
/// again in order with the budget (so the result never depends on the threads).
///
/// Neighbouring region boxes overlap (about half of each, along the tube). Each is bisected
/// only where it lies outside the region boxes bisected before it (later in `region`): its part
/// there is cut into at most eight boxes per overlapping box (`bisected_pieces`), which are
/// bisected in its place. Every intersection point of the rest lies in the kept boxes of a box
/// bisected before, so the guarantee is unchanged and the overlaps are bisected once.
pub fn contact_cover(
    p: &RationalBezierPatch,
    q: &RationalBezierPatch,
    region: &[[Interval; 4]],
    opts: &CoverOptions,
) -> ContactCover {
    let widths = pair_widths(&p.domain(), &q.domain());
    let leaf: [f64; 4] = std::array::from_fn(|i| opts.leaf_fraction * widths[i]);
    let clipped: Vec<[Interval; 4]> = region
        .iter()
        .filter_map(|y| clip_to_domains(p, q, y))
        .collect();
    let (cp, cq) = (CoverPatch::new(p), CoverPatch::new(q));
    let roots: Vec<Root> = bisected_pieces(&clipped)
        .par_iter()
        .map(|y| Root {
            y: *y,
            bp: cp.enclose(y[0], y[1]),
            bq: cq.enclose(y[2], y[3]),
        })
        .collect();
    let ctx = Bisection {
        p: &cp,
        q: &cq,
        widths,
        leaf,
        max_evaluations: opts.max_evaluations,
    };
    // Each root's enclosures count as two evaluations, all spent before any bisection.
    let mut evaluations = 2 * roots.len();
    // Optimistic parallel pass: each root without a budget, all of them stopped once together
    // they spent what the budget leaves.
    let spent = AtomicUsize::new(evaluations);
    let free: Vec<Option<RootCover>> = roots
        .par_iter()
        .map(|r| ctx.bisect(r, Limit::Shared(&spent)))
        .collect();
    let mut cover = ContactCover {
        region: clipped,
        resolved: true,
        ..Default::default()
    };
    for (root, free) in roots.iter().zip(free).rev() {
        // A root whose bisection stays below the budget from its place in the sequential order
        // never meets the budget there: its free result is the sequential one.
        let part = match free {
            Some(part) if evaluations + part.evaluations < opts.max_evaluations => part,
            _ => ctx
                .bisect(root, Limit::From(evaluations))
                .unwrap_or_default(),
        };
        evaluations += part.evaluations;
        cover.resolved &= part.resolved;
        cover.max_xyz_width = cover.max_xyz_width.max(part.max_xyz_width);
        cover.boxes.extend(part.boxes);
    }
    cover.evaluations = evaluations;
    cover
}

/// One region box with the enclosures of its two halves.
struct Root {
    y: [Interval; 4],
    bp: [Interval; 3],
    bq: [Interval; 3],
}

/// The boxes that [`contact_cover`] bisects for the region boxes `clipped`, in their order: each
/// region box minus the region boxes after it (bisected before it), as closed boxes whose union
/// is that difference's closure. Together they cover the union of `clipped`.
fn bisected_pieces(clipped: &[[Interval; 4]]) -> Vec<[Interval; 4]> {
    (0..clipped.len())
        .flat_map(|i| pieces_of(clipped, i))
        .collect()
}

/// The pieces of [`bisected_pieces`] for the box `clipped[i]`.
fn pieces_of(clipped: &[[Interval; 4]], i: usize) -> Vec<[Interval; 4]> {
    let mut parts = vec![clipped[i]];
    for r in &clipped[i + 1..] {
        parts = parts.iter().flat_map(|b| box_minus(b, r)).collect();
    }
    parts
}

/// The closed boxes (at most eight) whose union is the closure of `b` minus `r`: `b` itself when
/// their interiors do not meet. Cut coordinate by coordinate: the slabs of `b` below and above
/// `r`, then what is left between them.
fn box_minus(b: &[Interval; 4], r: &[Interval; 4]) -> Vec<[Interval; 4]> {
    let meet = (0..4).all(|k| b[k].inf() < r[k].sup() && r[k].inf() < b[k].sup());
    if !meet {
        return vec![*b];
    }
    let mut out = Vec::new();
    let mut rest = *b;
    for k in 0..4 {
        let (lo, hi) = (rest[k].inf(), rest[k].sup());
        if lo < r[k].inf() {
            let mut slab = rest;
            slab[k] = interval(lo, r[k].inf()).unwrap_or(rest[k]);
            out.push(slab);
        }
        if r[k].sup() < hi {
            let mut slab = rest;
            slab[k] = interval(r[k].sup(), hi).unwrap_or(rest[k]);
            out.push(slab);
        }
        rest[k] = interval(lo.max(r[k].inf()), hi.min(r[k].sup())).unwrap_or(rest[k]);
    }
    // `rest` lies inside `r`.
    out
}

/// A box waiting to be tested, with what its bisection can reuse.
struct Item {
    y: [Interval; 4],
    /// `P([σ], [t])` and `Q([u], [v])`.
    bp: [Interval; 3],
    bq: [Interval; 3],
    /// The u-columns of the sub-nets over `[σ]` and `[u]` ([`CoverPatch::columns`]).
    cols_p: Rc<Vec<Net4>>,
    cols_q: Rc<Vec<Net4>>,
}

/// The kept boxes of one root.
#[derive(Default)]
struct RootCover {
    boxes: Vec<CoverBox>,
    evaluations: usize,
    resolved: bool,
    max_xyz_width: f64,
}

/// The budget of one root's bisection.
#[derive(Clone, Copy)]
enum Limit<'a> {
    /// No budget of its own; every evaluation is added to the shared count, and the bisection
    /// is abandoned (`None`) once that reaches the budget.
    Shared(&'a AtomicUsize),
    /// The sequential budget: this many evaluations were spent before the root.
    From(usize),
}

/// What every root's bisection shares.
struct Bisection<'a> {
    p: &'a CoverPatch<'a>,
    q: &'a CoverPatch<'a>,
    widths: [f64; 4],
    leaf: [f64; 4],
    max_evaluations: usize,
}

impl Bisection<'_> {
    /// Bisects one root depth first (the order of the sequential cover).
    fn bisect(&self, root: &Root, limit: Limit<'_>) -> Option<RootCover> {
        let (p, q, widths, leaf) = (self.p, self.q, self.widths, self.leaf);
        let mut out = RootCover {
            resolved: true,
            ..Default::default()
        };
        let spend = |out: &mut RootCover, n: usize| -> bool {
            out.evaluations += n;
            match limit {
                Limit::Shared(s) => s.fetch_add(n, Ordering::Relaxed) + n < self.max_evaluations,
                Limit::From(_) => true,
            }
        };
        // Each work item carries the enclosures of its P- and Q-halves, so bisecting σ or t
        // only re-encloses P, and u or v only Q; and the u-columns of both sub-nets, so
        // bisecting t (or v) only restricts the rows again.
        let mut scratch = Scratch::default();
        let mut stack: Vec<Item> = vec![Item {
            y: root.y,
            bp: root.bp,
            bq: root.bq,
            cols_p: Rc::new(p.columns(root.y[0], &mut scratch)),
            cols_q: Rc::new(q.columns(root.y[2], &mut scratch)),
        }];
        while let Some(Item {
            y,
            bp,
            bq,
            cols_p,
            cols_q,
        }) = stack.pop()
        {
            if boxes_disjoint(&bp, &bq) {
                continue;
            }
            // The normal test pays off only on the smallest boxes (far costlier than the hull).
            let near_leaf = (0..4).all(|i| y[i].wid() <= NORMAL_TEST_LEAVES * leaf[i]);
            if near_leaf {
                if !spend(&mut out, 1) {
                    return None;
                }
                if normal_separates(p, q, &y) {
                    continue;
                }
            }
            let widest = (0..4)
                .max_by(|&a, &b| (y[a].wid() / widths[a]).total_cmp(&(y[b].wid() / widths[b])))
                .unwrap_or(0);
            let is_leaf = (0..4).all(|i| y[i].wid() <= leaf[i]);
            let spent_all = match limit {
                Limit::From(n) => n + out.evaluations >= self.max_evaluations,
                Limit::Shared(_) => false,
            };
            if is_leaf || spent_all {
                out.resolved &= is_leaf;
                let xyz: [Interval; 3] = std::array::from_fn(|c| bp[c].intersection(bq[c]));
                out.max_xyz_width = xyz.iter().fold(out.max_xyz_width, |m, x| m.max(x.wid()));
                out.boxes.push(CoverBox {
                    p: [y[0], y[1]],
                    q: [y[2], y[3]],
                    xyz,
                });
                continue;
            }
            let x = y[widest];
            let mid = x.mid();
            for half in [interval(x.inf(), mid), interval(mid, x.sup())]
                .into_iter()
                .flatten()
            {
                let mut z = y;
                z[widest] = half;
                if !spend(&mut out, 1) {
                    return None;
                }
                let mut item = Item {
                    y: z,
                    bp,
                    bq,
                    cols_p: cols_p.clone(),
                    cols_q: cols_q.clone(),
                };
                match widest {
                    0 => item.cols_p = Rc::new(p.columns(z[0], &mut scratch)),
                    2 => item.cols_q = Rc::new(q.columns(z[2], &mut scratch)),
                    _ => {}
                }
                if widest < 2 {
                    item.bp = p.enclose_rows(&item.cols_p, z[0], z[1], &mut scratch);
                } else {
                    item.bq = q.enclose_rows(&item.cols_q, z[2], z[3], &mut scratch);
                }
                stack.push(item);
            }
        }
        Some(out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::{Domain, PowerSurface};
    use crate::pair::fixtures::TANGENTIAL_CUBIC;

    /// The normal test as it was (on the patches' own functions).
    fn old_normal_separates(
        p: &RationalBezierPatch,
        q: &RationalBezierPatch,
        y: &[Interval; 4],
    ) -> bool {
        normal_separates_with(
            p,
            q,
            y,
            |a, b, c, d| p.scaled_partials_centred(a, b, c, d),
            |a, b, c, d| q.scaled_partials_centred(a, b, c, d),
        )
    }

    /// The cover as it was computed before the parallel bisection: one stack, one budget.
    fn sequential_cover(
        p: &RationalBezierPatch,
        q: &RationalBezierPatch,
        region: &[[Interval; 4]],
        opts: &CoverOptions,
    ) -> ContactCover {
        let widths = pair_widths(&p.domain(), &q.domain());
        let leaf: [f64; 4] = std::array::from_fn(|i| opts.leaf_fraction * widths[i]);
        let mut cover = ContactCover {
            resolved: true,
            ..Default::default()
        };
        // Each work item carries the enclosures of its P- and Q-halves, so bisecting σ or t only
        // re-encloses P, and u or v only Q.
        let mut stack: Vec<([Interval; 4], [Interval; 3], [Interval; 3])> = Vec::new();
        for y in region.iter().filter_map(|y| clip_to_domains(p, q, y)) {
            cover.region.push(y);
        }
        // Each region box where no box after it (bisected before it) lies.
        for y in bisected_pieces(&cover.region) {
            cover.evaluations += 2;
            stack.push((y, p.enclose(y[0], y[1]), q.enclose(y[2], y[3])));
        }
        while let Some((y, bp, bq)) = stack.pop() {
            if boxes_disjoint(&bp, &bq) {
                continue;
            }
            // The normal test pays off only on the smallest boxes (it is far costlier than the hull).
            let near_leaf = (0..4).all(|i| y[i].wid() <= NORMAL_TEST_LEAVES * leaf[i]);
            if near_leaf {
                cover.evaluations += 1;
                if old_normal_separates(p, q, &y) {
                    continue;
                }
            }
            let widest = (0..4)
                .max_by(|&a, &b| (y[a].wid() / widths[a]).total_cmp(&(y[b].wid() / widths[b])))
                .unwrap_or(0);
            let is_leaf = (0..4).all(|i| y[i].wid() <= leaf[i]);
            if is_leaf || cover.evaluations >= opts.max_evaluations {
                cover.resolved &= is_leaf;
                let xyz: [Interval; 3] = std::array::from_fn(|c| bp[c].intersection(bq[c]));
                cover.max_xyz_width = xyz.iter().fold(cover.max_xyz_width, |m, x| m.max(x.wid()));
                cover.boxes.push(CoverBox {
                    p: [y[0], y[1]],
                    q: [y[2], y[3]],
                    xyz,
                });
                continue;
            }
            let x = y[widest];
            let mid = x.mid();
            for half in [interval(x.inf(), mid), interval(mid, x.sup())]
                .into_iter()
                .flatten()
            {
                let mut z = y;
                z[widest] = half;
                cover.evaluations += 1;
                if widest < 2 {
                    stack.push((z, p.enclose(z[0], z[1]), bq));
                } else {
                    stack.push((z, bp, q.enclose(z[2], z[3])));
                }
            }
        }
        cover
    }

    #[test]
    fn disjoint_patches_leave_an_empty_cover_and_crossing_ones_do_not() {
        let d = Domain::new(-1.0, 1.0, -1.0, 1.0);
        let bowl = PowerSurface::graph(d, vec![(2, 0, 1.0), (0, 2, 1.0), (0, 0, 0.5)])
            .to_bezier()
            .unwrap();
        let plane = PowerSurface::graph(d, vec![]).to_bezier().unwrap();
        let all = [[interval(-1.0, 1.0).unwrap(); 4]];
        let opts = CoverOptions {
            leaf_fraction: 1.0 / 16.0,
            ..Default::default()
        };
        let none = contact_cover(&bowl, &plane, &all, &opts);
        assert!(none.boxes.is_empty() && none.resolved);
        // z = x² + y² − ¼ meets z = 0 on the circle of radius ½: every sampled circle point,
        // (σ,t) = (u,v), lies in a kept box.
        let cut = PowerSurface::graph(d, vec![(2, 0, 1.0), (0, 2, 1.0), (0, 0, -0.25)])
            .to_bezier()
            .unwrap();
        let c = contact_cover(&cut, &plane, &all, &opts);
        assert!(c.resolved && !c.boxes.is_empty());
        for k in 0..200 {
            let a = k as f64 * std::f64::consts::TAU / 200.0;
            let y = [0.5 * a.cos(), 0.5 * a.sin(), 0.5 * a.cos(), 0.5 * a.sin()];
            assert!(c.boxes.iter().any(|b| b.contains(&y)), "{y:?} not covered");
        }
    }

    #[test]
    fn bisected_pieces_cover_the_region_and_miss_the_later_boxes() {
        // Overlapping boxes along a diagonal, one inside another, one apart.
        let r = |c: [f64; 4], h: f64| c.map(|x| interval(x - h, x + h).unwrap());
        let region = vec![
            r([0.0, 0.0, 0.0, 0.0], 0.3),
            r([0.2, 0.1, 0.2, 0.1], 0.3),
            r([0.25, 0.1, 0.2, 0.15], 0.05),
            r([0.4, 0.2, 0.4, 0.2], 0.3),
            r([3.0, 3.0, 3.0, 3.0], 0.1),
        ];
        let pieces = bisected_pieces(&region);
        let inside = |b: &[Interval; 4], y: &[f64; 4]| (0..4).all(|k| b[k].contains(y[k]));
        // A grid of points of the region: each lies in a piece.
        let mut tried = 0;
        for k in 0..20_000u64 {
            let mut h = k.wrapping_mul(0x9E37_79B9_7F4A_7C15);
            let y: [f64; 4] = std::array::from_fn(|_| {
                h = h.rotate_left(17).wrapping_mul(0xBF58_476D_1CE4_E5B9);
                -0.4 + 1.2 * (h >> 11) as f64 / (1u64 << 53) as f64
            });
            if region.iter().any(|b| inside(b, &y)) {
                tried += 1;
                assert!(pieces.iter().any(|b| inside(b, &y)), "{y:?}");
            }
        }
        assert!(tried > 1000);
        // The pieces of a box lie in it and meet no later box's interior; the last box is kept
        // whole, and a box inside a later one leaves nothing.
        let meets = |a: &[Interval; 4], b: &[Interval; 4]| {
            (0..4).all(|k| a[k].inf() < b[k].sup() && b[k].inf() < a[k].sup())
        };
        for (i, y) in region.iter().enumerate() {
            for b in pieces_of(&region, i) {
                assert!((0..4).all(|k| b[k].subset(y[k])));
                assert!(region[i + 1..].iter().all(|later| !meets(&b, later)));
            }
        }
        assert_eq!(pieces_of(&region, 4), vec![region[4]]);
        assert!(pieces_of(&region, 2).is_empty());
    }

    #[test]
    fn parallel_cover_is_the_sequential_cover_with_and_without_budget() {
        let d = Domain::new(-1.0, 1.0, -1.0, 1.0);
        let q = PowerSurface::graph(d, vec![(0, 2, 1.0), (2, 0, 0.5), (1, 1, 0.3)])
            .to_bezier()
            .unwrap();
        let p = PowerSurface::graph(d, TANGENTIAL_CUBIC.to_vec())
            .to_bezier()
            .unwrap();
        // Boxes along the contact curve (x, x/2, x, x/2), overlapping, one partly outside.
        let region: Vec<[Interval; 4]> = (0..9)
            .map(|k| {
                let x = -1.05 + 0.25 * k as f64;
                let r = |c: f64, h: f64| interval(c - h, c + h).unwrap();
                [r(x, 0.14), r(0.5 * x, 0.1), r(x, 0.14), r(0.5 * x, 0.1)]
            })
            .collect();
        for max_evaluations in [400_000, 3_000, 700, 40, 5] {
            let opts = CoverOptions {
                leaf_fraction: 1.0 / 64.0,
                max_evaluations,
            };
            let want = sequential_cover(&p, &q, &region, &opts);
            let got = contact_cover(&p, &q, &region, &opts);
            assert_eq!(got, want, "budget {max_evaluations}");
            // The small budgets do bind.
            assert_eq!(
                got.resolved,
                max_evaluations > 3_000,
                "budget {max_evaluations}"
            );
        }
    }
}
