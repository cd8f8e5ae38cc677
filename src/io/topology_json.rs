//! JSON notes on the topology of a result: the boundary-direction check of each branch end
//! (`"boundary_ends"` on a branch) and the singular nodes of the graph tracer (`"node"` on a
//! singular event). They are written into the result document through
//! [`ResultMeta::branch_notes`](crate::io::result_json::ResultMeta::branch_notes) and
//! [`ResultMeta::event_notes`](crate::io::result_json::ResultMeta::event_notes).

use crate::error::Result;
use crate::pair::boundary_direction::{Bound, BoundaryDirection, DecidedBy};
use crate::pair::branch_point::SingularNode;
use crate::pair::contact_quadratic::ContactCase;
use crate::topology::branch_ends::BranchEndCheck;
use serde_json::{json, Value};

/// The name of a boundary direction in the result JSON.
pub fn direction_name(d: BoundaryDirection) -> &'static str {
    match d {
        BoundaryDirection::Enters => "enters",
        BoundaryDirection::Leaves => "leaves",
        BoundaryDirection::Touches { inside: true } => "touches_inside",
        BoundaryDirection::Touches { inside: false } => "touches_outside",
        BoundaryDirection::Isolated => "isolated",
        BoundaryDirection::Undecided => "undecided",
    }
}

fn decided_by_name(d: DecidedBy) -> &'static str {
    match d {
        DecidedBy::FirstOrder => "first_order",
        DecidedBy::SecondOrder => "second_order",
        DecidedBy::ContactQuadratic => "contact_quadratic",
        DecidedBy::PerturbationLimit => "perturbation_limit",
        DecidedBy::Nothing => "nothing",
    }
}

/// A branch's `"boundary_ends"` array: per boundary end and face, `{"end", "coordinate",
/// "bound", "seen", "consistent", "proven", "critical", "decided_by"}` (`seen`: what the curve
/// does there for a traveller along the branch), or `{"error"}` for an end that could not be
/// classified.
pub fn boundary_ends_to_json(checks: &[Result<Vec<BranchEndCheck>>]) -> Value {
    let mut out = Vec::new();
    for c in checks {
        match c {
            Ok(faces) => out.extend(faces.iter().map(|f| {
                json!({
                    "end": f.end,
                    "coordinate": f.side.coordinate,
                    "bound": if f.side.bound == Bound::Min { "min" } else { "max" },
                    "seen": direction_name(f.seen),
                    "consistent": f.consistent,
                    "proven": f.classification.proven,
                    "critical": f.classification.critical,
                    "decided_by": decided_by_name(f.classification.decided_by),
                })
            })),
            Err(e) => out.push(json!({ "error": e.to_string() })),
        }
    }
    Value::Array(out)
}

/// The name of a contact case in the result JSON (`"isolated_point"`, `"branch_point"`,
/// `"tangential_curve"`, `"higher_order"`).
pub fn contact_case_name(c: ContactCase) -> &'static str {
    match c {
        ContactCase::IsolatedPoint => "isolated_point",
        ContactCase::BranchPoint => "branch_point",
        ContactCase::TangentialCurve => "tangential_curve",
        ContactCase::HigherOrder => "higher_order",
    }
}

/// A singular event's `"node"` object: the contact case, `Δ`, whether the point was located
/// (parallel normals converged), the number of arcs leaving it and their exit points.
pub fn node_to_json(n: &SingularNode) -> Value {
    json!({
        "case": contact_case_name(n.case),
        "discriminant": n.discriminant,
        "located": n.located,
        "arcs": n.exits.len(),
        "exits": n.exits,
        "exit_xyz": n.exit_xyz,
        "radius": n.radius,
    })
}
