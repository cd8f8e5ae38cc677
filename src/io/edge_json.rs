//! The edge document (`ssitrace-edges`, version 1): each certified curve as a B-rep edge, a 3D
//! B-spline, its p-curves and its proven tolerance ([`crate::edge`]). The format is described
//! in `docs/result-format.md`.

use serde_json::{json, Value};
use std::path::Path;

use crate::edge::{BSpline, Edge, EdgeError, Shortfall};
use crate::{Error, Result};

/// The value of the `"format"` member.
pub const EDGE_FORMAT: &str = "ssitrace-edges";
/// The version written.
pub const EDGE_VERSION: u64 = 1;

fn spline_json<const D: usize>(b: &BSpline<D>) -> Value {
    json!({
        "degree": b.degree,
        "knots": b.knots,
        "control_points": b.points.iter().map(|p| p.to_vec()).collect::<Vec<_>>(),
        "weights": Value::Null,
    })
}

/// One edge as JSON.
pub fn edge_to_json(e: &Edge) -> Value {
    let b = &e.bounds;
    let pcurves: Vec<Value> = e
        .pcurves
        .iter()
        .map(|c| {
            let mut v = spline_json(&c.curve);
            v["surface"] = json!(if c.surface == 0 { "P" } else { "Q" });
            v["face"] = json!(c.face);
            v["piece"] = json!(c.piece);
            v["branch"] = json!(c.branch);
            v["param_tolerance"] = json!(c.param_tolerance);
            v["image_tolerance"] = json!(c.image_tolerance);
            v
        })
        .collect();
    let shortfall = e.shortfall.map(|s| {
        let mut v = match s {
            Shortfall::Certificate { floor } => json!({ "reason": "certificate", "floor": floor }),
            Shortfall::FitStalled { spans, level } => {
                json!({ "reason": "fit_stalled", "spans": spans, "level": level })
            }
            Shortfall::Rounds { rounds } => json!({ "reason": "rounds", "rounds": rounds }),
        };
        v["message"] = json!(s.to_string());
        v
    });
    json!({
        "branches": e.branches,
        "closed": e.closed,
        "edge_tolerance": e.edge_tolerance,
        "requested_tolerance": e.requested,
        "shortfall": shortfall,
        "links": e.links,
        "curve": spline_json(&e.curve),
        "pcurves": pcurves,
        "bounds": {
            "curve_3d": b.curve_3d,
            "model_fit": b.model_fit,
            "same_parameter": b.same_parameter,
            "pcurve_p_image": b.pcurve_p_image,
            "pcurve_q_image": b.pcurve_q_image,
            "pcurve_p_param": b.pcurve_p_param,
            "pcurve_q_param": b.pcurve_q_param,
            "cuts": b.cuts,
            "certified_tolerance": b.certified_tolerance,
        },
    })
}

/// The edge document: `source` names what each outcome is numbered by (`"branch"` for a
/// two-surface scene, `"curve"` for the joined curves of a shell scene). An edge's number is
/// written as `source`, except that a joined curve's is `"curve_index"` (`"curve"` is the
/// edge's 3D B-spline); a skipped outcome's as `source`.
pub fn edges_document(
    scene: Option<&str>,
    source: &str,
    outcomes: &[(usize, std::result::Result<Edge, EdgeError>)],
) -> Value {
    let mut edges = Vec::new();
    let mut skipped = Vec::new();
    for (k, o) in outcomes {
        match o {
            Ok(e) => {
                let mut v = edge_to_json(e);
                let key = if source == "curve" {
                    "curve_index"
                } else {
                    source
                };
                v[key] = json!(k);
                edges.push(v);
            }
            Err(err) => skipped.push(json!({ source: k, "error": err.to_string() })),
        }
    }
    json!({
        "format": EDGE_FORMAT,
        "version": EDGE_VERSION,
        "scene": scene,
        "edges": edges,
        "skipped": skipped,
    })
}

/// Writes the edge document to `path`.
///
/// Errors: [`Error::Io`] when the file cannot be written.
pub fn write_edges(path: &Path, doc: &Value) -> Result<()> {
    let mut text = serde_json::to_string_pretty(doc)
        .map_err(|e| Error::ResultFormat(format!("serialisation failed: {e}")))?;
    text.push('\n');
    std::fs::write(path, text).map_err(|e| Error::Io {
        path: path.display().to_string(),
        message: e.to_string(),
    })
}
