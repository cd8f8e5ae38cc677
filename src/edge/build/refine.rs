//! The refinement of an edge's coarse curves: coarse spans above the target are cut at fine
//! knots (or their knots raised in multiplicity) round by round, regions that stop improving
//! are left at their level, and the knots the cuts did not need are removed again.

use super::{fit_part, ratios, Break, PartData, PartFit, Span, DEGREE, GAIN, MOST_PIECES, ROUNDS};

/// New breakpoints for a part whose fine spans need the fit `ratio` times smaller (≤ 1: fine);
/// `None` when nothing can be (or need be) refined. A coarse span of several fine spans is cut
/// at fine knots; one that cannot be cut (a single fine span, or only knots next to its ends)
/// has the multiplicity of its inner ends raised (the reported curve's links are not exactly
/// smooth at their joins: lower continuity lets the coarse curves follow them there).
fn refine(breaks: &[Break], ratio: &[f64], fine: &[f64]) -> Option<Vec<Break>> {
    let last = breaks.len() - 1;
    let mut out: Vec<Break> = breaks.to_vec();
    let mut changed = false;
    let mut add = Vec::new();
    for (w, pair) in breaks.windows(2).enumerate() {
        let ((a, _), (b, _)) = (pair[0], pair[1]);
        let r = ratio[a..b].iter().copied().fold(0.0, f64::max);
        if r <= 1.0 {
            continue;
        }
        let pieces =
            ((1.2 * r.powf(1.0 / (DEGREE + 1) as f64)).ceil() as usize).clamp(2, MOST_PIECES);
        let pieces = pieces.min(b - a);
        // Not next to the span's ends (a cut piece of a link can be very short: a knot span of
        // almost no length is of no use to the fit).
        let room = 1e-3 * (fine[b] - fine[a]);
        let mut cut = false;
        for k in 1..pieces {
            // The fine knot nearest to the k-th of `pieces` equal parts in s.
            let s = fine[a] + (fine[b] - fine[a]) * k as f64 / pieces as f64;
            let i = (a + 1..b)
                .filter(|&i| fine[i] - fine[a] > room && fine[b] - fine[i] > room)
                .min_by(|&i, &j| (fine[i] - s).abs().total_cmp(&(fine[j] - s).abs()));
            if let Some(i) = i {
                add.push((i, 1));
                cut = true;
            }
        }
        if !cut {
            for e in [w, w + 1] {
                if e != 0 && e != last && out[e].1 < DEGREE {
                    out[e].1 = (out[e].1 + 2).min(DEGREE);
                    changed = true;
                }
            }
        }
    }
    for (i, m) in add {
        if !out.iter().any(|x| x.0 == i) {
            out.push((i, m));
            changed = true;
        }
    }
    out.sort_unstable();
    changed.then_some(out)
}

/// Per part, what the refinement knows of its fine spans: the ratios for the goal before the
/// last round, the fine-span ranges of the coarse spans that round refined, and per span how
/// many refinements in a row failed to divide its region's worst ratio by [`GAIN`].
struct Progress {
    before: Vec<f64>,
    refined: Vec<std::ops::Range<usize>>,
    strikes: Vec<u8>,
    /// The lowest bound each span has proven so far.
    best: Vec<f64>,
}

/// Refinements in a row without gain after which a span is stalled.
const STRIKES: u8 = 3;

impl Progress {
    fn new(n: usize) -> Self {
        Progress {
            before: vec![0.0; n],
            refined: Vec::new(),
            strikes: vec![0; n],
            best: vec![f64::INFINITY; n],
        }
    }

    /// Scores the last round's refinements against the ratios `now` (for the goal): a refined
    /// region whose worst ratio is still above 1 and fell by less than [`GAIN`] gives a strike
    /// to its spans above 1; one that gained clears them. (A region, not a span: the fit is
    /// global, and a span next to a cut can get worse while its region gains.)
    fn score(&mut self, now: &[(f64, f64)]) {
        for (b, x) in self.best.iter_mut().zip(now) {
            *b = b.min(x.1);
        }
        let worst = |r: &std::ops::Range<usize>, f: &dyn Fn(usize) -> f64| {
            r.clone().map(f).fold(0.0, f64::max)
        };
        for r in &self.refined {
            let was = worst(r, &|m| self.before[m]);
            let is = worst(r, &|m| now[m].0);
            let gained = is <= 1.0 || is * GAIN <= was;
            for m in r.clone() {
                if gained {
                    self.strikes[m] = 0;
                } else if now[m].0 > 1.0 {
                    self.strikes[m] = self.strikes[m].saturating_add(1);
                }
            }
        }
    }

    fn stalled(&self, m: usize) -> bool {
        self.strikes[m] >= STRIKES
    }
}

/// Fits, bounds and refines every part until its spans meet the goal, none can be refined, or
/// the rounds run out. A span whose region was refined [`STRIKES`] times in a row without
/// dividing its worst ratio by [`GAIN`] is stalled: never refined again, and all the other
/// spans aim at the lowest bound it has proven instead of the goal when that is higher
/// (control points that lower them below it buy nothing). Returns whether the rounds ran out.
pub(super) fn refine_all(
    data: &[PartData],
    spans: &[Span],
    knots_s: &[f64],
    fits: &mut [PartFit],
    goal: f64,
) -> bool {
    let mut progress: Vec<Progress> = data.iter().map(|d| Progress::new(d.range.len())).collect();
    for _ in 0..ROUNDS {
        let now: Vec<Vec<(f64, f64)>> = data
            .iter()
            .zip(fits.iter())
            .map(|(d, f)| ratios(d, spans, f, goal))
            .collect();
        let mut level = 0.0f64;
        for (pr, r) in progress.iter_mut().zip(&now) {
            pr.score(r);
            for m in 0..r.len() {
                if pr.stalled(m) {
                    level = level.max(pr.best[m]);
                }
            }
        }
        let aim = goal.max(level);
        let mut changed = false;
        for ((d, f), (pr, r)) in data
            .iter()
            .zip(fits.iter_mut())
            .zip(progress.iter_mut().zip(&now))
        {
            let mut want: Vec<f64> = ratios(d, spans, f, aim).iter().map(|x| x.0).collect();
            for (m, w) in want.iter_mut().enumerate() {
                if pr.stalled(m) {
                    *w = 0.0;
                }
            }
            pr.before = r.iter().map(|x| x.0).collect();
            pr.refined.clear();
            let fine = &knots_s[d.range.start..=d.range.end];
            if let Some(b) = refine(&f.breaks, &want, fine) {
                for pair in f.breaks.windows(2) {
                    let region = pair[0].0..pair[1].0;
                    if want[region.clone()].iter().any(|&x| x > 1.0) {
                        pr.refined.push(region);
                    }
                }
                *f = fit_part(d, spans, knots_s, b);
                changed = true;
            }
        }
        if !changed {
            return false;
        }
    }
    true
}

/// Breakpoints above which [`coarsen`] is not tried (each trial is a fit of the whole part).
const COARSEN_MOST: usize = 40;

/// Removes the coarse knots the refinement did not need: refinement cuts a coarse span into
/// several pieces at once, by an estimate. Each interior breakpoint in turn is lowered in
/// multiplicity (or removed) and the part fitted and bounded again; the change is kept when
/// the part's worst bound stays within the goal (or within what it proved, if that is above
/// the goal). Only on parts of at most [`COARSEN_MOST`] breakpoints.
pub(super) fn coarsen(d: &PartData, spans: &[Span], knots_s: &[f64], f: &mut PartFit, goal: f64) {
    if f.breaks.len() > COARSEN_MOST {
        return;
    }
    let worst = |f: &PartFit| {
        ratios(d, spans, f, f64::INFINITY)
            .iter()
            .map(|x| x.1)
            .fold(0.0, f64::max)
    };
    let limit = goal.max(worst(f));
    let mut i = 1;
    while i + 1 < f.breaks.len() {
        let mut b = f.breaks.clone();
        if b[i].1 > 1 {
            b[i].1 -= 1;
        } else {
            b.remove(i);
        }
        let g = fit_part(d, spans, knots_s, b);
        if worst(&g) <= limit {
            *f = g;
        } else {
            i += 1;
        }
    }
}
