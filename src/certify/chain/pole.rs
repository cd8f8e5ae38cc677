//! Guide points and links next to a pole: a side of a patch collapsed to one point, which a
//! marched branch runs into (a great circle of a sphere through its poles).
//!
//! There `P(σ, t) − X = t·G(σ, t)` (`t` the distance from the side, `σ` along it), so
//! `∂P/∂σ = t·G_σ` and a curve point fixes `σ` only to the rounding of `P` over `t`. The
//! velocity at such a point is the field's off the curve by that much, and its `σ` part grows
//! like `1/t`: holding `σ` in Newton sends a point onto the pole (for a `σ` off the curve
//! there is no other solution), the fastest coordinate is `σ`, and a jet built on that
//! velocity has derivatives like `1/tᵏ`; its sign, from a dot product with the step between
//! marched points, follows the `σ` parts of both, and they are noise. So next to the pole the
//! guide points hold `t` (where holding the fastest coordinate lands on the pole), the nodes
//! are oriented without `σ`, the links run along `t`, and their predictors hold `σ` (any
//! predictor is rigorous: the proof bounds the curve's offsets from it). The links then reach
//! the last marched point, a few `1e-12` from the pole on the sphere of
//! `scenes/nurbs_sphere_plane.json`; before, they stopped at `t ≈ 3e-9`.
//!
//! On a half whose march ends at a pole the links are proven on both patches moved so that
//! the pole is the origin (`geometry::pole::common_pole`, `LeanPatch::moved`): the other
//! surface's rounding there leaves `σ` known to about `1e-15/t`, and over such a range the
//! second partials of the net as given are differences of terms near the pole, each as wide;
//! moved, they are `t` times smaller. Small circles through the pole (planes at 60° to 76°)
//! then reach within a few `1e-12` of it as great circles do; they stopped at `5e-10`. On
//! other halves of a pair with a pole, a link the net as given does not prove is tried on the
//! moved forms too (a curve passing 1e-6 from the pole and leaving by a side next to it was
//! otherwise cut short there and traced three times).

use super::walker::{newton, Link, Node, PoleEnd, Walker};
use super::*;

/// Next to a pole, within this part of the patch's domain across from its collapsed side,
/// the links of a half that runs into it hold the angular parameter (`σ` above) in their
/// predictors. Farther out its derivatives are the curve's own and are kept (through a pole a
/// curve's angle is a smooth function of `t` with a nonzero slope in general, and a predictor
/// with a flat `σ` would be off by about that slope times the link's length there).
const POLE_ZONE: f64 = 1e-6;

/// The largest change of the angular coordinate (a part of the domain) that the rounding of
/// a marched point at a distance `g` (a part of the domain) from the pole explains, times
/// `g`: a point fixes the angle only to about `1e-16/g`; a thousand times that.
const ANGLE_NOISE: f64 = 1e-13;

/// The collapsed side of `s` nearest the parameter point `(a, b)`: its distance from there as
/// a part of the domain's width across it, and which parameter (0 for `u`, 1 for `v`) runs
/// away from it. `None` if `s` has no collapsed side.
pub(super) fn pole_gap(s: &RationalBezierPatch, a: f64, b: f64) -> Option<(f64, usize)> {
    let d = s.domain();
    let sides = s.collapsed_sides();
    (0..4)
        .filter(|&k| sides[k].is_some())
        .map(|k| {
            let (x, r) = if k < 2 { (a, d.u) } else { (b, d.v) };
            ((x - r[k % 2]).abs() / (r[1] - r[0]), k / 2)
        })
        .min_by(|x, y| x.0.total_cmp(&y.0))
}

/// The nearest collapsed side of either patch to `x`: its gap ([`pole_gap`]) and the
/// coordinate (0–3) that runs away from it.
fn nearest_side(
    p: &RationalBezierPatch,
    q: &RationalBezierPatch,
    x: &[f64; 4],
) -> Option<(f64, usize)> {
    let at_p = pole_gap(p, x[0], x[1]);
    let at_q = pole_gap(q, x[2], x[3]).map(|(g, r)| (g, 2 + r));
    at_p.into_iter()
        .chain(at_q)
        .min_by(|a, b| a.0.total_cmp(&b.0))
}

/// Whether `y` lies much nearer a collapsed side than `x` or much farther from it (its gap
/// changed by more than half of `x`'s): Newton from `x` went onto the pole (or off it).
fn moved_at_pole(
    p: &RationalBezierPatch,
    q: &RationalBezierPatch,
    x: &[f64; 4],
    y: &[f64; 4],
) -> bool {
    let gaps = |z: &[f64; 4]| [pole_gap(p, z[0], z[1]), pole_gap(q, z[2], z[3])];
    gaps(x).iter().zip(gaps(y)).any(
        |(a, b)| matches!((a, b), (Some((ga, _)), Some((gb, _))) if (gb - ga).abs() > 0.5 * ga),
    )
}

/// A guide point refined from the marched point `x` by Newton holding coordinate `j`
/// (`None` if it does not converge): when that lands on a pole (or leaves one, see
/// [`moved_at_pole`]), Newton again holding the coordinate that runs away from the nearest
/// collapsed side; `None` if that also fails.
pub(super) fn refine_guide(
    p: &RationalBezierPatch,
    q: &RationalBezierPatch,
    x: [f64; 4],
    j: usize,
) -> Option<[f64; 4]> {
    let y = newton(p, q, x, j, x[j]).map(|r| r.x)?;
    if !moved_at_pole(p, q, &x, &y) {
        return Some(y);
    }
    let (_, radial) = nearest_side(p, q, &x)?;
    newton(p, q, x, radial, x[radial])
        .map(|r| r.x)
        .filter(|y| radial != j && !moved_at_pole(p, q, &x, y))
}

impl<'a> Walker<'a> {
    /// A link from `a` to `b`. When the patches have one pole, the link proofs may also use
    /// both moved so that the pole is the origin (`pole.rs`): on a half whose march ended at
    /// the pole, first (and the forms as given where that is not proven within the tolerance:
    /// the narrower of the two); elsewhere only where the forms as given prove nothing (a
    /// curve passing close to the pole, whose links there did not contract).
    pub(super) fn try_link(
        &self,
        a: &Node,
        b: &Node,
        must_end: Option<&[Interval; 4]>,
    ) -> Option<Link> {
        let given = [&self.lean[0], &self.lean[1]];
        let Some([p, q]) = &self.lean_at_pole else {
            return self.link_on(given, a, b, must_end);
        };
        let moved = [p, q];
        if !self.march_at_pole {
            return self
                .link_on(given, a, b, must_end)
                .or_else(|| self.link_on(moved, a, b, must_end));
        }
        let first = self.link_on(moved, a, b, must_end);
        if first
            .as_ref()
            .is_some_and(|l| l.radius_xyz <= self.opts.required_tolerance)
        {
            return first;
        }
        match (first, self.link_on(given, a, b, must_end)) {
            (Some(x), Some(y)) => Some(if y.radius_xyz < x.radius_xyz { y } else { x }),
            (x, y) => x.or(y),
        }
    }

    /// The pole end of a half whose march ended at a pole of `surface` (0 for P, 1 for Q) at
    /// the marched point `x`.
    pub(super) fn pole_end(&self, surface: usize, x: &[f64; 4]) -> Option<PoleEnd> {
        let s = [self.p, self.q][surface];
        let (_, r) = pole_gap(s, x[2 * surface], x[2 * surface + 1])?;
        Some(PoleEnd {
            radial: 2 * surface + r,
            angular: 2 * surface + 1 - r,
        })
    }

    /// Whether the marched points `xs` run *into* the pole `e` (rather than past it): they come
    /// from outside [`POLE_ZONE`], and within
    /// [`POLE_ZONE`] of its side, their angular coordinate stays at that of the zone's outermost
    /// point to within what the rounding leaves it (`ANGLE_NOISE` over the distance to the
    /// side, both as parts of the domain). A curve passing the pole at a distance `δ` turns its
    /// angle by about `δ/t` at a distance `t`, far more; holding its angle would swing the
    /// links' tubes by that much.
    pub(super) fn runs_into(&self, xs: &[[f64; 4]], e: PoleEnd) -> bool {
        let surface = e.radial / 2;
        let s = [self.p, self.q][surface];
        let d = s.domain();
        let width = if e.angular.is_multiple_of(2) {
            d.u[1] - d.u[0]
        } else {
            d.v[1] - d.v[0]
        };
        let zone: Vec<(f64, f64)> = xs
            .iter()
            .filter_map(|x| {
                let (g, _) = pole_gap(s, x[2 * surface], x[2 * surface + 1])?;
                (g < POLE_ZONE).then_some((g, x[e.angular] / width))
            })
            .collect();
        // From outside the zone (a sliver of a curve passing the pole, all of it next to the
        // pole, gives no evidence).
        let from_outside = xs.iter().any(|x| {
            pole_gap(s, x[2 * surface], x[2 * surface + 1]).is_some_and(|(g, _)| g >= POLE_ZONE)
        });
        let Some(&(_, outer)) = zone.iter().max_by(|a, b| a.0.total_cmp(&b.0)) else {
            return from_outside;
        };
        if !from_outside {
            return false;
        }
        zone.iter()
            .all(|&(g, a)| (a - outer).abs() <= ANGLE_NOISE / g.max(f64::MIN_POSITIVE))
    }

    /// Whether `x` lies within [`POLE_ZONE`] of the collapsed side of the pole the half runs
    /// into.
    fn in_pole_zone(&self, x: &[f64; 4]) -> bool {
        self.toward_pole.is_some_and(|e| {
            let surface = e.radial / 2;
            let s = [self.p, self.q][surface];
            pole_gap(s, x[2 * surface], x[2 * surface + 1]).is_some_and(|(g, _)| g < POLE_ZONE)
        })
    }

    /// The angular coordinate of the pole the half runs into, if `x` lies within
    /// [`POLE_ZONE`] of it.
    pub(super) fn pole_angular_at(&self, x: &[f64; 4]) -> Option<usize> {
        self.toward_pole
            .filter(|_| self.in_pole_zone(x))
            .map(|e| e.angular)
    }

    /// Next to the pole the half runs into, the coordinate to run a link from `a` to `b` along
    /// (and to place a node between them by): the radial one, when both lie within
    /// [`POLE_ZONE`] and it moves between them as both velocities say.
    pub(super) fn pole_along(&self, a: &Node, b: &Node) -> Option<usize> {
        let e = self.toward_pole?;
        let i = e.radial;
        let d = b.x[i] - a.x[i];
        let monotone = d != 0.0 && d.signum() == a.t[i].signum() && d.signum() == b.t[i].signum();
        (monotone && self.in_pole_zone(&a.x) && self.in_pole_zone(&b.x)).then_some(i)
    }

    /// The coordinate a link from `a` to `b` along `j` holds constant in its predictor, at
    /// `a`'s value: the angular one of the pole the half runs into, when `j` is the radial one
    /// and both lie within [`POLE_ZONE`] of it. Interpolating the nodes' angles instead (each
    /// off the curve by up to the rounding over the distance `t` to the pole) swings the
    /// predictor by that much, `Δσ ~ 1e-5` at `t = 1e-10`, and the Taylor form of `P` along
    /// it, whose rational form does not cancel the swing in the pole's own coordinates, widens
    /// the residual by about `Δσ²`: the tube then grew to the tolerance at `t ≈ 1e-10`. With
    /// `σ` held, the proof's offsets take up the nodes' rounding instead, as a width of the
    /// tube, which the linearised terms multiply by `t`.
    pub(super) fn flat_coordinate(&self, j: usize, a: &Node, b: &Node) -> Option<usize> {
        let e = self.toward_pole.filter(|e| e.radial == j)?;
        (self.in_pole_zone(&a.x) && self.in_pole_zone(&b.x)).then_some(e.angular)
    }

    /// The jet of node `n` graphed over `j`: with the angular coordinate held
    /// ([`Jet::pinned`]) when `j` is the radial one of the pole the half runs into and `n` lies
    /// within [`POLE_ZONE`] of it.
    pub(super) fn node_jet(&self, n: &Node, j: usize) -> Option<Jet> {
        match self.toward_pole {
            Some(e) if e.radial == j && self.in_pole_zone(&n.x) => {
                Jet::pinned(self.p, self.q, &n.x, &n.t, j, e.angular)
            }
            _ => Jet::new(self.p, self.q, &n.x, &n.t, j),
        }
    }
}
