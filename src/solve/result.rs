//! What [`intersect`](super::intersect) returns: every branch with its marched points, its
//! certificate and its straying report; the events, nodes and certified contacts; how complete
//! the search was; counts and timings.

use inari::Interval;

use super::options::Options;
use crate::certify::contact::CertifiedContact;
use crate::certify::{CertifiedBranch, CertifiedEnd};
use crate::check::straying::StrayReport;
use crate::error::{Error, Result};
use crate::march::branch::{Branch, Event, EventKind, Intersection};
use crate::pair::branch_point::SingularNode;
use crate::search::start_points::UndecidedRegion;
use crate::topology::branch_ends::BranchEndCheck;
use crate::topology::intersect::IntersectStats;

/// The certification of one marched branch.
#[derive(Debug)]
pub struct BranchCertificate {
    /// The id of the marched branch.
    pub branch: usize,
    /// The marched point `(σ, t, u, v)` the certified trace started from (NaN when the branch
    /// had no points).
    pub start: [f64; 4],
    /// The arc-length budget per half branch that was given.
    pub max_length: f64,
    /// The certified branch, or why it could not be certified.
    pub result: Result<CertifiedBranch>,
    /// For each end of the certified branch that is [`CertifiedEnd::Singular`] or
    /// [`CertifiedEnd::CloseBranches`]: the model-space box `P(σ,t) ∩ Q(u,v)` of its parameter
    /// box, when that is bounded and not empty. `None` for other ends.
    pub end_xyz: [Option<[Interval; 3]>; 2],
    /// Wall-clock seconds spent (on the thread that certified it).
    pub seconds: f64,
}

impl BranchCertificate {
    /// The certified branch, `None` when certification failed.
    pub fn certified(&self) -> Option<&CertifiedBranch> {
        self.result.as_ref().ok()
    }

    /// Whether the certified tolerance is at most `tolerance`; `None` when certification failed.
    pub fn meets(&self, tolerance: f64) -> Option<bool> {
        self.certified().map(|c| c.certified_tolerance <= tolerance)
    }

    /// The model-space box of the end whose parameter box is `near` (see
    /// [`end_xyz`](Self::end_xyz)).
    pub fn xyz_of_end(&self, near: &[Interval; 4]) -> Option<[Interval; 3]> {
        let c = self.certified()?;
        c.ends
            .iter()
            .zip(&self.end_xyz)
            .find(|(e, _)| end_box(e) == Some(near))
            .and_then(|(_, x)| *x)
    }
}

/// The parameter box of a singular or close-branches end.
pub(crate) fn end_box(e: &CertifiedEnd) -> Option<&[Interval; 4]> {
    match e {
        CertifiedEnd::Singular { near } | CertifiedEnd::CloseBranches { near, .. } => Some(near),
        _ => None,
    }
}

/// One branch of the intersection.
#[derive(Debug)]
pub struct TracedBranch {
    /// The marched branch: its id, status, ends and points.
    pub marched: Branch,
    /// Its certification, when the method certifies.
    pub certificate: Option<BranchCertificate>,
    /// The marched points checked against the certificates, when the method certifies.
    pub straying: Option<StrayReport>,
    /// Grandine's test of each boundary end of the marched branch, on each face its point lies
    /// on (see [`check_branch_ends`](crate::topology::branch_ends::check_branch_ends)); empty
    /// when no end is on a boundary.
    pub boundary_ends: Vec<Result<Vec<BranchEndCheck>>>,
}

impl TracedBranch {
    /// The id of the branch.
    pub fn id(&self) -> usize {
        self.marched.id
    }

    /// The certified branch, when the method certifies and certification succeeded.
    pub fn certified(&self) -> Option<&CertifiedBranch> {
        self.certificate.as_ref().and_then(|c| c.certified())
    }

    /// The certified tolerance of the branch (model space), when it was certified.
    pub fn certified_tolerance(&self) -> Option<f64> {
        self.certified().map(|c| c.certified_tolerance)
    }
}

/// Counts and seconds of the certification stage.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct CertifyStats {
    /// Certified steps over all certified branches.
    pub certified_steps: usize,
    /// Branches whose certification failed.
    pub failures: usize,
    /// Seconds of branch certification, summed over the branches (each on its own thread).
    pub seconds: f64,
    /// Wall-clock seconds of branch certification (branches run in parallel).
    pub wall_seconds: f64,
    /// Seconds of the straying check.
    pub straying_seconds: f64,
    /// Seconds of the contact certification.
    pub contact_seconds: f64,
    /// Marched points proven off their certified curve, over all branches.
    pub straying_points: usize,
    /// Marched points not checked, over all branches.
    pub unchecked_points: usize,
    /// Branches whose march went round a closed loop more than once.
    pub looping_branches: usize,
    /// Marched branches dropped as traced twice: the marcher jumped between close curves and
    /// every point it marched lies in the certified tubes of other branches.
    pub duplicate_branches: usize,
    /// Branches traced again with a finer step where a marcher jump left a stretch of curve
    /// without a certificate (see `solve/repair.rs`); the branches they replace are dropped as
    /// duplicates.
    pub retraced_branches: usize,
}

/// Counts and timings of a run.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Stats {
    /// The start-point search and the marching: counts, undecided regions, seconds.
    pub search: IntersectStats,
    /// Wall-clock seconds of the marching stage (search and marching).
    pub march_seconds: f64,
    /// Boundary ends that failed Grandine's test (over all branches and faces).
    pub inconsistent_boundary_ends: usize,
    /// The certification stage, when the method certifies.
    pub certify: Option<CertifyStats>,
}

impl Stats {
    /// Seconds of branch certification summed over the branches; 0 when nothing was certified.
    pub fn certify_seconds(&self) -> f64 {
        self.certify.as_ref().map_or(0.0, |c| c.seconds)
    }
}

/// Everything [`intersect`](super::intersect) found on one pair of patches.
#[derive(Debug)]
pub struct SurfaceIntersection {
    /// The options of the run.
    pub options: Options,
    /// The branches, in the marcher's order (ids `0, 1, …`).
    pub branches: Vec<TracedBranch>,
    /// The marcher's events (singular points, boundary ends).
    pub events: Vec<Event>,
    /// The singular points met, with the curve points where their arcs leave.
    pub nodes: Vec<SingularNode>,
    /// The tangential contacts certified from the singular events (empty unless the method
    /// certifies).
    pub contacts: Vec<CertifiedContact>,
    /// Why contact certification failed as a whole, if it did (then `contacts` is empty).
    pub contact_error: Option<Error>,
    /// Counts and timings.
    pub stats: Stats,
}

impl SurfaceIntersection {
    /// The marched branches and events as one [`Intersection`] (a copy), e.g. to write the
    /// result JSON or a picture.
    pub fn marched(&self) -> Intersection {
        Intersection {
            branches: self.branches.iter().map(|b| b.marched.clone()).collect(),
            events: self.events.clone(),
        }
    }

    /// The certificates of the branches, in branch order (empty unless the method certifies).
    pub fn certificates(&self) -> Vec<&BranchCertificate> {
        self.branches
            .iter()
            .filter_map(|b| b.certificate.as_ref())
            .collect()
    }

    /// The straying reports of the branches, in branch order (empty unless the method
    /// certifies).
    pub fn straying(&self) -> Vec<&StrayReport> {
        self.branches
            .iter()
            .filter_map(|b| b.straying.as_ref())
            .collect()
    }

    /// Whether the search settled every region and every start point was traced: then every
    /// branch inside the domains is among [`branches`](Self::branches).
    pub fn is_complete(&self) -> bool {
        self.stats.search.search_complete && self.stats.search.failed_starts == 0
    }

    /// The regions the search could not settle (small features may hide there).
    pub fn undecided_regions(&self) -> &[UndecidedRegion] {
        &self.stats.search.undecided_regions
    }

    /// Whether every branch was certified and meets the required tolerance (`false` for
    /// [`Method::March`](super::Method::March)).
    pub fn all_certified(&self) -> bool {
        self.options.method.certifies()
            && self.branches.iter().all(|b| {
                b.certificate
                    .as_ref()
                    .and_then(|c| c.meets(self.options.required_tolerance))
                    == Some(true)
            })
    }

    /// The graph node at the `k`-th event, when that event is singular and a node lies at it
    /// (within a relative `1e-6` in model space).
    pub fn event_node(&self, k: usize) -> Option<&SingularNode> {
        let e = self.events.get(k)?;
        if e.kind != EventKind::Singular {
            return None;
        }
        self.nodes.iter().find(|n| {
            let d2: f64 = (0..3).map(|i| (n.xyz[i] - e.xyz[i]).powi(2)).sum();
            d2 <= 1e-12 * (1.0 + e.xyz.iter().map(|x| x * x).sum::<f64>())
        })
    }
}
