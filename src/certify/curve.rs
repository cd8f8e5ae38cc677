//! What a certified branch reports: gap-free boxes in three spaces, tight tubes, end reasons.

use inari::Interval;

/// One link of the chain: a box holding the true curve over an arc-length range, in both
/// parameter domains and in model space.
///
/// Guarantee: for every arc length `s ∈ [s[0], s[1]]` the true intersection point has
/// parameters in `p` (on P) and `q` (on Q) and lies in `xyz`. Consecutive ranges touch, and
/// consecutive boxes share the point at their common arc length, so they overlap: the chain has
/// no gaps. (A re-anchored step's nominal arc lengths are off by at most its
/// [`TubePiece::s0_error`]; the box holds the curve over its nominal range widened by that error on
/// both sides, and the published range is the part of it that makes the ranges touch.)
///
/// In a cover-chain certificate ([`crate::certify::chain`], where
/// [`CertifiedBranch::arc_length_proven`] is false) `s` is the arc length of the reported curve,
/// not a proven one, and the guarantee is stated in parameters instead: the certified arc is a
/// graph over its link's along coordinate ([`TubePiece::along`]), the box holds the part of it
/// whose along coordinate lies in the box's interval of that coordinate, and consecutive boxes
/// share a point of it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EnclosureBox {
    /// Arc-length range `[s0, s1]` from the branch's start point (negative backwards).
    pub s: [f64; 2],
    /// `[σ] × [t]` on P.
    pub p: [Interval; 2],
    /// `[u] × [v]` on Q.
    pub q: [Interval; 2],
    /// The model-space box: `P([σ],[t]) ∩ Q([u],[v])`.
    pub xyz: [Interval; 3],
}

impl EnclosureBox {
    /// The four parameter intervals `(σ, t, u, v)`.
    pub fn params(&self) -> [Interval; 4] {
        [self.p[0], self.p[1], self.q[0], self.q[1]]
    }

    /// Whether this box and `other` share a point in all three spaces.
    pub fn overlaps(&self, other: &EnclosureBox) -> bool {
        let meet = |a: &[Interval], b: &[Interval]| a.iter().zip(b).all(|(x, y)| !x.disjoint(*y));
        meet(&self.p, &other.p) && meet(&self.q, &other.q) && meet(&self.xyz, &other.xyz)
    }
}

/// One step's reported curve and its proven radius.
///
/// The reported parameter curve is `y(τ) = Σᵢ coeffs[i]·τⁱ` for `τ ∈ [0, h]` (arc length
/// `s0 + τ`, or `s0 − τ` for a backward piece), `y = (σ, t, u, v)`; the reported model curve
/// is `P(σ(τ), t(τ))`. Guarantee: the piece starts at a true curve point of arc length `s*`
/// with `|s* − s0| ≤ s0_error`, and for every `τ ∈ [0, h]` the true curve at arc length
/// `s* ± τ` is within `radius_param` (max norm, in parameters) and within `radius_xyz`
/// (Euclidean, in model space) of the reported point at `τ`. The radii are transversal: the
/// arc-length uncertainty `s0_error` does not enter them.
#[derive(Debug, Clone, PartialEq)]
pub struct TubePiece {
    /// Arc length at `τ = 0`.
    pub s0: f64,
    /// +1 along increasing arc length, −1 for a piece of the backward half.
    pub direction: f64,
    /// Length of the piece.
    pub h: f64,
    /// Polynomial coefficients in `τ` (midpoints of the proven interval coefficients).
    pub coeffs: Vec<[f64; 4]>,
    /// Proven bound on the parameter deviation.
    pub radius_param: f64,
    /// Proven bound on the model-space deviation.
    pub radius_xyz: f64,
    /// Proven bound on the error of `s0` as the arc length of the piece's start point (0 on
    /// steps that were not re-anchored since the branch's start point).
    pub s0_error: f64,
    /// `None`: `τ` is arc length, as above. `Some` (a cover-chain link): `τ` measures
    /// parameter `j` (its `index`), which the reported curve moves at unit rate (`y_j(τ) = y_j(0) ± τ`), and
    /// the guarantee is the same with "the true curve at arc length `s* ± τ`" read as "the true
    /// curve point with the same parameter `j`": every true curve point with `y_j` in the
    /// piece's range is within the radii of the reported point with that `y_j`, and the reverse.
    /// The arc lengths `s0`, `h` are then those of the reported curve (nominal) and `s0_error`
    /// is 0; `radius_xyz` then also bounds `Q(u(τ), v(τ))` against the true point, not only
    /// `P(σ(τ), t(τ))`.
    pub along: Option<AlongParameter>,
}

/// The parameter of a cover-chain tube piece ([`TubePiece::along`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AlongParameter {
    /// Which parameter `τ` measures (0..4 for σ, t, u, v).
    pub index: usize,
    /// Arc length of the reported curve over the piece (nominal, not a bound).
    pub arc_length: f64,
}

impl TubePiece {
    /// The (nominal, for a cover-chain piece) arc length at `τ`: `s0 ± τ`, or on a cover-chain
    /// piece `τ` scaled by the piece's arc length over its range `h`.
    pub fn arc_length_at(&self, tau: f64) -> f64 {
        match self.along {
            Some(a) if self.h > 0.0 => self.s0 + self.direction * tau * (a.arc_length / self.h),
            _ => self.s0 + self.direction * tau,
        }
    }

    /// The reported parameters `(σ, t, u, v)` at `τ ∈ [0, h]`.
    pub fn eval(&self, tau: f64) -> [f64; 4] {
        let mut y = [0.0; 4];
        for c in self.coeffs.iter().rev() {
            for i in 0..4 {
                y[i] = y[i] * tau + c[i];
            }
        }
        y
    }

    /// Whether the parameters `x` lie in a cover-chain piece (one with an along parameter): within
    /// `slack` (scaled by the domain widths `scales`) of a point of the tube, i.e. of the
    /// reported curve at an along coordinate within `slack` of `x`'s, with the others within the
    /// proven radius plus `slack`. An `f64` test: it decides what is reported or traced again,
    /// it proves nothing.
    ///
    /// The along coordinate may move by `slack` too: on a piece graphed over a slow coordinate
    /// (the other ones 450 times faster, beside the tight turn of a curve on nearly tangent
    /// surfaces), a marched point off the curve by its own rounding along the curve is off the
    /// reported curve at its exact along coordinate by that much times 450.
    pub(crate) fn holds(&self, x: &[f64; 4], scales: &[f64; 4], slack: f64) -> bool {
        let Some(along) = self.along else {
            return false;
        };
        let j = along.index;
        let start = self.eval(0.0)[j];
        let reach = slack * scales[j];
        let tau = (x[j] - start) * self.coeffs.get(1).map_or(1.0, |c| c[j].signum());
        if !(-reach..=self.h + reach).contains(&tau) {
            return false;
        }
        let tau = tau.clamp(0.0, self.h);
        let y = self.eval(tau);
        let dy = self.derivative(tau);
        // Move along the reported curve by δ (|δ| ≤ reach) to meet the fastest other coordinate.
        let fastest = (0..4).filter(|&k| k != j).max_by(|&a, &b| {
            (dy[a] / scales[a])
                .abs()
                .total_cmp(&(dy[b] / scales[b]).abs())
        });
        let delta = fastest
            .filter(|&m| dy[m] != 0.0)
            .map_or(0.0, |m| ((x[m] - y[m]) / dy[m]).clamp(-reach, reach));
        // The along coordinate within `reach` of the moved point's, the others within the tube.
        (x[j] - y[j] - dy[j] * delta).abs() <= reach
            && (0..4).filter(|&k| k != j).all(|k| {
                (x[k] - y[k] - dy[k] * delta).abs() <= self.radius_param + slack * scales[k]
            })
    }

    /// The derivative of the reported parameters in `τ` at `tau`.
    fn derivative(&self, tau: f64) -> [f64; 4] {
        let mut d = [0.0; 4];
        for (n, c) in self.coeffs.iter().enumerate().skip(1).rev() {
            for i in 0..4 {
                d[i] = d[i] * tau + n as f64 * c[i];
            }
        }
        d
    }
}

/// Why one end of a certified branch ends. Every variant is itself proven, except
/// [`CertifiedEnd::Unproven`], which says the tracer stopped without a proof of what is beyond.
#[derive(Debug, Clone, PartialEq)]
pub enum CertifiedEnd {
    /// The curve leaves the domain of surface `surface` (0 = P, 1 = Q); the last box straddles
    /// that boundary.
    Boundary {
        /// 0 for P, 1 for Q.
        surface: usize,
    },
    /// The curve returned to its start point (proven by the uniqueness box of the start): a
    /// closed loop, traced once.
    ClosedLoop,
    /// `0 ∈ |N^P × N^Q|` on the current box: a singular or tangential point may lie in `near`.
    Singular {
        /// Parameter box `(σ, t, u, v)` where the field could not be bounded away from zero.
        near: [Interval; 4],
    },
    /// The step fell below `h_min` although the normals are separated: two branches closer
    /// than can be resolved at this `h_min`.
    CloseBranches {
        /// The step size at which the proof failed.
        h: f64,
        /// The box reached.
        near: [Interval; 4],
    },
    /// Stopped without proof of what comes next (step or length budget, unbounded field).
    Unproven {
        /// Why.
        reason: String,
        /// The box reached.
        near: [Interval; 4],
    },
}

impl CertifiedEnd {
    /// A short name (`"boundary"`, `"closed_loop"`, `"singular"`, `"close_branches"`,
    /// `"unproven"`).
    pub fn kind(&self) -> &'static str {
        match self {
            CertifiedEnd::Boundary { .. } => "boundary",
            CertifiedEnd::ClosedLoop => "closed_loop",
            CertifiedEnd::Singular { .. } => "singular",
            CertifiedEnd::CloseBranches { .. } => "close_branches",
            CertifiedEnd::Unproven { .. } => "unproven",
        }
    }
}

impl CertifiedEnd {
    /// Whether the certificate reaches the curve's true end here: a proven boundary end or a
    /// closed loop (a singular box, close branches or an unproven end stop short of it).
    pub fn reaches_true_end(&self) -> bool {
        matches!(
            self,
            CertifiedEnd::Boundary { .. } | CertifiedEnd::ClosedLoop
        )
    }
}

impl std::fmt::Display for CertifiedEnd {
    /// `boundary of P` / `boundary of Q`, `closed loop`, `singular box`, `close branches (h =
    /// 1.0e-9)`, `UNPROVEN (reason)` (in capitals: no proof of what lies beyond).
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            CertifiedEnd::Boundary { surface } => {
                write!(f, "boundary of {}", if *surface == 0 { "P" } else { "Q" })
            }
            CertifiedEnd::ClosedLoop => f.write_str("closed loop"),
            CertifiedEnd::Singular { .. } => f.write_str("singular box"),
            CertifiedEnd::CloseBranches { h, .. } => write!(f, "close branches (h = {h:.1e})"),
            CertifiedEnd::Unproven { reason, .. } => write!(f, "UNPROVEN ({reason})"),
        }
    }
}

/// A certified branch: the chain of boxes in order along the curve, the tubes, and both ends.
#[derive(Debug, Clone, PartialEq)]
pub struct CertifiedBranch {
    /// The start box: coordinate `fixed` is a point, and for that value the curve meets
    /// `start_uniqueness` in exactly one point, which lies in this box.
    pub start: [Interval; 4],
    /// The parameter held fixed at the start (0..4 for σ, t, u, v).
    pub fixed: usize,
    /// The box of the uniqueness proof at the start.
    pub start_uniqueness: [Interval; 4],
    /// The chain of a-priori boxes, ordered by arc length (backward half first).
    pub boxes: Vec<EnclosureBox>,
    /// One tube piece per step, in the same order as `boxes`.
    pub tubes: Vec<TubePiece>,
    /// The certified (proven) tolerance of the branch: every point of the true curve between the ends is
    /// within this model-space distance of the reported tube curve, and every reported point is
    /// within it of the true curve: the largest `radius_xyz`, and for the short true curve piece
    /// of arc length `b` joining a step's end to the next step's re-anchored start, the larger
    /// radius of the two steps plus `b/2`.
    pub certified_tolerance: f64,
    /// The end at the smallest arc length, and at the largest.
    pub ends: [CertifiedEnd; 2],
    /// Transversal width of every step's end box, in order: the largest width over the three
    /// parameters other than the fastest-moving one, after the contraction / re-anchoring when it
    /// is on. With it this stays near rounding level; without it, it grows along the branch.
    pub widths: Vec<f64>,
    /// Where and why a cover chain kept a link wider than it aimed at, because shorter links
    /// did not narrow it (the widest such link); `None` when every link met the aim, and on
    /// Taylor-engine certificates. A cover chain whose tolerance is above the request always
    /// has one.
    pub tolerance_limit: Option<ToleranceLimit>,
}

/// Why a certified branch's tolerance is wider than the tracer aimed at, and where
/// ([`CertifiedBranch::tolerance_limit`]).
#[derive(Debug, Clone, PartialEq)]
pub struct ToleranceLimit {
    /// What held the tube up: the surfaces' near tangency there (with the sine of the angle
    /// between their normals) or the rounding of the coordinates.
    pub reason: String,
    /// The parameter box `(σ, t, u, v)` of that link.
    pub near: [Interval; 4],
    /// That link's proven model-space radius.
    pub width: f64,
}

impl CertifiedBranch {
    /// Number of validated steps.
    pub fn steps(&self) -> usize {
        self.boxes.len()
    }

    /// Whether the boxes' arc-length ranges are proven (Taylor-engine certificates), rather than
    /// the nominal arc lengths of the reported curve (cover chains; their guarantee is in the
    /// along coordinate of each tube piece, see [`TubePiece::along`]).
    pub fn arc_length_proven(&self) -> bool {
        self.tubes.iter().all(|t| t.along.is_none())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn piece() -> TubePiece {
        // σ = 0.2 + τ, t = 0.5 + 0.1τ, u = σ, v = t over τ ∈ [0, 0.3].
        TubePiece {
            s0: 0.0,
            direction: 1.0,
            h: 0.3,
            coeffs: vec![[0.2, 0.5, 0.2, 0.5], [1.0, 0.1, 1.0, 0.1]],
            radius_param: 1e-9,
            radius_xyz: 1e-9,
            s0_error: 0.0,
            along: Some(AlongParameter {
                index: 0,
                arc_length: 0.3,
            }),
        }
    }

    #[test]
    fn points_in_and_out_of_a_piece() {
        let (t, s) = (piece(), [1.0; 4]);
        assert!(t.holds(&[0.3, 0.51, 0.3, 0.51], &s, 0.0));
        assert!(t.holds(&[0.3, 0.51 + 5e-10, 0.3, 0.51], &s, 0.0));
        assert!(!t.holds(&[0.3, 0.51 + 5e-9, 0.3, 0.51], &s, 0.0));
        assert!(t.holds(&[0.3, 0.51 + 5e-9, 0.3, 0.51], &s, 1e-8));
        // Outside the piece's range of σ.
        assert!(!t.holds(&[0.6, 0.54, 0.6, 0.54], &s, 0.0));
        assert!(!t.holds(&[0.1, 0.49, 0.1, 0.49], &s, 0.0));
        // A piece walked the other way (σ decreasing).
        let mut back = piece();
        back.coeffs = vec![[0.5, 0.53, 0.5, 0.53], [-1.0, -0.1, -1.0, -0.1]];
        assert!(back.holds(&[0.3, 0.51, 0.3, 0.51], &s, 0.0));
        assert!(!back.holds(&[0.6, 0.54, 0.6, 0.54], &s, 0.0));
    }
}
