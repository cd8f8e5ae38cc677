//! The versioned result JSON (`"format": "ssitrace-result"`, `"version": 1`).
//!
//! The document is the public contract described in `docs/result-format.md`:
//!
//! ```json
//! {"format": "ssitrace-result", "version": 1, "scene": "name or null", "method": "march",
//!  "branches": [{"id": 0, "status": "open",
//!                "ends": [{"kind": "boundary", "surface": 0}, {"kind": "singular"}],
//!                "points": [{"p": [0.5, 0.0], "q": [0.5, 0.25], "xyz": [0.5, 0.0, 0.1]}]}],
//!  "events": [{"kind": "singular", "p": [0.5, 1.0], "q": [1.0, 0.5], "xyz": [0.5, 1.0, 0.0]}],
//!  "stats": {"points": 1}}
//! ```
//!
//! Certified output: a branch object may carry a `"certified"` member (the certified tracer's
//! enclosures, ends and tolerance, built by [`certified_to_json`]), and `"events"` may hold
//! certified boxes (`"singular_box"`, `"close_branches"`, built by [`certified_events_to_json`]).
//! Both are written from [`ResultMeta`] and read back verbatim, so adding them changes nothing
//! for readers that ignore the member. Interval bounds are written with [`interval_to_json`];
//! [`enclosures_from_json`] reads a chain of boxes back bit for bit.

use std::collections::BTreeMap;
use std::path::Path;

use inari::Interval;
use serde_json::{json, Map, Value};

use crate::certify::{CertifiedBranch, CertifiedEnd, EnclosureBox, TubePiece};
use crate::march::branch::{
    Branch, BranchStatus, CurvePoint, EndReason, Event, EventKind, Intersection,
};
use crate::{Error, Result};

/// The value of the `"format"` member.
pub const FORMAT_NAME: &str = "ssitrace-result";
/// The format version this module writes and reads.
pub const FORMAT_VERSION: u64 = 1;

/// Everything in a result document that is not the [`Intersection`] itself.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ResultMeta {
    /// Scene name (the scene's `options.name`), written as `null` when absent.
    pub scene: Option<String>,
    /// Tracing method, e.g. `"march"`.
    pub method: String,
    /// Free-form statistics (point counts, timings, ...), written as the `"stats"` object.
    pub stats: Map<String, Value>,
    /// Per-branch `"certified"` objects, keyed by branch id (see [`certified_to_json`]).
    pub certified: BTreeMap<usize, Value>,
    /// Events of the certified tracer (`"kind"` is `"singular_box"` or `"close_branches"`, see
    /// [`certified_events_to_json`]), written after the marcher's events in `"events"` and read
    /// back verbatim.
    pub certified_events: Vec<Value>,
    /// Further members of branch objects (e.g. `"boundary_ends"`), keyed by branch id; written
    /// into the branch object and read back from any member the format does not define.
    pub branch_notes: BTreeMap<usize, Map<String, Value>>,
    /// Further members of the marcher's event objects (e.g. `"boundary"`, `"node"`), keyed by
    /// the event's index in [`Intersection::events`]; written and read back like `branch_notes`.
    pub event_notes: BTreeMap<usize, Map<String, Value>>,
    /// Further top-level members of the document (e.g. a shell result's `"joined_curves"`);
    /// written after the defined ones and read back from any top-level member the format does
    /// not define.
    pub members: Map<String, Value>,
}

/// Members of a branch object that the format defines (anything else is a note).
const BRANCH_MEMBERS: [&str; 5] = ["id", "status", "ends", "points", "certified"];
/// Members of a marcher event object that the format defines (anything else is a note).
const EVENT_MEMBERS: [&str; 4] = ["kind", "p", "q", "xyz"];
/// Top-level members that the format defines (anything else is one of [`ResultMeta::members`]).
const DOCUMENT_MEMBERS: [&str; 7] = [
    "format", "version", "scene", "method", "branches", "events", "stats",
];

/// The members of `v` (an object) whose names are not in `known`.
fn notes_of(v: &Value, known: &[&str]) -> Map<String, Value> {
    v.as_object()
        .map(|m| {
            m.iter()
                .filter(|(k, _)| !known.contains(&k.as_str()))
                .map(|(k, x)| (k.clone(), x.clone()))
                .collect()
        })
        .unwrap_or_default()
}

impl ResultMeta {
    /// Metadata with the given scene name and method, no stats and no certificates.
    pub fn new(scene: Option<String>, method: impl Into<String>) -> Self {
        ResultMeta {
            scene,
            method: method.into(),
            ..ResultMeta::default()
        }
    }
}

/// A result document read back: the curves and the metadata.
#[derive(Debug, Clone, PartialEq)]
pub struct ResultDocument {
    /// Branches and events.
    pub intersection: Intersection,
    /// Scene name, method, stats and certificates.
    pub meta: ResultMeta,
}

/// The result document for `result` as a JSON value (see the module docs for the layout).
///
/// Non-finite coordinates (which a correct tracer never produces) are written as `null`,
/// which [`result_from_json`] rejects.
pub fn result_to_json(result: &Intersection, meta: &ResultMeta) -> Value {
    let branches: Vec<Value> = result
        .branches
        .iter()
        .map(|b| {
            let mut obj = Map::new();
            obj.insert("id".into(), json!(b.id));
            obj.insert("status".into(), json!(status_name(b.status)));
            obj.insert(
                "ends".into(),
                Value::Array(b.ends.iter().map(|e| end_to_json(*e)).collect()),
            );
            obj.insert(
                "points".into(),
                Value::Array(b.points.iter().map(point_to_json).collect()),
            );
            if let Some(cert) = meta.certified.get(&b.id) {
                obj.insert("certified".into(), cert.clone());
            }
            if let Some(notes) = meta.branch_notes.get(&b.id) {
                for (k, v) in notes {
                    obj.entry(k.clone()).or_insert_with(|| v.clone());
                }
            }
            Value::Object(obj)
        })
        .collect();
    let events: Vec<Value> = result
        .events
        .iter()
        .enumerate()
        .map(|(k, e)| {
            let mut v = event_to_json(e);
            if let (Value::Object(obj), Some(notes)) = (&mut v, meta.event_notes.get(&k)) {
                for (name, x) in notes {
                    obj.entry(name.clone()).or_insert_with(|| x.clone());
                }
            }
            v
        })
        .chain(meta.certified_events.iter().cloned())
        .collect();
    let mut doc = json!({
        "format": FORMAT_NAME,
        "version": FORMAT_VERSION,
        "scene": meta.scene,
        "method": meta.method,
        "branches": branches,
        "events": events,
        "stats": Value::Object(meta.stats.clone()),
    });
    if let Value::Object(obj) = &mut doc {
        for (k, v) in &meta.members {
            obj.entry(k.clone()).or_insert_with(|| v.clone());
        }
    }
    doc
}

/// Writes the result document for `result` to `path` (pretty-printed, trailing newline).
///
/// I/O failures become [`Error::Io`] naming the path.
pub fn write_result(path: &Path, result: &Intersection, meta: &ResultMeta) -> Result<()> {
    let doc = result_to_json(result, meta);
    let mut text = serde_json::to_string_pretty(&doc)
        .map_err(|e| Error::ResultFormat(format!("serialisation failed: {e}")))?;
    text.push('\n');
    std::fs::write(path, text).map_err(|e| Error::Io {
        path: path.display().to_string(),
        message: e.to_string(),
    })
}

/// Reads a result document back. Checks `format` and `version`, and the shape of every
/// documented field; unknown extra members are ignored (forward compatible).
pub fn result_from_json(doc: &Value) -> Result<ResultDocument> {
    let obj = doc
        .as_object()
        .ok_or_else(|| bad("the document is not a JSON object"))?;
    match obj.get("format").and_then(Value::as_str) {
        Some(FORMAT_NAME) => {}
        _ => return Err(bad("`format` is not \"ssitrace-result\"")),
    }
    match obj.get("version").and_then(Value::as_u64) {
        Some(FORMAT_VERSION) => {}
        Some(v) => return Err(bad(&format!("unsupported version {v}"))),
        None => return Err(bad("`version` is missing or not an integer")),
    }
    let scene = match obj.get("scene") {
        None | Some(Value::Null) => None,
        Some(Value::String(s)) => Some(s.clone()),
        Some(_) => return Err(bad("`scene` is neither a string nor null")),
    };
    let method = obj
        .get("method")
        .and_then(Value::as_str)
        .ok_or_else(|| bad("`method` is missing or not a string"))?
        .to_string();
    let stats = match obj.get("stats") {
        None => Map::new(),
        Some(Value::Object(m)) => m.clone(),
        Some(_) => return Err(bad("`stats` is not an object")),
    };
    let mut certified = BTreeMap::new();
    let mut branch_notes = BTreeMap::new();
    let mut event_notes = BTreeMap::new();
    let mut branches = Vec::new();
    for (k, b) in array(obj.get("branches"), "branches")?.iter().enumerate() {
        let branch = branch_from_json(b, k)?;
        if let Some(cert) = b.get("certified") {
            certified.insert(branch.id, cert.clone());
        }
        let notes = notes_of(b, &BRANCH_MEMBERS);
        if !notes.is_empty() {
            branch_notes.insert(branch.id, notes);
        }
        branches.push(branch);
    }
    let mut events = Vec::new();
    let mut certified_events = Vec::new();
    for (k, e) in array(obj.get("events"), "events")?.iter().enumerate() {
        match e.get("kind").and_then(Value::as_str) {
            Some(CERTIFIED_SINGULAR_EVENT | CERTIFIED_CLOSE_EVENT) => {
                if e.get("box").is_none() {
                    return Err(bad(&format!("events[{k}]: `box` is missing")));
                }
                certified_events.push(e.clone());
            }
            Some(CERTIFIED_CONTACT_EVENT) => {
                if e.get("tangential").is_none() && e.get("error").is_none() {
                    return Err(bad(&format!(
                        "events[{k}]: `tangential` or `error` is missing"
                    )));
                }
                certified_events.push(e.clone());
            }
            _ => {
                let notes = notes_of(e, &EVENT_MEMBERS);
                if !notes.is_empty() {
                    event_notes.insert(events.len(), notes);
                }
                events.push(event_from_json(e, k)?);
            }
        }
    }
    Ok(ResultDocument {
        intersection: Intersection { branches, events },
        meta: ResultMeta {
            scene,
            method,
            stats,
            certified,
            certified_events,
            branch_notes,
            event_notes,
            members: notes_of(doc, &DOCUMENT_MEMBERS),
        },
    })
}

/// An interval as the JSON pair `[lo, hi]` of its exact `f64` bounds (`inf()`, `sup()`).
///
/// serde_json writes each `f64` as the shortest decimal that reads back (round to nearest)
/// as exactly the same `f64`, so a reader parsing the numbers as binary64 recovers the
/// outward-rounded bounds bit for bit. A reader that treats the decimal text as an exact real
/// must first round it to the nearest binary64. Empty or unbounded intervals have no JSON
/// form and give [`Error::ResultFormat`].
pub fn interval_to_json(x: Interval) -> Result<Value> {
    if x.is_empty() {
        return Err(bad("an empty interval has no [lo, hi] form"));
    }
    let (lo, hi) = (x.inf(), x.sup());
    if !lo.is_finite() || !hi.is_finite() {
        return Err(bad("an unbounded interval has no JSON form"));
    }
    Ok(json!([lo, hi]))
}

/// Reads `[lo, hi]` (two finite numbers, `lo <= hi`) back into an interval.
pub fn interval_from_json(v: &Value) -> Result<Interval> {
    let [lo, hi] = numbers::<2>(v, "interval")?;
    crate::numeric::scalar::interval(lo, hi)
        .ok_or_else(|| bad(&format!("interval [{lo}, {hi}] is inverted")))
}

/// `"kind"` of a certified event: a parameter box where the surface normals could not be
/// proven apart (a singular or tangential point may lie in it).
pub const CERTIFIED_SINGULAR_EVENT: &str = "singular_box";
/// `"kind"` of a certified event: a parameter box where the certified step fell below its
/// minimum with the normals proven apart (two branches closer than the tracer resolves).
pub const CERTIFIED_CLOSE_EVENT: &str = "close_branches";
/// `"kind"` of a certified event: a tangential contact certified from a marcher contact event,
/// with its `"tangential"` object (see [`certified_contact_to_json`]) or an `"error"`.
pub const CERTIFIED_CONTACT_EVENT: &str = "tangential_contact";

/// `[lo, hi]` as [`interval_to_json`], or `null` for an interval with no finite form (empty or
/// unbounded): `null` claims nothing.
fn interval_or_null(x: Interval) -> Value {
    interval_to_json(x).unwrap_or(Value::Null)
}

fn intervals_to_json(v: &[Interval]) -> Value {
    Value::Array(v.iter().map(|x| interval_or_null(*x)).collect())
}

fn intervals_from_json<const N: usize>(v: &Value, what: &str) -> Result<[Interval; N]> {
    let arr = v
        .as_array()
        .filter(|a| a.len() == N)
        .ok_or_else(|| bad(&format!("`{what}` is not an array of {N} intervals")))?;
    let mut out = [Interval::EMPTY; N];
    for (o, x) in out.iter_mut().zip(arr) {
        *o = interval_from_json(x).map_err(|e| bad(&format!("`{what}`: {e}")))?;
    }
    Ok(out)
}

/// One link of a certified chain as `{"s": [s0, s1], "p": [[lo, hi]; 2], "q": [[lo, hi]; 2],
/// "xyz": [[lo, hi]; 3]}`; bounds are the exact outward-rounded `f64` bounds.
pub fn enclosure_to_json(b: &EnclosureBox) -> Value {
    json!({
        "s": b.s,
        "p": intervals_to_json(&b.p),
        "q": intervals_to_json(&b.q),
        "xyz": intervals_to_json(&b.xyz),
    })
}

/// Reads [`enclosure_to_json`]'s object back, bit for bit. Every interval must be a finite
/// `[lo, hi]` with `lo <= hi`, and `s[0] <= s[1]`.
pub fn enclosure_from_json(v: &Value) -> Result<EnclosureBox> {
    let s: [f64; 2] = numbers(field(v, "s", "enclosure")?, "enclosure.s")?;
    if s[0] > s[1] {
        return Err(bad("enclosure.s is inverted"));
    }
    Ok(EnclosureBox {
        s,
        p: intervals_from_json(field(v, "p", "enclosure")?, "enclosure.p")?,
        q: intervals_from_json(field(v, "q", "enclosure")?, "enclosure.q")?,
        xyz: intervals_from_json(field(v, "xyz", "enclosure")?, "enclosure.xyz")?,
    })
}

/// The enclosures of a branch's `"certified"` object, in order along the branch.
///
/// Errors: the object has no `"enclosures"` array (e.g. it is an `{"error": ...}` object), or
/// one of them is malformed.
pub fn enclosures_from_json(certified: &Value) -> Result<Vec<EnclosureBox>> {
    array(certified.get("enclosures"), "certified.enclosures")?
        .iter()
        .map(enclosure_from_json)
        .collect()
}

/// A certified end as `{"kind": ..., ...}`: `"boundary"` with `"surface"`, `"closed_loop"`,
/// `"singular"` with `"near"` (4 intervals σ, t, u, v), `"close_branches"` with `"h"` and
/// `"near"`, `"unproven"` with `"reason"` and `"near"`.
pub fn certified_end_to_json(e: &CertifiedEnd) -> Value {
    let kind = e.kind();
    match e {
        CertifiedEnd::Boundary { surface } => json!({"kind": kind, "surface": surface}),
        CertifiedEnd::ClosedLoop => json!({ "kind": kind }),
        CertifiedEnd::Singular { near } => json!({"kind": kind, "near": intervals_to_json(near)}),
        CertifiedEnd::CloseBranches { h, near } => {
            json!({"kind": kind, "h": h, "near": intervals_to_json(near)})
        }
        CertifiedEnd::Unproven { reason, near } => {
            json!({"kind": kind, "reason": reason, "near": intervals_to_json(near)})
        }
    }
}

/// One tube piece as `{"s0", "direction", "h", "coeffs": [[σ, t, u, v], ...], "radius_param",
/// "radius_xyz"}`, and on a cover-chain piece `"along"` (the parameter `τ` measures) and
/// `"arc_length"` (see [`TubePiece`] for the meaning).
pub fn tube_to_json(t: &TubePiece) -> Value {
    let mut v = json!({
        "s0": t.s0,
        "direction": t.direction,
        "h": t.h,
        "coeffs": t.coeffs,
        "radius_param": t.radius_param,
        "radius_xyz": t.radius_xyz,
    });
    if let (Some(a), Some(obj)) = (t.along, v.as_object_mut()) {
        obj.insert("along".into(), json!(a.index));
        obj.insert("arc_length".into(), json!(a.arc_length));
    }
    v
}

/// A branch's `"certified"` object (layout in `docs/result-format.md`): the chain of enclosures, the
/// certified tolerance, the step count, both ends, the start box, the fixed start coordinate,
/// the largest tight-box width and, when `tubes` is set, the tube pieces.
pub fn certified_to_json(c: &CertifiedBranch, tubes: bool) -> Value {
    let max_width = c
        .widths
        .iter()
        .copied()
        .chain(c.start.iter().map(|x| x.wid()))
        .fold(0.0, f64::max);
    let mut obj = Map::new();
    obj.insert(
        "enclosures".into(),
        Value::Array(c.boxes.iter().map(enclosure_to_json).collect()),
    );
    obj.insert("tolerance".into(), json!(c.certified_tolerance));
    obj.insert("steps".into(), json!(c.steps()));
    obj.insert(
        "end_reasons".into(),
        Value::Array(c.ends.iter().map(certified_end_to_json).collect()),
    );
    obj.insert("start".into(), intervals_to_json(&c.start));
    obj.insert("fixed".into(), json!(c.fixed));
    obj.insert(
        "start_uniqueness".into(),
        intervals_to_json(&c.start_uniqueness),
    );
    obj.insert("max_width".into(), json!(max_width));
    obj.insert("arc_length_proven".into(), json!(c.arc_length_proven()));
    if let Some(l) = &c.tolerance_limit {
        obj.insert(
            "tolerance_limit".into(),
            json!({
                "reason": l.reason,
                "near": intervals_to_json(&l.near),
                "width": l.width,
            }),
        );
    }
    if tubes {
        obj.insert(
            "tubes".into(),
            Value::Array(c.tubes.iter().map(tube_to_json).collect()),
        );
    }
    Value::Object(obj)
}

/// The `"certified"` object of a branch whose certification failed: `{"error": "..."}`.
pub fn certified_error_to_json(e: &Error) -> Value {
    json!({ "error": e.to_string() })
}

/// The certified events of one branch: one object per end that is
/// [`CertifiedEnd::Singular`] (`"kind": "singular_box"`) or [`CertifiedEnd::CloseBranches`]
/// (`"kind": "close_branches"`, with the step `"h"`), each with `"branch"` (the branch id),
/// `"end"` (0 = the end at the smallest arc length, 1 = the largest) and `"box"`:
/// `{"p": [[lo, hi]; 2], "q": [[lo, hi]; 2], "xyz": [[lo, hi]; 3] or null}`. `xyz` is
/// `xyz_of(box)`, the model-space box of the parameter box (`null` when not given).
pub fn certified_events_to_json(
    branch_id: usize,
    c: &CertifiedBranch,
    xyz_of: &dyn Fn(&[Interval; 4]) -> Option<[Interval; 3]>,
) -> Vec<Value> {
    let boxed = |near: &[Interval; 4]| {
        json!({
            "p": intervals_to_json(&near[..2]),
            "q": intervals_to_json(&near[2..]),
            "xyz": xyz_of(near).map_or(Value::Null, |x| intervals_to_json(&x)),
        })
    };
    let mut out = Vec::new();
    for (k, end) in c.ends.iter().enumerate() {
        match end {
            CertifiedEnd::Singular { near } => out.push(json!({
                "kind": CERTIFIED_SINGULAR_EVENT,
                "branch": branch_id,
                "end": k,
                "box": boxed(near),
            })),
            CertifiedEnd::CloseBranches { h, near } => out.push(json!({
                "kind": CERTIFIED_CLOSE_EVENT,
                "branch": branch_id,
                "end": k,
                "h": h,
                "box": boxed(near),
            })),
            _ => {}
        }
    }
    out
}

fn bad(msg: &str) -> Error {
    Error::ResultFormat(msg.to_string())
}

fn status_name(s: BranchStatus) -> &'static str {
    match s {
        BranchStatus::Closed => "closed",
        BranchStatus::Open => "open",
        BranchStatus::Incomplete => "incomplete",
    }
}

fn end_to_json(e: EndReason) -> Value {
    match e {
        EndReason::Boundary { surface } => json!({"kind": "boundary", "surface": surface}),
        EndReason::ClosedLoop => json!({"kind": "closed_loop"}),
        EndReason::Singular => json!({"kind": "singular"}),
        EndReason::NewtonFailed => json!({"kind": "newton_failed"}),
        EndReason::PointLimit => json!({"kind": "point_limit"}),
        EndReason::OwnPath => json!({"kind": "own_path"}),
    }
}

fn event_kind_name(k: EventKind) -> &'static str {
    match k {
        EventKind::Singular => "singular",
        EventKind::BoundaryEnd => "boundary_end",
    }
}

fn point_to_json(c: &CurvePoint) -> Value {
    json!({"p": c.p, "q": c.q, "xyz": c.xyz})
}

fn event_to_json(e: &Event) -> Value {
    json!({"kind": event_kind_name(e.kind), "p": e.p, "q": e.q, "xyz": e.xyz})
}

fn array<'a>(v: Option<&'a Value>, what: &str) -> Result<&'a Vec<Value>> {
    v.and_then(Value::as_array)
        .ok_or_else(|| bad(&format!("`{what}` is missing or not an array")))
}

fn numbers<const N: usize>(v: &Value, what: &str) -> Result<[f64; N]> {
    let arr = v
        .as_array()
        .filter(|a| a.len() == N)
        .ok_or_else(|| bad(&format!("`{what}` is not an array of {N} numbers")))?;
    let mut out = [0.0; N];
    for (o, x) in out.iter_mut().zip(arr) {
        *o = x
            .as_f64()
            .filter(|f| f.is_finite())
            .ok_or_else(|| bad(&format!("`{what}` holds a non-number")))?;
    }
    Ok(out)
}

fn field<'a>(v: &'a Value, name: &str, ctx: &str) -> Result<&'a Value> {
    v.get(name)
        .ok_or_else(|| bad(&format!("{ctx}: `{name}` is missing")))
}

fn curve_point_from_json(v: &Value, ctx: &str) -> Result<CurvePoint> {
    Ok(CurvePoint {
        p: numbers(field(v, "p", ctx)?, &format!("{ctx}.p"))?,
        q: numbers(field(v, "q", ctx)?, &format!("{ctx}.q"))?,
        xyz: numbers(field(v, "xyz", ctx)?, &format!("{ctx}.xyz"))?,
    })
}

fn end_from_json(v: &Value, ctx: &str) -> Result<EndReason> {
    let kind = field(v, "kind", ctx)?
        .as_str()
        .ok_or_else(|| bad(&format!("{ctx}: `kind` is not a string")))?;
    Ok(match kind {
        "boundary" => {
            let surface = field(v, "surface", ctx)?
                .as_u64()
                .filter(|s| *s <= 1)
                .ok_or_else(|| bad(&format!("{ctx}: `surface` is not 0 or 1")))?;
            EndReason::Boundary {
                surface: surface as usize,
            }
        }
        "closed_loop" => EndReason::ClosedLoop,
        "singular" => EndReason::Singular,
        "newton_failed" => EndReason::NewtonFailed,
        "point_limit" => EndReason::PointLimit,
        "own_path" => EndReason::OwnPath,
        other => return Err(bad(&format!("{ctx}: unknown end kind `{other}`"))),
    })
}

fn branch_from_json(v: &Value, k: usize) -> Result<Branch> {
    let ctx = format!("branches[{k}]");
    let id = field(v, "id", &ctx)?
        .as_u64()
        .ok_or_else(|| bad(&format!("{ctx}: `id` is not a non-negative integer")))?
        as usize;
    let status = match field(v, "status", &ctx)?.as_str() {
        Some("closed") => BranchStatus::Closed,
        Some("open") => BranchStatus::Open,
        Some("incomplete") => BranchStatus::Incomplete,
        _ => return Err(bad(&format!("{ctx}: unknown `status`"))),
    };
    let ends_json = field(v, "ends", &ctx)?
        .as_array()
        .filter(|a| a.len() == 2)
        .ok_or_else(|| bad(&format!("{ctx}: `ends` is not an array of 2")))?;
    let ends = [
        end_from_json(&ends_json[0], &format!("{ctx}.ends[0]"))?,
        end_from_json(&ends_json[1], &format!("{ctx}.ends[1]"))?,
    ];
    let points = array(v.get("points"), &format!("{ctx}.points"))?
        .iter()
        .enumerate()
        .map(|(i, p)| curve_point_from_json(p, &format!("{ctx}.points[{i}]")))
        .collect::<Result<Vec<_>>>()?;
    Ok(Branch {
        id,
        status,
        ends,
        points,
    })
}

fn event_from_json(v: &Value, k: usize) -> Result<Event> {
    let ctx = format!("events[{k}]");
    let kind = match field(v, "kind", &ctx)?.as_str() {
        Some("singular") => EventKind::Singular,
        Some("boundary_end") => EventKind::BoundaryEnd,
        _ => return Err(bad(&format!("{ctx}: unknown `kind`"))),
    };
    let c = curve_point_from_json(v, &ctx)?;
    Ok(Event {
        kind,
        p: c.p,
        q: c.q,
        xyz: c.xyz,
    })
}

/// The name of a certified step case in the result JSON (`"transversal"`, `"isolated_point"`,
/// `"branch_point"`, `"tangential_curve"`, `"higher_order"`, `"undefined"`).
pub fn step_case_name(k: crate::certify::contact::StepCase) -> &'static str {
    use crate::certify::contact::StepCase;
    match k {
        StepCase::Transversal => "transversal",
        StepCase::IsolatedPoint => "isolated_point",
        StepCase::BranchPoint => "branch_point",
        StepCase::TangentialCurve => "tangential_curve",
        StepCase::HigherOrder => "higher_order",
        StepCase::Undefined => "undefined",
    }
}

/// A certified tangential contact as `{"tangential": {...}}`: the start box and its case, the
/// per-step cases with their a-priori boxes (`"p"`, `"q"`, `"xyz"`, `"s"`), the ends, the tube
/// radius and (when `tubes` is set) the tube pieces, the cover (`"region"`: searched 4-D boxes,
/// `"boxes"`: kept boxes, `"resolved"`), the f64 band diagnostic and the proven statement. All
/// bounds are the exact outward-rounded `f64` bounds, as in [`enclosure_to_json`].
pub fn certified_contact_to_json(
    c: &crate::certify::contact::CertifiedContact,
    tubes: bool,
) -> Value {
    use crate::certify::contact::{ContactEnd, StepCase};
    let case = |k: StepCase| json!(step_case_name(k));
    let end = |e: &ContactEnd| match e {
        ContactEnd::Boundary { surface } => json!({"kind": "boundary", "surface": surface}),
        ContactEnd::CaseChanged { case: k, near } => {
            json!({"kind": "case_changed", "case": case(*k), "near": intervals_to_json(near)})
        }
        ContactEnd::StepFailed { reason, near } => {
            json!({"kind": "step_failed", "reason": reason, "near": intervals_to_json(near)})
        }
        ContactEnd::Budget { length } => json!({"kind": "budget", "length": length}),
        ContactEnd::NotTraced => json!({"kind": "not_traced"}),
    };
    let steps: Vec<Value> = c
        .steps
        .iter()
        .map(|s| {
            json!({
                "s": s.s,
                "case": case(s.case),
                "p": intervals_to_json(&s.apriori[..2]),
                "q": intervals_to_json(&s.apriori[2..]),
                "xyz": intervals_to_json(&s.xyz),
            })
        })
        .collect();
    let boxes: Vec<Value> = c
        .cover
        .boxes
        .iter()
        .map(|b| {
            json!({
                "p": intervals_to_json(&b.p),
                "q": intervals_to_json(&b.q),
                "xyz": intervals_to_json(&b.xyz),
            })
        })
        .collect();
    let region: Vec<Value> = c
        .cover
        .region
        .iter()
        .map(|r| intervals_to_json(r))
        .collect();
    let mut obj = Map::new();
    obj.insert("start".into(), intervals_to_json(&c.start));
    obj.insert("start_case".into(), case(c.start_case));
    obj.insert("steps".into(), Value::Array(steps));
    obj.insert("ends".into(), json!([end(&c.ends[0]), end(&c.ends[1])]));
    obj.insert("tube_radius".into(), json!(c.tube_radius));
    if tubes {
        obj.insert(
            "tubes".into(),
            Value::Array(c.tubes.iter().map(tube_to_json).collect()),
        );
    }
    obj.insert(
        "cover".into(),
        json!({
            "region": region,
            "boxes": boxes,
            "resolved": c.cover.resolved,
            "evaluations": c.cover.evaluations,
            "max_xyz_width": c.cover.max_xyz_width,
        }),
    );
    obj.insert("cover_band".into(), json!(c.cover_band));
    obj.insert("proven_statement".into(), json!(c.proven_statement));
    json!({ "tangential": Value::Object(obj) })
}
