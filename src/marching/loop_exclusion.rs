//! A rigorous test that two sub-patches intersect in no closed loop.
//!
//! **Criterion.** Let `B_P`, `B_Q` be parameter boxes of P and Q and `N_P = P_σ × P_t`,
//! `N_Q = Q_u × Q_v` their normals. If for one fixed direction `d`
//!
//! ```text
//! d · (N_P(σ,t) × N_Q(u,v)) ≠ 0      for all (σ,t) ∈ B_P, (u,v) ∈ B_Q,
//! ```
//!
//! then (i) both surfaces are regular and never tangent to each other on the pair, so
//! `C = {P(σ,t) = Q(u,v)} ∩ (B_P × B_Q)` is a smooth 1-manifold there (the 3×4 Jacobian
//! `[P_σ P_t −Q_u −Q_v]` has rank 3 exactly when the normals are not parallel) without singular
//! points; (ii) its model-space tangent is a non-zero multiple of `N_P × N_Q`, so along every
//! component, oriented continuously, `d · x` is strictly monotone (the sign of the expression above
//! is constant on the connected box pair). A component lying wholly in the interior of the box pair
//! would be compact without end points, hence a closed curve, and `∮ d · dx = 0` contradicts the
//! strict monotonicity. So **every component of `C` meets the boundary of `B_P × B_Q`**: it is found
//! from the points where it crosses a face of `B_P` or of `B_Q` (Sederberg–Meyers / Hohmeyer loop
//! detection, here in the "some plane is crossed monotonically" form).
//!
//! **Enclosures.** All bounds are interval arithmetic on the Bernstein nets of the sub-patches
//! ([`RationalBezierPatch::subnet`]), which enclose the exact nets. On the box, with normalised
//! parameters `(s, r) ∈ [0,1]²` and homogeneous net `(X_ij, w_ij)`:
//! `X ∈ hull{X_ij}`, `X_s ∈ m·hull{X_{i+1,j} − X_ij}`, likewise `w`, `w_s`, and in `r`. The
//! rational partial is `S_s = (X_s·w − X·w_s) / w²` with `w > 0`, so `S_s` is a positive multiple
//! of `X_s·w − X·w_s`; the positive factors `m`, `n`, `1/w²` and the box widths change neither
//! the direction of `S_s × S_r` nor the sign tested, so they are dropped. For a polynomial patch
//! (all weights exactly 1) `w ≡ 1`, `w_s ≡ 0` exactly.
//!
//! Before bounding, each net is translated to its own centre (normals do not change; the
//! products `X·w_s` become small) and multiplied by a floating-point matrix `R` whose rows are
//! roughly `N_P`, `N_Q`-ish and the curve tangent at the centres, so the boxes are aligned with
//! the geometry. For any invertible `R`, `(R a) × (R b) = cof(R)(a × b)` and
//! `cof(R)·x × cof(R)·y = det(R)·R(x × y)`, so the third component of the rotated product is
//! `det(R)·(r₃ · (N_P × N_Q))` with `r₃` the third row of `R`: if its enclosure excludes 0, the
//! criterion holds with `d = r₃` exactly (no orthogonality of `R` is needed for soundness).

use crate::geometry::RationalBezierPatch;
use crate::scalar::point;
use inari::Interval;

/// A proof that a pair of sub-patches holds no closed loop of the intersection.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LoopFree {
    /// The fixed direction `d` along which every intersection component in the pair is strictly
    /// monotone (`d · (N_P × N_Q)` is provably non-zero, of one sign, everywhere on the pair).
    pub direction: [f64; 3],
}

/// Proves, with interval arithmetic, that the intersection of `P` over `pu × pv` with `Q` over
/// `qu × qv` (declared parameters) contains no closed loop and no singular point: every
/// component of the intersection inside the pair reaches the pair's boundary.
///
/// `Some` is a proof (see the module documentation); `None` means "not proven" (a loop, a
/// tangency, or boxes too large for the bound), never a claim that a loop exists.
pub fn prove_loop_free(
    p: &RationalBezierPatch,
    pu: Interval,
    pv: Interval,
    q: &RationalBezierPatch,
    qu: Interval,
    qv: Interval,
) -> Option<LoopFree> {
    let centre = |x: Interval| 0.5 * (x.inf() + x.sup());
    let dp = p.derivs_f64(centre(pu), centre(pv));
    let dq = q.derivs_f64(centre(qu), centre(qv));
    let np = cross_f(&dp.su, &dp.sv);
    let nq = cross_f(&dq.su, &dq.sv);
    let frame = frame(&np, &nq);
    let enp = normal_enclosure(p, pu, pv, &frame, &dp.p)?;
    let enq = normal_enclosure(q, qu, qv, &frame, &dq.p)?;
    // Component k of (R N_P) × (R N_Q) is det(R)·(r_k · (N_P × N_Q)).
    for k in [2, 0, 1] {
        let (i, j) = ((k + 1) % 3, (k + 2) % 3);
        let t = enp[i] * enq[j] - enp[j] * enq[i];
        if t.is_empty() {
            continue;
        }
        if t.inf() > 0.0 || t.sup() < 0.0 {
            return Some(LoopFree {
                direction: frame[k],
            });
        }
    }
    None
}

/// An enclosure of a positive multiple of `R·(S_s × S_r)` over the box `u × v` (declared
/// parameters), from the interval Bernstein net of the sub-patch translated by `origin` and
/// multiplied by `frame` (rows of `R`). `None` if a weight of the sub-net is not provably
/// positive.
pub fn normal_enclosure(
    patch: &RationalBezierPatch,
    u: Interval,
    v: Interval,
    frame: &[[f64; 3]; 3],
    origin: &[f64; 3],
) -> Option<[Interval; 3]> {
    let [m, n] = patch.degree();
    let polynomial = patch
        .homogeneous()
        .iter()
        .all(|h| h[3].inf() == 1.0 && h[3].sup() == 1.0);
    let net = patch.subnet(u, v);
    if net.iter().any(|h| !(h[3].inf() > 0.0)) {
        return None;
    }
    let o = origin.map(point);
    let r: [[Interval; 3]; 3] = frame.map(|row| row.map(point));
    // The translated, rotated net Y_ij = R·(X_ij − o·w_ij) and its weights (exactly 1 for a
    // polynomial patch: the exact sub-net of a polynomial has unit weights).
    let y: Vec<([Interval; 3], Interval)> = net
        .iter()
        .map(|h| {
            let w = if polynomial { point(1.0) } else { h[3] };
            let x: [Interval; 3] = std::array::from_fn(|c| h[c] - o[c] * w);
            let rotated = std::array::from_fn(|k| r[k][0] * x[0] + r[k][1] * x[1] + r[k][2] * x[2]);
            (rotated, w)
        })
        .collect();
    let at = |i: usize, j: usize| y[i * (n + 1) + j];
    let mut hy = Hull::default();
    let mut hw = Hull1::default();
    let (mut hys, mut hws) = (Hull::default(), Hull1::default());
    let (mut hyr, mut hwr) = (Hull::default(), Hull1::default());
    for i in 0..=m {
        for j in 0..=n {
            let (yij, wij) = at(i, j);
            hy.add(&yij);
            hw.add(wij);
            if i < m {
                let (y1, w1) = at(i + 1, j);
                hys.add(&std::array::from_fn(|c| y1[c] - yij[c]));
                hws.add(w1 - wij);
            }
            if j < n {
                let (y1, w1) = at(i, j + 1);
                hyr.add(&std::array::from_fn(|c| y1[c] - yij[c]));
                hwr.add(w1 - wij);
            }
        }
    }
    let (ys, yr) = (hys.get()?, hyr.get()?);
    let (a, b) = if polynomial {
        (ys, yr)
    } else {
        let (yb, wb) = (hy.get()?, hw.get()?);
        let (ws, wr) = (hws.get()?, hwr.get()?);
        (
            std::array::from_fn(|c| ys[c] * wb - yb[c] * ws),
            std::array::from_fn(|c| yr[c] * wb - yb[c] * wr),
        )
    };
    Some(cross_i(&a, &b))
}

/// Rows of the frame: the normal of P, then completing, then the curve tangent `N_P × N_Q`
/// (normalised); the identity where the normals are (nearly) parallel or not finite.
fn frame(np: &[f64; 3], nq: &[f64; 3]) -> [[f64; 3]; 3] {
    let identity = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    let t = cross_f(np, nq);
    let (lt, lp) = (norm(&t), norm(np));
    if !(lt > 1e-300 && lp > 1e-300) || !lt.is_finite() || !lp.is_finite() {
        return identity;
    }
    let e3 = t.map(|x| x / lt);
    let e1 = np.map(|x| x / lp);
    let e2 = cross_f(&e3, &e1);
    [e1, e2, e3]
}

fn cross_f(a: &[f64; 3], b: &[f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn cross_i(a: &[Interval; 3], b: &[Interval; 3]) -> [Interval; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn norm(a: &[f64; 3]) -> f64 {
    (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt()
}

/// Running interval hull of 3-vectors.
#[derive(Default)]
struct Hull(Option<[Interval; 3]>);

impl Hull {
    fn add(&mut self, x: &[Interval; 3]) {
        self.0 = Some(match self.0 {
            None => *x,
            Some(h) => std::array::from_fn(|c| h[c].convex_hull(x[c])),
        });
    }
    fn get(&self) -> Option<[Interval; 3]> {
        self.0
    }
}

/// Running interval hull of scalars.
#[derive(Default)]
struct Hull1(Option<Interval>);

impl Hull1 {
    fn add(&mut self, x: Interval) {
        self.0 = Some(match self.0 {
            None => x,
            Some(h) => h.convex_hull(x),
        });
    }
    fn get(&self) -> Option<Interval> {
        self.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::{Domain, ParametricSurface, PowerSurface};
    use crate::scalar::interval;

    fn graph(terms: Vec<(u32, u32, f64)>) -> RationalBezierPatch {
        PowerSurface::graph(Domain::new(-1.0, 1.0, -1.0, 1.0), terms)
            .to_bezier()
            .unwrap()
    }

    fn iv(a: f64, b: f64) -> Interval {
        interval(a, b).unwrap()
    }

    #[test]
    fn normal_enclosure_contains_sampled_normals() {
        // A rational patch: check the enclosure (in the identity frame) holds a positive
        // multiple of the sampled normal, i.e. the normalised sample lies in the normalised box
        // direction-wise: every component's sign is compatible.
        let pts: Vec<[f64; 3]> = (0..9)
            .map(|k| {
                let (i, j) = ((k / 3) as f64, (k % 3) as f64);
                [i, j, 0.3 * ((k * 5) % 7) as f64 - 0.9]
            })
            .collect();
        let w = [1.0, 2.0, 1.0, 1.5, 0.7, 1.2, 1.0, 1.1, 0.9];
        let patch =
            RationalBezierPatch::from_f64_points([2, 2], &pts, Some(&w), Domain::UNIT).unwrap();
        let id = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
        let (u, v) = (iv(0.25, 0.375), iv(0.5, 0.625));
        let e = normal_enclosure(&patch, u, v, &id, &[0.0; 3]).unwrap();
        for a in 0..=4 {
            for b in 0..=4 {
                let (s, t) = (0.25 + 0.125 * a as f64 / 4.0, 0.5 + 0.125 * b as f64 / 4.0);
                let d = patch.derivs(s, t);
                let n = d.su.cross(&d.sv);
                // Some positive multiple λ·n lies in e: the ratio intervals e_c / n_c overlap.
                let mut lam = iv(0.0, f64::INFINITY);
                for c in 0..3 {
                    if n[c].abs() > 1e-9 {
                        lam = lam.intersection(e[c] / point(n[c]));
                    } else {
                        assert!(e[c].inf() <= 1e-9 * e[c].mag() || e[c].contains(0.0));
                    }
                }
                assert!(!lam.is_empty(), "normal at ({s}, {t}) not enclosed");
            }
        }
    }

    #[test]
    fn plane_against_tilted_plane_is_loop_free() {
        let plane = graph(vec![(0, 0, 0.0), (1, 1, 0.0)]);
        let tilted = graph(vec![(1, 0, 0.5), (0, 1, 0.2), (0, 0, 0.1)]);
        let whole = iv(-1.0, 1.0);
        let proof = prove_loop_free(&tilted, whole, whole, &plane, whole, whole)
            .expect("monotone pair proven loop-free");
        // The line 0.5x + 0.2y + 0.1 = 0 has direction ±(0.2, −0.5, 0): d is not orthogonal.
        let along = 0.2 * proof.direction[0] - 0.5 * proof.direction[1];
        assert!(along.abs() > 0.1, "{proof:?}");
    }

    #[test]
    fn pair_holding_a_loop_is_never_loop_free() {
        // z = x² + y² − ρ² against z = 0 holds the circle of radius ρ. Any pair of boxes both
        // containing the whole circle must fail, at every size and offset tried.
        let bump = graph(vec![(2, 0, 1.0), (0, 2, 1.0), (0, 0, -0.01)]);
        let plane = graph(vec![(0, 0, 0.0), (1, 1, 0.0)]);
        for (lo, hi) in [(-1.0, 1.0), (-0.2, 0.15), (-0.1000001, 0.1000001), (-0.5, 0.11)] {
            let b = iv(lo, hi);
            assert!(prove_loop_free(&bump, b, b, &plane, b, b).is_none());
            assert!(prove_loop_free(&plane, b, b, &bump, b, b).is_none());
        }
        // A box pair away from the apex is loop-free (the circle crosses it as an arc).
        let (x, y) = (iv(0.09, 0.11), iv(-0.02, 0.02));
        assert!(prove_loop_free(&bump, x, y, &plane, x, y).is_some());
    }
}
