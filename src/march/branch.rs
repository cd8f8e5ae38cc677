//! The result of intersecting two surfaces: branches of curve points and events.
//!
//! This is the data behind the result JSON (see `docs/result-format.md` for the versioned format).

/// One point of a traced branch, in both parameter domains and in model space.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CurvePoint {
    /// Parameters `[σ, t]` on the first surface P.
    pub p: [f64; 2],
    /// Parameters `[u, v]` on the second surface Q.
    pub q: [f64; 2],
    /// Model-space point (the midpoint of P(σ,t) and Q(u,v)).
    pub xyz: [f64; 3],
}

/// How a branch ended (at one of its two ends).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum EndReason {
    /// Reached the boundary of surface 0 (P) or 1 (Q).
    Boundary {
        /// Which surface's boundary (0 = P, 1 = Q).
        surface: usize,
    },
    /// Came back to its start: a closed loop, traced once.
    ClosedLoop,
    /// Reached a point where the surface normals are parallel (tangency / singular point).
    Singular,
    /// Newton refinement failed (the step could not be corrected onto the curve).
    NewtonFailed,
    /// Hit the point budget without another end condition.
    PointLimit,
    /// Came back onto its own earlier path (not at its start) with the same direction: it went
    /// on along another curve after a jump, reached a closed loop of that curve and would go
    /// round it again.
    OwnPath,
}

impl EndReason {
    /// Whether the end is a regular one, as the curve's own: a boundary or a singular point.
    pub fn is_regular(&self) -> bool {
        matches!(self, EndReason::Boundary { .. } | EndReason::Singular)
    }
}

impl std::fmt::Display for EndReason {
    /// `boundary of P`, `boundary of Q`, `closed loop`, `singular point`, `Newton failed`,
    /// `point limit`, `own path`.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            EndReason::Boundary { surface } => {
                write!(f, "boundary of {}", if *surface == 0 { "P" } else { "Q" })
            }
            EndReason::ClosedLoop => f.write_str("closed loop"),
            EndReason::Singular => f.write_str("singular point"),
            EndReason::NewtonFailed => f.write_str("Newton failed"),
            EndReason::PointLimit => f.write_str("point limit"),
            EndReason::OwnPath => f.write_str("own path"),
        }
    }
}

/// Overall status of a branch.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BranchStatus {
    /// A closed loop traced exactly once.
    Closed,
    /// An open branch whose both ends are regular ends (boundary or singular point).
    Open,
    /// Tracing stopped for a reason that leaves the branch possibly incomplete.
    Incomplete,
}

impl BranchStatus {
    /// The status of a branch with these ends: closed when the last one closes a loop, open
    /// when both are regular ([`EndReason::is_regular`]), incomplete otherwise.
    pub fn of_ends(ends: &[EndReason; 2]) -> BranchStatus {
        if ends[1] == EndReason::ClosedLoop {
            BranchStatus::Closed
        } else if ends.iter().all(EndReason::is_regular) {
            BranchStatus::Open
        } else {
            BranchStatus::Incomplete
        }
    }
}

/// A traced branch: points ordered along the curve.
#[derive(Debug, Clone, PartialEq)]
pub struct Branch {
    /// Index in the result.
    pub id: usize,
    /// Overall status.
    pub status: BranchStatus,
    /// How the branch ended at its start and at its end (for a closed loop both are `ClosedLoop`).
    pub ends: [EndReason; 2],
    /// The points, in order along the branch.
    pub points: Vec<CurvePoint>,
}

impl Branch {
    /// Model-space length of the polyline through the points (0 for fewer than two).
    pub fn length(&self) -> f64 {
        polyline_length(&self.points)
    }
}

/// Model-space length of the polyline through `points` (0 for fewer than two).
pub fn polyline_length(points: &[CurvePoint]) -> f64 {
    points
        .windows(2)
        .map(|w| {
            (0..3)
                .map(|i| (w[1].xyz[i] - w[0].xyz[i]).powi(2))
                .sum::<f64>()
                .sqrt()
        })
        .sum()
}

/// Kinds of noteworthy points.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum EventKind {
    /// Normals parallel: a tangential contact, branch point or singular point.
    Singular,
    /// A branch meets a domain boundary.
    BoundaryEnd,
}

/// A noteworthy point found while tracing.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Event {
    /// What it is.
    pub kind: EventKind,
    /// Parameters on P.
    pub p: [f64; 2],
    /// Parameters on Q.
    pub q: [f64; 2],
    /// Model-space point.
    pub xyz: [f64; 3],
}

/// All branches and events of one surface pair.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Intersection {
    /// The traced branches.
    pub branches: Vec<Branch>,
    /// Noteworthy points.
    pub events: Vec<Event>,
}
