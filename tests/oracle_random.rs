//! Random patch pairs against an independent reference intersection.
//!
//! Each pair is two height fields over `[0,1]²`, P a random bicubic and Q a random bicubic or
//! biquadratic (control points `(i/m, j/m, z_ij)`, so `P(σ,t) = (σ, t, f(σ,t))` exactly), either
//! as they are or both moved by the same rotation and translation. Their intersection in the
//! parameter plane is the zero set of `f − g`, with `(σ, t) = (u, v)`. The reference is computed
//! without the code under test: on grid lines `t = const` and `σ = const` the sign changes of
//! `f − g` (sampled in f64) are refined by bisection whose signs are proven in interval
//! arithmetic (de Casteljau in `inari`), so every reference bracket provably holds a true curve
//! point.
//!
//! Checked per pair, after `ssitrace::intersect` (method `validated`; the fixed seeds assert all
//! four, fresh seeds and the soak assert soundness and tolerance and print the rest):
//! - **soundness**: a reference point near a certified branch whose two ends are proven lies in
//!   one of that branch's parameter boxes, and within the proven parameter radius of one of its
//!   tube pieces (for the rotated copies, whose control points are rounded after rotation, both
//!   are widened by 1e-12 first: the surfaces differ from the reference's by about 1e-16);
//! - **completeness**: every reference point is near a marched branch, or inside an undecided
//!   region of the search;
//! - **each arc once**: no reference point lies in the boxes of two certified branches;
//! - **useful certificates**: a certificate above the requested tolerance, or with an end that
//!   is not proven, is counted with its reason.
//!
//! `cargo test --release --test oracle_random -- --nocapture` prints the figures. The soak runs
//! the same check on many more pairs from one command (see the README): `SSITRACE_ORACLE_PAIRS=
//! 100000 cargo test --release --test oracle_random soak -- --ignored --nocapture` (options: see
//! [`soak`]; `SSITRACE_ORACLE_ENGINE=taylor` runs any of them with the Taylor engine).

mod common;

use common::rng::Rng;
use inari::{interval, Interval};
use ssitrace::geometry::{Domain, RationalBezierPatch};
use ssitrace::{intersect, Engine, Method, Options, SurfaceIntersection};
use std::time::Instant;

/// A height field `z = Σ z_ij B_i(x) B_j(y)` of degree `m` in both directions.
#[derive(Clone)]
struct HeightField {
    m: usize,
    z: Vec<f64>,
}

impl HeightField {
    fn random(rng: &mut Rng, m: usize, amplitude: f64) -> Self {
        let z = (0..(m + 1) * (m + 1))
            .map(|_| rng.uniform(-amplitude, amplitude))
            .collect();
        HeightField { m, z }
    }

    /// The height at `(x, y)` in interval arithmetic (de Casteljau, rows first).
    fn eval(&self, x: Interval, y: Interval) -> Interval {
        let one = interval!(1.0, 1.0).unwrap();
        let lerp = |c: &mut Vec<Interval>, t: Interval| {
            for r in 1..c.len() {
                for k in 0..c.len() - r {
                    c[k] = (one - t) * c[k] + t * c[k + 1];
                }
            }
            c[0]
        };
        let mut col: Vec<Interval> = (0..=self.m)
            .map(|i| {
                let mut row: Vec<Interval> = (0..=self.m)
                    .map(|j| point(self.z[i * (self.m + 1) + j]))
                    .collect();
                lerp(&mut row, y)
            })
            .collect();
        lerp(&mut col, x)
    }

    /// The patch, its control points moved by `motion` (none: as they are).
    fn patch(&self, motion: Option<&Motion>) -> RationalBezierPatch {
        let m = self.m;
        let points = (0..=m)
            .flat_map(|i| (0..=m).map(move |j| (i, j)))
            .map(|(i, j)| {
                let c = [
                    i as f64 / m as f64,
                    j as f64 / m as f64,
                    self.z[i * (m + 1) + j],
                ];
                let c = motion.map_or(c, |mo| mo.apply(c));
                c.map(point)
            })
            .collect();
        RationalBezierPatch::new([m, m], points, None, Domain::new(0.0, 1.0, 0.0, 1.0)).unwrap()
    }
}

fn point(x: f64) -> Interval {
    interval!(x, x).unwrap()
}

/// A rotation (three angles) and a translation.
struct Motion {
    r: [[f64; 3]; 3],
    c: [f64; 3],
}

impl Motion {
    fn random(rng: &mut Rng) -> Self {
        let (a, b, g) = (
            rng.uniform(0.0, 6.3),
            rng.uniform(0.0, 6.3),
            rng.uniform(0.0, 6.3),
        );
        let rz = |t: f64| {
            [
                [t.cos(), -t.sin(), 0.0],
                [t.sin(), t.cos(), 0.0],
                [0.0, 0.0, 1.0],
            ]
        };
        let rx = |t: f64| {
            [
                [1.0, 0.0, 0.0],
                [0.0, t.cos(), -t.sin()],
                [0.0, t.sin(), t.cos()],
            ]
        };
        let mul = |a: [[f64; 3]; 3], b: [[f64; 3]; 3]| {
            std::array::from_fn(|i| {
                std::array::from_fn(|j| (0..3).map(|k| a[i][k] * b[k][j]).sum())
            })
        };
        let r = mul(rz(a), mul(rx(b), rz(g)));
        let c = [
            rng.uniform(-2.0, 2.0),
            rng.uniform(-2.0, 2.0),
            rng.uniform(-2.0, 2.0),
        ];
        Motion { r, c }
    }

    fn apply(&self, x: [f64; 3]) -> [f64; 3] {
        std::array::from_fn(|i| (0..3).map(|k| self.r[i][k] * x[k]).sum::<f64>() + self.c[i])
    }
}

/// A proven reference point: the curve meets the grid line in `(x, y)`, one of the two a point
/// (`[x0, x1] × {y}` or `{x} × [y0, y1]`).
#[derive(Clone, Copy, Debug)]
struct RefPoint {
    x: [f64; 2],
    y: [f64; 2],
}

/// Reference points of `f − g = 0` on `lines` grid lines in each direction, away from the domain
/// boundary by `margin`.
fn reference(f: &HeightField, g: &HeightField, lines: usize, margin: f64) -> Vec<RefPoint> {
    let h = |x: Interval, y: Interval| f.eval(x, y) - g.eval(x, y);
    let samples = 200;
    let mut out = Vec::new();
    for k in 1..lines {
        let c = k as f64 / lines as f64;
        for along_x in [true, false] {
            let at = |s: f64| {
                if along_x {
                    (point(s), point(c))
                } else {
                    (point(c), point(s))
                }
            };
            let sign = |s: f64| {
                let (x, y) = at(s);
                let v = h(x, y);
                if v.inf() > 0.0 {
                    1
                } else if v.sup() < 0.0 {
                    -1
                } else {
                    0
                }
            };
            let mut prev = (margin, sign(margin));
            for i in 1..=samples {
                let s = margin + (1.0 - 2.0 * margin) * i as f64 / samples as f64;
                let sg = sign(s);
                if sg != 0 && prev.1 != 0 && sg != prev.1 {
                    // Bisect on proven signs: the bracket always holds a root.
                    let (mut a, mut b, sa) = (prev.0, s, prev.1);
                    for _ in 0..60 {
                        let mid = 0.5 * (a + b);
                        if mid <= a || mid >= b {
                            break;
                        }
                        match sign(mid) {
                            0 => break,
                            sm if sm == sa => a = mid,
                            _ => b = mid,
                        }
                    }
                    out.push(if along_x {
                        RefPoint {
                            x: [a, b],
                            y: [c, c],
                        }
                    } else {
                        RefPoint {
                            x: [c, c],
                            y: [a, b],
                        }
                    });
                }
                if sg != 0 {
                    prev = (s, sg);
                }
            }
        }
    }
    out
}

/// The smallest max-norm distance in `(σ, t)` between the tube piece's reported curve and the
/// reference bracket (golden-section refinement of the best of 33 samples of `τ ∈ [0, h]`).
fn tube_distance(tp: &ssitrace::certify::TubePiece, r: &RefPoint) -> f64 {
    let gap = |v: f64, b: [f64; 2]| (b[0] - v).max(v - b[1]).max(0.0);
    let d = |tau: f64| {
        let y = tp.eval(tau);
        gap(y[0], r.x).max(gap(y[1], r.y))
    };
    let n: usize = 32;
    let k = (0..=n)
        .min_by(|&a, &b| d(tp.h * a as f64 / n as f64).total_cmp(&d(tp.h * b as f64 / n as f64)))
        .unwrap_or(0);
    let (mut lo, mut hi) = (
        tp.h * k.saturating_sub(1) as f64 / n as f64,
        tp.h * (k + 1).min(n) as f64 / n as f64,
    );
    let phi = 0.5 * (5f64.sqrt() - 1.0);
    for _ in 0..90 {
        let (a, b) = (hi - phi * (hi - lo), lo + phi * (hi - lo));
        if d(a) <= d(b) {
            hi = b;
        } else {
            lo = a;
        }
    }
    d(0.5 * (lo + hi)).min(d(tp.h * k as f64 / n as f64))
}

/// Figures over a run of pairs.
#[derive(Default, Debug)]
struct Figures {
    pairs: usize,
    branches: usize,
    reference_points: usize,
    soundness_violations: usize,
    missed_points: usize,
    in_undecided: usize,
    not_certified: usize,
    twice: usize,
    above_tolerance: usize,
    unproven_ends: usize,
    times: Vec<f64>,
    notes: Vec<String>,
    /// Pairs with at least one of each failure (the closing notes count pairs, not points).
    pairs_with: PairsWith,
}

/// Per failure class, how many pairs had it at least once.
#[derive(Default, Debug)]
struct PairsWith {
    soundness: usize,
    missed: usize,
    twice: usize,
    above_tolerance: usize,
    unproven_ends: usize,
    not_certified: usize,
}

fn params_distance(b: &ssitrace::march::branch::Branch, r: &RefPoint) -> f64 {
    let (x, y) = (0.5 * (r.x[0] + r.x[1]), 0.5 * (r.y[0] + r.y[1]));
    b.points
        .iter()
        .map(|p| (p.p[0] - x).hypot(p.p[1] - y))
        .fold(f64::INFINITY, f64::min)
}

/// The certification engine: the default, or `SSITRACE_ORACLE_ENGINE=taylor` (for comparing
/// the two engines on the same seeds).
fn engine() -> Engine {
    match std::env::var("SSITRACE_ORACLE_ENGINE").as_deref() {
        Ok("taylor") => Engine::Taylor,
        Ok("chain") => Engine::Chain,
        _ => Engine::default(),
    }
}

fn check_pair(seed: u64, fig: &mut Figures) {
    let before = (
        fig.soundness_violations,
        fig.missed_points,
        fig.twice,
        fig.above_tolerance,
        fig.unproven_ends,
        fig.not_certified,
    );
    check_pair_inner(seed, fig);
    let w = &mut fig.pairs_with;
    w.soundness += usize::from(fig.soundness_violations > before.0);
    w.missed += usize::from(fig.missed_points > before.1);
    w.twice += usize::from(fig.twice > before.2);
    w.above_tolerance += usize::from(fig.above_tolerance > before.3);
    w.unproven_ends += usize::from(fig.unproven_ends > before.4);
    w.not_certified += usize::from(fig.not_certified > before.5);
}

fn check_pair_inner(seed: u64, fig: &mut Figures) {
    let mut rng = Rng::new(seed);
    let f = HeightField::random(&mut rng, 3, 0.3);
    let degree = if rng.uniform(0.0, 1.0) < 0.5 { 2 } else { 3 };
    let g = HeightField::random(&mut rng, degree, 0.3);
    let motion = (seed % 2 == 1).then(|| Motion::random(&mut rng));
    let widen = if motion.is_some() { 1e-12 } else { 0.0 };
    let (p, q) = (f.patch(motion.as_ref()), g.patch(motion.as_ref()));
    let opts = Options {
        method: Method::Validated,
        engine: engine(),
        ..Options::default()
    };
    let clock = Instant::now();
    let result: SurfaceIntersection = intersect(&p, &q, &opts).expect("valid options");
    fig.times.push(clock.elapsed().as_secs_f64());
    fig.pairs += 1;
    fig.branches += result.branches.len();
    let required = opts.required_tolerance;
    for b in &result.branches {
        match b.certified() {
            Some(c) => {
                if c.certified_tolerance > required {
                    fig.above_tolerance += 1;
                    fig.notes.push(format!(
                        "seed {seed} branch {}: tolerance {:e}",
                        b.id(),
                        c.certified_tolerance
                    ));
                }
                if c.ends
                    .iter()
                    .any(|e| e.kind() == "unproven" || e.kind() == "singular")
                {
                    fig.unproven_ends += 1;
                    fig.notes.push(format!(
                        "seed {seed} branch {}: ends {} / {}",
                        b.id(),
                        c.ends[0],
                        c.ends[1]
                    ));
                }
            }
            None => fig.not_certified += 1,
        }
    }
    let refs = reference(&f, &g, 16, 1e-3);
    fig.reference_points += refs.len();
    for r in &refs {
        let inside = |c: &ssitrace::certify::CertifiedBranch| {
            c.boxes.iter().any(|bx| {
                let (s, t) = (bx.p[0], bx.p[1]);
                s.inf() - widen <= r.x[1]
                    && r.x[0] <= s.sup() + widen
                    && t.inf() - widen <= r.y[1]
                    && r.y[0] <= t.sup() + widen
            })
        };
        let holders: Vec<usize> = result
            .branches
            .iter()
            .filter(|b| b.certified().is_some_and(&inside))
            .map(|b| b.id())
            .collect();
        // The step boxes are hulls of whole steps; the tubes are the tight claim: some tube piece
        // of a holding branch must pass within its proven radius of the reference point.
        let on_tube = result
            .branches
            .iter()
            .filter(|b| holders.contains(&b.id()))
            .any(|b| {
                b.certified().is_some_and(|c| {
                    c.tubes
                        .iter()
                        .any(|tp| tube_distance(tp, r) <= tp.radius_param + widen + 1e-15)
                })
            });
        if !holders.is_empty() && !on_tube {
            fig.soundness_violations += 1;
            fig.notes.push(format!(
                "seed {seed}: reference point {r:?} off every certified tube"
            ));
        }
        if holders.len() > 1 {
            fig.twice += 1;
            fig.notes.push(format!(
                "seed {seed}: reference point {r:?} in branches {holders:?}"
            ));
        }
        if !holders.is_empty() {
            continue;
        }
        let near = result
            .branches
            .iter()
            .filter(|b| params_distance(&b.marched, r) < 0.02)
            .collect::<Vec<_>>();
        if near.is_empty() {
            let undecided = result.undecided_regions().iter().any(|u| {
                u.p[0][0] <= r.x[1]
                    && r.x[0] <= u.p[0][1]
                    && u.p[1][0] <= r.y[1]
                    && r.y[0] <= u.p[1][1]
            });
            if undecided {
                fig.in_undecided += 1;
            } else {
                fig.missed_points += 1;
                fig.notes
                    .push(format!("seed {seed}: reference point {r:?} on no branch"));
            }
            continue;
        }
        // Near a marched branch but in no certified box: a violation if that branch's certificate
        // claims both ends proven (it then covers its whole component).
        let claimed = near.iter().any(|b| {
            b.certified().is_some_and(|c| {
                c.ends
                    .iter()
                    .all(|e| e.kind() == "boundary" || e.kind() == "closed_loop")
            })
        });
        if claimed {
            fig.soundness_violations += 1;
            fig.notes.push(format!(
                "seed {seed}: reference point {r:?} outside the certified boxes"
            ));
        }
    }
}

fn run(seeds: impl Iterator<Item = u64>) -> Figures {
    run_with_progress(seeds, 0)
}

/// The figures line: counts of points / branches, then of pairs per class, then times.
fn print_figures(fig: &Figures) {
    let mut times = fig.times.clone();
    times.sort_by(f64::total_cmp);
    let median = times.get(times.len() / 2).copied().unwrap_or(0.0);
    let worst = times.last().copied().unwrap_or(0.0);
    let total: f64 = times.iter().sum();
    println!(
        "pairs {} branches {} reference points {} | soundness violations {} | missed {} | in undecided regions {} | arcs twice {} | above tolerance {} | unproven or singular ends {} | not certified {} | time median {:.3} s worst {:.3} s",
        fig.pairs, fig.branches, fig.reference_points, fig.soundness_violations, fig.missed_points,
        fig.in_undecided, fig.twice, fig.above_tolerance, fig.unproven_ends, fig.not_certified, median, worst
    );
    let w = &fig.pairs_with;
    println!(
        "  pairs with: soundness violations {} | missed points {} | arcs twice {} | above tolerance {} | unproven or singular ends {} | uncertified branches {} | total time {:.1} s",
        w.soundness, w.missed, w.twice, w.above_tolerance, w.unproven_ends, w.not_certified, total
    );
}

/// Runs the pairs; with `every > 0`, prints the figures so far after every `every` pairs (a long
/// soak can then be cut short and still report).
fn run_with_progress(seeds: impl Iterator<Item = u64>, every: usize) -> Figures {
    let mut fig = Figures::default();
    for seed in seeds {
        check_pair(seed, &mut fig);
        if every > 0 && fig.pairs % every == 0 {
            print!("[after seed {seed}] ");
            print_figures(&fig);
        }
    }
    print_figures(&fig);
    let shown = std::env::var("SSITRACE_ORACLE_NOTES")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(20usize);
    for n in fig.notes.iter().take(shown) {
        println!("  {n}");
    }
    fig
}

/// What every pair must satisfy: no certified claim is false, no certificate misses the
/// requested tolerance. Fresh seeds and the soak check this; the rarer topology failures that a
/// long soak still finds (a loop traced as two branches, a point on no branch: about 0.1 % of
/// pairs, see the closing notes) are printed, not asserted, so a fresh seed cannot fail CI on a
/// known open problem. The fixed seeds assert everything.
fn assert_sound(fig: &Figures) {
    assert_eq!(fig.soundness_violations, 0, "{:?}", fig.notes);
    assert_eq!(fig.above_tolerance, 0, "{:?}", fig.notes);
    assert!(
        fig.reference_points > fig.pairs,
        "too few reference points to mean anything"
    );
}

fn assert_clean(fig: &Figures) {
    assert_eq!(fig.soundness_violations, 0, "{:?}", fig.notes);
    assert_eq!(fig.missed_points, 0, "{:?}", fig.notes);
    assert_eq!(fig.twice, 0, "{:?}", fig.notes);
    assert_eq!(fig.above_tolerance, 0, "{:?}", fig.notes);
    assert!(
        fig.reference_points > fig.pairs,
        "too few reference points to mean anything"
    );
}

/// Seeds `first..first + count`, split over tests so the harness runs them on both cores.
fn fixed(first: u64, count: u64) {
    let fig = run(first..first + count);
    assert_clean(&fig);
}

#[test]
fn random_pairs_fixed_seeds_0() {
    fixed(0, 250);
}

#[test]
fn random_pairs_fixed_seeds_1() {
    fixed(250, 250);
}

#[test]
fn random_pairs_fixed_seeds_2() {
    fixed(500, 250);
}

#[test]
fn random_pairs_fixed_seeds_3() {
    fixed(750, 250);
}

/// Pairs the soak found with an arc traced twice: the marcher jumped between two curves at a
/// near-crossing and went on along a curve another branch had traced (seed 1 000 188: three
/// branches for two curves; its chain ends `close_branches` at the jump; 1 000 630: the chain
/// follows the true curve away from the marched points and ends unproven; 1 001 128: the near
/// crossing looks singular). The jumping branch is now dropped as a duplicate (its marched
/// points all lie in the other branches' certified tubes), and every arc is traced once.
#[test]
fn arcs_traced_twice_at_near_crossings_are_reported_once() {
    let fig = run([1_000_188, 1_000_630, 1_001_128].into_iter());
    assert_clean(&fig);
}

/// Fresh pairs on every run (the seed is printed, so a failure can be replayed with
/// `SSITRACE_ORACLE_SEED`).
#[test]
fn random_pairs_fresh_seeds() {
    let base = std::env::var("SSITRACE_ORACLE_SEED")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or_else(|| {
            std::time::SystemTime::now()
                .duration_since(std::time::UNIX_EPOCH)
                .map_or(1, |d| d.as_nanos() as u64)
        });
    println!("fresh seeds from {base} (replay: SSITRACE_ORACLE_SEED={base})");
    let fig = run((0..40).map(|k| base.wrapping_add(k)));
    assert_sound(&fig);
}

/// The long soak: `SSITRACE_ORACLE_PAIRS` pairs (default 100 000) from seed
/// `SSITRACE_ORACLE_FIRST` (default 1 000 000) on; `SSITRACE_ORACLE_PROGRESS=k` prints the figures
/// so far every `k` pairs, `SSITRACE_ORACLE_NOTES=k` prints the first `k` notes (default 20).
#[test]
#[ignore = "soak: run by hand, see the module doc"]
fn soak() {
    let n = std::env::var("SSITRACE_ORACLE_PAIRS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(100_000u64);
    let first = std::env::var("SSITRACE_ORACLE_FIRST")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(1_000_000u64);
    let every = std::env::var("SSITRACE_ORACLE_PROGRESS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(0usize);
    let fig = run_with_progress(first..first + n, every);
    assert_sound(&fig);
}
