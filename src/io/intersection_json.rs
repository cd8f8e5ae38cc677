//! The result document of a [`SurfaceIntersection`]: the stats, the `"certified"` member of each
//! branch with its `"straying"` report, the certified events and contacts, and the topology
//! notes, gathered into a [`ResultMeta`] for [`write_result`](super::result_json::write_result);
//! and the same for a shell intersection, whose branches each carry the `"pair"` of faces they
//! belong to ([`shell_result`]).

use std::collections::HashMap;

use serde_json::{json, Map, Value};

use super::result_json::{
    certified_contact_to_json, certified_error_to_json, certified_events_to_json,
    certified_to_json, ResultMeta, CERTIFIED_CONTACT_EVENT,
};
use super::topology_json::{boundary_ends_to_json, node_to_json};
use crate::check::straying::StrayReport;
use crate::march::branch::Intersection;
use crate::shell::{JoinStatus, JoinedCurve, ShellIntersection};
use crate::solve::{BranchCertificate, SurfaceIntersection};

/// Everything of `r` that goes into the result document besides the marched curves
/// ([`SurfaceIntersection::marched`]): scene name, method, stats, the certified members and
/// events, the boundary-end and node notes. With `tubes`, the certified tube pieces are written
/// too (large).
pub fn result_meta(scene: Option<String>, r: &SurfaceIntersection, tubes: bool) -> ResultMeta {
    let opts = &r.options;
    let mut meta = ResultMeta::new(scene, opts.method.name());
    meta.stats = stats_json(r);
    for b in &r.branches {
        if !b.boundary_ends.is_empty() {
            meta.branch_notes.entry(b.id()).or_default().insert(
                "boundary_ends".into(),
                boundary_ends_to_json(&b.boundary_ends),
            );
        }
    }
    for k in 0..r.events.len() {
        if let Some(n) = r.event_node(k) {
            meta.event_notes
                .entry(k)
                .or_default()
                .insert("node".into(), node_to_json(n));
        }
    }
    if !opts.method.certifies() {
        return meta;
    }
    for b in &r.branches {
        let Some(cert) = &b.certificate else { continue };
        let mut v = certificate_json(cert, opts.required_tolerance, tubes);
        if let (Some(s), Value::Object(m)) = (&b.straying, &mut v) {
            m.insert("straying".into(), straying_json(s));
        }
        meta.certified.insert(b.id(), v);
        if let Ok(c) = &cert.result {
            meta.certified_events
                .extend(certified_events_to_json(b.id(), c, &|y| cert.xyz_of_end(y)));
        }
    }
    for c in &r.contacts {
        let mut v = certified_contact_to_json(c, tubes);
        if let Value::Object(m) = &mut v {
            m.insert("kind".into(), json!(CERTIFIED_CONTACT_EVENT));
        }
        meta.certified_events.push(v);
    }
    if let Some(e) = &r.contact_error {
        meta.certified_events.push(json!({
            "kind": CERTIFIED_CONTACT_EVENT,
            "error": e.to_string(),
        }));
    }
    meta
}

/// The branch's `"certified"` object: [`certified_to_json`] (or `{"error": ...}`) plus
/// `"meets_tolerance"` (only when certified), `"required_tolerance"`, `"start_point"` (when the
/// branch had points), `"max_length"` and `"seconds"`.
pub fn certificate_json(c: &BranchCertificate, tolerance: f64, tubes: bool) -> Value {
    let mut v = match &c.result {
        Ok(cb) => certified_to_json(cb, tubes),
        Err(e) => certified_error_to_json(e),
    };
    if let Value::Object(m) = &mut v {
        if let Some(ok) = c.meets(tolerance) {
            m.insert("meets_tolerance".into(), json!(ok));
        }
        m.insert("required_tolerance".into(), json!(tolerance));
        if c.start.iter().all(|x| x.is_finite()) {
            m.insert("start_point".into(), json!(c.start));
        }
        m.insert("max_length".into(), json!(c.max_length));
        m.insert("seconds".into(), json!(c.seconds));
    }
    v
}

/// A branch's `"straying"` object: `straying_points` (objects with the marched point's `index`,
/// the proven parameter `distance` from the certified curve, its floating-point `estimate`, the
/// `slack` it exceeds and, when proven, the branch it strayed `onto`), `unchecked_points`
/// (indices), `looping`, `covered_fraction`, `marched_length` and `certified_length`.
pub fn straying_json(r: &StrayReport) -> Value {
    let points: Vec<Value> = r
        .straying
        .iter()
        .map(|s| {
            let mut v = json!({
                "index": s.index,
                "distance": s.distance,
                "estimate": s.estimate,
                "slack": s.slack,
            });
            if let (Some(j), Value::Object(m)) = (s.onto, &mut v) {
                m.insert("onto".into(), json!(j));
            }
            v
        })
        .collect();
    json!({
        "straying_points": points,
        "unchecked_points": r.unchecked,
        "looping": r.looping,
        "covered_fraction": r.covered_fraction,
        "marched_length": r.marched_length,
        "certified_length": r.certified_length,
    })
}

/// The `"stats"` object: the search and marching counts and seconds, the step, the inconsistent
/// boundary ends and, when the method certifies, the certification counts, budgets and seconds.
pub fn stats_json(r: &SurfaceIntersection) -> Map<String, Value> {
    let s = &r.stats.search;
    let v = json!({
        "step": r.options.step,
        "branches": r.branches.len(),
        "points": s.points,
        "boundary_starts": s.boundary_starts,
        "interior_candidates": s.interior_candidates,
        "skipped_covered": s.skipped_covered,
        "failed_starts": s.failed_starts,
        "undecided_leaves": s.undecided_leaves,
        "search_truncated": s.search_truncated,
        "search_complete": s.search_complete,
        "disjoint_pairs": s.disjoint_pairs,
        "loop_free_pairs": s.loop_free_pairs,
        "node_regions": s.node_regions,
        "undecided_regions": s
            .undecided_regions
            .iter()
            .map(|r| json!({"p": r.p, "q": r.q}))
            .collect::<Vec<_>>(),
        "contact_points": s.contact_points,
        "search_seconds": s.search_seconds,
        "march_seconds": s.march_seconds,
        "inconsistent_boundary_ends": r.stats.inconsistent_boundary_ends,
    });
    let mut m = match v {
        Value::Object(m) => m,
        _ => Map::new(),
    };
    if let Some(c) = &r.stats.certify {
        let mut put = |k: &str, v: Value| {
            m.insert(k.into(), v);
        };
        put("certified_steps", json!(c.certified_steps));
        put("certify_failures", json!(c.failures));
        put("certify_seconds", json!(c.seconds));
        put("max_steps", json!(r.options.max_steps));
        put("tolerance", json!(r.options.required_tolerance));
        put("straying_seconds", json!(c.straying_seconds));
        put("contact_seconds", json!(c.contact_seconds));
        put("straying_points", json!(c.straying_points));
        put("unchecked_points", json!(c.unchecked_points));
        put("looping_branches", json!(c.looping_branches));
        put("duplicate_branches", json!(c.duplicate_branches));
        put("retraced_branches", json!(c.retraced_branches));
        if r.contact_error.is_none() {
            put("certified_contacts", json!(r.contacts.len()));
        }
    }
    m
}

/// Add `"pair": [i, j]` (face of A, face of B) to every branch of `r` in `meta`.
pub fn mark_pair(meta: &mut ResultMeta, r: &SurfaceIntersection, pair: [usize; 2]) {
    for b in &r.branches {
        meta.branch_notes
            .entry(b.id())
            .or_default()
            .insert("pair".into(), json!(pair));
    }
}

/// Replaces the branch id at `v[key]`, if there is one, by its shell-wide number in `ids`
/// (a pair's own branch ids may have gaps where duplicates were dropped).
fn renumber(v: &mut Value, key: &str, ids: &HashMap<usize, usize>) {
    if let Some(x) = v.get_mut(key) {
        if let Some(n) = x.as_u64().and_then(|n| ids.get(&(n as usize))) {
            *x = json!(*n);
        }
    }
}

/// The result document of a shell intersection: the branches and events of every traced piece
/// pair, in the order of [`ShellIntersection::pairs`], renumbered into one sequence (branches
/// by their position, as [`ShellIntersection::branch`] and the joins number them; event
/// indices shifted by the counts before them; the branch references inside the certified
/// members and events mapped likewise). Every branch, marcher event note and certified event
/// carries `"pair": [i, j]` (the faces of A and B) and `"pieces"` (the Bézier pieces of those
/// faces). The stats hold `"piece_pairs"`, `"skipped_pairs"` (proven disjoint by their
/// bounding boxes), `"edge_copies"` (branches dropped as copies along a shared edge),
/// `"pole_settled"` (undecided search regions covered by a proven join through a pole),
/// `"branches"`, `"search_complete"` (every traced pair settled) and
/// `"pairs"`, the [`stats_json`] of each traced pair with its `"pair"` and `"pieces"`, and
/// `"joined_curves"` (their count) and `"join_seconds"`. The document gets the top-level member
/// `"joined_curves"` ([`joined_curve_json`] of each [`ShellIntersection::curves`]) and every
/// branch the index of its joined curve, `"curve"`.
pub fn shell_result(
    scene: Option<String>,
    s: &ShellIntersection,
    tubes: bool,
) -> (Intersection, ResultMeta) {
    let mut all = Intersection::default();
    let mut meta = ResultMeta::new(scene, s.options.method.name());
    let mut pair_stats = Vec::new();
    for pi in &s.pairs {
        let (b0, e0) = (all.branches.len(), all.events.len());
        let tag = |v: &mut Value| {
            if let Value::Object(m) = v {
                m.insert("pair".into(), json!(pi.faces));
                m.insert("pieces".into(), json!(pi.pieces));
            }
        };
        let mut m = result_meta(None, &pi.result, tubes);
        mark_pair(&mut m, &pi.result, pi.faces);
        let marched = pi.result.marched();
        // Shell-wide numbers in pair order, position by position, as the joins number them.
        let ids: HashMap<usize, usize> = marched
            .branches
            .iter()
            .enumerate()
            .map(|(k, b)| (b.id, b0 + k))
            .collect();
        for mut b in marched.branches {
            let id = b.id;
            b.id = ids[&id];
            let mut notes = m.branch_notes.remove(&id).unwrap_or_default();
            notes.insert("pieces".into(), json!(pi.pieces));
            meta.branch_notes.insert(b.id, notes);
            if let Some(mut c) = m.certified.remove(&id) {
                if let Some(points) = c
                    .get_mut("straying")
                    .and_then(|x| x.get_mut("straying_points"))
                    .and_then(|x| x.as_array_mut())
                {
                    for p in points {
                        renumber(p, "onto", &ids);
                    }
                }
                meta.certified.insert(b.id, c);
            }
            all.branches.push(b);
        }
        for (k, e) in marched.events.into_iter().enumerate() {
            let mut notes = Value::Object(m.event_notes.remove(&k).unwrap_or_default());
            tag(&mut notes);
            if let Value::Object(n) = notes {
                meta.event_notes.insert(k + e0, n);
            }
            all.events.push(e);
        }
        for mut v in m.certified_events {
            renumber(&mut v, "branch", &ids);
            tag(&mut v);
            meta.certified_events.push(v);
        }
        let mut st = Value::Object(m.stats);
        tag(&mut st);
        pair_stats.push(st);
    }
    let stats = &mut meta.stats;
    stats.insert("piece_pairs".into(), json!(s.piece_pairs));
    stats.insert("skipped_pairs".into(), json!(s.skipped_pairs));
    stats.insert("edge_copies".into(), json!(s.edge_copies));
    stats.insert("pole_settled".into(), json!(s.pole_settled));
    stats.insert("branches".into(), json!(all.branches.len()));
    stats.insert("search_complete".into(), json!(s.is_complete()));
    stats.insert("pairs".into(), Value::Array(pair_stats));
    stats.insert("joined_curves".into(), json!(s.curves.len()));
    stats.insert("join_seconds".into(), json!(s.join_seconds));
    for (k, c) in s.curves.iter().enumerate() {
        for part in &c.parts {
            meta.branch_notes
                .entry(part.branch)
                .or_default()
                .insert("curve".into(), json!(k));
        }
    }
    meta.members.insert(
        "joined_curves".into(),
        Value::Array(s.curves.iter().map(joined_curve_json).collect()),
    );
    (all, meta)
}

/// One entry of `"joined_curves"`: `parts` (objects with the shell-wide `branch` id and
/// `reversed`), `closed`, `joins` (objects with the two branch ends `from` and `to`, each
/// `{"branch", "end"}`, the `edge` kind, the `status` `"proven"`, `"unproven"` (with a
/// `reason`) or `"marched"`, the matched `gap`, and for a join across a corner of the piece
/// pair or proven through a pole `corner`: the other surface's `second_edge` (`"pole"` through
/// a pole), the model-space box `xyz` holding the
/// curve between the two parts (`null` bounds unless proven) and the `absorbed` branches) and
/// `certified_tolerance` (`null` unless every part is certified and every join proven).
pub fn joined_curve_json(c: &JoinedCurve) -> Value {
    let end = |e: &crate::shell::BranchEnd| json!({"branch": e.branch, "end": e.end});
    let joins: Vec<Value> = c
        .joins
        .iter()
        .map(|j| {
            let mut v = json!({
                "from": end(&j.ends[0]),
                "to": end(&j.ends[1]),
                "edge": j.edge.name(),
                "gap": j.gap,
            });
            if let Value::Object(m) = &mut v {
                let (status, reason) = match &j.status {
                    JoinStatus::Proven => ("proven", None),
                    JoinStatus::Unproven { reason } => ("unproven", Some(*reason)),
                    JoinStatus::Marched => ("marched", None),
                };
                m.insert("status".into(), json!(status));
                if let Some(r) = reason {
                    m.insert("reason".into(), json!(r));
                }
                if let Some(c) = &j.corner {
                    let xyz: Vec<Value> = c
                        .xyz
                        .iter()
                        .map(|x| {
                            if x.is_empty() {
                                Value::Null
                            } else {
                                json!([x.inf(), x.sup()])
                            }
                        })
                        .collect();
                    m.insert(
                        "corner".into(),
                        json!({"second_edge": c.second_edge.name(), "xyz": xyz,
                               "absorbed": c.absorbed}),
                    );
                }
            }
            v
        })
        .collect();
    json!({
        "parts": c
            .parts
            .iter()
            .map(|p| json!({"branch": p.branch, "reversed": p.reversed}))
            .collect::<Vec<_>>(),
        "closed": c.closed,
        "joins": joins,
        "certified_tolerance": c.certified_tolerance,
    })
}
