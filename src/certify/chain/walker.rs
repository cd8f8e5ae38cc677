//! The walk of one half of a cover chain: links between guide points, split where needed,
//! joined without gaps, and the end where the half stops.

use super::limit::LinkLimit;
use super::*;
use crate::certify::lean_patch::{costlier_side, LeanPatch};
use crate::geometry::pole::common_pole;
use std::cell::Cell;

/// The pole a half of a chain runs into (see `pole.rs`): which coordinates run away from its
/// side and along it, on the surface whose patch collapses there.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) struct PoleEnd {
    /// The coordinate (0–3) that runs away from the collapsed side.
    pub(super) radial: usize,
    /// The coordinate along the side (the angle about the pole).
    pub(super) angular: usize,
}

/// A guide point on the curve and its parameter velocity, oriented along the walk.
#[derive(Debug, Clone, Copy)]
pub(super) struct Node {
    pub(super) x: [f64; 4],
    pub(super) t: [f64; 4],
}

/// One proven link and what it reports.
#[derive(Debug, Clone, Copy)]
pub(super) struct Link {
    pub(super) proof: SegmentProof,
    /// `x_j` at the link's start node (the predictor's origin).
    pub(super) from: f64,
    /// `x_j` where the link's reported curve ends.
    pub(super) to: f64,
    /// `x_j` where its boxes start (before `from` when it reaches back to take in a join).
    pub(super) cover_from: f64,
    pub(super) radius_param: f64,
    pub(super) radius_xyz: f64,
    /// The enclosed slice at `x_j = to`: where the next link must take over.
    pub(super) end_slice: [Interval; 4],
    /// Whether `end_slice` was narrowed by [`tight_slice`] (see `Walker::settle_end_slice`).
    pub(super) tightened: bool,
    /// Why the link was kept although wider than the tolerance (`None`: it is not).
    pub(super) limit: Option<LinkLimit>,
    /// Whether it is graphed over a coordinate slower than [`Walker::along`] would take (see
    /// [`Walker::link_on`]): such a link is not kept wider than the tolerance for its own
    /// sake, only in place of a wider link that is (`Walker::narrowest_over_others`, `span`).
    pub(super) slow: bool,
}

impl Link {
    fn end_slice(&self) -> [Interval; 4] {
        self.end_slice
    }
}

/// The outcome of one link attempt.
pub(super) enum Attempt {
    /// Proven, within the tolerance.
    Proven(Link),
    /// Proven, but its tube is wider than the tolerance.
    TooWide(Link),
    /// Not proven.
    Failed,
}

/// How a half stopped.
#[derive(Debug, Clone)]
pub(super) enum Stop {
    /// Reached the end of its nodes.
    Done,
    /// Could not go on; the end to report.
    Failed(CertifiedEnd),
}

pub(super) struct Walker<'a> {
    pub(super) p: &'a RationalBezierPatch,
    pub(super) q: &'a RationalBezierPatch,
    pub(super) scales: [f64; 4],
    pub(super) opts: &'a ChainOptions,
    pub(super) links: Vec<Link>,
    /// Boxes the next link's tube must hold (the previous link's end slice).
    pub(super) join: Option<[Interval; 4]>,
    /// Links made by the other half (shared budget).
    pub(super) used: usize,
    /// Links made by all the walkers of one branch that run at the same time (the budget is
    /// shared through it; `None` for a walker on its own).
    pub(super) shared: Option<&'a AtomicUsize>,
    /// On a loop, the first link's start slice: a later link whose tube holds it closes the
    /// loop (the curve passes through the start point there), and the walk stops.
    pub(super) close_at: Option<[Interval; 4]>,
    /// Whether a link closed the loop.
    pub(super) closed: bool,
    /// Whether to watch for the loop closing (set `close_at` from the first link).
    pub(super) wants_closure: bool,
    /// The scaled length the next link should have, learnt from the last attempts (the tube's
    /// width grows like the eighth power of the length).
    pub(super) l_pred: Option<f64>,
    /// The last marched point when the march ended at a singular point there.
    pub(super) toward_singular: Option<[f64; 4]>,
    /// The pole the march ran into, if it did (see `pole.rs`).
    pub(super) toward_pole: Option<PoleEnd>,
    /// Whether the march of the half being walked ended at a pole (running into it, or
    /// passing it within rounding): its links are tried on the moved forms first.
    pub(super) march_at_pole: bool,
    /// Scaled length and model width of the last link added.
    pub(super) prev: Option<(f64, f64)>,
    /// Both patches in the form the link proofs evaluate.
    pub(super) lean: [LeanPatch<'a>; 2],
    /// The same moved so that the patches' one pole is the origin, for links near it
    /// ([`Self::try_link`], in `pole.rs`).
    pub(super) lean_at_pole: Option<[LeanPatch<'a>; 2]>,
    /// The first coordinate (0 for `P`, 2 for `Q`) of the patch that costs at least four times the
    /// other to evaluate, if one does (see [`Self::along`]).
    pub(super) costly_side: Option<usize>,
    /// The jets of the last two nodes a predictor was made from (node, along coordinate): a
    /// kept link's end node starts the next link, and a failed link's start node starts the
    /// split, so each jet (three patch evaluations per surface) is made about once.
    jets: Cell<[Option<(Node, usize, Jet)>; 2]>,
}

pub(super) fn velocity(p: &RationalBezierPatch, q: &RationalBezierPatch, x: &[f64; 4]) -> [f64; 4] {
    transversal_velocity::<f64, _, _>(p, q, x, 1.0)
}

pub(super) fn scaled_dist(a: &[f64; 4], b: &[f64; 4], scales: &[f64; 4]) -> f64 {
    (0..4)
        .map(|i| (a[i] - b[i]).abs() / scales[i])
        .fold(0.0, f64::max)
}

impl<'a> Walker<'a> {
    pub(super) fn new(
        p: &'a RationalBezierPatch,
        q: &'a RationalBezierPatch,
        opts: &'a ChainOptions,
    ) -> Self {
        let lean = [LeanPatch::new(p), LeanPatch::new(q)];
        // For links next to a pole, both forms moved so that it is the origin (see `pole.rs`).
        let lean_at_pole = common_pole(p, q)
            .and_then(|x| Some([LeanPatch::moved(p, x)?, LeanPatch::moved(q, x)?]));
        Walker {
            p,
            q,
            scales: pair_widths(&p.domain(), &q.domain()),
            opts,
            links: Vec::new(),
            join: None,
            used: 0,
            shared: None,
            close_at: None,
            closed: false,
            wants_closure: false,
            l_pred: None,
            toward_singular: None,
            toward_pole: None,
            march_at_pole: false,
            prev: None,
            costly_side: costlier_side(&lean),
            lean,
            lean_at_pole,
            jets: Cell::new([None; 2]),
        }
    }

    pub(super) fn node(&self, x: [f64; 4], along: &[f64; 4]) -> Option<Node> {
        let t = velocity(self.p, self.q, &x);
        if !t.iter().all(|v| v.is_finite()) || t.iter().all(|v| *v == 0.0) {
            return None;
        }
        // Next to the pole the half runs into, the angular part is rounding over the distance
        // to the pole, on both sides (`pole.rs`): orient by the other coordinates.
        let skip = self.pole_angular_at(&x);
        let dot: f64 = (0..4)
            .filter(|&i| Some(i) != skip)
            .map(|i| t[i] * along[i])
            .sum();
        let sign = if dot < 0.0 { -1.0 } else { 1.0 };
        Some(Node {
            x,
            t: t.map(|v| v * sign),
        })
    }

    /// The Hermite predictor from `a` to `b` graphed over `j`.
    fn predictor(&self, j: usize, a: &Node, b: &Node) -> Option<Predictor> {
        let ja = self.jet(a, j)?;
        let mut jb = self.jet(b, j)?;
        if let Some(k) = self.flat_coordinate(j, a, b) {
            jb.x[k] = ja.x[k];
        }
        Predictor::hermite(j, &ja, &jb)
    }

    /// The jet of node `n` graphed over `j`, from the last two made when it is one of them.
    fn jet(&self, n: &Node, j: usize) -> Option<Jet> {
        let mut kept = self.jets.get();
        let same = |m: &Node| m.x == n.x && m.t == n.t;
        if let Some((_, _, jet)) = kept.iter().flatten().find(|(m, k, _)| *k == j && same(m)) {
            return Some(*jet);
        }
        // On nearly tangent surfaces the node is first moved onto the curve (exact residual);
        // not where its jet is pinned next to a pole.
        let onto = (self.precise_at(&n.x) && self.pole_angular_at(&n.x).is_none())
            .then(|| self.precise_node(n, j))
            .flatten();
        let jet = self.node_jet(onto.as_ref().unwrap_or(n), j)?;
        kept = [Some((*n, j, jet)), kept[0]];
        self.jets.set(kept);
        Some(jet)
    }

    /// Tries one link from `a` to `b`; `must_end` must also lie in its tube (the closing join).
    ///
    /// After an attempt that is not proven within the tolerance, the join it started from is
    /// narrowed if it was not (a wide join widens every link from it, however short: the links
    /// after it would be split without narrowing).
    pub(super) fn link(&mut self, a: &Node, b: &Node, must_end: Option<&[Interval; 4]>) -> Attempt {
        let attempt = match self.try_link(a, b, must_end) {
            Some(l) if l.radius_xyz > self.opts.required_tolerance => Attempt::TooWide(l),
            Some(l) => Attempt::Proven(l),
            None => Attempt::Failed,
        };
        if !matches!(attempt, Attempt::Proven(_)) {
            self.tighten_join();
        }
        attempt
    }

    /// One attempt at the link from `a` to `b` graphed over `x_j`, on the exact residual at
    /// the link's start if `exact` (see [`prove_segment`]).
    pub(super) fn link_along(
        &self,
        lean: [&LeanPatch<'a>; 2],
        j: usize,
        a: &Node,
        b: &Node,
        must_end: Option<&[Interval; 4]>,
        exact: bool,
    ) -> Option<Link> {
        let pred = self.predictor(j, a, b)?;
        let musts: Vec<&[Interval; 4]> = self.join.iter().chain(must_end).collect();
        let (mut lo, mut hi) = (a.x[j].min(b.x[j]), a.x[j].max(b.x[j]));
        let mut need = [0.0f64; 3];
        for m in &musts {
            lo = lo.min(m[j].inf());
            hi = hi.max(m[j].sup());
            let o = pred.others_over(m[j] - point(pred.x0));
            for (r, &i) in others(j).iter().enumerate() {
                need[r] = need[r].max((m[i] - o[r]).mag());
            }
        }
        let dir = (b.x[j] - a.x[j]).signum();
        // The reported curve runs from the start node to the end node, or on to the far end of
        // the range when the link reaches past it to take in the closing join.
        let to = if dir > 0.0 { hi } else { lo };
        let cover_from = if dir > 0.0 { lo } else { hi };
        let proof = prove_segment(lean, pred, [lo, hi], need, exact).ok()?;
        if !musts.iter().all(|m| proof.tube_contains(m)) {
            return None;
        }
        let (radius_param, radius_xyz) = self.radii(&proof, a.x[j], cover_from)?;
        Some(Link {
            proof,
            from: a.x[j],
            to,
            cover_from,
            radius_param,
            radius_xyz,
            // The proof's own enclosure there; narrowed by Krawczyk (`tight_slice`, a seventh
            // of a link's cost) only once the link is kept and only if it is wide
            // (`settle_end_slice`), or when a link from it fails (`tighten_join`). Near-tangent
            // pairs need it: a wide slice widens the next link's uniqueness box and the tube.
            end_slice: proof.box_over(to, to),
            tightened: false,
            limit: None,
            slow: false,
        })
    }

    /// Proven deviations of the true curve from the reported one over the link: in parameters
    /// (max norm) and in model space, on both surfaces (`P` at the reported `σ, t` and `Q` at
    /// the reported `u, v`). The reported curve is the predictor from `from` to `to`;
    /// the arc before `from` (a reach back to `cover_from`) is measured against the reported
    /// start point.
    fn radii(&self, proof: &SegmentProof, from: f64, cover_from: f64) -> Option<(f64, f64)> {
        let j = proof.pred.along;
        // P(true) − P(reported) = ∫ DP · Δ over the segment between them: the columns of σ and
        // t among the offsets (P's part of the Jacobian of P − Q) times their offsets; the same
        // for Q with the columns of u and v. The radius bounds both reported model curves.
        let side = |surface: usize| {
            let mut v = [point(0.0); 3];
            for (c, &i) in others(j).iter().enumerate() {
                if i / 2 == surface {
                    for (r, vr) in v.iter_mut().enumerate() {
                        *vr += proof.jac[r][c] * proof.k[c];
                    }
                }
            }
            (v[0].sqr() + v[1].sqr() + v[2].sqr()).sqrt().sup()
        };
        let mut rx = side(0).max(side(1));
        let mut rp = proof.k.iter().map(|k| k.mag()).fold(0.0, f64::max);
        if cover_from != from {
            // True point at ξ ∈ [cover_from, from] against the reported point at `from`.
            let xi = hull(cover_from, from) - point(proof.pred.x0);
            let o = proof.pred.others_over(xi);
            let o0 = proof.pred.others_over(point(from) - point(proof.pred.x0));
            let mut e = [point(0.0); 4];
            e[j] = xi - (point(from) - point(proof.pred.x0));
            for (r, &i) in others(j).iter().enumerate() {
                e[i] = o[r] - o0[r] + proof.k[r];
            }
            let back = proof.tube_over(cover_from, from);
            let [_, bs, bt] = self.p.first_derivs(back[0], back[1]);
            let [_, bu, bv] = self.q.first_derivs(back[2], back[3]);
            let vp: [Interval; 3] = std::array::from_fn(|r| bs[r] * e[0] + bt[r] * e[1]);
            let vq: [Interval; 3] = std::array::from_fn(|r| bu[r] * e[2] + bv[r] * e[3]);
            for v in [vp, vq] {
                rx = rx.max((v[0].sqr() + v[1].sqr() + v[2].sqr()).sqrt().sup());
            }
            rp = rp.max(e.iter().map(|x| x.mag()).fold(0.0, f64::max));
        }
        (rp.is_finite() && rx.is_finite()).then_some((rp, rx))
    }

    /// A new node halfway (in the along coordinate of largest scaled change) from `a` to `b`.
    fn midpoint(&self, a: &Node, b: &Node, frac: f64) -> Option<Node> {
        let largest = (0..4).max_by(|&x, &y| {
            let dx = (b.x[x] - a.x[x]).abs() / self.scales[x];
            let dy = (b.x[y] - a.x[y]).abs() / self.scales[y];
            dx.total_cmp(&dy)
        });
        let j = self.pole_along(a, b).or(largest).unwrap_or(0);
        let value = a.x[j] + frac * (b.x[j] - a.x[j]);
        let guess = match self.predictor(j, a, b) {
            Some(pr) => pr.eval(value - pr.x0),
            None => std::array::from_fn(|i| a.x[i] + frac * (b.x[i] - a.x[i])),
        };
        // A Newton point far from the guess belongs to another curve.
        let span = scaled_dist(&a.x, &b.x, &self.scales);
        let near = |r: &Refined, g: &[f64; 4], d: f64| scaled_dist(&r.x, g, &self.scales) <= d;
        if let Some(r) =
            newton(self.p, self.q, guess, j, value).filter(|r| near(r, &guess, 0.5 * span))
        {
            return self.node(r.x, &a.t);
        }
        // The interpolant is a poor guess (a coarse march): a short step along the tangent.
        let speed = (0..4)
            .map(|i| a.t[i].abs() / self.scales[i])
            .fold(0.0, f64::max);
        if speed == 0.0 {
            return None;
        }
        let h = 0.25 * span / speed;
        let step: [f64; 4] = std::array::from_fn(|i| a.x[i] + h * a.t[i]);
        let k = (0..4)
            .max_by(|&x, &y| {
                (a.t[x].abs() / self.scales[x]).total_cmp(&(a.t[y].abs() / self.scales[y]))
            })
            .unwrap_or(0);
        let r = newton(self.p, self.q, step, k, step[k]).filter(|r| {
            near(r, &step, 0.125 * span) && scaled_dist(&r.x, &a.x, &self.scales) > 0.0
        })?;
        self.node(r.x, &a.t)
    }

    /// The tube width that rounding alone can cause near `node`: 1e-12 of the model's size
    /// there.
    fn rounding_floor(&self, node: &Node) -> f64 {
        let m = self.p.point_f64(node.x[0], node.x[1]);
        1e-12 * (1.0 + m.iter().fold(0.0f64, |a, v| a.max(v.abs())))
    }

    /// Learns the next link's length from an attempt of scaled length `len`: aim at a tube of
    /// half the tolerance (`r ∝ L⁸` for the septic predictor; the tube is the predictor's own deviation since the
    /// residual is ranged by its Bernstein form, so half leaves room enough), at most doubling
    /// after a success, at least halving after a failure without a width.
    fn learn(&mut self, len: f64, attempt: &Attempt) {
        let tol = self.opts.required_tolerance;
        let aim = |r: f64| {
            if r > 0.0 {
                (tol / (2.0 * r)).powf(1.0 / (PREDICTOR_DEGREE + 1) as f64)
            } else {
                2.0
            }
        };
        let f = match attempt {
            Attempt::Proven(l) => aim(l.radius_xyz).clamp(0.7, 3.0),
            Attempt::TooWide(l) => aim(l.radius_xyz).clamp(0.25, 0.9),
            Attempt::Failed => 0.5,
        };
        if len > 0.0 && f.is_finite() {
            self.l_pred = Some(len * f);
        }
    }

    /// Adds a proven link of scaled length `len`; on a loop, whether it closes the loop (then the walk stops).
    fn push(&mut self, mut link: Link, len: f64) -> bool {
        self.prev = Some((len, link.radius_xyz));
        if let Some(c) = self.shared {
            c.fetch_add(1, Ordering::Relaxed);
        }
        self.settle_end_slice(&mut link);
        self.join = Some(link.end_slice());
        self.links.push(link);
        if self.links.len() == 1 {
            if self.close_at.is_none() && self.wants_closure {
                let l0 = &self.links[0];
                self.close_at = Some(tight_slice(self.p, self.q, &l0.proof, l0.from));
            }
            return false;
        }
        self.closed = self
            .close_at
            .is_some_and(|s| self.links.last().is_some_and(|l| l.proof.tube_contains(&s)));
        self.closed
    }

    /// Why the link or time budget is spent, if it is (never before the first link of a half:
    /// the start is always proven).
    fn out_of_budget(&self) -> Option<String> {
        if self.links.is_empty() {
            return None;
        }
        if self.opts.deadline.is_some_and(|d| Instant::now() >= d) {
            return Some("time limit reached".into());
        }
        let made = self
            .shared
            .map_or(self.links.len(), |c| c.load(Ordering::Relaxed));
        (made + self.used >= self.opts.max_links)
            .then(|| format!("budget spent ({} links)", self.opts.max_links))
    }

    /// Links from `a` to `b`, splitting where needed; on failure the end to report there.
    pub(super) fn span(&mut self, a: Node, b: Node, must_end: Option<&[Interval; 4]>) -> Stop {
        let mut cur = a;
        // Targets, with the radius of a too wide link that was split to reach them.
        let mut stack: Vec<(Node, Option<f64>)> = vec![(b, None)];
        let mut splits = 0;
        // Consecutive splits that did not narrow the tube (see `STALLED_SPLITS`).
        let mut stalled = 0;
        // The narrowest too wide link tried from `cur`, with the stack index of its target.
        let mut narrowest: Option<(usize, Link)> = None;
        while let Some(&(tgt, wider)) = stack.last() {
            if let Some(reason) = self.out_of_budget() {
                return Stop::Failed(CertifiedEnd::Unproven {
                    reason,
                    near: point_box(&cur.x),
                });
            }
            let closing = (stack.len() == 1).then_some(must_end).flatten();
            let len = scaled_dist(&cur.x, &tgt.x, &self.scales);
            // Towards a singular end a link longer than its reach fails: split it untried.
            if let Some(r) = self
                .singular_reach(&cur)
                .filter(|&r| len > r && len > MIN_LINK)
            {
                if splits < MAX_SPLITS {
                    if let Some(m) = self.midpoint(&cur, &tgt, (r / len).clamp(0.1, 0.75)) {
                        splits += 1;
                        stack.push((m, wider));
                        continue;
                    }
                }
            }
            let attempt = self.link(&cur, &tgt, closing);
            self.learn(len, &attempt);
            let too_wide = match attempt {
                Attempt::Proven(link) => Some(link),
                // A short link that halving did not narrow: its width is rounding (a tolerance
                // below rounding was asked for) or the conditioning away from any singular
                // point; keep it (the certificate then reports a tolerance above the
                // requested one, and why, instead of failing).
                Attempt::TooWide(mut link)
                    if !link.slow
                        && wider.is_some_and(|w| link.radius_xyz > 0.5 * w)
                        && (link.radius_xyz <= self.rounding_floor(&cur)
                            || (scaled_dist(&cur.x, &tgt.x, &self.scales) < FLOOR_LINK
                                && self.conditioning_only(&cur.x, &tgt.x))) =>
                {
                    link = self.narrowest_over_others(&cur, &tgt, closing, link);
                    // A longer link from here that was split for its width but is narrower
                    // than this one (the along coordinate switched on the way) is kept instead.
                    if let Some((at, wide)) = narrowest.take() {
                        if wide.radius_xyz < link.radius_xyz {
                            stack.truncate(at + 1);
                            link = wide;
                        }
                    }
                    if link.radius_xyz > self.opts.required_tolerance {
                        let rounding = link.radius_xyz <= self.rounding_floor(&cur);
                        link.limit = Some(self.limit_at(&cur.x, rounding));
                    }
                    Some(link)
                }
                Attempt::TooWide(link) => {
                    let narrowed = wider.is_none_or(|w| link.radius_xyz <= STALL_RATIO * w);
                    if narrowest
                        .as_ref()
                        .is_none_or(|(_, n)| link.radius_xyz < n.radius_xyz)
                    {
                        narrowest = Some((stack.len() - 1, link));
                    }
                    stalled = if narrowed { 0 } else { stalled + 1 };
                    if let Some(top) = stack.last_mut() {
                        top.1 = Some(link.radius_xyz);
                    }
                    None
                }
                Attempt::Failed => None,
            };
            if let Some(link) = too_wide {
                stalled = 0;
                narrowest = None;
                // (The target is the kept link's: an earlier one when a longer link was kept.)
                let tgt = stack.last().map_or(tgt, |t| t.0);
                let len = scaled_dist(&cur.x, &tgt.x, &self.scales);
                let limited = self.conditioning_limited(len, link.radius_xyz);
                if self.push(link, len) {
                    return Stop::Done;
                }
                // Out of a domain on the way to a marched node: `leave.rs`.
                if let Some(end) = self.stopped_outside(&stack[0].0, stack.len() > 1) {
                    return Stop::Failed(end);
                }
                if let Some(end) = self.conditioning_end(limited, len, &cur.x, &tgt.x) {
                    return Stop::Failed(end);
                }
                cur = tgt;
                stack.pop();
                continue;
            }
            splits += 1;
            // Near a singular box a tube that several halvings in a row did not narrow is held
            // up by the conditioning there, not by the link's length: the half stops now with
            // that box, as it would after halving on down to `MIN_LINK`.
            if stalled >= STALLED_SPLITS && len < FLOOR_LINK {
                if let Some(near) = self.singular_box(&cur.x, &tgt.x, 1e-4) {
                    return Stop::Failed(CertifiedEnd::Singular { near });
                }
            }
            let long = scaled_dist(&cur.x, &tgt.x, &self.scales) > MIN_LINK;
            let frac = self.l_pred.map_or(0.5, |l| (l / len).clamp(0.1, 0.5));
            let mid = (splits <= MAX_SPLITS && long)
                .then(|| self.midpoint(&cur, &tgt, frac))
                .flatten();
            let inherited = stack.last().and_then(|t| t.1);
            match mid {
                Some(m) => stack.push((m, inherited)),
                None => return Stop::Failed(self.classify(&cur, &tgt)),
            }
        }
        Stop::Done
    }

    /// The nodes of the marched points `xs`, each velocity oriented along the march, up to the
    /// first point without a velocity (a singular point: the normals are parallel there).
    pub(super) fn nodes(&self, xs: &[[f64; 4]]) -> Vec<Node> {
        let n = xs.len();
        (0..n)
            .map_while(|i| {
                let (a, b) = if i + 1 < n {
                    (i, i + 1)
                } else {
                    (i.saturating_sub(1), i)
                };
                let dir: [f64; 4] = std::array::from_fn(|k| xs[b][k] - xs[a][k]);
                self.node(xs[i], &dir)
            })
            .collect()
    }

    /// Links from the first node to the last, skipping marched points while links hold (the
    /// stride doubles after a success and halves after a failure; a single marched interval
    /// that fails is split). The last link must also hold `closing` if given.
    pub(super) fn advance(
        &mut self,
        nodes: &[Node],
        closing: Option<&[Interval; 4]>,
    ) -> std::result::Result<(), CertifiedEnd> {
        let n = nodes.len();
        let mut i = 0;
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
            if let (true, Some(l)) = (i >= single_until, self.l_pred) {
                while i + k + 1 < n
                    && scaled_dist(&nodes[i].x, &nodes[i + k + 1].x, &self.scales) <= l
                {
                    k += 1;
                }
            }
            if let Some(r) = self.singular_reach(&nodes[i]) {
                while k > 1 && scaled_dist(&nodes[i].x, &nodes[i + k].x, &self.scales) > r {
                    k -= 1;
                }
            }
            let must = (i + k == n - 1).then_some(closing).flatten();
            if k > 1 {
                if let Some(reason) = self.out_of_budget() {
                    return Err(CertifiedEnd::Unproven {
                        reason,
                        near: point_box(&nodes[i].x),
                    });
                }
                let len = scaled_dist(&nodes[i].x, &nodes[i + k].x, &self.scales);
                let attempt = self.link(&nodes[i], &nodes[i + k], must);
                self.learn(len, &attempt);
                if let Attempt::Proven(link) = attempt {
                    let limited = self.conditioning_limited(len, link.radius_xyz);
                    if self.push(link, len) {
                        return Ok(());
                    }
                    if let Some(end) = self.stopped_outside(&nodes[i + k], false) {
                        return Err(end);
                    }
                    if let Some(end) =
                        self.conditioning_end(limited, len, &nodes[i].x, &nodes[i + k].x)
                    {
                        return Err(end);
                    }
                    i += k;
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
            if let Stop::Failed(e) = self.span(nodes[i], nodes[i + 1], must) {
                return Err(e);
            }
            if self.closed {
                return Ok(());
            }
            i += 1;
        }
        Ok(())
    }

    /// Walks the marched points `xs` (the first one is the start) and handles the marched
    /// `end`.
    pub(super) fn walk(&mut self, xs: &[[f64; 4]], end: EndReason) -> CertifiedEnd {
        let xs = &distinct(xs, &self.scales);
        // A march that ran into a pole: no link can reach it (the parameters degenerate
        // there), so the half ends where the links stop, and says why.
        let pole = match end {
            EndReason::Boundary { surface } => xs.last().and_then(|x| self.pole_at(surface, x)),
            _ => None,
        };
        self.march_at_pole = pole.is_some();
        if let (Some(_), EndReason::Boundary { surface }, Some(x)) = (&pole, end, xs.last()) {
            self.toward_pole = self.pole_end(surface, x).filter(|&e| self.runs_into(xs, e));
        }
        let nodes = self.nodes(xs);
        if end == EndReason::Singular {
            self.toward_singular = xs.last().copied();
        }
        if let Err(e) = self.advance(&nodes, None) {
            return match pole {
                Some(reason) => CertifiedEnd::Unproven {
                    reason,
                    near: self
                        .links
                        .last()
                        .map_or_else(|| point_box(&xs[0]), |l| l.end_slice),
                },
                None => e,
            };
        }
        let Some(&cur) = nodes.last() else {
            return CertifiedEnd::Unproven {
                reason: "no velocity at the start".into(),
                near: point_box(&xs[0]),
            };
        };
        if nodes.len() < xs.len() {
            // The next marched point has no velocity: a singular point. The half ends between.
            return self.singular_end(&cur, &xs[nodes.len()]);
        }
        match (end, pole) {
            // The last link's end slice: the proven box nearest the pole.
            (EndReason::Boundary { .. }, Some(reason)) => CertifiedEnd::Unproven {
                reason,
                near: self
                    .links
                    .last()
                    .map_or_else(|| point_box(&cur.x), |l| l.end_slice),
            },
            (EndReason::Boundary { surface }, None) => self.exit(cur, surface),
            (other, _) => CertifiedEnd::Unproven {
                // No proof of anything past the last marched point.
                reason: format!("the marched branch ends here ({other})"),
                near: point_box(&cur.x),
            },
        }
    }
}

/// The marched points `xs` without the ones that repeat the point before them to rounding
/// (scaled distance at most 1e-15; the march can land twice on one boundary point): no
/// coordinate runs along such a pair, so no link between them can be proven. The first and
/// the last point are kept (a repeat of the last replaces the point before it).
fn distinct(xs: &[[f64; 4]], scales: &[f64; 4]) -> Vec<[f64; 4]> {
    let mut out: Vec<[f64; 4]> = Vec::with_capacity(xs.len());
    for (k, x) in xs.iter().enumerate() {
        let kept = out.len();
        match out.last_mut() {
            Some(last) if scaled_dist(last, x, scales) <= 1e-15 => {
                if k + 1 == xs.len() && kept > 1 {
                    *last = *x;
                }
            }
            _ => out.push(*x),
        }
    }
    out
}

/// Newton onto `P = Q` with parameter `j` held at `value`: to rounding level where it converges
/// there, else (ill-conditioned, near-tangent surfaces) to the smallest of 1e-13, 1e-12, 1e-11
/// that it reaches.
pub(super) fn newton(
    p: &RationalBezierPatch,
    q: &RationalBezierPatch,
    guess: [f64; 4],
    j: usize,
    value: f64,
) -> Option<Refined> {
    let fixed = Constraint::Fixed { index: j, value };
    [1e-14, 1e-13, 1e-12, 1e-11]
        .iter()
        .find_map(|&tol| refine(p, q, guess, fixed, tol, 30).ok())
}

pub(super) fn point_box(x: &[f64; 4]) -> [Interval; 4] {
    x.map(point)
}
