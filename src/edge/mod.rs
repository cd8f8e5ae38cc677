//! Edges for a B-rep kernel: a certified branch (or a joined shell curve of several branches)
//! as a 3D B-spline, two p-curves and one proven tolerance.
//!
//! A cover-chain certificate ([`crate::certify::chain`]) reports, per link, a polynomial in
//! one parameter `τ` ([`TubePiece::coeffs`], all four parameters `(σ, t, u, v)`) and proven
//! radii: every true curve point is within `radius_param` (parameters, max norm) and
//! `radius_xyz` (model space) of the reported point with the same along-coordinate, and the
//! reverse. An edge is built from those polynomials:
//!
//! - **Fine spans.** Each link (cut where the edge ends) is two fine spans of the edge's
//!   parameter `s` (four where two stalled above the request, in a second build kept if
//!   closer), each as long as the arc length of its reported image `P(σ, t)` (nominal, `f64`):
//!   `s` is a nominal arc length, smooth across the links whatever their along coordinates.
//!   On the span, `r ∈ [0, 1]` is affine in `s`, and the reported curve is compared with the
//!   coarse curves at `u = w(r)`, the span's warp (`warp.rs`): a polynomial of degree 5 with
//!   exact ends `w(0) = 0`, `w(1) = 1` and `w([0, 1]) ⊂ [0, 1]` (Bernstein coefficients in
//!   `[0, 1]`), fitted to the inverse arc length. So every point of the link's piece is compared
//!   at some `s` of its span, and every `s` with a point of the piece.
//! - **Coarse curves.** Per part (one branch's stretch of a joined curve), one clamped B-spline
//!   of degree 8 on a few of the fine knots: the 3D curve and the two
//!   p-curves share its knots. Interior knots are simple (C7), raised (up to 8, C0) only where
//!   refining a single fine span cannot meet the target otherwise. Control points are fitted
//!   by least squares to samples `P(y(w(r)))`, `y(w(r))` (`f64`, guidance only; the p-curves
//!   per parameter, each sample weighted by the surface's derivative in it), the part's
//!   ends fixed; the parts' 3D curves share their end points and are joined with knots of
//!   multiplicity 8 (so each part's stretch is exactly a B-spline on the p-curves' knots).
//! - **Bounds**, per fine span: the coarse spline's polynomial on the span is enclosed by
//!   interval knot insertion and re-expansion in the span's `r` (`fit.rs`). P-curves:
//!   `δ = sup |pcurve − y(w(r))|` and 3D: `sup |curve − P(y(w(r)))|`, each by an interval
//!   Taylor form of order 8 in `r` with a Lagrange remainder on four sub-intervals (the
//!   reported side's coefficients, through the warp, computed once per span). Then 3D curve to
//!   true ≤ that + `radius_xyz`; `P(pcurve_P)` to true ≤ `radius_xyz` + `|DP·δ_P|`;
//!   `Q(pcurve_Q)` to true ≤ `radius_xyz` + `|DQ·δ_Q|` (a link's `radius_xyz` bounds the
//!   reported curve's images on both surfaces) or `|DQ·(radius_param + δ_Q)|` (the smaller),
//!   the derivatives enclosed over the span's parameter box widened by those amounts. `δ` is
//!   kept per parameter (`DQ·δ_Q = ∂Q/∂u·δ_u + ∂Q/∂v·δ_v`): on a domain whose sides differ by
//!   orders of magnitude a max-norm `δ` would multiply the long side's error by the short
//!   side's derivative. Every curve is compared
//!   with the same reported point at the same `s`, and the warp maps the span onto the link's
//!   piece, so each bound holds both ways.
//! - **Refinement.** The target is the requested tolerance (when the certificates' floor is
//!   under it, and never less than 2% above the floor: the fit's bounds add to it; else a
//!   quarter above the floor). Coarse spans whose fine spans' bounds exceed
//!   it are cut at fine knots (or their knots' multiplicity raised) and the part is fitted and
//!   bounded again, a bounded number of rounds. A region refined three times in a row without
//!   its worst bound falling stops being refined, and the other spans aim no lower than the
//!   best bound it reached. Then, on parts of few coarse spans, the knots the refinement did
//!   not need are removed one by one while the part's bounds stay within the goal. The bounds
//!   reported are those of the final curves, whatever the target. A request missed because
//!   the fit stalled is built again with four fine spans in the stalled spans' links; where
//!   regions stall also depends on the aim, so a request still missed with more room than 2%
//!   is aimed again at 2% above the floor (that aim costs control points, so it comes last).
//!   The closest edge is kept; one still above the request says why ([`Shortfall`]).
//! - **Cuts.** A chain is cut where the edge must end: a closed loop where its last link meets
//!   the start box again, a boundary end (the chain goes on a little past the domain's side, on
//!   the patch extended beyond it) and a joined curve's piece side at the side. A range `T` of
//!   the link's `τ` is proven to hold the true end point; every curve point over `T` is within
//!   `radius_xyz` + the diameter of `P(σ, t)` over `T` + the three curves' distance from the
//!   reported image on the cut link's fine spans.
//! - **Tolerance.** [`Edge::edge_tolerance`] is the largest of all those bounds and of the
//!   certificates' own tolerances: every point of the 3D curve, and of each p-curve's image on
//!   its surface, is within it of the true curve, and every true curve point is within it of
//!   each of them.
//!
//! Certificates of the Taylor engine (arc-length tubes with re-anchoring gaps) are refused with
//! [`EdgeError::NotCoverChain`].
//!
//! Limits: a cut is proven in the one coordinate of the side it crosses (a curve leaving a piece
//! through a corner is cut at the first side found); the links before the cut link are taken as
//! inside the piece, as the certificate's chain between its ends is. The 3D curve is not
//! rational and its knots are nominal; only the bounds are proven, the `f64` construction is not.
//! Coarse knots are fine knots (link ends). The arc-length parameter is not the best one for
//! every curve: the two loops of S31/S32 need about three times the spans that a parameter by
//! the angle round the loop's centre would.

mod bspline;
mod build;
mod fit;
mod joined;
mod poly;
mod span;
mod warp;

pub use bspline::BSpline;
pub use joined::edge_from_joined;

use crate::certify::{CertifiedBranch, CertifiedEnd, TubePiece};
use crate::geometry::RationalBezierPatch;
use crate::numeric::scalar::point;
use crate::solve::TracedBranch;
use build::assemble;
use inari::Interval;
use poly::DEGREE;

/// Why no edge can be made.
#[derive(Debug, Clone, PartialEq)]
pub enum EdgeError {
    /// The branch has no certificate (the method does not certify, or certification failed).
    NotCertified {
        /// The branch.
        branch: usize,
        /// Why.
        reason: String,
    },
    /// The certificate's boxes or tubes do not form one gap-free chain.
    NotGapFree {
        /// The branch.
        branch: usize,
        /// Where and why.
        reason: String,
    },
    /// The certificate is not a cover chain (no along-parameter polynomials of degree ≤ 7).
    NotCoverChain {
        /// The branch.
        branch: usize,
    },
    /// A join of a joined curve is not proven.
    UnprovenJoin {
        /// The index of the join in the curve.
        join: usize,
        /// Why.
        reason: String,
    },
    /// A joined curve's part could not be cut at the piece side it crosses.
    Trim {
        /// The branch.
        branch: usize,
        /// Why.
        reason: String,
    },
    /// An enclosure came out unbounded.
    Unbounded {
        /// The branch.
        branch: usize,
    },
}

impl std::fmt::Display for EdgeError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            EdgeError::NotCertified { branch, reason } => {
                write!(f, "branch {branch} is not certified: {reason}")
            }
            EdgeError::NotGapFree { branch, reason } => {
                write!(f, "branch {branch} is not a gap-free chain: {reason}")
            }
            EdgeError::NotCoverChain { branch } => {
                write!(f, "branch {branch} is not a cover-chain certificate")
            }
            EdgeError::UnprovenJoin { join, reason } => {
                write!(f, "join {join} is not proven: {reason}")
            }
            EdgeError::Trim { branch, reason } => {
                write!(
                    f,
                    "branch {branch} could not be cut at its piece side: {reason}"
                )
            }
            EdgeError::Unbounded { branch } => {
                write!(f, "an enclosure of branch {branch} is unbounded")
            }
        }
    }
}

impl std::error::Error for EdgeError {}

/// A p-curve: the edge on one surface, over a part of the edge's parameter range.
#[derive(Debug, Clone, PartialEq)]
pub struct PCurve {
    /// 0: on P (`(σ, t)`, shell A), 1: on Q (`(u, v)`, shell B).
    pub surface: usize,
    /// The face of that shell (0 for a two-surface scene).
    pub face: usize,
    /// The Bézier piece of that face (0 for a two-surface scene).
    pub piece: usize,
    /// The branch it comes from.
    pub branch: usize,
    /// The curve in the surface's parameters, on the same knots as the 3D curve over its range
    /// (degree 8).
    pub curve: BSpline<2>,
    /// Proven max-norm distance in parameters from the true curve's parameters.
    pub param_tolerance: f64,
    /// Proven model-space distance of its image on the surface from the true curve.
    pub image_tolerance: f64,
}

/// The proven bounds an edge's tolerance is the largest of (model space unless said).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EdgeBounds {
    /// 3D curve to the true curve.
    pub curve_3d: f64,
    /// 3D curve to the image of the reported link polynomials on P (the part of `curve_3d`
    /// that the construction adds).
    pub model_fit: f64,
    /// 3D curve to `P(pcurve_P)` at the same parameter.
    pub same_parameter: f64,
    /// `P(pcurve_P)` to the true curve.
    pub pcurve_p_image: f64,
    /// `Q(pcurve_Q)` to the true curve.
    pub pcurve_q_image: f64,
    /// P-curves to the true curve's parameters (max norm, parameter units).
    pub pcurve_p_param: f64,
    /// The same on Q.
    pub pcurve_q_param: f64,
    /// The largest bound at a cut (closed loop's end, piece side); 0 without cuts.
    pub cuts: f64,
    /// The largest certified tolerance of the branches.
    pub certified_tolerance: f64,
}

/// Why an edge's proven tolerance is above the tolerance it was asked for.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Shortfall {
    /// The certificates alone (the links' radii, the true arcs at the cuts) exceed the
    /// request: no curve compared with the chain can meet it; the chain must be certified
    /// more tightly. The coarse curves aimed a quarter above this floor (and came within twice
    /// it: farther above, the fit is named instead).
    Certificate {
        /// The largest certified tolerance or cut share.
        floor: f64,
    },
    /// Refining the coarse curves stopped lowering the bounds of some fine spans: a cut or a
    /// raised knot no longer halved them (a link too long for one degree-8 piece through its
    /// warp, the enclosures' rounding), or they could not be cut further. Refinement stopped
    /// there rather than add control points that buy nothing; the other spans aimed at their
    /// level.
    FitStalled {
        /// Fine spans whose bounds stayed above the request.
        spans: usize,
        /// The largest bound among them.
        level: f64,
    },
    /// The rounds of refinement ran out while the bounds were still falling.
    Rounds {
        /// The rounds used.
        rounds: usize,
    },
}

impl std::fmt::Display for Shortfall {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Shortfall::Certificate { floor } => {
                write!(f, "the certificates alone are {floor:.2e}")
            }
            Shortfall::FitStalled { spans, level } => write!(
                f,
                "refinement stopped lowering {spans} span(s) at {level:.2e}"
            ),
            Shortfall::Rounds { rounds } => write!(f, "{rounds} rounds of refinement ran out"),
        }
    }
}

/// An edge: the 3D curve, the p-curves and the proven tolerance.
#[derive(Debug, Clone, PartialEq)]
pub struct Edge {
    /// The 3D curve (degree 8; per part a B-spline with few knots, parts joined C0).
    pub curve: BSpline<3>,
    /// The p-curves: for one branch, one on P then one on Q; for a joined curve, one per part
    /// and surface.
    pub pcurves: Vec<PCurve>,
    /// Whether the edge is closed (its last point is its first).
    pub closed: bool,
    /// The proven two-sided tolerance: the largest of [`Edge::bounds`] (model space).
    pub edge_tolerance: f64,
    /// The bounds it is made of.
    pub bounds: EdgeBounds,
    /// The tolerance asked for (`None`: aim a little above the certificates').
    pub requested: Option<f64>,
    /// Why `edge_tolerance` is above `requested` (`None` when it is not, or none was asked).
    pub shortfall: Option<Shortfall>,
    /// The branches, in order along the edge.
    pub branches: Vec<usize>,
    /// Chain links used.
    pub links: usize,
}

/// One piece of a link in the edge's direction: `τ` from `ta` to `tb`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Seg {
    pub(crate) tube: usize,
    pub(crate) ta: f64,
    pub(crate) tb: f64,
}

/// A cut of the chain on `tube` at the end of the range `gap` of its `τ` (or inside it): the
/// true end point lies on the true arc over `gap`, or (`next`) over the range of the next
/// link's `τ` where the cut range straddles the junction of the two links. At a join across a
/// corner of the piece pair, `corner` is the diameter of the corner box holding the true arc
/// between this part's end and the next part's start (0 elsewhere): a share of its own.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Cut {
    pub(crate) tube: usize,
    pub(crate) gap: Interval,
    pub(crate) next: Option<(usize, Interval)>,
    pub(crate) corner: f64,
}

/// One branch's share of an edge.
pub(crate) struct Part<'a> {
    pub(crate) p: &'a RationalBezierPatch,
    pub(crate) q: &'a RationalBezierPatch,
    pub(crate) cert: &'a CertifiedBranch,
    pub(crate) branch: usize,
    pub(crate) faces: [usize; 2],
    pub(crate) pieces: [usize; 2],
    pub(crate) segs: Vec<Seg>,
    pub(crate) cuts: Vec<Cut>,
}

/// The edge of the traced branch `b` of `P ∩ Q`, aiming at a tolerance a little above the
/// certificate's (the requested one is not known here: see [`edge_from_branch_within`]).
///
/// Errors: [`EdgeError::NotCertified`] without a certificate, else as
/// [`edge_from_certified`].
pub fn edge_from_branch(
    p: &RationalBezierPatch,
    q: &RationalBezierPatch,
    b: &TracedBranch,
) -> Result<Edge, EdgeError> {
    edge_from_branch_within(p, q, b, None)
}

/// [`edge_from_branch`] aiming at the tolerance `requested` (the run's required tolerance):
/// the coarse curves use the room between the certificate's tolerance and it.
///
/// Errors: as [`edge_from_branch`].
pub fn edge_from_branch_within(
    p: &RationalBezierPatch,
    q: &RationalBezierPatch,
    b: &TracedBranch,
    requested: Option<f64>,
) -> Result<Edge, EdgeError> {
    let id = b.id();
    let cert = match &b.certificate {
        None => {
            return Err(EdgeError::NotCertified {
                branch: id,
                reason: "the method does not certify".into(),
            })
        }
        Some(c) => c.result.as_ref().map_err(|e| EdgeError::NotCertified {
            branch: id,
            reason: e.to_string(),
        })?,
    };
    edge_from_certified_within(p, q, cert, id, requested)
}

/// The edge of the certified branch `cert` (numbered `branch` in errors) of `P ∩ Q`. A branch
/// whose ends are both [`CertifiedEnd::ClosedLoop`] gives a closed edge.
///
/// Errors: [`EdgeError::NotCoverChain`], [`EdgeError::NotGapFree`], [`EdgeError::Unbounded`].
pub fn edge_from_certified(
    p: &RationalBezierPatch,
    q: &RationalBezierPatch,
    cert: &CertifiedBranch,
    branch: usize,
) -> Result<Edge, EdgeError> {
    edge_from_certified_within(p, q, cert, branch, None)
}

/// [`edge_from_certified`] aiming at the tolerance `requested` (see
/// [`edge_from_branch_within`]).
///
/// Errors: as [`edge_from_certified`].
pub fn edge_from_certified_within(
    p: &RationalBezierPatch,
    q: &RationalBezierPatch,
    cert: &CertifiedBranch,
    branch: usize,
    requested: Option<f64>,
) -> Result<Edge, EdgeError> {
    check_chain(cert, branch)?;
    let mut segs = chain_segs(cert, false);
    let closed = cert.ends.iter().all(|e| *e == CertifiedEnd::ClosedLoop);
    let mut cuts = Vec::new();
    if closed {
        cuts.push(close_loop(cert, &mut segs, branch)?);
    } else {
        // A boundary end: the chain goes on a little past the domain's side (on the patch
        // extended beyond it); it is cut at the side.
        let ends = [&cert.ends[0], &cert.ends[1]];
        cuts = joined::cut_ends(cert, &mut segs, ends, [p, q], branch, [None; 2])?;
    }
    let part = Part {
        p,
        q,
        cert,
        branch,
        faces: [0, 0],
        pieces: [0, 0],
        segs,
        cuts,
    };
    assemble(&[part], closed, closed, requested)
}

/// Checks that `cert` is a gap-free cover chain this module can read.
pub(crate) fn check_chain(cert: &CertifiedBranch, branch: usize) -> Result<(), EdgeError> {
    let gap = |reason: String| EdgeError::NotGapFree { branch, reason };
    if cert.tubes.is_empty() {
        return Err(gap("no tube pieces".into()));
    }
    if cert.tubes.len() != cert.boxes.len() {
        return Err(gap(format!(
            "{} tube pieces for {} boxes",
            cert.tubes.len(),
            cert.boxes.len()
        )));
    }
    for t in &cert.tubes {
        if t.along.is_none() || t.coeffs.len() > DEGREE + 1 || t.coeffs.is_empty() {
            return Err(EdgeError::NotCoverChain { branch });
        }
        let finite = t.radius_param.is_finite()
            && t.radius_xyz.is_finite()
            && t.h.is_finite()
            && t.coeffs.iter().flatten().all(|c| c.is_finite());
        if !finite {
            return Err(EdgeError::Unbounded { branch });
        }
    }
    for (k, w) in cert.boxes.windows(2).enumerate() {
        if !w[0].overlaps(&w[1]) {
            return Err(gap(format!("boxes {k} and {} do not overlap", k + 1)));
        }
    }
    Ok(())
}

/// The chain's links in the order of increasing arc length (or decreasing, `reversed`), each
/// from where it starts along that order to where it ends.
pub(crate) fn chain_segs(cert: &CertifiedBranch, reversed: bool) -> Vec<Seg> {
    let mut segs: Vec<Seg> = cert
        .tubes
        .iter()
        .enumerate()
        .map(|(k, t)| {
            let (ta, tb) = if t.direction > 0.0 {
                (0.0, t.h)
            } else {
                (t.h, 0.0)
            };
            Seg { tube: k, ta, tb }
        })
        .collect();
    if reversed {
        segs.reverse();
        for s in &mut segs {
            std::mem::swap(&mut s.ta, &mut s.tb);
        }
    }
    segs
}

/// The `τ` values of a tube piece at which its along coordinate takes the values `x`.
pub(crate) fn tau_of(t: &TubePiece, x: Interval) -> Interval {
    let j = t.along.map(|a| a.index).unwrap_or(0);
    let from = t.coeffs[0][j];
    let dir = t.coeffs.get(1).map(|c| c[j]).unwrap_or(1.0);
    (x - point(from)) * point(dir)
}

/// A closed loop: the last link is cut where it meets the start box again (its tube holds the
/// start box, so the true start point is its curve point at some `τ` of that box's range).
fn close_loop(cert: &CertifiedBranch, segs: &mut [Seg], branch: usize) -> Result<Cut, EdgeError> {
    let trim = |reason: &str| EdgeError::Trim {
        branch,
        reason: reason.into(),
    };
    let last = segs.last_mut().ok_or_else(|| trim("no links"))?;
    let t = &cert.tubes[last.tube];
    if last.ta != 0.0 {
        return Err(trim("a closed chain ends on a backward link"));
    }
    let j = t.along.map(|a| a.index).unwrap_or(0);
    let ts = tau_of(t, cert.start[j]);
    if ts.is_empty() || !ts.sup().is_finite() {
        return Err(trim("the start box does not meet the last link"));
    }
    let at = ts.mid().clamp(0.0, t.h);
    last.tb = at;
    let gap = ts
        .convex_hull(point(at))
        .intersection(inari::interval!(0.0, t.h).unwrap_or(Interval::ENTIRE));
    Ok(Cut {
        tube: last.tube,
        gap: if gap.is_empty() { point(at) } else { gap },
        next: None,
        corner: 0.0,
    })
}

/// Every branch of a two-surface result as an edge, or why not (branch id and outcome).
pub fn edges_of(
    p: &RationalBezierPatch,
    q: &RationalBezierPatch,
    r: &crate::solve::SurfaceIntersection,
) -> Vec<(usize, Result<Edge, EdgeError>)> {
    r.branches
        .iter()
        .map(|b| {
            let tol = Some(r.options.required_tolerance);
            (b.id(), edge_from_branch_within(p, q, b, tol))
        })
        .collect()
}

/// Every joined curve of a shell result as an edge, or why not (curve index and outcome).
pub fn edges_of_shells(
    a: &[crate::shell::Face],
    b: &[crate::shell::Face],
    r: &crate::shell::ShellIntersection,
) -> Vec<(usize, Result<Edge, EdgeError>)> {
    r.curves
        .iter()
        .enumerate()
        .map(|(k, c)| (k, edge_from_joined(a, b, r, c)))
        .collect()
}
