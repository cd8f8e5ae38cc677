//! Per example scene: every branch certified (default `CertifyOptions`, the pipeline's
//! arc-length budget of 1.5 × the marched length) next to the marcher on the same branches, and
//! where a certified step spends its time.
//!
//! Before the criterion groups run, one line per scene is printed with the measured ratio
//! certified / marched and the per-step split: the validated step (its Taylor work divided
//! between the expansion over the initial box, which also predicts the step, and phase I, the
//! a-priori box and its remainder; phase II is off on re-anchored thin boxes), the re-anchoring
//! (Krawczyk), the model-space boxes and tubes, and the loop-closing test. Fig. 7 is represented
//! by its smallest loop (one iteration takes seconds). Under load from other processes
//! the ratios printed here (one process, back to back) mean more than the absolute times.
//!
//! **What sizes a certified step** (measured with this bench, order 20, 2026-12): the last
//! columns print the mean step `h` and, relative to it, two radii summed by the integrator
//! ([`ssitrace::validated::IntegratorWork`]): the root-test radius of the Taylor coefficients at
//! the (thin) start box, about the solution's own radius of convergence, and `‖y_k([ỹ])‖^{−1/k}`
//! of the validated remainder over the a-priori box. The step is about 1/5 of the latter on
//! every scene (`(ε/C)^{1/k}` with the term target ε), while the former is 7–50 × `h`:
//! sphere 25×, bicubic 7×, S31/S32 13×, Fig. 7 50× (loops 0.036 apart). So the step is sized
//! by the interval Taylor coefficients over the a-priori box, not by the curve's own series:
//! that box spans the step in every parameter (the curve moves diagonally), so on close
//! branches it reaches towards the singular set of the normalised field between them, and its
//! coefficients grow as if the radius were 10× smaller (Fig. 7: 0.013–0.028 against 0.15–0.26).
//! A larger ε only helps as `ε^{1/k}` (and the re-anchoring's arc-length error grows with ε);
//! an a-priori enclosure thin across the curve (Taylor models in time) is what would lift it.
//!
//! **What a chain-engine run spends its time on** (default engine, `perf record` of the whole
//! `ssitrace trace SCENE --method validated` process, 2026-12): on the cylinders about 80 % is
//! the link proofs (`certify::segment::prove_segment`: the residual series of both patches along
//! the predictor 35 %, the Jacobian series 26 %, the Hessian box 5 %), and half of all samples
//! were `inari`'s interval product, whose sign classification mispredicts in series products;
//! search, march, straying check and output share the other 20 %. A third of the link attempts
//! were wasted at the tangency: strides to the last marched point (next to the singular point)
//! that failed on every halving of the approach, and halvings below 1e-6 that no longer
//! narrowed the tube. The branch-free product (`numeric::imul`) and the chain's two rules for
//! those attempts took the cylinders from 37 to 16 ms of task-clock, Viviani from 66 to 30 ms,
//! with the same certificates. On Viviani the search (loop exclusion, edge search) is a quarter
//! of the run; on the tangential pair the Taylor recurrences of the contact trace are.
//!
//! **Certified / marched on the same branches** (this bench's first lines, 2026-12-02, the
//! fastest of 9 runs each, other processes paused; the build of the session's start against
//! this one, run alternately twice, the range of both runs):
//!
//! | scene | links before → after | ratio before | ratio after | final |
//! |---|---|---|---|---|
//! | sphere_patch_plane | 245 → 111 | 13–16 | 5.5–5.7 | 108, 7.1 |
//! | bicubic_transversal | 21 → 21 | 10–12 | 5.3–5.7 | 21, 5.5 |
//! | two_loops_s31_s32 | 445 → 293 | 8.8 | 3.4–3.5 | 265, 3.1 |
//! | Fig. 7, smallest loop | 180 → 123 | 83–85 | 20 | 119, 19.4 |
//! | small_loop | 54 → 44 | 4.0–4.4 | 2.2–2.3 | 42, 2.3 |
//! | Fig. 7, three loops | 542 → 380 | 70–84 | 20 | 364, 19.8 |
//! | cylinders | 151 → 156 | 21–27 | 22 | 156, 22.4 |
//! | cylinders_full | 265 → 251 | 38–41 | 30 | 251, 31.2 |
//! | viviani | 167 → 168 | 22–23 | 23.5 | 168, 23.2 |
//!
//! (The last column, links and ratio, is one run after the links were set to aim at half the
//! tolerance instead of a third, `Walker::learn`.)
//!
//! What changed: (1) a link's model-space box comes from its own proof (each surface's Taylor
//! form along the predictor plus the mean-value change over the offsets, and the centred form
//! over the link's parameter box), not from the sub-patch nets of both patches over the box
//! (`geometry::enclosure::restrict_net` had been 40–60 % of the chain on Fig. 7); (2) the
//! residual's range over a link is the hull of its Bernstein coefficients on the two halves of
//! the link: it vanishes to third order at both ends like `(τ² − r²)³`, which Horner's rule
//! bounded 8 times too wide (the tube was 8.5 times the predictor's true deviation on every
//! Fig. 7 link, now 1.0), so links are now as long as the quintic predictor's own error allows;
//! (3) the power-basis form puts the affine series of the along coordinate inside Horner's rule.
//!
//! The goal of ≤ 10 holds on the sphere, the bicubic pair, S31/S32 and the small loop. On Fig. 7
//! a link costs about 55 µs (a degree-6 patch) and the links are limited by the quintic
//! predictor's error (`∝ L⁶`), about one marched interval each; a septic Hermite predictor
//! (third derivatives at the nodes, from one more series evaluation) would allow links about
//! 2.5 times longer at the same tolerance, but the edges (`src/edge`) read the tube pieces as
//! quintics. On the cylinders and Viviani two thirds of the link attempts are spent on the
//! approach to the tangential points, where the marched points halve their distance to the
//! point and the tube is held up by the conditioning, not the length.
//!
//! **Stop 19** (same bench, session-start build against the final one, run alternately twice,
//! the range of both runs; a soak ran at the lowest priority beside them):
//!
//! | scene | links before → after | ratio before | ratio after |
//! |---|---|---|---|
//! | sphere_patch_plane | 108 → 108 | 4.5–10.4 | 5.1–5.6 |
//! | bicubic_transversal | 21 → 11 | 5.4–6.2 | 2.6–2.8 |
//! | two_loops_s31_s32 | 265 → 249 | 4.4–6.2 | 2.8–2.9 |
//! | Fig. 7, smallest loop | 119 → 119 | 25.7–26.7 | 16.5–16.7 |
//! | small_loop | 42 → 40 | 3.4–3.6 | 1.9–2.2 |
//! | Fig. 7, three loops | 364 → 364 | 20.4–21.4 | 17.4–17.7 |
//! | cylinders | 156 → 84 | 18.3–19.2 | 7.9–12.1 |
//! | cylinders_full | 251 → 185 | 44.7–45.4 | 20.8–31.3 |
//! | viviani | 168 → 80 | 27.3–29.4 | 12.4–13.0 |
//!
//! What changed: towards a singular point a link spans two marched intervals (a link from
//! distance `r` reaches `r/4`, not `r/8`) and the half ends once a short link is held up by the
//! conditioning (wider than the aim although the longer link before it was narrower, a
//! singular box within four lengths) instead of creeping on with links as wide; a link may be
//! three times as long as the last proven one (was two); the Jacobian series forms the
//! partials alone and the Hessian comes from the centred power form; the end slice is narrowed
//! by Krawczyk only for kept links. A septic Hermite predictor (third derivatives at the nodes,
//! Taylor form of order 8) was measured and not landed: Fig. 7 364 → 254 links and ratio about
//! 12, cylinders_full 136 links, but with it one shell edge (sphere against the cube, two fine
//! spans per link) had a true point 7.7e-5 from the curve by the test's search, not yet
//! explained.
//!
//! **Stop 20: a machine without AVX-512** (AMD EPYC, Zen 3; certified ms / ratio, the build of
//! the session's start against the final one, run alternately twice, both runs within 1 %).
//! Here `inari` switched the rounding mode (two `ldmxcsr`) around every interval operation, and
//! its product branched on the operands' signs; `numeric::imul`'s branch-free product needs
//! AVX-512. A profile of Fig. 7 had 41 % of its samples in `inari`'s product. The vendored
//! `inari` (`vendor/inari/PATCHED.md`) rounds `+`, `−` and `×` from their exact errors (two-sum,
//! fused multiply-add) with the same results bit for bit, forms the four corner products
//! without branches, and inlines the three.
//!
//! | scene | links | certified ms before → after | ratio before → after |
//! |---|---|---|---|
//! | sphere_patch_plane | 108 | 16.7 → 5.9 | 24.8 → 8.6 |
//! | bicubic_transversal | 11 | 2.76 → 0.96 | 12.1 → 4.2 |
//! | two_loops_s31_s32 | 249 | 23.6 → 8.6 | 11.5 → 4.2 |
//! | Fig. 7, smallest loop | 119 | 62.1 → 17.4 | 110 → 31 |
//! | small_loop | 40 | 4.07 → 1.67 | 6.8 → 2.8 |
//! | Fig. 7, three loops | 364 | 191.6 → 53.4 | 111 → 31 |
//! | cylinders | 84 | 19.7 → 6.4 | 51 → 16.6 |
//! | cylinders_full | 190 | 73.1 → 22.7 | 123 → 38 |
//! | viviani | 80 | 22.1 → 7.1 | 46 → 15 |
//!
//! The marched times match those measured on the AVX-512 machine before; a certified link here
//! still costs about twice as much (Fig. 7's loop: 146 µs against 72 µs), and so the ratios
//! are about twice those above. The septic predictor was measured again here and again not
//! landed: fewer links on long smooth branches (Fig. 7 364 → 303, S31/S32 249 → 118; certified
//! time −12 % and −24 %) but each link costs about 20 % more (order 8), and near tangential
//! points, where the links are held up by the conditioning, the third derivatives make the
//! predictor worse (small loop 40 → 56 links, +37 %; Viviani +17 %).
//!
//! **Stop 22: an AVX-512 machine** (Intel Xeon, 2 cores; certified ms / ratio, the build of the
//! session's start against the final one, run alternately twice, the range of both runs; the
//! machine ran about 10 % slower in the second pair):
//!
//! | scene | links before → after | certified ms before → after | ratio before → after |
//! |---|---|---|---|
//! | sphere_patch_plane | 108 → 108 | 2.45–2.54 → 2.17–2.20 | 5.3–5.4 → 4.6–4.7 |
//! | bicubic_transversal | 11 → 11 | 0.48–0.50 → 0.34–0.37 | 3.0 → 2.0–2.4 |
//! | two_loops_s31_s32 | 249 → 249 | 3.92–4.03 → 3.62–3.89 | 2.8 → 2.6–2.7 |
//! | Fig. 7, smallest loop | 119 → 119 | 7.58–7.59 → 6.38–6.81 | 17.0–17.2 → 15.1–15.3 |
//! | small_loop | 40 → 40 | 0.89 → 0.80–0.95 | 2.1 → 1.9–2.1 |
//! | Fig. 7, three loops | 364 → 365 | 22.7–23.5 → 19.9–23.6 | 17.4–17.5 → 15.3–17.5 |
//! | cylinders | 84 → 82 | 3.02–3.10 → 2.43–2.67 | 11.1–11.2 → 9.0–9.3 |
//! | cylinders_full | 190 → 173 | 9.76–9.91 → 6.46–7.63 | 23.3–23.7 → 15.7–17.1 |
//! | viviani | 80 → 76 | 3.31–3.32 → 2.16–2.42 | 10.2 → 6.3–7.5 |
//!
//! What changed: rational patches (every quadric here: the sphere, the cylinders, Viviani's
//! pair) get the centred power form of `certify::lean_patch` too, in homogeneous coordinates
//! with one division; their Bernstein form had been 40 % of a chain on the cylinders (`perf`,
//! `RationalBezierPatch::eval` along the predictor).
//!
//! Measured and not landed: links that end between two marched nodes where the learnt length
//! reaches past one (10–18 % fewer links, 5–8 % less chain time), because the links then all
//! come out near the aim (half the tolerance) and leave the B-rep edges less room for their fit:
//! Fig. 7's edges at 1e-9 grew from 233, 283, 242 to 426, 369, 427 control points, the bicubic
//! edge at 1e-7 from 26 to 40 (`scripts/edge_size_table.py`). Also measured and not landed: the
//! Jacobian's Taylor form one order lower (cylinders_full 155 → 181 links), the residual's form
//! at other orders (order 7 is where Fig. 7's links stop being limited by the remainder: 717,
//! 484, 365, 365 links at orders 5, 6, 7, 8; higher orders only cost), aiming the links at 0.7
//! of the tolerance instead of 0.5 (more wide links than saved), series products skipping known
//! zero coefficients (no measurable change), two partial sums in a series product (none), and
//! the tight end slice on the lean forms (3–14 % slower: for Krawczyk's few evaluations over a
//! box the power form's partials cost more than the patch's own).
//!
//! Fig. 7 stays above 10: its links are limited by the quintic predictor's error (`∝ L⁶`) at
//! the tolerance, one marched interval each, about 55 µs each (a degree-6 patch: the residual
//! series costs two Horner evaluations of 49 coefficients, at the centre and over the link, and
//! the Jacobian two more). Longer links need a predictor of higher order with a residual form
//! of higher order, and room left for the edges' fit.
//!
//! Whole runs (`scripts/speed_table.py`, the same machine, median of five): Fig. 7 82 → 62 ms,
//! the tangential pair 106 → 85 ms, concentric circles 135 → 116 ms, cylinders_full 20 → 15 ms,
//! Viviani 19 → 15 ms. Besides the chain: a de Casteljau step that copied the next control
//! point by value compiled to overlapping stack stores, a store-forwarding stall per step
//! (`Piece::split` was 22 % of Fig. 7's run, now 3 %; the same in the contact cover's
//! `restrict_curve`), and on AVX-512 every interval product skips inari's sign cases
//! (`vendor/inari/PATCHED.md`).
//!
//! **Stop 23, the same machine** (the session's start build against the final one, `chain:`
//! lines of two runs each, the range of both):
//!
//! | scene | links before → after | certified ms before → after | ratio before → after |
//! |---|---|---|---|
//! | sphere_patch_plane | 108 → 108 | 2.18–2.27 → 1.85–1.86 | 4.9 → 3.9–4.0 |
//! | bicubic_transversal | 11 → 11 | 0.34–0.60 → 0.27 | 2.1–3.7 → 1.6 |
//! | two_loops_s31_s32 | 249 → 251 | 3.71–3.79 → 3.07–3.28 | 2.6–2.7 → 2.3 |
//! | Fig. 7, smallest loop | 119 → 119 | 6.57–6.63 → 4.42–4.83 | 14.9–15.6 → 10.9–11.2 |
//! | small_loop | 40 → 40 | 0.87–0.95 → 0.67–0.72 | 2.0–2.3 → 1.7 |
//! | Fig. 7, three loops | 365 → 366 | 20.3–20.6 → 13.9–15.1 | 15.7–16.0 → 11.0–11.5 |
//! | cylinders | 82 → 81 | 2.40–2.54 → 1.94–1.95 | 8.8–9.4 → 7.5 |
//! | cylinders_full | 173 → 173 | 6.35–6.45 → 5.24–5.45 | 15.2–15.4 → 12.9–13.6 |
//! | viviani | 76 → 76 | 2.23–2.32 → 1.84–1.86 | 6.8–7.0 → 5.6–5.9 |
//!
//! What changed: (1) Fig. 7's links were graphed over the plane's coordinates (they move a
//! little faster), so the degree-6 patch was evaluated along the predictor with both of its
//! arguments full series. A link now takes the costlier patch's coordinate when it is at least
//! half as fast; that argument is then an affine series, Horner's rule puts it inside, and the
//! series products skip its exact zero coefficients. (2) A series' length was a byte after the
//! coefficients; copies of a series then read it through overlapping stores (a store-forwarding
//! stall). (3) A series division multiplies by one enclosure of `1/b₀` instead of dividing every
//! coefficient. (4) A kept link's end slice is narrowed by Krawczyk only when the link is wider
//! than a quarter of the tolerance, or when a link from it fails or comes out too wide (without
//! that, a torus crossing of the random oracle certified at 1.12e-9 for 1e-9: short links from
//! a loose join were split without narrowing).
//!
//! Series arithmetic in midpoint–radius form (`validated::midrad`: round-to-nearest `f64` with
//! every rounding error bounded into the radius, four fused multiply-adds per product term) is
//! used by the link proofs only without AVX-512. On this machine it is 0–4 % slower than
//! inari's intervals, whose AVX-512 products round in the instruction; built for AVX2
//! (`-Ctarget-cpu=haswell`, where inari switches the rounding mode around each operation) it
//! takes 27 % off Fig. 7's chain, 20 % off cylinders_full's, 17 % off Viviani's and 12 % off
//! the sphere's (the probe's single-thread chains, 10 runs each, two alternations).
//!
//! **Stop 24, the same machine** (the session's start build against the final one, run
//! alternately two to five times; ratio ranges):
//!
//! | scene | links start → final | ratio start | ratio final |
//! |---|---|---|---|
//! | sphere_patch_plane | 108 → 50 | 4.1–4.2 | 2.9–3.0 |
//! | bicubic_transversal | 11 → 11 | 1.7–1.8 | 1.9–3.4 (a 0.3 ms chain) |
//! | two_loops_s31_s32 | 251 → 118 | 2.3–2.4 | 1.9 |
//! | Fig. 7, smallest loop | 119 → 86 | 11.2–11.3 | 8.7–8.8 |
//! | small_loop | 40 → 56 | 1.9–2.0 | 2.3–2.4 |
//! | Fig. 7, three loops | 366 → 305 | 11.3–11.5 | 9.4–9.6 |
//! | cylinders | 81 → 65 | 7.5–8.0 | 7.8–9.1 |
//! | cylinders_full | 173 → 124 | 13.7–13.9 | 9.5–9.9 |
//! | viviani | 76 → 68 | 6.2–7.1 | 6.7–7.8 |
//!
//! What changed: (1) the predictor is the septic Hermite interpolant (values and three
//! derivatives at both ends; the third derivative by a central difference of the second along
//! the curve's quadratic graph, two more `f64` patch evaluations per end, since a series
//! evaluation of the Bernstein form cost 12 % of Fig. 7's chain), the Taylor form is of order 8
//! (order 9: 226 links on Fig. 7 but 20 % slower; order 7: cylinders_full 155 links) and the next
//! link's length is learnt with the `L⁸` rule (`L⁶`: Fig. 7 257 links but six times the too-wide
//! attempts). (2) What limited cylinders_full was its eight node ends, not the predictor: the
//! marcher's last step lands near the node, each link reaching more than about 0.8 of the
//! distance to it failed to contract and was halved (one failed attempt per halving), and the
//! start chosen near the node made the half away from it begin with four failed links. Links
//! towards a marched singular end are now split untried at 0.8 of the distance, and a branch
//! with such an end starts half way along its marched length (its two halves run at the same
//! time): 139 → 124 links, no failed attempt left on the short arcs. On the single-node
//! `cylinders` scene that start costs a little (its start was already well placed).
//!
//! **Stop 25, the same machine** (the session's start build against the final one, two
//! alternations, `chain:` lines; certified / marched):
//!
//! | scene | links | ratio start | ratio final |
//! |---|---|---|---|
//! | sphere_patch_plane | 50 | 3.0–3.1 | 2.5–2.6 |
//! | bicubic_transversal | 11 | 1.9 | 1.8 |
//! | two_loops_s31_s32 | 118 | 1.9 | 1.5 |
//! | Fig. 7, smallest loop | 86 | 8.6 | 4.6–4.8 |
//! | small_loop | 56 | 2.2 | 1.7–1.8 |
//! | Fig. 7, three loops | 305 | 9.4–9.5 | 4.9 |
//! | cylinders | 65 | 8.0–9.0 | 7.8 |
//! | cylinders_full | 124 | 9.7–10.2 | 8.3 |
//! | viviani | 68 | 6.7–7.7 | 6.0 |
//!
//! What changed (same links, same certificates but for a few ulps): (1) a link's patch forms
//! are truncated to its window (`certify::lean_patch`): a term whose size over the window is
//! below 2⁻⁶⁰ of its coordinate's largest, or holds zero and is below 2⁻⁴⁰ of it, goes into a
//! rigorous bound added to the value, and a tube outside the window is proven again on the
//! whole forms. Fig. 7's degree-6 height field wrote `x = u` and `y = v` with 49 terms each
//! (44 of them intervals of width 1e-16 round zero, from rounding the Bernstein net) and `z`
//! with 49 where its total degree needs 28: every one was a series product. (2) The chain
//! rule's factors `1/Δu`, `1/Δv` are folded into the forms, not multiplied at every
//! evaluation. (3) The remainder's Bernstein hull takes its ratios `C(i,k)/C(n,k)` from a table
//! (it divided 60 intervals per link), the predictor's shift its binomials, and the shifted
//! coefficients are made once per link, not once per series. (4) Adding a shorter series (a
//! constant) touches only its terms.
//!
//! The group `halves` times the open bicubic branch with its two halves one after the other and
//! on two threads (`CertifyOptions::parallel_halves`).
//!
//! `cargo bench --bench scenes`; `SSITRACE_BENCH_ORDERS=12,14,16,20` also prints the split at
//! those Taylor orders.

// criterion_group!/criterion_main! generate undocumented functions.
#![allow(missing_docs)]

mod common;

use common::fastest;
use criterion::{criterion_group, criterion_main, Criterion};
use ssitrace::certify::budget::StepBudget;
use ssitrace::certify::{
    certify_branch_profiled, certify_chain, CertifyOptions, ChainOptions, TraceProfile,
};
use ssitrace::geometry::RationalBezierPatch;
use ssitrace::io::scene::Scene;
use ssitrace::march::branch::Branch;
use ssitrace::march::{trace_branch, MarchOptions};
use ssitrace::solve::{intersect, Method, Options, LENGTH_BUDGET_FACTOR};
use std::hint::black_box;
use std::path::Path;
use std::time::Instant;

/// One branch to certify: its start (the middle marched point), its arc-length budget and the
/// marched branch (the chain engine's guide).
struct Job {
    start: [f64; 4],
    max_length: f64,
    branch: Branch,
}

struct Case {
    name: &'static str,
    scene: Scene,
    jobs: Vec<Job>,
}

fn case(name: &'static str, file: &str, smallest_only: bool) -> Case {
    let scene = Scene::from_path(Path::new(file)).expect("scene");
    let [p, q] = &scene.surfaces;
    let opts = Options {
        method: Method::March,
        step: scene.options.step,
        ..Options::default()
    };
    let marched = intersect(p, q, &opts).expect("march");
    let mut jobs: Vec<Job> = marched
        .branches
        .iter()
        .map(|t| &t.marched)
        .filter(|b| !b.points.is_empty())
        .map(|b| {
            let pt = b.points[b.points.len() / 2];
            Job {
                start: [pt.p[0], pt.p[1], pt.q[0], pt.q[1]],
                max_length: LENGTH_BUDGET_FACTOR * b.length(),
                branch: b.clone(),
            }
        })
        .collect();
    if smallest_only {
        jobs.sort_by(|a, b| a.max_length.total_cmp(&b.max_length));
        jobs.truncate(1);
    }
    Case { name, scene, jobs }
}

fn certify_all(
    p: &RationalBezierPatch,
    q: &RationalBezierPatch,
    jobs: &[Job],
    order: usize,
) -> (usize, f64, TraceProfile) {
    certify_with(p, q, jobs, order, false)
}

fn certify_with(
    p: &RationalBezierPatch,
    q: &RationalBezierPatch,
    jobs: &[Job],
    order: usize,
    parallel_halves: bool,
) -> (usize, f64, TraceProfile) {
    let mut prof = TraceProfile::default();
    let (mut steps, mut tol) = (0, 0.0f64);
    for j in jobs {
        let opts = CertifyOptions {
            steps: StepBudget {
                max_length: j.max_length,
                order,
                ..StepBudget::CERTIFY
            },
            parallel_halves,
            ..CertifyOptions::default()
        };
        if let Ok((b, pr)) = certify_branch_profiled(p, q, black_box(j.start), &opts) {
            steps += b.steps();
            tol = tol.max(b.certified_tolerance);
            prof.step_seconds += pr.step_seconds;
            prof.anchor_seconds += pr.anchor_seconds;
            prof.enclosure_seconds += pr.enclosure_seconds;
            prof.closing_seconds += pr.closing_seconds;
            prof.integrator += pr.integrator;
        }
    }
    (steps, tol, prof)
}

/// Every branch certified by the cover chain (the pipeline's default engine) from the same
/// start; the links and the largest proven tolerance.
fn chain_all(p: &RationalBezierPatch, q: &RationalBezierPatch, jobs: &[Job]) -> (usize, f64) {
    let opts = ChainOptions::default();
    let (mut links, mut tol) = (0, 0.0f64);
    for j in jobs {
        if let Ok(c) = certify_chain(p, q, &j.branch, black_box(j.start), &opts) {
            links += c.tubes.len();
            tol = tol.max(c.certified_tolerance);
        }
    }
    (links, tol)
}

/// Prints the default engine's ratio on one scene: the cover chain over every branch against
/// the marcher on the same branches (the fastest of 9 runs each, back to back: the least
/// disturbed by other processes on a shared machine).
fn report_chain(c: &Case) {
    let [p, q] = &c.scene.surfaces;
    let mut out = (0, 0.0);
    let chain = fastest(9, || out = chain_all(p, q, &c.jobs));
    let march = fastest(9, || {
        black_box(march_all(p, q, &c.jobs, c.scene.options.step));
    });
    println!(
        "{:<22} chain: {:>5} links, tol {:.1e}, certified {:.2} ms, marched {:.2} ms, ratio {:.1}",
        c.name,
        out.0,
        out.1,
        1e3 * chain,
        1e3 * march,
        chain / march.max(1e-12),
    );
}

fn march_all(p: &RationalBezierPatch, q: &RationalBezierPatch, jobs: &[Job], step: f64) -> usize {
    let opts = MarchOptions {
        step,
        ..MarchOptions::default()
    };
    jobs.iter()
        .filter_map(|j| trace_branch(p, q, black_box(j.start), &opts).ok())
        .map(|b| b.branch.points.len())
        .sum()
}

/// Prints the ratio and the per-step split of one scene at one order.
fn report(c: &Case, order: usize) {
    let [p, q] = &c.scene.surfaces;
    let t0 = Instant::now();
    let (steps, tol, pr) = certify_all(p, q, &c.jobs, order);
    let cert = t0.elapsed().as_secs_f64();
    let t1 = Instant::now();
    march_all(p, q, &c.jobs, c.scene.options.step);
    let march = t1.elapsed().as_secs_f64();
    let w = pr.integrator;
    let units = (w.box_units + w.phase1_units + w.phase2_units).max(1e-300);
    let per = |x: f64| 1e3 * x / steps.max(1) as f64;
    println!(
        "{:<22} k={order:>2}: {steps:>5} steps, tol {tol:.1e}, certified {:.1} ms, marched {:.2} ms, \
         ratio {:.0} | per step {:.3} ms: series+predict {:.3}, phase I {:.3}, phase II {:.3}, \
         anchor {:.3}, boxes {:.3}, closing {:.3} | phase I tries/step {:.2}, remainder cuts {} | \
         mean h {:.2e}, radius point/h {:.1}, a-priori/h {:.1}",
        c.name,
        1e3 * cert,
        1e3 * march,
        cert / march.max(1e-12),
        per(cert),
        per(pr.step_seconds * w.box_units / units),
        per(pr.step_seconds * w.phase1_units / units),
        per(pr.step_seconds * w.phase2_units / units),
        per(pr.anchor_seconds),
        per(pr.enclosure_seconds),
        per(pr.closing_seconds),
        w.phase1_attempts as f64 / w.steps.max(1) as f64,
        w.remainder_cuts,
        w.h_sum / w.steps.max(1) as f64,
        w.radius_point_sum / w.h_sum,
        w.radius_apriori_sum / w.h_sum,
    );
}

fn cases() -> Vec<Case> {
    vec![
        case(
            "sphere_patch_plane",
            "scenes/sphere_patch_plane.json",
            false,
        ),
        case(
            "bicubic_transversal",
            "scenes/bicubic_transversal.json",
            false,
        ),
        case("two_loops_s31_s32", "scenes/two_loops_s31_s32.json", false),
        case("wu_andrade_fig7_loop", "scenes/wu_andrade_fig7.json", true),
        case("small_loop", "scenes/small_loop.json", false),
    ]
}

/// Scenes whose Taylor-engine runs take too long for this bench, measured with the chain only.
fn chain_only_cases() -> Vec<Case> {
    vec![
        case("wu_andrade_fig7", "scenes/wu_andrade_fig7.json", false),
        case("cylinders", "scenes/cylinders.json", false),
        case("cylinders_full", "scenes/cylinders_full.json", false),
        case("viviani", "scenes/viviani.json", false),
    ]
}

fn bench_scenes(crit: &mut Criterion) {
    let cases = cases();
    let order = CertifyOptions::default().steps.order;
    let orders: Vec<usize> = std::env::var("SSITRACE_BENCH_ORDERS")
        .ok()
        .map(|s| s.split(',').filter_map(|x| x.trim().parse().ok()).collect())
        .unwrap_or_default();
    for c in cases.iter().chain(&chain_only_cases()) {
        report_chain(c);
    }
    for c in &cases {
        report(c, order);
        for &k in orders.iter().filter(|&&k| k != order) {
            report(c, k);
        }
    }
    let mut group = crit.benchmark_group("scene");
    group.sample_size(10);
    for c in &cases {
        let [p, q] = &c.scene.surfaces;
        group.bench_function(format!("{}/certified", c.name), |b| {
            b.iter(|| certify_all(p, q, &c.jobs, order))
        });
        group.bench_function(format!("{}/chain", c.name), |b| {
            b.iter(|| chain_all(p, q, &c.jobs))
        });
        group.bench_function(format!("{}/marched", c.name), |b| {
            b.iter(|| march_all(p, q, &c.jobs, c.scene.options.step))
        });
    }
    group.finish();
}

/// The two halves of an open branch (bicubic transversal) one after the other and on two
/// threads (`CertifyOptions::parallel_halves`).
fn bench_halves(crit: &mut Criterion) {
    let c = case(
        "bicubic_transversal",
        "scenes/bicubic_transversal.json",
        false,
    );
    let [p, q] = &c.scene.surfaces;
    let order = CertifyOptions::default().steps.order;
    let mut group = crit.benchmark_group("halves");
    group.sample_size(10);
    for (name, parallel) in [("sequential", false), ("parallel", true)] {
        group.bench_function(format!("{}/{name}", c.name), |b| {
            b.iter(|| certify_with(p, q, &c.jobs, order, parallel))
        });
    }
    group.finish();
}

criterion_group!(benches, bench_scenes, bench_halves);
criterion_main!(benches);
