//! [`intersect`]: search, march, check the boundary ends, certify the branches (in parallel),
//! check the marched points against the certificates, certify the contacts.

use std::time::Instant;

use inari::Interval;
use rayon::prelude::*;

use super::duplicates::duplicate_branches;
use super::options::{Engine, Options};
use super::repair::{adds_cover, uncovered_starts};
use super::result::{
    end_box, BranchCertificate, CertifyStats, Stats, SurfaceIntersection, TracedBranch,
};
use super::turns::join_turns;
use crate::certify::contact::certify_contact_events;
use crate::certify::{
    certify_branch, certify_chain, CertifiedBranch, CertifyOptions, ChainOptions, StepBudget,
    TubePiece,
};
use crate::check::straying::{check_branches, StrayReport};
use crate::error::{Error, Result};
use crate::geometry::RationalBezierPatch;
use crate::march::branch::{Branch, BranchStatus};
use crate::march::MarchOptions;
use crate::pair::tangent::normals_sine_sqr;
use crate::topology::branch_ends::{check_branch_ends, BranchEndCheck};
use crate::topology::graph::trace_graph;
use crate::topology::intersect::intersect as march_all;

/// Scaled parameter distance, beyond a tube piece's proven radius, within which a marched point
/// counts as lying on that piece when duplicates are looked for (the marcher's points are on the
/// curve to about 1e-12 of the model; certified tubes are about 1e-9 wide).
const DUPLICATE_SLACK: f64 = 1e-9;

/// Rounds of tracing again what a marcher jump left uncertified ([`super::repair`]), with the
/// step divided by 8, then by 64.
const REPAIR_ROUNDS: i32 = 2;

/// The share of the required tolerance a cover chain aims at: the rest is left to the edge
/// built on it (the edge module), whose coarse B-spline adds its fit to the chain's tubes and
/// must stay within the required tolerance. Half: since the links are as long as their
/// predictor allows, at 0.8 the tubes left so little room that the edges of the STEP cube
/// needed ~100 control points instead of ~55 (and S31/S32's 248/152 instead of 170/123), for
/// 5–15 % fewer links.
pub(crate) const CHAIN_SHARE: f64 = 0.5;

/// Finds, traces and (unless the method is [`Method::March`](super::Method::March)) certifies
/// every branch of `P ∩ Q`.
///
/// The marcher finds and traces the branches. A certifying method then certifies each branch
/// with [`Options::engine`] (see [`certify_marched_branch`]; the branches are certified in
/// parallel, on rayon's thread pool, and reported in branch order), checks the marched points
/// against the certificates and certifies the tangential contacts behind the marcher's singular
/// events. A branch whose certification fails keeps the error in its
/// [`BranchCertificate::result`]; the run goes on.
///
/// Errors: the options fail [`Options::check`].
pub fn intersect(
    p: &RationalBezierPatch,
    q: &RationalBezierPatch,
    opts: &Options,
) -> Result<SurfaceIntersection> {
    opts.check()?;
    let march = MarchOptions {
        step: opts.marching_step(p, q),
        ..MarchOptions::default()
    };
    let started = Instant::now();
    let deadline = opts.time_limit.map(|limit| started + limit);
    let mut outcome = march_all(p, q, &march, &opts.search);
    let march_seconds = started.elapsed().as_secs_f64();
    let mut marched = outcome.intersection.branches;
    let mut boundary_ends: Vec<_> = marched
        .iter()
        .map(|b| check_branch_ends(p, q, b, &opts.boundary))
        .collect();
    let inconsistent_boundary_ends = boundary_ends
        .iter()
        .flatten()
        .flatten()
        .flatten()
        .filter(|c| !c.consistent)
        .count();
    let mut stats = Stats {
        search: outcome.stats,
        march_seconds,
        inconsistent_boundary_ends,
        certify: None,
    };
    let mut certificates: Vec<Option<BranchCertificate>> = marched.iter().map(|_| None).collect();
    let mut straying: Vec<Option<StrayReport>> = marched.iter().map(|_| None).collect();
    let mut contacts = Vec::new();
    let mut contact_error = None;
    if opts.method.certifies() {
        let certifying = Instant::now();
        // Arms of a turn too tight for the march, joined where the chain proves the curve
        // through it (`turns.rs`), with their certificates.
        let mut joined = join_turns(
            p,
            q,
            (&mut marched, &mut boundary_ends),
            (&mut outcome.nodes, &mut outcome.intersection.events),
            &|b| certify_within(p, q, b, opts, deadline),
            &|b| check_branch_ends(p, q, b, &opts.boundary),
        );
        let mut certs: Vec<BranchCertificate> = marched
            .par_iter()
            .zip(joined.par_iter_mut())
            .map(|(b, c)| {
                c.take()
                    .unwrap_or_else(|| certify_within(p, q, b, opts, deadline))
            })
            .collect();
        let retraced = retrace_uncovered(
            p,
            q,
            (&mut marched, &mut certs, &mut boundary_ends),
            &march,
            opts,
            deadline,
        );
        let wall_seconds = certifying.elapsed().as_secs_f64();
        // A branch traced twice (the marcher jumped between close curves) is dropped.
        let dropped = {
            let certified: Vec<Option<&CertifiedBranch>> =
                certs.iter().map(BranchCertificate::certified).collect();
            duplicate_branches(p, q, &marched, &certified, DUPLICATE_SLACK)
        };
        let keep = |i: &usize| !dropped[*i];
        let duplicates = dropped.iter().filter(|d| **d).count();
        let certs: Vec<BranchCertificate> = certs
            .into_iter()
            .enumerate()
            .filter(|(i, _)| keep(i))
            .map(|(_, c)| c)
            .collect();
        marched = std::mem::take(&mut marched)
            .into_iter()
            .enumerate()
            .filter(|(i, _)| keep(i))
            .map(|(_, b)| b)
            .collect();
        boundary_ends = std::mem::take(&mut boundary_ends)
            .into_iter()
            .enumerate()
            .filter(|(i, _)| keep(i))
            .map(|(_, b)| b)
            .collect();
        let certified: Vec<Option<&CertifiedBranch>> =
            certs.iter().map(BranchCertificate::certified).collect();
        let checking = Instant::now();
        let reports = check_branches(p, q, &marched, &certified, march.newton_tolerance);
        let straying_seconds = checking.elapsed().as_secs_f64();
        let contacting = Instant::now();
        let mut contact = opts.contact;
        contact.steps.deadline = deadline;
        match certify_contact_events(p, q, &outcome.intersection.events, &contact) {
            Ok(c) => contacts = c,
            Err(e) => contact_error = Some(e),
        }
        let contact_seconds = contacting.elapsed().as_secs_f64();
        let count = |f: &dyn Fn(&StrayReport) -> usize| reports.iter().map(f).sum::<usize>();
        stats.certify = Some(CertifyStats {
            certified_steps: certified.iter().flatten().map(|c| c.steps()).sum(),
            failures: certified.iter().filter(|c| c.is_none()).count(),
            // A fold from +0.0: an empty f64 sum is -0.0, which would print as such.
            seconds: certs.iter().fold(0.0, |t, c| t + c.seconds),
            wall_seconds,
            straying_seconds,
            contact_seconds,
            straying_points: count(&|r| r.straying.len()),
            unchecked_points: count(&|r| r.unchecked.len()),
            looping_branches: count(&|r| usize::from(r.looping)),
            duplicate_branches: duplicates,
            retraced_branches: retraced,
        });
        certificates = certs.into_iter().map(Some).collect();
        straying = reports.into_iter().map(Some).collect();
    }
    let branches = marched
        .into_iter()
        .zip(certificates)
        .zip(straying)
        .zip(boundary_ends)
        .map(
            |(((marched, certificate), straying), boundary_ends)| TracedBranch {
                marched,
                certificate,
                straying,
                boundary_ends,
            },
        )
        .collect();
    Ok(SurfaceIntersection {
        options: *opts,
        branches,
        events: outcome.intersection.events,
        nodes: outcome.nodes,
        contacts,
        contact_error,
        stats,
    })
}

/// The marched branches, their certificates and their checked boundary ends, index for index.
type Traced<'a> = (
    &'a mut Vec<Branch>,
    &'a mut Vec<BranchCertificate>,
    &'a mut Vec<Vec<Result<Vec<BranchEndCheck>>>>,
);

/// Traces again, with a finer step, what marcher jumps left uncertified ([`super::repair`]),
/// certifies the new branches and appends them; returns how many were added.
fn retrace_uncovered(
    p: &RationalBezierPatch,
    q: &RationalBezierPatch,
    (marched, certs, boundary_ends): Traced<'_>,
    march: &MarchOptions,
    opts: &Options,
    deadline: Option<Instant>,
) -> usize {
    let mut added = 0;
    let mut next_id = marched.iter().map(|b| b.id + 1).max().unwrap_or(0);
    for round in 1..=REPAIR_ROUNDS {
        let starts = {
            let certified: Vec<Option<&CertifiedBranch>> =
                certs.iter().map(BranchCertificate::certified).collect();
            uncovered_starts(p, q, marched, &certified, DUPLICATE_SLACK)
        };
        if starts.is_empty() || deadline.is_some_and(|d| Instant::now() >= d) {
            break;
        }
        let fine = MarchOptions {
            step: march.step / 8f64.powi(round),
            ..*march
        };
        let traced = trace_graph(p, q, &starts, &fine).branches;
        let new: Vec<BranchCertificate> = traced
            .par_iter()
            .map(|b| certify_within(p, q, b, opts, deadline))
            .collect();
        for (mut b, c) in traced.into_iter().zip(new) {
            // A trace that certifies nothing new (its chain stops at the same box: a node just
            // outside the domain, not a jump) would only report the branch twice.
            let before: Vec<&TubePiece> = certs
                .iter()
                .filter_map(BranchCertificate::certified)
                .flat_map(|c| &c.tubes)
                .collect();
            if !adds_cover(p, q, &b, c.certified(), &before, DUPLICATE_SLACK) {
                continue;
            }
            b.id = next_id;
            next_id += 1;
            boundary_ends.push(check_branch_ends(p, q, &b, &opts.boundary));
            marched.push(b);
            certs.push(c);
            added += 1;
        }
    }
    added
}

/// Certifies one marched branch within the budgets of `opts`, with `opts.engine`: from its
/// middle point (or a more transversal point at a quarter or a third of the way). The cover
/// chain has at most `2·opts.max_steps` links; the Taylor engine `opts.max_steps` steps and
/// `opts.length_budget` × the marched length of arc per half branch. Never fails as a whole: a
/// certification failure is kept in [`BranchCertificate::result`].
pub fn certify_marched_branch(
    p: &RationalBezierPatch,
    q: &RationalBezierPatch,
    b: &Branch,
    opts: &Options,
) -> BranchCertificate {
    let deadline = opts.time_limit.map(|limit| Instant::now() + limit);
    certify_within(p, q, b, opts, deadline)
}

/// [`certify_marched_branch`] with the run's deadline.
fn certify_within(
    p: &RationalBezierPatch,
    q: &RationalBezierPatch,
    b: &Branch,
    opts: &Options,
    deadline: Option<Instant>,
) -> BranchCertificate {
    let started = Instant::now();
    let length = b.length();
    // A closed loop is traced once from its start, an open branch each way from the middle:
    // 1.5 × the marched length covers either with room to spare.
    let max_length = if length > 0.0 {
        opts.length_budget * length
    } else {
        opts.marching_step(p, q)
    };
    let certify = CertifyOptions {
        steps: StepBudget {
            max_steps: opts.max_steps,
            max_length,
            deadline,
            ..StepBudget::CERTIFY
        },
        required_tolerance: opts.required_tolerance,
        parallel_halves: b.status != BranchStatus::Closed,
        ..CertifyOptions::default()
    };
    let chain = ChainOptions {
        required_tolerance: CHAIN_SHARE * opts.required_tolerance,
        max_links: opts.max_steps.saturating_mul(2),
        deadline,
    };
    let (start, result) = match choose_start(p, q, b) {
        Some(y) if opts.engine == Engine::Chain => (y, certify_chain(p, q, b, y, &chain)),
        Some(y) => (y, certify_branch(p, q, y, &certify)),
        None => (
            [f64::NAN; 4],
            Err(Error::Certification {
                reason: "the marched branch has no points".into(),
                near: [f64::NAN; 4],
            }),
        ),
    };
    let end_xyz = match &result {
        Ok(c) => c
            .ends
            .each_ref()
            .map(|e| end_box(e).and_then(|y| model_box(p, q, y))),
        Err(_) => [None, None],
    };
    BranchCertificate {
        branch: b.id,
        start,
        max_length,
        result,
        end_xyz,
        seconds: started.elapsed().as_secs_f64(),
    }
}

/// The start point of a certified trace: the middle point of the marched branch, unless a point
/// at a quarter or a third of the way is at least twice as transversal.
fn choose_start(p: &RationalBezierPatch, q: &RationalBezierPatch, b: &Branch) -> Option<[f64; 4]> {
    let n = b.points.len();
    if n == 0 {
        return None;
    }
    let at = |i: usize| {
        let c = &b.points[i.min(n - 1)];
        [c.p[0], c.p[1], c.q[0], c.q[1]]
    };
    let middle = at(n / 2);
    let mut best = (middle, 2.0 * normals_sine_sqr(p, q, &middle));
    for i in [n / 4, n / 3, 2 * n / 3, 3 * n / 4] {
        let y = at(i);
        let s = normals_sine_sqr(p, q, &y);
        if s > best.1 {
            best = (y, s);
        }
    }
    Some(best.0)
}

/// `P([σ],[t]) ∩ Q([u],[v])` for a bounded parameter box; `None` if unbounded or empty.
fn model_box(
    p: &RationalBezierPatch,
    q: &RationalBezierPatch,
    y: &[Interval; 4],
) -> Option<[Interval; 3]> {
    if y.iter()
        .any(|x| x.is_empty() || !x.inf().is_finite() || !x.sup().is_finite())
    {
        return None;
    }
    let (a, b) = (p.enclose(y[0], y[1]), q.enclose(y[2], y[3]));
    let out: [Interval; 3] = std::array::from_fn(|i| a[i].intersection(b[i]));
    (!out.iter().any(|x| x.is_empty())).then_some(out)
}
